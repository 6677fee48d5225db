//! The fast search for packets of rays: up to `PACKET` rays (the grid samples of a pixel or two, or
//! the shadow or secondary rays of their surfaces) searched together. With a BVH, rays whose
//! directions share their signs walk the tree as one packet (`bvh_packet.rs`); without one, every
//! object is tested against four rays at a time in four lanes (`F64x4`). Every ray finds the hit,
//! and counts the work, that the one-ray search finds for it.

use arrayvec::ArrayVec;
use glam::DVec3;

use super::bvh_packet::{any_packet, closest_packet, first_rays, quad_bits, signs, RaySet, PACKET};
use super::csg_lanes::{CsgLanes, LanesHits};
use super::footprint::Missed;
use super::hull::{Hull, Verdict};
use super::lanes::{box_hit_lanes, lane_mask, plane_hits_of_lanes, RayLanes, SlabLanes, LANES};
use super::probe::Probe;
use super::search::FastScene;
use super::shadow_cones::TowardLight;
use super::simd::{with_lanes, F64x4};
use super::sphere_group::sphere_against_lanes;
use crate::geometry::{Ray, Sphere, Surface};
use crate::scene::{Hit, Search};
use crate::stats::Stats;

/// Fewer rays than this search the BVH faster one by one than as a packet: the packet's
/// bookkeeping pays only when a node's box is tested for several rays.
const PACKET_MIN: usize = 4;

/// The rays of a packet in lanes, four to a group (the last group filled with `UNUSED`),
/// written where they stay: the array returned whole would be copied on (1.8 kB a packet),
/// and the copy's wide loads wait for the groups' narrower stores.
#[inline(always)]
fn ray_quads<V: F64x4>(rays: &[Ray], quads: &mut [RayLanes<V>; PACKET / LANES]) {
    for (quad, rays) in quads.iter_mut().zip(rays.chunks(LANES)) {
        *quad = RayLanes::new(rays);
    }
}

/// What a sphere did to one group of four rays: the rays whose t lies in 0 < t < limit (bit
/// k for the group's ray k), each lane's t, and the group's limits it was tested within.
#[derive(Clone, Copy)]
struct QuadHits<V> {
    within: u32,
    t: V,
    limit: V,
}

/// A plain sphere against the rays `reached` (bit i for ray i) of a packet in lanes, four at
/// a time, each ray within its `limits[i]`, as `probe_hit` tests one ray
/// (`sphere_against_lanes` is `sphere_hit` lane by lane); counts a test per ray. Loops
/// written out: a closure here would be compiled outside the lanes' copy.
#[inline(always)]
fn spheres_in_quads<V: F64x4>(
    sphere: &Sphere,
    quads: &[RayLanes<V>; PACKET / LANES],
    reached: RaySet,
    limits: &[f64; PACKET],
    stats: &mut Stats,
) -> [QuadHits<V>; PACKET / LANES] {
    let r2 = sphere.radius * sphere.radius;
    let none = QuadHits {
        within: 0,
        t: V::ZERO,
        limit: V::ZERO,
    };
    let mut found = [none; PACKET / LANES];
    for (q, quad) in quads.iter().enumerate() {
        let bits = quad_bits(reached, q);
        if bits == 0 {
            continue;
        }
        stats.primitives_tested += u64::from(bits.count_ones());
        let Some(t) = sphere_against_lanes(sphere.center, r2, quad, lane_mask(bits), 0.0) else {
            continue;
        };
        let limit = V::new(limits[LANES * q..LANES * (q + 1)].try_into().unwrap());
        let within = (t.simd_gt(V::ZERO) & t.simd_lt(limit)).to_bitmask() & bits;
        found[q] = QuadHits { within, t, limit };
    }
    found
}

/// The positions of the set bits, lowest first.
#[inline(always)]
fn ones(mut bits: RaySet) -> impl Iterator<Item = usize> {
    std::iter::from_fn(move || {
        (bits != 0).then(|| {
            let i = bits.trailing_zeros() as usize;
            bits &= bits - 1;
            i
        })
    })
}

impl FastScene<'_> {
    /// `intersect` (t_min = 0, t_max = ∞) for up to `PACKET` rays at once: `hits[i]` is exactly
    /// what `intersect` answers for ray i, and the stats are those of tracing the rays one by one.
    /// Without a BVH the rays go four at a time (`intersect_in_lanes`). Otherwise the rays
    /// that share the first one's direction signs go through the BVH as a packet (if there are
    /// at least `PACKET_MIN` of them); any others, one by one.
    pub fn intersect_packet(&self, rays: &[Ray], hits: &mut [Option<Hit>], stats: &mut Stats) {
        self.intersect_packet_knowing(rays, Missed::UNKNOWN, hits, stats)
    }

    /// `intersect_packet` for rays that are known to miss the boxes and plain spheres of
    /// `missed` (as the film's `Footprints` find them), every one of them.
    pub fn intersect_packet_knowing(
        &self,
        rays: &[Ray],
        missed: Missed,
        hits: &mut [Option<Hit>],
        stats: &mut Stats,
    ) {
        with_lanes!(V => self.intersect_packet_in::<V>(rays, missed, hits, stats))
    }

    #[inline(always)]
    fn intersect_packet_in<V: F64x4>(
        &self,
        rays: &[Ray],
        missed: Missed,
        hits: &mut [Option<Hit>],
        stats: &mut Stats,
    ) {
        if self.in_lanes {
            let missed = Missed {
                boxes: Some(match missed.boxes {
                    Some(boxes) => boxes,
                    None => self.boxes_missed_by_all::<V>(rays),
                }),
                ..missed
            };
            for (rays, hits) in rays.chunks(LANES).zip(hits.chunks_mut(LANES)) {
                self.intersect_in_lanes::<V>(rays, &RayLanes::new(rays), hits, missed, stats);
            }
            return;
        }
        let Some(first) = rays.first().map(signs) else {
            return;
        };
        let mut alike = [false; PACKET];
        for (a, ray) in alike.iter_mut().zip(rays) {
            *a = signs(ray) == first;
        }
        let one_by_one = alike.iter().filter(|&&a| a).count() < PACKET_MIN;
        // The rays that take part, pushed where they stay (no array of stand-ins written first).
        let mut packet: ArrayVec<Ray, PACKET> = ArrayVec::new();
        let mut packet_inv: ArrayVec<DVec3, PACKET> = ArrayVec::new();
        let mut lanes: ArrayVec<usize, PACKET> = ArrayVec::new();
        for (i, ray) in rays.iter().enumerate() {
            if !one_by_one && alike[i] {
                packet.push(*ray);
                packet_inv.push(self.inv_dir(ray));
                lanes.push(i);
            } else {
                hits[i] = self.nearest(ray, 0.0, f64::INFINITY, stats);
            }
        }
        let n = packet.len();
        if n == 0 {
            return;
        }
        // The objects outside the BVH first, four rays at a time (`nearest_unbounded` lane by
        // lane): each ray's nearest hit among them limits its walk.
        let mut quads = [RayLanes::new(&[]); PACKET / LANES];
        ray_quads::<V>(&packet[..n], &mut quads);
        let mut limits = [f64::INFINITY; PACKET];
        for (q, rays) in packet[..n].chunks(LANES).enumerate() {
            let mut found = [None; LANES];
            let found = &mut found[..rays.len()];
            self.intersect_in_lanes::<V>(rays, &quads[q], found, Missed::NOTHING, stats);
            for (k, hit) in found.iter().enumerate() {
                let lane = LANES * q + k;
                hits[lanes[lane]] = *hit;
                limits[lane] = hit.map_or(f64::INFINITY, |h| h.t);
            }
        }
        let visits = closest_packet::<V>(
            &self.bvh4,
            &packet[..n],
            &quads,
            0.0,
            &mut limits,
            // Inlined, so that it is compiled in the lanes' copy with the walk.
            #[inline(always)]
            |item, reached, limits| {
                let probe = &self.bounded[item as usize];
                if let Probe::Sphere {
                    sphere,
                    object,
                    leaf,
                } = probe
                {
                    let found = spheres_in_quads(sphere, &quads, reached, limits, stats);
                    let mut nearer = 0;
                    // Read where they lie: `into_iter` would move the eight groups' answers
                    // (768 bytes) into the iterator, through a call to memcpy, twice.
                    for (q, &QuadHits { within, t, limit }) in found.iter().enumerate() {
                        if within == 0 {
                            continue;
                        }
                        nearer |= within << (4 * q);
                        // The group's four limits stored at once: the walk reads them back
                        // as one vector, which four single stores would stall.
                        let lowered = lane_mask::<V>(within).bitselect(t, limit);
                        limits[4 * q..4 * q + 4].copy_from_slice(&lowered.to_array());
                        let t = t.to_array();
                        for lane in ones(within) {
                            hits[lanes[4 * q + lane]] = Some(Hit {
                                t: t[lane],
                                object: *object,
                                surface: Surface::new(*leaf, 0),
                            });
                        }
                    }
                    return nearer;
                }
                let mut nearer = 0;
                for lane in ones(reached) {
                    let (ray, inv) = (&packet[lane], packet_inv[lane]);
                    if let Some(h) = self.probe_hit::<V>(probe, ray, inv, 0.0, limits[lane], stats)
                    {
                        hits[lanes[lane]] = Some(h);
                        limits[lane] = limits[lane].min(h.t);
                        nearer |= 1 << lane;
                    }
                }
                nearer
            },
        );
        stats.bvh_nodes_visited += visits.nodes;
    }

    /// Whether a blocker with 0 < t < t_max is among the objects in the BVH.
    #[inline(always)]
    fn occluded_in_bvh<V: F64x4>(
        &self,
        ray: &Ray,
        inv_dir: DVec3,
        t_max: f64,
        stats: &mut Stats,
    ) -> bool {
        let (blocked, visits) = self
            .scene
            .index
            .bvh
            .any(ray.origin, ray.dir, 0.0, t_max, |item| {
                self.probe_blocker::<V>(
                    &self.bounded[item as usize],
                    ray,
                    inv_dir,
                    0.0,
                    t_max,
                    stats,
                )
                .is_some()
            });
        stats.bvh_nodes_visited += visits.nodes;
        blocked
    }

    /// `occluded` for up to `PACKET` shadow rays, ray i looking for blockers with 0 < t <
    /// `t_max[i]`: bit i of the answer is set when ray i is blocked. Without a BVH the rays go four
    /// at a time (`occluded_in_lanes`), and the stats are those of asking `occluded` ray by ray.
    /// Otherwise rays that get past the objects outside the BVH, if there are at least `PACKET_MIN`
    /// of them (fewer search it one by one), are first tried against `last_blocker` (a BVH item
    /// that blocked earlier rays toward the same light, if any), and those it does not block search
    /// the BVH as a packet (any directions will do: an any-hit search visits the nodes in a fixed
    /// order). The BVH item that blocks a ray is noted in `last_blocker`. The rays and their
    /// answers are those of asking ray by ray; the nodes visited and the objects tested are this
    /// search's own.
    pub fn occluded_packet(
        &self,
        rays: &[Ray],
        t_max: &[f64],
        last_blocker: &mut Option<u32>,
        stats: &mut Stats,
    ) -> u32 {
        with_lanes!(V => self.occluded_packet_in::<V>(rays, t_max, last_blocker, stats))
    }

    #[inline(always)]
    fn occluded_packet_in<V: F64x4>(
        &self,
        rays: &[Ray],
        t_max: &[f64],
        last_blocker: &mut Option<u32>,
        stats: &mut Stats,
    ) -> u32 {
        if self.in_lanes {
            let mut blocked = 0;
            for (k, (rays, t_max)) in rays.chunks(LANES).zip(t_max.chunks(LANES)).enumerate() {
                blocked |= self.occluded_in_lanes::<V>(rays, t_max, stats) << (k * LANES);
            }
            return blocked;
        }
        let mut blocked = 0u32;
        let mut packet: ArrayVec<Ray, PACKET> = ArrayVec::new();
        let mut packet_inv: ArrayVec<DVec3, PACKET> = ArrayVec::new();
        let mut reach = [0.0; PACKET];
        let mut lanes: ArrayVec<usize, PACKET> = ArrayVec::new();
        for (i, ray) in rays.iter().enumerate() {
            let inv_dir = self.inv_dir(ray);
            if self.unbounded.iter().any(|p| {
                self.probe_blocker::<V>(p, ray, inv_dir, 0.0, t_max[i], stats)
                    .is_some()
            }) {
                blocked |= 1 << i;
            } else if !self.bounded.is_empty() {
                reach[packet.len()] = t_max[i];
                packet.push(*ray);
                packet_inv.push(inv_dir);
                lanes.push(i);
            }
        }
        let n = packet.len();
        if n == 0 {
            return blocked;
        }
        if n < PACKET_MIN {
            for k in 0..n {
                if self.occluded_in_bvh::<V>(&packet[k], packet_inv[k], reach[k], stats) {
                    let i = lanes[k];
                    blocked |= 1 << i;
                }
            }
            return blocked;
        }
        let mut quads = [RayLanes::new(&[]); PACKET / LANES];
        ray_quads::<V>(&packet[..n], &mut quads);
        let packet = (&packet[..], &packet_inv[..], &quads);
        // The last blocker first: where it blocks every ray, the BVH is not walked at all.
        let all = first_rays(n);
        let first = match *last_blocker {
            Some(item) => self.blocked_by::<V>(item, all, packet, &reach, stats),
            None => 0,
        };
        let hit = if first == all {
            all
        } else {
            let (hit, visits) = any_packet::<V>(
                &self.bvh4,
                (packet.2, n),
                0.0,
                &mut reach,
                first,
                #[inline(always)]
                |item, reached, reach| {
                    let blocked = self.blocked_by::<V>(item, reached, packet, reach, stats);
                    if blocked != 0 {
                        *last_blocker = Some(item);
                    }
                    blocked
                },
            );
            stats.bvh_nodes_visited += visits.nodes;
            hit
        };
        for (k, &i) in lanes[..n].iter().enumerate() {
            if hit & (1 << k) != 0 {
                blocked |= 1 << i;
            }
        }
        blocked
    }

    /// The rays of a packet (bits) that BVH item `item` blocks, of those in `reached`: its
    /// rays, their 1/d and their groups of four, each ray looking for blockers with
    /// 0 < t < `t_max[i]`.
    #[inline(always)]
    fn blocked_by<V: F64x4>(
        &self,
        item: u32,
        reached: RaySet,
        (rays, inv_dirs, quads): (&[Ray], &[DVec3], &[RayLanes<V>; PACKET / 4]),
        t_max: &[f64; PACKET],
        stats: &mut Stats,
    ) -> RaySet {
        let probe = &self.bounded[item as usize];
        let mut blocked: RaySet = 0;
        if let Probe::Sphere { sphere, .. } = probe {
            let found = spheres_in_quads(sphere, quads, reached, t_max, stats);
            for (q, quad) in found.iter().enumerate() {
                blocked |= quad.within << (4 * q);
            }
            return blocked;
        }
        // Any other object ray by ray, out of line: the walk's loop stays small.
        V::outlined(
            #[inline(always)]
            || {
                for lane in ones(reached) {
                    let (ray, inv) = (&rays[lane], inv_dirs[lane]);
                    if self
                        .probe_blocker::<V>(probe, ray, inv, 0.0, t_max[lane], stats)
                        .is_some()
                    {
                        blocked |= 1 << lane;
                    }
                }
                blocked
            },
        )
    }

    /// `intersect` (t_min = 0, t_max = ∞) for up to four rays in a scene without a BVH: each
    /// plain sphere or plane is tested against all the rays at once, in `RayLanes`, and any
    /// other object ray by ray, behind its box (tested against all the rays at once). Each
    /// ray meets the objects in the same order as in `intersect`, with the same arithmetic and
    /// the same shrinking limit, so it finds the same hit and counts the same tests. `lanes`
    /// holds `rays` (`RayLanes::new`); the objects and plain spheres of `missed` are missed
    /// by every ray (a box, by its box too; `missed.boxes` is known).
    #[inline(always)]
    fn intersect_in_lanes<V: F64x4>(
        &self,
        rays: &[Ray],
        lanes: &RayLanes<V>,
        hits: &mut [Option<Hit>],
        missed: Missed,
        stats: &mut Stats,
    ) {
        let lanes = *lanes;
        // 1/d of each ray, found at the first box not ruled out: a packet whose footprint or
        // hull rules out every box (most of the film's primary rays) does without.
        let mut slabs = None;
        let used = (1u32 << rays.len()) - 1;
        let all = lane_mask::<V>(used);
        let mut limit = V::splat(f64::INFINITY);
        hits.fill(None);
        // Lanes whose t lies in 0 < t < limit take it as their nearest hit so far.
        let take =
            |hits: &mut [Option<Hit>], t: V, bits: u32, object: u32, leaf: u32, limit: &mut V| {
                let bits = bits & used;
                if bits == 0 {
                    return;
                }
                *limit = lane_mask::<V>(bits).bitselect(t, *limit);
                let t = t.to_array();
                for (i, hit) in hits.iter_mut().enumerate() {
                    if bits & (1 << i) != 0 {
                        *hit = Some(Hit {
                            t: t[i],
                            object,
                            surface: Surface::new(leaf, 0),
                        });
                    }
                }
            };
        let within = |t: V, limit: V| (t.simd_gt(V::ZERO) & t.simd_lt(limit)).to_bitmask();
        let n = rays.len() as u64;
        let boxes_missed = missed.boxes.unwrap_or(0);
        // The number of the next plain sphere (`plain_spheres`).
        let mut spheres_before = 0;
        for (k, p) in self.unbounded.iter().enumerate() {
            match p {
                Probe::Plane {
                    plane,
                    object,
                    leaf,
                } => {
                    stats.primitives_tested += n;
                    let (t, bits) = plane_hits_of_lanes(plane, &lanes, 0.0, limit);
                    take(hits, t, bits, *object, *leaf, &mut limit);
                }
                Probe::Sphere {
                    sphere,
                    object,
                    leaf,
                } => {
                    spheres_before += 1;
                    // A sphere ruled out is counted as the core's test of it counts.
                    stats.primitives_tested += n;
                    if ruled_out(missed.spheres, spheres_before - 1) {
                        continue;
                    }
                    let r2 = sphere.radius * sphere.radius;
                    if let Some(t) = sphere_against_lanes(sphere.center, r2, &lanes, all, 0.0) {
                        take(hits, t, within(t, limit), *object, *leaf, &mut limit);
                    }
                }
                Probe::Spheres {
                    group,
                    objects,
                    leaves,
                } => {
                    stats.primitives_tested += group.len() as u64 * n;
                    for k in 0..group.len() {
                        if ruled_out(missed.spheres, spheres_before + k) {
                            continue;
                        }
                        if let Some(t) = group.sphere_against(k, &lanes, all, 0.0) {
                            take(hits, t, within(t, limit), objects[k], leaves[k], &mut limit);
                        }
                    }
                    spheres_before += group.len();
                }
                Probe::Object(_) | Probe::Box { .. } if ruled_out(boxes_missed, k) => {
                    // Counted as each ray's own test of the box counts its miss.
                    stats.bounds_skipped += n;
                }
                Probe::Object(o) | Probe::Box { object: o, .. } => {
                    let slabs = match &slabs {
                        Some(slabs) => slabs,
                        None => slabs.insert(SlabLanes::new(&lanes)),
                    };
                    let mut t_max = limit.to_array();
                    self.object_in_lanes(*o, rays, slabs, &mut t_max, hits, stats);
                    limit = V::new(t_max);
                }
            }
        }
    }

    /// The objects tested behind their box (bit k: `unbounded[k]`, the first 64) whose box
    /// every one of `rays` misses, as the rays' hull proves (`Hull`): one test for a packet of
    /// up to `PACKET` rays, where the rays' own tests take one per group of four. A ray that misses
    /// a box searching [0, ∞) misses it searching less, so the rays' limits need not be known.
    #[inline(always)]
    fn boxes_missed_by_all<V: F64x4>(&self, rays: &[Ray]) -> u64 {
        if !self.boxes_outside_bvh || rays.len() <= LANES {
            return 0;
        }
        // The hull of 1/d as `SlabLanes` finds it: it bounds what the rays' own tests use.
        let hull = Hull::<V>::of_directions(rays.iter().map(|r| (r.origin, r.dir)));
        let Some(hull) = hull else {
            return 0;
        };
        let mut missed = 0;
        for (k, p) in self.unbounded.iter().enumerate().take(u64::BITS as usize) {
            if let Some(o) = p.boxed_object() {
                let bounds = &self.scene.objects[o as usize].bounds;
                if self.tested_behind_box(o)
                    && hull.classify(bounds, 0.0, (0.0, f64::INFINITY)) == Verdict::AllMiss
                {
                    missed |= 1 << k;
                }
            }
        }
        missed
    }

    /// `occluded` (t_min = 0) for up to four shadow rays in a scene without a BVH: each plain
    /// sphere or plane is tested against all the rays still open at once, in `RayLanes`, and
    /// any other object ray by ray, as in `intersect_in_lanes`. Each ray meets the objects in
    /// the same order as in `occluded`, with the same arithmetic, so it is blocked by the same
    /// one and counts the same tests.
    #[inline(always)]
    fn occluded_in_lanes<V: F64x4>(&self, rays: &[Ray], t_max: &[f64], stats: &mut Stats) -> u32 {
        let lanes = RayLanes::<V>::new(rays);
        // Lane by lane, not `copy_from_slice`: a call to memcpy here would spill every vector
        // register around it.
        let reach = |i: usize| t_max.get(i).copied().unwrap_or(0.0);
        let reach = V::setr(reach(0), reach(1), reach(2), reach(3));
        let all = (1u32 << rays.len()) - 1;
        self.occluded_lanes(&lanes, reach, all, None, stats)
    }

    /// The lanes of `open` whose ray is blocked before `reach`, for rays already in lanes.
    /// Shadow rays `toward` a point light skip the boxes their directions alone say they miss
    /// (`shadow_cones`).
    #[inline(always)]
    pub(super) fn occluded_lanes<V: F64x4>(
        &self,
        lanes: &RayLanes<V>,
        reach: V,
        all: u32,
        toward: Option<&TowardLight<V>>,
        stats: &mut Stats,
    ) -> u32 {
        // The rays' 1/d, found for the first box a ray may pass through.
        let mut slabs = None;
        let mut open = all;
        // The lanes whose t (NaN for none) lies in 0 < t < t_max.
        let within = |t: V| (t.simd_gt(V::ZERO) & t.simd_lt(reach)).to_bitmask();
        for (k, p) in self.unbounded.iter().enumerate() {
            if open == 0 {
                break;
            }
            match p {
                Probe::Plane { plane, .. } => {
                    stats.primitives_tested += open.count_ones() as u64;
                    open &= !plane_hits_of_lanes(plane, lanes, 0.0, reach).1;
                }
                Probe::Sphere { sphere, .. } => {
                    stats.primitives_tested += open.count_ones() as u64;
                    let r2 = sphere.radius * sphere.radius;
                    let open_lanes = lane_mask::<V>(open);
                    if let Some(t) = sphere_against_lanes(sphere.center, r2, lanes, open_lanes, 0.0)
                    {
                        open &= !within(t);
                    }
                }
                Probe::Spheres { group, .. } => {
                    // A ray is blocked by the first sphere in the group's order, and counts the
                    // spheres up to it, as `SphereGroup::first` does.
                    for k in 0..group.len() {
                        if open == 0 {
                            break;
                        }
                        stats.primitives_tested += open.count_ones() as u64;
                        if let Some(t) = group.sphere_against(k, lanes, lane_mask(open), 0.0) {
                            open &= !within(t);
                        }
                    }
                }
                Probe::Object(o) | Probe::Box { object: o, .. } => {
                    // The rays whose direction alone says they miss the box are counted as
                    // its slab test would count them.
                    let missed = match toward {
                        Some(toward) => toward.missed(k) & open,
                        None => 0,
                    };
                    stats.bounds_skipped += missed.count_ones() as u64;
                    let tested = open & !missed;
                    if tested != 0 {
                        let slabs = match &slabs {
                            Some(slabs) => slabs,
                            None => slabs.insert(SlabLanes::new(lanes)),
                        };
                        open &= !self.object_blocks_lanes(*o, slabs, reach, tested, stats);
                    }
                }
            }
        }
        all & !open
    }

    /// Object o against up to four rays of a packet, behind its box: the box is tried
    /// against all of them at once, then the object ray by ray where it passed, and each ray's
    /// nearest hit so far and its limit t_max are updated as `intersect` would.
    /// Out of line, so that the lanes' loop over plain spheres and planes stays small.
    #[inline(always)]
    fn object_in_lanes<V: F64x4>(
        &self,
        o: u32,
        rays: &[Ray],
        slabs: &SlabLanes<V>,
        t_max: &mut [f64; LANES],
        hits: &mut [Option<Hit>],
        stats: &mut Stats,
    ) {
        V::outlined(
            #[inline(always)]
            || {
                let used = (1 << rays.len()) - 1;
                let limit = V::new(*t_max);
                let mut passed = self.box_passed_by(o, used, slabs, limit, stats);
                if let Some((csg, found)) = self.csg_in_lanes(o, slabs, passed, limit, stats) {
                    let t = found.t.to_array();
                    for i in ones(found.hit & used) {
                        t_max[i] = t[i];
                        hits[i] = Some(Hit {
                            t: t[i],
                            object: o,
                            surface: csg.surface(&found, i),
                        });
                    }
                    passed = found.undecided;
                }
                for i in ones(passed & used) {
                    if let Some(h) =
                        self.object_hit::<V>(o, &rays[i], slabs.inv_dir(i), 0.0, t_max[i], stats)
                    {
                        t_max[i] = h.t;
                        hits[i] = Some(h);
                    }
                }
            },
        )
    }

    /// Object o against the shadow rays of a packet still `open` (bit i: ray i), behind its
    /// box tried against all of them at once: the bits of the rays it blocks. A ray the
    /// object is tested against alone is taken out of its lane then (most are decided in lanes).
    /// Out of line, as `object_in_lanes`.
    #[inline(always)]
    fn object_blocks_lanes<V: F64x4>(
        &self,
        o: u32,
        slabs: &SlabLanes<V>,
        t_max: V,
        open: u32,
        stats: &mut Stats,
    ) -> u32 {
        V::outlined(
            #[inline(always)]
            || {
                let mut passed = self.box_passed_by(o, open, slabs, t_max, stats);
                let reach = t_max.to_array();
                let mut blocked = 0;
                if let Some((_, found)) = self.csg_in_lanes(o, slabs, passed, t_max, stats) {
                    blocked = found.hit;
                    passed = found.undecided;
                }
                for i in ones(passed & open) {
                    if self
                        .object_hit::<V>(o, &slabs.ray(i), slabs.inv_dir(i), 0.0, reach[i], stats)
                        .is_some()
                    {
                        blocked |= 1 << i;
                    }
                }
                blocked
            },
        )
    }

    /// Which of the rays in `lanes` (bit i: lane i) pass through object o's box within
    /// [0, t_max] (all of them where the object is not tested behind its box), with the others
    /// counted as skipped, as `boxed_object_hit` counts them ray by ray.
    #[inline(always)]
    fn box_passed_by<V: F64x4>(
        &self,
        o: u32,
        lanes: u32,
        slabs: &SlabLanes<V>,
        t_max: V,
        stats: &mut Stats,
    ) -> u32 {
        if !self.tested_behind_box(o) {
            return lanes;
        }
        let passed =
            lanes & box_hit_lanes(&self.scene.objects[o as usize].bounds, slabs, 0.0, t_max);
        stats.bounds_skipped += (lanes & !passed).count_ones() as u64;
        passed
    }

    /// Object o, if it is a flat CSG object the lanes can test (`lanes_form`), against
    /// the rays whose bits are set in `open`, four at a time, counted as `object_hit` counts
    /// them ray by ray; the rays it leaves undecided are for `object_hit`.
    #[inline(always)]
    fn csg_in_lanes<V: F64x4>(
        &self,
        o: u32,
        slabs: &SlabLanes<V>,
        open: u32,
        t_max: V,
        stats: &mut Stats,
    ) -> Option<(&CsgLanes, LanesHits<V>)> {
        let csg = self.csg_lanes[o as usize].as_ref()?;
        let found = csg.hits(
            slabs,
            open,
            t_max,
            self.scene.csg_pruning,
            self.scene.csg_pruning,
        );
        stats.primitives_tested += (open & !found.undecided).count_ones() as u64;
        stats.csg_pruned += found.pruned;
        Some((csg, found))
    }
}

/// Whether a mask of `Missed` rules out box or sphere k: it holds a bit for each of the first
/// 64 only, and says nothing of the rest.
fn ruled_out(missed: u64, k: usize) -> bool {
    k < u64::BITS as usize && missed >> k & 1 != 0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::simd::Wide;
    use crate::scene::{parse, Limits};

    /// A pixel's samples that pass beside a boxed object rule its box out for all of them at
    /// once; samples aimed at it, or spread over its edge, do not, and neither do four rays or
    /// fewer (their own tests are as cheap).
    #[test]
    fn a_packet_rules_out_the_boxes_all_its_rays_miss() {
        let yaml = "camera: { eye: [0, 0, -10], look_at: [0, 0, 0] }\n\
            materials: { m: { kd: 0.5 } }\nobjects:\n\
            - { sphere: { center: [0, 0, 0], radius: 1 }, material: m }\n\
            - { box: { min: [2, -1, -1], max: [4, 1, 1] }, material: m }\n\
            - { difference: [ { box: { min: [-4, -1, -1], max: [-2, 1, 1] } },\
                { sphere: { center: [-3, 0, -1], radius: 1.2 } } ], material: m }\n";
        let scene = parse(yaml, "boxes.yaml", None, &Limits::default()).unwrap();
        let fast = FastScene::new(&scene);
        let bit = |object: u32| {
            let k = fast
                .unbounded
                .iter()
                .position(|p| p.boxed_object() == Some(object));
            1u64 << k.expect("a boxed object")
        };
        let (boxed, hollow) = (bit(1), bit(2));
        let packet = |aim: [f64; 3], spread: f64| -> Vec<Ray> {
            let eye = DVec3::new(0.0, 0.0, -10.0);
            (0..16)
                .map(|k| {
                    let (u, v) = ((k % 4) as f64 - 1.5, (k / 4) as f64 - 1.5);
                    let at = DVec3::from_array(aim) + spread * DVec3::new(u, v, 0.0);
                    Ray::new(eye, (at - eye).normalize())
                })
                .collect()
        };
        let missed = |rays: &[Ray]| fast.boxes_missed_by_all::<Wide>(rays);
        assert_eq!(missed(&packet([0.5, 0.5, 0.0], 0.01)), boxed | hollow);
        assert_eq!(missed(&packet([3.0, 0.5, 0.0], 0.01)), hollow);
        assert_eq!(missed(&packet([-3.0, 0.5, 0.0], 0.01)), boxed);
        assert_eq!(missed(&packet([0.5, 3.0, 0.0], 0.01)), boxed | hollow);
        assert_eq!(
            missed(&packet([2.0, 0.5, 0.0], 0.3)),
            hollow,
            "some rays meet the box"
        );
        // Directions of both signs on an axis (the pixels at the image's centre): no hull.
        assert_eq!(missed(&packet([0.0, 0.5, 0.0], 0.01)), 0);
        assert_eq!(missed(&packet([0.5, 0.5, 0.0], 0.01)[..4]), 0, "four rays");
    }
}
