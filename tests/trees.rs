//! Pinned outputs: ray trees (text and JSON) and CSG segment lists (text and JSON).
//! Each snapshot was read and checked by hand against the formulas before it was accepted.

use std::path::Path;

use glam::DVec3;
use raytree::geometry::Ray;
use raytree::scene::{load, Limits, Scene};
use raytree::trace::{text, Tracer};

fn scene(rel: &str) -> Scene {
    load(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join(rel),
        &Limits::default(),
    )
    .unwrap()
}

/// Glass in front of a mirror: shadow, reflection and refraction nodes, and a total internal
/// reflection inside the glass.
#[test]
fn glass_in_front_of_a_mirror() {
    let s = scene("lessons/examples/glass-mirror.yaml");
    let inspection = Tracer::new(&s).inspect_pixel(16, 10);
    let json = serde_json::to_string_pretty(&inspection).unwrap();
    assert!(json.contains("\"total_internal_reflection\""));
    assert!(json.contains("\"object\": \"mirror\""));
    insta::assert_snapshot!("glass_mirror_text", text::tree(&inspection.tree));
    insta::assert_snapshot!("glass_mirror_json", json);
}

/// Past the limiting angle the glass (kr = 0.1, kt = 0.8) sends one mirror ray for both
/// shares: its reflection ray, of weight w·(0.1 + 0.8), whose intensity the refraction node
/// (ended by total internal reflection, without a child of its own) receives too. Every such
/// surface in every pixel of the scene.
#[test]
fn past_the_limiting_angle_one_mirror_ray_carries_both_shares() {
    use raytree::trace::tree::{RayKind, RayNode, Termination};
    fn check(n: &RayNode, found: &mut usize) {
        let tir = n.children.iter().find(|c| {
            c.kind == RayKind::Refraction
                && c.terminated == Some(Termination::TotalInternalReflection)
        });
        if let Some(tir) = tir {
            *found += 1;
            assert!(tir.children.is_empty(), "no second mirror ray");
            let reflection = n
                .children
                .iter()
                .find(|c| c.kind == RayKind::Reflection)
                .expect("the glass reflects");
            assert_eq!(reflection.coefficient, 0.1);
            let weight = n.weight * 0.9;
            assert!((reflection.weight - weight).abs() <= 1e-15 * weight);
            assert_eq!(tir.color, reflection.color, "the same ray's intensity");
        }
        for c in &n.children {
            check(c, found);
        }
    }
    let s = scene("lessons/examples/glass-mirror.yaml");
    let mut tracer = Tracer::new(&s);
    let mut found = 0;
    for y in 0..s.camera.height {
        for x in 0..s.camera.width {
            check(&tracer.inspect_pixel(x, y).tree, &mut found);
        }
    }
    assert!(found > 200, "{found} surfaces past the limiting angle");
}

/// A glossy floor: its reflection is a cone of 4 sampled rays, the cone's intensity their
/// mean, each ray weighted 1/4.
#[test]
fn a_glossy_cone() {
    let s = scene("tests/scenes/explorer-glossy.yaml");
    let inspection = Tracer::new(&s).inspect_pixel(20, 26);
    let json = serde_json::to_string_pretty(&inspection).unwrap();
    assert!(json.contains("\"samples\": 4"));
    insta::assert_snapshot!("glossy_cone_text", text::tree(&inspection.tree));
}

fn csg_outputs(s: &Scene, ray: &Ray) -> (String, String) {
    let traces = s.csg_traces(ray, true);
    let text: Vec<String> = traces
        .iter()
        .map(|(n, t)| format!("object {n}\n{}", text::csg_trace(s, ray, t)))
        .collect();
    let json: Vec<serde_json::Value> = traces
        .iter()
        .map(|(n, t)| serde_json::json!({ "object": n, "node": raytree::cli::csg::trace_json(s, ray, t) }))
        .collect();
    (
        text.join("\n"),
        serde_json::to_string_pretty(&json).unwrap(),
    )
}

/// Seed 000's four expressions (and the leaves), on the notes' ray; (B − A) ∩ C shows the
/// intersection pruned after its empty first operand.
#[test]
fn seed_000_csg_text_and_json() {
    let s = scene("lessons/10-csg/scene.yaml");
    let ray = Ray::new(DVec3::new(0.0, 0.0, -10.0), DVec3::Z);
    let (text, json) = csg_outputs(&s, &ray);
    assert!(text.contains("pruned: an earlier operand of the intersection is empty"));
    insta::assert_snapshot!("csg_seed_text", text);
    insta::assert_snapshot!("csg_seed_json", json);
}

/// A transformed CSG node (the lens, rotated and moved) along the ray through its centre.
#[test]
fn transformed_lens_segments() {
    let s = scene("lessons/examples/csg.yaml");
    let ray = Ray::new(DVec3::new(0.0, 1.3, -8.0), DVec3::Z);
    let o = s.object_index("lens").unwrap();
    let (list, trace) = s.object_trace(o, &ray, true);
    // The lens is 0.8 thick along its axis, rotated 15° about y: along z the ray crosses the
    // two spherical caps; both sphere centres lie on the rotated axis at ±1.6.
    assert_eq!(list.len(), 1);
    let thickness = list[0].t_out - list[0].t_in;
    // Independent: the ray through the lens centre along z, at 15° to the axis, meets sphere
    // "front" (centre c1 = 1.6·(sin15°, 0, cos15°)) and "back" (c2 = −c1), radius 2.
    let a = 15f64.to_radians();
    let c1 = DVec3::new(1.6 * a.sin(), 0.0, 1.6 * a.cos());
    // The lens is front ∩ back: it starts at the later of the two entries and ends at the
    // earlier of the two exits.
    let entry = {
        let hit = |c: DVec3| {
            let b = DVec3::Z.dot(-c);
            let disc = b * b - (c.length_squared() - 4.0);
            (-b - disc.sqrt(), -b + disc.sqrt())
        };
        let (f0, f1) = hit(c1);
        let (b0, b1) = hit(-c1);
        (f0.max(b0), f1.min(b1))
    };
    assert!(
        (thickness - (entry.1 - entry.0)).abs() < 1e-12,
        "{thickness} vs {:?}",
        entry
    );
    insta::assert_snapshot!("csg_lens_text", text::csg_trace(&s, &ray, &trace));
}

/// The tree of a pixel through the lens: it enters the glass (1 → 1.5) and leaves it (1.5 → 1).
#[test]
fn a_ray_through_the_lens_enters_and_leaves_the_glass() {
    let s = scene("lessons/examples/csg.yaml");
    let ray = Ray::new(DVec3::new(0.0, 1.3, -8.0), DVec3::Z);
    let tree = Tracer::new(&s).inspect(&ray);
    let hit = tree.hit.as_ref().unwrap();
    assert_eq!(hit.object, "lens");
    assert!(!hit.csg_path.is_empty());
    let inside = tree.find("refraction").unwrap();
    assert_eq!(inside.indices.map(|i| (i.n1, i.n2)), Some((1.0, 1.5)));
    assert_eq!(inside.hit.as_ref().unwrap().object, "lens");
    assert!(inside.hit.as_ref().unwrap().inside);
    let out = inside.find("refraction").unwrap();
    assert_eq!(out.indices.map(|i| (i.n1, i.n2)), Some((1.5, 1.0)));
}
