//! `raytree completions SHELL`: the shell's completion script, on stdout.

use std::process::ExitCode;

use clap::CommandFactory;

use super::{Cli, Failure};

#[derive(clap::Args, Debug)]
#[command(after_help = "Examples:
  raytree completions bash > ~/.local/share/bash-completion/completions/raytree
  raytree completions zsh > ~/.zfunc/_raytree
  raytree completions fish > ~/.config/fish/completions/raytree.fish")]
pub struct Args {
    /// The shell to complete raytree's commands and options in.
    #[arg(value_enum)]
    shell: clap_complete::Shell,
}

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    let mut script = Vec::new();
    clap_complete::generate(a.shell, &mut Cli::command(), "raytree", &mut script);
    super::output::print_raw(&script)?;
    Ok(ExitCode::SUCCESS)
}
