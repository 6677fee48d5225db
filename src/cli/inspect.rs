//! `raytree inspect`: the ray tree of a pixel or of any ray.
//!
//! A pixel's value is the one `render` gives it (all its samples, through the scene's filter,
//! with the same seed), computed by the film on its own; the tree shown is then that of the
//! ray through the pixel's centre, or of one of its samples (`--sample K`), and says which.

use std::process::ExitCode;

use glam::{DVec2, DVec3};

use super::args::{depth, FilmArgs, SceneArgs, Target};
use super::output::{eprintln, print};
use super::Failure;
use crate::diagram::dot::dot;
use crate::render::antialias::{cell, grid_offsets, jitter};
use crate::render::film::Film;
use crate::render::{Engine, RenderOptions};
use crate::sampling::Rng;
use crate::scene::{Antialias, Filter, Scene};
use crate::trace::budget::{affordable_depth, budget_note};
use crate::trace::tree::Inspection;
use crate::trace::{text, Tracer};

#[derive(clap::Args, Debug)]
#[command(after_help = "Examples:
  raytree inspect lessons/08-pixel-intensity/scene.yaml --pixel 30,30
  raytree inspect lessons/05-reflection/scene.yaml --ray 0,3,-4:0,-3,4 --format json
  raytree inspect lessons/08-pixel-intensity/scene.yaml --pixel 30,30 --format dot | dot -Tsvg > tree.svg")]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    #[command(flatten)]
    target: Target,
    /// The image the pixel is one of, as `render` makes it.
    #[command(flatten)]
    film: FilmArgs,
    /// Rays per path, primary included (overrides the scene's max_depth).
    #[arg(long)]
    depth: Option<u32>,
    /// Seed of the random numbers, as for `render` (jittered samples, glossy rays, paths).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Show the tree of the pixel's K-th sample (1 … spp) instead of its centre ray (on a
    /// path-traced scene: sample K's path instead of the first four).
    #[arg(long, value_name = "K", requires = "pixel", conflicts_with = "ray")]
    sample: Option<u32>,
    /// Output: text to read, JSON for programs, or Graphviz (dot).
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
}

/// How the tree is printed.
#[derive(clap::ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Format {
    /// The tree as indented lines to read.
    #[default]
    Text,
    /// One JSON document (with "raytree_version") for programs.
    Json,
    /// Graphviz: one node per ray, edges labelled with their coefficients.
    Dot,
}

/// A path-traced pixel: its estimate over the scene's samples, and the first few paths. Its
/// ray tree (JSON's `tree`, and the Graphviz graph) is the Whitted reading of its centre
/// ray, as the explorer shows beside the paths: a path is one sampled chain of bounces, not
/// a tree.
fn paths(a: &Args, scene: &Scene, [x, y]: [u32; 2]) -> Result<ExitCode, Failure> {
    const SHOWN: u32 = 4;
    a.target.ray(scene)?;
    let max_depth = depth(scene, a.depth)?;
    let options = RenderOptions {
        max_depth,
        seed: a.seed,
        ..RenderOptions::of(scene)
    };
    // The pixel's value as rendered, and its first samples replayed with the same random
    // numbers, so the paths shown are the ones that went into it.
    let film = Film::new(scene, options);
    let estimate = film.lone_pixel(&mut film.tracer(), x, y);
    let spp = options.spp.max(1);
    let which = match a.sample {
        Some(k) if (1..=spp).contains(&k) => k - 1..k,
        Some(k) => return Err(sample_out_of_range(k, spp)),
        None => 0..SHOWN,
    };
    let shown = film.replay_paths(x, y, which.clone());
    let whitted = || {
        Tracer::new(scene)
            .with_depth(max_depth)
            .with_rng(Rng::for_pixel(options.seed, x, y))
            .inspect(&scene.camera.pixel_ray(x, y))
    };
    match a.format {
        Format::Json => {
            let doc = serde_json::json!({
                "pixel": [x, y],
                "integrator": "path",
                "samples": spp,
                "seed": options.seed,
                "color": estimate.to_array(),
                "paths": which.zip(&shown).map(|(i, (v, log))| serde_json::json!({ "sample": i + 1, "value": v.to_array(), "vertices": log })).collect::<Vec<_>>(),
                "tree": whitted(),
                "traced": "whitted reading of the centre ray",
            });
            super::output::print_json(doc)?;
        }
        Format::Dot => {
            let title = format!(
                "pixel ({x}, {y}): the Whitted reading of its centre ray, not the path-traced estimate {}",
                text::color(estimate)
            );
            print(&dot(&whitted(), Some(scene), &title))?;
        }
        Format::Text => {
            let mut out = format!(
                "pixel ({x}, {y}), path traced: estimate {} from {spp} samples\n",
                text::color(estimate)
            );
            for (i, (value, log)) in which.zip(&shown) {
                out += &format!("sample {}: {}\n", i + 1, text::color(*value));
                for v in log {
                    // A path that leaves the scene meets no point: it goes off in a direction.
                    let place = match v.toward {
                        Some(d) => format!("toward {}", text::vec3(d)),
                        None => format!(
                            "at {}",
                            text::point_at(v.point, v.point.abs().max_element())
                        ),
                    };
                    out += &format!(
                        "  {:<10} {:<14} {place}  throughput {}  adds {}\n",
                        v.event,
                        v.object.as_deref().unwrap_or("-"),
                        text::color(v.throughput),
                        text::color(v.added)
                    );
                }
            }
            print(&out)?;
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// Which ray of a pixel the tree follows.
#[derive(Clone, Copy)]
enum Traced {
    /// The ray through the pixel's centre.
    Centre,
    /// Sample K (from 1) of the pixel, through this image point.
    Sample(u32, DVec2),
}

/// What `render` computes for a pixel, and how.
struct Rendered {
    value: DVec3,
    options: RenderOptions,
    filter: Filter,
}

impl Rendered {
    /// A pixel whose one sample is its centre ray, through a box: the tree's value is the
    /// pixel's, and nothing more needs saying.
    fn is_centre_ray(&self) -> bool {
        centre_ray_is_the_pixel(&self.options, self.filter)
    }

    fn describe(&self) -> String {
        let spp = self.options.spp.max(1);
        let rays = match self.options.antialias {
            // Not a count of samples: the corners, and as many more as the splits ask for.
            Antialias::Adaptive { threshold } => {
                let side = 1 << crate::render::antialias::adaptive_levels(spp);
                format!(
                    "adaptive: rays at the corners, squares split down to {side} × {side} where \
                     corners differ by more than {}",
                    text::num(threshold)
                )
            }
            aa => format!(
                "{spp} sample{} ({})",
                if spp == 1 { "" } else { "s" },
                aa.name()
            ),
        };
        format!(
            "{rays}, {} filter, seed {}",
            match self.filter {
                Filter::Box => "box",
                Filter::Gaussian => "Gaussian",
            },
            self.options.seed
        )
    }
}

/// Whether a Whitted scene renders each pixel as its one centre ray through a box filter, so
/// that the tree of that ray gives the pixel's value.
pub(super) fn centre_ray_is_the_pixel(options: &RenderOptions, filter: Filter) -> bool {
    options.spp <= 1 && options.antialias == Antialias::Grid && filter == Filter::Box
}

fn sample_out_of_range(k: u32, spp: u32) -> Failure {
    Failure(format!(
        "--sample must be between 1 and {spp} (the pixel's samples), got {k}"
    ))
}

/// The ray of pixel (x, y) the tree follows, and the random numbers it starts with: those the
/// film gives that ray when it renders the pixel (the samples before it are replayed, so
/// glossy rays draw the same numbers).
fn pixel_ray(
    scene: &Scene,
    film: &Film,
    options: &RenderOptions,
    [x, y]: [u32; 2],
    sample: Option<u32>,
) -> Result<(crate::geometry::Ray, Rng, Traced), Failure> {
    let rng = Rng::for_pixel(options.seed, x, y);
    let Some(k) = sample else {
        return Ok((scene.camera.pixel_ray(x, y), rng, Traced::Centre));
    };
    let spp = options.spp.max(1);
    if matches!(film.antialias(), Antialias::Adaptive { .. }) {
        return Err(Failure(
            "--sample is for grid and jittered sampling (adaptive antialiasing traces the pixel's corners)".into(),
        ));
    }
    if !(1..=spp).contains(&k) {
        return Err(sample_out_of_range(k, spp));
    }
    let offsets = grid_offsets(spp);
    let cell = cell(offsets.len());
    let jittered = film.antialias() == Antialias::Jittered;
    let mut t = film.tracer();
    t.rng = rng;
    for (i, o) in offsets.iter().enumerate() {
        let uv = if jittered {
            jitter(*o, cell, &mut t.rng)
        } else {
            *o
        };
        let (px, py) = (x as f64 + uv.x, y as f64 + uv.y);
        if i as u32 + 1 == k {
            let at = DVec2::new(px, py);
            return Ok((scene.camera.ray(px, py), t.rng, Traced::Sample(k, at)));
        }
        film.sample(&mut t, px, py, film.sample_point(x, y, i as u32));
    }
    unreachable!("k is at most the number of offsets")
}

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    let mut scene = a.scene.load()?;
    a.film
        .apply(&mut scene, &super::args::limits(a.scene.allow_huge))?;
    let path_traced = scene.integrator == crate::scene::Integrator::Path;
    if let (true, Some(pixel)) = (path_traced, a.target.pixel) {
        return paths(&a, &scene, pixel);
    }
    let ray = a.target.ray(&scene)?;
    let max_depth = depth(&scene, a.depth)?;
    let film_options = a.target.pixel.map(|_| RenderOptions {
        max_depth,
        seed: a.seed,
        engine: Engine::Core,
        ..RenderOptions::of(&scene)
    });
    let film = film_options.map(|options| Film::new(&scene, options));
    let (ray, rng, traced) = match (&film, &film_options, a.target.pixel) {
        (Some(film), Some(options), Some(pixel)) => {
            pixel_ray(&scene, film, options, pixel, a.sample)?
        }
        // An explicit ray's glossy and frosted rays come from pixel (0, 0)'s generator.
        _ => (ray, Rng::for_pixel(a.seed, 0, 0), Traced::Centre),
    };
    // A tree of every ray to a deep recursion could fill the memory: it is shown as deep as
    // it stays within the budget of rays. Said before the pixel's value is rendered at the
    // full depth, which then takes as long as the tree is large.
    let shown_depth = affordable_depth(&scene, &ray, max_depth, &|| rng.clone());
    if shown_depth < max_depth {
        let mut note = budget_note(shown_depth);
        if a.target.pixel.is_some() {
            note.push_str(&format!(
                "; the pixel's value is rendered at depth {max_depth}, which may take very long (Ctrl-C stops it; a smaller --depth is quick)"
            ));
        }
        eprintln(&format!("warning: {note}"));
    }
    let rendered = match (&film, film_options, a.target.pixel) {
        (Some(film), Some(options), Some([x, y])) => Some(Rendered {
            value: film.lone_pixel(&mut film.tracer(), x, y),
            options,
            filter: scene.filter,
        }),
        _ => None,
    };
    let tree = Tracer::new(&scene)
        .with_depth(shown_depth)
        .with_rng(rng)
        .inspect(&ray);
    let inspection = Inspection {
        pixel: a.target.pixel,
        color: rendered.as_ref().map_or(tree.color, |r| r.value),
        tree,
    };
    // Which ray the tree is of, where the pixel is more than its centre ray.
    let which_tree = rendered
        .as_ref()
        .filter(|r| !(r.is_centre_ray() && a.sample.is_none()))
        .map(|r| match traced {
            Traced::Centre => format!(
                "the tree of the ray through the pixel's centre (I = {})",
                text::color(inspection.tree.color)
            ),
            Traced::Sample(k, at) => format!(
                "the tree of sample {k} of {}, through ({}, {}) (I = {})",
                r.options.spp.max(1),
                text::num(at.x),
                text::num(at.y),
                text::color(inspection.tree.color)
            ),
        });
    match a.format {
        Format::Json => {
            let mut doc = serde_json::to_value(&inspection)?;
            if path_traced {
                doc["integrator"] = serde_json::json!("path");
                doc["traced"] = serde_json::json!("whitted reading of the ray");
            }
            if let Some(r) = &rendered {
                doc["rendered"] = serde_json::json!({
                    "samples": r.options.spp.max(1),
                    "antialias": r.options.antialias.name(),
                    "filter": match r.filter { Filter::Box => "box", Filter::Gaussian => "gaussian" },
                    "seed": r.options.seed,
                });
                doc["traced"] = match traced {
                    Traced::Centre => serde_json::json!("centre"),
                    Traced::Sample(k, at) => {
                        serde_json::json!({ "sample": k, "at": [at.x, at.y] })
                    }
                };
            }
            super::output::print_json(doc)?;
        }
        Format::Dot => {
            let title = match inspection.pixel {
                Some([x, y]) => match &which_tree {
                    Some(which) => format!(
                        "pixel ({x}, {y}): I = {}; {which}",
                        text::color(inspection.color)
                    ),
                    None => format!("pixel ({x}, {y}): I = {}", text::color(inspection.color)),
                },
                None if path_traced => format!(
                    "ray {} → {}: its Whitted reading (the scene is path traced)",
                    text::point(ray.origin),
                    text::vec3(ray.dir)
                ),
                None => format!("ray {} → {}", text::point(ray.origin), text::vec3(ray.dir)),
            };
            print(&dot(&inspection.tree, Some(&scene), &title))?;
        }
        Format::Text => {
            let mut out = String::new();
            if path_traced {
                // Only an explicit ray gets here: a pixel shows its paths.
                out += "the Whitted reading of this ray (the scene is path traced: \
                        --pixel X,Y shows a pixel's estimate and its paths)\n";
            }
            if let (Some([x, y]), Some(r)) = (inspection.pixel, &rendered) {
                out += &format!("pixel ({x}, {y}) = {}", text::color(r.value));
                match &which_tree {
                    None => out += "\n",
                    Some(which) => {
                        out += &format!("  as rendered: {}\n", r.describe());
                        out += &format!("{which}:\n");
                    }
                }
            }
            out += &text::tree(&inspection.tree);
            print(&out)?;
        }
    }
    Ok(ExitCode::SUCCESS)
}
