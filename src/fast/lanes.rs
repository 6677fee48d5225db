//! Rays in lanes: up to four rays laid out axis by axis in four-lane vectors (`F64x4`: structure of
//! arrays), so that one shape or box is tested against all of them with the same instructions.
//! Every lane computes what the one-ray routine of the core computes, in the same order.

use glam::DVec3;

use super::simd::F64x4;
use crate::accel::Aabb;
use crate::geometry::{Plane, Ray};

/// Rays (or spheres) per vector: four f64 lanes fill one 256-bit (AVX) register.
pub const LANES: usize = 4;

/// A filler for the unused places of a fixed-size array of rays.
pub const UNUSED: Ray = Ray {
    origin: DVec3::ZERO,
    dir: DVec3::Z,
};

/// Up to four rays, one per lane: a packet's rays tested against one sphere or plane at a
/// time, or one ray repeated in every lane against a group of spheres.
#[derive(Clone, Copy, Debug)]
pub struct RayLanes<V> {
    pub origin: [V; 3],
    pub dir: [V; 3],
    /// d·d, as the sphere's quadratic computes it.
    pub a: V,
}

impl<V: F64x4> RayLanes<V> {
    /// One ray in every lane.
    #[inline(always)]
    pub fn splat(ray: &Ray) -> RayLanes<V> {
        let DVec3 {
            x: dx,
            y: dy,
            z: dz,
        } = ray.dir;
        let o = ray.origin;
        RayLanes {
            origin: [V::splat(o.x), V::splat(o.y), V::splat(o.z)],
            dir: [V::splat(dx), V::splat(dy), V::splat(dz)],
            a: V::splat(dx * dx + dy * dy + dz * dz),
        }
    }

    /// The rays in lanes 0, 1, …; lanes beyond them hold `UNUSED`.
    #[inline(always)]
    pub fn new(rays: &[Ray]) -> RayLanes<V> {
        assert!(rays.len() <= LANES);
        let (mut o, mut d) = ([UNUSED.origin; LANES], [UNUSED.dir; LANES]);
        for (k, r) in rays.iter().enumerate() {
            (o[k], d[k]) = (r.origin, r.dir);
        }
        // Put together in registers (`setr`): four stores and one wide load of them would
        // stall on store forwarding.
        let axis = |v: &[DVec3; LANES], i: usize| V::setr(v[0][i], v[1][i], v[2][i], v[3][i]);
        let dir = [axis(&d, 0), axis(&d, 1), axis(&d, 2)];
        RayLanes::from_lanes([axis(&o, 0), axis(&o, 1), axis(&o, 2)], dir)
    }

    /// Rays already in lanes: origins and directions, axis by axis.
    #[inline(always)]
    pub fn from_lanes(origin: [V; 3], dir: [V; 3]) -> RayLanes<V> {
        RayLanes {
            origin,
            dir,
            a: dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2],
        }
    }
}

/// All ones in lane i when bit i of `bits` is set (bits 0–3; the others are ignored). One
/// load from a table: built lane by lane, the mask was four narrow stores read back as one
/// wide load, which waits for the stores to drain.
#[inline(always)]
pub fn lane_mask<V: F64x4>(bits: u32) -> V {
    V::new(LANE_MASKS[(bits & 0b1111) as usize])
}

/// `lane_mask` for each of the 16 sets of lanes.
static LANE_MASKS: [[f64; LANES]; 16] = {
    let mut masks = [[0.0; LANES]; 16];
    let mut bits = 0;
    while bits < 16 {
        let mut lane = 0;
        while lane < LANES {
            if bits >> lane & 1 == 1 {
                masks[bits][lane] = f64::from_bits(u64::MAX);
            }
            lane += 1;
        }
        bits += 1;
    }
    masks
};

/// Four rays in lanes prepared for slab tests against many boxes: the core's `SlabRay` four at
/// a time.
#[derive(Clone, Copy, Debug)]
pub struct SlabLanes<V> {
    origin: [V; 3],
    dir: [V; 3],
    /// 1/d per component, as `DVec3::recip` finds it ray by ray.
    inv_dir: [V; 3],
    /// All ones where 1/d is negative (`SlabRay::negative`).
    negative: [V; 3],
}

impl<V: F64x4> SlabLanes<V> {
    #[inline(always)]
    pub fn new(rays: &RayLanes<V>) -> SlabLanes<V> {
        // Written out, not `array::map`: a closure over lanes may be compiled outside the
        // wing's copy, and call each lane operation there.
        let [dx, dy, dz] = rays.dir;
        let inv_dir = [V::ONE / dx, V::ONE / dy, V::ONE / dz];
        let [ix, iy, iz] = inv_dir;
        SlabLanes {
            origin: rays.origin,
            dir: rays.dir,
            inv_dir,
            negative: [
                ix.is_sign_negative(),
                iy.is_sign_negative(),
                iz.is_sign_negative(),
            ],
        }
    }

    /// The rays themselves, as `RayLanes::new` gave them.
    #[inline(always)]
    pub fn rays(&self) -> RayLanes<V> {
        RayLanes::from_lanes(self.origin, self.dir)
    }

    /// The 1/d of the ray in one lane, bit for bit `ray.dir.recip()`.
    #[inline(always)]
    pub fn inv_dir(&self, lane: usize) -> DVec3 {
        DVec3::from_array(self.inv_dir.map(|axis| axis.to_array()[lane]))
    }

    /// The ray in one lane, as it was put in.
    #[inline(always)]
    pub fn ray(&self, lane: usize) -> Ray {
        Ray {
            origin: DVec3::from_array(self.origin.map(|axis| axis.to_array()[lane])),
            dir: DVec3::from_array(self.dir.map(|axis| axis.to_array()[lane])),
        }
    }
}

/// `Aabb::hit_slabs` for four rays at once, each lane with its own t_max: the bits of the lanes
/// whose ray passes through the box. Lane by lane the very arithmetic and comparisons of the
/// core's `slab` and `overlaps`, so each bit is what the ray's own test answers.
#[inline(always)]
pub fn box_hit_lanes<V: F64x4>(b: &Aabb, r: &SlabLanes<V>, t_min: f64, t_max: V) -> u32 {
    let (mut enter, mut exit) = (V::splat(t_min), t_max);
    for axis in 0..3 {
        let (lo, hi) = (V::splat(b.min[axis]), V::splat(b.max[axis]));
        let negative = r.negative[axis];
        let (near, far) = (negative.bitselect(hi, lo), negative.bitselect(lo, hi));
        let inv = r.inv_dir[axis];
        let t_near = (near - r.origin[axis]) * inv;
        let t_far = (far - r.origin[axis]) * inv;
        // As `slab`: a NaN compares false and leaves the interval as it was.
        enter = t_near.simd_gt(enter).bitselect(t_near, enter);
        exit = t_far.simd_lt(exit).bitselect(t_far, exit);
    }
    let slack = exit.abs() * V::splat(4.0) * V::splat(f64::EPSILON);
    enter.simd_le(exit + slack).to_bitmask()
}

/// `probe::plane_hit` for the rays of `rays` with t_min ≥ 0, with the same operations in the
/// same order: bit i set when ray lane i crosses the plane with t_min < t < t_max[i], and the
/// lanes' t (in a set lane, the one `plane_hit` returns). As there, a lane whose height and
/// rate do not have strictly opposite signs has t = −height/rate ≤ 0 (or NaN) and no
/// crossing; where that holds in every lane (shadow rays from above a floor to a light above
/// it), the division is left out.
#[inline(always)]
pub fn plane_hits_of_lanes<V: F64x4>(
    plane: &Plane,
    rays: &RayLanes<V>,
    t_min: f64,
    t_max: V,
) -> (V, u32) {
    debug_assert!(t_min >= 0.0);
    let [nx, ny, nz] = plane.normal.to_array().map(V::splat);
    let [px, py, pz] = plane.point.to_array().map(V::splat);
    let [dx, dy, dz] = rays.dir;
    let [ox, oy, oz] = rays.origin;
    let rate = dx * nx + dy * ny + dz * nz;
    let height = (ox - px) * nx + (oy - py) * ny + (oz - pz) * nz;
    let zero = V::ZERO;
    let ahead =
        (height.simd_gt(zero) & rate.simd_lt(zero)) | (height.simd_lt(zero) & rate.simd_gt(zero));
    if !ahead.any() {
        return (zero, 0);
    }
    let t = -height / rate;
    let crossing = ahead
        & t.simd_gt(V::splat(t_min))
        & t.simd_lt(t_max)
        & t.abs().simd_lt(V::splat(f64::INFINITY));
    (t, crossing.to_bitmask())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::simd::Wide;
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
            let slabs = SlabLanes::new(&RayLanes::<Wide>::new(&rays));
            let bits = box_hit_lanes(&b, &slabs, 0.0, Wide::new(t_max));
            for (i, r) in rays.iter().enumerate() {
                let inv = r.dir.recip();
                prop_assert_eq!(slabs.inv_dir(i).to_array().map(f64::to_bits), inv.to_array().map(f64::to_bits));
                let alone = b.hit(r.origin, inv, 0.0, t_max[i]);
                prop_assert_eq!(bits & (1 << i) != 0, alone, "lane {} of {:?}", i, r);
            }
        }
    }

    proptest! {
        /// Each lane's bit, and its t where the bit is set, is its own ray's `plane_hit` to
        /// the bit: rays from either side of the floor y = 0 (or on it), going up, down or
        /// along it, so that whole groups face away from it (the lanes' early exit) as often
        /// as not, with t_min 0 or positive.
        #[test]
        fn each_lanes_plane_crossing_is_its_rays_own(
            rays in proptest::collection::vec(ray(), 1..=4),
            t_max in [reach(), reach(), reach(), reach()],
            t_min in prop_oneof![Just(0.0), 0.0..1.0f64],
            up in any::<bool>(),
        ) {
            // Half the cases: every direction turned away from the floor, every origin above.
            let rays: Vec<Ray> = rays
                .iter()
                .map(|r| match up {
                    true => Ray {
                        origin: DVec3::new(r.origin.x, r.origin.y.abs(), r.origin.z),
                        dir: DVec3::new(r.dir.x, r.dir.y.abs(), r.dir.z),
                    },
                    false => *r,
                })
                .collect();
            let floor = Plane { point: DVec3::ZERO, normal: DVec3::Y };
            let lanes = RayLanes::<Wide>::new(&rays);
            let (t, bits) = plane_hits_of_lanes(&floor, &lanes, t_min, Wide::new(t_max));
            prop_assert_eq!(bits >> rays.len(), 0);
            for (i, r) in rays.iter().enumerate() {
                let alone = crate::fast::probe::plane_hit(&floor, r, t_min, t_max[i]);
                let lane = (bits & (1 << i) != 0).then(|| t.to_array()[i]);
                prop_assert_eq!(lane.map(f64::to_bits), alone.map(f64::to_bits), "lane {} of {:?}", i, r);
            }
        }
    }

    /// Each of the table's masks has all 64 bits set in exactly the lanes its bits name, and
    /// bits above the fourth change nothing.
    #[test]
    fn a_lane_mask_sets_the_lanes_its_bits_name() {
        for bits in 0..64u32 {
            let lanes = lane_mask::<Wide>(bits).to_array().map(f64::to_bits);
            for (lane, value) in lanes.into_iter().enumerate() {
                let on = bits >> lane & 1 == 1;
                assert_eq!(
                    value,
                    if on { u64::MAX } else { 0 },
                    "{bits:06b} lane {lane}"
                );
            }
            assert_eq!(lane_mask::<Wide>(bits).to_bitmask(), bits & 0b1111);
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
        let slabs = SlabLanes::new(&RayLanes::<Wide>::new(&rays));
        let t_max = Wide::new([f64::INFINITY, f64::INFINITY, f64::INFINITY, 3.9]);
        assert_eq!(box_hit_lanes(&b, &slabs, 0.0, t_max), 0b0101);
    }
}
