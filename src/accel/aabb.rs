//! Axis-aligned bounding boxes: the cheap test that lets a ray skip everything inside.

use glam::{DAffine3, DVec3};
use wide::f64x4;

use crate::geometry::{Ray, RayLanes};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: DVec3,
    pub max: DVec3,
}

/// A ray prepared for slab tests against many boxes.
#[derive(Clone, Copy, Debug)]
pub struct SlabRay {
    pub origin: DVec3,
    /// 1/d per component (±∞ for zero components).
    pub inv_dir: DVec3,
    /// Which components of the direction are negative (1/d < 0, or −∞ for d = −0).
    pub negative: [bool; 3],
}

impl SlabRay {
    pub fn new(origin: DVec3, inv_dir: DVec3) -> SlabRay {
        SlabRay {
            origin,
            inv_dir,
            negative: [
                inv_dir.x.is_sign_negative(),
                inv_dir.y.is_sign_negative(),
                inv_dir.z.is_sign_negative(),
            ],
        }
    }
}

/// Four rays in lanes prepared for slab tests: `SlabRay` four at a time.
#[derive(Clone, Copy, Debug)]
pub struct SlabLanes {
    origin: [f64x4; 3],
    dir: [f64x4; 3],
    /// 1/d per component, as `DVec3::recip` finds it ray by ray.
    inv_dir: [f64x4; 3],
    /// All ones where 1/d is negative (`SlabRay::negative`).
    negative: [f64x4; 3],
}

impl SlabLanes {
    pub fn new(rays: &RayLanes) -> SlabLanes {
        let inv_dir = rays.dir.map(|d| f64x4::ONE / d);
        SlabLanes {
            origin: rays.origin,
            dir: rays.dir,
            inv_dir,
            negative: inv_dir.map(f64x4::is_sign_negative),
        }
    }

    /// The rays themselves, as `RayLanes::new` gave them.
    #[inline(always)]
    pub fn rays(&self) -> RayLanes {
        RayLanes::from_lanes(self.origin, self.dir)
    }

    /// The 1/d of the ray in one lane, bit for bit `ray.dir.recip()`.
    pub fn inv_dir(&self, lane: usize) -> DVec3 {
        DVec3::from_array(self.inv_dir.map(|axis| axis.to_array()[lane]))
    }
}

impl Aabb {
    pub fn new(min: DVec3, max: DVec3) -> Aabb {
        Aabb { min, max }
    }

    /// The empty box: the identity of `union`.
    pub fn empty() -> Aabb {
        Aabb::new(DVec3::INFINITY, DVec3::NEG_INFINITY)
    }

    /// All of space: for planes and complements, which no box can bound.
    pub fn everything() -> Aabb {
        Aabb::new(DVec3::NEG_INFINITY, DVec3::INFINITY)
    }

    pub fn point(p: DVec3) -> Aabb {
        Aabb::new(p, p)
    }

    /// Bounds of a disc of radius r around `center`, perpendicular to the unit `axis`.
    pub fn around_disc(center: DVec3, axis: DVec3, r: f64) -> Aabb {
        // Along coordinate axis i the disc extends r·√(1 − aᵢ²).
        let e: DVec3 = r * DVec3::from_array(
            (DVec3::ONE - axis * axis)
                .max(DVec3::ZERO)
                .to_array()
                .map(f64::sqrt),
        );
        Aabb::new(center - e, center + e)
    }

    pub fn is_finite(&self) -> bool {
        self.min.is_finite() && self.max.is_finite()
    }

    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x || self.min.y > self.max.y || self.min.z > self.max.z
    }

    pub fn union(&self, o: &Aabb) -> Aabb {
        Aabb::new(self.min.min(o.min), self.max.max(o.max))
    }

    pub fn intersection(&self, o: &Aabb) -> Aabb {
        Aabb::new(self.min.max(o.min), self.max.min(o.max))
    }

    pub fn grow(&self, p: DVec3) -> Aabb {
        Aabb::new(self.min.min(p), self.max.max(p))
    }

    pub fn center(&self) -> DVec3 {
        0.5 * (self.min + self.max)
    }

    pub fn surface_area(&self) -> f64 {
        let e = (self.max - self.min).max(DVec3::ZERO);
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    /// The box around the transformed corners.
    pub fn transformed(&self, m: &DAffine3) -> Aabb {
        if !self.is_finite() {
            return if self.is_empty() {
                *self
            } else {
                Aabb::everything()
            };
        }
        (0..8).fold(Aabb::empty(), |b, i| {
            let corner = DVec3::new(
                if i & 1 == 0 { self.min.x } else { self.max.x },
                if i & 2 == 0 { self.min.y } else { self.max.y },
                if i & 4 == 0 { self.min.z } else { self.max.z },
            );
            b.grow(m.transform_point3(corner))
        })
    }

    /// Slab test: does the ray pass through the box for some t in [t_min, t_max]?
    /// `inv_dir` is 1/d per component (±∞ for zero components).
    #[inline]
    pub fn hit(&self, ray: &Ray, inv_dir: DVec3, t_min: f64, t_max: f64) -> bool {
        self.hit_slabs(&SlabRay::new(ray.origin, inv_dir), t_min, t_max)
    }

    /// The slab test for a ray prepared once for many boxes (Williams et al. 2005): the
    /// direction's signs say which face of each slab is entered first, so every slab costs a
    /// subtraction and a multiplication per face and the interval only ever shrinks.
    #[inline(always)]
    pub fn hit_slabs(&self, r: &SlabRay, t_min: f64, t_max: f64) -> bool {
        let (mut enter, mut exit) = (t_min, t_max);
        for axis in 0..3 {
            (enter, exit) = slab(
                (self.min[axis], self.max[axis]),
                r.origin[axis],
                r.inv_dir[axis],
                (enter, exit),
            );
        }
        overlaps(enter, exit)
    }

    /// `hit_slabs` for four rays at once, each lane with its own t_max: the bits of the lanes
    /// whose ray passes through the box. Lane by lane the very arithmetic and comparisons of
    /// `slab` and `overlaps`, so each bit is what the ray's own test answers.
    #[inline(always)]
    pub fn hit_lanes(&self, r: &SlabLanes, t_min: f64, t_max: f64x4) -> u32 {
        let (mut enter, mut exit) = (f64x4::splat(t_min), t_max);
        for axis in 0..3 {
            let (lo, hi) = (f64x4::splat(self.min[axis]), f64x4::splat(self.max[axis]));
            let negative = r.negative[axis];
            let (near, far) = (negative.bitselect(hi, lo), negative.bitselect(lo, hi));
            let inv = r.inv_dir[axis];
            let t_near = (near - r.origin[axis]) * inv;
            let t_far = (far - r.origin[axis]) * inv;
            // As `slab`: a NaN compares false and leaves the interval as it was.
            enter = t_near.simd_gt(enter).bitselect(t_near, enter);
            exit = t_far.simd_lt(exit).bitselect(t_far, exit);
        }
        let slack = exit.abs() * f64x4::splat(4.0) * f64x4::splat(f64::EPSILON);
        enter.simd_le(exit + slack).to_bitmask()
    }
}

/// One slab of the slab test: the interval (enter, exit) of t, narrowed to where the ray lies
/// between the planes lo and hi of one axis. The sign of 1/d says which plane it meets first.
/// Written so a NaN (0·∞: the origin on a slab's plane, the ray parallel to it) compares false
/// and leaves the interval as it was: it must not reject.
#[inline(always)]
pub fn slab(
    (lo, hi): (f64, f64),
    origin: f64,
    inv_dir: f64,
    (enter, exit): (f64, f64),
) -> (f64, f64) {
    let (near, far) = if inv_dir.is_sign_negative() {
        (hi, lo)
    } else {
        (lo, hi)
    };
    let t_near = (near - origin) * inv_dir;
    let t_far = (far - origin) * inv_dir;
    (
        if t_near > enter { t_near } else { enter },
        if t_far < exit { t_far } else { exit },
    )
}

/// Whether the slabs left an interval: enter ≤ exit, with a few ulps of slack so that a ray
/// grazing an edge (where rounding can put enter a hair past exit) still counts.
#[inline(always)]
pub fn overlaps(enter: f64, exit: f64) -> bool {
    enter <= exit + exit.abs() * 4.0 * f64::EPSILON
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A coordinate that often sits exactly on a box's face (−1 or 1), at zero, or anywhere.
    fn coordinate() -> impl Strategy<Value = f64> {
        prop_oneof![Just(-1.0), Just(1.0), Just(0.0), Just(-0.0), -3.0..3.0f64]
    }

    /// A direction component that is often zero (of either sign: a ray parallel to a slab),
    /// tiny, or anything.
    fn component() -> impl Strategy<Value = f64> {
        prop_oneof![Just(0.0), Just(-0.0), Just(1e-300), -1.0..1.0f64]
    }

    fn ray() -> impl Strategy<Value = Ray> {
        (
            [coordinate(), coordinate(), coordinate()],
            [component(), component(), component()],
        )
            .prop_map(|(o, d)| Ray {
                origin: DVec3::from_array(o),
                dir: DVec3::from_array(d),
            })
    }

    fn reach() -> impl Strategy<Value = f64> {
        prop_oneof![Just(f64::INFINITY), Just(0.0), 0.0..5.0f64]
    }

    proptest! {
        /// Each lane's bit is its own ray's slab test, for rays that start on a face, run
        /// parallel to a slab (0 · ∞ is NaN there) or along an edge, and each lane's 1/d is
        /// the ray's own `recip` to the last bit.
        #[test]
        fn each_lanes_bit_is_its_rays_own_slab_test(
            rays in proptest::collection::vec(ray(), 1..=4),
            t_max in [reach(), reach(), reach(), reach()],
            flat in any::<bool>(),
        ) {
            // The box [−1, 1]³, or a flat one (a face with no thickness along y).
            let max = if flat { DVec3::new(1.0, -1.0, 1.0) } else { DVec3::ONE };
            let b = Aabb::new(-DVec3::ONE, max);
            let slabs = SlabLanes::new(&RayLanes::new(&rays));
            let bits = b.hit_lanes(&slabs, 0.0, f64x4::new(t_max));
            for (i, r) in rays.iter().enumerate() {
                let inv = r.dir.recip();
                prop_assert_eq!(slabs.inv_dir(i).to_array().map(f64::to_bits), inv.to_array().map(f64::to_bits));
                let alone = b.hit(r, inv, 0.0, t_max[i]);
                prop_assert_eq!(bits & (1 << i) != 0, alone, "lane {} of {:?}", i, r);
            }
        }
    }

    /// The cases the lanes must get right, named: a ray through the box, one beside it, one
    /// lying in a face's plane and parallel to it (NaN, which must not reject), and one whose
    /// box lies beyond its t_max.
    #[test]
    fn lanes_hit_miss_graze_and_stop_short() {
        let b = Aabb::new(-DVec3::ONE, DVec3::ONE);
        let z = DVec3::new(0.0, 0.0, 1.0);
        // From x = 0 (through), x = 2 (beside), x = 1 (in the face x = 1), x = 0 again.
        let rays = [0.0, 2.0, 1.0, 0.0].map(|x| Ray {
            origin: DVec3::new(x, 0.0, -5.0),
            dir: z,
        });
        let slabs = SlabLanes::new(&RayLanes::new(&rays));
        let t_max = f64x4::new([f64::INFINITY, f64::INFINITY, f64::INFINITY, 3.9]);
        assert_eq!(b.hit_lanes(&slabs, 0.0, t_max), 0b0101);
    }
}
