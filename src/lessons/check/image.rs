//! Image questions: the value a pixel renders to (all its primary rays, with the scene's
//! `spp`, antialiasing and integrator), and the work rendering takes: the primary rays traced
//! and the squares adaptive antialiasing splits, for one pixel or the whole image.

use glam::DVec3;

use super::{adaptive, Mistake, Question, Traced, Worked};
use crate::lessons::{Answer, Ask, Exercise};
use crate::render::antialias;
use crate::render::film::Film;
use crate::render::{render_simple, RenderOptions};
use crate::scene::Antialias;
use crate::scene::{Integrator, Scene};
use crate::stats::Stats;
use crate::trace::{text, RayNode};

const FULL_GRID: &str = "that is the full grid of spp rays: adaptive antialiasing splits only the squares whose corners differ by more than the threshold, and a square it does not split takes the mean of its 4 corners";

pub(super) struct PixelValue;

impl Question for PixelValue {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        let (value, _) = rendered_as_set(q)?;
        Ok(Answer::color(value))
    }

    fn mistakes(&self, w: &Worked, ex: &Exercise) -> Vec<Mistake> {
        let options = render_options(&w.scene, ex);
        let mut tries = Vec::new();
        if w.scene.integrator == Integrator::Whitted && (options.spp > 1 || is_adaptive(&options)) {
            tries.push(Mistake {
                answer: Answer::color(w.tree.color),
                hint: "that is the ray through the pixel's centre alone: the pixel is the mean of all its rays".into(),
            });
        }
        if let Some((value, _)) = full_grid(w, ex) {
            tries.push(Mistake {
                answer: Answer::color(value),
                hint: FULL_GRID.into(),
            });
        }
        tries
    }

    fn explain(&self, w: &Worked, ex: &Exercise, _n: &RayNode) -> Result<Vec<String>, String> {
        explain_render(w, ex)
    }
}

pub(super) struct PrimaryRays;

impl Question for PrimaryRays {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        let (_, stats) = rendered_as_set(q)?;
        Ok(Answer::Number(stats.primary_rays as f64))
    }

    fn mistakes(&self, w: &Worked, ex: &Exercise) -> Vec<Mistake> {
        let mut tries = Vec::new();
        if let Some((_, stats)) = full_grid(w, ex) {
            tries.push(Mistake {
                answer: Answer::Number(stats.primary_rays as f64),
                hint: FULL_GRID.into(),
            });
        }
        if is_adaptive(&render_options(&w.scene, ex)) && ex.pixel.is_none() {
            if let Answer::Number(n) = w.expected {
                // The count of a student who traces every pixel's 4 corners anew.
                let (nc, nr) = (w.scene.camera.width as f64, w.scene.camera.height as f64);
                tries.push(Mistake {
                    answer: Answer::Number(n - (nc + 1.0) * (nr + 1.0) + 4.0 * nc * nr),
                    hint: "neighbouring pixels share their corners: each of the (w + 1)·(h + 1) corners of the image is traced once".into(),
                });
            }
        }
        tries
    }

    fn explain(&self, w: &Worked, ex: &Exercise, _n: &RayNode) -> Result<Vec<String>, String> {
        explain_render(w, ex)
    }
}

pub(super) struct SquaresSplit;

impl Question for SquaresSplit {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        let (_, stats) = rendered_as_set(q)?;
        Ok(Answer::Number(stats.aa_splits as f64))
    }

    fn explain(&self, w: &Worked, ex: &Exercise, _n: &RayNode) -> Result<Vec<String>, String> {
        explain_render(w, ex)
    }
}

// --- Rendering what an exercise is about ---

/// How an exercise renders: the scene's own settings (seed 0), with `depth` as max_depth.
fn render_options(scene: &Scene, ex: &Exercise) -> RenderOptions {
    let mut o = RenderOptions::of(scene);
    if let Some(d) = ex.depth {
        o.max_depth = d.clamp(1, 64);
    }
    o
}

/// The exercise rendered with the scene's own settings.
fn rendered_as_set(q: &Traced) -> Result<(DVec3, Stats), String> {
    rendered(q.scene, q.ex, render_options(q.scene, q.ex))
}

fn is_adaptive(options: &RenderOptions) -> bool {
    matches!(options.antialias, Antialias::Adaptive { .. })
}

/// Renders what an image exercise is about: its pixel alone (its value, and the work it took
/// with its corners traced on the spot), or without a pixel the whole image (the work only).
fn rendered(
    scene: &Scene,
    ex: &Exercise,
    options: RenderOptions,
) -> Result<(DVec3, Stats), String> {
    match ex.pixel {
        Some([x, y]) => {
            super::pixel_inside(scene, ex, x, y)?;
            let film = Film::new(scene, options);
            let mut t = film.tracer();
            let value = film.lone_pixel(&mut t, x, y);
            Ok((value, t.stats))
        }
        None if ex.ask == Ask::PixelValue => {
            Err(format!("exercise `{}`: pixel_value needs a pixel", ex.id))
        }
        None => Ok((DVec3::ZERO, render_simple(scene, options).1)),
    }
}

/// The same render with the full grid of `spp` rays in every pixel, when the scene asks for
/// adaptive antialiasing: what a student gets who forgets that it adapts.
fn full_grid(w: &Worked, ex: &Exercise) -> Option<(DVec3, Stats)> {
    let options = render_options(&w.scene, ex);
    if !is_adaptive(&options) {
        return None;
    }
    let grid = RenderOptions {
        antialias: Antialias::Grid,
        ..options
    };
    rendered(&w.scene, ex, grid).ok()
}

// --- Explanation: the rays of a pixel, or of the image ---

/// How the exercise's image is rendered, as `Film::pixel` renders it.
pub(super) struct Rendering<'s> {
    options: RenderOptions,
    pub(super) film: Film<'s>,
    /// The antialiasing the film uses (the path tracer always spreads its samples).
    aa: Antialias,
    pub(super) spp: u32,
    /// How many times adaptive antialiasing may halve a square.
    pub(super) levels: u32,
}

impl<'s> Rendering<'s> {
    fn new(scene: &'s Scene, ex: &Exercise) -> Rendering<'s> {
        let options = render_options(scene, ex);
        let film = Film::new(scene, options);
        let spp = options.spp.max(1);
        Rendering {
            options,
            aa: film.antialias(),
            film,
            spp,
            levels: antialias::adaptive_levels(spp),
        }
    }
}

/// How a pixel (or the whole image) is rendered: its rays, where they go and what they bring.
/// Each sample is recomputed the way `Film::pixel` takes it (same generator, same order), so
/// the values listed are the ones the render averages.
fn explain_render(w: &Worked, ex: &Exercise) -> Result<Vec<String>, String> {
    let r = Rendering::new(&w.scene, ex);
    let mut out = Vec::new();
    if w.scene.integrator == Integrator::Path {
        out.push(format!(
            "integrator: path, max_depth {}: each primary ray carries one random path (seed {})",
            r.options.max_depth, r.options.seed
        ));
        if w.scene.stop_rules.local_at_max_depth {
            out.push(
                "stop rule local_at_max_depth (seed 002): a path cut by the maximum depth adds one sample of the direct light at its last surface"
                    .into(),
            );
        }
    }
    match ex.pixel {
        None => out.extend(whole_image(&r, &w.scene, ex)?),
        Some(pixel) => out.extend(one_pixel(&r, w, ex, pixel)),
    }
    Ok(out)
}

fn whole_image(r: &Rendering, scene: &Scene, ex: &Exercise) -> Result<Vec<String>, String> {
    let (nc, nr) = (scene.camera.width, scene.camera.height);
    let (_, stats) = rendered(scene, ex, r.options)?;
    Ok(match r.aa {
        Antialias::Adaptive { threshold } => adaptive::whole_image(r, threshold, [nc, nr], &stats),
        _ => vec![format!(
            "{} antialiasing: {} primary ray{} in each of the {nc}·{nr} pixels = {}",
            r.aa.name(),
            r.spp,
            if r.spp == 1 { "" } else { "s" },
            stats.primary_rays
        )],
    })
}

fn one_pixel(r: &Rendering, w: &Worked, ex: &Exercise, [x, y]: [u32; 2]) -> Vec<String> {
    let mut out = vec![format!(
        "pixel ({x}, {y}) covers the image square [{x}, {}] × [{y}, {}]; a ray through (u, v) of the pixel goes through the image point ({x} + u, {y} + v)",
        x + 1,
        y + 1
    )];
    let path = w.scene.integrator == Integrator::Path;
    let value = match r.aa {
        Antialias::Grid | Antialias::Jittered => samples(r, [x, y], path, &mut out),
        Antialias::Adaptive { threshold } => adaptive::pixel(r, threshold, [x, y], &mut out),
    };
    if ex.ask == Ask::PixelValue
        && !Answer::color(value).matches(&w.expected, &crate::lessons::Tolerance::absolute(1e-12))
    {
        out.push(format!(
            "(the render gives {}: the steps above do not follow it exactly)",
            w.expected.show()
        ));
    }
    if ex.ask != Ask::PixelValue {
        out.push(pixel_work(r, [x, y]));
    }
    out
}

/// A pixel's grid or jittered samples, their mean, and for the Gaussian filter the weighted
/// mean over the pixels around that the film takes instead.
fn samples(r: &Rendering, [x, y]: [u32; 2], path: bool, out: &mut Vec<String>) -> DVec3 {
    let (aa, spp) = (r.aa, r.spp);
    let n = (spp as f64).sqrt().round() as u32;
    let pattern = match (aa, n * n == spp) {
        _ if path => "each path enters the pixel at the first pair of its sample point, a \
                      scrambled Sobol net (for 2^m samples: one in each cell of every split of \
                      the pixel into 2^j × 2^(m−j) cells)"
            .to_string(),
        (Antialias::Grid, true) => {
            format!("a regular {n} × {n} grid: u, v at the centres of the cells, (k + ½)/{n}")
        }
        (Antialias::Grid, false) => "the R2 sequence (spp is not a square)".to_string(),
        _ => "jittered: one ray at a random point of each cell of the grid".to_string(),
    };
    let how = if path {
        "path-traced samples".to_string()
    } else {
        format!("{} antialiasing", aa.name())
    };
    out.push(format!("{how}, spp {spp}: {pattern}"));
    let samples = r.film.own_samples(&mut r.film.tracer(), x, y);
    for smp in samples.iter().take(16) {
        out.push(format!(
            "{} through (u, v) = ({}, {}): {}",
            if path { "path" } else { "ray" },
            text::num(smp.uv.x),
            text::num(smp.uv.y),
            text::color(smp.value)
        ));
    }
    let values: Vec<DVec3> = samples.iter().map(|s| s.value).collect();
    if values.len() > 16 {
        out.push(format!("… and {} more", values.len() - 16));
    }
    let count = values.len() as f64;
    let mean = values.iter().sum::<DVec3>() / count;
    out.push(format!(
        "pixel = the mean of the {} values = {}",
        values.len(),
        text::color(mean)
    ));
    if aa == Antialias::Jittered && values.len() > 1 {
        out.push(spread(&values, mean));
    }
    if !r.film.splats() {
        return mean;
    }
    let splatted = r.film.lone_pixel(&mut r.film.tracer(), x, y);
    out.push(format!(
        "the Gaussian filter (Mitsuba's: f(d) = e^(−d²/2σ²) − e^(−r²/2σ²), σ = 0.5 px, r = 2 px) then mixes in the samples of the pixels around: pixel = Σ w·L / Σ w over the samples of the 5 × 5 pixels around, w = f(dx)·f(dy) = {}",
        text::color(splatted)
    ));
    splatted
}

/// How far jittered samples scatter, and so how noisy their mean is.
fn spread(values: &[DVec3], mean: DVec3) -> String {
    let count = values.len() as f64;
    let var = values
        .iter()
        .map(|v| (*v - mean) * (*v - mean))
        .sum::<DVec3>()
        / (count - 1.0);
    let sd = DVec3::new(var.x.sqrt(), var.y.sqrt(), var.z.sqrt());
    format!(
        "spread of the samples: standard deviation s = {}; the mean's noise, s/√N = {} for \
         independent samples (samples spread over strata do better)",
        text::color(sd),
        text::color(sd / count.sqrt())
    )
}

/// The work the pixel takes when it is rendered alone, its corners included.
fn pixel_work(r: &Rendering, [x, y]: [u32; 2]) -> String {
    let mut t = r.film.tracer();
    r.film.lone_pixel(&mut t, x, y);
    let lone = t.stats;
    let (corners, rays) = if matches!(r.aa, Antialias::Adaptive { .. }) {
        ("4 corners + ", format!("5·{}", lone.aa_splits))
    } else {
        ("", format!("{}", r.spp))
    };
    format!(
        "rendered alone, the pixel traces {corners}{rays} = {} primary rays and splits {} squares",
        lone.primary_rays, lone.aa_splits
    )
}
