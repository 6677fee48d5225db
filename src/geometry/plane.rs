//! Plane (x − p)·n = 0, taken as the solid half-space behind its normal so that it can take
//! part in CSG like any other solid.

use glam::DVec3;
use wide::f64x4;

use super::ray::RayLanes;
use super::{Ray, Span};

#[derive(Clone, Debug, PartialEq)]
pub struct Plane {
    pub point: DVec3,
    /// Unit outward normal.
    pub normal: DVec3,
}

impl Plane {
    /// t = −(o − p)·n / (d·n); entering when the ray travels against the normal.
    pub fn span(&self, ray: &Ray) -> Option<Span> {
        let height = (ray.origin - self.point).dot(self.normal);
        let rate = ray.dir.dot(self.normal);
        if rate == 0.0 {
            return (height <= 0.0).then(|| Span::new(f64::NEG_INFINITY, 0, f64::INFINITY, 0));
        }
        let t = -height / rate;
        Some(if rate < 0.0 {
            Span::new(t, 0, f64::INFINITY, 0)
        } else {
            Span::new(f64::NEG_INFINITY, 0, t, 0)
        })
    }

    /// The crossing with t_min < t < t_max (and finite): what the nearest-hit search would take
    /// from `span` (the finite end past t_min), without building the span.
    #[inline]
    pub fn hit(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
        let rate = ray.dir.dot(self.normal);
        if rate == 0.0 {
            // Parallel: `span` is all or nothing, with no finite end.
            return None;
        }
        let height = (ray.origin - self.point).dot(self.normal);
        if t_min >= 0.0 && height.is_sign_negative() == rate.is_sign_negative() {
            // t = −height/rate ≤ 0 (or NaN): behind the ray; no division needed to know.
            return None;
        }
        let t = -height / rate;
        (t > t_min && t < t_max && t.is_finite()).then_some(t)
    }

    /// `hit` for the rays of `rays` with t_min ≥ 0, with the same operations in the same
    /// order: each lane's t, and bit i set when ray lane i crosses the plane with
    /// t_min < t < t_max[i] (that t is then the one `hit` returns). `hit`'s early exit for
    /// height and rate of the same sign needs no test here: t = −height/rate ≤ 0 there.
    #[inline(always)]
    pub fn hits_of_lanes(&self, rays: &RayLanes, t_min: f64, t_max: f64x4) -> (f64x4, u32) {
        debug_assert!(t_min >= 0.0);
        let [nx, ny, nz] = self.normal.to_array().map(f64x4::splat);
        let [px, py, pz] = self.point.to_array().map(f64x4::splat);
        let [dx, dy, dz] = rays.dir;
        let [ox, oy, oz] = rays.origin;
        let rate = dx * nx + dy * ny + dz * nz;
        let height = (ox - px) * nx + (oy - py) * ny + (oz - pz) * nz;
        let t = -height / rate;
        let crossing = rate.simd_ne(f64x4::ZERO)
            & t.simd_gt(f64x4::splat(t_min))
            & t.simd_lt(t_max)
            & t.abs().simd_lt(f64x4::splat(f64::INFINITY));
        (t, crossing.to_bitmask())
    }
}
