//! The ray tree as a derivation: every node with its terms, then every node's intensity
//! collected from the leaves up. It is how a pixel's intensity is worked out by hand, and the
//! explanation of any question that has no derivation of its own.

use crate::trace::{text, RayNode};

/// The tree below `n`, then the sums from its leaves up to `n`.
pub(super) fn tree_explanation(n: &RayNode) -> Vec<String> {
    let mut out = vec!["the ray tree, each node with its terms:".to_string()];
    out.extend(text::tree(n).lines().map(str::to_string));
    out.push("collecting from the leaves up:".into());
    collect_lines(n, &mut out);
    out
}

/// Post-order: every node's intensity from its local term and its children's.
fn collect_lines(n: &RayNode, out: &mut Vec<String>) {
    for c in n.secondary() {
        collect_lines(c, out);
    }
    let label = format!("I({} depth {})", n.kind.name(), n.depth);
    if let Some((lobe, k)) = n.cone() {
        out.push(format!(
            "I({lobe} depth {}) = (I_1 + … + I_{k})/{k}, the mean of its sampled rays = {}",
            n.depth,
            text::color(n.color)
        ));
        return;
    }
    match (&n.local, n.terminated) {
        (Some(local), _) => {
            let mut terms = vec![text::color(local.total())];
            for c in n.secondary() {
                terms.push(format!(
                    "{}·{}",
                    text::num(c.coefficient),
                    text::color(c.color)
                ));
            }
            out.push(format!(
                "{label} = {} = {}",
                terms.join(" + "),
                text::color(n.color)
            ));
        }
        (None, Some(t)) => out.push(format!("{label} = {} ({})", text::color(n.color), t.name())),
        _ => {}
    }
}
