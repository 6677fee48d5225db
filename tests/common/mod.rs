//! Helpers shared by the integration tests (each test binary uses some of them).
#![allow(dead_code)]

pub mod tmux;

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::Child;
use std::thread::JoinHandle;

use proptest::prelude::*;
use raytree::scene::{parse, Limits, Scene};

/// Points the explorer's data folder (answers marked right) at one of this test binary's own,
/// not the user's (set once per test process).
pub fn private_data() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let dir = std::env::temp_dir().join(format!("raytree-tests-{}", std::process::id()));
        std::env::set_var("RAYTREE_DATA", dir);
    });
}

/// A scene from YAML text; a test scene that does not parse is a bug in the test.
pub fn scene(yaml: &str) -> Scene {
    parse(yaml, "test.yaml", None, &Limits::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// The refractions along a ray tree's chain of refraction rays: for each surface crossed,
/// the object's name and the indices n1 → n2 its refraction ray names.
pub fn refraction_crossings(tree: &raytree::trace::RayNode) -> Vec<(String, f64, f64)> {
    let mut node = tree;
    let mut crossings = vec![];
    while let Some(next) = node
        .children
        .iter()
        .find(|c| c.kind == raytree::trace::RayKind::Refraction)
    {
        let i = next.indices.expect("a refraction ray names its media");
        crossings.push((node.hit.as_ref().unwrap().object.clone(), i.n1, i.n2));
        node = next;
    }
    crossings
}

/// A scene file of the project (path relative to its root).
pub fn scene_file(path: &str) -> Scene {
    raytree::scene::load(Path::new(path), &Limits::default()).unwrap_or_else(|e| panic!("{e}"))
}

/// A scene file of the project, its image resized (the camera's aspect kept by the caller).
pub fn scene_file_resized(path: &str, width: u32, height: u32) -> Scene {
    let mut s = scene_file(path);
    s.camera = s.camera.resized(width, height);
    s
}

/// Every scene file of every lesson (`lessons/*/*.yaml` but the exercises).
pub fn lesson_scene_files() -> Vec<PathBuf> {
    let mut out = vec![];
    for lesson in std::fs::read_dir("lessons").unwrap() {
        let dir = lesson.unwrap().path();
        if !dir.is_dir() {
            continue;
        }
        for f in std::fs::read_dir(&dir).unwrap() {
            let p = f.unwrap().path();
            let yaml = p.extension().is_some_and(|e| e == "yaml");
            if yaml && p.file_name().is_some_and(|n| n != "exercises.yaml") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// A scene of the 10 000-sphere peer scene's kind: n small spheres in a grid over a plane
/// (every third a mirror), lit by two lights; enough spheres for a BVH.
pub fn many_spheres(n: usize) -> String {
    let side = (n as f64).sqrt().ceil() as usize;
    let mut yaml = String::from(
        "camera: { eye: [0, 30, -60], look_at: [0, 0, 0], fov: 45, width: 32, height: 24 }
max_depth: 5
ambient: 0.1
lights:
  - { name: key, point: [40, 60, -40] }
  - { name: fill, point: [-50, 40, -30], intensity: 0.4 }
materials:
  floor: { color: [0.8, 0.8, 0.8], ka: 0.1, kd: 0.7 }
  matte: { color: [0.7, 0.3, 0.2], ka: 0.1, kd: 0.8, ks: 0.3, shininess: 30 }
  mirror: { color: [0.9, 0.9, 0.9], ka: 0.05, kd: 0.2, ks: 0.6, shininess: 100, kr: 0.6 }
objects:
  - { name: floor, plane: { point: [0, -1, 0], normal: [0, 1, 0] }, material: floor }
",
    );
    for k in 0..n {
        let (i, j) = (k % side, k / side);
        let x = (i as f64 - side as f64 / 2.0) * 0.6;
        let z = (j as f64 - side as f64 / 2.0) * 0.6;
        let m = if k % 3 == 0 { "mirror" } else { "matte" };
        yaml.push_str(&format!(
            "  - {{ name: s{k}, sphere: {{ center: [{x:.3}, 0, {z:.3}], radius: 0.25 }}, material: {m} }}\n"
        ));
    }
    yaml
}

pub fn random_scene(objects: &[(u8, [f64; 3], f64)]) -> Scene {
    let mut yaml = String::from(
        "camera: { eye: [0, 0, -30], look_at: [0, 0, 0], width: 24, height: 18 }\nambient: 0.1\nmax_depth: 3\nlights: [ { point: [10, 20, -20] } ]\nmaterials: { m: { ka: 0.2, kd: 0.6, kr: 0.3 } }\nobjects:\n",
    );
    yaml.push_str(
        "  - { name: floor, plane: { point: [0, -12, 0], normal: [0, 1, 0] }, material: m }\n",
    );
    for (i, (kind, c, r)) in objects.iter().enumerate() {
        let [x, y, z] = c;
        let shape = match kind % 4 {
            0 => format!("sphere: {{ center: [{x}, {y}, {z}], radius: {r} }}"),
            1 => format!(
                "box: {{ min: [{}, {}, {}], max: [{}, {}, {}] }}",
                x - r,
                y - r,
                z - r,
                x + r,
                y + r,
                z + r
            ),
            2 => format!(
                "cylinder: {{ base: [{x}, {y}, {z}], top: [{}, {}, {z}], radius: {} }}",
                x + r,
                y + r,
                r / 2.0
            ),
            _ => format!(
                "cone: {{ apex: [{x}, {}, {z}], base: [{x}, {y}, {z}], radius: {r} }}",
                y + 2.0 * r
            ),
        };
        yaml.push_str(&format!("  - {{ name: o{i}, {shape}, material: m }}\n"));
    }
    parse(&yaml, "random.yaml", None, &Limits::default()).unwrap()
}

pub fn objects() -> impl Strategy<Value = Vec<(u8, [f64; 3], f64)>> {
    prop::collection::vec(
        (
            any::<u8>(),
            prop::array::uniform3(-10.0..10.0f64),
            0.2..2.0f64,
        ),
        8..120,
    )
}

/// The child's standard output and error, each read to its end on a thread of its own (so that
/// a chatty child cannot block on a full pipe while the test waits for it to exit); join them
/// once it has. A pipe that was not captured reads as "".
pub fn drain_output(child: &mut Child) -> (JoinHandle<String>, JoinHandle<String>) {
    fn drain(pipe: Option<impl Read + Send + 'static>) -> JoinHandle<String> {
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            if let Some(mut p) = pipe {
                let _ = p.read_to_end(&mut bytes);
            }
            String::from_utf8_lossy(&bytes).into_owned()
        })
    }
    (drain(child.stdout.take()), drain(child.stderr.take()))
}
