//! Segment lists: the parts of a ray that lie inside a solid.
//!
//! The lecture notes' CSG works on these: a ray starting outside a solid crosses its surface an
//! even number of times, and each pair (entry, exit) is one segment. Every end remembers which
//! surface it lies on, so that CSG results can still be shaded.

use smallvec::SmallVec;

/// Which surface of which primitive a segment end lies on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Surface {
    /// Index of the primitive ("leaf") in the compiled scene.
    pub leaf: u32,
    /// Face of the primitive (a box has six, a cylinder three, ...), or triangle of a mesh.
    pub face: u32,
    /// True when the surface is seen from its inside as the boundary of the result, e.g. the
    /// carved-out wall of a difference: its outward normal must be reversed.
    pub flip: bool,
}

impl Surface {
    /// The surface of face `face` of leaf `leaf`, normal as the primitive has it.
    pub fn new(leaf: u32, face: u32) -> Surface {
        Surface {
            leaf,
            face,
            flip: false,
        }
    }
    /// The same surface with its normal reversed (what a difference or complement does to B's
    /// boundary).
    pub fn flipped(self) -> Surface {
        Surface {
            flip: !self.flip,
            ..self
        }
    }
}

/// One inside interval `[t_in, t_out]` of a ray. Ends may be infinite (half-spaces).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// Where the ray enters the solid (may be −∞).
    pub t_in: f64,
    /// Where the ray leaves the solid (may be +∞).
    pub t_out: f64,
    /// The surface crossed at `t_in`.
    pub enter: Surface,
    /// The surface crossed at `t_out`.
    pub exit: Surface,
}

/// Ordered, non-overlapping segments along a ray. Most lists hold one or two segments, so two
/// live inline (larger inline lists cost more in copies than they save in allocations).
pub type SegmentList = SmallVec<[Segment; 2]>;

/// The nearest surface crossing strictly after `t_min`: the first segment end past it.
pub fn first_crossing(list: &[Segment], t_min: f64) -> Option<(f64, Surface)> {
    for s in list {
        if s.t_in > t_min && s.t_in.is_finite() {
            return Some((s.t_in, s.enter));
        }
        if s.t_out > t_min && s.t_out.is_finite() {
            return Some((s.t_out, s.exit));
        }
    }
    None
}
