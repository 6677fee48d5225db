//! `raytree preview`: the scene as half-block characters (or ASCII) on stdout.

use std::process::ExitCode;

use super::args::{depth, SceneArgs};
use super::Failure;
use crate::render::preview::{to_text, ColorMode};
use crate::render::{render_simple, RenderOptions};

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    /// Width in characters (default: the terminal's, or 80).
    #[arg(long)]
    columns: Option<u32>,
    /// Plain ASCII intensity ramp instead of colour (also chosen by NO_COLOR or TERM=dumb).
    #[arg(long)]
    ascii: bool,
    #[arg(long)]
    depth: Option<u32>,
}

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    let scene = a.scene.load()?;
    let columns = a
        .columns
        .or_else(|| crossterm::terminal::size().ok().map(|(c, _)| c as u32))
        .unwrap_or(80)
        .clamp(4, 1000);
    let (w, h) = (scene.camera.width as f64, scene.camera.height as f64);
    // Two pixels per character cell vertically; cells are about twice as tall as wide.
    let rows = ((columns as f64 * h / w).round() as u32).max(2);
    let mut small = scene.clone();
    small.camera = scene.camera.resized(columns, rows);
    let options = RenderOptions {
        max_depth: depth(&scene, a.depth)?,
        spp: scene.spp.min(4),
        ..RenderOptions::of(&scene)
    };
    let (image, _) = render_simple(&small, options);
    let mode = if a.ascii {
        ColorMode::Ascii
    } else {
        ColorMode::detect()
    };
    super::output::print_raw(to_text(&image, mode).as_bytes())?;
    Ok(ExitCode::SUCCESS)
}
