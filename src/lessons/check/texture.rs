//! Texture questions: the texture coordinates (u, v) of a hit, and the surface's colour O there
//! (a pattern's or a texture's value), worked out from the hit point in the object's own space.

use std::f64::consts::PI;

use glam::{DVec2, DVec3};

use super::{Mistake, Question, Traced, Worked};
use crate::geometry::uv::Edges;
use crate::geometry::Shape;
use crate::lessons::{Answer, Exercise};
use crate::scene::Leaf;
use crate::shading::pattern::{cell, Kind};
use crate::shading::texture::{Image, Mapping};
use crate::shading::Pattern;
use crate::trace::tree::HitInfo;
use crate::trace::{text, RayNode};

/// u or v of the hit's texture coordinates.
pub(super) struct TextureCoordinate {
    pub v: bool,
}

impl Question for TextureCoordinate {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        let uv = q.hit()?.uv.ok_or_else(|| {
            format!(
                "exercise `{}`: the hit's material has no texture or uv pattern",
                q.ex.id
            )
        })?;
        Ok(Answer::Number(if self.v { uv.y } else { uv.x }))
    }

    /// 1 − u or 1 − v: the coordinate counted from the wrong end, said in the terms of the
    /// shape hit (a plane's coordinates are distances, with no end to count from).
    fn mistakes(&self, w: &Worked, ex: &Exercise) -> Vec<Mistake> {
        let Answer::Number(x) = w.expected else {
            return vec![];
        };
        let shape = w
            .tree
            .find(&ex.node)
            .and_then(|n| n.hit.as_ref())
            .and_then(|h| leaf(w, h))
            .map(|l| &l.shape);
        let hint = match (shape, self.v) {
            (Some(Shape::Sphere(_)), true) => {
                "v runs up: v = 1 − φ/π is 0 at the bottom (the south pole, φ = π) and 1 at the top"
            }
            (Some(Shape::Sphere(_)), false) => {
                "u runs the other way round: u = 1 − (θ/2π + ½), with θ = atan2(d.x, d.z)"
            }
            (Some(Shape::Cylinder(_) | Shape::OpenCylinder(_)), true) => {
                "v runs up the axis: v = (w·a)/h is 0 at the base and 1 at the top"
            }
            (Some(Shape::Cylinder(_) | Shape::OpenCylinder(_)), false) => {
                "u runs the other way round: u = 1 − (θ/2π + ½), with θ = atan2(w.x, w.z), w = p − base"
            }
            _ => return vec![],
        };
        // On the seam (u = 0) the other end is u = 1 itself: the formula is right, its wrap is
        // not.
        let hint = if x == 0.0 && !self.v {
            "u = 1 is u = 0 on the seam: the sign of a zero in atan2 gives θ = ±π there, and \
             raytree wraps u into [0, 1)"
        } else {
            hint
        };
        vec![Mistake {
            answer: Answer::Number(1.0 - x),
            hint: hint.into(),
        }]
    }

    fn explain(&self, w: &Worked, _ex: &Exercise, n: &RayNode) -> Result<Vec<String>, String> {
        let h = hit(n)?;
        let mut out = hit_lines(n, h);
        out.extend(own_uv(w, h));
        out.extend(lookups(n));
        Ok(out)
    }
}

/// O at the hit: the value of the material's colour pattern or texture there.
pub(super) struct SurfaceColor;

impl Question for SurfaceColor {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        let local = q
            .node
            .local
            .as_ref()
            .ok_or_else(|| format!("exercise `{}`: the ray hits nothing", q.ex.id))?;
        let color = local
            .color
            .ok_or_else(|| format!("exercise `{}`: the hit's material has no pattern", q.ex.id))?;
        Ok(Answer::color(color))
    }

    fn mistakes(&self, w: &Worked, ex: &Exercise) -> Vec<Mistake> {
        // The pattern's other value: the cell counted wrong.
        let Some(n) = w.tree.find(&ex.node) else {
            return vec![];
        };
        let (Some(h), Some(local)) = (&n.hit, &n.local) else {
            return vec![];
        };
        let Some(Pattern::Placed(p)) = color_pattern(w, h) else {
            return vec![];
        };
        let values = match &p.kind {
            Kind::Stripes(v) | Kind::Rings(v) | Kind::Checker(v) => v,
            Kind::UvChecker { values, .. } => values,
            _ => return vec![],
        };
        let (Pattern::Constant(a), Pattern::Constant(b)) = (&values[0], &values[1]) else {
            return vec![];
        };
        let other = if Some(*a) == local.color { *b } else { *a };
        vec![Mistake {
            answer: Answer::color(other),
            hint: "the other cell: ⌊x⌋ of a negative x is the integer below it (⌊−0.3⌋ = −1), and the point is taken in the pattern's own space (through the inverse of its transform)".into(),
        }]
    }

    fn explain(&self, w: &Worked, _ex: &Exercise, n: &RayNode) -> Result<Vec<String>, String> {
        let h = hit(n)?;
        let mut out = hit_lines(n, h);
        if h.uv.is_some() {
            out.extend(own_uv(w, h));
        }
        if let (Some(Pattern::Placed(p)), Some(local)) = (color_pattern(w, h), &n.local) {
            let at = local.patterns.iter().find(|l| l.varies == "O");
            if let Some(at) = at {
                let uv_mapped = matches!(
                    p.kind,
                    Kind::Image {
                        mapping: Mapping::Uv,
                        ..
                    } | Kind::UvChecker {
                        mapping: Mapping::Uv,
                        ..
                    }
                );
                if !uv_mapped {
                    out.push(format!(
                        "in the pattern's own space (the object's, through the inverse of the pattern's transform): p = {}",
                        text::vec3(at.point)
                    ));
                }
                out.extend(cell_lines(&p.kind, at.point, at.uv, at.edges));
            }
        }
        out.extend(lookups(n));
        Ok(out)
    }
}

fn hit(n: &RayNode) -> Result<&HitInfo, String> {
    n.hit
        .as_ref()
        .ok_or_else(|| "the ray hits nothing".to_string())
}

fn hit_lines(n: &RayNode, h: &HitInfo) -> Vec<String> {
    vec![
        format!(
            "ray o = {}, d = {} (unit)",
            text::vec3(n.origin),
            text::vec3(n.direction)
        ),
        format!(
            "nearest hit on {} at t = {}: p = {}",
            h.leaf,
            text::num(h.t),
            text::vec3(h.point)
        ),
    ]
}

/// The leaf the hit is on.
fn leaf<'s>(w: &'s Worked, h: &HitInfo) -> Option<&'s Leaf> {
    w.scene.leaves.iter().find(|l| l.name == h.leaf)
}

/// The material's colour pattern, for a hit on it.
fn color_pattern<'s>(w: &'s Worked, h: &HitInfo) -> Option<&'s Pattern> {
    let m = w.scene.materials.iter().find(|m| m.name == h.material)?;
    m.patterns.as_ref()?.color.as_ref()
}

/// The shape's own (u, v), worked for a sphere, a cylinder and a plane.
fn own_uv(w: &Worked, h: &HitInfo) -> Vec<String> {
    let Some(l) = leaf(w, h) else {
        return vec![];
    };
    let p = l
        .transform
        .as_ref()
        .map_or(h.point, |tf| tf.to_local.transform_point3(h.point));
    let mut out = vec![];
    if l.transform.is_some() {
        out.push(format!(
            "in the object's own space (through the inverse of its transform): p = {}",
            text::vec3(p)
        ));
    }
    let angle = |x: f64, z: f64, out: &mut Vec<String>| {
        let theta = x.atan2(z);
        let u = 1.0 - (theta / (2.0 * PI) + 0.5);
        out.push(format!(
            "θ = atan2({}, {}) = {} rad;  u = 1 − (θ/2π + ½) = {}",
            text::num(x),
            text::num(z),
            text::num(theta),
            text::num(u - u.floor())
        ));
    };
    match &l.shape {
        Shape::Sphere(s) => {
            let d = (p - s.center) / s.radius;
            out.push(format!(
                "sphere c = {}, r = {}: the direction d = (p − c)/r = {}",
                text::vec3(s.center),
                text::num(s.radius),
                text::vec3(d)
            ));
            angle(d.x, d.z, &mut out);
            let phi = d.y.clamp(-1.0, 1.0).acos();
            out.push(format!(
                "φ = acos(d.y) = {} rad;  v = 1 − φ/π = {}",
                text::num(phi),
                text::num(1.0 - phi / PI)
            ));
        }
        Shape::Cylinder(c) | Shape::OpenCylinder(c) => {
            let w = p - c.base;
            let a = c.axis();
            let height = (c.top - c.base).length();
            out.push(format!(
                "cylinder from {} to {}: w = p − base = {}; up the axis w·a = {}",
                text::vec3(c.base),
                text::vec3(c.top),
                text::vec3(w),
                text::num(w.dot(a))
            ));
            if a == DVec3::Y {
                angle(w.x, w.z, &mut out);
            }
            out.push(format!(
                "v = (w·a)/h = {}/{} = {}",
                text::num(w.dot(a)),
                text::num(height),
                text::num(w.dot(a) / height)
            ));
        }
        Shape::Plane(s) => {
            let own = l.shape.uv(p, 0);
            out.push(format!(
                "plane through {} with normal {}: u and v are the distances from that point along the plane's axes (u along n × y, v along u × n): (u, v) = ({}, {})",
                text::vec3(s.point),
                text::vec3(s.normal),
                text::num(own.x),
                text::num(own.y)
            ));
        }
        _ => {}
    }
    if let Some(uv) = h.uv {
        out.push(format!(
            "the texture is read at (u, v) = ({}, {}){}",
            text::num(uv.x),
            text::num(uv.y),
            if placed(w, h) {
                ": the surface's (u, v) through the inverse of the pattern's transform"
            } else {
                ""
            }
        ));
    }
    out
}

/// Whether the material's colour pattern has a transform.
fn placed(w: &Worked, h: &HitInfo) -> bool {
    matches!(color_pattern(w, h), Some(Pattern::Placed(p)) if p.to_pattern.is_some())
}

/// The cell a point falls in, for the patterns made of cells.
fn cell_lines(kind: &Kind, p: DVec3, uv: Option<DVec2>, edges: Edges) -> Vec<String> {
    let parity = |n: f64| {
        if n.rem_euclid(2.0) == 0.0 {
            "even: the first value A"
        } else {
            "odd: the second value B"
        }
    };
    match kind {
        Kind::Checker(_) => {
            let (x, y, z) = (cell(p.x), cell(p.y), cell(p.z));
            vec![format!(
                "⌊x⌋ + ⌊y⌋ + ⌊z⌋ = {} + {} + {} = {}, {}",
                text::num(x),
                text::num(y),
                text::num(z),
                text::num(x + y + z),
                parity(x + y + z)
            )]
        }
        Kind::Stripes(_) => vec![format!(
            "⌊x⌋ = {}, {}",
            text::num(cell(p.x)),
            parity(cell(p.x))
        )],
        Kind::Rings(_) => {
            let r = (p.x * p.x + p.z * p.z).sqrt();
            vec![format!(
                "⌊√(x² + z²)⌋ = ⌊{}⌋ = {}, {}",
                text::num(r),
                text::num(cell(r)),
                parity(cell(r))
            )]
        }
        Kind::UvChecker { width, height, .. } => {
            let Some(uv) = uv else { return vec![] };
            let (a, b) = (cell(uv.x * width), cell(uv.y * height));
            vec![format!(
                "⌊u·{}⌋ + ⌊v·{}⌋ = ⌊{}⌋ + ⌊{}⌋ = {} + {} = {}, {}",
                text::num(*width),
                text::num(*height),
                text::num(uv.x * width),
                text::num(uv.y * height),
                text::num(a),
                text::num(b),
                text::num(a + b),
                parity(a + b)
            )]
        }
        Kind::Image { image, .. } => uv.map_or(vec![], |uv| bilinear_lines(image, uv, edges)),
        _ => vec![],
    }
}

/// Bilinear filtering of an image at (u, v), step by step.
fn bilinear_lines(image: &Image, uv: DVec2, edges: Edges) -> Vec<String> {
    let f = image.footprint(uv, edges);
    let t = |di: i64, dj: i64| image.texel(f.i + di, f.j + dj, edges);
    let (a, b, c, d) = (t(0, 0), t(1, 0), t(0, 1), t(1, 1));
    let top = a.lerp(b, f.fx);
    let bottom = c.lerp(d, f.fx);
    let (w, h) = (image.width as i64, image.height as i64);
    let at = |i: i64, j: i64| {
        let (i, j) = image.texel_at(i, j, edges);
        format!("({i}, {j})")
    };
    // Where the footprint reads the image, back from the grid of centres.
    let (u, v) = ((f.x + 0.5) / w as f64, 1.0 - (f.y + 0.5) / h as f64);
    let ends = match (edges.u, edges.v) {
        (false, false) => "",
        (false, true) => "; v runs from the image's bottom edge to its top here, so it does not wrap round them: the rows beyond are the edge's own",
        (true, false) => "; u runs from the image's left edge to its right here, so it does not wrap round them: the columns beyond are the edge's own",
        (true, true) => "; u and v run from edge to edge of the image here, so it does not wrap round them: the texels beyond are the edge's own",
    };
    vec![
        format!(
            "image {}, {}×{} texels (linear values, decoded from sRGB when it was read); it repeats, so (u, v) = ({}, {}) reads it at ({}, {}){ends}",
            image.name,
            w,
            h,
            text::num(uv.x),
            text::num(uv.y),
            text::num(u),
            text::num(v)
        ),
        format!(
            "among the texel centres: x = u·{w} − ½ = {}, y = (1 − v)·{h} − ½ = {} (columns from the left, rows from the top)",
            text::num(f.x),
            text::num(f.y)
        ),
        format!(
            "texels {} = {}, {} = {} (upper row), {} = {}, {} = {} (lower row); fx = {}, fy = {}",
            at(f.i, f.j),
            text::color(a),
            at(f.i + 1, f.j),
            text::color(b),
            at(f.i, f.j + 1),
            text::color(c),
            at(f.i + 1, f.j + 1),
            text::color(d),
            text::num(f.fx),
            text::num(f.fy)
        ),
        format!(
            "upper = {} + fx·({} − {}) = {};  lower = {} + fx·({} − {}) = {}",
            text::color(a),
            text::color(b),
            text::color(a),
            text::color(top),
            text::color(c),
            text::color(d),
            text::color(c),
            text::color(bottom)
        ),
        format!(
            "O = upper + fy·(lower − upper) = {}",
            text::color(top.lerp(bottom, f.fy))
        ),
    ]
}

/// The tree's record of every pattern looked up at the hit.
fn lookups(n: &RayNode) -> Vec<String> {
    let Some(local) = &n.local else {
        return vec![];
    };
    local
        .patterns
        .iter()
        .map(|p| {
            let at = match p.uv {
                Some(uv) => format!("(u, v) = ({}, {})", text::num(uv.x), text::num(uv.y)),
                None => format!("p = {}", text::vec3(p.point)),
            };
            format!(
                "{} = {} ({} at {at})",
                p.varies,
                text::color(p.value),
                p.pattern
            )
        })
        .collect()
}
