//! Rendering an image: primary rays per pixel, in parallel over rows, deterministic for any
//! number of threads (each pixel's samples and random numbers depend only on the pixel, and
//! partial sums are added in a fixed order).

use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};

use arrayvec::ArrayVec;
use glam::{DVec2, DVec3};
use rayon::prelude::*;

use super::antialias::{
    adaptive_levels, adaptive_pixel_observed, cell, gaussian_weights, grid_offsets, jitter, Step,
    GAUSS_RADIUS,
};
use super::Image;
use crate::fast::{
    trace_packet, DiffusePaths, FastScene, Footprints, ImagePlane, Missed, PACKET, SHADED,
};
use crate::geometry::Ray;
use crate::sampling::{pixel_key, Rng, SamplePoint};
use crate::scene::{Antialias, Camera, Filter, Integrator, Scene, Search};
use crate::stats::Stats;
use crate::trace::path::{PathTracer, PathVertex};
use crate::trace::Tracer;

/// How an image is rendered: depth, samples per pixel, seed, antialiasing and engine.
#[derive(Clone, Copy, Debug)]
pub struct RenderOptions {
    /// Rays per path, primary included (1: primary rays only).
    pub max_depth: u32,
    /// Samples (primary rays) per pixel.
    pub spp: u32,
    /// Seed of the random numbers (jittered samples, glossy rays, paths).
    pub seed: u64,
    /// Where a pixel's primary rays go.
    pub antialias: Antialias,
    /// Which code computes the image (both give the same image).
    pub engine: Engine,
}

/// Which code computes the image. Both give the same image, bit for bit.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Engine {
    /// The fast wing: packets of rays, SIMD lanes, fast searches.
    #[default]
    Fast,
    /// The textbook core alone: every ray traced by `trace::whitted` (or the path tracer) with
    /// the scene's own search, one after another.
    Core,
}

impl RenderOptions {
    /// The scene's own settings: its depth, spp and antialiasing, seed 0, the fast engine.
    pub fn of(scene: &Scene) -> RenderOptions {
        RenderOptions {
            max_depth: scene.max_depth,
            spp: scene.spp,
            seed: 0,
            antialias: scene.antialias,
            engine: Engine::Fast,
        }
    }
}

/// Where adaptive antialiasing takes a pixel corner's random numbers from: a stream of its
/// own, so a corner has the same value for each of the four pixels that share it.
const CORNER_STREAM: u64 = 0xC0_4E_E5;

/// How many pixel rows (and columns) a splatted sample reaches on each side of its own.
const SPLAT_REACH: i64 = GAUSS_RADIUS as i64;

/// One sample of a pixel: where it went, in pixel-relative (u, v) ∈ [0, 1)², and its value.
#[derive(Clone, Copy, Debug)]
pub struct Sample {
    /// Where the sample went in the pixel, (u, v) ∈ [0, 1)², (0, 0) its top-left corner.
    pub uv: DVec2,
    /// The intensity the sample's ray brought back.
    pub value: DVec3,
}

/// Everything needed to compute one pixel: the integrator, the antialiasing pattern, and (for
/// the fast engine) the fast wing's search, which the film's tracers find their hits with.
pub struct Film<'s> {
    scene: &'s Scene,
    /// The scene's camera, or another one through the same scene (a preview's smaller image).
    camera: Camera,
    fast: Option<FastScene<'s>>,
    options: RenderOptions,
    path: Option<PathTracer<'s>>,
    /// The fast wing's form of the path tracer, for a scene of diffuse surfaces only.
    diffuse_paths: Option<DiffusePaths<'s>>,
    offsets: Vec<DVec2>,
    /// The look-at camera's image plane at the grid samples, where the fast wing traces
    /// them in packets.
    plane: Option<ImagePlane>,
    /// Where on that plane each boxed object can appear, so that a packet of primary rays
    /// skips the boxes it cannot meet without asking its rays.
    footprints: Option<Footprints>,
}

impl<'s> Film<'s> {
    /// The film of `scene` with `options` (building the fast wing's search when the engine is
    /// `Fast`).
    pub fn new(scene: &'s Scene, options: RenderOptions) -> Film<'s> {
        Film::through(scene, scene.camera.clone(), options)
    }

    /// The film of `scene` seen through `camera` instead of the scene's own.
    pub fn through(scene: &'s Scene, camera: Camera, options: RenderOptions) -> Film<'s> {
        let fast = options.engine == Engine::Fast;
        let path = (scene.integrator == Integrator::Path)
            .then(|| PathTracer::new(scene, options.max_depth));
        let mut film = Film {
            scene,
            camera,
            fast: fast.then(|| FastScene::new(scene)),
            options,
            path,
            diffuse_paths: path.filter(|_| fast).and_then(DiffusePaths::new),
            offsets: grid_offsets(options.spp.max(1)),
            plane: None,
            footprints: None,
        };
        if fast && film.antialias() == Antialias::Grid {
            film.plane = ImagePlane::new(&film.camera, &film.offsets);
            film.footprints = film
                .fast
                .as_ref()
                .and_then(|fast| Footprints::new(&film.camera, &film.offsets, fast));
        }
        film
    }

    /// A tracer of this film's rays. Each thread takes its own: it carries the random numbers
    /// and the counters of work.
    pub fn tracer(&self) -> Tracer<'_> {
        Tracer::new(self.scene)
            .with_search(self.search())
            .with_depth(self.options.max_depth)
    }

    fn search(&self) -> &dyn Search {
        match &self.fast {
            Some(fast) => fast,
            None => self.scene,
        }
    }

    /// The antialiasing actually used: the path tracer never takes the regular grid (it would
    /// alias its noise into patterns) but spreads its samples over the pixel with their sample
    /// points (pair 0, `sampling::sobol`).
    pub fn antialias(&self) -> Antialias {
        match (self.options.antialias, &self.path) {
            (Antialias::Grid, Some(_)) => Antialias::Jittered,
            (a, _) => a,
        }
    }

    /// Samples are splatted through the Gaussian filter (grid and jittered sampling only).
    pub fn splats(&self) -> bool {
        self.scene.filter == Filter::Gaussian
            && !matches!(self.antialias(), Antialias::Adaptive { .. })
    }

    /// The value seen through image point (px, py) (pixel (x, y) covers [x, x+1) × [y, y+1)).
    /// A path draws its random numbers from `point`; the Whitted tracer from `t.rng`.
    pub fn sample(&self, t: &mut Tracer, px: f64, py: f64, point: SamplePoint) -> DVec3 {
        let ray = self.camera.ray(px, py);
        match (&self.path, &self.diffuse_paths, &self.fast) {
            (None, _, _) => t.radiance(&ray),
            (Some(_), Some(paths), Some(fast)) => paths.radiance(fast, &ray, &point, &mut t.stats),
            (Some(pt), _, _) => pt
                .with_search(t.search)
                .radiance(&ray, &point, &mut t.stats),
        }
    }

    /// The sample point of pixel (x, y)'s sample number `index` (from 0).
    pub fn sample_point(&self, x: u32, y: u32, index: u32) -> SamplePoint {
        SamplePoint::new(pixel_key(self.options.seed, x, y), index)
    }

    /// The value at the image corner (i, j) (adaptive antialiasing shares these).
    pub fn corner(&self, t: &mut Tracer, i: u32, j: u32) -> DVec3 {
        t.rng = Rng::for_pixel(self.options.seed ^ CORNER_STREAM, i, j);
        let point = SamplePoint::new(pixel_key(self.options.seed ^ CORNER_STREAM, i, j), 0);
        self.sample(t, i as f64, j as f64, point)
    }

    /// The samples numbered `which` (from 0; those beyond the pixel's samples left out) of
    /// pixel (x, y) of a path-traced film, traced again with the random numbers the film gives
    /// them, each with its path's vertices: the paths that went into the pixel (none when the
    /// film traces no paths).
    pub fn replay_paths(&self, x: u32, y: u32, which: Range<u32>) -> Vec<(DVec3, Vec<PathVertex>)> {
        let Some(pt) = &self.path else {
            return vec![];
        };
        let mut paths = vec![];
        for i in which.start..which.end.min(self.offsets.len() as u32) {
            let point = self.sample_point(x, y, i);
            let [u, v] = point.pair(0);
            let ray = self.camera.ray(x as f64 + u, y as f64 + v);
            let mut log = vec![];
            let value = pt.sample(&ray, &point, &mut Stats::default(), Some(&mut log));
            paths.push((value, log));
        }
        paths
    }

    /// The grid or jittered samples of pixel (x, y), in order, from the pixel's generator (a
    /// path-traced film's: at the first pair of their sample points).
    pub fn own_samples(&self, t: &mut Tracer, x: u32, y: u32) -> Vec<Sample> {
        let mut out = Vec::with_capacity(self.offsets.len());
        self.for_each_own_sample(t, x, y, &mut |s| out.push(s));
        out
    }

    /// `own_samples` without collecting them (the render loop allocates nothing per pixel).
    fn for_each_own_sample(&self, t: &mut Tracer, x: u32, y: u32, visit: &mut dyn FnMut(Sample)) {
        t.rng = Rng::for_pixel(self.options.seed, x, y);
        let (fx, fy) = (x as f64, y as f64);
        let jittered = self.antialias() == Antialias::Jittered;
        let packets = self.offsets.len() > 1;
        if let (false, None, true, Some(fast)) = (jittered, &self.path, packets, &self.fast) {
            self.grid_in_packets(t, fast, x, y, visit);
            return;
        }
        if self.path.is_some() {
            // Each sample's place in the pixel is worked out before the sample before it is
            // traced: it depends on nothing that sample finds, and the processor works out its
            // chain of hashes while the path runs.
            let key = pixel_key(self.options.seed, x, y);
            let point = |i: usize| SamplePoint::new(key, i as u32);
            let mut next = DVec2::from(point(0).pair(0));
            for i in 0..self.offsets.len() {
                let uv = next;
                if i + 1 < self.offsets.len() {
                    next = DVec2::from(point(i + 1).pair(0));
                }
                let value = self.sample(t, fx + uv.x, fy + uv.y, point(i));
                visit(Sample { uv, value });
            }
            return;
        }
        let cell = cell(self.offsets.len());
        for (i, o) in self.offsets.iter().enumerate() {
            let uv = if jittered {
                jitter(*o, cell, &mut t.rng)
            } else {
                *o
            };
            let value = self.sample(t, fx + uv.x, fy + uv.y, self.sample_point(x, y, i as u32));
            visit(Sample { uv, value });
        }
    }

    /// The grid samples of pixel (x, y), as `for_each_own_sample` takes them, traced as
    /// packets by the fast wing: a regular grid's rays are all known before any is traced.
    fn grid_in_packets(
        &self,
        t: &mut Tracer,
        fast: &FastScene,
        x: u32,
        y: u32,
        visit: &mut dyn FnMut(Sample),
    ) {
        for (c, chunk) in self.offsets.chunks(SHADED).enumerate() {
            let mut rays = ArrayVec::new();
            let first = c * SHADED;
            self.grid_rays(x, y, first..first + chunk.len(), &mut rays);
            let mut values = [DVec3::ZERO; SHADED];
            let missed = self
                .footprints
                .as_ref()
                .map_or(Missed::UNKNOWN, |f| f.missed(x, x, y));
            trace_packet(t, fast, &rays, missed, &mut values[..rays.len()]);
            for (o, value) in chunk.iter().zip(values) {
                visit(Sample { uv: *o, value });
            }
        }
    }

    /// The primary rays of pixel (x, y) through the grid offsets numbered `which`, in order
    /// (`Camera::ray` for each, to the bit).
    fn grid_rays(&self, x: u32, y: u32, which: Range<usize>, rays: &mut ArrayVec<Ray, PACKET>) {
        match &self.plane {
            Some(plane) if plane.holds(x, y) => plane.rays(x, y, which, rays),
            _ => {
                let (fx, fy) = (x as f64, y as f64);
                let ray = |o: &DVec2| self.camera.ray(fx + o.x, fy + o.y);
                rays.extend(self.offsets[which].iter().map(ray));
            }
        }
    }

    /// How many neighbouring pixels of a row go into one packet of the fast wing: as many as
    /// their grid samples fill (32 pixels of one sample, 2 of sixteen). A packet searches and
    /// shades its rays together: it walks a BVH once for all of them, or tests each object
    /// against them four at a time, and a wider packet shares that work among more rays. One
    /// wherever the samples are traced any other way, draw random numbers (each pixel draws
    /// from its own generator), or fill a packet alone.
    pub fn pixels_per_packet(&self) -> usize {
        let n = self.offsets.len();
        match &self.fast {
            Some(_)
                if self.antialias() == Antialias::Grid
                    && self.path.is_none()
                    && !self.scene.features.sampled
                    && n <= SHADED =>
            {
                PACKET / n
            }
            _ => 1,
        }
    }

    /// The pixels (x, y), (x + 1, y), … of a row, one for each of `out`, from their grid
    /// samples traced as one packet: each exactly what `pixel` gives it (the same samples,
    /// summed in the same order). For up to `pixels_per_packet` pixels, where that is more
    /// than one.
    pub fn grid_pixels(&self, t: &mut Tracer, x: u32, y: u32, out: &mut [DVec3]) {
        let fast = self.fast.as_ref().expect("the fast wing traces packets");
        let n = self.offsets.len();
        let group = self.pixels_per_packet();
        assert!(
            group > 1 && out.len() <= group,
            "{} pixels of {n} samples do not make one packet",
            out.len()
        );
        let mut rays = ArrayVec::<Ray, PACKET>::new();
        for k in 0..out.len() {
            self.grid_rays(x + k as u32, y, 0..n, &mut rays);
        }
        let mut values = [DVec3::ZERO; PACKET];
        let last = x + out.len().saturating_sub(1) as u32;
        let missed = self
            .footprints
            .as_ref()
            .map_or(Missed::UNKNOWN, |f| f.missed(x, last, y));
        trace_packet(t, fast, &rays, missed, &mut values[..rays.len()]);
        for (px, samples) in out.iter_mut().zip(values.chunks(n)) {
            *px = samples.iter().fold(DVec3::ZERO, |sum, v| sum + *v) / n as f64;
        }
    }

    /// Pixel (x, y) from its own samples (box filter) or its corners (adaptive). `corner(i, j)`
    /// gives the value at an image corner (computed once per image by `render`, or on the spot
    /// for a single pixel).
    pub fn pixel(
        &self,
        t: &mut Tracer,
        x: u32,
        y: u32,
        corner: &dyn Fn(&mut Tracer, u32, u32) -> DVec3,
    ) -> DVec3 {
        match self.antialias() {
            Antialias::Grid | Antialias::Jittered => {
                let mut sum = DVec3::ZERO;
                self.for_each_own_sample(t, x, y, &mut |s| sum += s.value);
                sum / self.offsets.len() as f64
            }
            Antialias::Adaptive { .. } => {
                let corners = [
                    corner(t, x, y),
                    corner(t, x + 1, y),
                    corner(t, x, y + 1),
                    corner(t, x + 1, y + 1),
                ];
                self.adaptive(t, x, y, corners, &mut |_| {})
            }
        }
    }

    /// Adaptive antialiasing of pixel (x, y) from its corners, telling `observe` every step
    /// (the lessons' explanations listen; the renderer does not).
    pub fn adaptive(
        &self,
        t: &mut Tracer,
        x: u32,
        y: u32,
        corners: [DVec3; 4],
        observe: &mut dyn FnMut(&Step),
    ) -> DVec3 {
        let Antialias::Adaptive { threshold } = self.antialias() else {
            return corners.iter().sum::<DVec3>() / 4.0;
        };
        let levels = adaptive_levels(self.options.spp);
        t.rng = Rng::for_pixel(self.options.seed, x, y);
        let (fx, fy) = (x as f64, y as f64);
        let mut taken = 0;
        let (value, splits) = adaptive_pixel_observed(
            corners,
            levels,
            threshold,
            &mut |u, v| {
                let point = self.sample_point(x, y, taken);
                taken += 1;
                self.sample(t, fx + u, fy + v, point)
            },
            observe,
        );
        t.stats.aa_splits += splits as u64;
        value
    }

    /// The footprint of every sample of row `sy`, columns `columns`, in a fixed order (source
    /// pixel, then sample). The image and a lone pixel both accumulate through this, so they
    /// add the same numbers in the same order.
    fn splats_of_row(
        &self,
        t: &mut Tracer,
        sy: u32,
        columns: std::ops::RangeInclusive<i64>,
        visit: &mut dyn FnMut(&Footprint),
    ) {
        let w = self.camera.width as i64;
        for sx in columns {
            if sx < 0 || sx >= w {
                continue;
            }
            self.for_each_own_sample(t, sx as u32, sy, &mut |s| {
                visit(&Footprint::new(sx, sy as i64, w, s))
            });
        }
    }

    /// What row `sy`'s samples add to rows sy − 2 … sy + 2.
    fn splat_row(&self, t: &mut Tracer, sy: u32) -> Band {
        let w = self.camera.width;
        let mut band = Band::new(w);
        self.splats_of_row(t, sy, 0..=w as i64 - 1, &mut |f| {
            f.for_each(|dy, tx, weight| {
                band.add((dy + SPLAT_REACH) as usize, tx as usize, weight, f.value)
            })
        });
        band
    }

    /// A single pixel computed on its own: equal, bit for bit, to the rendered pixel.
    pub fn lone_pixel(&self, t: &mut Tracer, x: u32, y: u32) -> DVec3 {
        if !self.splats() {
            return self.pixel(t, x, y, &|t, i, j| self.corner(t, i, j));
        }
        // The rows whose samples reach this pixel, each summed on its own and then added in
        // row order, as `render` adds its bands.
        let h = self.camera.height as i64;
        let (x, y) = (x as i64, y as i64);
        let mut total = Splat::default();
        for sy in (y - SPLAT_REACH).max(0)..=(y + SPLAT_REACH).min(h - 1) {
            let mut row = Splat::default();
            let columns = (x - SPLAT_REACH)..=(x + SPLAT_REACH);
            self.splats_of_row(t, sy as u32, columns, &mut |f| {
                f.for_each(|dy, tx, weight| {
                    if sy + dy == y && tx == x {
                        row.add(weight, weight * f.value);
                    }
                })
            });
            total.add(row.weight, row.sum);
        }
        total.value()
    }
}

/// Where one sample lands through the Gaussian filter: the weights of the columns and of the
/// rows it reaches (the filter is separable, f(x)·f(y)), and its value.
struct Footprint {
    /// The first column reached, and the columns' weights from it on.
    first: i64,
    columns: usize,
    wx: [f64; 2 * SPLAT_REACH as usize + 1],
    /// The weights of rows sy − 2 … sy + 2.
    wy: [f64; 2 * SPLAT_REACH as usize + 1],
    value: DVec3,
}

impl Footprint {
    /// The footprint of sample `s` of pixel (sx, sy) in an image `width` pixels wide.
    #[inline(always)]
    fn new(sx: i64, sy: i64, width: i64, s: Sample) -> Footprint {
        let (px, py) = (sx as f64 + s.uv.x, sy as f64 + s.uv.y);
        let first = (sx - SPLAT_REACH).max(0);
        let last = (sx + SPLAT_REACH).min(width - 1);
        Footprint {
            first,
            columns: (last - first + 1) as usize,
            wx: gaussian_weights(first as f64 + 0.5 - px),
            wy: gaussian_weights((sy - SPLAT_REACH) as f64 + 0.5 - py),
            value: s.value,
        }
    }

    /// `visit(dy, tx, w)` for each pixel (tx, sy + dy) the sample reaches with weight w > 0,
    /// row by row.
    #[inline(always)]
    fn for_each(&self, mut visit: impl FnMut(i64, i64, f64)) {
        for (dy, wy) in (-SPLAT_REACH..).zip(self.wy) {
            if wy == 0.0 {
                continue;
            }
            for (tx, f) in (self.first..).zip(&self.wx[..self.columns]) {
                let weight = wy * f;
                if weight > 0.0 {
                    visit(dy, tx, weight);
                }
            }
        }
    }
}

/// A weighted sum of samples reaching one pixel.
#[derive(Clone, Copy, Debug, Default)]
struct Splat {
    sum: DVec3,
    weight: f64,
}

impl Splat {
    fn add(&mut self, weight: f64, weighted: DVec3) {
        self.sum += weighted;
        self.weight += weight;
    }

    fn value(self) -> DVec3 {
        if self.weight > 0.0 {
            self.sum / self.weight
        } else {
            DVec3::ZERO
        }
    }
}

/// What one row's samples add to the five rows around it.
struct Band {
    width: usize,
    cells: Vec<Splat>,
}

impl Band {
    fn new(width: u32) -> Band {
        let rows = (2 * SPLAT_REACH + 1) as usize;
        Band {
            width: width as usize,
            cells: vec![Splat::default(); rows * width as usize],
        }
    }

    fn add(&mut self, row: usize, x: usize, weight: f64, value: DVec3) {
        self.cells[row * self.width + x].add(weight, weight * value);
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
    render_through(scene, scene.camera.clone(), options, on_row, cancel)
}

/// `render` through another camera than the scene's (the explorer's preview, at the size of
/// its pane), without copying the scene.
pub fn render_through(
    scene: &Scene,
    camera: Camera,
    options: RenderOptions,
    on_row: &(dyn Fn(u32) + Sync),
    cancel: &AtomicBool,
) -> Option<(Image, Stats)> {
    let film = Film::through(scene, camera, options);
    let image = if film.splats() {
        splatted(&film, on_row, cancel, BANDS_HELD_BYTES)
    } else {
        per_pixel(&film, on_row, cancel)
    };
    image.filter(|_| !cancel.load(Ordering::Relaxed))
}

/// Every pixel from its own samples (or its corners, shared with the neighbours).
fn per_pixel(
    film: &Film,
    on_row: &(dyn Fn(u32) + Sync),
    cancel: &AtomicBool,
) -> Option<(Image, Stats)> {
    let cam = &film.camera;
    let (w, h) = (cam.width, cam.height);
    // Adaptive antialiasing first traces the (w+1) × (h+1) pixel corners.
    let (corners, mut stats) = match film.antialias() {
        Antialias::Adaptive { .. } => {
            // `0..h + 1`, not `0..=h`: rayon's inclusive ranges take no `with_max_len`.
            let rows: Vec<(Vec<DVec3>, Stats)> = (0..h + 1)
                .into_par_iter()
                .with_max_len(1)
                .map(|j| {
                    let mut t = film.tracer();
                    let row = (0..=w).map(|i| film.corner(&mut t, i, j)).collect();
                    (row, t.stats)
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
    let corner = |_: &mut Tracer, i: u32, j: u32| corners[(j * (w + 1) + i) as usize];
    let mut image = Image::new(w, h);
    // One row per job (`with_max_len(1)`, here and in the loops above and below). Left to
    // itself, rayon cuts the rows into a few long runs, and a run cannot be stolen once it has
    // started, so a thread out of work would wait for the other's last run. With rows handed
    // out one at a time, the threads finish at most a row apart, however unevenly the cost of
    // rows is spread (a glass lens makes some rows far dearer than others).
    let rows = image
        .pixels
        .par_chunks_mut(w as usize)
        .with_max_len(1)
        .enumerate()
        .map(|(y, row)| {
            let mut t = film.tracer();
            if cancel.load(Ordering::Relaxed) {
                return t.stats;
            }
            let group = film.pixels_per_packet();
            if group > 1 {
                for (k, pixels) in row.chunks_mut(group).enumerate() {
                    film.grid_pixels(&mut t, (k * group) as u32, y as u32, pixels);
                }
            } else {
                for (x, px) in row.iter_mut().enumerate() {
                    *px = film.pixel(&mut t, x as u32, y as u32, &corner);
                }
            }
            on_row(y as u32);
            t.stats
        })
        .reduce(Stats::default, |mut a, b| {
            a.add(&b);
            a
        });
    stats.add(&rows);
    Some((image, stats))
}

/// Samples splatted through the Gaussian filter: every row's samples are spread over the rows
/// around it in parallel, then the bands are added in row order (so the image does not
/// depend on the thread count). The rows go a slice at a time, so that only one slice's bands
/// (five rows of sums each) and the sums of the rows they reach are held at once: a row is
/// final, and goes into the image, once no later band reaches it.
fn splatted(
    film: &Film,
    on_row: &(dyn Fn(u32) + Sync),
    cancel: &AtomicBool,
    held_bytes: usize,
) -> Option<(Image, Stats)> {
    let cam = &film.camera;
    let (w, h) = (cam.width as usize, cam.height as usize);
    let reach = SPLAT_REACH as usize;
    let band_bytes = (2 * reach + 1) * w * std::mem::size_of::<Splat>();
    let slice = (held_bytes / band_bytes.max(1)).max(16);
    let mut image = Image::new(cam.width, cam.height);
    let mut stats = Stats::default();
    // The sums of rows `top − reach ..`, where `top` is the slice's first row.
    let mut sums: Vec<Splat> = vec![];
    for top in (0..h).step_by(slice) {
        let rows = top..(top + slice).min(h);
        sums.resize((rows.len() + 2 * reach) * w, Splat::default());
        let bands: Vec<(Band, Stats)> = rows
            .clone()
            .into_par_iter()
            .with_max_len(1)
            .map(|sy| {
                let mut t = film.tracer();
                if cancel.load(Ordering::Relaxed) {
                    return (Band::new(cam.width), t.stats);
                }
                let band = film.splat_row(&mut t, sy as u32);
                on_row(sy as u32);
                (band, t.stats)
            })
            .collect();
        for (k, (band, s)) in bands.iter().enumerate() {
            stats.add(s);
            // Band row r of image row top + k is image row top + k + r − reach: row k + r of
            // the sums.
            for r in 0..2 * reach + 1 {
                let row = &mut sums[(k + r) * w..(k + r + 1) * w];
                for (total, c) in row.iter_mut().zip(&band.cells[r * band.width..]) {
                    total.add(c.weight, c.sum);
                }
            }
        }
        // Rows before `rows.end − reach` are final; the last 2·reach rows of sums carry over.
        let done = if rows.end == h {
            rows.len() + reach
        } else {
            rows.len()
        };
        for k in 0..done {
            let y = (top + k).checked_sub(reach).filter(|&y| y < h);
            if let Some(y) = y {
                let out = &mut image.pixels[y * w..(y + 1) * w];
                for (px, total) in out.iter_mut().zip(&sums[k * w..(k + 1) * w]) {
                    *px = total.value();
                }
            }
        }
        sums.drain(..done.min(sums.len() / w) * w);
    }
    Some((image, stats))
}

/// How much the splatting holds in bands at once, at most (a slice has at least 16 rows).
const BANDS_HELD_BYTES: usize = 32 << 20;

/// Renders without progress or cancellation.
pub fn render_simple(scene: &Scene, options: RenderOptions) -> (Image, Stats) {
    render(scene, options, &|_| {}, &AtomicBool::new(false)).expect("not cancelled")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Splatting a slice of rows at a time gives the image of splatting them all at once, bit
    /// for bit: rows of 16 (the fewest a slice holds) against one slice of all 100, on a
    /// Gaussian-filtered scene with an edge in every row.
    #[test]
    fn splatting_by_slices_is_splatting_at_once() {
        let yaml =
            "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], fov: 40, width: 37, height: 100 }
antialias: jittered
filter: gaussian
spp: 4
lights: [ { point: [-3, 4, -5], intensity: 1 } ]
materials: { m: { color: [0.9, 0.4, 0.2], kd: 0.8, ks: 0.3, shininess: 8 } }
objects: [ { sphere: { center: [0.3, 0, 0], radius: 1.2 }, material: m } ]
";
        let scene =
            crate::scene::parse(yaml, "slices.yaml", None, &crate::scene::Limits::default())
                .unwrap();
        let options = RenderOptions {
            max_depth: 3,
            spp: 4,
            seed: 7,
            antialias: scene.antialias,
            engine: Default::default(),
        };
        let film = Film::through(&scene, scene.camera.clone(), options);
        assert!(film.splats());
        let cancel = AtomicBool::new(false);
        let (sliced, a) = splatted(&film, &|_| {}, &cancel, 1).unwrap();
        let (whole, b) = splatted(&film, &|_| {}, &cancel, usize::MAX).unwrap();
        assert_eq!(a.rays(), b.rays());
        assert!(whole.pixels.iter().any(|p| p.x > 0.1) && whole.pixels.iter().any(|p| p.x == 0.0));
        assert_eq!(sliced.pixels, whole.pixels);
    }
}
