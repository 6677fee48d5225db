//! Plain-text views of ray trees and CSG traces, for the terminal and for snapshots.

use glam::DVec3;

use super::tree::{LightTerm, PatternLookup, RayKind, RayNode};
use crate::geometry::csg::{CsgTrace, Pruned};
use crate::geometry::Ray;
use crate::scene::{Hit, Scene, Search};
use crate::stats::Stats;

/// A number with at most six decimals, trailing zeros dropped ("0.4125", "13", "-0.6").
pub fn num(x: f64) -> String {
    if x.is_infinite() {
        return if x > 0.0 {
            "∞".into()
        } else {
            "−∞".into()
        };
    }
    if x.is_nan() {
        return "NaN".into();
    }
    if x.abs() >= 1e15 {
        // Beyond 10¹⁵ the digits of a fixed-point number run to hundreds (±1e100 is allowed).
        let s = format!("{x:.6e}");
        let (mantissa, exponent) = s.split_once('e').expect("`e` formatting has an exponent");
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        return format!("{mantissa}e{exponent}");
    }
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

/// A point or vector as "(x, y, z)", each number with at most six decimals.
pub fn vec3(v: DVec3) -> String {
    format!("({}, {}, {})", num(v.x), num(v.y), num(v.z))
}

/// A length or coordinate (t, a segment's end): as `num`, but one that six decimals would
/// write as 0 is written with its own digits ("5.12e-10"): a scene can be 10⁻¹⁰ across, and
/// its distances are not 0. (Intensities and cosines stay `num`'s: 10⁻²⁵ of a light is none.)
pub fn length(x: f64) -> String {
    let fixed = num(x);
    if fixed != "0" || x == 0.0 {
        return fixed;
    }
    scientific(x)
}

/// A number with six significant digits and an exponent, trailing zeros dropped ("1.1e-6").
pub fn scientific(x: f64) -> String {
    let s = format!("{x:.5e}");
    let (mantissa, exponent) = s.split_once('e').expect("`e` formatting has an exponent");
    let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
    format!("{mantissa}e{exponent}")
}

/// A point given as it is (a ray's origin given on the command line), as "(x, y, z)", with
/// `length`'s digits.
pub fn point(p: DVec3) -> String {
    format!("({}, {}, {})", length(p.x), length(p.y), length(p.z))
}

/// Below this share of the size of the numbers around it, a coordinate or a length is their
/// rounding, or the bias that moves a secondary ray off its surface (10⁻¹⁰ of the
/// coordinates), and is written as 0.
const NOISE: f64 = 1e-9;

/// A length or coordinate found by arithmetic among numbers of size `scale` (a ray tree's, a
/// ray's): 0 below `NOISE` of it, else with `length`'s digits (a scene 10⁻¹⁰ across keeps its
/// own).
pub fn length_at(x: f64, scale: f64) -> String {
    if x.abs() < NOISE * scale {
        "0".into()
    } else {
        length(x)
    }
}

/// A point found by arithmetic among numbers of size `scale`, as "(x, y, z)" (`length_at`):
/// a floor met at the origin from 4 away is at (0, 0, 0), not at (4.4e-16, −8.9e-16, 0).
pub fn point_at(p: DVec3, scale: f64) -> String {
    format!(
        "({}, {}, {})",
        length_at(p.x, scale),
        length_at(p.y, scale),
        length_at(p.z, scale)
    )
}

/// The size of the numbers a ray tree was found from: its largest |coordinate| of a ray's
/// origin or a hit point, and its longest finite t.
pub fn tree_scale(n: &RayNode) -> f64 {
    let own = n.hit.as_ref().map_or(0.0, |h| {
        let t = if h.t.is_finite() { h.t.abs() } else { 0.0 };
        t.max(h.point.abs().max_element())
    });
    n.children
        .iter()
        .map(tree_scale)
        .fold(own.max(n.origin.abs().max_element()), f64::max)
}

/// A grey colour as one number, others as (r, g, b).
pub fn color(c: DVec3) -> String {
    if c.x == c.y && c.y == c.z {
        num(c.x)
    } else {
        vec3(c)
    }
}

/// One line naming a ray and its intensity.
pub fn node_title(n: &RayNode) -> String {
    let what = match (&n.hit, n.terminated) {
        (_, Some(t)) if n.kind != RayKind::Shadow => match t {
            super::Termination::Background => "background".to_string(),
            super::Termination::MaxDepth => "not traced: max depth".to_string(),
            super::Termination::Adaptive => "not traced: adaptive cut-off".to_string(),
            // Without a child the share follows the surface's reflection ray, the same ray.
            super::Termination::TotalInternalReflection if n.children.is_empty() => {
                "total internal reflection, along the reflection ray".to_string()
            }
            super::Termination::TotalInternalReflection => "total internal reflection".to_string(),
            super::Termination::Light => format!(
                "reaches light {} (stop rule)",
                n.light.as_deref().unwrap_or("?")
            ),
            super::Termination::Diffuse => match &n.hit {
                Some(h) => format!("hit {}, diffuse: the path stops (stop rule)", h.object),
                None => "diffuse: the path stops".to_string(),
            },
        },
        (_, _) if n.kind == RayKind::Shadow => shadow_outcome(n),
        (Some(h), _) => format!("hit {}", h.object),
        (None, _) => "no hit".to_string(),
    };
    if let Some((lobe, k)) = n.cone() {
        return format!(
            "{lobe} (depth {}): mean of {k} sampled ray{}, I = {}",
            n.depth,
            if k == 1 { "" } else { "s" },
            color(n.color)
        );
    }
    match n.kind {
        RayKind::Shadow => format!(
            "shadow → {}: {what}, s = {}",
            n.light.as_deref().unwrap_or("?"),
            num(n.shadow.unwrap_or(0.0))
        ),
        _ => format!(
            "{} (depth {}): {what}, I = {}",
            n.kind.name(),
            n.depth,
            color(n.color)
        ),
    }
}

/// What a shadow test found: blocked or clear, and for a light sampled by several shadow rays
/// how many got through.
pub fn shadow_outcome(n: &RayNode) -> String {
    let blocker = n.hit.as_ref().map(|h| h.object.as_str());
    let Some(rays) = n.shadow_rays else {
        return blocker.map_or("clear".into(), |b| format!("blocked by {b}"));
    };
    let clear = (n.shadow.unwrap_or(0.0) * rays as f64).round() as u32;
    match blocker {
        None => format!("clear (all {rays} rays)"),
        Some(b) if clear == 0 => format!("blocked by {b} (all {rays} rays)"),
        Some(b) => format!("partly blocked by {b} ({clear} of {rays} clear)"),
    }
}

/// Where a node's ray starts: a primary ray's origin as given (the eye, or a ray asked for),
/// any other's as found (a hit point moved off its surface by the bias), in a tree whose
/// numbers are of size `scale`.
pub fn ray_origin(n: &RayNode, scale: f64) -> String {
    match n.kind {
        RayKind::Primary => point(n.origin),
        _ => point_at(n.origin, scale),
    }
}

/// The formula lines of one node: hit, then every term of the illumination model. `scale` is
/// the size of its tree's numbers (`tree_scale`), below which its points' coordinates are
/// rounding.
pub fn node_details(n: &RayNode, scale: f64) -> Vec<String> {
    let origin = ray_origin(n, scale);
    let mut out = vec![match n.samples {
        Some(_) => format!("principal direction from {origin} → {}", vec3(n.direction)),
        None => format!("ray {origin} → {}", vec3(n.direction)),
    }];
    if n.kind != RayKind::Primary && n.kind != RayKind::Shadow {
        out.push(format!(
            "weight {} (coefficient {})",
            num(n.weight),
            num(n.coefficient)
        ));
    }
    if let Some(i) = n.indices {
        out.push(format!("n1 = {} → n2 = {}", num(i.n1), num(i.n2)));
    }
    if let Some(k) = n.samples {
        out.push(format!(
            "I = (I_1 + … + I_{k}) / {k} = {}  (each sampled ray has coefficient 1/{k})",
            color(n.color)
        ));
    }
    if let Some(h) = &n.hit {
        let mut leaf = String::new();
        if h.leaf != h.object && h.csg_path.is_empty() {
            leaf = format!(" (member {})", h.leaf);
        } else if h.leaf != h.object {
            leaf = format!(" (leaf {} via {})", h.leaf, h.csg_path.join(" → "));
        }
        out.push(format!("hit {}{leaf}, material {}", h.object, h.material));
        out.push(format!(
            "t = {}  point {}  normal {}  {}",
            length_at(h.t, scale),
            point_at(h.point, scale),
            vec3(h.normal),
            if h.inside {
                "inside (leaving)"
            } else {
                "outside (entering)"
            }
        ));
        if let Some(b) = h.barycentric {
            out.push(format!("barycentric (λ1, λ2, λ3) = {}", vec3(b)));
        }
        if let Some(uv) = h.uv {
            out.push(format!("texture (u, v) = ({}, {})", num(uv.x), num(uv.y)));
        }
    }
    if let Some(local) = &n.local {
        out.extend(local.patterns.iter().map(pattern));
        out.push(format!("ambient  ka·Ia·O = {}", color(local.ambient)));
        for l in &local.lights {
            out.extend(light_lines(l));
        }
        for c in n.secondary() {
            out.push(secondary_term(c));
        }
        out.push(format!(
            "I = local {} + secondary = {}",
            color(local.total()),
            color(n.color)
        ));
    }
    out
}

/// A secondary ray's intensity as its parent receives it: divided by c0 + c1·d + c2·d² when
/// the scene attenuates secondary rays by distance.
pub fn received(c: &RayNode) -> DVec3 {
    match c.attenuation {
        Some(a) => c.color / a,
        None => c.color,
    }
}

/// "kr·I_r = 0.7 × 0.773234 = 0.541264", with the distance attenuation written out where
/// there is one, so that the terms add up to the node's intensity.
pub fn secondary_term(c: &RayNode) -> String {
    let k = if c.kind == RayKind::Reflection {
        "kr·I_r"
    } else {
        "kt·I_t"
    };
    match c.attenuation {
        None => format!(
            "{k} = {} × {} = {}",
            num(c.coefficient),
            color(c.color),
            color(c.coefficient * c.color)
        ),
        Some(a) => format!(
            "{k}/(c0 + c1·d + c2·d²) = {} × {} / {} = {}  (attenuated over d = {})",
            num(c.coefficient),
            color(c.color),
            num(a),
            color(c.coefficient * received(c)),
            c.hit.as_ref().map_or("?".into(), |h| length(h.t))
        ),
    }
}

fn light_lines(l: &LightTerm) -> Vec<String> {
    if l.n_dot_l < 0.0 && l.skipped.is_none() {
        // A light behind a transparent surface, lit through it: Hall's transmitted highlight.
        return vec![
            format!(
                "light {}: n·l = {}, behind the surface, seen through it: s = {}, fatt = {}",
                l.light,
                num(l.n_dot_l),
                num(l.shadow),
                num(l.attenuation)
            ),
            "  diffuse  none (the light is behind the surface)".into(),
            format!(
                "  transmitted highlight s·fatt·Iℓ·ks·(h′·n)^m = {}  (h′·n = {})",
                color(l.specular),
                num(l.highlight_cos)
            ),
        ];
    }
    let mut out = vec![format!(
        "light {}: n·l = {}, s = {}, fatt = {}{}",
        l.light,
        num(l.n_dot_l),
        num(l.shadow),
        num(l.attenuation),
        l.skipped
            .as_ref()
            .map_or(String::new(), |why| format!("  (no shadow ray: {why})"))
    )];
    out.push(format!(
        "  diffuse  s·fatt·Iℓ·kd·O·(n·l) = {}",
        color(l.diffuse)
    ));
    out.push(format!(
        "  specular s·fatt·Iℓ·ks·(cos)^m = {}  (cos = {})",
        color(l.specular),
        num(l.highlight_cos)
    ));
    out
}

/// The whole tree, drawn with box characters, every node with its details.
pub fn tree(root: &RayNode) -> String {
    let mut out = String::new();
    draw(root, tree_scale(root), "", "", &mut out);
    out
}

fn draw(n: &RayNode, scale: f64, first: &str, rest: &str, out: &mut String) {
    out.push_str(first);
    out.push_str(&node_title(n));
    out.push('\n');
    let has_children = !n.children.is_empty();
    if n.kind != RayKind::Shadow {
        for line in node_details(n, scale) {
            out.push_str(rest);
            out.push_str(if has_children { "│   " } else { "    " });
            out.push_str(&line);
            out.push('\n');
        }
    }
    for (i, c) in n.children.iter().enumerate() {
        let last = i + 1 == n.children.len();
        let (f, r) = if last {
            ("└── ", "    ")
        } else {
            ("├── ", "│   ")
        };
        if n.samples.is_some() && i >= SAMPLES_SHOWN {
            // Later samples of a cone get one line each: the first few show the pattern.
            out.push_str(&format!("{rest}{f}{}", node_title(c)));
            if c.size() > 1 {
                let more = c.size() - 1;
                let rays = if more == 1 { "ray" } else { "rays" };
                out.push_str(&format!("  [{more} more {rays}: --format json]"));
            }
            out.push('\n');
            continue;
        }
        draw(c, scale, &format!("{rest}{f}"), &format!("{rest}{r}"), out);
    }
}

/// Sampled rays of a glossy or frosted cone drawn in full; the rest get a line each.
const SAMPLES_SHOWN: usize = 3;

/// A CSG trace drawn bottom-up readable: every node with its segment list.
pub fn csg_trace(scene: &Scene, ray: &Ray, trace: &CsgTrace) -> String {
    csg_trace_at(scene, ray, trace, 0.0)
}

/// `csg_trace` for a ray of a tree whose numbers are of size `scale` (`tree_scale`): a
/// secondary ray leaving a surface near the origin has an origin of the bias's size, and its
/// segments' t and points below `NOISE` of the tree's size are rounding, written as 0.
pub fn csg_trace_at(scene: &Scene, ray: &Ray, trace: &CsgTrace, scale: f64) -> String {
    let mut out = String::new();
    draw_csg(scene, ray, trace, scale, ("", ""), &mut out);
    out
}

/// A segment list as text: each segment's [t_in, t_out] and the points at its ends ("(empty)" for
/// none).
pub fn segment_list(ray: &Ray, segments: &[crate::geometry::Segment]) -> String {
    segment_list_at(ray, segments, 0.0)
}

/// `segment_list` among numbers of size at least `scale`.
fn segment_list_at(ray: &Ray, segments: &[crate::geometry::Segment], scale: f64) -> String {
    if segments.is_empty() {
        return "(empty)".into();
    }
    let scale = segments
        .iter()
        .flat_map(|s| [s.t_in, s.t_out])
        .filter(|t| t.is_finite())
        .fold(ray.origin.abs().max_element().max(scale), |m, t| {
            m.max(t.abs())
        });
    segments
        .iter()
        .map(|s| {
            let p = |t: f64| {
                if t.is_finite() {
                    point_at(ray.at(t), scale)
                } else {
                    num(t)
                }
            };
            let t = |t: f64| {
                if t.is_finite() {
                    length_at(t, scale)
                } else {
                    num(t)
                }
            };
            format!(
                "[{}, {}] {} → {}",
                t(s.t_in),
                t(s.t_out),
                p(s.t_in),
                p(s.t_out)
            )
        })
        .collect::<Vec<_>>()
        .join("  ")
}

/// The size of the numbers a ray's hit point is found from: o and t.
fn hit_scale(ray: &Ray, h: &Hit) -> f64 {
    ray.origin.abs().max_element() + h.t.abs()
}

/// What the CSG listing of one ray holds: the objects it meets, each with its trace, and a
/// line for every other object saying why it is not shown.
pub struct CsgSurvey {
    /// The objects the ray's line meets, each with its CSG trace (also one whose list is
    /// empty because parts of it were pruned).
    pub met: Vec<MetObject>,
    /// "object X (op): culled: …" for a CSG object skipped whole, "object X: the ray meets none
    /// of its parts" for one evaluated to nothing, and one line naming the plain shapes the
    /// ray misses.
    pub unmet: Vec<String>,
    /// The object the ray hits first, ahead of its origin, as the tracer finds it (none when
    /// every segment lies behind the origin).
    pub nearest: Option<(String, Hit)>,
}

/// An object whose segment lists the listing shows.
pub struct MetObject {
    /// The object's name.
    pub name: String,
    /// Its segment list at every node of its tree.
    pub trace: CsgTrace,
    /// Its first surface crossing ahead of the ray's origin (t > 0), as the tracer's search
    /// finds it: the lists run along the whole line, and a segment behind the origin is not hit.
    pub hit: Option<Hit>,
}

impl MetObject {
    /// What the ray hits of the object, in words: where it crosses its surface first ahead of
    /// its origin, or why it does not.
    pub fn verdict(&self, ray: &Ray) -> String {
        match &self.hit {
            Some(h) => format!(
                "hit ahead: t = {} at {}",
                length(h.t),
                point_at(ray.at(h.t), hit_scale(ray, h))
            ),
            None if self.trace.segments.is_empty() => "not hit: its segment list is empty".into(),
            None => "not hit: its segments lie behind the ray's origin (t ≤ 0)".into(),
        }
    }
}

impl CsgSurvey {
    /// The ray's nearest hit, in words (as `raytree inspect` finds it).
    pub fn nearest_line(&self, ray: &Ray) -> String {
        match &self.nearest {
            Some((name, h)) => format!(
                "nearest hit: object {name} at t = {}, {}",
                length(h.t),
                point_at(ray.at(h.t), hit_scale(ray, h))
            ),
            None => "nearest hit: none, the ray hits nothing ahead of its origin".into(),
        }
    }
}

/// The plain shapes the ray misses are named up to this many.
const MISSED_NAMED: usize = 8;

/// Every object along the ray's line: traced through bounding boxes (as the image is), or with
/// `all` every object evaluated whole without them.
pub fn csg_survey(scene: &Scene, ray: &Ray, all: bool) -> CsgSurvey {
    fn has_segments(t: &CsgTrace) -> bool {
        !t.segments.is_empty() || t.children.iter().any(has_segments)
    }
    // An empty list with parts pruned inside is shown whole: the parts were never tried, and
    // the tree says why.
    fn has_pruned(t: &CsgTrace) -> bool {
        t.children
            .iter()
            .any(|c| c.pruned.is_some() || has_pruned(c))
    }
    let stats = &mut Stats::default();
    let nearest = scene.nearest(ray, 0.0, f64::INFINITY, stats).map(|h| {
        let name = scene.objects[h.object as usize].name.clone();
        (name, h)
    });
    let mut survey = CsgSurvey {
        met: vec![],
        unmet: vec![],
        nearest,
    };
    let mut missed = vec![];
    for o in 0..scene.objects.len() as u32 {
        let name = scene.objects[o as usize].name.clone();
        let (list, trace) = scene.object_trace(o, ray, !all);
        let pruned_inside = trace.pruned.is_none() && has_pruned(&trace);
        if all || !list.is_empty() || has_segments(&trace) || pruned_inside {
            let hit = scene.object_hit(o, ray, ray.dir.recip(), 0.0, f64::INFINITY, stats);
            survey.met.push(MetObject { name, trace, hit });
        } else if let Some(p) = trace.pruned {
            survey.unmet.push(format!(
                "object {name} ({}): culled: {}",
                trace.op.map_or("shape", |op| op.name()),
                pruned_reason(p)
            ));
        } else if trace.op.is_some() {
            survey.unmet.push(format!(
                "object {name}: the ray meets none of its parts (every segment list is empty)"
            ));
        } else {
            missed.push(name);
        }
    }
    if !missed.is_empty() {
        let n = missed.len();
        let mut names = missed[..n.min(MISSED_NAMED)].join(", ");
        if n > MISSED_NAMED {
            names.push_str(&format!(", … ({} more)", n - MISSED_NAMED));
        }
        let other = if survey.met.is_empty() && survey.unmet.is_empty() {
            ""
        } else {
            " other"
        };
        let objects = if n == 1 { "object" } else { "objects" };
        survey
            .unmet
            .push(format!("the ray misses {n}{other} {objects}: {names}"));
    }
    survey
}

/// Why a CSG node was skipped, in words.
pub fn pruned_reason(p: Pruned) -> &'static str {
    match p {
        Pruned::Bounds => "ray misses its bounding box",
        Pruned::EmptyIntersection => "an earlier operand of the intersection is empty",
        Pruned::EmptyDifference => "the left operand of the difference is empty",
        Pruned::ParentPruned => "its parent was pruned",
    }
}

fn draw_csg(
    scene: &Scene,
    ray: &Ray,
    t: &CsgTrace,
    scale: f64,
    (first, rest): (&str, &str),
    out: &mut String,
) {
    let kind = match (t.op, t.leaf) {
        (Some(op), _) => op.name().to_string(),
        (None, Some(leaf)) => scene.leaves[leaf as usize].shape.kind().to_string(),
        (None, None) => "group".into(),
    };
    let label = if t.node == kind {
        kind.clone()
    } else {
        format!("{kind} {}", t.node)
    };
    let body = match t.pruned {
        Some(Pruned::ParentPruned) => "not evaluated: its parent was pruned".to_string(),
        Some(p) => format!("pruned: {}", pruned_reason(p)),
        None => segment_list_at(ray, &t.segments, scale),
    };
    out.push_str(&format!("{first}{label}: {body}\n"));
    for (i, c) in t.children.iter().enumerate() {
        let last = i + 1 == t.children.len();
        let (f, r) = if last {
            ("└── ", "    ")
        } else {
            ("├── ", "│   ")
        };
        draw_csg(
            scene,
            ray,
            c,
            scale,
            (&format!("{rest}{f}"), &format!("{rest}{r}")),
            out,
        );
    }
}

/// A pattern looked up at a hit: what it varies, its value, and where it was evaluated.
pub fn pattern(p: &PatternLookup) -> String {
    let at = match p.uv {
        Some(uv) => format!("(u, v) = ({}, {})", num(uv.x), num(uv.y)),
        None => format!("p = {}", point_at(p.point, p.point.abs().max_element())),
    };
    format!("{} = {}  ({} at {at})", p.varies, color(p.value), p.pattern)
}

#[cfg(test)]
mod tests {
    use super::{length, length_at, num, point, point_at};
    use glam::DVec3;

    /// Six decimals at most, trailing zeros dropped; beyond 10¹⁵ six significant decimals and
    /// an exponent, so the largest coordinates a scene allows stay one short number.
    #[test]
    fn numbers_are_short_at_every_scale() {
        let cases = [
            (0.870161, "0.870161"),
            (2.5, "2.5"),
            (-0.0, "0"),
            (1e-9, "0"),
            (123456789012345.0, "123456789012345"),
            (1e15, "1e15"),
            (-1e200, "-1e200"),
            (1.2345678e100, "1.234568e100"),
            (f64::INFINITY, "∞"),
        ];
        for (x, shown) in cases {
            assert_eq!(num(x), shown, "{x:e}");
        }
    }

    /// Lengths too small for six decimals keep their digits; a point given keeps every
    /// coordinate, a point found drops only the rounding of a zero, 10¹² times below the
    /// numbers it was found from.
    #[test]
    fn small_lengths_and_points_keep_their_digits() {
        let cases = [
            (5.119556e-10, "5.11956e-10"),
            (-6e-10, "-6e-10"),
            (0.4, "0.4"),
            (0.0, "0"),
            (4e-7, "4e-7"),
            (6e-7, "0.000001"),
        ];
        for (x, shown) in cases {
            assert_eq!(length(x), shown, "{x:e}");
        }
        assert_eq!(point(DVec3::new(0.0, 0.0, -6e-10)), "(0, 0, -6e-10)");
        let near_origin = DVec3::new(4.44e-16, -8.88e-16, 0.0);
        assert_eq!(point_at(near_origin, 4.0 + 4.0), "(0, 0, 0)");
        // A secondary ray's origin moved off its surface by the bias, in a scene of size 5.
        assert_eq!(
            point_at(DVec3::new(4.4e-16, 3.46e-10, 0.0), 5.0),
            "(0, 0, 0)"
        );
        assert_eq!(length_at(5.119556e-10, 6e-10), "5.11956e-10");
        assert_eq!(point(DVec3::new(-1e100, 3.0, 0.0)), "(-1e100, 3, 0)");
        assert_eq!(
            point_at(DVec3::new(1e-17, 0.6, -0.8), 0.8),
            "(0, 0.6, -0.8)"
        );
        assert_eq!(
            point_at(DVec3::new(3e-11, -3e-11, 9e-11), 6e-10),
            "(3e-11, -3e-11, 9e-11)"
        );
    }
}
