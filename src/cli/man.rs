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
    /// Write raytree.1 and a page per command (raytree-render.1, …) into this folder instead.
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

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    // Built, the commands know their full names (raytree-bench-sweep) and lose `help`.
    let mut cmd = Cli::command().disable_help_subcommand(true);
    cmd.build();
    match a.output {
        None => super::output::print_raw(&page(cmd)?.1)?,
        Some(dir) => {
            // create_dir_all takes a file in the way for a folder that exists.
            if dir.exists() && !dir.is_dir() {
                let why = "not a folder: -o names the folder the pages are written into";
                return Err(Failure(format!("{}: {why}", dir.display())));
            }
            std::fs::create_dir_all(&dir)
                .map_err(|e| Failure(format!("{}: cannot create: {e}", dir.display())))?;
            write_pages(cmd, &dir)?;
        }
    }
    Ok(ExitCode::SUCCESS)
}
