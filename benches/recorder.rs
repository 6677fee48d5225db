//! "The recorder costs nothing when off": the same render (a) through the library's `Tracer`,
//! which calls its recorder at every step (here `NoRecorder`, `ACTIVE = false`), and (b) through
//! a replica of the Whitted shading written below with no recorder calls at all, from the
//! library's public pieces only. Both must give identical pixels (checked before timing); the
//! ratio of their times is what the recorder costs.
//!
//! Run: `cargo bench --bench recorder`.

use criterion::{criterion_group, criterion_main, Criterion};
use glam::DVec3;
use raytree::geometry::Ray;
use raytree::scene::{Interaction, Scene, Search};
use raytree::shading::local::{ambient, light_terms};
use raytree::shading::optics::{reflect, refract, schlick};
use raytree::shading::Fresnel;
use raytree::stats::Stats;
use raytree::trace::{shadow_reach, Tracer};
use std::hint::black_box;

const SCENE: &str = "lessons/examples/showcase.yaml";
const WIDTH: u32 = 160;
const HEIGHT: u32 = 120;

fn scene() -> Scene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(SCENE);
    let mut scene = raytree::scene::load(&path, &raytree::scene::Limits::default())
        .expect("the example scene loads");
    scene.camera.width = WIDTH;
    scene.camera.height = HEIGHT;
    scene
}

/// One primary ray per pixel centre, row by row.
fn render(scene: &Scene, radiance: impl FnMut(&Ray, &mut Stats) -> DVec3) -> Vec<DVec3> {
    render_counting(scene, radiance).0
}

fn render_counting(
    scene: &Scene,
    mut radiance: impl FnMut(&Ray, &mut Stats) -> DVec3,
) -> (Vec<DVec3>, Stats) {
    let mut stats = Stats::default();
    let cam = &scene.camera;
    let pixels = (0..cam.height)
        .flat_map(|y| (0..cam.width).map(move |x| (x, y)))
        .map(|(x, y)| radiance(&cam.ray(x as f64 + 0.5, y as f64 + 0.5), &mut stats))
        .collect();
    (pixels, stats)
}

/// The render through the tracer (one for the whole image, as the renderer keeps one per row:
/// none is made per ray).
fn traced(scene: &Scene) -> (Vec<DVec3>, Stats) {
    let mut tracer = Tracer::new(scene);
    let pixels = render(scene, |r, _| tracer.radiance(r));
    (pixels, tracer.stats)
}

/// The Whitted recursion with nothing but the arithmetic and the statistics (which are not the
/// recorder's: the tracer keeps them when the recorder is off): no recorder calls, no ray tree.
/// It follows `Tracer` step by step (for scenes with at most one transparent object, whose
/// media need no probing), and counts the same rays.
struct Bare<'s> {
    scene: &'s Scene,
}

/// The refractive media a ray is inside, innermost last.
#[derive(Clone, Copy)]
struct Media {
    entries: [(u32, f64); 8],
    len: usize,
}

impl Media {
    const NONE: Media = Media {
        entries: [(u32::MAX, 1.0); 8],
        len: 0,
    };
    fn current(&self) -> f64 {
        if self.len == 0 {
            1.0
        } else {
            self.entries[self.len - 1].1
        }
    }
    fn entering(&self, object: u32, ior: f64) -> Media {
        let mut m = *self;
        if m.len < m.entries.len() {
            m.entries[m.len] = (object, ior);
            m.len += 1;
        }
        m
    }
}

#[derive(Clone, Copy)]
enum Kind {
    Reflection,
    Refraction,
}

impl Bare<'_> {
    fn radiance(&self, ray: &Ray, stats: &mut Stats) -> DVec3 {
        stats.primary_rays += 1;
        self.trace(ray, 0, 1.0, &Media::NONE, stats).0
    }

    fn trace(
        &self,
        ray: &Ray,
        depth: u32,
        weight: f64,
        media: &Media,
        stats: &mut Stats,
    ) -> (DVec3, f64) {
        let scene = self.scene;
        let Some(hit) = scene.nearest(ray, 0.0, f64::INFINITY, stats) else {
            return (scene.background, f64::INFINITY);
        };
        let si = scene.interaction(ray, &hit);
        let m = scene.material(si.material);
        let v = -ray.dir;
        let mut color = ambient(m, &si.paint, scene.ambient);
        for (k, light) in scene.lights.iter().enumerate() {
            let sample = light.sample(si.point);
            let lit = light_terms(
                m,
                &si.paint,
                si.normal,
                v,
                sample.l,
                sample.attenuation * light.intensity,
                false,
            );
            let s = if lit.n_dot_l <= 0.0 {
                stats.shadow_skipped_backfacing += 1;
                0.0
            } else if light.is_dark() {
                stats.shadow_skipped_dark += 1;
                0.0
            } else if si.inside && scene.features.hides_light_inside(si.object, k) {
                stats.shadow_skipped_inside += 1;
                0.0
            } else {
                self.shadow(&si, sample.l, sample.distance, light, stats)
            };
            color += s * (lit.diffuse + lit.specular);
        }
        if m.kr > 0.0 || m.kt > 0.0 {
            color += self.secondary(ray, depth, weight, media, &si, stats);
        }
        (color, hit.t)
    }

    fn secondary(
        &self,
        ray: &Ray,
        depth: u32,
        weight: f64,
        media: &Media,
        si: &Interaction,
        stats: &mut Stats,
    ) -> DVec3 {
        let scene = self.scene;
        let m = scene.material(si.material);
        let (d, n) = (ray.dir, si.normal);
        let (near, beyond) = if m.kt == 0.0 && m.fresnel == Fresnel::None {
            (*media, *media)
        } else if si.inside {
            let mut outside = Media::NONE;
            for &(o, ior) in &media.entries[..media.len] {
                if o != si.object {
                    outside = outside.entering(o, ior);
                }
            }
            (media.entering(si.object, m.ior), outside)
        } else {
            (*media, media.entering(si.object, m.ior))
        };
        let (n1, n2) = if scene.leaves[si.leaf as usize].shape.is_solid() {
            (near.current(), beyond.current())
        } else {
            (near.current(), near.current())
        };
        let transmitted = if m.kt > 0.0 {
            refract(d, n, n1, n2)
        } else {
            None
        };
        let (kr, kt) = match m.fresnel {
            Fresnel::None => (m.kr, m.kt),
            Fresnel::Schlick => {
                let f = schlick(-d.dot(n), n1, n2);
                (m.kr * f, m.kt * (1.0 - f))
            }
        };
        let mirror = reflect(d, n);
        let mut sum = DVec3::ZERO;
        if kr > 0.0 {
            let r = self.spawn(si, mirror);
            sum += kr * self.child(&r, Kind::Reflection, depth + 1, weight * kr, media, stats);
        }
        if kt > 0.0 {
            let (r, kind, media) = match transmitted {
                Some(dir) => (self.spawn(si, dir), Kind::Refraction, &beyond),
                // Total internal reflection: the refraction ray turns into a mirror ray inside
                // (or is cut off, and counted as such, like any secondary ray).
                None => {
                    let cut =
                        depth + 1 >= scene.max_depth || weight * kt < scene.adaptive_threshold;
                    if !cut {
                        stats.total_internal_reflections += 1;
                    }
                    (self.spawn(si, mirror), Kind::Reflection, media)
                }
            };
            sum += kt * self.child(&r, kind, depth + 1, weight * kt, media, stats);
        }
        sum
    }

    fn child(
        &self,
        ray: &Ray,
        kind: Kind,
        depth: u32,
        weight: f64,
        media: &Media,
        stats: &mut Stats,
    ) -> DVec3 {
        let scene = self.scene;
        if depth >= scene.max_depth {
            stats.max_depth_cutoffs += 1;
            return DVec3::ZERO;
        }
        if weight < scene.adaptive_threshold {
            stats.adaptive_cutoffs += 1;
            return DVec3::ZERO;
        }
        match kind {
            Kind::Reflection => stats.reflection_rays += 1,
            Kind::Refraction => stats.refraction_rays += 1,
        }
        let (color, distance) = self.trace(ray, depth, weight, media, stats);
        match scene.secondary_attenuation {
            Some([c0, c1, c2]) if distance.is_finite() => {
                color / (c0 + c1 * distance + c2 * distance * distance)
            }
            _ => color,
        }
    }

    fn shadow(
        &self,
        si: &Interaction,
        l: DVec3,
        distance: f64,
        light: &raytree::shading::Light,
        stats: &mut Stats,
    ) -> f64 {
        let count = light.shadow_rays();
        let mut visible = 0u32;
        for k in 0..count {
            let (dir, dist) = match light.shadow_point(k, si.point) {
                Some(q) => {
                    let to = q - si.point;
                    (to.normalize(), to.length())
                }
                None => (l, distance),
            };
            stats.shadow_rays += 1;
            let (from, moved) = self.scene.offset(si, dir);
            let t_max = shadow_reach(dist, moved);
            let ray = Ray { origin: from, dir };
            if self.scene.blocker(&ray, 0.0, t_max, stats).is_none() {
                visible += 1;
            }
        }
        visible as f64 / count as f64
    }

    fn spawn(&self, si: &Interaction, dir: DVec3) -> Ray {
        Ray {
            origin: self.scene.offset(si, dir).0,
            dir,
        }
    }
}

fn recorder(c: &mut Criterion) {
    let scene = scene();
    assert!(
        scene.features.transparent_objects.len() <= 1,
        "the replica skips media probing"
    );
    let bare = Bare { scene: &scene };
    let (with, counted) = traced(&scene);
    let (without, replica_counted) = render_counting(&scene, |r, s| bare.radiance(r, s));
    assert_eq!(
        counted, replica_counted,
        "the replica must do the tracer's work"
    );
    assert!(
        with.iter()
            .zip(&without)
            .all(|(a, b)| a.to_array().map(f64::to_bits) == b.to_array().map(f64::to_bits)),
        "the replica must compute the tracer's pixels exactly"
    );
    alternating_ratio(&scene, &bare);
    let mut g = c.benchmark_group("recorder");
    g.sample_size(30);
    g.measurement_time(std::time::Duration::from_secs(8));
    g.bench_function("tracer_with_no_recorder", |b| {
        b.iter(|| traced(black_box(&scene)).0)
    });
    g.bench_function("replica_without_recorder", |b| {
        b.iter(|| render(black_box(&scene), |r, s| bare.radiance(r, s)))
    });
    g.finish();
}

/// Criterion times one variant after the other; on a shared, noisy machine the honest ratio
/// comes from alternating them: the median over rounds of (tracer time / replica time).
fn alternating_ratio(scene: &Scene, bare: &Bare) {
    let time = |f: &dyn Fn() -> Vec<DVec3>| {
        let start = std::time::Instant::now();
        black_box(f());
        start.elapsed().as_secs_f64()
    };
    let with = || traced(black_box(scene)).0;
    let without = || render(black_box(scene), |r, s| bare.radiance(r, s));
    // Which goes first alternates too (ABBA), so a warm-up or clock effect favours neither.
    let mut ratios: Vec<f64> = (0..41)
        .map(|round| {
            if round % 2 == 0 {
                let a = time(&with);
                a / time(&without)
            } else {
                let b = time(&without);
                time(&with) / b
            }
        })
        .collect();
    ratios.sort_by(f64::total_cmp);
    println!(
        "recorder/alternating: tracer with NoRecorder / replica without recorder = {:.4} \
         (median of {} alternating rounds; quartiles {:.4} .. {:.4})",
        ratios[ratios.len() / 2],
        ratios.len(),
        ratios[ratios.len() / 4],
        ratios[3 * ratios.len() / 4]
    );
}

criterion_group!(benches, recorder);
criterion_main!(benches);
