//! The ray tree as a graph, the way the lecture draws it beside the rays: one node per ray
//! (its kind, the object it hit, its intensity), an edge from each ray to the rays it spawned,
//! labelled by the coefficient the child is weighted with (kr, kt, the shadow factor s).
//! Laid out as a tidy tree: the root on top, each level of recursion one row lower, leaves
//! side by side and each parent centred over its children.

use glam::DVec2;

use super::rays::{short, short_color};
use crate::scene::Scene;
use crate::shading::Fresnel;
use crate::trace::{RayKind, RayNode, Termination};

/// A node of the graph, placed.
#[derive(Clone, Debug, PartialEq)]
pub struct GraphNode {
    /// The node's place in the tree: child indices from the root.
    pub path: Vec<usize>,
    /// Primary, shadow, reflection or refraction.
    pub kind: RayKind,
    /// Its column (leaves are 0, 1, 2, … from the left; a parent sits over its children) and
    /// row (the level of recursion of its parent's children: depth, shadow rays one below
    /// their parent).
    pub pos: DVec2,
    /// The index of its parent in the list.
    pub parent: Option<usize>,
    /// "reflection → b", "shadow → L".
    pub title: String,
    /// "I = 0.462", "lit, s = 1", "blocked by a".
    pub value: String,
    /// The edge from its parent: "kr = 0.3", "kt = 0.3", "s = 1".
    pub edge: Option<String>,
    /// Not traced (max depth, adaptive, total internal reflection): drawn faint.
    pub untraced: bool,
}

/// The graph of a tree, nodes in depth-first order (a parent before its children).
pub fn layout(root: &RayNode, scene: Option<&Scene>) -> Vec<GraphNode> {
    let mut out = vec![];
    let mut next_leaf = 0.0;
    place(
        root,
        None,
        None,
        scene,
        &mut vec![],
        0,
        &mut next_leaf,
        &mut out,
    );
    out
}

#[allow(clippy::too_many_arguments)]
fn place(
    n: &RayNode,
    parent_node: Option<&RayNode>,
    parent: Option<usize>,
    scene: Option<&Scene>,
    path: &mut Vec<usize>,
    row: u32,
    next_leaf: &mut f64,
    out: &mut Vec<GraphNode>,
) -> f64 {
    let index = out.len();
    out.push(GraphNode {
        path: path.clone(),
        kind: n.kind,
        pos: DVec2::ZERO,
        parent,
        title: title(n),
        value: value(n),
        edge: parent_node.and_then(|p| edge(p, n, scene)),
        untraced: matches!(
            n.terminated,
            Some(
                Termination::MaxDepth
                    | Termination::Adaptive
                    | Termination::TotalInternalReflection
            )
        ),
    });
    let x = if n.children.is_empty() {
        let x = *next_leaf;
        *next_leaf += 1.0;
        x
    } else {
        let mut xs = vec![];
        for (i, c) in n.children.iter().enumerate() {
            path.push(i);
            xs.push(place(
                c,
                Some(n),
                Some(index),
                scene,
                path,
                row + 1,
                next_leaf,
                out,
            ));
            path.pop();
        }
        0.5 * (xs[0] + xs[xs.len() - 1])
    };
    out[index].pos = DVec2::new(x, row as f64);
    x
}

/// "primary → a", "reflection → background", "shadow → L".
pub fn title(n: &RayNode) -> String {
    match n.kind {
        RayKind::Shadow => format!("shadow → {}", n.light.as_deref().unwrap_or("?")),
        k => {
            let to = match (&n.hit, n.terminated) {
                (Some(h), _) => h.object.clone(),
                (None, Some(Termination::Background)) | (None, None) => "background".into(),
                (None, Some(_)) => "not traced".into(),
            };
            format!("{} → {to}", k.name())
        }
    }
}

/// "I = 0.462" for a ray, "lit, s = 1" or "blocked by a" for a shadow ray, why a ray was not
/// traced.
pub fn value(n: &RayNode) -> String {
    match (n.kind, &n.hit, n.terminated) {
        (RayKind::Shadow, Some(h), _) => format!("blocked by {}", h.object),
        (RayKind::Shadow, None, _) => format!("lit, s = {}", short(n.shadow.unwrap_or(1.0))),
        (_, None, Some(Termination::MaxDepth)) => "(max depth)".into(),
        (_, None, Some(Termination::Adaptive)) => "(adaptive cut-off)".into(),
        (_, None, Some(Termination::TotalInternalReflection)) => {
            "(total internal reflection)".into()
        }
        _ => format!("I = {}", short_color(n.color)),
    }
}

/// The coefficient a child is weighted with in its parent, named as in the formula.
pub fn edge(parent: &RayNode, child: &RayNode, scene: Option<&Scene>) -> Option<String> {
    let fresnel = scene
        .zip(parent.hit.as_ref())
        .and_then(|(s, h)| s.materials.iter().find(|m| m.name == h.material))
        .is_some_and(|m| m.fresnel == Fresnel::Schlick);
    let c = short(child.coefficient);
    Some(match child.kind {
        RayKind::Primary => return None,
        RayKind::Shadow => format!("s = {}", short(child.shadow.unwrap_or(0.0))),
        _ if parent.samples.is_some() => format!("1/{}", parent.samples.unwrap_or(1)),
        RayKind::Reflection if fresnel => format!("kr·R = {c}"),
        RayKind::Reflection => format!("kr = {c}"),
        RayKind::Refraction if fresnel => format!("kt·(1−R) = {c}"),
        RayKind::Refraction => format!("kt = {c}"),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn leaves_side_by_side_and_parents_over_their_children() {
        let path = std::path::Path::new("lessons/08-pixel-intensity/scene.yaml");
        let scene = crate::scene::load(path, &Default::default()).unwrap();
        let ray = scene.camera.pixel_ray(30, 30);
        let tree = crate::trace::Tracer::new(&scene).inspect(&ray);
        let g = layout(&tree, Some(&scene));
        assert_eq!(g.len(), tree.size());
        for n in &g {
            let kids: Vec<&GraphNode> = g
                .iter()
                .filter(|c| c.parent == Some(g.iter().position(|m| m == n).unwrap()))
                .collect();
            if kids.is_empty() {
                assert_eq!(n.pos.x.fract(), 0.0, "a leaf sits in a column of its own");
            } else {
                let mid = 0.5 * (kids[0].pos.x + kids[kids.len() - 1].pos.x);
                assert_eq!(n.pos.x, mid);
                assert!(kids.iter().all(|c| c.pos.y == n.pos.y + 1.0));
            }
        }
        // The sheet a: kr = kt = 0.3, as the exercise gives them.
        let edges: Vec<&str> = g.iter().filter_map(|n| n.edge.as_deref()).collect();
        assert!(
            edges.contains(&"kr = 0.3") && edges.contains(&"kt = 0.3"),
            "{edges:?}"
        );
    }
}
