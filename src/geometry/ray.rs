//! A ray `p(t) = o + t·d`.
//!
//! World-space rays always carry a unit direction, so `t` is a distance. A ray mapped into an
//! object's own space keeps the (no longer unit) transformed direction, so the same `t` names
//! the same point in both spaces and segment lists never need re-scaling.

use glam::DVec3;
use wide::f64x4;

use super::sphere_group::LANES;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    pub origin: DVec3,
    pub dir: DVec3,
}

impl Ray {
    /// A filler for the unused places of a fixed-size array of rays (a packet).
    pub const UNUSED: Ray = Ray {
        origin: DVec3::ZERO,
        dir: DVec3::Z,
    };

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

    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + t * self.dir
    }
}

/// Up to four rays, one per `f64x4` lane (structure of arrays): a packet's rays tested against
/// one sphere or plane at a time, or one ray repeated in every lane against a group of spheres.
#[derive(Clone, Copy, Debug)]
pub struct RayLanes {
    pub origin: [f64x4; 3],
    pub dir: [f64x4; 3],
    /// d·d, as `Sphere::hit` computes it.
    pub a: f64x4,
}

impl RayLanes {
    /// One ray in every lane.
    #[inline(always)]
    pub fn splat(ray: &Ray) -> RayLanes {
        let DVec3 {
            x: dx,
            y: dy,
            z: dz,
        } = ray.dir;
        let o = ray.origin;
        RayLanes {
            origin: [o.x, o.y, o.z].map(f64x4::splat),
            dir: [dx, dy, dz].map(f64x4::splat),
            // As `Sphere::hit` computes d·d.
            a: f64x4::splat(dx * dx + dy * dy + dz * dz),
        }
    }

    /// The rays in lanes 0, 1, …; lanes beyond them hold `Ray::UNUSED`.
    pub fn new(rays: &[Ray]) -> RayLanes {
        assert!(rays.len() <= LANES);
        let (mut o, mut d) = ([Ray::UNUSED.origin; LANES], [Ray::UNUSED.dir; LANES]);
        for (k, r) in rays.iter().enumerate() {
            (o[k], d[k]) = (r.origin, r.dir);
        }
        let axis = |v: &[DVec3; LANES], i: usize| f64x4::new(v.map(|p| p[i]));
        let dir = [axis(&d, 0), axis(&d, 1), axis(&d, 2)];
        RayLanes::from_lanes([axis(&o, 0), axis(&o, 1), axis(&o, 2)], dir)
    }

    /// Rays already in lanes: origins and directions, axis by axis.
    #[inline(always)]
    pub fn from_lanes(origin: [f64x4; 3], dir: [f64x4; 3]) -> RayLanes {
        RayLanes {
            origin,
            dir,
            a: dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2],
        }
    }
}

/// All ones in lane i when bit i of `bits` is set.
pub fn lane_mask(bits: u32) -> f64x4 {
    let on = f64::from_bits(u64::MAX);
    f64x4::new([0, 1, 2, 3].map(|i| if bits & (1 << i) != 0 { on } else { 0.0 }))
}
