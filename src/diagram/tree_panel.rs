//! The right panel of the `raytree diagram` figure: the ray tree as a graph (laid out by
//! `graph.rs`), each node a box with its kind, what it reached and its intensity, each edge
//! labelled with its coefficient. A shadow ray's box is round, an untraced ray's dashed.

use glam::DVec2;
use svg::node::element::{Group, Rectangle};

use super::figure::Figure;
use super::graph::{layout, GraphNode};
use super::ink::{line, r, ray_color, text, text_width, INK};
use super::rays::SegKind;
use crate::trace::{RayKind, RayNode};

impl Figure<'_> {
    /// The ray tree as a graph in the rectangle at `origin` of `size`.
    pub(super) fn graph(&self, origin: DVec2, area: DVec2) -> Group {
        let size = area;
        let nodes = layout(self.tree, Some(self.scene));
        let mut g = Group::new().add(
            text(origin + DVec2::new(0.0, 12.0), "ray tree", 14.0, INK).set("font-weight", "bold"),
        );
        let cols = nodes.iter().map(|n| n.pos.x).fold(0.0, f64::max) + 1.0;
        let rows = nodes.iter().map(|n| n.pos.y).fold(0.0, f64::max) + 1.0;
        let top = origin.y + 30.0;
        let col_w = size.x / cols;
        let row_h = ((size.y - 30.0) / rows).min(110.0);
        let chars = nodes
            .iter()
            .map(|n| {
                node_lines(n)
                    .iter()
                    .map(|l| l.chars().count())
                    .max()
                    .unwrap_or(1)
            })
            .max()
            .unwrap_or(1) as f64;
        // Small enough that the widest node fits its column, and that a row holds a node's
        // three lines (3.75 em and 6 px of box) and, in the gap below, an edge's label.
        let font = (0.92 * col_w / (0.62 * chars))
            .min((row_h - 6.0) / 5.1)
            .clamp(6.0, 13.0);
        let box_w = |n: &GraphNode| {
            let c = node_lines(n)
                .iter()
                .map(|l| l.chars().count())
                .max()
                .unwrap_or(1) as f64;
            (c * 0.62 * font + 8.0).min(col_w * 0.98).max(font * 4.0)
        };
        // A short figure with a deep tree keeps a node's first lines, as many as a row holds;
        // one that cannot hold a line a row says so instead of drawing boxes over each other.
        let Some(kept) = (1..=3usize)
            .rev()
            .find(|&k| k as f64 * font * 1.25 + 6.0 <= row_h)
        else {
            return g
                .add(text(
                    origin + DVec2::new(0.0, 32.0),
                    &format!("{rows} levels: too deep"),
                    11.0,
                    INK,
                ))
                .add(text(
                    origin + DVec2::new(0.0, 46.0),
                    "for this height",
                    11.0,
                    INK,
                ));
        };
        let box_h = kept as f64 * font * 1.25 + 6.0;
        let centre = |n: &GraphNode| {
            DVec2::new(
                origin.x + (n.pos.x + 0.5) * col_w,
                top + n.pos.y * row_h + box_h / 2.0,
            )
        };
        // Edges first, under the boxes, with their coefficients.
        for n in &nodes {
            let Some(pi) = n.parent else { continue };
            let (a, b) = (centre(&nodes[pi]), centre(n));
            let (a, b) = (
                a + DVec2::new(0.0, box_h / 2.0),
                b - DVec2::new(0.0, box_h / 2.0),
            );
            let color = node_color(self.tree, n);
            g = g.add(line(a, b, &color, 1.4));
            if let Some(e) = &n.edge {
                // Centred in the gap between the boxes (a baseline 0.35 em below the middle).
                let size = font * 0.95;
                let mid = (a + b) / 2.0 + DVec2::new(3.0, 0.35 * size);
                // Kept inside the graph's right edge.
                let right = origin.x + area.x - text_width(e, size);
                let mid = DVec2::new(mid.x.min(right), mid.y);
                g = g.add(text(mid, e, size, "#444444"));
            }
        }
        for n in &nodes {
            let c = centre(n);
            let bw = box_w(n);
            let color = node_color(self.tree, n);
            let shadow = n.kind == RayKind::Shadow;
            let mut rect = Rectangle::new()
                .set("x", r(c.x - bw / 2.0))
                .set("y", r(c.y - box_h / 2.0))
                .set("width", r(bw))
                .set("height", r(box_h))
                .set("rx", if shadow { box_h / 2.0 } else { 5.0 })
                .set("fill", "white")
                .set("stroke", color.as_str())
                .set("stroke-width", if n.path.is_empty() { 2.5 } else { 1.6 });
            if n.untraced {
                rect = rect
                    .set("stroke-dasharray", "4 3")
                    .set("stroke-opacity", 0.6);
            }
            g = g.add(rect);
            // Where the box is narrower than a line (its column is), the line is cut.
            let most = ((bw - 4.0) / (0.62 * font)).floor().max(1.0) as usize;
            for (i, l) in node_lines(n).iter().take(kept).enumerate() {
                let y = c.y - box_h / 2.0 + 3.0 + font * (1.0 + 1.25 * i as f64);
                let l = if l.chars().count() > most {
                    l.chars().take(most - 1).chain(['…']).collect()
                } else {
                    l.clone()
                };
                let t = text(
                    DVec2::new(c.x, y),
                    &l,
                    font,
                    if i == 0 { color.as_str() } else { INK },
                )
                .set("text-anchor", "middle")
                .set("stroke-width", 0);
                g = g.add(if i == 0 {
                    t.set("font-weight", "bold")
                } else {
                    t
                });
            }
        }
        g
    }
}

/// A graph node's three lines: the kind, what it reached, the value.
fn node_lines(n: &GraphNode) -> [String; 3] {
    let (kind, to) = n
        .title
        .split_once(" → ")
        .map_or((n.title.clone(), String::new()), |(a, b)| {
            (a.to_string(), b.to_string())
        });
    [kind, format!("→ {to}"), n.value.clone()]
}

fn node_color(root: &RayNode, n: &GraphNode) -> String {
    ray_color(super::node_at(root, &n.path).map_or(SegKind::Missed, SegKind::of))
}
