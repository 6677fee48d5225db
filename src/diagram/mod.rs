//! Ray diagrams: a pixel's rays drawn in the scene, as the lecture draws the ray tree (seed
//! 004: rays between surfaces, normals dashed, the light and the eye), beside its numbers.
//!
//! The geometry is here, once, for both places that draw it: the explorer's diagram pane
//! (braille on a ratatui canvas, `tui`) and the `raytree diagram` figure (SVG and PNG, this
//! module's `figure.rs`, with `section.rs`, `tree_panel.rs`, `labels.rs` and `ink.rs`, and
//! `raster.rs`). `view.rs` is the orthographic projection,
//! `frame.rs` the part of the plane shown, `rays.rs` the tree's rays as segments,
//! `outline.rs` the objects' outlines, `drawing.rs` all of it together; `graph.rs` lays the
//! tree out as a graph (the figure, `dot.rs` for Graphviz) and `marks.rs` finds where the
//! rays' hit points appear in the picture.

pub mod dot;
pub mod drawing;
pub mod figure;
pub mod frame;
pub mod graph;
mod ink;
mod labels;
pub mod marks;
pub mod outline;
pub mod raster;
pub mod rays;
mod section;
mod tree_panel;
pub mod view;

pub use drawing::Drawing;
pub use frame::Frame;
pub use rays::{SegKind, Segment};
pub use view::{View, ViewChoice};

use crate::trace::RayNode;

/// The node at a path of child indices (the root at []).
pub fn node_at<'a>(root: &'a RayNode, path: &[usize]) -> Option<&'a RayNode> {
    let mut node = root;
    for &i in path {
        node = node.children.get(i)?;
    }
    Some(node)
}
