//! The hull of a packet of rays: on each axis, the range of their origins and of their 1/d.
//!
//! A pixel's sixteen samples, or their shadow rays toward one light, are so alike that a box
//! of the BVH is almost always met by all of them or by none. One slab test of the box
//! against the hull, in interval arithmetic, proves most of those cases at the cost of a
//! single ray's test, and only the rest need the test ray by ray.
//!
//! The proof holds to the last bit, because every step of the slab test is monotone in its
//! inputs, rounding included: fl(near − o) falls as o grows; fl(a · i) over a box of a and i
//! takes its extremes at the corners; max, min and the `overlaps` slack keep their order. So
//! every ray's entry and exit lie between the hull's bounds, and a verdict on the bounds is
//! the verdict on each ray. A NaN (0 · ∞, a ray parallel to a slab) breaks that chain: a hull
//! with an infinite 1/d is not built, and such packets are tested ray by ray.

use glam::DVec3;

use super::lanes::lane_mask;
use super::simd::F64x4;
use crate::accel::aabb::overlaps;
use crate::accel::Aabb;

/// What the hull says about every ray of the packet and one box.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Verdict {
    /// Every ray misses the box.
    AllMiss,
    /// Every ray meets the box.
    AllHit,
    /// The hull cannot tell: test the rays one by one.
    Mixed,
}

/// The bounds on each axis side by side in one vector's lanes 0–2 (lane 3 is unused), so that
/// a box's three slabs are tested at once: the hull test is the largest part of a packet's
/// search of the BVH.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hull<V> {
    origin_lo: V,
    origin_hi: V,
    inv_lo: V,
    inv_hi: V,
    /// All ones on the axes where 1/d is negative, for every ray.
    negative: V,
    /// The same bounds axis by axis, for testing four boxes at once (`classify_four`).
    axes: [Axis; 3],
}

/// The hull's bounds on one axis.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Axis {
    origin_lo: f64,
    origin_hi: f64,
    inv_lo: f64,
    inv_hi: f64,
    negative: bool,
}

impl<V: F64x4> Hull<V> {
    /// The hull of rays given as (origin, 1/d), or None when two rays' 1/d differ in sign on
    /// an axis, or an origin or a 1/d is infinite or NaN (the bounds would not bound them).
    /// The definition the faster constructors (`of_directions`, `of_groups`) are tested
    /// against.
    #[cfg(test)]
    pub fn new(rays: impl IntoIterator<Item = ([f64; 3], [f64; 3])>) -> Option<Hull<V>> {
        let mut rays = rays
            .into_iter()
            .map(|(o, inv)| (DVec3::from_array(o), DVec3::from_array(inv)));
        let (o, inv) = rays.next()?;
        let negative = inv.is_negative_bitmask();
        let (mut origin_lo, mut origin_hi, mut inv_lo, mut inv_hi) = (o, o, inv, inv);
        let mut sound = (o.is_finite_mask() & inv.is_finite_mask()).all();
        for (o, inv) in rays {
            sound &= (o.is_finite_mask() & inv.is_finite_mask()).all();
            sound &= inv.is_negative_bitmask() == negative;
            origin_lo = origin_lo.min(o);
            origin_hi = origin_hi.max(o);
            inv_lo = inv_lo.min(inv);
            inv_hi = inv_hi.max(inv);
        }
        sound.then(|| Hull::of_bounds([origin_lo, origin_hi], [inv_lo, inv_hi], negative))
    }

    /// `new` for rays given by their origins and directions d: the same hull, with six
    /// divisions in all rather than three a ray. On each side of zero 1/x falls as x rises, and
    /// a correctly rounded division keeps that order, so over rays whose d share a sign on an
    /// axis the smallest 1/d is 1/(the largest d) and the largest is 1/(the smallest d), to
    /// the bit. (Sign bits and finiteness follow too: 1/d has d's sign bit, and is finite for
    /// every ray where it is for both extremes.) The bounds are found with a ray's x, y and z
    /// side by side in one vector's lanes 0–2.
    #[inline(always)]
    pub fn of_directions(rays: impl IntoIterator<Item = (DVec3, DVec3)>) -> Option<Hull<V>> {
        let mut rays = rays.into_iter();
        let (o, d) = rays.next()?;
        let (o, d) = (xyz::<V>(o), xyz::<V>(d));
        let negative = d.to_bitmask();
        let (mut origin_lo, mut origin_hi, mut d_lo, mut d_hi) = (o, o, d, d);
        // All ones where every origin is finite and no d is NaN (lane 3 holds zeros).
        let mut sound = o.is_finite() & d.simd_eq(d);
        // The axes where some ray's d differs in sign from the first's.
        let mut signs_differ = 0;
        for (o, d) in rays {
            let (o, d) = (xyz::<V>(o), xyz::<V>(d));
            sound = sound & o.is_finite() & d.simd_eq(d);
            signs_differ |= d.to_bitmask() ^ negative;
            origin_lo = origin_lo.fast_min(o);
            origin_hi = origin_hi.fast_max(o);
            d_lo = d_lo.fast_min(d);
            d_hi = d_hi.fast_max(d);
        }
        if !sound.all() || signs_differ != 0 {
            return None;
        }
        let vector = |v: V| {
            let [x, y, z, _] = v.to_array();
            DVec3::new(x, y, z)
        };
        let (inv_lo, inv_hi) = (vector(d_hi).recip(), vector(d_lo).recip());
        let finite = (inv_lo.is_finite_mask() & inv_hi.is_finite_mask()).all();
        finite.then(|| {
            let origin = [vector(origin_lo), vector(origin_hi)];
            Hull::of_bounds(origin, [inv_lo, inv_hi], negative)
        })
    }

    /// `new` for rays laid out four to a group, axis by axis: `group(q)` for each of the
    /// `count` groups, its origins and 1/d (lane k for its ray k) and the lanes that hold
    /// rays. The same bounds, found four rays at a time, and so the same hull. (Groups asked
    /// for one by one, not iterated: an iterator's items, ~200 bytes each, are copied on.)
    #[inline(always)]
    pub fn of_groups(
        count: usize,
        group: impl Fn(usize) -> ([V; 3], [V; 3], u32),
    ) -> Option<Hull<V>> {
        let (inf, neg_inf) = (V::splat(f64::INFINITY), V::splat(f64::NEG_INFINITY));
        let (mut origin_lo, mut origin_hi) = ([inf; 3], [neg_inf; 3]);
        let (mut inv_lo, mut inv_hi) = ([inf; 3], [neg_inf; 3]);
        // By axis (bit a): some ray's 1/d has its sign bit set, or some ray's has not.
        let (mut negative, mut positive) = (0u32, 0u32);
        let mut finite = true;
        for q in 0..count {
            let (origin, inv, used) = group(q);
            let unused = lane_mask::<V>(!used);
            for a in 0..3 {
                let both = origin[a].is_finite() & inv[a].is_finite();
                finite &= both.to_bitmask() & used == used;
                let signs = inv[a].to_bitmask() & used;
                negative |= ((signs != 0) as u32) << a;
                positive |= ((signs != used) as u32) << a;
                // Unused lanes hold ±∞, which neither bound takes.
                origin_lo[a] = origin_lo[a].fast_min(unused.bitselect(inf, origin[a]));
                origin_hi[a] = origin_hi[a].fast_max(unused.bitselect(neg_inf, origin[a]));
                inv_lo[a] = inv_lo[a].fast_min(unused.bitselect(inf, inv[a]));
                inv_hi[a] = inv_hi[a].fast_max(unused.bitselect(neg_inf, inv[a]));
            }
        }
        if !finite || negative & positive != 0 {
            return None;
        }
        let across = |v: [V; 3], pick: fn(f64, f64) -> f64| {
            DVec3::from_array(v.map(|v| {
                let [a, b, c, d] = v.to_array();
                pick(pick(a, b), pick(c, d))
            }))
        };
        Some(Hull::of_bounds(
            [across(origin_lo, min), across(origin_hi, max)],
            [across(inv_lo, min), across(inv_hi, max)],
            negative,
        ))
    }

    /// The hull with these bounds on origins and 1/d, whose 1/d are negative on the axes set in
    /// `negative` (bit a for axis a).
    #[inline(always)]
    fn of_bounds(
        [origin_lo, origin_hi]: [DVec3; 2],
        [inv_lo, inv_hi]: [DVec3; 2],
        negative: u32,
    ) -> Hull<V> {
        let axes = std::array::from_fn(|a| Axis {
            origin_lo: origin_lo[a],
            origin_hi: origin_hi[a],
            inv_lo: inv_lo[a],
            inv_hi: inv_hi[a],
            negative: negative & (1 << a) != 0,
        });
        Hull {
            axes,
            origin_lo: lanes(origin_lo),
            origin_hi: lanes(origin_hi),
            inv_lo: lanes(inv_lo),
            inv_hi: lanes(inv_hi),
            negative: lane_mask(negative),
        }
    }

    /// The slab test of box b for every ray at once, each ray searching [t_min, t_max] with
    /// its own t_max within [t_max_lo, t_max_hi].
    #[inline(always)]
    pub fn classify(&self, b: &Aabb, t_min: f64, (t_max_lo, t_max_hi): (f64, f64)) -> Verdict {
        let (low, high) = (lanes(b.min), lanes(b.max));
        let (near_lo, near_hi) = self.times(self.negative.bitselect(high, low));
        let (far_lo, far_hi) = self.times(self.negative.bitselect(low, high));
        // The latest entry and earliest exit over the three slabs, as the ray-by-ray test
        // finds them (the order of max and min does not change their result).
        let latest = |v: V| {
            let [x, y, z, _] = v.to_array();
            max(max(x, y), z)
        };
        let earliest = |v: V| {
            let [x, y, z, _] = v.to_array();
            min(min(x, y), z)
        };
        let (enter_lo, enter_hi) = (max(t_min, latest(near_lo)), max(t_min, latest(near_hi)));
        let (exit_lo, exit_hi) = (
            min(t_max_lo, earliest(far_lo)),
            min(t_max_hi, earliest(far_hi)),
        );
        if !overlaps(enter_lo, exit_hi) {
            Verdict::AllMiss
        } else if overlaps(enter_hi, exit_lo) {
            Verdict::AllHit
        } else {
            Verdict::Mixed
        }
    }

    /// `classify` of four boxes at once, given as their bounds axis by axis (lane k for box
    /// k, see `Node4::planes`): bit k of the first answer is set when every ray misses box k
    /// (`AllMiss`), of the second when every ray meets it (`AllHit`). The same operations
    /// in the same order as `classify`, each box in its own lane instead of each axis: the
    /// same verdicts to the last bit.
    #[inline(always)]
    pub fn classify_four(
        &self,
        planes: impl Fn(usize, bool) -> [f64; 4],
        t_min: f64,
        (t_max_lo, t_max_hi): (f64, f64),
    ) -> (u32, u32) {
        let mut near = [(V::ZERO, V::ZERO); 3];
        let mut far = [(V::ZERO, V::ZERO); 3];
        for (a, axis) in self.axes.iter().enumerate() {
            let origin = (V::splat(axis.origin_lo), V::splat(axis.origin_hi));
            let inv = (V::splat(axis.inv_lo), V::splat(axis.inv_hi));
            near[a] = times(V::new(planes(a, axis.negative)), origin, inv);
            far[a] = times(V::new(planes(a, !axis.negative)), origin, inv);
        }
        // The latest entry and earliest exit over the three slabs, in `classify`'s order.
        let t_min = V::splat(t_min);
        let enter_lo = t_min.fast_max(near[0].0.fast_max(near[1].0).fast_max(near[2].0));
        let enter_hi = t_min.fast_max(near[0].1.fast_max(near[1].1).fast_max(near[2].1));
        let exit_lo = V::splat(t_max_lo).fast_min(far[0].0.fast_min(far[1].0).fast_min(far[2].0));
        let exit_hi = V::splat(t_max_hi).fast_min(far[0].1.fast_min(far[1].1).fast_min(far[2].1));
        (
            !overlaps_lanes(enter_lo, exit_hi) & 0xf,
            overlaps_lanes(enter_hi, exit_lo),
        )
    }

    /// The range of (plane − o)·(1/d) over the hull on each axis.
    #[inline(always)]
    fn times(&self, plane: V) -> (V, V) {
        times(
            plane,
            (self.origin_lo, self.origin_hi),
            (self.inv_lo, self.inv_hi),
        )
    }
}

/// The range of (plane − o)·(1/d) for o and 1/d within their ranges, lane by lane: the
/// extremes are among the four corners of the box of (plane − o) and 1/d.
#[inline(always)]
fn times<V: F64x4>(plane: V, (origin_lo, origin_hi): (V, V), (inv_lo, inv_hi): (V, V)) -> (V, V) {
    let (a_lo, a_hi) = (plane - origin_hi, plane - origin_lo);
    let corners = [a_lo * inv_lo, a_lo * inv_hi, a_hi * inv_lo, a_hi * inv_hi];
    // Nothing here is NaN: the fast min and max, one instruction each, are exact.
    let lo = (corners[0].fast_min(corners[1])).fast_min(corners[2].fast_min(corners[3]));
    let hi = (corners[0].fast_max(corners[1])).fast_max(corners[2].fast_max(corners[3]));
    (lo, hi)
}

/// `overlaps` in each lane, as four bits (bit k for lane k): exit + |exit|·4·ε multiplied in
/// `overlaps`' order, so every bit is the same.
#[inline(always)]
pub fn overlaps_lanes<V: F64x4>(enter: V, exit: V) -> u32 {
    let slack = exit.abs() * V::splat(4.0) * V::splat(f64::EPSILON);
    enter.simd_le(exit + slack).to_bitmask()
}

/// A vector's x, y, z in lanes 0–2.
#[inline(always)]
fn lanes<V: F64x4>(v: DVec3) -> V {
    V::new([v.x, v.y, v.z, 0.0])
}

/// `lanes` from registers (`F64x4::setr`), for vectors just computed or read.
#[inline(always)]
fn xyz<V: F64x4>(v: DVec3) -> V {
    V::setr(v.x, v.y, v.z, 0.0)
}

// Plain comparisons (one instruction each): nothing here is NaN, so `f64::min`'s care for
// NaN would only cost time.
#[inline(always)]
fn min(a: f64, b: f64) -> f64 {
    if a < b {
        a
    } else {
        b
    }
}

#[inline(always)]
fn max(a: f64, b: f64) -> f64 {
    if a > b {
        a
    } else {
        b
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::aabb::SlabRay;
    use crate::fast::simd::Wide;
    use crate::sampling::Rng;

    /// Packets of 16 rays (from one point, or from points spread over a patch; directions
    /// nearly parallel or spread wide) against boxes placed so that some rays graze them:
    /// whenever the hull says all miss or all hit, every ray's own slab test agrees.
    #[test]
    fn a_verdict_on_the_hull_is_every_rays_verdict() {
        let mut rng = Rng::for_pixel(11, 0, 0);
        let mut u = move || rng.uniform();
        let mut seen = [0usize; 3];
        for case in 0..4000 {
            let base = DVec3::new(u() - 0.5, u() - 0.5, -5.0);
            let aim = DVec3::new(u() - 0.5, u() - 0.5, 1.0);
            let (spread_o, spread_d) = match case % 4 {
                0 => (0.0, 1e-3),
                1 => (1e-2, 1e-3),
                2 => (0.0, 0.3),
                _ => (0.5, 0.1),
            };
            let rays: Vec<(DVec3, DVec3)> = (0..16)
                .map(|_| {
                    let jitter = |s: f64, u: &mut dyn FnMut() -> f64| {
                        DVec3::new(u() - 0.5, u() - 0.5, u() - 0.5) * s
                    };
                    let o = base + jitter(spread_o, &mut u);
                    let d = (aim + jitter(spread_d, &mut u)).normalize();
                    (o, d)
                })
                .collect();
            let hull = Hull::<Wide>::new(
                rays.iter()
                    .map(|(o, d)| (o.to_array(), d.recip().to_array())),
            );
            let Some(hull) = hull else {
                continue;
            };
            // A box about the packet's path, its corner near the rays half the time.
            let c = base + aim * (2.0 + 4.0 * u());
            let half = DVec3::new(u(), u(), u()) * 0.3 + 0.01;
            let shift = DVec3::new(u() - 0.5, u() - 0.5, 0.0) * (4.0 * half.x);
            let b = Aabb::new(c + shift - half, c + shift + half);
            let t_max: Vec<f64> = (0..16)
                .map(|_| {
                    if u() < 0.5 {
                        f64::INFINITY
                    } else {
                        3.0 + 5.0 * u()
                    }
                })
                .collect();
            let reach = t_max
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &t| {
                    (lo.min(t), hi.max(t))
                });
            let each: Vec<bool> = rays
                .iter()
                .zip(&t_max)
                .map(|((o, d), &t)| b.hit_slabs(&SlabRay::new(*o, d.recip()), 0.0, t))
                .collect();
            match hull.classify(&b, 0.0, reach) {
                Verdict::AllMiss => {
                    seen[0] += 1;
                    assert!(each.iter().all(|h| !h), "case {case}: {each:?}");
                }
                Verdict::AllHit => {
                    seen[1] += 1;
                    assert!(each.iter().all(|&h| h), "case {case}: {each:?}");
                }
                Verdict::Mixed => seen[2] += 1,
            }
            // Four boxes at once: box 0 this one, the others moved about it.
            let boxes: [Aabb; 4] = std::array::from_fn(|k| {
                let step = DVec3::new(k as f64 * 0.7 * half.x, 0.0, -(k as f64) * half.z);
                Aabb::new(b.min + step, b.max + step)
            });
            let planes =
                |axis: usize, max: bool| boxes.map(|b| if max { b.max[axis] } else { b.min[axis] });
            let (misses, hits) = hull.classify_four(planes, 0.0, reach);
            for (k, b) in boxes.iter().enumerate() {
                let verdict = hull.classify(b, 0.0, reach);
                assert_eq!(
                    misses >> k & 1 == 1,
                    verdict == Verdict::AllMiss,
                    "case {case}"
                );
                assert_eq!(
                    hits >> k & 1 == 1,
                    verdict == Verdict::AllHit,
                    "case {case}"
                );
            }
        }
        // Every verdict was given, many times.
        assert!(seen.iter().all(|&n| n > 100), "{seen:?}");
    }

    /// Rays parallel to a slab (1/d infinite) or with 1/d of both signs on an axis get no
    /// hull: their box tests go ray by ray.
    #[test]
    fn no_hull_for_parallel_rays_or_mixed_signs() {
        let o = [0.0, 0.0, 0.0];
        assert!(Hull::<Wide>::new([(o, [1.0, f64::INFINITY, 1.0])]).is_none());
        assert!(Hull::<Wide>::new([(o, [1.0, 2.0, 1.0]), (o, [1.0, -2.0, 1.0])]).is_none());
        assert!(Hull::<Wide>::new([
            (o, [1.0, 2.0, 1.0]),
            ([f64::NAN, 0.0, 0.0], [1.0, 2.0, 1.0])
        ])
        .is_none());
        assert!(Hull::<Wide>::new([(o, [1.0, 2.0, 1.0]), (o, [3.0, 0.5, 1.0])]).is_some());
    }

    /// The hull of rays given by their directions is the hull of their 1/d, to the bit:
    /// for directions of one sign or of both, with zeros of either sign, infinities, NaN,
    /// numbers so small that 1/d overflows, and ties.
    #[test]
    fn a_hull_built_from_directions_is_the_hull_of_their_reciprocals() {
        let mut rng = Rng::for_pixel(13, 0, 0);
        let mut u = move || rng.uniform();
        let special = [
            0.0,
            -0.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            1e-310,
            -1e-310,
            f64::MIN_POSITIVE,
            f64::MAX,
            1.0,
        ];
        let mut built = 0;
        for case in 0..4000 {
            let len = 1 + case % 20;
            let sign = [1.0, -1.0, 1.0, -1.0][case % 4];
            let mut rays: Vec<(DVec3, DVec3)> = (0..len)
                .map(|_| {
                    let o = DVec3::new(u() - 0.5, 10.0 * u(), -5.0 + u());
                    let d = DVec3::new(sign * (0.1 + u()), 1e-3 + u(), sign * u().powi(9));
                    (o, d)
                })
                .collect();
            let i = (case * 7) % len;
            if case % 5 == 1 {
                rays[i].1[case % 3] = special[(case / 5) % special.len()];
            }
            if case % 13 == 2 {
                rays[i].0[1] = [f64::NAN, f64::INFINITY][case % 2];
            }
            if case % 7 == 3 {
                rays[i].1 = rays[(i + 1) % len].1; // a tie
            }
            let from_directions = Hull::<Wide>::of_directions(rays.iter().copied());
            let reciprocals = rays
                .iter()
                .map(|(o, d)| (o.to_array(), d.recip().to_array()));
            let from_reciprocals = Hull::<Wide>::new(reciprocals);
            assert_eq!(
                from_directions.map(bits),
                from_reciprocals.map(bits),
                "case {case}: {rays:?}"
            );
            built += from_reciprocals.is_some() as usize;
        }
        assert!((2000..4000).contains(&built), "{built}");
    }

    /// Every number of a hull, to the bit (its sign mask is NaN where set).
    fn bits(h: Hull<Wide>) -> Vec<u64> {
        let lanes = [h.origin_lo, h.origin_hi, h.inv_lo, h.inv_hi, h.negative];
        let axes = h.axes.iter().flat_map(|a| {
            [
                a.origin_lo,
                a.origin_hi,
                a.inv_lo,
                a.inv_hi,
                a.negative as u8 as f64,
            ]
        });
        lanes
            .iter()
            .flat_map(|v| v.to_array())
            .chain(axes)
            .map(f64::to_bits)
            .collect()
    }

    /// The hull of rays laid out four to a group is the hull of the same rays one by one, for
    /// packets of 1 to 32 rays (the last group partly filled, its spare lanes holding values
    /// that would widen the bounds), with the rays' origins and 1/d of one sign or of both, an
    /// infinite 1/d, a NaN origin, and a 1/d of −0.
    #[test]
    fn a_hull_built_four_rays_at_a_time_is_the_hull_built_ray_by_ray() {
        let mut rng = Rng::for_pixel(12, 0, 0);
        let mut u = move || rng.uniform();
        let mut built = 0;
        for case in 0..3000 {
            let len = 1 + case % 32;
            let sign = if case % 3 == 0 { -1.0 } else { 1.0 };
            let mut rays: Vec<([f64; 3], [f64; 3])> = (0..len)
                .map(|_| {
                    let o = [u() - 0.5, 10.0 * u(), -5.0 + u()];
                    let inv = [sign * (0.5 + u()), 1.0 + u(), sign * (1.0 + 3.0 * u())];
                    (o, inv)
                })
                .collect();
            let i = (case * 7) % len;
            match case % 11 {
                1 => rays[i].1[0] = -rays[i].1[0],
                2 => rays[i].1[1] = f64::INFINITY,
                3 => rays[i].0[2] = f64::NAN,
                4 => rays[i].1[2] = -0.0,
                _ => {}
            }
            // Spare lanes: far outside the rays' bounds, of the other sign, or not finite.
            let spare = [1e300, -1e300, f64::NAN, f64::INFINITY][case % 4];
            let groups: Vec<([Wide; 3], [Wide; 3], u32)> = rays
                .chunks(4)
                .map(|group| {
                    let lane = |k: usize, axis: usize, inv: bool| {
                        group
                            .get(k)
                            .map_or(spare, |(o, d)| if inv { d } else { o }[axis])
                    };
                    let axis = |axis: usize, inv: bool| {
                        Wide::new(std::array::from_fn(|k| lane(k, axis, inv)))
                    };
                    let used = (1u32 << group.len()) - 1;
                    (
                        std::array::from_fn(|a| axis(a, false)),
                        std::array::from_fn(|a| axis(a, true)),
                        used,
                    )
                })
                .collect();
            let one_by_one = Hull::<Wide>::new(rays.iter().copied());
            let four_at_a_time = Hull::<Wide>::of_groups(groups.len(), |q| groups[q]);
            assert_eq!(
                four_at_a_time.map(bits),
                one_by_one.map(bits),
                "case {case}"
            );
            built += one_by_one.is_some() as usize;
        }
        // Most packets have a hull; some have none.
        assert!((1500..3000).contains(&built), "{built}");
    }
}
