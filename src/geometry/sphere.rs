//! Sphere: |x − c|² = r².

use glam::DVec3;

use super::{Ray, Span};

#[derive(Clone, Debug, PartialEq)]
pub struct Sphere {
    pub center: DVec3,
    pub radius: f64,
}

/// Relative tolerance under which a slightly negative discriminant counts as a tangent. The
/// lecture's tangent example (P = (−3, 1), d = (0.8, −0.6)) lands 2e−16 below zero in floating
/// point; without this it would be reported as a miss.
const TANGENT_TOLERANCE: f64 = 1e-12;

impl Sphere {
    /// Substituting p(t) = o + t·d gives a·t² + 2b·t + c = 0 with a = d·d, b = d·(o − c),
    /// c = |o − c|² − r². The discriminant b² − ac is computed as a·(r² − ℓ²), ℓ the distance from
    /// the centre to the ray's line, which does not cancel catastrophically for far-away rays;
    /// the roots use the stable form q = −(b + sign(b)·√disc), t = q/a and c/q.
    pub fn span(&self, ray: &Ray) -> Option<Span> {
        let oc = ray.origin - self.center;
        let a = ray.dir.length_squared();
        let b = ray.dir.dot(oc);
        let r2 = self.radius * self.radius;
        let closest = oc - (b / a) * ray.dir;
        let mut disc = r2 - closest.length_squared();
        if disc < 0.0 {
            if disc < -TANGENT_TOLERANCE * r2 {
                return None;
            }
            disc = 0.0;
        }
        let root = (a * disc).sqrt();
        let q = -(b + b.signum() * root);
        let c = oc.length_squared() - r2;
        let (t0, t1) = if q == 0.0 {
            (0.0, 0.0)
        } else {
            let (x, y) = (q / a, c / q);
            if disc == 0.0 {
                (x, x)
            } else {
                (x.min(y), x.max(y))
            }
        };
        Some(Span::new(t0, 0, t1, 0))
    }

    /// The nearest crossing with t_min < t < t_max: the same arithmetic as `span`, but a ray
    /// that starts outside and moves away is rejected before any division or square root.
    #[inline]
    pub fn hit(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        let oc = ray.origin - self.center;
        let b = ray.dir.dot(oc);
        let r2 = self.radius * self.radius;
        let c = oc.length_squared() - r2;
        if c > 0.0 && b > 0.0 {
            return None;
        }
        let s = self.span(ray)?;
        let t = if s.t_in > t_min { s.t_in } else { s.t_out };
        (t > t_min && t < t_max).then_some(t)
    }

    pub fn normal(&self, p: DVec3) -> DVec3 {
        (p - self.center) / self.radius
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
