//! The scaling sweep: how the time per ray grows with the number of objects, with and without
//! the BVH (seed 002's O(n·p) → O(p·log n)).

use std::sync::Arc;
use std::time::Instant;

use glam::DVec3;

use super::error::BenchError;
use crate::geometry::{Mesh, Shape};
use crate::render::{render_simple, RenderOptions};
use crate::scene::{parse, Accel, Limits, Scene};

/// One line of the scaling table.
#[derive(Clone, Debug)]
pub struct Row {
    /// The scene: `spheres` or `mesh`.
    pub kind: &'static str,
    /// Its size: the number of spheres, or of the mesh's triangles.
    pub n: usize,
    /// Seconds to parse and compile the scene, BVH included.
    pub build: f64,
    /// Nanoseconds per ray with the BVH (None where the scene is too small to get one).
    pub bvh_ns: Option<f64>,
    /// Nanoseconds per ray testing everything (None when skipped as too slow).
    pub brute_ns: Option<f64>,
    /// BVH nodes visited per ray, on average.
    pub nodes_per_ray: f64,
    /// Primitives tested for a hit per ray with the BVH, on average.
    pub prims_per_ray: f64,
    /// A mesh's heap bytes per triangle: vertices, triangles and its BVH (None for spheres).
    pub bytes_per_triangle: Option<f64>,
}

const HEADER: &str =
    "camera: { eye: [0, 0, -40], look_at: [0, 0, 0], fov: 40, width: 160, height: 120 }\n\
    background: 0.2\nambient: 0.2\nmax_depth: 1\n\
    lights: [ { point: [20, 30, -30], intensity: 1 } ]\n\
    materials: { m: { ka: 0.2, kd: 0.8 } }\nobjects:\n";

/// N spheres at quasi-random places in a cube of side 20; their total volume stays fixed, so
/// the image looks alike for every N.
pub fn spheres(n: usize) -> String {
    let mut yaml = String::from(HEADER);
    let r = 6.0 / (n as f64).cbrt();
    for i in 0..n {
        // The R3 low-discrepancy sequence: well spread, deterministic.
        let g = 1.220_744_084_605_759_5_f64;
        let k = i as f64 + 1.0;
        let c = DVec3::new(
            (k / g).fract(),
            (k / (g * g)).fract(),
            (k / (g * g * g)).fract(),
        ) * 20.0
            - 10.0;
        yaml.push_str(&format!(
            "  - {{ sphere: {{ center: [{}, {}, {}], radius: {r} }}, material: m }}\n",
            c.x, c.y, c.z
        ));
    }
    yaml
}

/// An icosphere mesh of 20·4^k triangles filling the view.
pub fn mesh(subdivisions: u32) -> String {
    format!("{HEADER}  - {{ icosphere: {{ subdivisions: {subdivisions} }}, material: m, transform: [ {{ scale: 10 }} ] }}\n")
}

fn time_per_ray(scene: &Scene) -> (f64, crate::stats::Stats) {
    let start = Instant::now();
    let (_, stats) = render_simple(
        scene,
        RenderOptions {
            max_depth: 1,
            spp: 1,
            seed: 0,
            antialias: Default::default(),
            engine: Default::default(),
        },
    );
    (
        start.elapsed().as_secs_f64() * 1e9 / stats.rays() as f64,
        stats,
    )
}

/// Measures one scene with the BVH and (when `brute` is true) without.
pub fn measure(kind: &'static str, n: usize, yaml: &str, brute: bool) -> Result<Row, BenchError> {
    let start = Instant::now();
    let mut scene = parse(yaml, kind, None, &Limits::default())?;
    let build = start.elapsed().as_secs_f64();
    let mesh_bytes: usize = meshes(&scene).map(|m| m.memory().total()).sum();
    let bytes_per_triangle = (mesh_bytes > 0).then(|| mesh_bytes as f64 / n as f64);
    let (default_ns, stats) = time_per_ray(&scene);
    // A scene's BVH or a mesh's own: either is entered by every ray.
    let bvh_ns = (stats.bvh_nodes_visited > 0).then_some(default_ns);
    let rays = stats.rays() as f64;
    // Without a BVH the default search is already brute force: measured once.
    let brute_ns = match bvh_ns {
        None => Some(default_ns),
        Some(_) => brute.then(|| {
            scene.set_accel(Accel::None);
            time_per_ray(&scene).0
        }),
    };
    Ok(Row {
        kind,
        n,
        build,
        bvh_ns,
        brute_ns,
        nodes_per_ray: stats.bvh_nodes_visited as f64 / rays,
        prims_per_ray: stats.primitives_tested as f64 / rays,
        bytes_per_triangle,
    })
}

/// The scene's triangle meshes, each once.
fn meshes(scene: &Scene) -> impl Iterator<Item = &Mesh> {
    let mut seen = vec![];
    scene
        .leaves
        .iter()
        .filter_map(move |leaf| match &leaf.shape {
            Shape::Mesh(m) if !seen.iter().any(|s| Arc::ptr_eq(s, m)) => {
                seen.push(m.clone());
                Some(&**m)
            }
            _ => None,
        })
}

/// The scaling table: its header and a line per row.
pub fn table(rows: &[Row]) -> String {
    let mut s = table_header();
    for r in rows {
        s.push_str(&table_row(r));
    }
    s
}

/// The scaling table's header line, for printing the rows one at a time as they are measured.
pub fn table_header() -> String {
    format!(
        "{:<8} {:>9} {:>10} {:>14} {:>16} {:>8} {:>12} {:>12} {:>10}\n",
        "scene",
        "N",
        "load s",
        "BVH ns/ray",
        "brute ns/ray",
        "ratio",
        "nodes/ray",
        "prims/ray",
        "bytes/tri"
    )
}

/// One line of the scaling table; the brute-force columns read `(skipped)` when not measured,
/// the BVH's `(no BVH)` when the scene has too few objects to get one.
pub fn table_row(r: &Row) -> String {
    let bvh = r.bvh_ns.map_or("(no BVH)".into(), |t| format!("{t:.0}"));
    let brute = r.brute_ns.map_or("(skipped)".into(), |b| format!("{b:.0}"));
    let ratio = match (r.brute_ns, r.bvh_ns) {
        (Some(b), Some(t)) => format!("{:.1}×", b / t),
        _ => "".into(),
    };
    let bytes = r
        .bytes_per_triangle
        .map_or("".into(), |b| format!("{b:.1}"));
    format!(
        "{:<8} {:>9} {:>10.3} {:>14} {:>16} {:>8} {:>12.1} {:>12.1} {:>10}\n",
        r.kind, r.n, r.build, bvh, brute, ratio, r.nodes_per_ray, r.prims_per_ray, bytes
    )
}
