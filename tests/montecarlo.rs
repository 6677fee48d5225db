//! The path tracer against closed-form answers (furnace tests), its own reference (convergence
//! at the 1/√N rate, next-event estimation unbiased) and thread counts (determinism).

mod common;

use common::scene;

use std::path::Path;

use glam::DVec3;
use raytree::render::{render_simple, Image, RenderOptions};
use raytree::sampling::{pixel_key, SamplePoint};
use raytree::scene::{load, Limits, Scene};
use raytree::stats::Stats;
use raytree::trace::path::PathTracer;

fn mean(img: &Image) -> DVec3 {
    img.pixels.iter().sum::<DVec3>() / img.pixels.len() as f64
}

/// How a pixel's samples draw their random numbers.
#[derive(Clone, Copy)]
enum Points {
    /// As the film does: sample i of the pixel is point i of the pixel's spread points.
    Spread,
    /// Plain Monte Carlo: every sample a point of its own, independent of the others.
    Independent,
}

/// Average radiance over the image with the given integrator switches.
fn estimate(s: &Scene, spp: u32, next_event: bool, roulette: bool, seed: u64) -> Image {
    estimate_with(s, spp, next_event, roulette, seed, Points::Spread)
}

fn estimate_with(
    s: &Scene,
    spp: u32,
    next_event: bool,
    roulette: bool,
    seed: u64,
    points: Points,
) -> Image {
    let tracer = PathTracer {
        next_event,
        roulette,
        ..PathTracer::new(s, s.max_depth)
    };
    let cam = &s.camera;
    let mut img = Image::new(cam.width, cam.height);
    for y in 0..cam.height {
        for x in 0..cam.width {
            let mut sum = DVec3::ZERO;
            for i in 0..spp {
                let point = match points {
                    Points::Spread => SamplePoint::new(pixel_key(seed, x, y), i),
                    Points::Independent => {
                        SamplePoint::new(pixel_key(seed << 32 | i as u64, x, y), 0)
                    }
                };
                // As the film takes them: pair 0 is the point in the pixel.
                let [u, v] = point.pair(0);
                let ray = cam.ray(x as f64 + u, y as f64 + v);
                sum += tracer.radiance(&ray, &point, &mut Stats::default());
            }
            img.pixels[(y * cam.width + x) as usize] = sum / spp as f64;
        }
    }
    img
}

#[test]
fn furnace_a_diffuse_sphere_under_uniform_light_shows_its_albedo() {
    // Every path off a convex diffuse sphere escapes after one bounce: exactly ρ·1.
    let s = scene(
        "integrator: path\ncamera: { eye: [0, 0, -4], look_at: [0, 0, 0], fov: 30, width: 16, height: 16 }\nbackground: 1\nmax_depth: 8\nmaterials: { m: { color: 1, kd: 0.6 } }\nobjects: [ { name: s, sphere: { center: [0, 0, 0], radius: 1 }, material: m } ]\n",
    );
    for (nee, rr) in [(true, true), (false, false)] {
        let img = estimate(&s, 4, nee, rr, 1);
        let center = img.get(8, 8);
        assert!(
            (center - DVec3::splat(0.6)).abs().max_element() < 1e-12,
            "{center}"
        );
        assert!((img.get(0, 0) - DVec3::ONE).abs().max_element() < 1e-12);
    }
}

#[test]
fn furnace_a_glowing_enclosure_converges_to_e_over_one_minus_rho() {
    // Inside a closed diffuse sphere of albedo ρ = 0.5 emitting E = 0.25 everywhere, every
    // bounce adds E: L = E(1 + ρ + ρ² + …) = E/(1 − ρ) = 0.5.
    let s = scene(
        "integrator: path\ncamera: { eye: [0, 0, 0], look_at: [0, 0, 1], fov: 60, width: 8, height: 8 }\nmax_depth: 64\nmaterials: { m: { color: 1, kd: 0.5, emission: 0.25 } }\nobjects: [ { name: room, sphere: { center: [0, 0, 0], radius: 5 }, material: m } ]\n",
    );
    for (nee, rr) in [(true, true), (false, true), (true, false)] {
        let m = mean(&estimate(&s, 256, nee, rr, 7));
        assert!((m.x - 0.5).abs() < 0.01, "nee {nee} rr {rr}: {m}");
    }
}

fn small_cornell() -> Scene {
    let mut s = load(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/examples/cornell.yaml"),
        &Limits::default(),
    )
    .unwrap();
    s.camera = s.camera.resized(24, 24);
    s.max_depth = 5;
    s
}

/// The RMSE over all pixels and channels, as `raytree bench` reports it.
fn rmse(a: &Image, b: &Image) -> f64 {
    raytree::bench::errors(a, b).0
}

/// Least-squares slope of log RMSE against log N.
fn slope(spps: &[u32], errors: &[f64]) -> f64 {
    let xs: Vec<f64> = spps.iter().map(|&n| (n as f64).ln()).collect();
    let ys: Vec<f64> = errors.iter().map(|e| e.ln()).collect();
    let k = xs.len() as f64;
    let (mx, my) = (xs.iter().sum::<f64>() / k, ys.iter().sum::<f64>() / k);
    xs.iter()
        .zip(&ys)
        .map(|(x, y)| (x - mx) * (y - my))
        .sum::<f64>()
        / xs.iter().map(|x| (x - mx).powi(2)).sum::<f64>()
}

/// Plain Monte Carlo's error falls as 1/√N; the film's spread points fall at least as fast
/// and lie below it at every N; and next-event estimation changes the noise, not the image.
#[test]
fn error_falls_as_one_over_root_n_and_next_event_estimation_is_unbiased() {
    let s = small_cornell();
    let reference = estimate(&s, 4096, true, true, 99);
    let spps = [16u32, 64, 256];
    // One RMSE is noisy (paths to a small bright light are heavy-tailed): pool six seeds.
    let errors = |points: Points| -> Vec<f64> {
        spps.iter()
            .map(|&n| {
                let mse: f64 = [5u64, 6, 7, 8, 9, 10]
                    .iter()
                    .map(|&seed| {
                        let image = estimate_with(&s, n, true, true, seed, points);
                        rmse(&image, &reference).powi(2)
                    })
                    .sum();
                (mse / 6.0).sqrt()
            })
            .collect()
    };
    let (independent, spread) = (errors(Points::Independent), errors(Points::Spread));
    let plain = slope(&spps, &independent);
    assert!(
        (-0.65..=-0.35).contains(&plain),
        "slope {plain}, errors {independent:?}"
    );
    assert!(
        slope(&spps, &spread) <= plain && spread.iter().zip(&independent).all(|(a, b)| a < b),
        "spread {spread:?}, independent {independent:?}"
    );
    // BSDF sampling alone converges to the same image: compare means within their noise.
    let without = mean(&estimate(&s, 512, false, true, 3));
    let with = mean(&reference);
    assert!(
        ((without - with).abs() / with).max_element() < 0.03,
        "{without} vs {with}"
    );
}

#[test]
fn path_traced_images_are_identical_for_one_and_two_threads() {
    let s = small_cornell();
    let options = RenderOptions {
        max_depth: 5,
        spp: 8,
        seed: 42,
        ..RenderOptions::of(&s)
    };
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| render_simple(&s, options).0);
    let two = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap()
        .install(|| render_simple(&s, options).0);
    assert_eq!(one, two);
    let other_seed = render_simple(
        &s,
        RenderOptions {
            seed: 43,
            ..options
        },
    )
    .0;
    assert_ne!(one, other_seed);
}
