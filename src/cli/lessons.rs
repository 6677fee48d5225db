//! `raytree lessons`: the course at a glance.

use std::process::ExitCode;

use super::Failure;
use crate::lessons::{all_lessons, lessons_root};

#[derive(clap::Args, Debug)]
pub struct Args {}

pub fn run(_: Args) -> Result<ExitCode, Failure> {
    let root = lessons_root();
    for lesson in all_lessons(&root)? {
        println!("{}  {}", lesson.dir.display(), lesson.title);
        println!("    {}", lesson.summary.trim());
        for ex in &lesson.exercises {
            let q = ex.question.split_whitespace().collect::<Vec<_>>().join(" ");
            println!("    - {:<24} {}", ex.id, q);
        }
        println!();
    }
    Ok(ExitCode::SUCCESS)
}
