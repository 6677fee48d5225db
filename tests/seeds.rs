//! The worked examples of the lecture notes (../shared/seeds), reproduced through the library.

mod common;

use common::scene;

use std::path::Path;

use glam::DVec3;
use raytree::geometry::Ray;
use raytree::scene::Limits;
use raytree::scene::Search;
use raytree::stats::Stats;
use raytree::trace::{text, Tracer};

const SEED_000_CSG: &str = r#"
camera: { eye: [0, 0, -10], look_at: [0, 0, 0], width: 8, height: 8 }
materials: { m: { kd: 1 } }
objects:
  - name: A+B+C
    union:
      - { name: A, sphere: { center: [0, 0, 8], radius: 5 } }
      - { name: B, sphere: { center: [0, 0, 9], radius: 3 } }
      - { name: C, sphere: { center: [0, -3, 8], radius: 2 } }
    material: m
  - name: A-B
    difference:
      - { name: A, sphere: { center: [0, 0, 8], radius: 5 } }
      - { name: B, sphere: { center: [0, 0, 9], radius: 3 } }
    material: m
  - name: (B-A)∩C
    intersection:
      - difference:
          - { name: B, sphere: { center: [0, 0, 9], radius: 3 } }
          - { name: A, sphere: { center: [0, 0, 8], radius: 5 } }
      - { name: C, sphere: { center: [0, -3, 8], radius: 2 } }
    material: m
  - name: A+(B∩C)
    union:
      - { name: A, sphere: { center: [0, 0, 8], radius: 5 } }
      - intersection:
          - { name: B, sphere: { center: [0, 0, 9], radius: 3 } }
          - { name: C, sphere: { center: [0, -3, 8], radius: 2 } }
    material: m
"#;

/// Seed 000: the viewpoint (0, 0, −10), the ray through (0, 0, 0), and the notes' answers.
#[test]
fn seed_000_csg_segment_lists() {
    let s = scene(SEED_000_CSG);
    let ray = Ray::new(DVec3::new(0.0, 0.0, -10.0), DVec3::Z);
    let lists: Vec<Vec<(f64, f64)>> = (0..4)
        .map(|o| {
            s.object_trace(o, &ray, false)
                .0
                .iter()
                .map(|g| (g.t_in, g.t_out))
                .collect()
        })
        .collect();
    assert_eq!(lists[0], vec![(13.0, 23.0)]);
    assert_eq!(lists[1], vec![(13.0, 16.0), (22.0, 23.0)]);
    assert_eq!(lists[2], vec![]);
    assert_eq!(lists[3], vec![(13.0, 23.0)]);
    let shown: String = s
        .csg_traces(&ray, true)
        .iter()
        .map(|(name, t)| format!("object {name}\n{}", text::csg_trace(&s, &ray, t)))
        .collect::<Vec<_>>()
        .join("\n");
    insta::assert_snapshot!("seed_000_csg", shown);
}

/// Seed 004: P = (−3, 1), d = (0.8, −0.6) against the unit circle: a tangent, double root t = 3.
#[test]
fn seed_004_tangent_ray_is_a_double_root() {
    let s = scene(
        "camera: { eye: [0, 0, -10], look_at: [0, 0, 0] }\nmaterials: { m: { kd: 1 } }\nobjects: [ { name: circle, sphere: { center: [0, 0, 0], radius: 1 }, material: m } ]",
    );
    let ray = Ray::new(DVec3::new(-3.0, 1.0, 0.0), DVec3::new(0.8, -0.6, 0.0));
    let hit = s
        .nearest(&ray, 0.0, f64::INFINITY, &mut Stats::default())
        .expect("tangent hit");
    assert!((hit.t - 3.0).abs() < 1e-12);
    let p = ray.at(hit.t);
    assert!((p - DVec3::new(-0.6, -0.8, 0.0)).length() < 1e-12);
}

/// The ray tree of the lecture's pixel-intensity exercise (lesson 08), pinned as text.
#[test]
fn seed_004_pixel_intensity_ray_tree() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/08-pixel-intensity");
    let lesson = raytree::lessons::Lesson::load(&dir).unwrap();
    let ex = lesson.exercise("pixel-p").unwrap();
    let worked = raytree::lessons::work(&lesson, ex).unwrap();
    insta::assert_snapshot!("pixel_intensity_tree", text::tree(&worked.tree));
    let explained = raytree::lessons::explain(&lesson, ex).unwrap().join("\n");
    insta::assert_snapshot!("pixel_intensity_explained", explained);
}

/// Inspecting a pixel runs the renderer's own computation: the root colour is the rendered
/// pixel, bit for bit, in every lesson scene.
#[test]
fn inspected_root_equals_rendered_pixel_in_every_lesson() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
    let mut checked = 0;
    for entry in std::fs::read_dir(root).unwrap() {
        let dir = entry.unwrap().path();
        if !dir.is_dir() {
            continue; // lessons/README.md, the coverage table
        }
        for f in std::fs::read_dir(&dir).unwrap() {
            let path = f.unwrap().path();
            if path.extension().is_none_or(|e| e != "yaml") || path.ends_with("exercises.yaml") {
                continue;
            }
            let mut s = raytree::scene::load(&path, &Limits::default()).unwrap();
            // The claim is about the Whitted tracer; a path-traced pixel is a random estimate
            // that no single tree describes (tests/montecarlo.rs covers those scenes).
            if s.integrator == raytree::scene::Integrator::Path {
                continue;
            }
            s.spp = 1;
            // One centre ray per pixel: adaptive antialiasing would average the corners.
            s.antialias = raytree::scene::Antialias::Grid;
            let small = s
                .camera
                .resized(s.camera.width.min(40), s.camera.height.min(30));
            s.camera = small;
            let (image, _) =
                raytree::render::render_simple(&s, raytree::render::RenderOptions::of(&s));
            let mut tracer = Tracer::new(&s);
            for y in (0..s.camera.height).step_by(3) {
                for x in (0..s.camera.width).step_by(3) {
                    let tree = tracer.inspect_pixel(x, y).tree;
                    assert_eq!(
                        tree.color,
                        image.get(x, y),
                        "{} pixel {x},{y}",
                        path.display()
                    );
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 1000);
}
