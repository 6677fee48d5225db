//! `raytree explore`: the terminal ray-tree debugger (being written; see src/tui/).

use std::path::PathBuf;
use std::process::ExitCode;

use super::Failure;

#[derive(clap::Args, Debug)]
pub struct Args {
    /// A scene file or a lesson folder; none opens the lesson list.
    pub target: Option<PathBuf>,
}

pub fn run(_: Args) -> Result<ExitCode, Failure> {
    Err(Failure("the explorer is not built yet".into()))
}
