//! `raytree diagram`: a pixel's (or a ray's) rays drawn in a cross-section of the scene, beside
//! its ray tree as a graph: a figure for handouts and slides, as SVG or PNG.

use std::path::PathBuf;
use std::process::ExitCode;

use super::args::{depth, SceneArgs, Target};
use super::inspect::centre_ray_is_the_pixel;
use super::output::eprintln;
use super::Failure;
use crate::diagram::figure::Figure;
use crate::diagram::{raster, Drawing, ViewChoice};
use crate::render::{write_atomically, RenderOptions};
use crate::sampling::Rng;
use crate::scene::Integrator;
use crate::trace::budget::{affordable_depth, budget_note};
use crate::trace::{text, Tracer};

#[derive(clap::Args, Debug)]
#[command(after_help = "Examples:
  raytree diagram lessons/08-pixel-intensity/scene.yaml --pixel 30,30 -o pixel.svg
  raytree diagram lessons/06-refraction/scene.yaml --pixel 80,60 --view side -o refraction.png")]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    #[command(flatten)]
    target: Target,
    /// The figure: FIG.svg, or FIG.png (the same figure drawn by resvg).
    #[arg(short, long)]
    output: PathBuf,
    /// The view: from above (top), from the side (side, z across), from the front (front,
    /// x across), or the one that best holds the rays (auto).
    #[arg(long, default_value_t = ViewChoice::Auto, value_parser = |s: &str| s.parse::<ViewChoice>())]
    view: ViewChoice,
    /// Rays per path, primary included (overrides the scene's max_depth).
    #[arg(long)]
    depth: Option<u32>,
    /// The figure's width in pixels, 400 to 8000.
    #[arg(long, default_value_t = 1200)]
    width: u32,
    /// The figure's height in pixels, 200 to 8000.
    #[arg(long, default_value_t = 640)]
    height: u32,
}

enum Kind {
    Svg,
    Png,
}

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    let kind = match a.output.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("svg") => Kind::Svg,
        Some(e) if e.eq_ignore_ascii_case("png") => Kind::Png,
        _ => {
            return Err(Failure(format!(
                "{}: the figure is written as .svg or .png",
                a.output.display()
            )))
        }
    };
    // Narrower, the legend's rows would leave the section no room, and the graph's boxes no
    // room for a word.
    let least = crate::diagram::figure::MIN_WIDTH;
    for (name, v, least) in [("--width", a.width, least), ("--height", a.height, 200)] {
        if !(least..=8000).contains(&v) {
            return Err(Failure(format!(
                "{name} must be between {least} and 8000 pixels, got {v}"
            )));
        }
    }
    let scene = a.scene.load()?;
    let ray = a.target.ray(&scene)?;
    let rng = match a.target.pixel {
        Some([x, y]) => Rng::for_pixel(0, x, y),
        None => Rng::for_pixel(0, 0, 0),
    };
    // Drawn as deep as the tree stays within the budget of rays.
    let asked = depth(&scene, a.depth)?;
    let shown_depth = affordable_depth(&scene, &ray, asked, &|| rng.clone());
    if shown_depth < asked {
        eprintln(&format!("warning: {}", budget_note(shown_depth)));
    }
    let tree = Tracer::new(&scene)
        .with_depth(shown_depth)
        .with_rng(rng)
        .inspect(&ray);
    let pixel = a.target.pixel.map(|[x, y]| (x, y));
    let drawing = Drawing::new(&scene, &tree, &tree, a.view, pixel);
    // "08-pixel-intensity/scene.yaml": the folder says which lesson.
    let path = &a.scene.scene;
    let name = [path.parent().and_then(|p| p.file_name()), path.file_name()]
        .into_iter()
        .flatten()
        .map(|s| s.to_string_lossy().into_owned())
        .collect::<Vec<_>>()
        .join("/");
    let options = RenderOptions::of(&scene);
    let at = match pixel {
        Some((x, y)) if scene.integrator == Integrator::Path => format!(
            "pixel ({x}, {y}): the Whitted reading of its centre ray, not the path-traced estimate"
        ),
        Some((x, y)) if !centre_ray_is_the_pixel(&options, scene.filter) => {
            format!("pixel ({x}, {y}): its centre ray, not the pixel's antialiased value")
        }
        Some((x, y)) => format!("pixel ({x}, {y})"),
        None => format!("ray {} → {}", text::vec3(ray.origin), text::vec3(ray.dir)),
    };
    let figure = Figure {
        scene: &scene,
        tree: &tree,
        drawing: &drawing,
        title: format!(
            "{name} · {at} · I = {} · {}",
            text::color(tree.color),
            drawing.view.caption()
        ),
        width: a.width,
        height: a.height,
    };
    let svg = figure.svg().to_string();
    let bytes = match kind {
        Kind::Svg => svg.into_bytes(),
        Kind::Png => {
            if !raster::have_fonts() {
                super::output::eprintln(
                    "warning: no fonts found on this system: the PNG has no labels",
                );
            }
            raster::png(&svg)?
        }
    };
    write_atomically(&a.output, &bytes)?;
    Ok(ExitCode::SUCCESS)
}
