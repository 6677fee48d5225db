//! The ray tree as a derivation: every node with its terms, then every node's intensity
//! collected from the leaves up. It is how a pixel's intensity is worked out by hand, and the
//! explanation of any question that has no derivation of its own.

use crate::trace::{text, RayKind, RayNode, Termination};

/// The tree below `n`, then the sums from its leaves up to `n`.
pub(super) fn tree_explanation(n: &RayNode) -> Vec<String> {
    let mut out = vec!["the ray tree, each node with its terms:".to_string()];
    out.extend(text::tree(n).lines().map(str::to_string));
    out.push("collecting from the leaves up:".into());
    collect_lines(n, &root_name(n), &mut out);
    out
}

/// A tree's root named by the surface its ray hits.
pub(super) fn root_name(n: &RayNode) -> String {
    step_name(n)
}

/// What a ray meets, as one step of a node's name: the object it hits, or why it has none.
fn step_name(n: &RayNode) -> String {
    if let Some((lobe, _)) = n.cone() {
        return lobe.into();
    }
    match (&n.hit, n.terminated) {
        (Some(h), _) => h.object.clone(),
        (None, Some(Termination::MaxDepth | Termination::Adaptive)) => "not traced".into(),
        (None, Some(Termination::TotalInternalReflection)) => "total internal reflection".into(),
        (None, Some(Termination::Light)) => format!("light {}", n.light.as_deref().unwrap_or("?")),
        (None, _) => "background".into(),
    }
}

/// The names of a node's reflection and refraction rays: its own name and the step each takes
/// (`a → b`), with the kind of ray added where two would read the same.
pub(super) fn child_names(n: &RayNode, name: &str) -> Vec<String> {
    let steps: Vec<String> = n.secondary().map(step_name).collect();
    n.secondary()
        .zip(&steps)
        .map(|(c, step)| {
            if steps.iter().filter(|s| *s == step).count() > 1 {
                format!("{name} → {step} ({})", c.kind.name())
            } else {
                format!("{name} → {step}")
            }
        })
        .collect()
}

/// Steps a node's name shows in full; a deeper node shows its first and last two.
const STEPS_SHOWN: usize = 6;

/// A node's name as printed: long paths shortened to their ends and the node's depth
/// (`mirror → ball → … → ball → mirror, depth 10`).
pub(super) fn short(name: &str) -> String {
    let steps: Vec<&str> = name.split(" → ").collect();
    if steps.len() <= STEPS_SHOWN {
        return name.to_string();
    }
    let n = steps.len();
    format!(
        "{} → {} → … → {} → {}, depth {}",
        steps[0],
        steps[1],
        steps[n - 2],
        steps[n - 1],
        n - 1
    )
}

/// Post-order: every node's intensity from its local term and its children's.
pub(super) fn collect_lines(n: &RayNode, name: &str, out: &mut Vec<String>) {
    let names = child_names(n, name);
    if n.cone().is_none() {
        for (c, child) in n.secondary().zip(&names) {
            collect_lines(c, child, out);
        }
    }
    let label = format!("I({})", short(name));
    if let Some((_, k)) = n.cone() {
        out.push(format!(
            "{label} = (I_1 + … + I_{k})/{k}, the mean of its sampled rays = {}",
            text::color(n.color)
        ));
        return;
    }
    match (&n.local, n.terminated) {
        (Some(local), _) => {
            let mut symbols = vec![format!("I_local({})", short(name))];
            let mut terms = vec![text::color(local.total())];
            for (c, child) in n.secondary().zip(&names) {
                let k = if c.kind == RayKind::Reflection {
                    "kr"
                } else {
                    "kt"
                };
                match c.attenuation {
                    None => {
                        symbols.push(format!("{k}·I({})", short(child)));
                        terms.push(format!(
                            "{}·{}",
                            text::num(c.coefficient),
                            text::color(c.color)
                        ));
                    }
                    Some(a) => {
                        let d = c.hit.as_ref().map_or(f64::NAN, |h| h.t);
                        symbols.push(format!("{k}·I({})/a(d = {})", short(child), text::num(d)));
                        terms.push(format!(
                            "{}·{}/{}",
                            text::num(c.coefficient),
                            text::color(c.color),
                            text::num(a)
                        ));
                    }
                }
            }
            if symbols.len() == 1 {
                out.push(format!("{label} = I_local = {}", text::color(n.color)));
            } else {
                out.push(format!(
                    "{label} = {} = {} = {}",
                    symbols.join(" + "),
                    terms.join(" + "),
                    text::color(n.color)
                ));
            }
        }
        (None, Some(t)) => out.push(format!("{label} = {} ({})", text::color(n.color), t.name())),
        _ => {}
    }
}
