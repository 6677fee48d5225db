//! `raytree explore`: the terminal ray-tree debugger (see src/tui/).

use std::path::PathBuf;
use std::process::ExitCode;

use super::args::{limits, parse_pixel};
use super::Failure;

#[derive(clap::Args, Debug)]
#[command(after_help = "Examples:
  raytree explore
  raytree explore lessons/08-pixel-intensity
  raytree explore lessons/examples/cornell.yaml --pixel 100,120 --depth 3")]
pub struct Args {
    /// A scene file or a lesson folder; none opens the lesson list.
    pub target: Option<PathBuf>,
    /// The pixel picked at the start, X,Y ((0,0) is top-left; default: the centre). Needs a
    /// scene or lesson (the lesson list has no pixels).
    #[arg(long, value_parser = parse_pixel, requires = "target")]
    pub pixel: Option<[u32; 2]>,
    /// The maximum depth at the start (default: the scene's max_depth). Needs a scene or
    /// lesson.
    #[arg(long, requires = "target")]
    pub depth: Option<u32>,
    /// An ASCII preview instead of colour (also chosen by NO_COLOR or TERM=dumb).
    #[arg(long)]
    pub ascii: bool,
    /// Go beyond the budgets that keep a mistake from exhausting memory: 64 million pixels,
    /// 16 MiB scene files, 256 MiB mesh files, 200 000 objects, 4 million triangles (for the
    /// scene as opened and as it is edited).
    #[arg(long)]
    pub allow_huge: bool,
}

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    let target = match a.target.as_deref() {
        None => None,
        // A name without an extension is taken for a lesson's: one that is neither a folder
        // nor a lesson is said to be no lesson (a missing scene file is the loader's to report).
        Some(t) if t.extension().is_none() => Some(crate::lessons::lesson_dir(t)?),
        Some(t) => Some(crate::lessons::find_lesson(t)),
    };
    crate::tui::run(crate::tui::Options {
        target,
        ascii: a.ascii,
        pixel: a.pixel,
        depth: a.depth,
        limits: limits(a.allow_huge),
    })
    .map_err(Failure)?;
    Ok(ExitCode::SUCCESS)
}
