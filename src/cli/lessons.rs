//! `raytree lessons`: the course at a glance.

use std::process::ExitCode;

use super::Failure;
use crate::lessons::{all_lessons, lessons_root};

#[derive(clap::Args, Debug)]
pub struct Args {}

pub fn run(_: Args) -> Result<ExitCode, Failure> {
    let root = lessons_root();
    let mut out = String::new();
    for lesson in all_lessons(&root)? {
        out += &format!("{}  {}\n", lesson.dir.display(), lesson.title);
        out += &format!("    {}\n", lesson.summary.trim());
        for ex in &lesson.exercises {
            let q = ex.question.split_whitespace().collect::<Vec<_>>().join(" ");
            out += &format!("    - {:<24} {}\n", ex.id, q);
        }
        out += "\n";
    }
    super::output::print(&out)?;
    Ok(ExitCode::SUCCESS)
}
