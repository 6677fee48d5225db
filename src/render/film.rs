//! Rendering an image: primary rays per pixel, in parallel over rows, deterministic for any
//! number of threads (each pixel's samples and random numbers depend only on the pixel).

use std::sync::atomic::{AtomicBool, Ordering};

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use super::antialias::{
    adaptive_levels, adaptive_pixel, cell, gaussian, grid_offsets, jitter, Antialias, Filter,
};
use super::Image;
use crate::scene::{Integrator, Scene};
use crate::trace::path::PathTracer;
use crate::trace::sampling::Rng;
use crate::trace::{Stats, Tracer};

#[derive(Clone, Copy, Debug)]
pub struct RenderOptions {
    pub max_depth: u32,
    pub spp: u32,
    /// Seed of the random numbers (jittered samples, glossy rays, paths).
    pub seed: u64,
    pub antialias: Antialias,
}

impl RenderOptions {
    pub fn of(scene: &Scene) -> RenderOptions {
        RenderOptions {
            max_depth: scene.max_depth,
            spp: scene.spp,
            seed: 0,
            antialias: scene.antialias,
        }
    }
}

/// Kept for callers that want the regular sample pattern.
pub fn sample_offsets(spp: u32) -> Vec<DVec2> {
    grid_offsets(spp)
}

/// Where adaptive antialiasing takes a pixel corner's random numbers from: a stream of its
/// own, so a corner has the same value for each of the four pixels that share it.
const CORNER_STREAM: u64 = 0xC0_4E_E5;

/// Everything needed to compute one pixel: the integrator and the antialiasing pattern.
pub struct Film<'s> {
    scene: &'s Scene,
    options: RenderOptions,
    whitted: Tracer<'s>,
    path: Option<PathTracer<'s>>,
    offsets: Vec<DVec2>,
}

impl<'s> Film<'s> {
    pub fn new(scene: &'s Scene, options: RenderOptions) -> Film<'s> {
        Film {
            scene,
            options,
            whitted: Tracer::with_depth(scene, options.max_depth),
            path: (scene.integrator == Integrator::Path)
                .then(|| PathTracer::new(scene, options.max_depth)),
            offsets: grid_offsets(options.spp.max(1)),
        }
    }

    /// The value seen through image point (px, py) (pixel (x, y) covers [x, x+1) × [y, y+1)).
    pub fn sample(&self, px: f64, py: f64, rng: &mut Rng, stats: &mut Stats) -> DVec3 {
        let ray = self.scene.camera.ray(px, py);
        match &self.path {
            None => self.whitted.radiance_with(&ray, rng, stats),
            Some(pt) => pt.radiance(&ray, rng, stats),
        }
    }

    /// The value at the image corner (i, j) (adaptive antialiasing shares these).
    pub fn corner(&self, i: u32, j: u32, stats: &mut Stats) -> DVec3 {
        let mut rng = Rng::for_pixel(self.options.seed ^ CORNER_STREAM, i, j);
        self.sample(i as f64, j as f64, &mut rng, stats)
    }

    /// Pixel (x, y). `corner(i, j)` gives the value at an image corner (computed once per
    /// image by `render`, or on the spot for a single pixel).
    pub fn pixel(
        &self,
        x: u32,
        y: u32,
        corner: &dyn Fn(u32, u32, &mut Stats) -> DVec3,
        stats: &mut Stats,
    ) -> DVec3 {
        let mut rng = Rng::for_pixel(self.options.seed, x, y);
        let (fx, fy) = (x as f64, y as f64);
        let n = self.offsets.len() as f64;
        // The path tracer always jitters: a regular grid would alias its noise into patterns.
        let antialias = match (self.options.antialias, &self.path) {
            (Antialias::Grid, Some(_)) => Antialias::Jittered,
            (a, _) => a,
        };
        match antialias {
            Antialias::Grid => {
                let mut sum = DVec3::ZERO;
                for o in &self.offsets {
                    sum += self.sample(fx + o.x, fy + o.y, &mut rng, stats);
                }
                sum / n
            }
            Antialias::Jittered => {
                let cell = cell(self.offsets.len());
                let mut sum = DVec3::ZERO;
                for o in &self.offsets {
                    let j = match self.scene.filter {
                        Filter::Box => jitter(*o, cell, &mut rng),
                        Filter::Gaussian => gaussian(&mut rng),
                    };
                    sum += self.sample(fx + j.x, fy + j.y, &mut rng, stats);
                }
                sum / n
            }
            Antialias::Adaptive { threshold } => {
                let corners = [
                    corner(x, y, stats),
                    corner(x + 1, y, stats),
                    corner(x, y + 1, stats),
                    corner(x + 1, y + 1, stats),
                ];
                let levels = adaptive_levels(self.options.spp);
                let mut inner = Stats::default();
                let (value, splits) = adaptive_pixel(corners, levels, threshold, &mut |u, v| {
                    self.sample(fx + u, fy + v, &mut rng, &mut inner)
                });
                stats.add(&inner);
                stats.aa_splits += splits as u64;
                value
            }
        }
    }

    /// A single pixel, its corners computed on the spot: equal to the rendered pixel.
    pub fn lone_pixel(&self, x: u32, y: u32, stats: &mut Stats) -> DVec3 {
        self.pixel(x, y, &|i, j, s| self.corner(i, j, s), stats)
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
    let film = Film::new(scene, options);
    let (w, h) = (cam.width, cam.height);
    // Adaptive antialiasing first traces the (w+1) × (h+1) pixel corners, shared by
    // neighbouring pixels.
    let (corners, mut stats) = match options.antialias {
        Antialias::Adaptive { .. } => {
            let rows: Vec<(Vec<DVec3>, Stats)> = (0..=h)
                .into_par_iter()
                .map(|j| {
                    let mut stats = Stats::default();
                    let row = (0..=w).map(|i| film.corner(i, j, &mut stats)).collect();
                    (row, stats)
                })
                .collect();
            let mut stats = Stats::default();
            let mut grid = Vec::with_capacity(((w + 1) * (h + 1)) as usize);
            for (row, s) in rows {
                grid.extend(row);
                stats.add(&s);
            }
            (grid, stats)
        }
        _ => (vec![], Stats::default()),
    };
    let corner = |i: u32, j: u32, _: &mut Stats| corners[(j * (w + 1) + i) as usize];
    let mut image = Image::new(w, h);
    let rows = image
        .pixels
        .par_chunks_mut(w as usize)
        .enumerate()
        .map(|(y, row)| {
            let mut stats = Stats::default();
            if cancel.load(Ordering::Relaxed) {
                return stats;
            }
            for (x, px) in row.iter_mut().enumerate() {
                *px = film.pixel(x as u32, y as u32, &corner, &mut stats);
            }
            on_row(y as u32);
            stats
        })
        .reduce(Stats::default, |mut a, b| {
            a.add(&b);
            a
        });
    stats.add(&rows);
    (!cancel.load(Ordering::Relaxed)).then_some((image, stats))
}

/// Renders without progress or cancellation.
pub fn render_simple(scene: &Scene, options: RenderOptions) -> (Image, Stats) {
    render(scene, options, &|_| {}, &AtomicBool::new(false)).expect("not cancelled")
}
