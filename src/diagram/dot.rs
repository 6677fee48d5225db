//! The ray tree as Graphviz (`raytree inspect … --format dot`): one node per ray, labelled with
//! its kind, the object it hit and its intensity; edges labelled with the coefficient the
//! child is weighted with. `dot -Tsvg` draws it.

use super::graph::layout;
use super::rays::SegKind;
use crate::scene::Scene;
use crate::trace::{RayKind, RayNode};

/// The DOT text of a tree; `title` names it (the pixel or the ray).
pub fn dot(root: &RayNode, scene: Option<&Scene>, title: &str) -> String {
    let nodes = layout(root, scene);
    let mut out = String::new();
    out.push_str("digraph ray_tree {\n");
    out.push_str(&format!("  label={};\n  labelloc=t;\n", quote(title)));
    out.push_str("  node [shape=box, style=\"rounded\", fontname=\"Helvetica\"];\n");
    out.push_str("  edge [fontname=\"Helvetica\", fontsize=10];\n");
    for (i, n) in nodes.iter().enumerate() {
        let node = super::node_at(root, &n.path);
        let color = hex(node.map_or(SegKind::Missed, SegKind::of).rgb());
        let style = if n.untraced {
            ", style=\"rounded,dashed\""
        } else {
            ""
        };
        let shape = if n.kind == RayKind::Shadow {
            ", shape=ellipse"
        } else {
            ""
        };
        out.push_str(&format!(
            "  n{i} [label={}, color=\"{color}\"{shape}{style}];\n",
            quote(&format!("{}\n{}", n.title, n.value))
        ));
    }
    for (i, n) in nodes.iter().enumerate() {
        if let Some(p) = n.parent {
            let label = n.edge.as_deref().unwrap_or("");
            out.push_str(&format!("  n{p} -> n{i} [label={}];\n", quote(label)));
        }
    }
    out.push_str("}\n");
    out
}

fn hex([r, g, b]: [u8; 3]) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// A DOT string: quotes and backslashes escaped, newlines as \n.
fn quote(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}
