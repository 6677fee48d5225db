//! `raytree check`: is a homework answer right? Exit 0 right, 1 wrong, 2 usage error.

use std::path::PathBuf;
use std::process::ExitCode;

use serde_json::json;

use super::args::Format;
use super::Failure;
use crate::lessons::progress::Progress;
use crate::lessons::{check, explain, CheckError, Lesson, Solutions};

#[derive(clap::Args, Debug)]
#[command(after_help = "Examples:
  raytree check lessons/08-pixel-intensity --exercise pixel-p --answer 0.87
  raytree check lessons/10-csg --exercise b-difference --answer \"13, 16; 22, 23\" --explain
  raytree check lessons/08-pixel-intensity --exercise pixel-p --answer 0.87 --format json")]
pub struct Args {
    /// The lesson: its folder (lessons/08-pixel-intensity) or its name (08-pixel-intensity).
    lesson: PathBuf,
    /// The exercise id (see `raytree lessons`).
    #[arg(long)]
    exercise: String,
    /// Your answer: a number, a vector `x,y,z`, a segment list `a,b; c,d`, `none` or `tir`.
    #[arg(long, allow_hyphen_values = true, required_unless_present = "explain")]
    answer: Option<String>,
    /// Show the worked derivation, step by step (a lesson whose solutions are hidden only
    /// checks the answer).
    #[arg(long)]
    explain: bool,
    /// Check against this student's own variant of the lesson (see `raytree homework`).
    #[arg(long)]
    student: Option<String>,
    /// Output: text to read, or JSON for programs.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
}

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    let mut lesson = Lesson::named(&a.lesson)?;
    if let Some(student) = &a.student {
        lesson = lesson.variant(student)?;
    }
    // A student may try their own changes in their homework folder: it is checked as it is,
    // and said so.
    for name in lesson.edited_scenes() {
        super::output::eprintln(&format!(
            "note: {} was changed since `raytree homework` wrote it: this checks against the changed scene",
            lesson.dir.join(name).display()
        ));
    }
    let ex = lesson.exercise(&a.exercise)?;
    let verdict = match &a.answer {
        Some(answer) => Some(check(&lesson, ex, answer)?),
        None => None,
    };
    // A lesson that hides its solutions still checks an answer given with --explain, and says
    // that no derivation follows; --explain alone is refused.
    let mut hidden = false;
    let explanation = if a.explain {
        match explain(&lesson, ex) {
            Ok(lines) => Some(lines),
            Err(CheckError::Hidden { .. }) if verdict.is_some() => {
                hidden = true;
                None
            }
            Err(e) => return Err(e.into()),
        }
    } else {
        None
    };
    // Progress is the user's own: an answer checked for another student (grading) is not
    // theirs. And it is a convenience: a data folder that cannot be written does not fail a
    // check.
    if a.student.is_none() && verdict.as_ref().is_some_and(|v| v.correct) {
        if let Err(e) = Progress::record(&lesson, &ex.id) {
            super::output::eprintln(&format!("raytree: progress not saved: {e}"));
        }
    }
    match a.format {
        Format::Json => {
            let mut doc = json!({
                "lesson": lesson.id,
                "exercise": ex.id,
            });
            if let Some(s) = &a.student {
                doc["student"] = json!(s);
            }
            if let Some(v) = &verdict {
                doc["correct"] = json!(v.correct);
                doc["answer"] = v.given.to_json();
                // A lesson that hides its solutions does not give a wrong answer the right one
                // (the text says only that it is wrong), nor the allowance around it, which a
                // relative rule makes a multiple of the answer: only the rule.
                let shown = v.correct || lesson.solutions != Solutions::Hidden;
                doc["expected"] = if shown {
                    v.expected.to_json()
                } else {
                    serde_json::Value::Null
                };
                doc["tolerance"] = if shown {
                    json!(v.expected.allowance(&v.tolerance))
                } else {
                    serde_json::Value::Null
                };
                doc["tolerance_rule"] = json!(v.tolerance);
                doc["hint"] = json!(v.hint);
                doc["model"] = json!(v.model);
            }
            if let Some(lines) = &explanation {
                doc["explanation"] = json!(lines);
            }
            if hidden {
                doc["explanation_hidden"] = json!(true);
            }
            super::output::print_json(doc)?;
        }
        Format::Text => {
            if let Some(v) = &verdict {
                super::output::println(&v.message().to_string())?;
            }
            if let Some(lines) = &explanation {
                super::output::println("")?;
                for line in lines {
                    super::output::println(&line.to_string())?;
                }
            }
            if hidden {
                super::output::println(&format!(
                    "the worked solution is hidden for lesson {} (solutions: hidden)",
                    lesson.id
                ))?;
            }
        }
    }
    Ok(match verdict {
        Some(v) if !v.correct => ExitCode::from(1),
        _ => ExitCode::SUCCESS,
    })
}
