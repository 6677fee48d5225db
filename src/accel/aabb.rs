//! Axis-aligned bounding boxes: the cheap test that lets a ray skip everything inside.

use glam::{DAffine3, DVec3};

/// An axis-aligned bounding box in world space: the points with `min ≤ p ≤ max` per axis; empty
/// when some `min` exceeds its `max`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Corner with the smallest x, y and z.
    pub min: DVec3,
    /// Corner with the largest x, y and z.
    pub max: DVec3,
}

/// A ray prepared for slab tests against many boxes.
#[derive(Clone, Copy, Debug)]
pub struct SlabRay {
    /// Where the ray starts (world space).
    pub origin: DVec3,
    /// 1/d per component (±∞ for zero components).
    pub inv_dir: DVec3,
    /// Which components of the direction are negative (1/d < 0, or −∞ for d = −0).
    pub negative: [bool; 3],
}

impl SlabRay {
    /// Prepares a ray from its origin and the per-component reciprocal of its direction; the sign
    /// flags are read off `inv_dir`.
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

impl Aabb {
    /// The box with corners `min` and `max` (not checked: `min > max` on some axis gives an empty
    /// box).
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

    /// The degenerate box holding the single point `p`.
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

    /// Whether both corners are finite (false for `everything` and `empty`, and for unbounded
    /// shapes such as planes).
    pub fn is_finite(&self) -> bool {
        self.min.is_finite() && self.max.is_finite()
    }

    /// Whether the box holds no point: some axis has `min > max`.
    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x || self.min.y > self.max.y || self.min.z > self.max.z
    }

    /// The smallest box holding both boxes.
    pub fn union(&self, o: &Aabb) -> Aabb {
        Aabb::new(self.min.min(o.min), self.max.max(o.max))
    }

    /// The common part of both boxes; empty when they do not overlap.
    pub fn intersection(&self, o: &Aabb) -> Aabb {
        Aabb::new(self.min.max(o.min), self.max.min(o.max))
    }

    /// The smallest box holding this box and the point `p`.
    pub fn grow(&self, p: DVec3) -> Aabb {
        Aabb::new(self.min.min(p), self.max.max(p))
    }

    /// The midpoint of the box, the point the BVH sorts boxes by.
    pub fn center(&self) -> DVec3 {
        0.5 * (self.min + self.max)
    }

    /// The box's surface area (0 for an empty box): the SAH's measure of how likely a ray is to hit
    /// it.
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
    pub fn hit(&self, origin: DVec3, inv_dir: DVec3, t_min: f64, t_max: f64) -> bool {
        self.hit_slabs(&SlabRay::new(origin, inv_dir), t_min, t_max)
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
