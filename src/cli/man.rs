//! `raytree man`: the manual page (roff) on stdout, or a page per command into a folder.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::CommandFactory;

use super::{Cli, Failure};
use crate::render::write_atomically;

#[derive(clap::Args, Debug)]
#[command(after_help = "Examples:
  raytree man | man -l -
  raytree man -o ~/.local/share/man/man1")]
pub struct Args {
    /// Write raytree.1 and a page per command (raytree-render.1, …) into this folder instead
    /// (made if missing, when its parent folder exists).
    #[arg(short, long, value_name = "DIR")]
    output: Option<PathBuf>,
}

/// A command's page as roff.
fn page(cmd: clap::Command) -> Result<(String, Vec<u8>), Failure> {
    let man = clap_mangen::Man::new(cmd);
    let mut roff = Vec::new();
    man.render(&mut roff)
        .map_err(|e| Failure(format!("cannot write the manual page: {e}")))?;
    Ok((man.get_filename(), roff))
}

/// The pages of `cmd` and of every command under it, each written whole.
fn write_pages(cmd: clap::Command, dir: &Path) -> Result<(), Failure> {
    for sub in cmd.get_subcommands().filter(|s| !s.is_hide_set()).cloned() {
        write_pages(sub, dir)?;
    }
    let (name, roff) = page(cmd)?;
    write_atomically(&dir.join(name), &roff)?;
    Ok(())
}

/// The pages' folder, made if it is missing but its parent is there: like every other output, a
/// folder named with a mistake in its path is refused rather than made, with all the folders
/// above it.
fn make_folder(dir: &Path) -> Result<(), Failure> {
    if dir.is_dir() {
        return Ok(());
    }
    let parent = dir
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if !parent.is_dir() {
        return Err(Failure(format!(
            "{}: cannot create the folder: there is no folder {}",
            dir.display(),
            parent.display()
        )));
    }
    std::fs::create_dir(dir)
        .map_err(|e| Failure(format!("{}: cannot create the folder: {e}", dir.display())))
}

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    // Built, the commands know their full names (raytree-bench-sweep) and lose `help`.
    let mut cmd = Cli::command().disable_help_subcommand(true);
    cmd.build();
    match a.output {
        None => super::output::print_raw(&page(cmd)?.1)?,
        Some(dir) => {
            make_folder(&dir)?;
            write_pages(cmd, &dir)?;
        }
    }
    Ok(ExitCode::SUCCESS)
}
