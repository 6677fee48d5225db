//! The ray tree as the tree panel sees it: nodes named by their path of child indices, which
//! nodes are open, and the visible rows with their guide lines.

use std::collections::HashSet;

use crate::trace::{RayKind, RayNode};

/// A node's place in the tree: the child index at every level below the root (root = []).
pub type NodePath = Vec<usize>;

/// One visible line of the tree panel.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Row {
    pub path: NodePath,
    /// Guide lines drawn before the node ("│  ├─ ").
    pub guides: String,
    pub has_children: bool,
    pub open: bool,
}

/// The node at a path.
pub fn node_at<'a>(root: &'a RayNode, path: &[usize]) -> Option<&'a RayNode> {
    let mut node = root;
    for &i in path {
        node = node.children.get(i)?;
    }
    Some(node)
}

/// The longest prefix of `path` that names a node of this tree.
pub fn valid_prefix(root: &RayNode, path: &[usize]) -> NodePath {
    let mut node = root;
    let mut out = Vec::new();
    for &i in path {
        match node.children.get(i) {
            Some(c) => {
                out.push(i);
                node = c;
            }
            None => break,
        }
    }
    out
}

/// The path of the node reached by following child kinds ("reflection/refraction").
pub fn path_of_kinds(root: &RayNode, kinds: &str) -> Option<NodePath> {
    let mut node = root;
    let mut path = Vec::new();
    for step in kinds.split('/').filter(|s| !s.is_empty()) {
        let i = node.children.iter().position(|c| c.kind.name() == step)?;
        path.push(i);
        node = &node.children[i];
    }
    Some(path)
}

/// The kinds along a path ("reflection/refraction"; "" for the root).
pub fn kinds_of_path(root: &RayNode, path: &[usize]) -> String {
    let mut node = root;
    let mut parts = Vec::new();
    for &i in path {
        match node.children.get(i) {
            Some(c) => {
                parts.push(c.kind.name());
                node = c;
            }
            None => break,
        }
    }
    parts.join("/")
}

/// Every node that has children.
pub fn all_parents(root: &RayNode) -> HashSet<NodePath> {
    let mut out = HashSet::new();
    fn walk(n: &RayNode, path: &mut NodePath, out: &mut HashSet<NodePath>) {
        if n.children.is_empty() {
            return;
        }
        out.insert(path.clone());
        for (i, c) in n.children.iter().enumerate() {
            path.push(i);
            walk(c, path, out);
            path.pop();
        }
    }
    walk(root, &mut Vec::new(), &mut out);
    out
}

/// Parents whose depth in the tree (path length) is below `levels`.
pub fn parents_above(root: &RayNode, levels: usize) -> HashSet<NodePath> {
    all_parents(root)
        .into_iter()
        .filter(|p| p.len() < levels)
        .collect()
}

/// What is open when a tree is first shown: everything for a small tree, else the first
/// levels; the sampled rays of a glossy or frosted cone stay folded under their mean.
pub fn default_open(root: &RayNode) -> HashSet<NodePath> {
    let open = if root.size() <= 64 {
        all_parents(root)
    } else {
        parents_above(root, 2)
    };
    open.into_iter()
        .filter(|p| node_at(root, p).is_some_and(|n| n.samples.is_none()))
        .collect()
}

/// The rows a tree shows with these nodes open, in display order.
pub fn visible_rows(root: &RayNode, open: &HashSet<NodePath>) -> Vec<Row> {
    let mut rows = Vec::new();
    fn walk(
        n: &RayNode,
        path: &mut NodePath,
        lead: &str,
        own: &str,
        open: &HashSet<NodePath>,
        rows: &mut Vec<Row>,
    ) {
        let is_open = !n.children.is_empty() && open.contains(path);
        rows.push(Row {
            path: path.clone(),
            guides: format!("{lead}{own}"),
            has_children: !n.children.is_empty(),
            open: is_open,
        });
        if !is_open {
            return;
        }
        let below = match own {
            "" => String::new(),
            "└─" => format!("{lead}  "),
            _ => format!("{lead}│ "),
        };
        for (i, c) in n.children.iter().enumerate() {
            let last = i + 1 == n.children.len();
            path.push(i);
            walk(c, path, &below, if last { "└─" } else { "├─" }, open, rows);
            path.pop();
        }
    }
    walk(root, &mut Vec::new(), "", "", open, &mut rows);
    rows
}

/// A short number for tree lines: at most four decimals, trailing zeros dropped.
pub fn short(x: f64) -> String {
    if !x.is_finite() {
        return crate::trace::text::num(x);
    }
    let s = format!("{x:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

/// A colour for tree lines: one number when grey (four decimals), else three decimals each.
pub fn short_color(c: glam::DVec3) -> String {
    if c.x == c.y && c.y == c.z {
        short(c.x)
    } else {
        let s3 = |x: f64| {
            let s = format!("{x:.3}");
            let s = s.trim_end_matches('0').trim_end_matches('.');
            if s == "-0" {
                "0".to_string()
            } else {
                s.to_string()
            }
        };
        format!("({}, {}, {})", s3(c.x), s3(c.y), s3(c.z))
    }
}

/// What a ray did, in a few words: the object it hit, or why it stopped.
pub fn outcome(n: &RayNode) -> String {
    use crate::trace::Termination as T;
    if n.kind == RayKind::Shadow {
        // A soft shadow's blocker is named in the details: the line stays short.
        return match (n.shadow_rays, &n.hit) {
            (Some(rays), Some(_)) if n.shadow.unwrap_or(0.0) > 0.0 => format!(
                "partly blocked ({} of {rays} clear)",
                (n.shadow.unwrap_or(0.0) * rays as f64).round()
            ),
            _ => crate::trace::text::shadow_outcome(n),
        };
    }
    match (n.terminated, &n.hit) {
        (Some(T::Background), _) => "background".into(),
        (Some(T::MaxDepth), _) => "not traced: max depth".into(),
        (Some(T::Adaptive), _) => "not traced: adaptive cut-off".into(),
        (Some(T::TotalInternalReflection), _) if n.children.is_empty() => {
            "total internal reflection, along the reflection ray".into()
        }
        (Some(T::TotalInternalReflection), _) => "total internal reflection".into(),
        (Some(T::Light), _) => format!("light {}", n.light.as_deref().unwrap_or("?")),
        (Some(T::Diffuse), Some(h)) => format!("hit {} (diffuse: stops)", h.object),
        (Some(T::Diffuse), None) => "diffuse: stops".into(),
        (None, Some(h)) => format!("hit {}", h.object),
        (None, None) => "no hit".into(),
    }
}

/// The text of a tree line without the intensity: "reflection: hit b".
pub fn label(n: &RayNode) -> String {
    if let Some((lobe, k)) = n.cone() {
        return format!("{lobe}: mean of {k} rays");
    }
    match n.kind {
        RayKind::Shadow => format!(
            "shadow → {}: {}, s = {}",
            n.light.as_deref().unwrap_or("?"),
            outcome(n),
            short(n.shadow.unwrap_or(0.0))
        ),
        k => format!("{}: {}", k.name(), outcome(n)),
    }
}

/// The intensity shown after a ray's label ("  I = 0.462 "); none for a shadow ray.
pub fn intensity_text(n: &RayNode) -> Option<String> {
    (n.kind != RayKind::Shadow).then(|| format!("  I = {} ", short_color(n.color)))
}

/// The nodes that are rays with an intensity of their own (not shadow rays), in display order.
pub fn ray_paths(root: &RayNode) -> Vec<NodePath> {
    let mut out = Vec::new();
    fn walk(n: &RayNode, path: &mut NodePath, out: &mut Vec<NodePath>) {
        if n.kind != RayKind::Shadow {
            out.push(path.clone());
        }
        for (i, c) in n.children.iter().enumerate() {
            path.push(i);
            walk(c, path, out);
            path.pop();
        }
    }
    walk(root, &mut Vec::new(), &mut out);
    out
}
