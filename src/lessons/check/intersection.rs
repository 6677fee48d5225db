//! Intersection questions: where a ray meets a surface (t and the point), the normal there, and
//! a triangle hit's barycentric coordinates.

use glam::DVec3;

use super::tree::tree_explanation;
use super::{Mistake, Question, Traced, Worked};
use crate::geometry::{Ray, SegmentList, Shape, Sphere, Triangle};
use crate::lessons::{Answer, Exercise};
use crate::trace::tree::HitInfo;
use crate::trace::{text, RayNode};

const FAR_ROOT: &str = "you took the far root: the nearest hit is the smaller positive t";

pub(super) struct HitT;

impl Question for HitT {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        Ok(Answer::Number(q.hit()?.t))
    }

    fn mistakes(&self, w: &Worked, ex: &Exercise) -> Vec<Mistake> {
        far_exit(w, ex)
            .map(|(_, t)| Mistake {
                answer: Answer::Number(t),
                hint: FAR_ROOT.into(),
            })
            .into_iter()
            .collect()
    }

    fn explain(&self, w: &Worked, _ex: &Exercise, n: &RayNode) -> Result<Vec<String>, String> {
        Ok(nearest_hit(w, n))
    }
}

pub(super) struct HitPoint;

impl Question for HitPoint {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        Ok(Answer::Vector(q.hit()?.point))
    }

    fn mistakes(&self, w: &Worked, ex: &Exercise) -> Vec<Mistake> {
        far_exit(w, ex)
            .map(|(ray, t)| Mistake {
                answer: Answer::Vector(ray.at(t)),
                hint: FAR_ROOT.into(),
            })
            .into_iter()
            .collect()
    }

    fn explain(&self, w: &Worked, _ex: &Exercise, n: &RayNode) -> Result<Vec<String>, String> {
        Ok(nearest_hit(w, n))
    }
}

pub(super) struct Normal;

impl Question for Normal {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        Ok(Answer::Vector(q.hit()?.normal))
    }

    fn mistakes(&self, w: &Worked, _ex: &Exercise) -> Vec<Mistake> {
        let Answer::Vector(v) = &w.expected else {
            return Vec::new();
        };
        vec![Mistake {
            answer: Answer::Vector(-*v),
            hint: "the normal used for shading faces the incoming ray (flip it when the ray is inside)".into(),
        }]
    }

    fn explain(&self, w: &Worked, _ex: &Exercise, n: &RayNode) -> Result<Vec<String>, String> {
        Ok(nearest_hit(w, n))
    }
}

pub(super) struct Barycentric;

impl Question for Barycentric {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        let b = q
            .hit()?
            .barycentric
            .ok_or_else(|| format!("exercise `{}`: the hit is not on a triangle", q.ex.id))?;
        Ok(Answer::Vector(b))
    }

    fn explain(&self, w: &Worked, _ex: &Exercise, n: &RayNode) -> Result<Vec<String>, String> {
        let Some((h, b)) = n.hit.as_ref().and_then(|h| h.barycentric.map(|b| (h, b))) else {
            return Ok(tree_explanation(n));
        };
        let mut out = vec![format!(
            "ray o = {}, d = {} hits {} at t = {}, p = {}",
            text::vec3(n.origin),
            text::vec3(n.direction),
            h.leaf,
            text::num(h.t),
            text::vec3(h.point)
        )];
        let untransformed = w
            .scene
            .leaves
            .iter()
            .find(|l| l.name == h.leaf && l.transform.is_none());
        match untransformed.map(|l| &l.shape) {
            Some(Shape::Triangle(tri)) => out.extend(area_ratios(tri, h.point)),
            _ => out.push(format!("on a mesh triangle (a, b, c in the file's order): (λ1, λ2, λ3) = {}, p = λ1·a + λ2·b + λ3·c", text::vec3(b))),
        }
        Ok(out)
    }
}

/// Where the ray leaves the object whose entry is the nearest hit: the far root of its
/// equation, the answer of a student who took the wrong root.
fn far_exit(w: &Worked, ex: &Exercise) -> Option<(Ray, f64)> {
    let n = w.tree.find(&ex.node)?;
    let h = n.hit.as_ref()?;
    let (ray, list) = segments_of_hit(w, n, h)?;
    let s = list.iter().find(|s| (s.t_in - h.t).abs() < 1e-9)?;
    Some((ray, s.t_out))
}

/// The node's ray, and the segment list of the object its hit is on along that ray (the whole
/// object, without its bounding boxes).
fn segments_of_hit(w: &Worked, n: &RayNode, h: &HitInfo) -> Option<(Ray, SegmentList)> {
    let object = w.scene.object_index(&h.object)?;
    let ray = Ray {
        origin: n.origin,
        dir: n.direction,
    };
    let list = w.scene.object_trace(object, &ray, false).0;
    Some((ray, list))
}

/// The shape a hit is on, when it is written in world space (no transform), so that its
/// equation can be solved with the ray's own numbers.
fn untransformed_shape<'s>(w: &'s Worked, h: &HitInfo) -> Option<&'s Shape> {
    let leaf = w.scene.leaves.iter().find(|l| l.name == h.leaf)?;
    leaf.transform.is_none().then_some(&leaf.shape)
}

/// The nearest hit along the node's ray, with the sphere's quadratic solved when it is one.
fn nearest_hit(w: &Worked, n: &RayNode) -> Vec<String> {
    let mut out = vec![format!(
        "ray o = {}, d = {} (unit)",
        text::vec3(n.origin),
        text::vec3(n.direction)
    )];
    let Some(h) = &n.hit else {
        out.push("the ray hits nothing".into());
        return out;
    };
    let csg = !h.csg_path.is_empty();
    if csg {
        out.push(format!(
            "the hit is on {}, an operand of the CSG object {}: its own roots first",
            h.leaf, h.object
        ));
    }
    match untransformed_shape(w, h) {
        Some(Shape::Sphere(s)) => out.extend(sphere_roots(n, s, h.t)),
        _ => out.push(format!("nearest hit on {}: t = {}", h.leaf, text::num(h.t))),
    }
    if csg {
        out.extend(csg_hit(w, n, h));
    }
    out.push(format!("point p = o + t·d = {}", text::vec3(h.point)));
    out.push(format!(
        "unit normal facing the ray n = {}",
        text::vec3(h.normal)
    ));
    out
}

/// A CSG object's hit: its segment list along the ray, and which end of which segment is the
/// first past t = 0, entering the object or leaving it.
fn csg_hit(w: &Worked, n: &RayNode, h: &HitInfo) -> Vec<String> {
    let Some((ray, list)) = segments_of_hit(w, n, h) else {
        return vec![];
    };
    vec![
        format!(
            "{}'s segment list along the ray: {}",
            h.object,
            text::segment_list(&ray, &list)
        ),
        format!(
            "its first segment end past t = 0 is t = {}, where the ray {} {}",
            text::num(h.t),
            if h.inside { "leaves" } else { "enters" },
            h.object
        ),
    ]
}

/// The ray–sphere quadratic for a unit direction, its discriminant, and the root taken.
fn sphere_roots(n: &RayNode, s: &Sphere, t: f64) -> Vec<String> {
    // Lesson 02's names: a·t² + b·t + c = 0 with a = d·d, b = 2 d·(o − c), D = b² − 4ac.
    let oc = n.origin - s.center;
    let a = n.direction.length_squared();
    let b = 2.0 * n.direction.dot(oc);
    let c = oc.length_squared() - s.radius * s.radius;
    let disc = b * b - 4.0 * a * c;
    let tangent = if disc.abs() < 4e-9 * a {
        " (zero: the ray is tangent, a double root)"
    } else {
        ""
    };
    vec![
        format!(
            "sphere centre {}, r = {}: |o + t·d − centre|² = r², a·t² + b·t + c = 0",
            text::vec3(s.center),
            text::num(s.radius)
        ),
        format!(
            "a = d·d = {}, b = 2 d·(o − centre) = {}, c = |o − centre|² − r² = {}",
            text::num(a),
            text::num(b),
            text::num(c)
        ),
        format!("discriminant D = b² − 4ac = {}{tangent}", text::num(disc)),
        format!(
            "t = (−b ± √D)/2a → nearest positive root t = {}",
            text::num(t)
        ),
    ]
}

/// Barycentric coordinates as ratios of the areas of the sub-triangles facing each corner.
fn area_ratios(tri: &Triangle, p: DVec3) -> Vec<String> {
    let area = |a: DVec3, b: DVec3, c: DVec3| 0.5 * (b - a).cross(c - a).length();
    let whole = area(tri.a, tri.b, tri.c);
    let ratio = |name: &str, sub: &str, part: f64| {
        format!(
            "{name} = area({sub})/area(a, b, c) = {}/{} = {}",
            text::num(part),
            text::num(whole),
            text::num(part / whole)
        )
    };
    vec![
        format!(
            "a = {}, b = {}, c = {}; area(a, b, c) = {}",
            text::vec3(tri.a),
            text::vec3(tri.b),
            text::vec3(tri.c),
            text::num(whole)
        ),
        ratio("λ1", "p, b, c", area(p, tri.b, tri.c)),
        ratio("λ2", "a, p, c", area(tri.a, p, tri.c)),
        ratio("λ3", "a, b, p", area(tri.a, tri.b, p)),
        "check: λ1 + λ2 + λ3 = 1 and p = λ1·a + λ2·b + λ3·c".into(),
    ]
}
