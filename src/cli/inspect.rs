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

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    let scene = a.scene.load()?;
    if scene.integrator == crate::scene::Integrator::Path {
        eprintln!("note: this scene is path traced; shown is the Whitted ray tree of the same scene (its rays, hits and local terms), not a random path sample");
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
