//! Rendering an image: primary rays per pixel, in parallel over rows, deterministic for any
//! number of threads (each pixel's samples are fixed; rows are independent).

use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};

use glam::DVec2;
use rayon::prelude::*;

use super::Image;
use crate::scene::{Integrator, Scene};
use crate::trace::path::PathTracer;
use crate::trace::sampling::Rng;
use crate::trace::{Stats, Tracer};

#[derive(Clone, Copy, Debug)]
pub struct RenderOptions {
    pub max_depth: u32,
    pub spp: u32,
    /// Seed of the Monte Carlo integrators' random numbers.
    pub seed: u64,
}

impl RenderOptions {
    pub fn of(scene: &Scene) -> RenderOptions {
        RenderOptions {
            max_depth: scene.max_depth,
            spp: scene.spp,
            seed: 0,
        }
    }
}

/// Sample positions inside a pixel, in [0, 1)². A square count is a regular n × n grid (seed
/// 004's supersampling); any other count uses the R2 low-discrepancy sequence.
pub fn sample_offsets(spp: u32) -> Vec<DVec2> {
    let n = (spp as f64).sqrt().round() as u32;
    if n * n == spp {
        let step = 1.0 / n as f64;
        (0..spp)
            .map(|k| DVec2::new(((k % n) as f64 + 0.5) * step, ((k / n) as f64 + 0.5) * step))
            .collect()
    } else {
        // Roberts' R2 sequence: the plastic number's powers.
        let g = 1.324_717_957_244_746;
        let (a1, a2) = (1.0 / g, 1.0 / (g * g));
        (0..spp)
            .map(|k| DVec2::new((0.5 + a1 * k as f64).fract(), (0.5 + a2 * k as f64).fract()))
            .collect()
    }
}

/// Renders the scene. `on_row(y)` is called as rows finish; setting `cancel` stops early
/// (the result is then None).
pub fn render(
    scene: &Scene,
    options: RenderOptions,
    on_row: &(dyn Fn(u32) + Sync),
    cancel: &AtomicBool,
) -> Option<(Image, Stats)> {
    let cam = &scene.camera;
    let tracer = Tracer::with_depth(scene, options.max_depth);
    let path =
        (scene.integrator == Integrator::Path).then(|| PathTracer::new(scene, options.max_depth));
    let offsets = sample_offsets(options.spp.max(1));
    let mut image = Image::new(cam.width, cam.height);
    let done = AtomicU32::new(0);
    let stats = image
        .pixels
        .par_chunks_mut(cam.width as usize)
        .enumerate()
        .map(|(y, row)| {
            let mut stats = Stats::default();
            if cancel.load(Ordering::Relaxed) {
                return stats;
            }
            for (x, px) in row.iter_mut().enumerate() {
                let mut sum = glam::DVec3::ZERO;
                match &path {
                    None => {
                        for o in &offsets {
                            let ray = cam.ray(x as f64 + o.x, y as f64 + o.y);
                            sum += tracer.radiance(&ray, &mut stats);
                        }
                    }
                    Some(pt) => {
                        // Monte Carlo: each sample jittered inside its stratum of the grid.
                        let mut rng = Rng::for_pixel(options.seed, x as u32, y as u32);
                        let cell = 1.0 / (offsets.len() as f64).sqrt().ceil();
                        for o in &offsets {
                            let jx = (o.x + (rng.uniform() - 0.5) * cell).clamp(0.0, 0.999_999);
                            let jy = (o.y + (rng.uniform() - 0.5) * cell).clamp(0.0, 0.999_999);
                            let ray = cam.ray(x as f64 + jx, y as f64 + jy);
                            sum += pt.radiance(&ray, &mut rng, &mut stats);
                        }
                    }
                }
                *px = sum / offsets.len() as f64;
            }
            done.fetch_add(1, Ordering::Relaxed);
            on_row(y as u32);
            stats
        })
        .reduce(Stats::default, |mut a, b| {
            a.add(&b);
            a
        });
    (!cancel.load(Ordering::Relaxed)).then_some((image, stats))
}

/// Renders without progress or cancellation.
pub fn render_simple(scene: &Scene, options: RenderOptions) -> (Image, Stats) {
    render(scene, options, &|_| {}, &AtomicBool::new(false)).expect("not cancelled")
}
