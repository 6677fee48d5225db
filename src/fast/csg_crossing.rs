//! The nearest surface crossing of a flat CSG object (one operation over primitives), read off
//! the primitives' spans without building segment lists.
//!
//! A ray is inside the result exactly where the operation's rule holds for "inside A", "inside
//! B", … (seed 000's tables), and a primitive's span says where the ray is inside it. So the
//! result's boundaries are the span ends at which the rule changes its answer, and the nearest
//! hit is the first such end past t_min. This is what the segment-list sweep computes, one
//! boundary at a time; the two can differ only where several ends coincide and the rule
//! changes there (touching or shared faces: which surface does the result keep?). There this
//! path answers `Undecided` and the caller asks the segment lists, which settle it as the notes
//! do. Bounding boxes and the notes' pruning rules are applied in the tree's own order and
//! counted the same way, so `--stats` does not change either.

use arrayvec::ArrayVec;
use smallvec::SmallVec;

use super::lanes::LANES;
use super::simd::F64x4;
use super::sphere_group::SphereGroup;
use crate::accel::Aabb;
use crate::geometry::csg::{same_end, CsgNode, CsgOp, CsgRay, CsgWork};
use crate::geometry::{Ray, Span, Sphere, Surface};

/// At most this many primitives: the inside flags fit a mask, the ends sort quickly, and the
/// working lists live on the stack (a heap allocation per ray would cost more than the lists).
const MAX_LEAVES: usize = 16;

/// A CSG tree of depth one, ready for `nearest`.
#[derive(Clone, Debug)]
pub struct FlatCsg {
    op: CsgOp,
    /// The operands in the tree's order: leaf index, and world bounds worth testing. A box
    /// that holds the root's box is met whenever the root's is (the slab test is monotone in
    /// the box's planes), so it is not tested again: None.
    leaves: SmallVec<[(u32, Option<Aabb>); 2]>,
    /// The operands, when all are spheres in world space and fit one group: then their spans
    /// are found side by side (a lens).
    spheres: Option<SphereGroup>,
}

/// The answer of `FlatCsg::nearest`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Crossing {
    Hit(f64, Surface),
    Miss,
    /// Several span ends coincide where the rule changes: ask the segment lists.
    Undecided,
}

/// The environment: a primitive's span along a ray.
pub trait LeafSpans {
    fn leaf_span(&self, leaf: u32, ray: &Ray) -> Option<Span>;
}

impl FlatCsg {
    /// The flat form of a tree that is one ∪ or ∩ over up to sixteen primitives, or one
    /// difference A − B of two. Deeper trees, longer differences and complements keep the
    /// segment lists (their pruning depends on whole intermediate lists).
    /// `sphere` tells a leaf that is a sphere in world space.
    pub fn new(root: &CsgNode, sphere: impl Fn(u32) -> Option<Sphere>) -> Option<FlatCsg> {
        let CsgNode::Op { op, children, .. } = root else {
            return None;
        };
        let fits = match op {
            CsgOp::Union | CsgOp::Intersection => children.len() <= MAX_LEAVES,
            CsgOp::Difference => children.len() == 2,
            CsgOp::Complement => false,
        };
        let root_bounds = root.bounds();
        let holds_root =
            |b: &Aabb| b.min.cmple(root_bounds.min).all() && root_bounds.max.cmple(b.max).all();
        let leaves = children
            .iter()
            .map(|c| match c {
                CsgNode::Leaf { leaf, bounds } => {
                    Some((*leaf, (!holds_root(bounds)).then_some(*bounds)))
                }
                CsgNode::Op { .. } => None,
            })
            .collect::<Option<SmallVec<_>>>()?;
        let spheres = (leaves.len() <= LANES)
            .then(|| {
                leaves
                    .iter()
                    .map(|&(leaf, _)| sphere(leaf))
                    .collect::<Option<Vec<_>>>()
            })
            .flatten()
            .map(|s| SphereGroup::new(&s));
        fits.then_some(FlatCsg {
            op: *op,
            leaves,
            spheres,
        })
    }

    pub fn op(&self) -> CsgOp {
        self.op
    }

    /// The operands in the tree's order: leaf, and the box worth testing before it.
    pub fn operands(&self) -> &[(u32, Option<Aabb>)] {
        &self.leaves
    }

    /// Inside the result, given the inside flags of the operands (bit k: operand k).
    #[inline]
    fn keeps(&self, inside: u32) -> bool {
        match self.op {
            CsgOp::Union => inside != 0,
            CsgOp::Intersection => inside == (1 << self.leaves.len()) - 1,
            // A and not B.
            CsgOp::Difference => inside == 1,
            CsgOp::Complement => unreachable!("complements stay trees"),
        }
    }

    /// The first boundary of the result with r.t_min < t < r.t_max (finite). The caller has
    /// already tested the root's box (the object's box) when `r.use_bounds` is set. `work` is
    /// only added to when the answer is decided, so an `Undecided` evaluation can be redone by
    /// the segment lists without counting anything twice.
    ///
    /// Its pieces (the operands' spans, then the walk along the ends) are inlined into one
    /// function on purpose, so that the spans stay in registers.
    #[inline(always)]
    pub fn nearest<V: F64x4>(
        &self,
        env: &impl LeafSpans,
        r: &CsgRay,
        work: &mut CsgWork,
    ) -> Crossing {
        // Most CSG objects have two operands: their spans stay in registers (held in a list,
        // each was stored and at once read back, and the read stalled on store forwarding).
        if self.leaves.len() == 2 {
            return self.nearest_of_two::<V>(env, r, work);
        }
        let grouped = self.spheres.as_ref().map(|g| g.spans::<V>(r.ray));
        let mut spans: ArrayVec<Option<Span>, MAX_LEAVES> = ArrayVec::new();
        let mut done = CsgWork::default();
        // The intersection so far: [latest entry, earliest exit], empty once an operand is.
        let (mut latest_in, mut earliest_out) = (f64::NEG_INFINITY, f64::INFINITY);
        let mut empty = false;
        for k in 0..self.leaves.len() {
            let Ok(span) = self.operand_span(env, r, k, empty, &grouped, &mut done) else {
                return Crossing::Undecided;
            };
            // Emptiness as the segment lists see it: the first operand's list is empty only
            // without a span; ∩ with more operands is empty unless its entry precedes its exit.
            match span {
                None => empty = true,
                Some(s) => {
                    latest_in = latest_in.max(s.t_in);
                    earliest_out = earliest_out.min(s.t_out);
                    if k > 0 && latest_in >= earliest_out {
                        empty = true;
                    }
                }
            }
            spans.push(span);
        }

        // An end that is one with a bound of the window (`same_end`) belongs to a group of ends
        // the segment lists apply together whatever the window: they settle it.
        let at_bound = |e: f64| e.is_finite() && (same_end(e, r.t_min) || same_end(e, r.t_max));
        if spans
            .iter()
            .flatten()
            .any(|s| at_bound(s.t_in) || at_bound(s.t_out))
        {
            return Crossing::Undecided;
        }

        // The walk: inside flags just after t_min, and the span ends beyond it, in order.
        let mut inside = 0u32;
        let mut ends: ArrayVec<(f64, usize, bool), { 2 * MAX_LEAVES }> = ArrayVec::new();
        let within = |t: f64| t > r.t_min && t < r.t_max && t.is_finite();
        for (k, s) in spans.iter().enumerate() {
            let Some(s) = s else { continue };
            if s.t_in <= r.t_min && r.t_min < s.t_out {
                inside |= 1 << k;
            }
            if within(s.t_in) {
                ends.push((s.t_in, k, true));
            }
            if within(s.t_out) {
                ends.push((s.t_out, k, false));
            }
        }
        ends.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));

        let mut result = Crossing::Miss;
        let was = self.keeps(inside);
        let mut i = 0;
        while i < ends.len() {
            // Every end at this t, applied together.
            let t = ends[i].0;
            let first = i;
            let mut operands = 0u32;
            while i < ends.len() && same_end(ends[i].0, t) {
                let (_, k, entering) = ends[i];
                // Both ends of one operand here (a span of no thickness, a ray grazing a
                // rim): the order they are applied in decides, and the segment lists settle it.
                if operands & 1 << k != 0 {
                    return Crossing::Undecided;
                }
                operands |= 1 << k;
                if entering {
                    inside |= 1 << k;
                } else {
                    inside &= !(1 << k);
                }
                i += 1;
            }
            let now = self.keeps(inside);
            if now == was {
                continue;
            }
            if i - first > 1 {
                return Crossing::Undecided;
            }
            let (_, k, entering) = ends[first];
            let s = spans[k].expect("an end belongs to a span");
            let face = if entering { s.face_in } else { s.face_out };
            let surface = Surface::new(self.leaves[k].0, face as u32);
            // B's surfaces bound a difference from the other side.
            let carved = self.op == CsgOp::Difference && k > 0;
            result = Crossing::Hit(t, if carved { surface.flipped() } else { surface });
            break;
        }
        work.pruned += done.pruned;
        work.leaves_tested += done.leaves_tested;
        result
    }
}

impl FlatCsg {
    /// Operand k's span, through its box and the notes' pruning rule: once ∩'s operands so
    /// far, or −'s first one, are `empty`, so is the result, and the rest need not be looked
    /// at. Err: reversed ends, which only the segment lists' sweep understands.
    #[inline(always)]
    fn operand_span(
        &self,
        env: &impl LeafSpans,
        r: &CsgRay,
        k: usize,
        empty: bool,
        grouped: &Option<[Option<Span>; LANES]>,
        done: &mut CsgWork,
    ) -> Result<Option<Span>, ()> {
        let (leaf, bounds) = self.leaves[k];
        let prunes = matches!(self.op, CsgOp::Intersection | CsgOp::Difference);
        let missed = |b: Aabb| !b.hit(r.ray.origin, r.inv_dir, r.t_min, r.t_max);
        if (k > 0 && r.prune && prunes && empty) || (r.use_bounds && bounds.is_some_and(missed)) {
            done.pruned += 1;
            return Ok(None);
        }
        done.leaves_tested += 1;
        let span = match grouped {
            Some(spans) => spans[k],
            None => env.leaf_span(leaf, r.ray),
        };
        match span {
            // A span of NaN (overflow on absurd input) is no intersection.
            Some(s) if s.t_in.is_nan() || s.t_out.is_nan() => Ok(None),
            Some(s) if s.t_in > s.t_out => Err(()),
            s => Ok(s),
        }
    }

    /// `nearest` for two operands.
    #[inline(always)]
    fn nearest_of_two<V: F64x4>(
        &self,
        env: &impl LeafSpans,
        r: &CsgRay,
        work: &mut CsgWork,
    ) -> Crossing {
        // Two spheres' common part, searched from t = 0 on, is missed as soon as one sphere
        // is: passed by, or met only behind the origin (a ray leaving the lens outward). The
        // group says so before its square roots, and the count is the operands' own: the
        // second is pruned where the first has no span.
        let unboxed = !r.use_bounds || self.leaves.iter().all(|(_, bounds)| bounds.is_none());
        let common = self.op == CsgOp::Intersection && r.t_min >= 0.0 && unboxed;
        let grouped = match &self.spheres {
            Some(group) if common => match group.common_spans::<V>(r.ray) {
                Ok(spans) => Some(spans),
                Err(empty) => {
                    let pruned = (r.prune && empty & 1 != 0) as u64;
                    work.pruned += pruned;
                    work.leaves_tested += 2 - pruned;
                    return Crossing::Miss;
                }
            },
            Some(group) => Some(group.spans::<V>(r.ray)),
            None => None,
        };
        let mut done = CsgWork::default();
        let Ok(a) = self.operand_span(env, r, 0, false, &grouped, &mut done) else {
            return Crossing::Undecided;
        };
        let Ok(b) = self.operand_span(env, r, 1, a.is_none(), &grouped, &mut done) else {
            return Crossing::Undecided;
        };
        let result = self.first_change_of_two::<V>(a, b, r);
        if result != Crossing::Undecided {
            work.pruned += done.pruned;
            work.leaves_tested += done.leaves_tested;
        }
        result
    }

    /// The walk of `nearest` for two operands, with all four span ends looked at at
    /// once instead of sorted and visited in order (the commonest CSG object, and there the
    /// walk cost as much as both spans).
    ///
    /// An operand's inside flag just before an end t is t_in < t ≤ t_out, and just after it
    /// t_in ≤ t < t_out: the walk's flags once every end before t, or up to t, is applied (its
    /// ends at one t entering before leaving, so a span of zero length is never inside). So
    /// the result changes at an end exactly when the rule gives different answers for the two,
    /// and the first such end in the window is the walk's answer; several ends at that t are
    /// left to the segment lists, as the walk leaves them.
    #[inline(always)]
    fn first_change_of_two<V: F64x4>(
        &self,
        a: Option<Span>,
        b: Option<Span>,
        r: &CsgRay,
    ) -> Crossing {
        let ends = |s: Option<Span>| s.map_or((f64::NAN, f64::NAN), |s| (s.t_in, s.t_out));
        let ((a_in, a_out), (b_in, b_out)) = (ends(a), ends(b));
        // A span of no thickness in the window (a ray grazing a rim) is the segment lists' to
        // settle: the walk never sees it inside, the lists may keep it as a segment.
        let thin = |t_in: f64, t_out: f64| {
            same_end(t_in, t_out) && t_in > r.t_min && t_in < r.t_max && t_in.is_finite()
        };
        if thin(a_in, a_out) || thin(b_in, b_out) {
            return Crossing::Undecided;
        }
        let t = V::setr(a_in, a_out, b_in, b_out);
        let ((a_before, a_after), (b_before, b_after)) =
            (inside_bits(a_in, a_out, t), inside_bits(b_in, b_out, t));
        // The rule, lane by lane on the flags' bits.
        let rule = |a: u32, b: u32| match self.op {
            CsgOp::Union => a | b,
            CsgOp::Intersection => a & b,
            CsgOp::Difference => a & !b,
            CsgOp::Complement => unreachable!("complements stay trees"),
        };
        let within = (t.simd_gt(V::splat(r.t_min))
            & t.simd_lt(V::splat(r.t_max))
            & t.abs().simd_lt(V::splat(f64::INFINITY)))
        .to_bitmask();
        let changes = (rule(a_before, b_before) ^ rule(a_after, b_after)) & within;
        if changes == 0 {
            return Crossing::Miss;
        }
        let ts = t.to_array();
        let k = (0..4)
            .filter(|&k| changes & (1 << k) != 0)
            .min_by(|&i, &j| ts[i].total_cmp(&ts[j]))
            .expect("some end changes the result");
        // Another end that is one with it (`same_end`: a face shared by both operands, or a
        // span of no thickness) is applied with it by the segment lists, which settle it.
        let at_t = (0..4).filter(|&i| same_end(ts[i], ts[k])).count();
        if at_t > 1 {
            return Crossing::Undecided;
        }
        let (operand, entering) = (k / 2, k % 2 == 0);
        let s = if operand == 0 { a } else { b }.expect("an end belongs to a span");
        let face = if entering { s.face_in } else { s.face_out };
        let surface = Surface::new(self.leaves[operand].0, face as u32);
        // B's surfaces bound a difference from the other side.
        let carved = self.op == CsgOp::Difference && operand > 0;
        Crossing::Hit(ts[k], if carved { surface.flipped() } else { surface })
    }
}

/// The bits of the ends t at which a span is inside just before and just after them (the
/// walk's inside flags); a function rather than a closure, so that it is surely inlined into
/// the lanes' copy for the processor (`simd::with_lanes`).
#[inline(always)]
fn inside_bits<V: F64x4>(t_in: f64, t_out: f64, t: V) -> (u32, u32) {
    let (t_in, t_out) = (V::splat(t_in), V::splat(t_out));
    let before = t_in.simd_lt(t) & t.simd_le(t_out);
    let after = t_in.simd_le(t) & t.simd_lt(t_out);
    (before.to_bitmask(), after.to_bitmask())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::simd::Wide;
    use glam::DVec3;

    /// Spans given directly, per leaf.
    struct Fixed(Vec<Option<(f64, f64)>>);

    impl LeafSpans for Fixed {
        fn leaf_span(&self, leaf: u32, _: &Ray) -> Option<Span> {
            self.0[leaf as usize].map(|(a, b)| Span::new(a, 1, b, 2))
        }
    }

    fn flat(op: CsgOp, n: u32) -> FlatCsg {
        let everything = Aabb::everything();
        FlatCsg::new(
            &CsgNode::Op {
                op,
                name: "t".into(),
                children: (0..n)
                    .map(|leaf| CsgNode::Leaf {
                        leaf,
                        bounds: everything,
                    })
                    .collect(),
                bounds: everything,
            },
            |_| None,
        )
        .unwrap()
    }

    fn nearest(op: CsgOp, spans: &[Option<(f64, f64)>], t_min: f64) -> (Crossing, CsgWork) {
        let ray = Ray::raw(DVec3::ZERO, DVec3::X);
        let r = CsgRay {
            ray: &ray,
            inv_dir: ray.dir.recip(),
            t_min,
            t_max: f64::INFINITY,
            use_bounds: true,
            prune: true,
        };
        let mut work = CsgWork::default();
        let c = flat(op, spans.len() as u32).nearest::<Wide>(&Fixed(spans.to_vec()), &r, &mut work);
        (c, work)
    }

    #[test]
    fn seed_000_difference_is_entered_at_a_and_left_at_b() {
        // The notes' A = [13, 23], B = [16, 22]: A − B = [13, 16] ∪ [22, 23].
        let spans = [Some((13.0, 23.0)), Some((16.0, 22.0))];
        let hit = |t_min| nearest(CsgOp::Difference, &spans, t_min).0;
        assert_eq!(hit(0.0), Crossing::Hit(13.0, Surface::new(0, 1)));
        // From inside A − B the ray leaves through B's near wall, seen from the other side.
        assert_eq!(hit(14.0), Crossing::Hit(16.0, Surface::new(1, 1).flipped()));
        assert_eq!(hit(17.0), Crossing::Hit(22.0, Surface::new(1, 2).flipped()));
        assert_eq!(hit(22.5), Crossing::Hit(23.0, Surface::new(0, 2)));
        assert_eq!(hit(23.0), Crossing::Miss);
        // A ray starting on A's entry is inside A: it leaves through B's near wall.
        assert_eq!(hit(13.0), Crossing::Hit(16.0, Surface::new(1, 1).flipped()));
    }

    #[test]
    fn coinciding_ends_where_the_result_changes_are_left_to_the_sweep() {
        // Shared face: A ∪ B touching at 2 does not change there; ∩ of the same is empty.
        let touching = [Some((1.0, 2.0)), Some((2.0, 3.0))];
        assert_eq!(
            nearest(CsgOp::Union, &touching, 1.5).0,
            Crossing::Hit(3.0, Surface::new(1, 2))
        );
        assert_eq!(
            nearest(CsgOp::Intersection, &touching, 0.0).0,
            Crossing::Miss
        );
        // Equal spans: the rule changes where two ends coincide.
        let same = [Some((1.0, 2.0)), Some((1.0, 2.0))];
        assert_eq!(nearest(CsgOp::Union, &same, 0.0).0, Crossing::Undecided);
        // Reversed ends are not a span this path understands.
        assert_eq!(
            nearest(CsgOp::Union, &[Some((2.0, 1.0)), None], 0.0).0,
            Crossing::Undecided
        );
    }

    #[test]
    fn empty_operands_prune_the_rest_and_only_decided_answers_count() {
        let (c, work) = nearest(CsgOp::Intersection, &[None, Some((1.0, 2.0))], 0.0);
        assert_eq!((c, work.pruned, work.leaves_tested), (Crossing::Miss, 1, 1));
        // Disjoint operands of ∩: the third is pruned.
        let spans = [Some((1.0, 2.0)), Some((3.0, 4.0)), Some((0.0, 5.0))];
        let (c, work) = nearest(CsgOp::Intersection, &spans, 0.0);
        assert_eq!((c, work.pruned, work.leaves_tested), (Crossing::Miss, 1, 2));
        // Operands of ∩ that only touch leave nothing: the third is pruned.
        let spans = [Some((1.0, 2.0)), Some((2.0, 3.0)), Some((0.0, 5.0))];
        let (c, work) = nearest(CsgOp::Intersection, &spans, 0.0);
        assert_eq!((c, work.pruned, work.leaves_tested), (Crossing::Miss, 1, 2));
        let (c, work) = nearest(CsgOp::Union, &[Some((1.0, 2.0)), Some((1.0, 3.0))], 0.0);
        assert_eq!(
            (c, work.pruned, work.leaves_tested),
            (Crossing::Undecided, 0, 0)
        );
    }
}
