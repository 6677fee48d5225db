//! What the node details pane says: where the selected ray starts and goes, what it hit, and
//! the illumination formula with the numbers filled in, term by term, summing to its
//! intensity; as rows at the pane's width, which the ray tree scrolls through.

use glam::DVec3;

use crate::trace::text::{color, length_at, node_details, num, ray_origin, received, vec3};
use crate::trace::{RayKind, RayNode, Termination};
use crate::tui::wrap::wrap;

/// The formula every shaded node follows.
pub const FORMULA: &str = "I = ka·Ia·O + Σℓ s·fatt·Iℓ·(kd·O·(n·l) + ks·(h·n)^m) + kr·I_r + kt·I_t";

/// The detail lines of a node; a line may carry a colour swatch (drawn after it).
pub fn details_lines(n: &RayNode, max_depth: u32, scale: f64) -> Vec<(String, Option<DVec3>)> {
    let mut out: Vec<(String, Option<DVec3>)> = Vec::new();
    let plain = |s: String| (s, None);
    match n.kind {
        RayKind::Shadow => out.push(plain(format!(
            "shadow ray towards light {} · depth {}",
            n.light.as_deref().unwrap_or("?"),
            n.depth
        ))),
        k => out.push((
            format!(
                "{} ray · depth {} · I = {}",
                k.name(),
                n.depth,
                color(n.color)
            ),
            Some(n.color),
        )),
    }
    out.push(plain(format!("origin    {}", ray_origin(n, scale))));
    out.push(plain(format!("direction {}", vec3(n.direction))));
    // node_details starts with "ray o → d", said above in two lines.
    for l in node_details(n, scale).into_iter().skip(1) {
        if l.starts_with("ambient") {
            out.push(plain(FORMULA.to_string()));
        }
        // The surface's colour at the hit, from its pattern or texture, with its swatch.
        let swatch = l
            .starts_with("O = ")
            .then(|| n.local.as_ref().and_then(|local| local.color))
            .flatten();
        out.push((l, swatch));
    }
    match n.kind {
        RayKind::Shadow => {
            if let Some(t) = n.t_max {
                out.push(plain(format!("looks for blockers up to t = {}", length_at(t, scale))));
            }
            let s = n.shadow.unwrap_or(0.0);
            out.push(plain(match (&n.hit, n.shadow_rays) {
                (Some(h), Some(rays)) => format!(
                    "{} of {rays} shadow rays reach the light (the first blocked meets {} at t = {}): s = {}",
                    (s * rays as f64).round(),
                    h.object,
                    length_at(h.t, scale),
                    num(s)
                ),
                (None, Some(rays)) => format!("all {rays} shadow rays reach the light: s = 1"),
                (Some(h), None) => format!(
                    "blocked by {} at t = {}: s = {}",
                    h.object,
                    length_at(h.t, scale),
                    num(n.shadow.unwrap_or(0.0))
                ),
                (None, None) => format!(
                    "nothing in the way: s = {}",
                    num(n.shadow.unwrap_or(1.0))
                ),
            }));
        }
        _ => match n.terminated {
            Some(Termination::Background) => out.push((
                format!("hit nothing: I = background = {}", color(n.color)),
                Some(n.color),
            )),
            // Cut by the level being stepped: the full tree traces it.
            Some(Termination::MaxDepth) if n.depth < max_depth => out.push(plain(
                "not yet revealed: level stepping shows one more level at each n".into(),
            )),
            Some(Termination::MaxDepth) => out.push(plain(format!(
                "not traced: the path already has {max_depth} rays (the maximum depth); + goes deeper"
            ))),
            Some(Termination::Adaptive) => out.push(plain(format!(
                "not traced: its weight {} is below the adaptive threshold",
                num(n.weight)
            ))),
            Some(Termination::TotalInternalReflection) if n.children.is_empty() => out.push(plain(
                "total internal reflection: no light is transmitted; the share kt follows the surface's reflection ray, the same mirror ray (traced once, weighted kr + kt)"
                    .into(),
            )),
            Some(Termination::TotalInternalReflection) => out.push(plain(
                "total internal reflection: no light is transmitted; the energy follows the mirror ray"
                    .into(),
            )),
            Some(Termination::Light) => out.push((
                format!(
                    "reached light {}: the ray stops there (stop rule) and brings back its intensity {}",
                    n.light.as_deref().unwrap_or("?"),
                    color(n.color)
                ),
                Some(n.color),
            )),
            Some(Termination::Diffuse) => out.push(plain(
                "a diffuse surface: no reflection or refraction ray (stop rule), local illumination only"
                    .into(),
            )),
            None => {}
        },
    }
    if let Some(local) = &n.local {
        let mut terms = vec![local.ambient];
        for l in &local.lights {
            terms.push(l.diffuse);
            terms.push(l.specular);
        }
        for c in n.secondary() {
            terms.push(c.coefficient * received(c));
        }
        let sum = terms
            .iter()
            .map(|t| color(*t))
            .collect::<Vec<_>>()
            .join(" + ");
        out.push((
            format!("sum  I = {sum} = {}", color(n.color)),
            Some(n.color),
        ));
    }
    out
}

/// How a row of the details is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DetailKind {
    /// The first line: the ray's kind, depth and intensity.
    Title,
    Formula,
    Sum,
    Plain,
}

/// A row of the details pane; the last row of a line may end with a colour swatch.
#[derive(Clone, Debug, PartialEq)]
pub struct DetailRow {
    pub text: String,
    pub kind: DetailKind,
    pub swatch: Option<DVec3>,
}

/// What stands in for the terms of the model while a lesson hides its solutions.
pub const HIDDEN: &str =
    "intensities hidden until this scene's exercises about them are answered (solutions: hidden)";

/// The detail lines without the intensities and the terms that make them up: where the ray
/// goes and what it hits stay.
fn without_intensities(
    n: &RayNode,
    lines: Vec<(String, Option<DVec3>)>,
) -> Vec<(String, Option<DVec3>)> {
    let terms = [
        "ambient",
        "light ",
        "  diffuse",
        "  specular",
        "kr·I_r",
        "kt·I_t",
        "I = ",
        "sum ",
        "hit nothing",
        I_FORMULA_START,
    ];
    let mut out: Vec<(String, Option<DVec3>)> = lines
        .into_iter()
        .enumerate()
        .filter_map(|(i, (s, _))| {
            if i == 0 {
                return Some((s.split(" · I = ").next().unwrap_or(&s).to_string(), None));
            }
            (!terms.iter().any(|t| s.starts_with(t))).then_some((s, None))
        })
        .collect();
    if n.kind != RayKind::Shadow {
        out.push((HIDDEN.into(), None));
    }
    out
}

/// The start of the formula line.
const I_FORMULA_START: &str = "I = ka";

/// The details of a node wrapped to `width` cells (a swatch takes three of them), without the
/// intensities when they are `hidden`.
pub fn rows(n: &RayNode, max_depth: u32, scale: f64, width: usize, hidden: bool) -> Vec<DetailRow> {
    let mut rows = Vec::new();
    let mut lines = details_lines(n, max_depth, scale);
    if hidden {
        lines = without_intensities(n, lines);
    }
    for (i, (s, sw)) in lines.into_iter().enumerate() {
        let kind = if i == 0 {
            DetailKind::Title
        } else if s.starts_with("I = ka") {
            DetailKind::Formula
        } else if s.starts_with("sum") {
            DetailKind::Sum
        } else {
            DetailKind::Plain
        };
        let sw_w = if sw.is_some() { 3 } else { 0 };
        let parts = wrap(&s, width.saturating_sub(sw_w).max(10));
        let count = parts.len();
        for (j, text) in parts.into_iter().enumerate() {
            rows.push(DetailRow {
                text,
                kind,
                swatch: sw.filter(|_| j + 1 == count),
            });
        }
    }
    rows
}
