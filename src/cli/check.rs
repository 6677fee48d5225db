//! `raytree check`: is a homework answer right? Exit 0 right, 1 wrong, 2 usage error.

use std::path::PathBuf;
use std::process::ExitCode;

use super::Failure;
use crate::lessons::{check, explain, Lesson};

#[derive(clap::Args, Debug)]
pub struct Args {
    /// The lesson folder (e.g. lessons/08-pixel-intensity).
    lesson: PathBuf,
    /// The exercise id (see `raytree lessons`).
    #[arg(long)]
    exercise: String,
    /// Your answer: a number, a vector `x,y,z`, a segment list `a,b; c,d` (`none` for an empty
    /// one) or `tir`.
    #[arg(long, allow_hyphen_values = true, required_unless_present = "explain")]
    answer: Option<String>,
    /// Show the worked derivation, step by step.
    #[arg(long)]
    explain: bool,
}

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    let lesson = Lesson::load(&a.lesson)?;
    let ex = lesson.exercise(&a.exercise)?;
    let mut code = ExitCode::SUCCESS;
    let mut out = String::new();
    if let Some(answer) = &a.answer {
        let verdict = check(&lesson, ex, answer)?;
        out += &format!("{}\n", verdict.message());
        if !verdict.correct {
            code = ExitCode::from(1);
        }
    }
    if a.explain {
        out += "\n";
        for line in explain(&lesson, ex)? {
            out += &format!("{line}\n");
        }
    }
    super::output::print(&out)?;
    Ok(code)
}
