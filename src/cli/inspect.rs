//! `raytree inspect`: the ray tree of a pixel or of any ray.

use std::process::ExitCode;

use super::args::{depth, Format, SceneArgs, Target};
use super::Failure;
use crate::trace::tree::Inspection;
use crate::trace::{text, Stats, Tracer};

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

/// A path-traced pixel: its estimate over the scene's samples, and the first few paths.
fn paths(a: &Args, scene: &crate::scene::Scene) -> Result<ExitCode, Failure> {
    use crate::trace::path::PathTracer;
    use crate::trace::sampling::Rng;
    const SHOWN: usize = 4;
    let [x, y] = a
        .target
        .pixel
        .ok_or_else(|| Failure("a path-traced scene is inspected by --pixel X,Y".into()))?;
    a.target.ray(scene)?;
    let tracer = PathTracer::new(scene, depth(scene, a.depth)?);
    // The renderer's own sequence for this pixel (seed 0), so the estimate is the pixel's value
    // up to the sub-pixel positions.
    let mut rng = Rng::for_pixel(0, x, y);
    let spp = scene.spp.max(1);
    let mut sum = glam::DVec3::ZERO;
    let mut shown = vec![];
    for k in 0..spp {
        let ray = scene
            .camera
            .ray(x as f64 + rng.uniform(), y as f64 + rng.uniform());
        let mut log = vec![];
        let value = tracer.sample(
            &ray,
            &mut rng,
            &mut Stats::default(),
            (k < SHOWN as u32).then_some(&mut log),
        );
        sum += value;
        if (k as usize) < SHOWN {
            shown.push((value, log));
        }
    }
    let estimate = sum / spp as f64;
    match a.format {
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
    let tracer = Tracer::with_depth(&scene, depth(&scene, a.depth)?);
    let tree = tracer.inspect(&ray, &mut Stats::default());
    let inspection = Inspection {
        pixel: a.target.pixel,
        color: tree.color,
        tree,
    };
    match a.format {
        Format::Json => println!("{}", serde_json::to_string_pretty(&inspection)?),
        Format::Text => {
            if let Some([x, y]) = inspection.pixel {
                println!("pixel ({x}, {y}) = {}", text::color(inspection.color));
            }
            print!("{}", text::tree(&inspection.tree));
        }
    }
    Ok(ExitCode::SUCCESS)
}
