//! The BVH searched by a packet of rays at once (the grid samples of a pixel or two, which take
//! nearly the same path through the tree): the fast wing's tree of four children a node
//! (`bvh4.rs`), each node fetched once for the packet and its four boxes tested for all its rays
//! together. Each ray meets the leaves in the order the core's `Bvh::closest` or `Bvh::any` meets
//! them in the binary tree, and tests the items of exactly the leaves those visit, with the same
//! arithmetic.

use arrayvec::ArrayVec;

use super::bvh4::{Bvh4, Node4};
use super::hull::{overlaps_lanes, Hull, Verdict};
use super::lanes::{lane_mask, RayLanes};
use super::simd::F64x4;
use crate::accel::aabb::slab;
use crate::accel::{Aabb, Visits};
use crate::geometry::Ray;

/// Which way a ray's direction points on each axis, as the traversal orders children by it
/// (the signs of 1/d, −0 counting as negative: the signs of d itself, read without the
/// divisions). Rays with equal signs take the same path through the ordering.
pub fn signs(r: &Ray) -> [bool; 3] {
    r.dir.to_array().map(f64::is_sign_negative)
}

/// Up to `PACKET` rays laid out by component in groups of four, for slab tests of one box against
/// all of them: each group is one set of 4-wide vector instructions. The unused lanes of the
/// last group hold `UNUSED` (their answers are masked off).
struct Packet<V> {
    quads: [Quad; PACKET / 4],
    len: usize,
    /// The rays' hull, which answers most box tests for all of them at once.
    hull: Option<Hull<V>>,
}

#[derive(Clone, Copy, Default)]
struct Quad {
    origin: [[f64; 4]; 3],
    inv_dir: [[f64; 4]; 3],
}

/// The most rays searched together.
pub const PACKET: usize = 32;

/// A set of a packet's rays: bit i for ray i.
pub type RaySet = u32;

const _: () = assert!(PACKET <= RaySet::BITS as usize, "a RaySet names every ray");

/// The four bits of a set of rays for its group of four number `q` (rays 4q to 4q + 3).
#[inline(always)]
pub fn quad_bits(rays: RaySet, q: usize) -> u32 {
    rays >> (4 * q) & 0b1111
}

/// The set of the first `len` rays of a packet (1 ≤ len ≤ `PACKET`).
#[inline(always)]
pub fn first_rays(len: usize) -> RaySet {
    RaySet::MAX >> (RaySet::BITS as usize - len)
}

impl<V: F64x4> Packet<V> {
    /// A packet of `len` rays, to be laid out where it stays (`lay_out`): a packet returned
    /// whole would be copied on (1.9 kB), and the copy's wide loads wait for the narrower
    /// stores just made.
    #[inline(always)]
    fn empty(len: usize) -> Packet<V> {
        assert!((1..=PACKET).contains(&len), "1 to {PACKET} rays per packet");
        Packet {
            quads: [Quad::default(); PACKET / 4],
            len,
            hull: None,
        }
    }

    /// The packet's rays from the groups of four the searches lay them out in for the
    /// objects' tests (`RayLanes`): 1/d four lanes at a time, the same division as
    /// `DVec3::recip` in each lane.
    #[inline(always)]
    fn lay_out(&mut self, quads: &[RayLanes<V>; PACKET / 4]) {
        let groups = self.len.div_ceil(4);
        for (quad, lanes) in self.quads.iter_mut().zip(quads).take(groups) {
            for axis in 0..3 {
                quad.origin[axis] = lanes.origin[axis].to_array();
                quad.inv_dir[axis] = (V::splat(1.0) / lanes.dir[axis]).to_array();
            }
        }
        let rays = first_rays(self.len);
        self.hull = Hull::of_groups(
            groups,
            #[inline(always)]
            |q| {
                let [x, y, z] = self.quads[q].inv_dir;
                (
                    quads[q].origin,
                    [V::new(x), V::new(y), V::new(z)],
                    quad_bits(rays, q),
                )
            },
        );
    }

    /// Bit i set if ray i meets the box within [t_min, t_max[i]], for the rays `active` names:
    /// `Aabb::hit_slabs` for every lane, with the same `slab` and `overlaps` steps, so the same
    /// answer to the last bit. `reach` bounds the rays' t_max; with it the hull answers for all
    /// of them when it can (as exactly: see `hull.rs`).
    #[inline(always)]
    fn hits(
        &self,
        b: &Aabb,
        t_min: f64,
        t_max: &[f64; PACKET],
        reach: (f64, f64),
        active: RaySet,
    ) -> RaySet {
        if let Some(hull) = &self.hull {
            match hull.classify(b, t_min, reach) {
                Verdict::AllMiss => return 0,
                Verdict::AllHit => return active,
                Verdict::Mixed => {}
            }
        }
        self.ray_by_ray(b, t_min, t_max, active)
    }

    /// The hull's verdicts on the four children of a node at once, in one set of vector
    /// instructions; none without a hull.
    #[inline(always)]
    fn verdicts_four(&self, node: &Node4, t_min: f64, reach: (f64, f64)) -> Verdicts {
        let (misses, all_hit) = match &self.hull {
            Some(hull) => hull.classify_four(
                #[inline(always)]
                |axis, max| node.planes(axis, max),
                t_min,
                reach,
            ),
            None => (0, 0),
        };
        Verdicts { misses, all_hit }
    }

    /// `hits` for child k of a node, given the hull's `verdicts` on its children (0 for an
    /// unused child): the rays one by one where the hull cannot tell. (Asked child by child
    /// as the walk pushes them: an array of the four answers, written four bytes at a time
    /// and copied on sixteen at a time, waits for its stores.)
    #[inline(always)]
    fn child_hits(
        &self,
        node: &Node4,
        k: usize,
        verdicts: Verdicts,
        t_min: f64,
        t_max: &[f64; PACKET],
        active: RaySet,
    ) -> RaySet {
        let bit = 1 << k;
        if u32::from(node.used) & bit == 0 || verdicts.misses & bit != 0 {
            0
        } else if verdicts.all_hit & bit != 0 {
            active
        } else {
            self.ray_by_ray(&node.bounds(k), t_min, t_max, active)
        }
    }

    /// The slab test of one box, ray by ray in groups of four.
    #[inline(always)]
    fn ray_by_ray(&self, b: &Aabb, t_min: f64, t_max: &[f64; PACKET], active: RaySet) -> RaySet {
        let mut mask: RaySet = 0;
        for (q, quad) in self.quads.iter().enumerate().take(self.len.div_ceil(4)) {
            if quad_bits(active, q) == 0 {
                continue;
            }
            let mut enter = [t_min; 4];
            let mut exit: [f64; 4] = t_max[4 * q..4 * q + 4].try_into().unwrap();
            for axis in 0..3 {
                for lane in 0..4 {
                    (enter[lane], exit[lane]) = slab(
                        (b.min[axis], b.max[axis]),
                        quad.origin[axis][lane],
                        quad.inv_dir[axis][lane],
                        (enter[lane], exit[lane]),
                    );
                }
            }
            mask |= RaySet::from(overlaps4::<V>(&enter, &exit)) << (4 * q);
        }
        mask & active
    }
}

/// `overlaps` for four lanes, as four bits (bit k for lane k): one vector compare and one mask
/// move (written lane by lane, the compiler takes the four bits out of the compare one at a
/// time and puts them back together).
#[inline(always)]
fn overlaps4<V: F64x4>(enter: &[f64; 4], exit: &[f64; 4]) -> u8 {
    overlaps_lanes(V::new(*enter), V::new(*exit)) as u8
}

/// For each group of four lanes, the mask of the lanes that hold one of the first `len` rays.
#[inline(always)]
fn lane_masks<V: F64x4>(len: usize) -> [V; PACKET / 4] {
    let bits = first_rays(len);
    let mut masks = [V::ZERO; PACKET / 4];
    for (q, mask) in masks.iter_mut().enumerate() {
        *mask = lane_mask(quad_bits(bits, q));
    }
    masks
}

/// The lowest and highest t_max of the rays the masks name (∞ and −∞ without any; a NaN is
/// passed over): four-lane minima and maxima folded pairwise, a tree as deep as the packet
/// has groups of four, where a fold over the rays one by one is a chain as long as the packet,
/// and the next box test waits on it.
#[inline(always)]
fn reach_of<V: F64x4>(t_max: &[f64; PACKET], used: &[V; PACKET / 4]) -> (f64, f64) {
    let (inf, neg_inf) = (V::splat(f64::INFINITY), V::splat(f64::NEG_INFINITY));
    let mut lo = [inf; PACKET / 4];
    let mut hi = [neg_inf; PACKET / 4];
    for q in 0..PACKET / 4 {
        let t = V::new(t_max[4 * q..4 * q + 4].try_into().unwrap());
        // `min` and `max` keep their first operand where the second is NaN.
        lo[q] = inf.min(used[q].bitselect(t, inf));
        hi[q] = neg_inf.max(used[q].bitselect(t, neg_inf));
    }
    let mut width = PACKET / 4;
    while width > 1 {
        width /= 2;
        for q in 0..width {
            lo[q] = lo[q].min(lo[q + width]);
            hi[q] = hi[q].max(hi[q + width]);
        }
    }
    let (lo, hi) = (lo[0].to_array(), hi[0].to_array());
    let least = |a: f64, b: f64| if b < a { b } else { a };
    let most = |a: f64, b: f64| if b > a { b } else { a };
    (
        least(least(lo[0], lo[1]), least(lo[2], lo[3])),
        most(most(hi[0], hi[1]), most(hi[2], hi[3])),
    )
}

/// `closest` for a packet of up to `PACKET` rays at once (the samples of a pixel or two:
/// nearly the same path through the tree), also given in groups of four (`quads`,
/// `RayLanes::new` of each four in order). A node is fetched once for the packet and its four
/// children's boxes tested for all its rays together. At a leaf, `visit(item, rays, t_max)`
/// runs for each item with the set of rays that reached it (bit i for ray i): it is
/// `closest`'s visit for each of them, lowering `t_max[i]` to a nearer hit, and answers the
/// rays whose t_max it may have lowered (a superset will do: the walk tests boxes again only
/// after a leaf that lowered some t_max).
///
/// The rays' directions must have the signs of the first one's (see `signs`): then every ray
/// meets the leaves in the order `closest` takes it through the binary tree, and visits the
/// items of exactly the leaves `closest` visits, so its answer is `closest`'s to the last
/// bit, ties included.
#[inline(always)]
pub fn closest_packet<V: F64x4>(
    bvh: &Bvh4,
    rays: &[Ray],
    quads: &[RayLanes<V>; PACKET / 4],
    t_min: f64,
    t_max: &mut [f64; PACKET],
    mut visit: impl FnMut(u32, RaySet, &mut [f64; PACKET]) -> RaySet,
) -> Visits {
    let Some(first) = rays.first() else {
        return Visits::default();
    };
    let negative = signs(first);
    debug_assert!(rays.iter().all(|r| signs(r) == negative));
    let (_, work) = walk_packet::<V>(
        bvh,
        (quads, rays.len()),
        t_min,
        t_max,
        Some(negative),
        0,
        // Inlined into the walk, so that the visits are compiled in the lanes' copy.
        #[inline(always)]
        |item, rays, t_max| Reached {
            done: 0,
            lowered: visit(item, rays, t_max),
        },
    );
    work
}

/// `any` for a packet of up to `PACKET` rays, given as their groups of four (`RayLanes::new` of
/// each four in order) and their count, ray i searching [t_min, t_max[i]]: bit i of the
/// answer is set when ray i met a blocker. The rays of `blocked` are answered already (a
/// blocker found before the walk): they take no part. At a leaf, `visit(item, rays, t_max)`
/// runs for each item with the set of rays still searching that reached it and answers those
/// it blocks. Each other ray meets the leaves in the order `any` takes it, visits the items
/// of the leaves `any` visits, and leaves the packet at its first blocker; the directions may
/// point anywhere (the order does not depend on them). The walk takes `t_max` as its own and
/// hands it to `visit` as it is (a blocker lowers no ray's t_max): the caller's array, not a
/// copy of it (256 bytes through memcpy, for every packet).
#[inline(always)]
pub fn any_packet<V: F64x4>(
    bvh: &Bvh4,
    rays: (&[RayLanes<V>; PACKET / 4], usize),
    t_min: f64,
    t_max: &mut [f64; PACKET],
    blocked: RaySet,
    mut visit: impl FnMut(u32, RaySet, &[f64; PACKET]) -> RaySet,
) -> (RaySet, Visits) {
    walk_packet::<V>(
        bvh,
        rays,
        t_min,
        t_max,
        None,
        blocked,
        #[inline(always)]
        |item, rays, t_max| Reached {
            done: visit(item, rays, t_max),
            lowered: 0,
        },
    )
}

/// What a leaf's item did to the rays that reached it: the rays it answered for good
/// (`any`'s blockers), and those whose t_max it may have lowered (`closest`'s nearer hits).
struct Reached {
    done: RaySet,
    lowered: RaySet,
}

/// The hull's verdicts on a node's four children: bit k of `misses`, every ray misses child
/// k; of `all_hit`, every ray meets it.
#[derive(Clone, Copy)]
struct Verdicts {
    misses: u32,
    all_hit: u32,
}

/// A child waiting on the walk's stack: child `slot` of node `node`, with the rays that met its
/// box when it was tested, after `leaves` leaves had been visited.
#[derive(Clone, Copy)]
struct Pending {
    node: u32,
    slot: u8,
    rays: RaySet,
    leaves: u32,
}

/// A packet's walk in progress: the children waiting, and how many visited leaves lowered
/// some ray's t_max (only closest's visits lower them).
struct Walk<'a, V> {
    bvh: &'a Bvh4,
    packet: &'a Packet<V>,
    t_min: f64,
    signs: Option<[bool; 3]>,
    stack: ArrayVec<Pending, STACK>,
    leaves: u32,
}

impl<V: F64x4> Walk<'_, V> {
    /// Tests node `index`'s children for the rays `active` and pushes those met, so that they
    /// come off the stack in the binary walk's order.
    #[inline(always)]
    fn enter(
        &mut self,
        index: u32,
        active: RaySet,
        t_max: &[f64; PACKET],
        reach: (f64, f64),
        work: &mut Visits,
    ) {
        let node = &self.bvh.nodes()[index as usize];
        work.nodes += u64::from(active.count_ones());
        let verdicts = self.packet.verdicts_four(node, self.t_min, reach);
        for k in node.order(self.signs).into_iter().rev() {
            let rays = self
                .packet
                .child_hits(node, k, verdicts, self.t_min, t_max, active);
            if rays != 0 {
                self.stack.push(Pending {
                    node: index,
                    slot: k as u8,
                    rays,
                    leaves: self.leaves,
                });
            }
        }
    }

    #[inline(always)]
    fn pop(&mut self) -> Option<Pending> {
        self.stack.pop()
    }
}

/// The most children waiting at once: three a level (a node's fourth child is taken at once)
/// for the binary tree's deepest path folded in two, and the root's four.
const STACK: usize = 128;

/// The depth-first walk of both packet searches, for the packet's `len` rays given in groups
/// of four (`quads`) that are not `done` at its start. A node's four children are tested at
/// once for the rays that reached the node, and pushed in the order the binary tree's walk
/// meets them (`Node4::order`): nearer side first by the rays' common `signs`, or left first
/// without them (as `any` does). At a leaf, `step(item, rays, t_max)` runs for every item, in
/// order, with the rays that meet the leaf's box and are not done, and answers those that are
/// done now (they leave the packet) and those whose t_max it lowered. Answers the rays that
/// are done.
///
/// Which rays visit a leaf is exactly the binary walk's: there, a ray visits a leaf when it
/// meets the leaf's box with the t_max it has when the leaf comes off the stack (meeting it
/// then, it met every box above, which holds it, earlier and with a t_max no smaller). Here
/// the children are tested when their parent is taken; a leaf tested before an earlier leaf
/// lowered some t_max (closest's visits) is tested again when it comes off the stack (a leaf
/// tested since would answer the same).
/// Subtrees are not tested again: their rays are a superset of those that meet them, and their
/// leaves' own tests decide.
#[inline(always)]
fn walk_packet<V: F64x4>(
    bvh: &Bvh4,
    (quads, len): (&[RayLanes<V>; PACKET / 4], usize),
    t_min: f64,
    t_max: &mut [f64; PACKET],
    signs: Option<[bool; 3]>,
    mut done: RaySet,
    mut step: impl FnMut(u32, RaySet, &mut [f64; PACKET]) -> Reached,
) -> (RaySet, Visits) {
    let mut work = Visits::default();
    if bvh.nodes().is_empty() || len == 0 {
        return (0, work);
    }
    let all = first_rays(len);
    // The range of the rays' t_max, narrowed again after every leaf (a closer hit).
    let used = lane_masks::<V>(len);
    let mut reach = reach_of::<V>(t_max, &used);
    let mut packet = Packet::<V>::empty(len);
    packet.lay_out(quads);
    let mut walk = Walk {
        bvh,
        packet: &packet,
        t_min,
        signs,
        stack: ArrayVec::new(),
        leaves: 0,
    };
    walk.enter(0, all & !done, t_max, reach, &mut work);
    while let Some(Pending {
        node,
        slot,
        rays,
        leaves: tested_after,
    }) = walk.pop()
    {
        let active = rays & !done;
        if active == 0 {
            continue;
        }
        let parent = &bvh.nodes()[node as usize];
        let k = slot as usize;
        let (offset, count) = (parent.offset[k], parent.count[k]);
        if count == 0 {
            walk.enter(offset, active, t_max, reach, &mut work);
            continue;
        }
        work.nodes += u64::from(active.count_ones());
        let hit = if tested_after == walk.leaves {
            active
        } else {
            walk.packet
                .hits(&parent.bounds(k), t_min, t_max, reach, active)
        };
        if hit == 0 {
            continue;
        }
        let first = offset as usize;
        let mut lowered = 0;
        for &item in &bvh.items()[first..first + count as usize] {
            let reached = hit & !done;
            if reached != 0 {
                work.items += u64::from(reached.count_ones());
                let answer = step(item, reached, t_max);
                done |= answer.done & reached;
                lowered |= answer.lowered;
            }
        }
        if lowered != 0 {
            walk.leaves += 1;
            reach = reach_of::<V>(t_max, &used);
        }
    }
    (done, work)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::aabb::SlabRay;
    use crate::fast::simd::Wide;
    use glam::DVec3;

    /// The signs read off d are those of 1/d, which the slab tests order children by: at ±0,
    /// subnormals, the largest numbers and ±∞ too.
    #[test]
    fn signs_are_those_of_the_reciprocal() {
        let values = [
            0.0,
            -0.0,
            f64::MIN_POSITIVE / 8.0,
            -f64::MIN_POSITIVE / 8.0,
            0.3,
            -0.3,
            f64::MAX,
            -f64::MAX,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for &x in &values {
            for &y in &values {
                let r = Ray {
                    origin: DVec3::ZERO,
                    dir: DVec3::new(x, y, -x),
                };
                assert_eq!(
                    signs(&r),
                    SlabRay::new(r.origin, r.dir.recip()).negative,
                    "{x} {y}"
                );
            }
        }
    }

    /// The tree of minima and maxima finds the fold's range over the first `len` rays, with
    /// infinities, signed zeros and NaN among them and anything in the lanes beyond `len`.
    #[test]
    fn reach_is_the_range_of_the_rays_t_max() {
        let mut rng = crate::sampling::Rng::for_pixel(5, 0, 0);
        let special = [
            f64::INFINITY,
            f64::NEG_INFINITY,
            0.0,
            -0.0,
            f64::NAN,
            1e-300,
            7.5,
        ];
        for case in 0..5000 {
            let len = 1 + case % PACKET;
            let t_max: [f64; PACKET] = std::array::from_fn(|_| {
                let u = rng.uniform();
                if u < 0.3 {
                    special[(u * 100.0) as usize % special.len()]
                } else {
                    100.0 * rng.uniform()
                }
            });
            let fold = t_max[..len]
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &t| {
                    (if t < lo { t } else { lo }, if t > hi { t } else { hi })
                });
            let (lo, hi) = reach_of::<Wide>(&t_max, &lane_masks::<Wide>(len));
            // Equal as numbers (a zero's sign may differ, which no comparison sees).
            assert!(
                lo == fold.0 && hi == fold.1,
                "{t_max:?}[..{len}]: {lo} {hi} {fold:?}"
            );
        }
    }

    /// The four-lane overlap test answers every lane as `overlaps` does, at the edges of the
    /// number line too (signed zeros, subnormals, the largest finite numbers, ∞, NaN).
    #[test]
    fn overlaps4_is_overlaps_lane_by_lane() {
        let values = [
            f64::NEG_INFINITY,
            -f64::MAX,
            -1e300,
            -1.0,
            -0.0,
            0.0,
            1e-320,
            1.0,
            1.0 + f64::EPSILON,
            1.0 + 4.0 * f64::EPSILON,
            f64::MAX / 2.0,
            f64::MAX,
            f64::INFINITY,
            f64::NAN,
        ];
        let pairs: Vec<(f64, f64)> = values
            .iter()
            .flat_map(|&e| values.iter().map(move |&x| (e, x)))
            .collect();
        for chunk in pairs.chunks(4) {
            let enter = std::array::from_fn(|k| chunk[k % chunk.len()].0);
            let exit = std::array::from_fn(|k| chunk[k % chunk.len()].1);
            let bits = overlaps4::<Wide>(&enter, &exit);
            for lane in 0..4 {
                let expected = crate::accel::aabb::overlaps(enter[lane], exit[lane]);
                assert_eq!(
                    bits >> lane & 1 == 1,
                    expected,
                    "{} {}",
                    enter[lane],
                    exit[lane]
                );
            }
        }
    }
}
