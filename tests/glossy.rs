//! Monte Carlo reflection and refraction (seed 000), soft shadows from sphere lights, and the
//! path tracer's light sampling, against closed-form answers.

mod common;

use common::scene;

use glam::DVec3;
use raytree::geometry::Ray;
use raytree::render::{render_simple, RenderOptions};
use raytree::sampling::{pixel_key, Rng, SamplePoint};
use raytree::scene::Scene;
use raytree::stats::Stats;
use raytree::trace::path::PathTracer;
use raytree::trace::tree::{RayKind, RayNode, Termination};
use raytree::trace::Tracer;

const CAMERA: &str =
    "camera: { eye: [0, 1, -1], look_at: [0, 0, 0], fov: 30, width: 16, height: 12 }\n";

/// A ray from (0, 1, −1) that meets the floor at the origin; its mirror direction is
/// (0, 1, 1)/√2, in the plane x = 0.
fn down_ray() -> Ray {
    Ray {
        origin: DVec3::new(0.0, 1.0, -1.0),
        dir: DVec3::new(0.0, -1.0, 1.0).normalize(),
    }
}

/// A glossy floor (kr = 1, nothing else) whose cone looks at a glowing wall filling the half
/// x > 0 of the view, black elsewhere. The lobe is symmetric about the mirror direction, which
/// lies in the plane x = 0, so each sampled ray brings 1 or 0 with probability ½: the cone's
/// value is ½ on average, with standard deviation ½/√n for n rays.
fn half_wall(samples: u32) -> Scene {
    scene(&format!(
        "{CAMERA}background: 0\nambient: 1\n\
         materials:\n  floor: {{ kr: 1, glossy: {{ spread: 5, samples: {samples} }} }}\n  \
         glow: {{ color: 1, ka: 1 }}\n\
         objects:\n  - {{ name: floor, plane: {{ point: [0, 0, 0], normal: [0, 1, 0] }}, material: floor }}\n  \
         - {{ name: wall, box: {{ min: [0, 0.5, 20], max: [100, 100, 21] }}, material: glow }}\n"
    ))
}

#[test]
fn glossy_noise_falls_as_one_over_root_n_about_the_right_mean() {
    let runs = 600;
    for n in [4u32, 16, 64] {
        let s = half_wall(n);
        let values: Vec<f64> = (0..runs)
            .map(|seed| {
                let rng = Rng::for_pixel(seed, 0, 0);
                Tracer::new(&s).with_rng(rng).radiance(&down_ray()).x
            })
            .collect();
        let mean = values.iter().sum::<f64>() / runs as f64;
        let sd =
            (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (runs - 1) as f64).sqrt();
        let expected_sd = 0.5 / (n as f64).sqrt();
        assert!(
            (mean - 0.5).abs() < 4.0 * expected_sd / (runs as f64).sqrt(),
            "n = {n}: mean {mean}"
        );
        // The sample standard deviation of 600 runs is within ±12 % of the true one.
        assert!(
            (sd / expected_sd - 1.0).abs() < 0.12,
            "n = {n}: sd {sd}, expected {expected_sd}"
        );
    }
}

#[test]
fn a_glossy_floor_under_a_uniform_sky_reflects_exactly_kr_times_the_sky() {
    // Every sampled ray sees the sky: one drawn below the floor is folded back above it. A
    // black floor just below would darken any ray that went under.
    for lobe in ["spread: 30", "spread: 2", "exponent: 3"] {
        let s = scene(&format!(
            "{CAMERA}background: 0.8\n\
             materials: {{ floor: {{ kr: 0.5, glossy: {{ {lobe}, samples: 8 }} }}, black: {{}} }}\n\
             objects:\n\
             - {{ plane: {{ point: [0, 0, 0], normal: [0, 1, 0] }}, material: floor }}\n\
             - {{ plane: {{ point: [0, -0.01, 0], normal: [0, 1, 0] }}, material: black }}\n"
        ));
        let (image, _) = render_simple(&s, RenderOptions::of(&s));
        for p in &image.pixels {
            assert!(
                (*p - DVec3::splat(0.4)).abs().max_element() < 1e-12,
                "{lobe}: {p}"
            );
        }
    }
}

#[test]
fn a_very_narrow_lobe_is_a_mirror() {
    let yaml = |glossy: &str| {
        format!(
            "camera: {{ eye: [0, 2, -6], look_at: [0, 0.5, 0], fov: 40, width: 32, height: 24 }}\n\
             background: [0.2, 0.3, 0.5]\nambient: 0.2\n\
             lights: [ {{ point: [3, 6, -4], intensity: 0.9 }} ]\n\
             materials:\n  floor: {{ color: 0.5, ka: 0.2, kd: 0.3, kr: 0.6 {glossy} }}\n  \
             red: {{ color: [1, 0.2, 0.1], ka: 0.2, kd: 0.8 }}\n\
             objects:\n  - {{ plane: {{ point: [0, 0, 0], normal: [0, 1, 0] }}, material: floor }}\n  \
             - {{ sphere: {{ center: [0, 1, 1], radius: 1 }}, material: red }}\n"
        )
    };
    let mirror = scene(&yaml(""));
    let narrow = scene(&yaml(", glossy: { spread: 0.000001, samples: 4 }"));
    let (a, _) = render_simple(&mirror, RenderOptions::of(&mirror));
    let (b, _) = render_simple(&narrow, RenderOptions::of(&narrow));
    let close = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .filter(|(x, y)| (**x - **y).abs().max_element() < 1e-6)
        .count();
    // Only a pixel whose mirror ray grazes the sphere's silhouette may differ.
    assert!(close + 2 >= a.pixels.len(), "{close} of {}", a.pixels.len());
}

fn cones(n: &RayNode, out: &mut Vec<(u32, RayNode)>, depth: u32) {
    if n.samples.is_some() {
        out.push((depth, n.clone()));
    }
    for c in &n.children {
        cones(c, out, depth + 1);
    }
}

#[test]
fn the_tree_shows_the_cone_as_the_mean_of_its_sampled_rays() {
    // Two glossy mirrors facing each other: the first cone splits into 6 rays, and every cone
    // below it sends one ray, so the work grows linearly with depth, not as 6^depth.
    let s = scene(
        "camera: { eye: [0, 0, 0], look_at: [0, 0, 1], width: 8, height: 8 }\n\
         background: 0.5\nambient: 0.1\nmax_depth: 5\n\
         materials: { m: { color: 1, ka: 1, kr: 0.5, glossy: { spread: 3, samples: 6 } } }\n\
         objects:\n  - { box: { min: [-50, -50, 5], max: [50, 50, 6] }, material: m }\n  \
         - { box: { min: [-50, -50, -6], max: [50, 50, -5] }, material: m }\n",
    );
    let tree = Tracer::new(&s).inspect_pixel(4, 4).tree;
    let mut found = vec![];
    cones(&tree, &mut found, 0);
    let (_, first) = &found[0];
    assert_eq!(first.samples, Some(6));
    assert_eq!(first.children.len(), 6);
    let mean = first.children.iter().map(|c| c.color).sum::<DVec3>() / 6.0;
    assert!((first.color - mean).abs().max_element() < 1e-12);
    for c in &first.children {
        assert_eq!(c.kind, RayKind::Reflection);
        assert!((c.coefficient - 1.0 / 6.0).abs() < 1e-15);
        // Within 5σ of the principal direction.
        assert!(c.direction.angle_between(first.direction) < 15f64.to_radians());
    }
    assert!(found.len() > 6, "{} cones", found.len());
    assert!(found[1..].iter().all(|(_, n)| n.samples == Some(1)));
    // The root's colour is the one the renderer computes for that pixel.
    let (image, _) = render_simple(&s, RenderOptions::of(&s));
    assert_eq!(tree.color, image.pixels[4 * 8 + 4]);
}

#[test]
fn frosted_glass_blurs_but_keeps_the_light_it_lets_through() {
    // A frosted slab (no reflection, kt = 1) between the eye and a uniform glowing wall:
    // every refracted ray ends on the wall or the background, both of radiance 1. (The lobe
    // is narrow enough that no sampled ray meets the back face beyond the critical angle.)
    let s = scene(
        "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], fov: 30, width: 12, height: 12 }\n\
         background: 1\nambient: 1\n\
         materials: { frost: { kt: 1, ior: 1.5, frosted: { spread: 3, samples: 8 } }, glow: { color: 1, ka: 1 } }\n\
         objects:\n  - { box: { min: [-10, -10, -0.5], max: [10, 10, 0.5] }, material: frost }\n  \
         - { box: { min: [-100, -100, 10], max: [100, 100, 11] }, material: glow }\n",
    );
    let (image, stats) = render_simple(&s, RenderOptions::of(&s));
    assert!(stats.glossy_rays > 0);
    for p in &image.pixels {
        assert!((*p - DVec3::ONE).abs().max_element() < 1e-12, "{p}");
    }
}

/// The furnace test of frosted glass: a clear sphere (kt = 1, nothing absorbed) under a uniform
/// sky of 0.5 shows 0.5 wherever it is seen, every ray ending in the sky. Frosted, a ray
/// drawn into the sphere may meet its far side beyond the limiting angle; turned back by a
/// perfect mirror it would keep that angle and bounce inside until the depth limit (a sphere's
/// chords all meet it at one angle), darkening the ball. The frosted face spreads that
/// reflection too, so the ray leaves within a few bounces. Whitted: every sample ends in the
/// sky, 0.5 to the last bit but for rays cut at the depth limit; path traced (no roulette, so
/// a path brings 0.5 or, cut at the depth limit, 0) the same.
#[test]
fn frosted_glass_passes_the_furnace_test() {
    let furnace = |integrator: &str| {
        scene(&format!(
            "camera: {{ eye: [0, 0, -5], look_at: [0, 0, 0], fov: 30, width: 21, height: 21 }}
integrator: {integrator}
background: 0.5
max_depth: 64
spp: 16
materials: {{ frost: {{ color: 1, kt: 1, ior: 1.5, frosted: {{ spread: 20, samples: 1 }} }} }}
objects: [ {{ name: ball, sphere: {{ center: [0, 0, 0], radius: 1 }}, material: frost }} ]
"
        ))
    };
    let whitted = furnace("whitted");
    let (image, stats) = render_simple(&whitted, RenderOptions::of(&whitted));
    assert!(stats.total_internal_reflections > 1000, "{stats:?}");
    let dark = image
        .pixels
        .iter()
        .filter(|p| (**p - DVec3::splat(0.5)).abs().max_element() > 1e-12);
    assert_eq!(
        dark.count(),
        0,
        "max-depth cut-offs: {}",
        stats.max_depth_cutoffs
    );

    let path = furnace("path");
    let tracer = PathTracer {
        roulette: false,
        ..PathTracer::new(&path, path.max_depth)
    };
    let cam = &path.camera;
    let (mut sum, mut n) = (0.0, 0);
    for (x, y) in [(4, 10), (10, 10), (7, 6), (10, 4), (13, 13)] {
        for i in 0..256 {
            let point = SamplePoint::new(pixel_key(1, x, y), i);
            let [u, v] = point.pair(0);
            let ray = cam.ray(x as f64 + u, y as f64 + v);
            let l = tracer.radiance(&ray, &point, &mut Stats::default());
            assert!(l == DVec3::splat(0.5) || l == DVec3::ZERO, "{l}");
            (sum, n) = (sum + l.x, n + 1);
        }
    }
    assert!(sum / n as f64 > 0.4995, "mean {}", sum / n as f64);
}

/// Inside a frosted glass ball, a ray from (0, 0.9, 0) along +z meets the surface at
/// (0, 0.9, √0.19) with cos θ = √0.19 ≈ 0.436: θ ≈ 64°, past the limiting angle asin(1/1.5) ≈
/// 41.8°. The refraction ray ends in total internal reflection, and the ray that stays inside
/// is a cone of the frosted lobe's 4 samples, named for what it is.
#[test]
fn frosted_total_internal_reflection_is_a_frosted_reflection_cone() {
    let s = scene(
        "camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }
materials: { frost: { kt: 1, ior: 1.5, frosted: { spread: 5, samples: 4 } } }
objects: [ { name: ball, sphere: { center: [0, 0, 0], radius: 1 }, material: frost } ]
",
    );
    let tree = Tracer::new(&s).inspect(&Ray::new(DVec3::new(0.0, 0.9, 0.0), DVec3::Z));
    assert!(tree.hit.as_ref().unwrap().inside);
    let refraction = &tree.children[0];
    assert_eq!(refraction.kind, RayKind::Refraction);
    assert_eq!(
        refraction.terminated,
        Some(Termination::TotalInternalReflection)
    );
    let inside = &refraction.children[0];
    assert_eq!(inside.kind, RayKind::Reflection);
    assert_eq!(inside.cone(), Some(("frosted reflection", 4)));
    assert_eq!(inside.children.len(), 4);
}

/// Between two glossy planes every secondary ray is a glossy sample, so the samples counted
/// are the reflection rays traced: a sample cut off at the maximum depth is counted as skipped,
/// not as traced. 40 × 30 primary rays, each followed by one sample a bounce to depth 3.
#[test]
fn glossy_samples_are_counted_only_when_traced() {
    let s = scene(
        "camera: { eye: [0, 1, -5], look_at: [0, 0, 0], width: 40, height: 30 }
max_depth: 4
materials: { g: { color: 1, kd: 0.2, kr: 0.5, glossy: { exponent: 50, samples: 1 } } }
objects:
  - { name: floor, plane: { point: [0, 0, 0], normal: [0, 1, 0] }, material: g }
  - { name: ceiling, plane: { point: [0, 3, 0], normal: [0, -1, 0] }, material: g }
",
    );
    let (_, stats) = render_simple(&s, RenderOptions::of(&s));
    assert_eq!(stats.reflection_rays, 1200 * 3);
    assert_eq!(stats.glossy_rays, stats.reflection_rays);
    assert_eq!(stats.max_depth_cutoffs, 1200);
}

/// A sphere light right above a point, and a blocker whose edge plane contains the line from
/// the point to the light's centre: the shadow-ray pattern on the disc is point-symmetric,
/// so exactly half of the rays pass.
#[test]
fn a_sphere_light_half_hidden_gives_a_shadow_factor_of_one_half() {
    let light = |samples: u32| {
        format!(
            "camera: {{ eye: [0, 1, -5], look_at: [0, 0, 0], width: 8, height: 8 }}\n\
             lights: [ {{ name: bulb, sphere: {{ center: [0, 4, 0], radius: 1 }}, intensity: 1, samples: {samples} }} ]\n\
             materials: {{ m: {{ color: 1, kd: 1 }} }}\n\
             objects:\n  - {{ plane: {{ point: [0, 0, 0], normal: [0, 1, 0] }}, material: m }}\n  \
             - {{ name: blocker, box: {{ min: [0, 2, -5], max: [5, 2.1, 5] }}, material: m }}\n"
        )
    };
    for samples in [2u32, 4, 6] {
        let s = scene(&light(samples));
        let ray = Ray {
            origin: DVec3::new(0.0, 1.0, -1.0),
            dir: DVec3::new(0.0, -1.0, 1.0).normalize(),
        };
        let tree = Tracer::new(&s).inspect(&ray);
        let s_factor = tree.local.as_ref().unwrap().lights[0].shadow;
        assert_eq!(s_factor, 0.5, "{samples} × {samples} rays");
        // Far from the blocker's edge: fully lit, or fully in its shadow.
        for (x, expected) in [(-3.0, 1.0), (2.0, 0.0)] {
            let ray = Ray {
                origin: DVec3::new(x, 1.0, -1.0),
                dir: DVec3::new(0.0, -1.0, 1.0).normalize(),
            };
            let tree = Tracer::new(&s).inspect(&ray);
            assert_eq!(
                tree.local.as_ref().unwrap().lights[0].shadow,
                expected,
                "x = {x}"
            );
        }
    }
}

/// A Lambertian floor of albedo ρ lit by a sphere of radiance L and radius r whose centre is
/// at distance d, at angle θ from the normal, and wholly above the horizon: the irradiance is
/// E = π·L·(r/d)²·cos θ, so the floor's radiance is ρ·E/π = ρ·L·(r/d)²·cos θ.
fn lit_floor() -> Scene {
    scene(
        "camera: { eye: [2, 6, -3], look_at: [2, 0, 0], fov: 20, width: 6, height: 6 }\n\
         integrator: path\nmax_depth: 2\nbackground: 0\n\
         lights: [ { name: bulb, sphere: { center: [0, 2, 0], radius: 0.5 }, intensity: 3 } ]\n\
         materials: { floor: { color: 1, kd: 0.5 } }\n\
         objects: [ { name: floor, plane: { point: [0, 0, 0], normal: [0, 1, 0] }, material: floor } ]\n",
    )
}

fn analytic(p: DVec3) -> f64 {
    let to = DVec3::new(0.0, 2.0, 0.0) - p;
    let d = to.length();
    0.5 * 3.0 * (0.5 / d).powi(2) * (to.y / d)
}

/// The mean of many one-sample estimates of each pixel's centre against the closed form,
/// within its standard error: light sampling with MIS, and BSDF sampling alone, are unbiased.
#[test]
fn sphere_light_estimates_are_unbiased_with_and_without_light_sampling() {
    let s = lit_floor();
    for next_event in [true, false] {
        let tracer = PathTracer {
            next_event,
            ..PathTracer::new(&s, 2)
        };
        let runs = if next_event { 400 } else { 4000 };
        let mut worst: f64 = 0.0;
        for (x, y) in [(0, 0), (2, 3), (5, 5), (3, 1)] {
            let ray = s.camera.pixel_ray(x, y);
            let t = -ray.origin.y / ray.dir.y;
            let exact = analytic(ray.at(t));
            // Independent estimates (each from a pixel key of its own), so that the sample
            // variance gives the standard error of their mean.
            let values: Vec<f64> = (0..runs)
                .map(|k| {
                    let point = SamplePoint::new(pixel_key(9 + k, x, y), 0);
                    tracer.radiance(&ray, &point, &mut Stats::default()).x
                })
                .collect();
            let mean = values.iter().sum::<f64>() / runs as f64;
            let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (runs - 1) as f64;
            let se = (var / runs as f64).sqrt().max(1e-12);
            worst = worst.max((mean - exact).abs() / se);
            // With light sampling the estimate is useful, not just unbiased: within 3 %.
            assert!(
                !next_event || (mean / exact - 1.0).abs() < 0.03,
                "{mean} vs {exact}"
            );
        }
        assert!(worst < 4.0, "next_event {next_event}: worst |z| = {worst}");
    }
}

#[test]
fn light_sampling_beats_bsdf_sampling_on_a_small_light() {
    let s = lit_floor();
    let ray = s.camera.pixel_ray(3, 3);
    let spread = |next_event: bool| {
        let tracer = PathTracer {
            next_event,
            ..PathTracer::new(&s, 2)
        };
        let v: Vec<f64> = (0..2000)
            .map(|k| {
                let point = SamplePoint::new(pixel_key(k, 3, 3), 0);
                tracer.radiance(&ray, &point, &mut Stats::default()).x
            })
            .collect();
        let m = v.iter().sum::<f64>() / v.len() as f64;
        v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / v.len() as f64
    };
    // The light covers (r/d)²/4 ≈ 1.5 % of the hemisphere's cosine-weighted measure: BSDF
    // sampling rarely finds it, light sampling always does.
    assert!(spread(true) * 20.0 < spread(false));
}

/// What the sample points are for: a pixel's 16 points spread over each pair of numbers a path
/// draws, so their mean misses the closed form by less than the mean of 16 independent points
/// (each from a key of its own) does: under half the squared error, over 64 pixels' keys.
#[test]
fn a_pixels_spread_sample_points_beat_independent_ones() {
    let s = lit_floor();
    let tracer = PathTracer::new(&s, 2);
    let ray = s.camera.pixel_ray(3, 3);
    let exact = analytic(ray.at(-ray.origin.y / ray.dir.y));
    let mse = |point: &dyn Fn(u64, u32) -> SamplePoint| {
        let trials = 64;
        (0..trials)
            .map(|trial| {
                let sum: f64 = (0..16)
                    .map(|i| {
                        let p = point(trial, i);
                        tracer.radiance(&ray, &p, &mut Stats::default()).x
                    })
                    .sum();
                (sum / 16.0 - exact).powi(2)
            })
            .sum::<f64>()
            / trials as f64
    };
    let spread = mse(&|trial, i| SamplePoint::new(pixel_key(trial, 3, 3), i));
    let independent =
        mse(&|trial, i| SamplePoint::new(pixel_key(1000 + trial * 16 + i as u64, 3, 3), 0));
    assert!(
        spread * 2.0 < independent,
        "MSE {spread} spread, {independent} independent"
    );
}
