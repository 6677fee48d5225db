//! What a class relies on (issue 28): the CSG trace says truthfully why each node was skipped
//! and lists the objects it culled, and a soft shadow says how many of its rays got through.

use std::path::Path;
use std::process::Command;

use raytree::geometry::csg::{CsgTrace, Pruned};
use raytree::geometry::Ray;
use raytree::scene::{Limits, Scene};
use raytree::trace::{text, RayKind, RayNode, Tracer};

fn scene(path: &str) -> Scene {
    raytree::scene::load(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join(path),
        &Limits::default(),
    )
    .unwrap()
}

fn raytree(args: &[&str]) -> String {
    let o = Command::new(env!("CARGO_BIN_EXE_raytree"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8(o.stdout).unwrap()
}

/// The lecture's CSG ray: from the eye (0, 0, −10) along +z.
fn csg_ray() -> Ray {
    Ray::new(glam::DVec3::new(0.0, 0.0, -10.0), glam::DVec3::Z)
}

fn find<'t>(t: &'t CsgTrace, name: &str) -> Option<&'t CsgTrace> {
    if t.node == name {
        return Some(t);
    }
    t.children.iter().find_map(|c| find(c, name))
}

/// Defect 1: in A + (B ∩ C) the ray misses the box of B ∩ C (C lies below the ray), so the
/// intersection is skipped; B is skipped with it, but the ray runs straight through B
/// (centre (0, 0, 9), radius 3: t from 16 to 22), so "the ray misses its bounding box" would
/// be false of B.
#[test]
fn a_node_skipped_with_its_parent_says_so() {
    let s = scene("lessons/10-csg/scene.yaml");
    let traces = s.csg_traces(&csg_ray(), false);
    let (_, t) = traces.iter().find(|(n, _)| n == "Aplus_BcapC").unwrap();
    let cap = &t.children[1];
    assert_eq!(cap.pruned, Some(Pruned::Bounds));
    let b = find(cap, "B").unwrap();
    assert_eq!(b.pruned, Some(Pruned::ParentPruned));
    let out = raytree(&["csg", "lessons/10-csg/scene.yaml", "--ray", "0,0,-10:0,0,1"]);
    let b_line = out
        .lines()
        .skip_while(|l| !l.contains("union Aplus_BcapC"))
        .find(|l| l.contains("sphere B"))
        .unwrap();
    assert!(!b_line.contains("misses its bounding box"), "{b_line}");
    assert!(b_line.contains("its parent was pruned"), "{b_line}");
}

/// Whenever a node is said to be skipped because the ray misses its bounding box, the ray
/// really misses its shape: checked for every leaf of every lesson's CSG objects along the
/// lecture's ray and the rays of the CSG exercises.
#[test]
fn every_bounding_box_reason_is_true() {
    fn check(s: &Scene, ray: &Ray, t: &CsgTrace, errors: &mut Vec<String>) {
        if let (Some(Pruned::Bounds), Some(leaf)) = (t.pruned, t.leaf) {
            let list = s.leaves[leaf as usize].segments(leaf, ray);
            if !list.is_empty() {
                errors.push(format!("{} said missed but the ray meets it", t.node));
            }
        }
        for c in &t.children {
            check(s, ray, c, errors);
        }
    }
    let mut errors = vec![];
    for file in ["lessons/10-csg/scene.yaml", "lessons/10-csg/algebra.yaml"] {
        let s = scene(file);
        for ray in [
            csg_ray(),
            Ray::new(glam::DVec3::new(0.0, -3.0, -10.0), glam::DVec3::Z),
        ] {
            for (_, t) in s.csg_traces(&ray, false) {
                check(&s, &ray, &t, &mut errors);
            }
        }
    }
    assert!(errors.is_empty(), "{errors:?}");
}

/// Defect 2: (B − A) ∩ C is culled along the lecture's ray (its box, the boxes of B and C
/// overlapped, lies below y = −1), and the listing says so instead of leaving it out.
#[test]
fn culled_objects_are_listed_with_the_reason() {
    let out = raytree(&["csg", "lessons/10-csg/scene.yaml", "--ray", "0,0,-10:0,0,1"]);
    let line = out
        .lines()
        .find(|l| l.contains("BminusA_cap_C"))
        .unwrap_or_else(|| panic!("BminusA_cap_C not listed:\n{out}"));
    assert!(line.contains("culled"), "{line}");
    assert!(line.contains("bounding box"), "{line}");
    // C is a plain sphere the ray misses (centre (0, −3, 8), radius 2): listed as missed.
    assert!(
        out.lines()
            .any(|l| l.contains("misses") && l.contains(" C")),
        "{out}"
    );
    // With --all every object is evaluated and shown with its segment lists.
    let all = raytree(&[
        "csg",
        "lessons/10-csg/scene.yaml",
        "--ray",
        "0,0,-10:0,0,1",
        "--all",
    ]);
    assert!(all.contains("object BminusA_cap_C"), "{all}");
}

fn shadow_nodes(n: &RayNode, out: &mut Vec<RayNode>) {
    for c in &n.children {
        if c.kind == RayKind::Shadow {
            out.push(c.clone());
        }
        shadow_nodes(c, out);
    }
}

/// Defect 3: at P = (0, 0, 0), right under the sphere light whose centre is above the shelf's
/// edge x = 0, half of the 4 × 4 shadow rays are blocked (lesson 14's README: s = 8/16 = 0.5).
/// The tree must not say "blocked" as if all were.
#[test]
fn a_soft_shadow_says_how_many_rays_got_through() {
    let s = scene("lessons/14-monte-carlo-glossy/scene.yaml");
    let ray = Ray::new(
        glam::DVec3::new(0.0, 1.0, -1.0),
        glam::DVec3::new(0.0, -1.0, 1.0),
    );
    let tree = Tracer::new(&s).inspect(&ray);
    let mut shadows = vec![];
    shadow_nodes(&tree, &mut shadows);
    let bulb = shadows
        .iter()
        .find(|n| n.light.as_deref() == Some("bulb"))
        .unwrap();
    assert_eq!(bulb.shadow, Some(0.5));
    let title = text::node_title(bulb);
    assert!(title.contains("partly blocked"), "{title}");
    assert!(title.contains("8 of 16 clear"), "{title}");
}

/// Along pixel (83, 77) of lesson 10 the ray misses B and meets A and C. In (B − A) ∩ C the
/// empty B leaves A and C untried: the object is listed with its tree, which says they were
/// pruned and why, not as an object whose parts the ray meets none of.
#[test]
fn an_object_emptied_by_pruning_is_listed_with_its_tree() {
    let out = raytree(&["csg", "lessons/10-csg/scene.yaml", "--pixel", "83,77"]);
    let (_, object) = out
        .split_once("object BminusA_cap_C\n")
        .unwrap_or_else(|| panic!("BminusA_cap_C not listed with its tree:\n{out}"));
    let tree: Vec<&str> = object.lines().take_while(|l| !l.is_empty()).collect();
    assert!(
        tree[0].starts_with("intersection BminusA_cap_C: (empty)"),
        "{out}"
    );
    let said = |leaf: &str, why: &str| {
        tree.iter()
            .any(|l| l.contains(&format!("sphere {leaf}: pruned: {why}")))
    };
    assert!(
        said("A", "the left operand of the difference is empty"),
        "{out}"
    );
    assert!(
        said("C", "an earlier operand of the intersection is empty"),
        "{out}"
    );
    assert!(!out.contains("meets none of its parts"), "{out}");
}

/// The hint for a coordinate counted from the wrong end (1 − v) names the shape's own v: a
/// cylinder's runs up its axis (lesson 16's can: v = (w·a)/h = 0.5/2 = 0.25, so 0.75 is that
/// mistake), with no sphere's pole; a plane's v is a distance, with no end to count from.
#[test]
fn the_one_minus_v_hint_is_the_shapes_own() {
    // A wrong answer exits 1, with the verdict on stdout.
    let check = |exercise: &str, answer: &str| {
        let args = [
            "check",
            "16-textures",
            "--exercise",
            exercise,
            "--answer",
            answer,
        ];
        let o = Command::new(env!("CARGO_BIN_EXE_raytree"))
            .args(args)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(1), "{args:?}");
        String::from_utf8(o.stdout).unwrap()
    };
    let can = check("can-v", "0.75");
    assert!(can.contains("hint: v runs up the axis"), "{can}");
    assert!(!can.contains("pole"), "{can}");
    let wall = check("wall-v", "0.4");
    assert!(wall.starts_with("wrong"), "{wall}");
    assert!(!wall.contains("pole"), "{wall}");
}
