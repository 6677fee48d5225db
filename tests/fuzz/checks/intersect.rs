//! The check of the `intersect` fuzz target, shared with `tests/fuzz_regressions.rs`, which
//! replays every saved input on stable Rust in the ordinary test run: random rays against random
//! shapes give ordered spans without NaN, and normals without NaN.

use glam::DVec3;
use raytree::geometry::{Aabox, Cone, Cylinder, Plane, Ray, Shape, Sphere, Triangle};

fn vec(v: &[f64]) -> DVec3 {
    DVec3::new(v[0], v[1], v[2])
}

/// Panics on a finding.
pub fn check(data: &[u8]) {
    if data.len() < 8 * 13 + 1 {
        return;
    }
    let nums: Vec<f64> = data[1..]
        .chunks_exact(8)
        .take(13)
        .map(|c| {
            // Map bytes to moderate finite numbers (the scene validator keeps inputs finite).
            let x = f64::from_le_bytes(c.try_into().unwrap());
            if x.is_finite() {
                x.clamp(-1e6, 1e6)
            } else {
                0.5
            }
        })
        .collect();
    let (a, b, r) = (vec(&nums[0..3]), vec(&nums[3..6]), nums[6].abs().max(1e-3));
    let shape = match data[0] % 6 {
        0 => Shape::Sphere(Sphere {
            center: a,
            radius: r,
        }),
        1 => match b.try_normalize() {
            Some(n) => Shape::Plane(Plane {
                point: a,
                normal: n,
            }),
            None => return,
        },
        2 => Shape::Box(Aabox {
            min: a.min(b),
            max: a.max(b) + DVec3::splat(1e-3),
        }),
        3 if (a - b).length() > 1e-6 => Shape::Cylinder(Cylinder {
            base: a,
            top: b,
            radius: r,
        }),
        4 if (a - b).length() > 1e-6 => Shape::Cone(Cone {
            apex: a,
            base: b,
            radius: r,
        }),
        5 => Shape::Triangle(Triangle {
            a,
            b,
            c: a + DVec3::new(r, 0.0, r),
        }),
        _ => return,
    };
    let (o, d) = (vec(&nums[7..10]), vec(&nums[10..13]));
    let Some(d) = d.try_normalize() else { return };
    let ray = Ray::new(o, d);
    if let Some(s) = shape.span(&ray) {
        assert!(!s.t_in.is_nan() && !s.t_out.is_nan(), "NaN span {s:?}");
        assert!(s.t_in <= s.t_out, "unordered span {s:?}");
        for t in [s.t_in, s.t_out] {
            if t.is_finite() {
                let n = shape.normal(
                    ray.at(t),
                    if t == s.t_in {
                        s.face_in as u32
                    } else {
                        s.face_out as u32
                    },
                );
                assert!(
                    !n.is_nan() || matches!(shape, Shape::Triangle(_)),
                    "NaN normal"
                );
            }
        }
    }
}
