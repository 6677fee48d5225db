//! Flat CSG objects of two operands (spheres, boxes, cylinders, cones) against four rays at
//! once.
//!
//! A lens (A ∩ B of two spheres) or a box with a spherical hole (A − B) is met by many rays:
//! a glass lens's own refraction and reflection rays bounce inside it. Ray by ray, each test
//! is a call into the CSG evaluation (`FlatCsg::nearest`). Here the same steps run for four
//! rays side by side in four lanes (`F64x4`), one ray per lane: the operands' boxes and the notes'
//! pruning rule, both operands' spans (`span_lanes`: each primitive's own arithmetic, to the
//! last bit), and the walk along the four span ends that finds where the operation's rule
//! first changes its answer. Where that walk meets ends that coincide, or spans that are
//! reversed or odd, the ray is left `undecided`, for the ray-by-ray evaluation to settle as
//! the segment lists do.

use glam::{DAffine3, DVec3};

use super::lanes::{box_hit_lanes, lane_mask, RayLanes, SlabLanes};
use super::simd::F64x4;
use super::span_lanes::{self, SpanLanes};
use crate::accel::Aabb;
use crate::geometry::csg::CsgOp;
use crate::geometry::{Shape, Sphere, Surface};

/// An operand the lanes can test.
#[derive(Clone, Debug)]
pub enum Operand {
    /// A sphere in world space: centre and r².
    Sphere(DVec3, f64),
    /// A box, cylinder or cone in its own space, and the transform that carries rays there
    /// (if any).
    Solid(Shape, Option<DAffine3>),
}

/// A flat CSG object of two operands, ready to be tested four rays at a time.
#[derive(Clone, Debug)]
pub struct CsgLanes {
    op: CsgOp,
    operands: [Operand; 2],
    /// The operands' leaves in the scene.
    leaves: [u32; 2],
    /// Each operand's box, where it is worth testing (`FlatCsg` leaves out a box that holds
    /// the object's).
    bounds: [Option<Aabb>; 2],
}

/// What `CsgLanes::hits` finds for four rays (bit i and lane i: ray i).
#[derive(Clone, Copy, Debug)]
pub struct LanesHits<V> {
    /// The rays that hit the object within their window.
    pub hit: u32,
    /// Each hit's t.
    pub t: V,
    /// The hits on B's surface (the others are on A's).
    pub on_b: u32,
    /// Each hit's face of its operand.
    pub face: V,
    /// The rays to be evaluated one by one: coinciding span ends, or spans that are reversed
    /// or odd (`SpanLanes::odd`).
    pub undecided: u32,
    /// Operands pruned (box missed, or made irrelevant by an empty one) in the decided rays:
    /// what `FlatCsg::nearest` counts in `CsgWork::pruned`.
    pub pruned: u64,
}

impl<V: F64x4> LanesHits<V> {
    const NONE: LanesHits<V> = LanesHits {
        hit: 0,
        t: V::ZERO,
        on_b: 0,
        face: V::ZERO,
        undecided: 0,
        pruned: 0,
    };
}

impl CsgLanes {
    /// The object `op` over two operands, when the lanes can test it.
    pub fn new(
        op: CsgOp,
        operands: [Option<Operand>; 2],
        leaves: [u32; 2],
        bounds: [Option<Aabb>; 2],
    ) -> Option<CsgLanes> {
        let [Some(a), Some(b)] = operands else {
            return None;
        };
        (op != CsgOp::Complement).then_some(CsgLanes {
            op,
            operands: [a, b],
            leaves,
            bounds,
        })
    }

    pub fn sphere(s: &Sphere) -> Operand {
        Operand::Sphere(s.center, s.radius * s.radius)
    }

    /// A solid the lanes can carry to its own space and test there.
    pub fn solid(shape: &Shape, to_local: Option<DAffine3>) -> Option<Operand> {
        matches!(shape, Shape::Box(_) | Shape::Cylinder(_) | Shape::Cone(_))
            .then(|| Operand::Solid(shape.clone(), to_local))
    }

    /// The surface of ray i's hit.
    #[inline(always)]
    pub fn surface<V: F64x4>(&self, hits: &LanesHits<V>, i: usize) -> Surface {
        let on_b = hits.on_b & (1 << i) != 0;
        let surface = Surface::new(self.leaves[on_b as usize], hits.face.to_array()[i] as u32);
        // B's surfaces bound a difference from the other side.
        if on_b && self.op == CsgOp::Difference {
            surface.flipped()
        } else {
            surface
        }
    }

    /// The nearest crossing of the object's surface with 0 < t < t_max for each ray in
    /// `open`, exactly as `FlatCsg::nearest` finds it ray by ray (t_min = 0), with the
    /// operands' boxes tested when `use_bounds` and the notes' pruning rule when `prune`.
    #[inline(always)]
    pub fn hits<V: F64x4>(
        &self,
        slabs: &SlabLanes<V>,
        open: u32,
        t_max: V,
        use_bounds: bool,
        prune: bool,
    ) -> LanesHits<V> {
        if open == 0 {
            return LanesHits::NONE;
        }
        let rays = &slabs.rays();
        if let Some((a, b)) = self.lens() {
            return lens_hits(rays, a, b, open, t_max, prune);
        }
        let open = lane_mask::<V>(open);
        // Operand A, behind its box.
        let a_pruned = self.box_missed(0, slabs, open, t_max, use_bounds);
        let a = self.span(0, rays).only(open & !a_pruned);
        let a_empty = open & !a.exists();
        // Operand B: not needed where A is empty and the rule makes it irrelevant (∩, −),
        // else behind its box.
        let b_irrelevant = if prune && self.op != CsgOp::Union {
            a_empty
        } else {
            V::ZERO
        };
        let b_pruned = b_irrelevant | self.box_missed(1, slabs, open, t_max, use_bounds);
        let b_lanes = open & !b_pruned;
        let b = if b_lanes.to_bitmask() == 0 {
            SpanLanes::none()
        } else {
            self.span(1, rays).only(b_lanes)
        };
        let reversed = a.t_in.simd_gt(a.t_out) | b.t_in.simd_gt(b.t_out);
        let odd = (!a_pruned & a.odd) | (!b_pruned & b.odd);
        // A span of no thickness in the window (a ray grazing a rim) is the segment lists'.
        let thin = (a.exists() & thin(a.t_in, a.t_out, t_max))
            | (b.exists() & thin(b.t_in, b.t_out, t_max));
        let left = open & (reversed | odd | thin);

        let walk = walk(self.op, [a.t_in, a.t_out, b.t_in, b.t_out], t_max);
        let faces = [a.face_in, a.face_out, b.face_in, b.face_out];
        let mut found = walk.hits(open & !left, faces, left);
        let decided = open.to_bitmask() & !found.undecided;
        found.pruned = (a_pruned.to_bitmask() & decided).count_ones() as u64
            + (b_pruned.to_bitmask() & decided).count_ones() as u64;
        found
    }

    /// All ones in the lanes of `open` whose ray misses operand k's box (none when the boxes
    /// are not used).
    #[inline(always)]
    fn box_missed<V: F64x4>(
        &self,
        k: usize,
        slabs: &SlabLanes<V>,
        open: V,
        t_max: V,
        use_bounds: bool,
    ) -> V {
        match &self.bounds[k] {
            Some(b) if use_bounds => open & !lane_mask::<V>(box_hit_lanes(b, slabs, 0.0, t_max)),
            _ => V::ZERO,
        }
    }

    /// A ∩ B of two spheres without boxes of their own: a lens, whose evaluation leaves the
    /// spheres' common part early (`SphereGroup::common_spans`).
    fn lens(&self) -> Option<((DVec3, f64), (DVec3, f64))> {
        match (&self.operands, self.op, self.bounds) {
            (
                [Operand::Sphere(ca, ra), Operand::Sphere(cb, rb)],
                CsgOp::Intersection,
                [None, None],
            ) => Some(((*ca, *ra), (*cb, *rb))),
            _ => None,
        }
    }

    /// Operand k's spans along the four rays.
    #[inline(always)]
    fn span<V: F64x4>(&self, k: usize, rays: &RayLanes<V>) -> SpanLanes<V> {
        match &self.operands[k] {
            Operand::Sphere(centre, r2) => span_lanes::sphere(rays, *centre, *r2),
            Operand::Solid(shape, to_local) => {
                let local;
                let rays = match to_local {
                    Some(m) => {
                        local = span_lanes::to_local(rays, m);
                        &local
                    }
                    None => rays,
                };
                match shape {
                    Shape::Box(b) => span_lanes::aabox(b, rays),
                    Shape::Cylinder(c) => span_lanes::cylinder(c, rays),
                    Shape::Cone(c) => span_lanes::cone(c, rays),
                    _ => unreachable!("only boxes, cylinders and cones are solid operands"),
                }
            }
        }
    }
}

/// The lens's evaluation: the steps of `FlatCsg::nearest_of_two` for the spheres' common part
/// searched from t = 0 (`SphereGroup::common_spans`, then the walk).
#[inline(always)]
fn lens_hits<V: F64x4>(
    rays: &RayLanes<V>,
    (ca, ra2): (DVec3, f64),
    (cb, rb2): (DVec3, f64),
    open: u32,
    t_max: V,
    prune: bool,
) -> LanesHits<V> {
    let a = span_lanes::sphere_quadratic(rays, ca, ra2);
    let b = span_lanes::sphere_quadratic(rays, cb, rb2);
    let ((a_disc, a_no_root), (b_disc, b_no_root)) = (a.disc(), b.disc());
    let open = lane_mask::<V>(open);
    let finite = a.finite & b.finite;
    // The common part searched from t = 0 is missed as soon as one sphere is passed by, has
    // no root, or is met only behind the origin; B counts as pruned where A has no span.
    let a_empty = a.passes | a_no_root;
    let missed = open & finite & (a_empty | b.passes | b_no_root | a.away | b.away);
    let pruned = if prune {
        (missed & a_empty).to_bitmask().count_ones() as u64
    } else {
        0
    };
    let rest = open & !missed;
    if rest.to_bitmask() == 0 {
        return LanesHits {
            pruned,
            ..LanesHits::NONE
        };
    }
    let (a_in, a_out) = a.roots(a_disc);
    let (b_in, b_out) = b.roots(b_disc);
    // Both spans exist here; NaN ends, reversed ones or ones of no thickness in the window
    // are for the segment lists.
    let thin = thin(a_in, a_out, t_max) | thin(b_in, b_out, t_max);
    let live = rest & finite & a_in.simd_le(a_out) & b_in.simd_le(b_out) & !thin;
    let walk = walk(CsgOp::Intersection, [a_in, a_out, b_in, b_out], t_max);
    // A sphere has one face.
    let found = walk.hits(live, [V::ZERO; 4], rest & !live);
    LanesHits { pruned, ..found }
}

/// Where the rule first changes along four rays.
struct Walk<V> {
    /// The first end in the window (0, t_max) where the rule's answer changes (∞: none).
    first: V,
    /// All ones where end k (A in, A out, B in, B out) lies at `first`.
    at_first: [V; 4],
    /// Another end at the same t: left to the segment lists.
    tie: V,
}

impl<V: F64x4> Walk<V> {
    /// The hits of the rays in `live` where the walk found a change; `left` are rays already
    /// left to the one-ray path, joined by those whose first change ties with another end.
    /// Each hit's face is the one of its end among `faces` (A in, A out, B in, B out).
    #[inline(always)]
    fn hits(&self, live: V, faces: [V; 4], left: V) -> LanesHits<V> {
        let found = live & self.first.simd_lt(V::splat(f64::INFINITY));
        let hit = found & !self.tie;
        let mut face = V::ZERO;
        for (at, f) in self.at_first.iter().zip(faces) {
            face = at.bitselect(f, face);
        }
        LanesHits {
            hit: hit.to_bitmask(),
            t: self.first,
            on_b: (hit & (self.at_first[2] | self.at_first[3])).to_bitmask(),
            face,
            undecided: (left | (found & self.tie)).to_bitmask(),
            pruned: 0,
        }
    }
}

/// The walk of `first_change_of_two`, four rays at a time: at each end t, each operand's
/// inside flag just before and just after it (an end at t enters before it leaves), and the
/// first end in the window where the rule's answer differs between the two. NaN ends (no
/// span) are never inside and never in the window.
#[inline(always)]
fn walk<V: F64x4>(op: CsgOp, ends: [V; 4], t_max: V) -> Walk<V> {
    let [a_in, a_out, b_in, b_out] = ends;
    // (Helper functions rather than closures or array maps: each must be inlined into the
    // lanes' copy for the processor, `simd::with_lanes`.)
    let within = [
        in_window(a_in, t_max),
        in_window(a_out, t_max),
        in_window(b_in, t_max),
        in_window(b_out, t_max),
    ];
    let mut first = V::splat(f64::INFINITY);
    for (&t, &within) in ends.iter().zip(&within) {
        let (a_before, a_after) = inside(a_in, a_out, t);
        let (b_before, b_after) = inside(b_in, b_out, t);
        let changes = (rule(op, a_before, b_before) ^ rule(op, a_after, b_after)) & within;
        first = changes.bitselect(first.fast_min(t), first);
    }
    let at_first: [V; 4] = [
        within[0] & a_in.simd_eq(first),
        within[1] & a_out.simd_eq(first),
        within[2] & b_in.simd_eq(first),
        within[3] & b_out.simd_eq(first),
    ];
    // Another end that is one with the first change (`csg::same_end`: within 10⁻¹² of their
    // size, a face shared by both operands): left to the segment lists, which apply them
    // together. Within 2·10⁻¹² of the first change's size takes in every end `same_end` takes
    // (and a few more, which the segment lists settle alike) for fewer operations.
    let reach = V::splat(2e-12) * first.abs();
    let one = [
        (a_in - first).abs().simd_le(reach),
        (a_out - first).abs().simd_le(reach),
        (b_in - first).abs().simd_le(reach),
        (b_out - first).abs().simd_le(reach),
    ];
    let mut tie = V::ZERO;
    for i in 0..4 {
        for j in i + 1..4 {
            tie |= one[i] & one[j];
        }
    }
    Walk {
        first,
        at_first,
        tie,
    }
}

/// All ones where a span's ends are one (`csg::same_end`, within 2·10⁻¹² as the walk's ties)
/// inside the window: a span of no thickness.
#[inline(always)]
fn thin<V: F64x4>(t_in: V, t_out: V, t_max: V) -> V {
    let reach = V::splat(2e-12) * t_in.abs();
    (t_in - t_out).abs().simd_le(reach) & in_window(t_in, t_max)
}

/// All ones where the end t lies in the window: 0 < t < t_max, finite.
#[inline(always)]
fn in_window<V: F64x4>(t: V, t_max: V) -> V {
    t.simd_gt(V::ZERO) & t.simd_lt(t_max) & t.abs().simd_lt(V::splat(f64::INFINITY))
}

/// An operand's inside flag just before and just after t.
#[inline(always)]
fn inside<V: F64x4>(t_in: V, t_out: V, t: V) -> (V, V) {
    let before = t_in.simd_lt(t) & t.simd_le(t_out);
    let after = t_in.simd_le(t) & t.simd_lt(t_out);
    (before, after)
}

/// The operation's rule on the operands' inside flags.
#[inline(always)]
fn rule<V: F64x4>(op: CsgOp, a: V, b: V) -> V {
    match op {
        CsgOp::Union => a | b,
        CsgOp::Intersection => a & b,
        CsgOp::Difference => a & !b,
        CsgOp::Complement => unreachable!("complements stay trees"),
    }
}
