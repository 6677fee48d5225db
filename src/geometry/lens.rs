//! A lens, the common part of two spheres (A ∩ B), against four rays at once.
//!
//! The lens is the commonest CSG object, and in a scene with glass it is met by many rays:
//! the glass's own refraction and reflection rays bounce inside it. Ray by ray, each test is a
//! call into the CSG evaluation (`FlatCsg::nearest`). Here the same steps run for four rays
//! side by side in `f64x4` lanes, one ray per lane: both spheres' spans (`LaneQuadratic`, the
//! arithmetic of `Sphere::span` to the last bit), the early exits of the two spheres' common
//! part, and the walk along the four span ends that finds where "inside A and inside B" first
//! changes. Where that walk meets ends that coincide, or numbers that are not finite, the lane
//! is left `undecided`, for the ray-by-ray evaluation to settle as the segment lists do.

use glam::DVec3;
use wide::f64x4;

use super::sphere_group::LaneQuadratic;
use super::{lane_mask, RayLanes, Sphere};

/// Two spheres in world space whose common part is a CSG object.
#[derive(Clone, Debug)]
pub struct Lens {
    centres: [DVec3; 2],
    r2: [f64; 2],
}

/// What `Lens::hits` finds for four rays (bit i and lane i: ray i).
#[derive(Clone, Copy, Debug)]
pub struct LensHits {
    /// The rays that hit the lens within their window.
    pub hit: u32,
    /// Each hit's t.
    pub t: f64x4,
    /// The hits on B's surface (the others are on A's).
    pub on_b: u32,
    /// The rays to be evaluated one by one: coinciding span ends, or arithmetic that is not
    /// finite.
    pub undecided: u32,
    /// The rays whose evaluation prunes B, because A is missed: what `FlatCsg::nearest`
    /// counts in `CsgWork::pruned`.
    pub pruned: u32,
}

impl Lens {
    pub fn new(a: &Sphere, b: &Sphere) -> Lens {
        Lens {
            centres: [a.center, b.center],
            r2: [a.radius * a.radius, b.radius * b.radius],
        }
    }

    /// The nearest crossing of the lens's surface with 0 < t < t_max for each ray in `open`,
    /// exactly as `FlatCsg::nearest` finds it ray by ray (t_min = 0, the spheres' boxes not
    /// tested: they hold the lens's box), with `prune` the notes' pruning rule.
    #[inline(always)]
    pub fn hits(&self, rays: &RayLanes, open: u32, t_max: f64x4, prune: bool) -> LensHits {
        let none = LensHits {
            hit: 0,
            t: f64x4::splat(f64::NAN),
            on_b: 0,
            undecided: 0,
            pruned: 0,
        };
        let quadratic = |k: usize| {
            let centre = self.centres[k].to_array().map(f64x4::splat);
            LaneQuadratic::new(rays, centre, f64x4::splat(self.r2[k]))
        };
        let (a, b) = (quadratic(0), quadratic(1));
        let ((a_disc, a_no_root), (b_disc, b_no_root)) = (a.disc(), b.disc());
        let open_lanes = lane_mask(open);
        let finite = a.finite & b.finite;
        // The common part searched from t = 0 is missed as soon as one sphere is passed by,
        // has no root, or is met only behind the origin (`SphereGroup::common_spans`).
        let a_empty = a.passes | a_no_root;
        let missed = open_lanes & finite & (a_empty | b.passes | b_no_root | a.away | b.away);
        let pruned = if prune {
            (missed & a_empty).to_bitmask()
        } else {
            0
        };
        let rest = open_lanes & !missed;
        if rest.to_bitmask() == 0 {
            return LensHits { pruned, ..none };
        }
        let (a_in, a_out) = a.roots(a_disc);
        let (b_in, b_out) = b.roots(b_disc);
        // Both spans exist here; NaN ends or reversed ones are for the segment lists.
        let ordered = a_in.simd_le(a_out) & b_in.simd_le(b_out);
        let live = rest & finite & ordered;

        // The walk: at each end t, inside A and B just before and just after it (an end at
        // t enters before it leaves). The first end in the window where A ∩ B changes is the
        // hit; another end at the same t leaves the ray undecided, as `first_change_of_two`.
        let ends = [a_in, a_out, b_in, b_out];
        let inside = |t_in: f64x4, t_out: f64x4, t: f64x4| {
            let before = t_in.simd_lt(t) & t.simd_le(t_out);
            let after = t_in.simd_le(t) & t.simd_lt(t_out);
            (before, after)
        };
        let infinity = f64x4::splat(f64::INFINITY);
        let within =
            ends.map(|t| t.simd_gt(f64x4::ZERO) & t.simd_lt(t_max) & t.abs().simd_lt(infinity));
        let mut first = infinity;
        for (&t, &within) in ends.iter().zip(&within) {
            let (a_before, a_after) = inside(a_in, a_out, t);
            let (b_before, b_after) = inside(b_in, b_out, t);
            let changes = ((a_before & b_before) ^ (a_after & b_after)) & within;
            first = changes.bitselect(first.fast_min(t), first);
        }
        let at_first: [f64x4; 4] = std::array::from_fn(|k| within[k] & ends[k].simd_eq(first));
        let mut tie = f64x4::ZERO;
        for i in 0..4 {
            for j in i + 1..4 {
                tie |= at_first[i] & at_first[j];
            }
        }
        let found = live & first.simd_lt(infinity);
        let hit = (found & !tie).to_bitmask();
        LensHits {
            hit,
            t: first,
            on_b: ((at_first[2] | at_first[3]).to_bitmask()) & hit,
            undecided: (rest & !live).to_bitmask() | (found & tie).to_bitmask(),
            pruned,
        }
    }
}
