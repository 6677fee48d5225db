//! CSG questions: the segment list of an object along the ray, combined bottom-up through the
//! object's tree of unions, intersections and differences; and how many of its leaves are
//! evaluated at all, the rest skipped by pruning or by bounding boxes.

use super::{Mistake, Question, Traced, Worked};
use crate::geometry::csg::CsgTrace;
use crate::geometry::Ray;
use crate::lessons::{Answer, Exercise};
use crate::scene::Scene;
use crate::trace::{text, RayNode};

pub(super) struct Segments;

impl Question for Segments {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        let ex = q.ex;
        let id = &ex.id;
        let name = ex
            .object
            .as_deref()
            .ok_or_else(|| format!("exercise `{id}` needs `object`"))?;
        let o = q
            .scene
            .object_index(name)
            .ok_or_else(|| format!("exercise `{id}`: no object `{name}`"))?;
        let (list, _) = q.scene.object_trace(o, q.ray, false);
        // A segment that ends behind the ray's origin is not on the ray.
        Ok(Answer::Segments(
            list.iter()
                .filter(|s| s.t_out >= 0.0)
                .map(|s| (s.t_in, s.t_out))
                .collect(),
        ))
    }

    /// The lecture draws CSG along the z axis; a student may read the z-coordinates of the
    /// points off the drawing instead of the ray's t.
    fn mistakes(&self, w: &Worked, _ex: &Exercise) -> Vec<Mistake> {
        let Answer::Segments(list) = &w.expected else {
            return Vec::new();
        };
        let z = |t: f64| w.ray.at(t).z;
        vec![Mistake {
            answer: Answer::Segments(list.iter().map(|(a, b)| (z(*a), z(*b))).collect()),
            hint: format!(
                "those are the z-coordinates of the points: a segment list holds the ray's parameters t (distances from its origin along it; here z = {} + {}·t)",
                text::num(w.ray.origin.z),
                text::num(w.ray.dir.z)
            ),
        }]
    }

    fn explain(&self, w: &Worked, ex: &Exercise, _n: &RayNode) -> Result<Vec<String>, String> {
        let name = ex.object.as_deref().unwrap_or("");
        let Some(o) = w.scene.object_index(name) else {
            return Ok(Vec::new());
        };
        let (_, t) = w.scene.object_trace(o, &w.ray, false);
        let mut out = vec![
            format!(
                "ray {} → {}",
                text::vec3(w.ray.origin),
                text::vec3(w.ray.dir)
            ),
            "segment lists, combined bottom-up:".to_string(),
        ];
        out.extend(
            text::csg_trace(&w.scene, &w.ray, &t)
                .lines()
                .map(str::to_string),
        );
        Ok(out)
    }
}

pub(super) struct LeavesEvaluated;

/// The leaves of a traced CSG tree whose segment lists were computed.
fn evaluated(t: &CsgTrace) -> usize {
    match (t.leaf, &t.pruned) {
        (_, Some(_)) => 0,
        (Some(_), None) => 1,
        (None, None) => t.children.iter().map(evaluated).sum(),
    }
}

/// The exercise's object, traced with pruning and bounding boxes as rendering does.
fn traced(scene: &Scene, ray: &Ray, ex: &Exercise) -> Result<CsgTrace, String> {
    let id = &ex.id;
    let name = ex
        .object
        .as_deref()
        .ok_or_else(|| format!("exercise `{id}` needs `object`"))?;
    let o = scene
        .object_index(name)
        .ok_or_else(|| format!("exercise `{id}`: no object `{name}`"))?;
    Ok(scene.object_trace(o, ray, true).1)
}

fn leaves(t: &CsgTrace) -> usize {
    match t.leaf {
        Some(_) => 1,
        None => t.children.iter().map(leaves).sum(),
    }
}

impl Question for LeavesEvaluated {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        let t = traced(q.scene, q.ray, q.ex)?;
        Ok(Answer::Number(evaluated(&t) as f64))
    }

    fn mistakes(&self, w: &Worked, ex: &Exercise) -> Vec<Mistake> {
        let Ok(t) = traced(&w.scene, &w.ray, ex) else {
            return Vec::new();
        };
        let all = w
            .scene
            .object_index(ex.object.as_deref().unwrap_or(""))
            .map(|o| w.scene.object_trace(o, &w.ray, false).1);
        let mut tries = vec![Mistake {
            answer: Answer::Number(leaves(&t) as f64),
            hint: "that is every leaf of the tree: a subtree whose bounding box the ray misses, or the other operand of an empty intersection or of a difference with an empty left side, is never evaluated".into(),
        }];
        if let Some(all) = all {
            tries.push(Mistake {
                answer: Answer::Number(evaluated(&all) as f64),
                hint: "that counts pruning alone: the bounding boxes skip more (a subtree whose box the ray misses is an empty list without any test of its leaves)".into(),
            });
        }
        tries
    }

    fn explain(&self, w: &Worked, ex: &Exercise, _n: &RayNode) -> Result<Vec<String>, String> {
        let t = traced(&w.scene, &w.ray, ex)?;
        let mut out = vec![format!(
            "ray {} → {}; the tree, evaluated depth first with pruning and bounding boxes:",
            text::vec3(w.ray.origin),
            text::vec3(w.ray.dir)
        )];
        out.extend(
            text::csg_trace(&w.scene, &w.ray, &t)
                .lines()
                .map(str::to_string),
        );
        out.push(format!(
            "leaves whose segment lists are computed: {} of {}",
            evaluated(&t),
            leaves(&t)
        ));
        Ok(out)
    }
}
