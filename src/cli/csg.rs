//! `raytree csg`: the segment lists at every node of every object a ray meets.

use std::process::ExitCode;

use serde_json::{json, Value};

use super::args::{Format, SceneArgs, Target};
use super::Failure;
use crate::geometry::csg::CsgTrace;
use crate::geometry::Ray;
use crate::scene::Scene;
use crate::trace::text;

#[derive(clap::Args, Debug)]
#[command(after_help = "Examples:
  raytree csg lessons/10-csg/scene.yaml --ray 0,0,-10:0,0,1
  raytree csg lessons/examples/csg.yaml --pixel 160,120 --all
  raytree csg lessons/10-csg/scene.yaml --ray 0,0,-10:0,0,1 --format json")]
/// The arguments of `raytree csg`.
pub(crate) struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    #[command(flatten)]
    target: Target,
    /// Show every object, and evaluate whole trees without bounding boxes, so only the
    /// notes' pruning rules (empty operands of ∩ and −) skip work.
    #[arg(long)]
    all: bool,
    /// Output: text to read, or JSON for programs.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
}

/// The JSON form of a CSG trace (`raytree csg --format json`): each node's name, operation or
/// shape, segment list (t values and points along `ray`) and why it was pruned, with its children.
pub fn trace_json(scene: &Scene, ray: &Ray, t: &CsgTrace) -> Value {
    let op = match (t.op, t.leaf) {
        (Some(op), _) => op.name(),
        (None, Some(leaf)) => scene.leaves[leaf as usize].shape.kind(),
        (None, None) => "group",
    };
    let point = |t: f64| {
        if t.is_finite() {
            json!(ray.at(t).to_array())
        } else {
            Value::Null
        }
    };
    let segments: Vec<Value> = t
        .segments
        .iter()
        .map(|s| json!({ "t_in": s.t_in, "t_out": s.t_out, "point_in": point(s.t_in), "point_out": point(s.t_out) }))
        .collect();
    let mut node = json!({
        "op": op,
        "name": t.node,
        "segments": segments,
        "pruned": t.pruned.is_some(),
        "children": t.children.iter().map(|c| trace_json(scene, ray, c)).collect::<Vec<_>>(),
    });
    if let Some(p) = t.pruned {
        node["pruned_reason"] = json!(p);
    }
    node
}

/// Where the ray crosses a surface at `t`: `{ "t", "point" }`.
fn hit_json(ray: &Ray, t: f64) -> Value {
    json!({ "t": t, "point": ray.at(t).to_array() })
}

/// Runs `raytree csg`: the CSG segment lists a ray meets, as a tree of text or as JSON.
pub(crate) fn run(a: Args) -> Result<ExitCode, Failure> {
    let scene = a.scene.load()?;
    let ray = a.target.ray(&scene)?;
    let survey = text::csg_survey(&scene, &ray, a.all);
    match a.format {
        Format::Json => {
            let doc = json!({
                "ray": { "origin": ray.origin.to_array(), "direction": ray.dir.to_array() },
                "objects": survey.met.iter().map(|m| json!({
                    "object": m.name,
                    "node": trace_json(&scene, &ray, &m.trace),
                    "hit": m.hit.map(|h| hit_json(&ray, h.t)),
                })).collect::<Vec<_>>(),
                "not_met": survey.unmet,
                "nearest": survey.nearest.as_ref().map(|(name, h)| {
                    let mut hit = hit_json(&ray, h.t);
                    hit["object"] = json!(name);
                    hit
                }),
            });
            super::output::print_json(doc)?;
        }
        Format::Text => {
            super::output::println(&format!(
                "ray {} → {}",
                text::point(ray.origin),
                text::vec3(ray.dir)
            ))?;
            if survey.met.is_empty() {
                super::output::println("the ray meets no object")?;
            }
            for m in &survey.met {
                super::output::println(&format!("\nobject {}", m.name))?;
                super::output::print(&text::csg_trace(&scene, &ray, &m.trace))?;
                super::output::println(&format!("→ {}", m.verdict(&ray)))?;
            }
            if !survey.unmet.is_empty() {
                super::output::println("")?;
            }
            for line in &survey.unmet {
                super::output::println(&line.to_string())?;
            }
            if survey.unmet.iter().any(|l| l.contains("culled")) {
                super::output::println(
                    "(--all evaluates every object whole, without bounding boxes)",
                )?;
            }
            // The last line is always the nearest hit, "none" included.
            super::output::println(&format!("\n{}", survey.nearest_line(&ray)))?;
        }
    }
    Ok(ExitCode::SUCCESS)
}
