//! An intensity derived as a student derives it on paper: for every surface the tree's rays
//! meet, the vectors (l, v, h or r), n·l, the power, the distance d and fatt, and each term of
//! the local model with its numbers; then every node's intensity collected from the leaves
//! up. Nodes are named by the surfaces on their path, `I(a → b → d)`, as in the lecture's
//! drawing of the tree.

use glam::DVec3;

use super::tree::{child_names, collect_lines, short};
use super::Worked;
use crate::lessons::Exercise;
use crate::shading::{Highlight, Light, LightKind, Material, Paint};
use crate::trace::tree::{HitInfo, LightTerm, Local};
use crate::trace::{text, RayKind, RayNode, Termination};

/// The whole derivation of the intensity of node `n`, named `name`: every node below it,
/// then the sums.
fn intensity(w: &Worked, n: &RayNode, name: &str) -> Vec<String> {
    let mut out = Vec::new();
    walk(w, n, name, &mut out);
    out.push("collecting from the leaves up, I = I_local + kr·I_r + kt·I_t:".into());
    collect_lines(n, name, &mut out);
    out
}

fn walk(w: &Worked, n: &RayNode, name: &str, out: &mut Vec<String>) {
    node(w, n, name, out);
    if n.cone().is_some() {
        // The sampled rays of a glossy or frosted cone are not derived one by one.
        return;
    }
    for (c, child) in n.secondary().zip(child_names(n, name)) {
        walk(w, c, &child, out);
    }
}

/// One node: how its ray arrives, and its local term worked out.
fn node(w: &Worked, n: &RayNode, name: &str, out: &mut Vec<String>) {
    let name = &short(name);
    let ray = match n.kind {
        RayKind::Primary => "the primary ray".to_string(),
        k => format!(
            "the {} ray (coefficient {})",
            k.name(),
            text::num(n.coefficient)
        ),
    };
    if let Some((lobe, k)) = n.cone() {
        let mut values: Vec<String> = n.secondary().map(|c| text::color(c.color)).collect();
        if values.len() > 16 {
            // Too many to list: each value once, with how many rays brought it.
            let mut counts: Vec<(String, usize)> = Vec::new();
            for v in values {
                match counts.iter_mut().find(|(x, _)| *x == v) {
                    Some((_, c)) => *c += 1,
                    None => counts.push((v, 1)),
                }
            }
            values = counts
                .into_iter()
                .map(|(v, c)| format!("{c} × {v}"))
                .collect();
        }
        out.push(format!(
            "I({name}): {lobe} about {}: {k} rays sampled about it bring {}; their mean = {}",
            text::vec3(n.direction),
            values.join(", "),
            text::color(n.color)
        ));
        return;
    }
    let Some(h) = &n.hit else {
        out.push(match n.terminated {
            Some(Termination::MaxDepth) => format!(
                "I({name}): {ray} is not traced (the path has reached max_depth {}): 0",
                w.depth
            ),
            Some(Termination::Adaptive) => format!(
                "I({name}): {ray} is not traced (its weight {} is below the adaptive threshold): 0",
                text::num(n.weight)
            ),
            Some(Termination::TotalInternalReflection) if n.children.is_empty() => format!(
                "I({name}): total internal reflection: no refracted ray; its share follows the surface's reflection ray, the same mirror ray = {}",
                text::color(n.color)
            ),
            Some(Termination::TotalInternalReflection) => format!(
                "I({name}): total internal reflection: no refracted ray; its share goes into a mirror ray inside = {}",
                text::color(n.color)
            ),
            Some(Termination::Light) => format!(
                "I({name}): {ray} from {} along {} reaches light {} and stops there (stop rule): its intensity, {}",
                text::vec3(n.origin),
                text::vec3(n.direction),
                n.light.as_deref().unwrap_or("?"),
                text::color(n.color)
            ),
            _ => format!(
                "I({name}): {ray} from {} along {} hits nothing: the background, {}",
                text::vec3(n.origin),
                text::vec3(n.direction),
                text::color(n.color)
            ),
        });
        return;
    };
    let v = -n.direction;
    let surface = if h.leaf == h.object {
        h.object.clone()
    } else {
        format!("{} (the surface of its part {})", h.object, h.leaf)
    };
    out.push(format!(
        "I({name}): {ray} from {} along {} hits {surface} at t = {}: p = {}, n = {}, v = −d = {}",
        text::vec3(n.origin),
        text::vec3(n.direction),
        text::num(h.t),
        text::vec3(h.point),
        text::vec3(h.normal),
        text::vec3(v)
    ));
    let (Some(local), Some(m)) = (
        &n.local,
        w.scene.materials.iter().find(|m| m.name == h.material),
    ) else {
        return;
    };
    let at = paint_at(m, local);
    for p in &local.patterns {
        out.push(format!("  {}", text::pattern(p)));
    }
    out.push(format!(
        "  ambient ka·Ia·O = {}·{}·{} = {}",
        text::num(m.ka),
        text::color(w.scene.ambient),
        text::color(at.color),
        text::color(local.ambient)
    ));
    for t in &local.lights {
        let light = w.scene.lights.iter().find(|l| l.name == t.light);
        if let Some(light) = light {
            out.extend(light_lines(n, h, (m, &at), light, t, v));
        }
    }
    let mut terms = vec![text::color(local.ambient)];
    for t in &local.lights {
        terms.push(text::color(t.diffuse));
        terms.push(text::color(t.specular));
    }
    out.push(format!(
        "  I_local({name}) = {} = {}",
        terms.join(" + "),
        text::color(local.total())
    ));
    if n.terminated == Some(Termination::Diffuse) {
        out.push(format!(
            "  {} is diffuse (kd = {}): by the stop rule the path ends here, no reflection or refraction ray",
            h.object,
            text::num(m.kd)
        ));
    }
}

/// The material's values at the hit: a pattern's where one varies them, else its constants.
fn paint_at(m: &Material, local: &Local) -> Paint {
    let mut at = m.paint();
    if let Some(color) = local.color {
        at.color = color;
    }
    if let Some(c) = local.coefficients {
        (at.kd, at.ks, at.kr, at.kt) = (c.kd, c.ks, c.kr, c.kt);
    }
    at
}

/// One light's share at a hit: l and n·l, d and fatt, the shadow factor, the highlight's vector
/// and power, then the diffuse and specular terms.
fn light_lines(
    n: &RayNode,
    h: &HitInfo,
    (m, at): (&Material, &Paint),
    light: &Light,
    t: &LightTerm,
    v: DVec3,
) -> Vec<String> {
    let name = &light.name;
    let mut out = vec![format!(
        "  light {name}: l = {}, n·l = {}",
        text::vec3(t.l),
        text::num(t.n_dot_l)
    )];
    if t.n_dot_l < 0.0 && t.skipped.is_none() {
        out.extend(transmitted_lines(n, h, m, light, t, v));
        return out;
    }
    if t.n_dot_l <= 0.0 {
        out.push(format!(
            "    n·l ≤ 0: {name} is behind the surface: no shadow ray, no diffuse, no specular"
        ));
        return out;
    }
    out.push(format!("    {}", distance(light, h, t)));
    out.push(format!("    {}", shadow(n, light, t)));
    let m_exp = text::num(m.shininess);
    let power = t.highlight_cos.powf(m.shininess);
    if at.ks > 0.0 {
        out.push(match m.highlight {
            Highlight::Blinn => {
                let hv = (t.l + v).normalize();
                format!(
                    "    h = (l + v)/|l + v| = {}, h·n = {}, (h·n)^{m_exp} = {}",
                    text::vec3(hv),
                    text::num(t.highlight_cos),
                    text::num(power)
                )
            }
            Highlight::Phong => {
                let r = 2.0 * t.n_dot_l * h.normal - t.l;
                format!(
                    "    r = 2(n·l)n − l = {}, r·v = {}, (r·v)^{m_exp} = {}",
                    text::vec3(r),
                    text::num(t.highlight_cos),
                    text::num(power)
                )
            }
        });
    }
    let factors = format!(
        "{}·{}·{}",
        text::num(t.shadow),
        text::num(t.attenuation),
        text::color(light.intensity)
    );
    out.push(format!(
        "    diffuse s·fatt·Iℓ·kd·O·(n·l) = {factors}·{}·{}·{} = {}",
        text::num(at.kd),
        text::color(at.color),
        text::num(t.n_dot_l),
        text::color(t.diffuse)
    ));
    out.push(if at.ks > 0.0 {
        let cos = if m.highlight == Highlight::Blinn {
            "(h·n)^m"
        } else {
            "(r·v)^m"
        };
        format!(
            "    specular s·fatt·Iℓ·ks·{cos} = {factors}·{}·{} = {}",
            text::num(at.ks),
            text::num(power),
            text::color(t.specular)
        )
    } else {
        "    specular: ks = 0, none".into()
    });
    out
}

/// A light behind a transparent surface seen through it (Hall's transmitted highlight): the
/// shadow ray through the surface, H′ from η, and the specular term with h′·n.
fn transmitted_lines(
    n: &RayNode,
    h: &HitInfo,
    m: &Material,
    light: &Light,
    t: &LightTerm,
    v: DVec3,
) -> Vec<String> {
    let mut out = vec![format!(
        "    n·l < 0: {} is behind the surface; the surface is transparent (kt = {}) and takes the transmitted highlight, so the light is seen through it",
        light.name,
        text::num(m.kt)
    )];
    out.push(format!("    {}", distance(light, h, t)));
    out.push(format!("    {}", shadow(n, light, t)));
    // η as the tracer found it: the indices n1 → n2 recorded on the surface's refraction ray
    // (a transparent surface always records one, traced or cut off).
    let eta = n
        .children
        .iter()
        .find_map(|c| c.indices)
        .map_or(if h.inside { 1.0 / m.ior } else { m.ior }, |i| i.n2 / i.n1);
    let hv = (-(eta * t.l + v) / (eta - 1.0)).normalize_or_zero();
    let power = t.highlight_cos.powf(m.shininess);
    out.push(format!(
        "    η = n(light's side)/n(viewer's side) = {}, h′ = −(η·l + v)/(η − 1), normalised = {}, h′·n = {}, (h′·n)^{} = {}",
        text::num(eta),
        text::vec3(hv),
        text::num(t.highlight_cos),
        text::num(m.shininess),
        text::num(power)
    ));
    out.push("    diffuse: none (n·l < 0)".into());
    out.push(format!(
        "    transmitted highlight s·fatt·Iℓ·ks·(h′·n)^m = {}·{}·{}·{}·{} = {}",
        text::num(t.shadow),
        text::num(t.attenuation),
        text::color(light.intensity),
        text::num(m.ks),
        text::num(power),
        text::color(t.specular)
    ));
    out
}

/// The light's distance and attenuation.
fn distance(light: &Light, h: &HitInfo, t: &LightTerm) -> String {
    let fatt = |at: DVec3, [c0, c1, c2]: [f64; 3], what: &str| {
        let d = (at - h.point).length();
        format!(
            "{what} at {}: d = |L − p| = {}, fatt = 1/(c0 + c1·d + c2·d²) = 1/({} + {}·{} + {}·{}²) = {}",
            text::vec3(at),
            text::num(d),
            text::num(c0),
            text::num(c1),
            text::num(d),
            text::num(c2),
            text::num(d),
            text::num(t.attenuation)
        )
    };
    match &light.kind {
        LightKind::Point {
            position,
            attenuation,
        } => fatt(*position, *attenuation, "point light"),
        LightKind::Sphere {
            center,
            attenuation,
            ..
        } => fatt(*center, *attenuation, "sphere light, centre"),
        LightKind::Directional { .. } => "directional light: no distance, fatt = 1".into(),
        LightKind::Rect { .. } => format!(
            "area light: l points to its centre, fatt = {}",
            text::num(t.attenuation)
        ),
    }
}

/// The shadow factor s and where it comes from.
fn shadow(n: &RayNode, light: &Light, t: &LightTerm) -> String {
    if let Some(why) = &t.skipped {
        return format!("no shadow ray ({why}): s = {}", text::num(t.shadow));
    }
    let ray = n
        .children
        .iter()
        .find(|c| c.kind == RayKind::Shadow && c.light.as_deref() == Some(light.name.as_str()));
    match ray {
        Some(sh) => format!(
            "shadow ray: {}: s = {}",
            text::shadow_outcome(sh),
            text::num(t.shadow)
        ),
        None => format!("s = {}", text::num(t.shadow)),
    }
}

/// The explanation of an exercise about an intensity: the highlight model, then the
/// derivation of the node's whole intensity, or (`whole` false) of its local term alone.
pub(super) fn explain(w: &Worked, ex: &Exercise, n: &RayNode, whole: bool) -> Vec<String> {
    let mut out = Vec::new();
    if let Some(model) = super::highlight_model(w, ex) {
        out.push(model);
    }
    let name = path_name(&w.tree, &ex.node);
    if whole {
        out.extend(intensity(w, n, &name));
    } else {
        node(w, n, &name, &mut out);
    }
    out
}

/// The name of the node at a path of kinds ("reflection/refraction") below the root: the
/// surfaces its rays meet on the way, `a → b → d`.
fn path_name(root: &RayNode, path: &str) -> String {
    let mut n = root;
    let mut name = super::tree::root_name(root);
    for step in path.split('/').filter(|s| !s.is_empty()) {
        let Some((c, child)) = n
            .secondary()
            .zip(child_names(n, &name))
            .find(|(c, _)| c.kind.name() == step)
        else {
            break;
        };
        n = c;
        name = child;
    }
    name
}
