//! Sphere: |x − c|² = r².

use glam::DVec3;

use super::{Ray, Span};

/// A sphere primitive, in object space: the points within `radius` of `center`.
#[derive(Clone, Debug, PartialEq)]
pub struct Sphere {
    /// Centre of the sphere.
    pub center: DVec3,
    /// Radius of the sphere, > 0.
    pub radius: f64,
}

/// Relative tolerance under which a slightly negative discriminant counts as a tangent. The
/// lecture's tangent example (P = (−3, 1), d = (0.8, −0.6)) lands 2e−16 below zero in floating
/// point; without this it would be reported as a miss.
pub(crate) const TANGENT_TOLERANCE: f64 = 1e-12;

impl Sphere {
    /// Substituting p(t) = o + t·d gives a·t² + 2b·t + c = 0 with a = d·d, b = d·(o − c),
    /// c = |o − c|² − r² (see `Quadratic::roots` for how it is solved stably).
    pub fn span(&self, ray: &Ray) -> Option<Span> {
        let q = Quadratic::new(self, ray);
        // A line that clearly passes the sphere by needs no division or square root (the test
        // never rejects a line `roots` would accept: see `MISS_MARGIN`).
        if q.clearly_misses() {
            return None;
        }
        let (t0, t1) = q.roots()?;
        Some(Span::new(t0, 0, t1, 0))
    }

    /// Outward unit normal at a point `p` on the sphere: (p − c)/r.
    #[inline]
    pub fn normal(&self, p: DVec3) -> DVec3 {
        self.normal_facing(p, DVec3::ZERO)
    }

    /// `normal`, or `facing` where p rounds to the centre itself and has no normal: a ray's
    /// hit record passes −d, so that the surface faces the ray.
    #[inline]
    pub fn normal_facing(&self, p: DVec3, facing: DVec3) -> DVec3 {
        let n = (p - self.center) / self.radius;
        if (n.length_squared() - 1.0).abs() <= UNIT_TOLERANCE {
            n
        } else {
            self.normal_off_surface(p, facing)
        }
    }

    /// The normal at a point found off the surface: where the point's rounding is as large as
    /// the sphere (a tiny sphere seen from afar, a point 10¹⁰⁰ away), (p − c)/r is not of
    /// unit length, and (p − c)/|p − c| is the normal of the nearest point that is on it.
    #[cold]
    #[inline(never)]
    fn normal_off_surface(&self, p: DVec3, facing: DVec3) -> DVec3 {
        (p - self.center).try_normalize().unwrap_or(facing)
    }
}

/// How far |(p − c)/r|² may be from 1 for (p − c)/r to be the normal: a point on the
/// surface to rounding is off by some 10⁻¹⁶ of its coordinates, which moves |n|² by 10⁻⁹ only
/// where the sphere is 10⁻⁷ of the point's distance from the origin.
const UNIT_TOLERANCE: f64 = 1e-9;

/// Margin of the division-free miss test, relative to the size of the terms involved. Rounding
/// moves those terms by ~1e−15 of their size, so anything the test rejects is missed by a factor
/// of ~10⁹ more than the exact test's tangent tolerance needs: it never rejects a ray `span`
/// would accept.
pub(crate) const MISS_MARGIN: f64 = 1e-6;

/// Below this size of terms, products may be subnormal and lose their relative accuracy: the
/// miss test stands aside and the exact arithmetic decides.
pub(crate) const MISS_TEST_FLOOR: f64 = 1e-250;

/// The ray–sphere quadratic a·t² + 2b·t + c = 0, with the terms `span` needs (and the fast
/// wing's nearest-hit test, which must give the same t to the last bit).
pub(crate) struct Quadratic {
    oc: DVec3,
    dir: DVec3,
    a: f64,
    pub(crate) b: f64,
    pub(crate) c: f64,
    oc2: f64,
    r2: f64,
}

impl Quadratic {
    #[inline]
    pub(crate) fn new(s: &Sphere, ray: &Ray) -> Quadratic {
        let oc = ray.origin - s.center;
        let r2 = s.radius * s.radius;
        let oc2 = oc.length_squared();
        Quadratic {
            oc,
            dir: ray.dir,
            a: ray.dir.length_squared(),
            b: ray.dir.dot(oc),
            c: oc2 - r2,
            oc2,
            r2,
        }
    }

    /// b² − a·c is a times the discriminant. It cancels catastrophically for far-away rays, so
    /// it only rejects when it is negative by far more than its rounding error (bounded by a
    /// few ulps of b² + a·(|oc|² + r²)); everything else goes to the exact `roots`.
    #[inline]
    pub(crate) fn clearly_misses(&self) -> bool {
        let scale = self.b * self.b + self.a * (self.oc2 + self.r2);
        let d = self.b * self.b - self.a * self.c;
        scale > MISS_TEST_FLOOR && d < -MISS_MARGIN * scale
    }

    /// The two roots in order (equal for a tangent), or None for a miss. The discriminant
    /// b² − ac is computed as a·(r² − ℓ²), ℓ the distance from the centre to the ray's line,
    /// which does not cancel catastrophically for far-away rays; the roots use the stable form
    /// q = −(b + sign(b)·√disc), t = q/a and c/q.
    #[inline]
    pub(crate) fn roots(&self) -> Option<(f64, f64)> {
        let (a, b, r2) = (self.a, self.b, self.r2);
        let closest = self.oc - (b / a) * self.dir;
        let mut disc = r2 - closest.length_squared();
        if disc < 0.0 {
            if disc < -TANGENT_TOLERANCE * r2 {
                return None;
            }
            disc = 0.0;
        }
        let root = (a * disc).sqrt();
        let q = -(b + b.signum() * root);
        let c = self.c;
        Some(if q == 0.0 {
            (0.0, 0.0)
        } else {
            let (x, y) = (q / a, c / q);
            if disc == 0.0 {
                (x, x)
            } else {
                (x.min(y), x.max(y))
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ray that starts on the unit sphere and runs along its tangent plane touches it at
    /// t = 0, also where |oc|² rounds to 1 + 2⁻⁵² (the point at 25.2° on the equator): the
    /// division-free miss test must weigh its margin by b² + a·(|oc|² + r²), not by the
    /// terms' difference, which is as small as the rounding there.
    #[test]
    fn a_tangent_ray_from_the_surface_touches_at_zero() {
        let s = Sphere {
            center: DVec3::ZERO,
            radius: 1.0,
        };
        let angle = 56.0 * std::f64::consts::PI / 400.0;
        let origin = DVec3::new(angle.cos(), angle.sin(), 0.0);
        assert!(origin.length_squared() > 1.0);
        let span = s
            .span(&Ray::new(origin, DVec3::Z))
            .expect("a tangent touch");
        assert_eq!((span.t_in, span.t_out), (0.0, 0.0));
    }

    #[test]
    fn lecture_tangent_ray_has_double_root_at_three() {
        // Seed 004: P = (−3, 1), d = (0.8, −0.6) against the unit circle: t = 3 twice.
        let s = Sphere {
            center: DVec3::ZERO,
            radius: 1.0,
        };
        let span = s
            .span(&Ray::new(
                DVec3::new(-3.0, 1.0, 0.0),
                DVec3::new(0.8, -0.6, 0.0),
            ))
            .unwrap();
        assert!((span.t_in - 3.0).abs() < 1e-12 && (span.t_out - 3.0).abs() < 1e-12);
    }

    #[test]
    fn roots_are_accurate_far_from_the_sphere() {
        // A unit sphere seen from 1e8 away: the entry is at 1e8 − 1 exactly.
        let s = Sphere {
            center: DVec3::ZERO,
            radius: 1.0,
        };
        let span = s
            .span(&Ray::new(DVec3::new(0.0, 0.0, -1e8), DVec3::Z))
            .unwrap();
        // Within an ulp or two of 1e8 (≈ 1.5e−8): the distance itself is exact to 16 digits.
        assert!(
            (span.t_in - (1e8 - 1.0)).abs() <= 4.0 * f64::EPSILON * 1e8,
            "{}",
            span.t_in
        );
        assert!(
            (span.t_out - (1e8 + 1.0)).abs() <= 4.0 * f64::EPSILON * 1e8,
            "{}",
            span.t_out
        );
    }

    /// The division-free miss test only ever rejects lines that have no roots: swept over
    /// lines that pass the centre at (1 ± 10⁻ᵏ) radii (tangent and just inside included), from
    /// near and far, at scales from 10⁻⁴ to 10⁶.
    #[test]
    fn the_miss_test_never_rejects_a_line_with_roots() {
        for scale_exp in -4..=6 {
            let k = 10f64.powi(scale_exp);
            let s = Sphere {
                center: DVec3::new(0.3, -0.2, 0.1) * k,
                radius: 0.7 * k,
            };
            for distance in [1.5, 10.0, 1e3, 1e6] {
                for offset_exp in 1..=17 {
                    for sign in [-1.0, 0.0, 1.0] {
                        let offset = sign * 10f64.powi(-offset_exp);
                        // From `origin`, aim so the line passes the centre at (1 + offset)·r.
                        let origin = s.center + DVec3::new(-distance, 0.0, 0.0) * s.radius;
                        let sin = (1.0 + offset) / distance;
                        let dir = DVec3::new((1.0 - sin * sin).sqrt(), sin, 0.0);
                        let q = Quadratic::new(&s, &Ray { origin, dir });
                        if q.clearly_misses() {
                            assert!(q.roots().is_none(), "{s:?} {origin} {dir}");
                        } else {
                            // The margin grows with the size of the terms (the distance), but
                            // from up to 10 radii away every line that misses by 10⁻³ radii
                            // or more is rejected: the test has teeth.
                            let clear = sign > 0.0 && offset_exp <= 3 && distance <= 10.0;
                            assert!(!clear, "{offset}: {s:?} {origin}");
                        }
                    }
                }
            }
        }
    }
}
