//! Constructive solid geometry on segment lists, as seed 000 teaches it: every child returns the
//! segments where the ray is inside it, and the operation combines the lists.
//!
//! The set operations are *regularised*: a result of zero thickness (two solids touching in a
//! face, the notes' "Cube A ∩ Cube B = a plane") is dropped, and segments that touch are merged.
//! A face shared by two solids is found twice, once by each, and the two computations may
//! differ in their last bits: ends this close (`same_end`) are one end, so a shared face leaves
//! no sliver a rounding error thick.
//! A surface of the result keeps the leaf it comes from; where a difference carves B out of A,
//! B's surface bounds the result from the other side, so its normal is flipped.

use glam::DVec3;
use serde::Serialize;

use super::{Ray, Segment, SegmentList, Surface};
use crate::accel::Aabb;

/// A CSG operation on the inside of solids, acting pointwise on the segment lists along a ray.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CsgOp {
    /// A ∪ B: inside either operand.
    Union,
    /// A ∩ B: inside both operands.
    Intersection,
    /// A − B: inside A but not B.
    Difference,
    /// Not A: the outside of a single operand (its segments inverted).
    Complement,
}

impl CsgOp {
    /// The operation's name as written in scene files (`union`, `intersection`, …).
    pub fn name(self) -> &'static str {
        match self {
            CsgOp::Union => "union",
            CsgOp::Intersection => "intersection",
            CsgOp::Difference => "difference",
            CsgOp::Complement => "complement",
        }
    }

    /// Inside the result of a binary operation, given inside A and inside B.
    fn keeps(self, a: bool, b: bool) -> bool {
        match self {
            CsgOp::Union => a || b,
            CsgOp::Intersection => a && b,
            CsgOp::Difference => a && !b,
            CsgOp::Complement => unreachable!("combine takes the complement whole"),
        }
    }
}

/// A node of a CSG tree: a primitive leaf, or an operation over children (n-ary lists fold
/// left: `difference: [A, B, C]` is (A − B) − C).
#[derive(Clone, Debug)]
pub enum CsgNode {
    /// A primitive operand: its segment list comes straight from the shape.
    Leaf {
        /// Index of the primitive among the scene's CSG leaves.
        leaf: u32,
        /// World-space box around the primitive, to skip it when the ray misses.
        bounds: Aabb,
    },
    /// An operation over two or more children (one for `complement`).
    Op {
        /// Which operation combines the children's segment lists.
        op: CsgOp,
        /// The node's name in the scene file, or the operation's name when it has none.
        name: String,
        /// The operands, folded left to right.
        children: Vec<CsgNode>,
        /// World-space box around the node's result, tightened by bounding balls where possible.
        bounds: Aabb,
    },
}

/// Why a node was not evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Pruned {
    /// The ray misses the node's bounding box.
    Bounds,
    /// An earlier operand of an intersection was empty.
    EmptyIntersection,
    /// The left operand of a difference was empty.
    EmptyDifference,
    /// Not evaluated because a node above it was pruned (whatever the ray does near it).
    ParentPruned,
}

/// What a CSG evaluation did at each node, for `raytree csg` and the inspector.
#[derive(Clone, Debug)]
pub struct CsgTrace {
    /// Name of the node (its name in the scene file, or its operation's or shape's).
    pub node: String,
    /// The operation, for an operation node; None for a leaf.
    pub op: Option<CsgOp>,
    /// The leaf index, for a primitive; None for an operation.
    pub leaf: Option<u32>,
    /// The node's segment list along the ray (empty when pruned).
    pub segments: SegmentList,
    /// Why the node was skipped, or None when it was evaluated.
    pub pruned: Option<Pruned>,
    /// The traces of the node's children, in order.
    pub children: Vec<CsgTrace>,
}

/// Counters of the work CSG did and skipped.
#[derive(Clone, Copy, Debug, Default)]
pub struct CsgWork {
    /// Primitive segment lists computed (ray–leaf intersections).
    pub leaves_tested: u64,
    /// Nodes skipped, by their bounds or by the pruning rules.
    pub pruned: u64,
}

/// The environment a CSG evaluation needs: the leaf segment lists.
pub trait LeafSegments {
    /// The segment list of leaf `leaf` along `ray` (world space): where the ray is inside it.
    fn leaf_segments(&self, leaf: u32, ray: &Ray) -> SegmentList;
    /// A name for leaf `leaf`, for traces.
    fn leaf_name(&self, leaf: u32) -> String;
}

/// The ray with its reciprocal direction and the window of t that matters: a subtree whose box
/// the ray misses within the window contributes nothing there (the operations act pointwise
/// on t, so restricting every input to the window restricts the result to it).
pub struct CsgRay<'a> {
    /// The ray, in world space.
    pub ray: &'a Ray,
    /// 1/d per component, for the slab tests of the nodes' boxes.
    pub inv_dir: DVec3,
    /// Start of the window of t that matters.
    pub t_min: f64,
    /// End of the window of t that matters.
    pub t_max: f64,
    /// Skip subtrees whose bounding box the ray misses (off to show the notes' own pruning).
    pub use_bounds: bool,
    /// Skip operands the notes' rules make irrelevant (off only to measure what they save).
    pub prune: bool,
}

impl CsgNode {
    /// The world-space box around everything the node can contain.
    pub fn bounds(&self) -> Aabb {
        match self {
            CsgNode::Leaf { bounds, .. } | CsgNode::Op { bounds, .. } => *bounds,
        }
    }

    /// The segment list of this subtree along the ray.
    pub fn segments(&self, env: &impl LeafSegments, r: &CsgRay, work: &mut CsgWork) -> SegmentList {
        self.evaluate::<false>(env, r, work, &mut Vec::new())
    }

    /// The segment list, and what happened at every node on the way.
    pub fn trace(
        &self,
        env: &impl LeafSegments,
        r: &CsgRay,
        work: &mut CsgWork,
    ) -> (SegmentList, CsgTrace) {
        let mut out = Vec::with_capacity(1);
        let list = self.evaluate::<true>(env, r, work, &mut out);
        (list, out.pop().expect("tracing records every node"))
    }

    /// The segment list of this subtree; with TRACE, the node's trace is pushed onto `out`
    /// (the render path passes an empty Vec that is never touched, so it costs nothing).
    fn evaluate<const TRACE: bool>(
        &self,
        env: &impl LeafSegments,
        r: &CsgRay,
        work: &mut CsgWork,
        out: &mut Vec<CsgTrace>,
    ) -> SegmentList {
        if r.use_bounds && !self.bounds().hit(r.ray.origin, r.inv_dir, r.t_min, r.t_max) {
            work.pruned += 1;
            if TRACE {
                out.push(self.skipped(env, Pruned::Bounds));
            }
            return SegmentList::new();
        }
        match self {
            CsgNode::Leaf { leaf, .. } => {
                work.leaves_tested += 1;
                let list = env.leaf_segments(*leaf, r.ray);
                if TRACE {
                    out.push(CsgTrace {
                        node: env.leaf_name(*leaf),
                        op: None,
                        leaf: Some(*leaf),
                        segments: list.clone(),
                        pruned: None,
                        children: vec![],
                    });
                }
                list
            }
            CsgNode::Op {
                op, name, children, ..
            } => {
                let mut traces = Vec::new();
                let mut acc = children[0].evaluate::<TRACE>(env, r, work, &mut traces);
                if *op == CsgOp::Complement {
                    acc = complement(&acc);
                }
                for child in &children[1..] {
                    let prune = match op {
                        _ if !r.prune => None,
                        CsgOp::Intersection if acc.is_empty() => Some(Pruned::EmptyIntersection),
                        CsgOp::Difference if acc.is_empty() => Some(Pruned::EmptyDifference),
                        _ => None,
                    };
                    if let Some(why) = prune {
                        work.pruned += 1;
                        if TRACE {
                            traces.push(child.skipped(env, why));
                        }
                        continue;
                    }
                    let list = child.evaluate::<TRACE>(env, r, work, &mut traces);
                    acc = combine(*op, &acc, &list);
                }
                if TRACE {
                    out.push(CsgTrace {
                        node: name.clone(),
                        op: Some(*op),
                        leaf: None,
                        segments: acc.clone(),
                        pruned: None,
                        children: traces,
                    });
                }
                acc
            }
        }
    }

    /// The trace of a subtree that was not evaluated: its root for `why`, every node below it
    /// for its parent.
    fn skipped(&self, env: &impl LeafSegments, why: Pruned) -> CsgTrace {
        match self {
            CsgNode::Leaf { leaf, .. } => CsgTrace {
                node: env.leaf_name(*leaf),
                op: None,
                leaf: Some(*leaf),
                segments: SegmentList::new(),
                pruned: Some(why),
                children: vec![],
            },
            CsgNode::Op {
                op, name, children, ..
            } => CsgTrace {
                node: name.clone(),
                op: Some(*op),
                leaf: None,
                segments: SegmentList::new(),
                pruned: Some(why),
                children: children
                    .iter()
                    .map(|c| c.skipped(env, Pruned::ParentPruned))
                    .collect(),
            },
        }
    }
}

/// One boundary of a segment list, seen as an event along the ray.
#[derive(Clone, Copy)]
struct Event {
    t: f64,
    entering: bool,
    surface: Surface,
}

/// How close two ends must be, relative to their size, to be one end: far above the few
/// units in the last place by which two computations of one face differ, far below any
/// thickness a scene can mean (10⁻¹² of the distance along the ray).
const SAME_END: f64 = 1e-12;

/// Whether two span ends are one end: equal, or within `SAME_END` of each other relative to
/// their size (a face shared by two solids, each computing it).
#[inline]
pub fn same_end(x: f64, y: f64) -> bool {
    let size = x.abs().max(y.abs());
    x == y || (size < f64::INFINITY && (x - y).abs() <= SAME_END * size)
}

/// Boundary k of a list: segment k/2's entry (k even) or exit (k odd).
#[inline]
fn event(list: &[Segment], k: usize) -> Option<Event> {
    let s = list.get(k / 2)?;
    Some(if k.is_multiple_of(2) {
        Event {
            t: s.t_in,
            entering: true,
            surface: s.enter,
        }
    } else {
        Event {
            t: s.t_out,
            entering: false,
            surface: s.exit,
        }
    })
}

/// Combine two segment lists: the sweep below, or its answer read off directly in the two
/// common cases.
///
/// - One list is empty (the ray missed that operand, often by its bounding box). ∅ ∩ B, A ∩ ∅
///   and ∅ − B are empty; A ∪ ∅ and A − ∅ are A, and ∅ ∪ B is B, provided that list is
///   already regular (segments of positive length, not touching), which is what the sweep
///   would make of it.
/// - Each list is one segment (two convex primitives) and no two ends coincide: see `pair`.
pub fn combine(op: CsgOp, a: &[Segment], b: &[Segment]) -> SegmentList {
    match (op, a, b) {
        (CsgOp::Complement, _, _) => complement(a),
        (CsgOp::Intersection, [], _)
        | (CsgOp::Intersection, _, [])
        | (CsgOp::Difference, [], _) => SegmentList::new(),
        (CsgOp::Union | CsgOp::Difference, _, []) if is_regular(a) => a.into(),
        (CsgOp::Union, [], _) if is_regular(b) => b.into(),
        (CsgOp::Union | CsgOp::Intersection | CsgOp::Difference, [x], [y]) => {
            pair(op, x, y).unwrap_or_else(|| sweep(op, a, b))
        }
        _ => sweep(op, a, b),
    }
}

/// A op B for single segments A = [a₀, a₁] and B = [b₀, b₁] whose four ends are distinct and
/// in order (a₀ < a₁, b₀ < b₁; never true with a NaN). Then every end of the result is one
/// end of A or B, with its surface, and which one follows from the order of the ends alone,
/// as the sweep would find it one boundary at a time. Coinciding ends (touching or shared
/// faces, `same_end`, which the sweep merges or drops) are left to the sweep: None.
fn pair(op: CsgOp, a: &Segment, b: &Segment) -> Option<SegmentList> {
    let ordered = a.t_in < a.t_out && b.t_in < b.t_out;
    let distinct = !same_end(a.t_in, b.t_in)
        && !same_end(a.t_in, b.t_out)
        && !same_end(a.t_out, b.t_in)
        && !same_end(a.t_out, b.t_out);
    if !(ordered && distinct) {
        return None;
    }
    let segment = |t_in, enter, t_out, exit| Segment {
        t_in,
        t_out,
        enter,
        exit,
    };
    let mut out = SegmentList::new();
    match op {
        // The later entry and the earlier exit, if the entry comes first.
        CsgOp::Intersection => {
            let (t_in, enter) = if a.t_in > b.t_in {
                (a.t_in, a.enter)
            } else {
                (b.t_in, b.enter)
            };
            let (t_out, exit) = if a.t_out < b.t_out {
                (a.t_out, a.exit)
            } else {
                (b.t_out, b.exit)
            };
            if t_in < t_out {
                out.push(segment(t_in, enter, t_out, exit));
            }
        }
        // Apart: both, in order. Overlapping: from the earlier entry to the later exit.
        CsgOp::Union => {
            if a.t_out < b.t_in {
                out.extend([*a, *b]);
            } else if b.t_out < a.t_in {
                out.extend([*b, *a]);
            } else {
                let (t_in, enter) = if a.t_in < b.t_in {
                    (a.t_in, a.enter)
                } else {
                    (b.t_in, b.enter)
                };
                let (t_out, exit) = if a.t_out > b.t_out {
                    (a.t_out, a.exit)
                } else {
                    (b.t_out, b.exit)
                };
                out.push(segment(t_in, enter, t_out, exit));
            }
        }
        // A where B is not: B's entry ends a piece of A and its exit starts one, with B's
        // surfaces seen from the other side.
        CsgOp::Difference => {
            let (b_enter, b_exit) = (b.enter.flipped(), b.exit.flipped());
            if b.t_out < a.t_in || a.t_out < b.t_in {
                out.push(*a);
            } else {
                if a.t_in < b.t_in {
                    out.push(segment(a.t_in, a.enter, b.t_in, b_enter));
                }
                if b.t_out < a.t_out {
                    out.push(segment(b.t_out, b_exit, a.t_out, a.exit));
                }
            }
        }
        CsgOp::Complement => return None,
    }
    Some(out)
}

/// Every segment has positive length and ends before the next begins, no two ends one
/// (`same_end`) (false for any NaN).
fn is_regular(list: &[Segment]) -> bool {
    let apart = |x: f64, y: f64| x < y && !same_end(x, y);
    list.iter().all(|s| apart(s.t_in, s.t_out))
        && list.windows(2).all(|w| apart(w[0].t_out, w[1].t_in))
}

/// Combine two segment lists by sweeping their boundaries in order of t. All boundaries at the
/// same t (`same_end` of the first of them) are applied together before the result is compared
/// with its state before, so touching segments merge and zero-thickness results never appear.
fn sweep(op: CsgOp, a: &[Segment], b: &[Segment]) -> SegmentList {
    let (mut i, mut j) = (0, 0);
    let (mut in_a, mut in_b) = (false, false);
    let mut out = SegmentList::new();
    let mut open: Option<(f64, Surface)> = None;
    loop {
        let (ea, eb) = (event(a, i), event(b, j));
        let t = match (ea, eb) {
            (Some(x), Some(y)) => x.t.min(y.t),
            (Some(x), None) => x.t,
            (None, Some(y)) => y.t,
            (None, None) => break,
        };
        let before = op.keeps(in_a, in_b);
        // The surface the result crosses here: the first boundary at t that enters (or
        // leaves) as the result does, A's before B's; failing that, the first one at t. B's
        // surfaces bound a difference from the other side: flip them.
        let mut first: [Option<Surface>; 2] = [None, None]; // [leaving, entering]
        let mut any: Option<Surface> = None;
        let mut note = |entering: bool, surface: Surface| {
            first[entering as usize].get_or_insert(surface);
            any.get_or_insert(surface);
        };
        while let Some(e) = event(a, i).filter(|e| same_end(e.t, t)) {
            in_a = e.entering;
            note(e.entering, e.surface);
            i += 1;
        }
        while let Some(e) = event(b, j).filter(|e| same_end(e.t, t)) {
            in_b = e.entering;
            let flip = op == CsgOp::Difference;
            let s = if flip { e.surface.flipped() } else { e.surface };
            note(e.entering != flip, s);
            j += 1;
        }
        let Some(fallback) = any else {
            // Only a NaN boundary is left (no t equals it): nothing more can be combined.
            break;
        };
        let after = op.keeps(in_a, in_b);
        if before == after {
            continue;
        }
        let surface = first[after as usize].unwrap_or(fallback);
        if after {
            open = Some((t, surface));
        } else if let Some((t_in, enter)) = open.take() {
            out.push(Segment {
                t_in,
                t_out: t,
                enter,
                exit: surface,
            });
        }
    }
    out
}

/// ¬A: the gaps between A's segments, out to ±∞; every surface now faces the other way.
pub fn complement(a: &[Segment]) -> SegmentList {
    let mut out = SegmentList::new();
    let mut start = (f64::NEG_INFINITY, a.first().map(|s| s.enter.flipped()));
    for s in a {
        if s.t_in > start.0 {
            let enter = start.1.unwrap_or(s.enter.flipped());
            out.push(Segment {
                t_in: start.0,
                t_out: s.t_in,
                enter,
                exit: s.enter.flipped(),
            });
        }
        start = (s.t_out, Some(s.exit.flipped()));
    }
    if start.0 < f64::INFINITY {
        let surface = start.1.unwrap_or(Surface::new(u32::MAX, 0));
        out.push(Segment {
            t_in: start.0,
            t_out: f64::INFINITY,
            enter: surface,
            exit: surface,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn list(pairs: &[(f64, f64)], leaf: u32) -> SegmentList {
        pairs
            .iter()
            .map(|&(t_in, t_out)| Segment {
                t_in,
                t_out,
                enter: Surface::new(leaf, 0),
                exit: Surface::new(leaf, 0),
            })
            .collect()
    }

    fn ts(l: &[Segment]) -> Vec<(f64, f64)> {
        l.iter().map(|s| (s.t_in, s.t_out)).collect()
    }

    /// With one operand empty, `combine` answers without sweeping: the same lists, surfaces and
    /// all, as the sweep, for regular lists and for the ones it must regularise.
    #[test]
    fn combining_with_nothing_is_the_sweep() {
        let lists = [
            list(&[], 0),
            list(&[(1.0, 2.0)], 0),
            list(&[(1.0, 2.0), (3.0, 5.0)], 0),
            list(&[(1.0, 1.0)], 0),
            list(&[(1.0, 2.0), (2.0, 4.0)], 0),
            list(&[(f64::NEG_INFINITY, 2.0), (3.0, f64::INFINITY)], 0),
            list(&[(1.0, f64::NAN)], 0),
        ];
        let empty = list(&[], 1);
        for op in [CsgOp::Union, CsgOp::Intersection, CsgOp::Difference] {
            for l in &lists {
                assert_eq!(
                    combine(op, l, &empty),
                    sweep(op, l, &empty),
                    "{op:?} {l:?} ∅"
                );
                assert_eq!(
                    combine(op, &empty, l),
                    sweep(op, &empty, l),
                    "{op:?} ∅ {l:?}"
                );
            }
        }
    }

    /// Two single segments combine to exactly what the sweep builds, surfaces included, for
    /// every order of their ends: distinct (the direct answer), coinciding (left to the sweep),
    /// infinite, of zero length, and NaN.
    #[test]
    fn combining_two_segments_is_the_sweep() {
        let ends = [
            f64::NEG_INFINITY,
            0.0,
            1.0,
            2.0,
            3.0,
            4.0,
            f64::INFINITY,
            f64::NAN,
        ];
        let mut pairs = 0;
        for &a0 in &ends {
            for &a1 in &ends {
                for &b0 in &ends {
                    for &b1 in &ends {
                        let a = [Segment {
                            t_in: a0,
                            t_out: a1,
                            enter: Surface::new(0, 1),
                            exit: Surface::new(0, 2),
                        }];
                        let b = [Segment {
                            t_in: b0,
                            t_out: b1,
                            enter: Surface::new(1, 3),
                            exit: Surface::new(1, 4),
                        }];
                        for op in [CsgOp::Union, CsgOp::Intersection, CsgOp::Difference] {
                            let (fast, slow) = (combine(op, &a, &b), sweep(op, &a, &b));
                            // Bitwise, so that NaN ends compare too.
                            let bits = |l: &[Segment]| {
                                l.iter()
                                    .map(|s| (s.t_in.to_bits(), s.t_out.to_bits(), s.enter, s.exit))
                                    .collect::<Vec<_>>()
                            };
                            assert_eq!(bits(&fast), bits(&slow), "{op:?} {a:?} {b:?}");
                            pairs += pair(op, &a[0], &b[0]).is_some() as u32;
                        }
                    }
                }
            }
        }
        // The direct answer took every ordered choice of four distinct ends from the seven
        // non-NaN ones, and nothing else: C(7, 4) sets × 6 ways to split one into A and B
        // (4!/(2!·2!)) × 3 operations.
        assert_eq!(pairs, 35 * 6 * 3);
    }

    #[test]
    fn seed_000_sphere_lists_combine_as_the_notes_state() {
        // Along the ray from (0,0,−10) in +z: A = [13, 23], B = [16, 22], C (touching at 18) = [18, 18].
        let (a, b, c) = (
            list(&[(13.0, 23.0)], 0),
            list(&[(16.0, 22.0)], 1),
            list(&[(18.0, 18.0)], 2),
        );
        assert_eq!(
            ts(&combine(CsgOp::Difference, &a, &b)),
            vec![(13.0, 16.0), (22.0, 23.0)]
        );
        assert_eq!(
            ts(&combine(CsgOp::Union, &combine(CsgOp::Union, &a, &b), &c)),
            vec![(13.0, 23.0)]
        );
        assert!(combine(CsgOp::Intersection, &combine(CsgOp::Difference, &b, &a), &c).is_empty());
    }

    #[test]
    fn carved_surfaces_are_flipped_and_touching_segments_merge() {
        let a = list(&[(0.0, 10.0)], 0);
        let b = list(&[(4.0, 6.0)], 1);
        let d = combine(CsgOp::Difference, &a, &b);
        assert_eq!(d[0].exit, Surface::new(1, 0).flipped());
        assert_eq!(d[1].enter, Surface::new(1, 0).flipped());
        let touching = combine(
            CsgOp::Union,
            &list(&[(0.0, 1.0)], 0),
            &list(&[(1.0, 2.0)], 1),
        );
        assert_eq!(ts(&touching), vec![(0.0, 2.0)]);
        let face = combine(
            CsgOp::Intersection,
            &list(&[(0.0, 1.0)], 0),
            &list(&[(1.0, 2.0)], 1),
        );
        assert!(face.is_empty(), "a shared face has no thickness");
    }

    /// A face shared by two solids, computed once by each, may differ in its last bits: the
    /// two ends are one, so a hole drilled flush with a top face leaves no film a rounding
    /// error thick, A − A computed two ways is empty, and two solids touching merge. A real
    /// gap, a millionth of the distance, stays.
    #[test]
    fn ends_a_rounding_error_apart_are_one_end() {
        let ulp = |x: f64, n: u64| f64::from_bits(x.to_bits() + n);
        let cup = list(&[(3.001889, 7.004408)], 0);
        let hole = list(&[(ulp(3.001889, 1), 6.404031)], 1);
        let carved = combine(CsgOp::Difference, &cup, &hole);
        assert_eq!(ts(&carved), vec![(6.404031, 7.004408)]);
        assert_eq!(carved[0].enter, Surface::new(1, 0).flipped());
        let a = list(&[(10.016988140466118, 10.169791882574955)], 0);
        let b = list(&[(10.016988140466122, 10.169791882574952)], 1);
        assert!(combine(CsgOp::Difference, &a, &b).is_empty());
        assert_eq!(ts(&combine(CsgOp::Intersection, &a, &b)).len(), 1);
        let touching = combine(
            CsgOp::Union,
            &list(&[(0.0, 1.0)], 0),
            &list(&[(ulp(1.0, 3), 2.0)], 1),
        );
        assert_eq!(ts(&touching), vec![(0.0, 2.0)]);
        let apart = combine(
            CsgOp::Union,
            &list(&[(0.0, 1.0)], 0),
            &list(&[(1.000001, 2.0)], 1),
        );
        assert_eq!(ts(&apart), vec![(0.0, 1.0), (1.000001, 2.0)]);
        // Infinite ends are one only when equal.
        assert!(same_end(f64::INFINITY, f64::INFINITY));
        assert!(!same_end(f64::INFINITY, 5.0) && !same_end(5.0, f64::NEG_INFINITY));
        assert!(!same_end(f64::NAN, f64::NAN));
    }

    /// The complement is unary: `combine` gives the complement of its first list, surfaces
    /// flipped (the inside of the result is the outside of A), whatever the second.
    #[test]
    fn combining_by_complement_is_the_complement_of_the_first_list() {
        let a = list(&[(0.0, 10.0), (12.0, 14.0)], 0);
        let b = list(&[(4.0, 6.0)], 1);
        let c = combine(CsgOp::Complement, &a, &b);
        assert_eq!(c, complement(&a));
        assert_eq!(
            ts(&c),
            vec![
                (f64::NEG_INFINITY, 0.0),
                (10.0, 12.0),
                (14.0, f64::INFINITY)
            ]
        );
        assert_eq!(c[1].enter, Surface::new(0, 0).flipped());
    }

    /// A list open at either end (a plane's half-space, say) has no gap beyond that end: the
    /// complement of (−∞, 2] ∪ [3, ∞) is [2, 3] alone, and that of nothing is the whole line.
    #[test]
    fn the_complement_has_no_empty_piece_beyond_an_infinite_end() {
        let inf = f64::INFINITY;
        let c = complement(&list(&[(-inf, 2.0), (3.0, inf)], 0));
        assert_eq!(ts(&c), vec![(2.0, 3.0)]);
        assert_eq!(ts(&complement(&list(&[(-inf, 2.0)], 0))), vec![(2.0, inf)]);
        assert_eq!(ts(&complement(&list(&[(3.0, inf)], 0))), vec![(-inf, 3.0)]);
        assert_eq!(ts(&complement(&[])), vec![(-inf, inf)]);
    }

    /// Leaves as fixed lists along any ray: 0 is missed, 1 is [2, 3], 2 is [1, 4].
    struct Lists;

    impl LeafSegments for Lists {
        fn leaf_segments(&self, leaf: u32, _: &Ray) -> SegmentList {
            match leaf {
                0 => list(&[], 0),
                1 => list(&[(2.0, 3.0)], 1),
                _ => list(&[(1.0, 4.0)], 2),
            }
        }
        fn leaf_name(&self, leaf: u32) -> String {
            format!("leaf {leaf}")
        }
    }

    fn op(op: CsgOp, leaves: &[u32]) -> CsgNode {
        let leaf = |leaf| CsgNode::Leaf {
            leaf,
            bounds: Aabb::everything(),
        };
        CsgNode::Op {
            op,
            name: op.name().into(),
            children: leaves.iter().map(|&l| leaf(l)).collect(),
            bounds: Aabb::everything(),
        }
    }

    /// The notes' pruning rules: an intersection or a difference whose first operand is empty
    /// is empty, so its second is never intersected with the ray (one leaf tested, one node
    /// pruned); with pruning off both are tested. A union always needs both.
    #[test]
    fn an_empty_first_operand_prunes_the_second_of_an_intersection_or_difference() {
        let ray = Ray::new(DVec3::ZERO, DVec3::X);
        let counts = |node: &CsgNode, prune: bool| {
            let r = CsgRay {
                ray: &ray,
                inv_dir: ray.dir.recip(),
                t_min: 0.0,
                t_max: f64::INFINITY,
                use_bounds: false,
                prune,
            };
            let mut work = CsgWork::default();
            let (list, trace) = node.trace(&Lists, &r, &mut work);
            let why = trace.children.iter().map(|c| c.pruned).collect::<Vec<_>>();
            (ts(&list), work.leaves_tested, work.pruned, why)
        };
        let empty: Vec<(f64, f64)> = vec![];
        let intersection = op(CsgOp::Intersection, &[0, 1]);
        assert_eq!(
            counts(&intersection, true),
            (
                empty.clone(),
                1,
                1,
                vec![None, Some(Pruned::EmptyIntersection)]
            )
        );
        assert_eq!(
            counts(&intersection, false),
            (empty.clone(), 2, 0, vec![None, None])
        );
        let difference = op(CsgOp::Difference, &[0, 2]);
        assert_eq!(
            counts(&difference, true),
            (empty, 1, 1, vec![None, Some(Pruned::EmptyDifference)])
        );
        let union = op(CsgOp::Union, &[1, 2]);
        assert_eq!(
            counts(&union, true),
            (vec![(1.0, 4.0)], 2, 0, vec![None, None])
        );
    }

    #[test]
    fn complement_then_intersection_is_difference() {
        let a = list(&[(0.0, 10.0), (12.0, 14.0)], 0);
        let b = list(&[(4.0, 6.0), (13.0, 20.0)], 1);
        assert_eq!(
            ts(&combine(CsgOp::Intersection, &a, &complement(&b))),
            ts(&combine(CsgOp::Difference, &a, &b))
        );
    }
}
