//! Scan conversion counted (seed 004, ray tracing against rasterisation): the fragments of
//! hand-worked triangles, and the numbers lesson 11 states for its torus.

mod common;

use common::{scene, scene_file};
use raytree::lessons::raster::{raster_work, RasterWork};
use raytree::scene::Search;
use raytree::stats::Stats;

/// A 4 × 4 image of the square [−1, 1]² at distance 1 (fov 90): pixel centres at x, y in
/// {±0.25, ±0.75}, one per pixel.
fn square(triangles: &[[[f64; 2]; 3]]) -> RasterWork {
    let objects: String = triangles
        .iter()
        .enumerate()
        .map(|(k, t)| {
            format!(
                "  - {{ name: t{k}, triangle: [[{}, {}, 0], [{}, {}, 0], [{}, {}, 0]], material: m }}\n",
                t[0][0], t[0][1], t[1][0], t[1][1], t[2][0], t[2][1]
            )
        })
        .collect();
    raster_work(&scene(&format!(
        "camera: {{ eye: [0, 0, -1], look_at: [0, 0, 0], up: [0, 1, 0], fov: 90, width: 4, height: 4 }}
materials:
  m: {{ kd: 1 }}
objects:
{objects}"
    )))
}

#[test]
fn a_triangle_covers_the_pixel_centres_inside_it_and_a_shared_edge_counts_once() {
    // The lower-left half x + y < 0 holds 6 centres, and 4 lie on the diagonal.
    let lower = square(&[[[-1.0, -1.0], [1.0, -1.0], [-1.0, 1.0]]]);
    let upper = square(&[[[1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]]]);
    assert_eq!(lower.fragments + upper.fragments, 16);
    assert!([6, 10].contains(&lower.fragments), "{lower:?}");
    let both = square(&[
        [[-1.0, -1.0], [1.0, -1.0], [-1.0, 1.0]],
        [[1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]],
    ]);
    assert_eq!((both.fragments, both.covered_pixels), (16, 16));
    // Seen from z = −1 the first winding faces +z, away from the eye; reversed, it faces it.
    assert_eq!((lower.back_facing, lower.front_fragments), (1, 0));
    let reversed = square(&[[[-1.0, -1.0], [-1.0, 1.0], [1.0, -1.0]]]);
    assert_eq!(reversed.front_fragments, lower.fragments);
    // Four triangles whose shared edges run through pixel centres (x = 0.25, y = −0.25):
    // every centre once, none twice.
    let quads = square(&[
        [[-1.0, -1.0], [0.25, -1.0], [0.25, -0.25]],
        [[-1.0, -1.0], [0.25, -0.25], [-1.0, 1.0]],
        [[0.25, -0.25], [0.25, -1.0], [1.0, -1.0]],
        [[0.25, -0.25], [1.0, -1.0], [1.0, 1.0]],
        [[0.25, -0.25], [1.0, 1.0], [-1.0, 1.0]],
    ]);
    assert_eq!((quads.fragments, quads.covered_pixels), (16, 16));
    // A triangle behind the eye is not rasterised.
    let behind = raster_work(&scene(
        "camera: { eye: [0, 0, -1], look_at: [0, 0, 0], up: [0, 1, 0], fov: 90, width: 4, height: 4 }
materials:
  m: { kd: 1 }
objects:
  - { name: t, triangle: [[-1, -1, -2], [1, -1, -2], [-1, 1, -2]], material: m }
",
    ));
    assert_eq!((behind.clipped, behind.fragments), (1, 0));
}

#[test]
fn the_torus_of_lesson_11_as_lesson_11_counts_it() {
    let s = scene_file("lessons/11-triangles/torus.yaml");
    let w = raster_work(&s);
    // The numbers lesson 11 states.
    assert_eq!(
        w,
        RasterWork {
            triangles: 2304,
            back_facing: 1216,
            clipped: 0,
            fragments: 9412,
            front_fragments: 4706,
            covered_pixels: 4706,
        }
    );
    // The pixels the rasteriser covers are the pixels whose primary ray hits the torus.
    let mut stats = Stats::default();
    let hit = (0..s.camera.height)
        .flat_map(|y| (0..s.camera.width).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            s.nearest(&s.camera.pixel_ray(x, y), 0.0, f64::INFINITY, &mut stats)
                .is_some()
        })
        .count() as u64;
    assert_eq!(hit, w.covered_pixels);
}
