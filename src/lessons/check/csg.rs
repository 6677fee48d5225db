//! CSG questions: the segment list of an object along the ray, combined bottom-up through the
//! object's tree of unions, intersections and differences.

use super::{Mistake, Question, Traced, Worked};
use crate::lessons::{Answer, Exercise};
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
