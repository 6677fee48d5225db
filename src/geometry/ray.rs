//! A ray `p(t) = o + t·d`.
//!
//! World-space rays always carry a unit direction, so `t` is a distance. A ray mapped into an
//! object's own space keeps the (no longer unit) transformed direction, so the same `t` names
//! the same point in both spaces and segment lists never need re-scaling.

use glam::DVec3;

/// A ray p(t) = origin + t·dir; `t` is a distance when `dir` is a unit vector (world rays).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Where the ray starts (the eye, or a hit point).
    pub origin: DVec3,
    /// The direction; unit length for world rays made by `Ray::new`.
    pub dir: DVec3,
}

impl Ray {
    /// A world ray; the direction is normalised here.
    pub fn new(origin: DVec3, dir: DVec3) -> Ray {
        Ray {
            origin,
            dir: dir.normalize(),
        }
    }

    /// A ray whose direction is used as given (object-space rays).
    pub fn raw(origin: DVec3, dir: DVec3) -> Ray {
        Ray { origin, dir }
    }

    /// The point origin + t·dir at parameter `t` along the ray.
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + t * self.dir
    }
}
