//! `raytree explore`: the terminal ray-tree debugger (see src/tui/).

use std::path::PathBuf;
use std::process::ExitCode;

use super::args::parse_pixel;
use super::Failure;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// A scene file or a lesson folder; none opens the lesson list.
    pub target: Option<PathBuf>,
    /// The pixel picked at the start, X,Y ((0,0) is top-left; default: the centre).
    #[arg(long, value_parser = parse_pixel)]
    pub pixel: Option<[u32; 2]>,
    /// The maximum depth at the start (default: the scene's max_depth).
    #[arg(long)]
    pub depth: Option<u32>,
    /// An ASCII preview instead of colour (also chosen by NO_COLOR or TERM=dumb).
    #[arg(long)]
    pub ascii: bool,
}

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    crate::tui::run(crate::tui::Options {
        target: a.target.as_deref().map(crate::lessons::find_lesson),
        ascii: a.ascii,
        pixel: a.pixel,
        depth: a.depth,
    })
    .map_err(Failure)?;
    Ok(ExitCode::SUCCESS)
}
