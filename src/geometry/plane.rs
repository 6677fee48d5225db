//! Plane (x − p)·n = 0, taken as the solid half-space behind its normal so that it can take
//! part in CSG like any other solid.

use super::{Ray, Span};
use glam::DVec3;

/// An infinite plane primitive, a half-space solid: the inside is the side the normal points away
/// from.
#[derive(Clone, Debug, PartialEq)]
pub struct Plane {
    /// Any point on the plane.
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
}
