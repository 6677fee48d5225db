//! `raytree homework LESSON --student ID -o DIR`: one student's own variant of a lesson.

use std::path::PathBuf;
use std::process::ExitCode;

use super::Failure;
use crate::lessons::{homework, Lesson};

#[derive(clap::Args, Debug)]
#[command(after_help = "Examples:
  raytree homework lessons/03-local-illumination --student s1234 -o hw/s1234
  raytree check lessons/03-local-illumination --student s1234 --exercise diffuse --answer 0.5")]
pub struct Args {
    /// The lesson: its folder, or its name (its exercises.yaml may declare `vary:` values).
    lesson: PathBuf,
    /// The student's ID: the same ID always gets the same values.
    #[arg(long)]
    student: String,
    /// The folder to write (it must not exist yet, or be empty).
    #[arg(short, long)]
    output: PathBuf,
}

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    let lesson = Lesson::named(&a.lesson)?;
    let (hw, left_out) = homework::write(&lesson, &a.student, &a.output)?;
    for link in &left_out {
        super::output::eprintln(&format!("left out {link}"));
    }
    super::output::println(&format!(
        "{}: homework of {} ({} exercises) from {}",
        a.output.display(),
        a.student.trim(),
        hw.exercises.len(),
        lesson.dir.display()
    ))?;
    match &hw.variant {
        Some(v) => {
            for (path, value) in &v.values {
                super::output::println(&format!("  {path} = {value}"))?;
            }
        }
        None => super::output::println(
            "  (the lesson declares no `vary:` values: everyone gets the same)",
        )?,
    }
    Ok(ExitCode::SUCCESS)
}
