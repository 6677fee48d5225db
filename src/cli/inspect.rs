//! `raytree inspect`: the ray tree of a pixel or of any ray.

use std::process::ExitCode;

use super::args::{depth, SceneArgs, Target};
use super::Failure;
use crate::diagram::dot::dot;
use crate::sampling::Rng;
use crate::stats::Stats;
use crate::trace::tree::Inspection;
use crate::trace::{text, Tracer};

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    #[command(flatten)]
    target: Target,
    /// Rays per path, primary included (overrides the scene's max_depth).
    #[arg(long)]
    depth: Option<u32>,
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
}

/// How the tree is printed.
#[derive(clap::ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Format {
    #[default]
    Text,
    Json,
    /// Graphviz: one node per ray, edges labelled with their coefficients.
    Dot,
}

/// A path-traced pixel: its estimate over the scene's samples, and the first few paths.
fn paths(a: &Args, scene: &crate::scene::Scene) -> Result<ExitCode, Failure> {
    use crate::render::antialias::{cell, grid_offsets, jitter};
    use crate::render::film::Film;
    use crate::render::RenderOptions;
    use crate::trace::path::PathTracer;
    const SHOWN: usize = 4;
    let [x, y] = a
        .target
        .pixel
        .ok_or_else(|| Failure("a path-traced scene is inspected by --pixel X,Y".into()))?;
    a.target.ray(scene)?;
    let max_depth = depth(scene, a.depth)?;
    let tracer = PathTracer::new(scene, max_depth);
    let options = RenderOptions {
        max_depth,
        ..RenderOptions::of(scene)
    };
    // The pixel's value as rendered (seed 0), and its first samples replayed with the same
    // random numbers, so the paths shown are the ones that went into it.
    let film = Film::new(scene, options);
    let estimate = film.lone_pixel(&mut film.tracer(), x, y);
    let spp = options.spp.max(1);
    let offsets = grid_offsets(spp);
    let cell = cell(offsets.len());
    let mut rng = Rng::for_pixel(options.seed, x, y);
    let mut shown = vec![];
    for o in offsets.iter().take(SHOWN) {
        let j = jitter(*o, cell, &mut rng);
        let ray = scene.camera.ray(x as f64 + j.x, y as f64 + j.y);
        let mut log = vec![];
        let value = tracer.sample(&ray, &mut rng, &mut Stats::default(), Some(&mut log));
        shown.push((value, log));
    }
    match a.format {
        Format::Dot => {
            return Err(Failure(
                "--format dot draws a Whitted ray tree; a path-traced scene has paths, not a tree (use --format json)".into(),
            ))
        }
        Format::Json => {
            let doc = serde_json::json!({
                "pixel": [x, y],
                "integrator": "path",
                "samples": spp,
                "color": estimate.to_array(),
                "paths": shown.iter().map(|(v, log)| serde_json::json!({ "value": v.to_array(), "vertices": log })).collect::<Vec<_>>(),
            });
            println!("{}", serde_json::to_string_pretty(&doc)?);
        }
        Format::Text => {
            println!(
                "pixel ({x}, {y}), path traced: estimate {} from {spp} samples",
                text::color(estimate)
            );
            for (k, (value, log)) in shown.iter().enumerate() {
                println!("sample {}: {}", k + 1, text::color(*value));
                for v in log {
                    println!(
                        "  {:<10} {:<14} at {}  throughput {}  adds {}",
                        v.event,
                        v.object.as_deref().unwrap_or("-"),
                        text::vec3(v.point),
                        text::color(v.throughput),
                        text::color(v.added)
                    );
                }
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    let scene = a.scene.load()?;
    if scene.integrator == crate::scene::Integrator::Path {
        return paths(&a, &scene);
    }
    let ray = a.target.ray(&scene)?;
    // A pixel's glossy and frosted rays come from its own generator, as in the renderer.
    let rng = match a.target.pixel {
        Some([x, y]) => Rng::for_pixel(0, x, y),
        None => Rng::for_pixel(0, 0, 0),
    };
    let tree = Tracer::new(&scene)
        .with_depth(depth(&scene, a.depth)?)
        .with_rng(rng)
        .inspect(&ray);
    let inspection = Inspection {
        pixel: a.target.pixel,
        color: tree.color,
        tree,
    };
    match a.format {
        Format::Json => println!("{}", serde_json::to_string_pretty(&inspection)?),
        Format::Dot => {
            let title = match inspection.pixel {
                Some([x, y]) => format!("pixel ({x}, {y}): I = {}", text::color(inspection.color)),
                None => format!("ray {} → {}", text::vec3(ray.origin), text::vec3(ray.dir)),
            };
            print!("{}", dot(&inspection.tree, Some(&scene), &title));
        }
        Format::Text => {
            if let Some([x, y]) = inspection.pixel {
                println!("pixel ({x}, {y}) = {}", text::color(inspection.color));
            }
            print!("{}", text::tree(&inspection.tree));
        }
    }
    Ok(ExitCode::SUCCESS)
}
