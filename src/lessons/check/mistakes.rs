//! The mistakes students make when they collect a ray tree by hand, each as the answer it
//! gives: a term of the model left out or changed, the tree cut one level off, kt applied once
//! instead of at each surface, glass letting shadow rays through.
//!
//! A mistake is computed in one of two ways. Most trace the exercise again with the mistake
//! built in: a changed copy of the scene (no ambient term, fatt = 1, kt = 0, the other
//! highlight model) or other options (no shadow rays, another depth). Two cannot be built into
//! a scene, so they collect the traced tree again with the mistaken rule: the tree's own
//! numbers, summed from the leaves up as the student sums them.

use glam::DVec3;

use super::{answer, trace, Mistake, Worked};
use crate::lessons::{Answer, Exercise};
use crate::scene::Scene;
use crate::shading::{Highlight, LightKind};
use crate::trace::{text, RayKind, RayNode, TraceOptions};

/// A secondary ray's intensity already multiplied by its coefficient (kr or kt): what its
/// parent adds, where the exercise asks what the ray brings back.
fn weighted_by_parent(w: &Worked, ex: &Exercise) -> (Option<Answer>, String) {
    let node = (!ex.node.is_empty())
        .then(|| w.tree.find(&ex.node))
        .flatten()
        .filter(|n| matches!(n.kind, RayKind::Reflection | RayKind::Refraction));
    let answer = node
        .filter(|n| n.coefficient != 1.0)
        .and_then(|n| match &w.expected {
            Answer::Number(x) => Some(Answer::Number(x * n.coefficient)),
            Answer::Vector(v) => Some(Answer::Vector(*v * n.coefficient)),
            _ => None,
        });
    let name = match node.map(|n| n.kind) {
        Some(RayKind::Refraction) => "kt",
        _ => "kr",
    };
    (
        answer,
        format!("that is the ray's intensity times {name}, what its parent adds: the question asks what the ray itself brings back, before its parent weights it"),
    )
}

/// Every mistake in the order the hints are tried: the more specific first (glass blocking a
/// shadow ray is a case of leaving out the shadow term, and is named as such when it is).
pub(super) fn tree_mistakes(w: &Worked, ex: &Exercise) -> Vec<Mistake> {
    let full = TraceOptions {
        max_depth: w.depth,
        ..TraceOptions::of(&w.scene)
    };
    let no_shadows = TraceOptions {
        shadows: false,
        ..full
    };
    let highlight = used_highlight(w, ex).name();
    let other = other(used_highlight(w, ex)).name();
    let mut tries: Vec<(Option<Answer>, String)> = vec![
        (
            glass_lets_light_through(w, ex),
            "glass casts shadows too: in Whitted's model a shadow ray that meets any object, a transparent one included, is blocked (s = 0)".into(),
        ),
        (retrace(w, ex, &w.scene, no_shadows), shadow_hint(w, ex)),
        (
            retrace(w, ex, &other_highlight(&w.scene), full),
            format!("the highlight here is {highlight}; you used {other}"),
        ),
        (
            retrace(w, ex, &without_ambient(&w.scene), full),
            "you ignored the ambient term ka·Ia·O".into(),
        ),
        (
            retrace(w, ex, &unattenuated(&w.scene), full),
            "you left out the distance attenuation fatt = 1/(c0 + c1·d + c2·d²)".into(),
        ),
    ];
    // The node's local term alone: the tree cut just below the node (the primary ray is
    // depth 1 of max_depth).
    let below_node = ex.node.split('/').filter(|step| !step.is_empty()).count() as u32 + 1;
    if w.depth > below_node {
        let local_only = TraceOptions {
            max_depth: below_node,
            ..full
        };
        tries.push((
            retrace(w, ex, &w.scene, local_only),
            "you stopped at the local term: add kr·I_r and kt·I_t from the secondary rays".into(),
        ));
    }
    tries.push((
        retrace(w, ex, &opaque(&w.scene), full),
        "you dropped the transmitted term kt·I_t".into(),
    ));
    tries.push((
        kt_once(w, ex),
        "kt weights the ray at every surface it passes: entering the glass and leaving it each multiply by kt (kt² through a slab)".into(),
    ));
    tries.push(weighted_by_parent(w, ex));
    let d = w.depth;
    let bounces = if d == 2 {
        "1 bounce".to_string()
    } else {
        format!("{} bounces", d - 1)
    };
    if d > 1 {
        tries.push((
            retrace(w, ex, &w.scene, TraceOptions { max_depth: d - 1, ..full }),
            format!("max_depth counts the rays on a path, the primary ray included: max_depth {d} traces {d} rays on a path ({bounces}); you cut the tree one level short"),
        ));
    }
    if d < 64 {
        tries.push((
            retrace(w, ex, &w.scene, TraceOptions { max_depth: d + 1, ..full }),
            format!("max_depth counts the rays on a path, the primary ray included: max_depth {d} traces {d} rays on a path ({bounces}); you went one level deeper"),
        ));
    }
    tries
        .into_iter()
        .filter_map(|(a, hint)| Some(Mistake { answer: a?, hint }))
        .collect()
}

/// What the shadow term is where the student left it out: each light's s at the exercise's
/// node where one is under 1 there (a fraction for a light sampled by several shadow rays),
/// else that a shadow ray further down the tree is blocked.
fn shadow_hint(w: &Worked, ex: &Exercise) -> String {
    // Where s itself is asked, its value is the answer: the hint names the mistake only.
    if ex.ask == crate::lessons::Ask::ShadowFactor {
        return "s = 1 would mean every shadow ray reaches the light: count the ones an object \
                stops on their way"
            .into();
    }
    let shaded = (w.tree.find(&ex.node).and_then(|n| n.local.as_ref()))
        .map(|local| {
            (local.lights.iter())
                .filter(|term| term.shadow < 1.0)
                .map(|term| format!("s = {} for {}", text::num(term.shadow), term.light))
                .collect::<Vec<_>>()
        })
        .unwrap_or_default();
    if shaded.is_empty() {
        return "you left out the shadow term: a shadow ray further down the tree is blocked, \
                and that light's terms there are multiplied by its shadow factor s"
            .into();
    }
    format!(
        "you left out the shadow term: here {} (s is the fraction of a light's shadow rays \
         that reach it: 0 or 1 for one ray), and the light's terms are multiplied by it",
        shaded.join(", ")
    )
}

/// The highlight model the exercise is worked in: the one it states, or the one of the
/// surface the node's ray hits (Blinn when it hits nothing).
pub(super) fn used_highlight(w: &Worked, ex: &Exercise) -> Highlight {
    if let Some(m) = ex.model {
        return m;
    }
    w.tree
        .find(&ex.node)
        .and_then(|n| n.hit.as_ref())
        .and_then(|h| w.scene.materials.iter().find(|m| m.name == h.material))
        .map_or(Highlight::Blinn, |m| m.highlight)
}

fn other(h: Highlight) -> Highlight {
    match h {
        Highlight::Blinn => Highlight::Phong,
        Highlight::Phong => Highlight::Blinn,
    }
}

fn retrace(w: &Worked, ex: &Exercise, scene: &Scene, options: TraceOptions) -> Option<Answer> {
    answer(scene, &w.ray, &trace(scene, &w.ray, options), ex).ok()
}

/// Every material with Phong highlights where it has Blinn, and Blinn where it has Phong.
fn other_highlight(scene: &Scene) -> Scene {
    let mut swapped = scene.clone();
    for m in &mut swapped.materials {
        m.highlight = other(m.highlight);
    }
    swapped
}

fn without_ambient(scene: &Scene) -> Scene {
    let mut dark = scene.clone();
    dark.ambient = DVec3::ZERO;
    dark
}

/// Every point light with fatt = 1 at any distance.
fn unattenuated(scene: &Scene) -> Scene {
    let mut unattenuated = scene.clone();
    for l in &mut unattenuated.lights {
        if let LightKind::Point { attenuation, .. } = &mut l.kind {
            *attenuation = [1.0, 0.0, 0.0];
        }
    }
    unattenuated
}

/// Every material with kt = 0 (the same scene when none transmits: that mistake then gives
/// the right answer and is passed over).
fn opaque(scene: &Scene) -> Scene {
    let mut opaque = scene.clone();
    for m in &mut opaque.materials {
        m.kt = 0.0;
    }
    opaque
}

// --- Collecting the tree again with a mistaken rule ---

/// The tree's intensities summed again from the leaves up, I = local + Σ k·I_child, with the
/// coefficient `k(parent, child)` of each reflection or refraction; a leaf keeps its own.
fn recollect(n: &RayNode, k: &dyn Fn(&RayNode, &RayNode) -> f64) -> RayNode {
    let mut out = n.clone();
    out.children = n.children.iter().map(|c| recollect(c, k)).collect();
    let secondary: Vec<(f64, DVec3)> = n
        .children
        .iter()
        .zip(&out.children)
        .filter(|(c, _)| c.kind != RayKind::Shadow)
        .map(|(c, again)| (k(n, c), again.color))
        .collect();
    if n.local.is_some() || !secondary.is_empty() {
        let local = n.local.as_ref().map_or(DVec3::ZERO, |l| l.total());
        out.color = local + secondary.iter().map(|(k, c)| *k * *c).sum::<DVec3>();
    }
    out
}

/// The tree's own coefficients sum it to its own intensities: recollecting is then a faithful
/// model of the student's sum (not so with secondary_attenuation, which divides each child's
/// intensity by its distance, and which these mistakes leave alone).
fn recollects(tree: &RayNode) -> bool {
    let again = recollect(tree, &|_, c| c.coefficient);
    (again.color - tree.color).abs().max_element() <= 1e-9 * tree.color.abs().max_element().max(1.0)
}

/// kt counted once per trip through a solid: a refraction leaving the solid (its parent hit
/// from inside) passes its intensity on unweighted.
fn kt_once(w: &Worked, ex: &Exercise) -> Option<Answer> {
    if !recollects(&w.tree) {
        return None;
    }
    let mistaken = recollect(&w.tree, &|parent, c| {
        let leaving = parent.hit.as_ref().is_some_and(|h| h.inside);
        if c.kind == RayKind::Refraction && leaving {
            1.0
        } else {
            c.coefficient
        }
    });
    answer(&w.scene, &w.ray, &mistaken, ex).ok()
}

/// Shadow rays passing through transparent objects: every light term whose shadow ray was
/// blocked by a surface with kt > 0 taken from the tree traced without shadows, then the tree
/// summed again.
fn glass_lets_light_through(w: &Worked, ex: &Exercise) -> Option<Answer> {
    if !w.scene.materials.iter().any(|m| m.kt > 0.0) || !recollects(&w.tree) {
        return None;
    }
    let open = trace(
        &w.scene,
        &w.ray,
        TraceOptions {
            max_depth: w.depth,
            shadows: false,
            ..TraceOptions::of(&w.scene)
        },
    );
    let mistaken = recollect(&unblock_glass(&w.scene, &w.tree, &open)?, &|_, c| {
        c.coefficient
    });
    answer(&w.scene, &w.ray, &mistaken, ex).ok()
}

/// `real` with the light terms of `open` (the same tree traced without shadows) wherever the
/// shadow ray was blocked by a transparent surface; None if the two trees differ in shape.
fn unblock_glass(scene: &Scene, real: &RayNode, open: &RayNode) -> Option<RayNode> {
    if real.children.len() != open.children.len() || real.kind != open.kind {
        return None;
    }
    let mut out = real.clone();
    if let (Some(local), Some(open_local)) = (&mut out.local, &open.local) {
        for (term, open_term) in local.lights.iter_mut().zip(&open_local.lights) {
            let shadow = real
                .children
                .iter()
                .find(|c| c.kind == RayKind::Shadow && c.light.as_deref() == Some(&term.light));
            let glass = shadow
                .and_then(|s| s.hit.as_ref())
                .and_then(|h| scene.materials.iter().find(|m| m.name == h.material))
                .is_some_and(|m| m.kt > 0.0);
            if glass {
                *term = open_term.clone();
            }
        }
    }
    out.children = real
        .children
        .iter()
        .zip(&open.children)
        .map(|(r, o)| unblock_glass(scene, r, o))
        .collect::<Option<_>>()?;
    Some(out)
}
