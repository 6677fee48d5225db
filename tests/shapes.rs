//! Every shape against hand-derived answers: a hit, a miss, a tangent, a ray starting inside,
//! and a shape behind the ray. Plus the lighting terms and attenuation.

use glam::{DAffine3, DMat3, DQuat, DVec3};
use proptest::prelude::*;
use raytree::geometry::{Aabox, Cone, Cylinder, Plane, Ray, Shape, Sphere, Transform, Triangle};
use raytree::scene::{parse, Limits, Search};
use raytree::shading::local::{ambient, light_terms};
use raytree::shading::{Highlight, Material};

const E: f64 = 1e-12;

fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
    Ray::new(DVec3::from_array(o), DVec3::from_array(d))
}

fn span(s: &Shape, r: &Ray) -> Option<(f64, f64)> {
    s.span(r).map(|s| (s.t_in, s.t_out))
}

fn close(a: Option<(f64, f64)>, b: (f64, f64)) {
    let a = a.expect("a hit");
    assert!(
        (a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9,
        "{a:?} vs {b:?}"
    );
}

#[test]
fn sphere_cases() {
    // Centre (0,0,5), r = 2, ray along +z from the origin: enters at 3, leaves at 7.
    let s = Shape::Sphere(Sphere {
        center: DVec3::new(0.0, 0.0, 5.0),
        radius: 2.0,
    });
    close(span(&s, &ray([0.0; 3], [0.0, 0.0, 1.0])), (3.0, 7.0));
    // Miss: offset 2.5 > r.
    assert!(span(&s, &ray([2.5, 0.0, 0.0], [0.0, 0.0, 1.0])).is_none());
    // Tangent: offset exactly r, double root at 5.
    close(span(&s, &ray([2.0, 0.0, 0.0], [0.0, 0.0, 1.0])), (5.0, 5.0));
    // Inside: from the centre, the entry is behind (−2) and the exit ahead (2).
    close(
        span(&s, &ray([0.0, 0.0, 5.0], [0.0, 0.0, 1.0])),
        (-2.0, 2.0),
    );
    // Behind: both roots negative.
    close(
        span(&s, &ray([0.0, 0.0, 10.0], [0.0, 0.0, 1.0])),
        (-7.0, -3.0),
    );
    // Normal at (0, 2, 5) is +y.
    assert!((s.normal(DVec3::new(0.0, 2.0, 5.0), 0) - DVec3::Y).length() < E);
}

#[test]
fn plane_cases() {
    let s = Shape::Plane(Plane {
        point: DVec3::new(0.0, -1.0, 0.0),
        normal: DVec3::Y,
    });
    // From y = 3 straight down: crosses y = −1 at t = 4, inside (below) from then on.
    let (a, b) = span(&s, &ray([0.0, 3.0, 0.0], [0.0, -1.0, 0.0])).unwrap();
    assert_eq!((a, b), (4.0, f64::INFINITY));
    // Parallel above: miss; parallel below: inside everywhere.
    assert!(span(&s, &ray([0.0, 3.0, 0.0], [1.0, 0.0, 0.0])).is_none());
    assert_eq!(
        span(&s, &ray([0.0, -3.0, 0.0], [1.0, 0.0, 0.0])).unwrap(),
        (f64::NEG_INFINITY, f64::INFINITY)
    );
    // Going up from below: leaves at t = 2.
    assert_eq!(
        span(&s, &ray([0.0, -3.0, 0.0], [0.0, 1.0, 0.0])).unwrap(),
        (f64::NEG_INFINITY, 2.0)
    );
    // Behind: the plane is below a ray going up from y = 3: the crossing is at t = −4.
    assert_eq!(
        span(&s, &ray([0.0, 3.0, 0.0], [0.0, 1.0, 0.0])).unwrap(),
        (f64::NEG_INFINITY, -4.0)
    );
    // A 3-4-5 slant: from (0, 3, 0) along (0.6, −0.8, 0) the drop of 4 takes t = 5.
    close(
        span(&s, &ray([0.0, 3.0, 0.0], [0.6, -0.8, 0.0])).map(|(a, _)| (a, a)),
        (5.0, 5.0),
    );
}

#[test]
fn box_cases() {
    let s = Shape::Box(Aabox {
        min: DVec3::splat(-1.0),
        max: DVec3::splat(1.0),
    });
    close(
        span(&s, &ray([0.0, 0.0, -5.0], [0.0, 0.0, 1.0])),
        (4.0, 6.0),
    );
    assert_eq!(
        s.span(&ray([0.0, 0.0, -5.0], [0.0, 0.0, 1.0]))
            .unwrap()
            .face_in,
        4,
        "enters through −z"
    );
    assert!(span(&s, &ray([2.0, 0.0, -5.0], [0.0, 0.0, 1.0])).is_none());
    // Through two opposite vertical edges: from (−3, 0, −3) along (1, 0, 1)/√2 the ray enters at
    // the edge (−1, 0, −1) and leaves at the edge (1, 0, 1): t = 2√2 … 4√2.
    let r = 2f64.sqrt();
    close(
        span(&s, &ray([-3.0, 0.0, -3.0], [1.0, 0.0, 1.0])),
        (2.0 * r, 4.0 * r),
    );
    // Tangent to a face (grazing along y = 1): inside the closed slab, the whole chord.
    close(
        span(&s, &ray([0.0, 1.0, -5.0], [0.0, 0.0, 1.0])),
        (4.0, 6.0),
    );
    close(
        span(&s, &ray([0.0, 0.0, 0.0], [0.0, 0.0, 1.0])),
        (-1.0, 1.0),
    );
    close(
        span(&s, &ray([0.0, 0.0, 5.0], [0.0, 0.0, 1.0])),
        (-6.0, -4.0),
    );
    assert_eq!(s.normal(DVec3::new(1.0, 0.2, 0.3), 1), DVec3::X);
}

#[test]
fn cylinder_cases() {
    // Radius 1 around the y axis from y = 0 to y = 2.
    let s = Shape::Cylinder(Cylinder {
        base: DVec3::ZERO,
        top: DVec3::new(0.0, 2.0, 0.0),
        radius: 1.0,
    });
    close(
        span(&s, &ray([-5.0, 1.0, 0.0], [1.0, 0.0, 0.0])),
        (4.0, 6.0),
    );
    assert!(
        span(&s, &ray([-5.0, 3.0, 0.0], [1.0, 0.0, 0.0])).is_none(),
        "above the top cap"
    );
    close(
        span(&s, &ray([-5.0, 1.0, 1.0], [1.0, 0.0, 0.0])),
        (5.0, 5.0),
    );
    // Down the axis: through the top cap (t = 3) and out of the base (t = 5).
    let down = s.span(&ray([0.0, 5.0, 0.0], [0.0, -1.0, 0.0])).unwrap();
    assert_eq!(
        (down.t_in, down.t_out, down.face_in, down.face_out),
        (3.0, 5.0, 2, 1)
    );
    close(
        span(&s, &ray([0.0, 1.0, 0.0], [1.0, 0.0, 0.0])),
        (-1.0, 1.0),
    );
    close(
        span(&s, &ray([5.0, 1.0, 0.0], [1.0, 0.0, 0.0])),
        (-6.0, -4.0),
    );
    // In through the side, out through the top cap: from (−2, 0.5, 0) along (1, 1, 0)/√2 the
    // side x = −1 is reached at t = √2 (y = 1.5) and the cap y = 2 at t = 1.5·√2.
    let r = 2f64.sqrt();
    close(
        span(&s, &ray([-2.0, 0.5, 0.0], [1.0, 1.0, 0.0])),
        (r, 1.5 * r),
    );
    assert!((s.normal(DVec3::new(0.6, 1.0, 0.8), 0) - DVec3::new(0.6, 0.0, 0.8)).length() < E);
}

#[test]
fn cone_cases() {
    // Seed 003's cone: apex (0, 2, 0), base centre (0, 0, 0), radius 1.
    let s = Shape::Cone(Cone {
        apex: DVec3::new(0.0, 2.0, 0.0),
        base: DVec3::ZERO,
        radius: 1.0,
    });
    // At height 1 the radius is ½: crossing x = −½ and ½.
    close(
        span(&s, &ray([-5.0, 1.0, 0.0], [1.0, 0.0, 0.0])),
        (4.5, 5.5),
    );
    assert!(span(&s, &ray([-5.0, 1.0, 0.6], [1.0, 0.0, 0.0])).is_none());
    // Tangent: at height 1, offset z = ½ touches the side at x = 0.
    close(
        span(&s, &ray([-5.0, 1.0, 0.5], [1.0, 0.0, 0.0])),
        (5.0, 5.0),
    );
    close(
        span(&s, &ray([0.0, 0.5, 0.0], [1.0, 0.0, 0.0])),
        (-0.75, 0.75),
    );
    close(
        span(&s, &ray([5.0, 1.0, 0.0], [1.0, 0.0, 0.0])),
        (-5.5, -4.5),
    );
    // Up the axis: base cap at t = 1, apex at t = 3.
    close(
        span(&s, &ray([0.0, -1.0, 0.0], [0.0, 1.0, 0.0])),
        (1.0, 3.0),
    );
    // Side normal ∝ (2, 1, 0) (the slope rises 2 over 1), base normal −y.
    assert!(
        (s.normal(DVec3::new(0.5, 1.0, 0.0), 0) - DVec3::new(2.0, 1.0, 0.0).normalize()).length()
            < E
    );
    assert_eq!(s.normal(DVec3::new(0.3, 0.0, 0.0), 1), DVec3::NEG_Y);
}

#[test]
fn triangle_cases() {
    let t = Triangle {
        a: DVec3::new(0.0, 0.0, 2.0),
        b: DVec3::new(2.0, 0.0, 2.0),
        c: DVec3::new(0.0, 2.0, 2.0),
    };
    let hit = t.intersect(&ray([0.5, 0.5, 0.0], [0.0, 0.0, 1.0])).unwrap();
    // t = 2; barycentrics: λ2 = x/2, λ3 = y/2, λ1 = 1 − λ2 − λ3.
    assert!((hit.t - 2.0).abs() < E);
    assert!((hit.bary - DVec3::new(0.5, 0.25, 0.25)).length() < E);
    assert!(
        t.intersect(&ray([1.5, 1.5, 0.0], [0.0, 0.0, 1.0]))
            .is_none(),
        "outside the hypotenuse"
    );
    assert!(
        t.intersect(&ray([0.5, 0.5, 3.0], [0.0, 0.0, 1.0]))
            .map(|h| h.t < 0.0)
            .unwrap_or(true),
        "behind"
    );
    assert!(
        t.intersect(&ray([0.5, 0.5, 0.0], [1.0, 0.0, 0.0]))
            .is_none(),
        "parallel"
    );
    // On an edge (x + y = 2): still a hit (closed triangle).
    assert!(t
        .intersect(&ray([1.0, 1.0, 0.0], [0.0, 0.0, 1.0]))
        .is_some());
    assert_eq!(t.normal(), DVec3::Z);
}

#[test]
fn transforms_keep_t_and_turn_normals_by_the_inverse_transpose() {
    // A unit sphere scaled by (2, 1, 1) then moved to (0, 0, 10): an ellipsoid.
    let s = parse(
        "camera: { eye: [0, 0, -1], look_at: [0, 0, 0] }\nmaterials: { m: { kd: 1 } }\nobjects:\n  - { name: e, sphere: { center: [0, 0, 0], radius: 1 }, material: m, transform: [ { scale: [2, 1, 1] }, { translate: [0, 0, 10] } ] }\n",
        "t.yaml",
        None,
        &Limits::default(),
    )
    .unwrap();
    let r = ray([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
    let h = s
        .nearest(
            &r,
            0.0,
            f64::INFINITY,
            &mut raytree::stats::Stats::default(),
        )
        .unwrap();
    assert!((h.t - 9.0).abs() < E, "t is a world distance");
    // On the ellipse x = 2cos θ, y = sin θ (cos θ = 0.6) the normal is ∝ (x/4, y, 0).
    let p = DVec3::new(2.0 * 0.6, 0.8, 10.0);
    let n = s.leaves[0].normal(p, 0, -r.dir);
    assert!(
        (n - DVec3::new(0.3, 0.8, 0.0).normalize()).length() < 1e-12,
        "{n}"
    );
}

#[test]
fn lighting_terms_match_the_formulas() {
    let m = Material {
        ka: 0.2,
        kd: 0.5,
        ks: 0.4,
        shininess: 2.0,
        color: DVec3::new(1.0, 0.5, 0.25),
        ..Material::matte("m", DVec3::ONE)
    };
    // n = +y, light 60° from the normal in the xy plane, viewer straight above.
    let n = DVec3::Y;
    let l = DVec3::new(3f64.sqrt() / 2.0, 0.5, 0.0);
    let v = DVec3::Y;
    let t = light_terms(&m, &m.paint(), n, v, l, DVec3::ONE, false);
    assert!((t.n_dot_l - 0.5).abs() < E);
    assert!((t.highlight_cos - 0.75f64.sqrt()).abs() < E);
    assert!((t.diffuse - 0.5 * 0.5 * m.color).length() < E);
    // Blinn: h halfway between l (60°) and v (0°) is at 30°: (h·n)² = cos²30° = 0.75.
    assert!((t.specular - DVec3::splat(0.4 * 0.75)).length() < E);
    // Phong: r is l mirrored, at −60°; r·v = cos 60° = ½, squared ¼.
    let phong = Material {
        highlight: Highlight::Phong,
        ..m.clone()
    };
    let t = light_terms(&phong, &phong.paint(), n, v, l, DVec3::ONE, false);
    assert!((t.specular - DVec3::splat(0.4 * 0.25)).length() < E);
    // Without a highlight (ks = 0) the cosine is worked out only where it is shown.
    let matte = Material {
        ks: 0.0,
        ..m.clone()
    };
    let (unshown, shown) = (
        light_terms(&matte, &matte.paint(), n, v, l, DVec3::ONE, false),
        light_terms(&matte, &matte.paint(), n, v, l, DVec3::ONE, true),
    );
    assert_eq!(
        (unshown.highlight_cos, unshown.specular),
        (0.0, DVec3::ZERO)
    );
    assert!((shown.highlight_cos - 0.75f64.sqrt()).abs() < E);
    assert_eq!(unshown.diffuse, shown.diffuse);
    assert!((ambient(&m, &m.paint(), DVec3::splat(0.3)) - 0.06 * m.color).length() < E);
}

#[test]
fn point_light_attenuation_is_one_over_the_quadratic() {
    let light = raytree::shading::Light {
        name: "L".into(),
        kind: raytree::shading::LightKind::Point {
            position: DVec3::new(0.0, 4.0, 3.0),
            attenuation: [1.0, 0.5, 0.25],
        },
        intensity: DVec3::ONE,
        surface: None,
    };
    let s = light.sample(DVec3::ZERO);
    // d = 5: 1/(1 + 2.5 + 6.25) = 1/9.75.
    assert_eq!(s.distance, 5.0);
    assert!((s.attenuation - 1.0 / 9.75).abs() < E);
    assert!((s.l - DVec3::new(0.0, 0.8, 0.6)).length() < E);
}

/// A box around c, at least 0.1 from it on every side.
fn box_around(c: DVec3, e: DVec3) -> Shape {
    let e = e.abs() + 0.1;
    Shape::Box(Aabox {
        min: c - e,
        max: c + e,
    })
}

/// A shape, and a transform of the kind it keeps (or any transform, for `keeps = false`).
fn moved_case() -> impl Strategy<Value = (Shape, DAffine3, bool)> {
    let v = |r: f64| prop::array::uniform3(-r..r).prop_map(DVec3::from_array);
    let turn = (v(1.0), -3.2..3.2f64).prop_filter_map("axis", |(a, angle)| {
        Some(DQuat::from_axis_angle(a.try_normalize()?, angle))
    });
    let similarity = (turn, 0.1..10.0f64, prop::bool::ANY, v(5.0)).prop_map(|(q, s, mirror, t)| {
        let m = if mirror { -1.0 } else { 1.0 };
        DAffine3::from_scale_rotation_translation(DVec3::new(m * s, s, s), q, t)
    });
    let axis_scale = (v(3.0), v(5.0)).prop_filter_map("scale", |(s, t)| {
        (s.abs().min_element() > 0.05)
            .then(|| DAffine3::from_scale_rotation_translation(s, DQuat::IDENTITY, t))
    });
    let any = (v(2.0), v(2.0), v(2.0), v(5.0)).prop_filter_map("invertible", |(a, b, c, t)| {
        let m = DAffine3::from_mat3_translation(DMat3::from_cols(a, b, c), t);
        (m.matrix3.determinant().abs() > 0.1).then_some(m)
    });
    let round =
        (v(2.0), 0.2..2.0f64, v(2.0)).prop_filter("axis", |(a, _, b)| (*a - *b).length() > 0.2);
    prop_oneof![
        (v(2.0), 0.2..2.0f64, similarity.clone()).prop_map(|(c, r, m)| (
            Shape::Sphere(Sphere {
                center: c,
                radius: r
            }),
            m,
            true
        )),
        (round.clone(), similarity.clone()).prop_map(|((a, r, b), m)| (
            Shape::Cylinder(Cylinder {
                base: a,
                top: b,
                radius: r
            }),
            m,
            true
        )),
        (round, similarity.clone()).prop_map(|((a, r, b), m)| (
            Shape::Cone(Cone {
                apex: a,
                base: b,
                radius: r
            }),
            m,
            true
        )),
        (v(2.0), v(1.0), axis_scale).prop_map(|(c, e, m)| (box_around(c, e), m, true)),
        (v(2.0), v(1.0), any.clone()).prop_filter_map("normal", |(p, n, m)| {
            Some((
                Shape::Plane(Plane {
                    point: p,
                    normal: n.try_normalize()?,
                }),
                m,
                true,
            ))
        }),
        (v(2.0), v(2.0), v(2.0), any.clone()).prop_filter_map("triangle", |(a, b, c, m)| {
            ((b - a).cross(c - a).length() > 0.1).then_some((
                Shape::Triangle(Triangle { a, b, c }),
                m,
                m.matrix3.determinant() > 0.0,
            ))
        }),
        (v(2.0), 0.2..2.0f64, any.clone()).prop_map(|(c, r, m)| {
            (
                Shape::Sphere(Sphere {
                    center: c,
                    radius: r,
                }),
                m,
                false,
            )
        }),
        (v(2.0), v(1.0), any).prop_map(|(c, e, m)| (box_around(c, e), m, false)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    /// A shape carried to world space (`Shape::moved`) is the shape seen through its
    /// transform: the same span along every ray (t to 1e−9 relative) and the same outward
    /// normals; and the shapes a transform would not keep of their kind are left alone.
    #[test]
    fn shapes_moved_to_world_space_are_the_transformed_shapes(
        (shape, m, keeps) in moved_case(),
        origin in prop::array::uniform3(-12.0..12.0f64),
        aim in prop::array::uniform3(-1.0..1.0f64),
    ) {
        let tf = Transform::new(m);
        let moved = shape.moved(&tf);
        if !keeps {
            // A general transform turns spheres into ellipsoids and boxes into parallelepipeds.
            // Rarely, a random one is close enough to a similarity or a scaling to be kept.
            let kept_of_kind = tf.similarity_scale().is_some()
                || matches!(shape, Shape::Box(_)) && m.matrix3 == DMat3::from_diagonal(DVec3::new(m.matrix3.x_axis.x, m.matrix3.y_axis.y, m.matrix3.z_axis.z));
            prop_assert_eq!(moved.is_some(), kept_of_kind);
            return Ok(());
        }
        let moved = moved.expect("kept of its kind");
        let origin = DVec3::from_array(origin);
        // Aim near the shape (most rays at a random point would miss it).
        let b = shape.bounds();
        let anchor = match &shape {
            Shape::Plane(p) => p.point,
            _ => (b.min + b.max) / 2.0,
        };
        let target = m.transform_point3(anchor + DVec3::from_array(aim));
        let Some(dir) = (target - origin).try_normalize() else {
            return Ok(());
        };
        let ray = Ray { origin, dir };
        let world = moved.span(&ray);
        let local = shape.span(&tf.ray_to_local(&ray));
        match (world, local) {
            (Some(w), Some(l)) => {
                let scale = 1.0 + l.t_in.abs().min(1e6) + l.t_out.abs().min(1e6);
                let close = |a: f64, b: f64| a == b || (a - b).abs() <= 1e-9 * scale;
                prop_assert!(close(w.t_in, l.t_in) && close(w.t_out, l.t_out), "{:?} vs {:?}", w, l);
                // Normals where the ray enters and leaves (faces may differ only at edges,
                // where the two ends' t nearly tie with another face's).
                for (t, wf, lf) in [(w.t_in, w.face_in, l.face_in), (w.t_out, w.face_out, l.face_out)] {
                    if !t.is_finite() || wf != lf {
                        continue;
                    }
                    let p = ray.at(t);
                    let n_world = moved.normal(p, wf as u32);
                    let n_local = tf.normal_to_world(shape.normal(tf.to_local.transform_point3(p), lf as u32));
                    prop_assert!((n_world - n_local).length() < 1e-7, "{} vs {}", n_world, n_local);
                }
            }
            (None, None) => {}
            // A ray that grazes the surface may be a tangent on one side and a miss on the other.
            (w, l) => {
                let width = w.or(l).map(|s| (s.t_out - s.t_in).abs()).unwrap();
                prop_assert!(width < 1e-6 * (1.0 + w.or(l).unwrap().t_in.abs()), "{:?} vs {:?}", w, l);
            }
        }
    }
}
