//! Lighting questions: a ray's intensity, its local term, and one light's share of it (the
//! shadow factor, the diffuse and the specular terms) in the lecture's model
//! `I = ka·Ia·O + Σ s·fatt·Iℓ·(kd·O·(n·l) + ks·(h·n)^m) + kr·I_r + kt·I_t`.

use super::derive;
use super::mistakes::tree_mistakes;
use super::tree::tree_explanation;
use super::{Mistake, Question, Traced, Worked};
use crate::lessons::{Answer, Exercise};
use crate::shading::{Highlight, Light, LightKind, Material};
use crate::trace::tree::{HitInfo, LightTerm};
use crate::trace::{text, RayNode};

pub(super) struct Intensity;

impl Question for Intensity {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        Ok(Answer::color(q.node.color))
    }

    fn mistakes(&self, w: &Worked, ex: &Exercise) -> Vec<Mistake> {
        tree_mistakes(w, ex)
    }

    fn explain(&self, w: &Worked, ex: &Exercise, n: &RayNode) -> Result<Vec<String>, String> {
        Ok(derive::explain(w, ex, n, true))
    }
}

pub(super) struct Local;

impl Question for Local {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        // A ray that meets no surface has no local term (its intensity is the background's).
        match (&q.node.local, &q.node.hit) {
            (Some(l), _) => Ok(Answer::color(l.total())),
            (None, None) => Err(format!(
                "exercise `{}`: the ray hits nothing, so it has no local term",
                q.ex.id
            )),
            (None, Some(_)) => Err(format!(
                "exercise `{}`: the surface the ray hits is not shaded here",
                q.ex.id
            )),
        }
    }

    fn mistakes(&self, w: &Worked, ex: &Exercise) -> Vec<Mistake> {
        tree_mistakes(w, ex)
    }

    fn explain(&self, w: &Worked, ex: &Exercise, n: &RayNode) -> Result<Vec<String>, String> {
        Ok(derive::explain(w, ex, n, false))
    }
}

pub(super) struct ShadowFactor;

impl Question for ShadowFactor {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        Ok(Answer::Number(light_term(q)?.shadow))
    }

    fn mistakes(&self, w: &Worked, ex: &Exercise) -> Vec<Mistake> {
        tree_mistakes(w, ex)
    }

    fn explain(&self, w: &Worked, ex: &Exercise, n: &RayNode) -> Result<Vec<String>, String> {
        Ok(one_light(w, ex, n))
    }
}

pub(super) struct Diffuse;

impl Question for Diffuse {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        Ok(Answer::color(light_term(q)?.diffuse))
    }

    fn mistakes(&self, w: &Worked, ex: &Exercise) -> Vec<Mistake> {
        tree_mistakes(w, ex)
    }

    fn explain(&self, w: &Worked, ex: &Exercise, n: &RayNode) -> Result<Vec<String>, String> {
        Ok(one_light(w, ex, n))
    }
}

pub(super) struct Specular;

impl Question for Specular {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        Ok(Answer::color(light_term(q)?.specular))
    }

    fn mistakes(&self, w: &Worked, ex: &Exercise) -> Vec<Mistake> {
        tree_mistakes(w, ex)
    }

    fn explain(&self, w: &Worked, ex: &Exercise, n: &RayNode) -> Result<Vec<String>, String> {
        Ok(one_light(w, ex, n))
    }
}

/// The terms of the exercise's light at the node.
fn light_term<'a>(q: &Traced<'a>) -> Result<&'a LightTerm, String> {
    let ex = q.ex;
    let name = ex
        .light
        .as_deref()
        .ok_or_else(|| format!("exercise `{}` needs `light`", ex.id))?;
    if !q.scene.lights.iter().any(|l| l.name == name) {
        let names: Vec<&str> = q.scene.lights.iter().map(|l| l.name.as_str()).collect();
        return Err(format!(
            "exercise `{}`: the scene has no light named `{name}` (its lights: {})",
            ex.id,
            if names.is_empty() {
                "none".to_string()
            } else {
                names.join(", ")
            }
        ));
    }
    if q.node.hit.is_none() {
        return Err(format!(
            "exercise `{}`: the ray hits nothing, so no light shines on it",
            ex.id
        ));
    }
    q.node
        .local
        .as_ref()
        .and_then(|l| l.lights.iter().find(|t| t.light == name))
        .ok_or_else(|| {
            format!(
                "exercise `{}`: no term for light `{name}` at this node",
                ex.id
            )
        })
}

// --- Explanation: one light's terms ---

/// One light's share of the local term, from its direction and distance to the diffuse and
/// specular terms. A node without that light's terms is explained by its tree.
fn one_light(w: &Worked, ex: &Exercise, n: &RayNode) -> Vec<String> {
    let (Some(local), Some(name), Some(h)) = (&n.local, ex.light.as_deref(), &n.hit) else {
        return tree_explanation(n);
    };
    let mut out = vec![format!(
        "hit {} at p = {}, n = {}",
        h.object,
        text::vec3(h.point),
        text::vec3(h.normal)
    )];
    let t = local.lights.iter().find(|t| t.light == name);
    let m = w.scene.materials.iter().find(|m| m.name == h.material);
    let light = w.scene.lights.iter().find(|l| l.name == name);
    let (Some(t), Some(m), Some(light)) = (t, m, light) else {
        return out;
    };
    out.push(format!(
        "toward {name}: l = {}, n·l = {}",
        text::vec3(t.l),
        text::num(t.n_dot_l)
    ));
    out.extend(light_source(light, h, t));
    out.extend(shadow_rays(n, light, t));
    out.push(diffuse_line(light, m, t));
    out.push(specular_line(light, m, t));
    out
}

/// What kind of light it is: where its shadow rays go and how it fades with distance.
fn light_source(light: &Light, h: &HitInfo, t: &LightTerm) -> Vec<String> {
    match &light.kind {
        LightKind::Point {
            position,
            attenuation: [c0, c1, c2],
        } => {
            let dist = (*position - h.point).length();
            vec![
                format!("point light at {}: distance d = {}; a shadow ray is blocked by a hit with 0 < t < d", text::vec3(*position), text::num(dist)),
                format!(
                    "fatt = 1/(c0 + c1·d + c2·d²) = 1/({} + {}·{} + {}·{}²) = {}",
                    text::num(*c0),
                    text::num(*c1),
                    text::num(dist),
                    text::num(*c2),
                    text::num(dist),
                    text::num(t.attenuation)
                ),
            ]
        }
        LightKind::Directional { .. } => vec![
            "directional light: a shadow ray is blocked by any hit with t > 0; fatt = 1".into(),
        ],
        LightKind::Rect { samples, .. } => vec![format!(
            "area light: l points to its centre; s = the fraction of {} shadow rays (to the centres of a {samples} × {samples} grid on it) that reach it",
            samples * samples
        )],
        LightKind::Sphere {
            radius, samples, ..
        } => vec![format!(
            "sphere light of radius {}: l points to its centre (fatt as for a point light); s = the fraction of {} shadow rays (to a {samples} × {samples} pattern on the disc it shows this point) that reach it",
            text::num(*radius),
            samples * samples
        )],
    }
}

/// The shadow factor s: why no shadow ray was cast, or what the shadow rays met.
fn shadow_rays(n: &RayNode, light: &Light, t: &LightTerm) -> Option<String> {
    if let Some(why) = &t.skipped {
        return Some(format!(
            "no shadow ray: {why}, so the light adds nothing (s = 0)"
        ));
    }
    let sh = n
        .children
        .iter()
        .find(|c| c.light.as_deref() == Some(light.name.as_str()))?;
    let count = light.shadow_rays();
    Some(match &sh.hit {
        Some(b) if count > 1 => {
            let through = (t.shadow * count as f64).round();
            format!(
                "{through} of the {count} shadow rays reach the light (the first one blocked meets {} at t = {}) → s = {through}/{count} = {}",
                b.object,
                text::num(b.t),
                text::num(t.shadow)
            )
        }
        None if count > 1 => format!("all {count} shadow rays reach the light → s = 1"),
        Some(b) => format!(
            "shadow ray from {} toward l: blocked by {} at t = {} → s = 0",
            text::vec3(sh.origin),
            b.object,
            text::num(b.t)
        ),
        None => format!(
            "shadow ray from {} toward l: reaches the light → s = 1",
            text::vec3(sh.origin)
        ),
    })
}

fn diffuse_line(light: &Light, m: &Material, t: &LightTerm) -> String {
    let il = light.intensity;
    let raw = t.attenuation * il * m.kd * m.color * t.n_dot_l.max(0.0);
    format!(
        "diffuse = s·fatt·Iℓ·kd·O·(n·l) = {}·{}·{}·{}·{}·{} = {}",
        text::num(t.shadow),
        text::num(t.attenuation),
        text::color(il),
        text::num(m.kd),
        text::color(m.color),
        text::num(t.n_dot_l.max(0.0)),
        text::color(t.shadow * raw)
    )
}

fn specular_line(light: &Light, m: &Material, t: &LightTerm) -> String {
    let model = if t.n_dot_l < 0.0 && t.skipped.is_none() {
        // A light behind a transparent surface, seen through it (Hall's transmitted highlight).
        "h′·n, h′ = −(η·l + v)/(η − 1) normalised, η = n(light's side)/n(viewer's side)"
    } else if m.highlight == Highlight::Blinn {
        "h·n, h = (l + v)/|l + v|"
    } else {
        "r·v, r = 2(n·l)n − l"
    };
    format!(
        "specular = s·fatt·Iℓ·ks·({model})^m = {}·{}·{}·{}·{}^{} = {}",
        text::num(t.shadow),
        text::num(t.attenuation),
        text::color(light.intensity),
        text::num(m.ks),
        text::num(t.highlight_cos),
        text::num(m.shininess),
        text::color(t.specular)
    )
}
