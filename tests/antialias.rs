//! Antialiasing (seed 004's supersampling; POV-Ray's adaptive method): where primary rays go,
//! what they cost, and how close each mode comes to the exact pixel coverage.

mod common;

use common::scene;

use std::sync::atomic::AtomicBool;

use glam::DVec3;
use raytree::render::film::Film;
use raytree::render::{render, render_simple, Image, RenderOptions};
use raytree::scene::{parse, Limits, Scene};
use raytree::scene::{Antialias, Filter};

/// A white triangle on black, lit only by the ambient term (so a pixel's exact value is the
/// fraction of it the triangle covers): slanted edges, the worst case for a regular grid.
fn edges() -> Scene {
    scene(
        "camera: { eye: [0, 0, -10], look_at: [0, 0, 0], fov: 30, width: 24, height: 16 }\n\
         background: 0\nambient: 1\n\
         materials: { white: { color: 1, ka: 1 } }\n\
         objects:\n  - { name: tri, triangle: [[-2.3, -1.7, 0], [2.9, -0.9, 0], [-0.4, 2.1, 0]], material: white }\n",
    )
}

fn options(s: &Scene, spp: u32, antialias: Antialias, seed: u64) -> RenderOptions {
    RenderOptions {
        spp,
        antialias,
        seed,
        ..RenderOptions::of(s)
    }
}

/// The RMSE over all pixels and channels, as `raytree bench` reports it.
fn rmse(a: &Image, b: &Image) -> f64 {
    raytree::bench::errors(a, b).0
}

/// The converged coverage: a 32 × 32 grid in every pixel.
fn reference(s: &Scene) -> Image {
    render_simple(s, options(s, 1024, Antialias::Grid, 0)).0
}

#[test]
fn a_flat_image_costs_adaptive_antialiasing_only_its_corners() {
    let s = scene(
        "camera: { eye: [0, 0, -10], look_at: [0, 0, 0], fov: 30, width: 20, height: 10 }\n\
         background: 0.5\n",
    );
    let (image, stats) = render_simple(
        &s,
        options(&s, 16, Antialias::Adaptive { threshold: 0.1 }, 0),
    );
    // (w + 1)(h + 1) corners, shared by neighbouring pixels, and nothing split.
    assert_eq!(stats.primary_rays, 21 * 11);
    assert_eq!(stats.aa_splits, 0);
    assert!(image.pixels.iter().all(|p| *p == DVec3::splat(0.5)));
}

#[test]
fn adaptive_antialiasing_approaches_the_full_grid_for_a_fraction_of_the_rays() {
    let s = edges();
    let exact = reference(&s);
    let (centre, _) = render_simple(&s, options(&s, 1, Antialias::Grid, 0));
    let (grid, grid_stats) = render_simple(&s, options(&s, 64, Antialias::Grid, 0));
    let (adaptive, adaptive_stats) = render_simple(
        &s,
        options(&s, 64, Antialias::Adaptive { threshold: 0.1 }, 0),
    );
    let (e_centre, e_grid, e_adaptive) = (
        rmse(&centre, &exact),
        rmse(&grid, &exact),
        rmse(&adaptive, &exact),
    );
    // Supersampling cuts the one-ray error several times over.
    assert!(e_grid < 0.1 * e_centre, "{e_grid} vs {e_centre}");
    assert!(e_adaptive < 0.2 * e_centre, "{e_adaptive} vs {e_centre}");
    // Adaptive sampling (up to 8 × 8 squares) reaches about the error of a 4 × 4 grid with
    // less than half its rays. It cannot reach the 8 × 8 grid: an edge that clips a pixel
    // without separating two of its corners is never seen (POV-Ray's method shares this).
    let (grid16, grid16_stats) = render_simple(&s, options(&s, 16, Antialias::Grid, 0));
    let e_grid16 = rmse(&grid16, &exact);
    assert!(e_adaptive < 1.25 * e_grid16, "{e_adaptive} vs {e_grid16}");
    assert!(
        adaptive_stats.primary_rays * 2 < grid16_stats.primary_rays,
        "{} vs {} rays",
        adaptive_stats.primary_rays,
        grid16_stats.primary_rays
    );
    assert!(adaptive_stats.primary_rays * 8 < grid_stats.primary_rays);
    assert!(adaptive_stats.aa_splits > 0);
}

#[test]
fn a_lower_threshold_splits_more_and_errs_less() {
    // A dim grey triangle (edges of contrast 3 × 0.2 = 0.6) beside a white one (contrast 3).
    let s = scene(
        "camera: { eye: [0, 0, -10], look_at: [0, 0, 0], fov: 30, width: 24, height: 16 }\n\
         background: 0\nambient: 1\n\
         materials: { white: { color: 1, ka: 1 }, grey: { color: 0.2, ka: 1 } }\n\
         objects:\n  - { triangle: [[-2.3, -1.7, 0], [0.2, -0.9, 0], [-0.4, 2.1, 0]], material: white }\n  \
         - { triangle: [[0.5, -1.5, 0], [2.9, -0.2, 0], [0.9, 2.0, 0]], material: grey }\n",
    );
    let exact = reference(&s);
    let run = |t: f64| render_simple(&s, options(&s, 64, Antialias::Adaptive { threshold: t }, 0));
    // 0.9 splits only at the white triangle's edges, 0.3 at the grey one's too.
    let (loose, loose_stats) = run(0.9);
    let (tight, tight_stats) = run(0.3);
    assert!(
        tight_stats.aa_splits > loose_stats.aa_splits + 20,
        "{} vs {}",
        tight_stats.aa_splits,
        loose_stats.aa_splits
    );
    assert!(tight_stats.primary_rays > loose_stats.primary_rays);
    let (e_loose, e_tight) = (rmse(&loose, &exact), rmse(&tight, &exact));
    assert!(e_tight < 0.8 * e_loose, "{e_tight} vs {e_loose}");
}

#[test]
fn jittered_sampling_is_unbiased() {
    // The mean over many seeds of a 4-sample jittered image is the exact coverage, within
    // its standard error, pixel by pixel.
    let s = edges();
    let exact = reference(&s);
    let runs = 96;
    let images: Vec<Image> = (0..runs)
        .map(|seed| render_simple(&s, options(&s, 4, Antialias::Jittered, seed)).0)
        .collect();
    let mut worst: f64 = 0.0;
    for (i, e) in exact.pixels.iter().enumerate() {
        let values: Vec<f64> = images.iter().map(|im| im.pixels[i].x).collect();
        let mean = values.iter().sum::<f64>() / runs as f64;
        let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (runs - 1) as f64;
        // A 32 × 32 reference is itself off by up to ~1/64 on an edge pixel.
        let se = (var / runs as f64).sqrt() + 1.0 / 64.0;
        worst = worst.max((mean - e.x).abs() / se);
    }
    assert!(worst < 4.5, "worst |z| = {worst}");
}

#[test]
fn a_lone_pixel_equals_the_rendered_one_in_every_mode() {
    let mut s = edges();
    for (antialias, filter) in [
        (Antialias::Grid, Filter::Box),
        (Antialias::Jittered, Filter::Box),
        (Antialias::Adaptive { threshold: 0.2 }, Filter::Box),
        (Antialias::Grid, Filter::Gaussian),
        (Antialias::Jittered, Filter::Gaussian),
    ] {
        s.filter = filter;
        let o = options(&s, 16, antialias, 7);
        let (image, _) = render_simple(&s, o);
        let film = Film::new(&s, o);
        for y in 0..s.camera.height {
            for x in 0..s.camera.width {
                let lone = film.lone_pixel(&mut film.tracer(), x, y);
                assert_eq!(lone, image.pixels[(y * s.camera.width + x) as usize]);
            }
        }
    }
}

#[test]
fn every_mode_gives_the_same_image_on_one_and_two_threads() {
    let mut s = edges();
    for (antialias, filter) in [
        (Antialias::Jittered, Filter::Box),
        (Antialias::Adaptive { threshold: 0.2 }, Filter::Box),
        (Antialias::Jittered, Filter::Gaussian),
    ] {
        s.filter = filter;
        let o = options(&s, 16, antialias, 3);
        let on = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| render(&s, o, &|_| {}, &AtomicBool::new(false)).unwrap().0)
        };
        assert_eq!(on(1), on(2), "{antialias:?}");
    }
}

#[test]
fn the_scene_file_and_the_flag_choose_the_mode() {
    let s = scene(
        "camera: { eye: [0, 0, -10], look_at: [0, 0, 0], width: 4, height: 4 }\n\
         spp: 16\nantialias: adaptive\naa_threshold: 0.05\n",
    );
    assert_eq!(s.antialias, Antialias::Adaptive { threshold: 0.05 });
    assert_eq!(RenderOptions::of(&s).antialias, s.antialias);
    let err = parse(
        "camera: { eye: [0, 0, -10], look_at: [0, 0, 0] }\naa_threshold: 7\n",
        "aa.yaml",
        None,
        &Limits::default(),
    )
    .unwrap_err()
    .to_string();
    assert!(
        err.contains("aa.yaml:2:15") && err.contains("aa_threshold"),
        "{err}"
    );
}

#[test]
fn the_gaussian_filter_keeps_a_flat_image_flat_and_softens_an_edge() {
    let flat = scene(
        "camera: { eye: [0, 0, -10], look_at: [0, 0, 0], width: 9, height: 7 }\n\
         background: 0.25\nspp: 4\nfilter: gaussian\n",
    );
    let (image, _) = render_simple(&flat, RenderOptions::of(&flat));
    // Σ w·L / Σ w of equal values, corners and edges (fewer neighbours) included.
    assert!(image
        .pixels
        .iter()
        .all(|p| (*p - DVec3::splat(0.25)).abs().max_element() < 1e-15));
    // Across an edge the filter mixes in the neighbours: a pixel fully inside the triangle but
    // next to its edge is no longer exactly 1, and the image is smoother than the box's.
    let mut s = edges();
    let (boxed, _) = render_simple(&s, options(&s, 16, Antialias::Grid, 0));
    s.filter = Filter::Gaussian;
    let (soft, _) = render_simple(&s, options(&s, 16, Antialias::Grid, 0));
    let roughness = |im: &Image| {
        let w = im.width as usize;
        im.pixels
            .windows(2)
            .enumerate()
            .filter(|(i, _)| (i + 1) % w != 0)
            .map(|(_, p)| (p[1] - p[0]).abs().x)
            .fold(0.0, f64::max)
    };
    assert!(
        roughness(&soft) < 0.8 * roughness(&boxed),
        "{} vs {}",
        roughness(&soft),
        roughness(&boxed)
    );
}

/// Mitsuba's Gaussian filter, f(x) = exp(−x²/2σ²) − exp(−r²/2σ²) for |x| < r, σ = ½ pixel,
/// r = 2 pixels (written here from its definition), applied to a straight edge: a pixel
/// centred at c, with the scene lit below the edge at y0, has the value ∫ f(x)·[c + x > y0] dx
/// / ∫ f(x) dx (the filter is separable and the scene constant along the edge).
fn filtered_step(c: f64, y0: f64) -> f64 {
    let (sigma, r) = (0.5, 2.0);
    let f =
        |x: f64| (-x * x / (2.0 * sigma * sigma)).exp() - (-r * r / (2.0 * sigma * sigma)).exp();
    let n = 200_000;
    let dx = 2.0 * r / n as f64;
    let (mut lit, mut all) = (0.0, 0.0);
    for i in 0..n {
        let x = -r + (i as f64 + 0.5) * dx;
        all += f(x);
        if c + x > y0 {
            lit += f(x);
        }
    }
    lit / all
}

/// A white box on black (ambient only: a pixel's value is what the filter sees of it) whose
/// top edge lies at row 7.7 of a 16 × 16 image, above the eye, so that only its front face
/// shows: the rows around the edge take the values of the filtered step, 0.345 on the edge's
/// row and 0.945 below it, where a box filter would give 0.3 and 1. Averaged along the edge,
/// jittered 256 samples a pixel.
#[test]
fn the_gaussian_filter_blurs_an_edge_as_the_filtered_step_predicts() {
    let y0 = 7.7;
    // Row y0 of a 16-row image with a vertical field of view of 30°, seen at distance 10.
    let edge = (1.0 - y0 / 8.0) * 10.0 * 15f64.to_radians().tan();
    let s = scene(&format!(
        "camera: {{ eye: [0, 0, -10], look_at: [0, 0, 0], fov: 30, width: 16, height: 16 }}\n\
         background: 0\nambient: 1\nfilter: gaussian\n\
         materials: {{ white: {{ color: 1, ka: 1 }} }}\n\
         objects:\n  - {{ box: {{ min: [-100, -100, 0], max: [100, {edge}, 1] }}, material: white }}\n"
    ));
    let (image, _) = render_simple(&s, options(&s, 256, Antialias::Jittered, 3));
    for row in 5..12 {
        let mean = (0..16).map(|x| image.pixels[row * 16 + x].x).sum::<f64>() / 16.0;
        let expected = filtered_step(row as f64 + 0.5, y0);
        assert!(
            (mean - expected).abs() < 0.01,
            "row {row}: {mean} against {expected}"
        );
    }
    assert!((filtered_step(7.5, y0) - 0.345).abs() < 0.001);
    assert!((filtered_step(8.5, y0) - 0.945).abs() < 0.001);
}
