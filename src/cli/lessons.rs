//! `raytree lessons`: the course at a glance, with a ✓ for every exercise answered right; a
//! teacher's own folder of lessons; `lessons validate DIR` checks a folder of lessons.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use serde_json::json;

use super::args::Format;
use super::Failure;
use crate::lessons::progress::Progress;
use crate::lessons::validate::validate;
use crate::lessons::{lesson_dir, lessons_root, Lesson, Solutions};

#[derive(clap::Args, Debug)]
#[command(args_conflicts_with_subcommands = true)]
#[command(after_help = "Examples:
  raytree lessons
  raytree lessons 08-pixel-intensity
  raytree lessons --format json
  raytree lessons validate my-course/")]
pub struct Args {
    #[command(subcommand)]
    action: Option<Action>,
    /// A folder of lessons (default: raytree's own, or RAYTREE_LESSONS), or one lesson, by
    /// its folder or its name (`08-pixel-intensity`).
    dir: Option<PathBuf>,
    /// Output: text to read, or JSON for programs.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
}

#[derive(clap::Subcommand, Debug)]
enum Action {
    /// Every exercise of every lesson in DIR can be worked out, and every answer a README
    /// states equals raytree's (exit 1 naming each disagreement).
    #[command(after_help = "Examples:
  raytree lessons validate lessons
  raytree lessons validate my-course/03-shading")]
    Validate {
        /// A lesson folder, or a folder of lessons.
        dir: PathBuf,
    },
    /// Writes raytree's built-in lessons to DIR (new or empty), to read or to change.
    #[command(after_help = "Examples:
  raytree lessons export my-course
  raytree --lessons my-course explore 08-pixel-intensity")]
    Export {
        /// The folder to write them to.
        dir: PathBuf,
    },
}

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    match a.action {
        Some(Action::Validate { dir }) => return run_validate(&lesson_dir(&dir)?),
        Some(Action::Export { dir }) => {
            crate::lessons::builtin::export(&dir)?;
            super::output::println(&format!("wrote the lessons to {}", dir.display()))?;
            return Ok(ExitCode::SUCCESS);
        }
        None => {}
    }
    let root = match a.dir {
        Some(dir) => lesson_dir(&dir)?,
        None => lessons_root()?,
    };
    let lessons = load_all(&root)?;
    let progress = Progress::load();
    match a.format {
        Format::Json => {
            let list: Vec<_> = lessons
                .iter()
                .map(|(dir, l)| match l {
                    Ok(l) => lesson_json(l, &progress),
                    Err(e) => json!({ "dir": dir.display().to_string(), "error": e }),
                })
                .collect();
            let doc = json!({
                "root": root.display().to_string(),
                "lessons": list,
            });
            super::output::print_json(doc)?;
        }
        Format::Text => {
            for (dir, lesson) in &lessons {
                match lesson {
                    Ok(l) => print_lesson(l, &progress)?,
                    Err(e) => super::output::println(&format!(
                        "{}  (does not load: {e})\n",
                        dir.display()
                    ))?,
                }
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}

/// A lesson folder, and its lesson or why it does not load.
type Loaded = (PathBuf, Result<Lesson, String>);

/// Every lesson folder under `root` in name order, loaded or with why it does not load.
fn load_all(root: &Path) -> Result<Vec<Loaded>, Failure> {
    if crate::lessons::is_lesson_folder(root) {
        return Ok(vec![(
            root.to_path_buf(),
            Lesson::load(root).map_err(String::from),
        )]);
    }
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(root)
        .map_err(|e| Failure(format!("{}: cannot list lessons: {e}", root.display())))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| crate::lessons::is_lesson_folder(p))
        .collect();
    if dirs.is_empty() {
        return Err(Failure(format!(
            "{}: no lessons (folders with an exercises.yaml)",
            root.display()
        )));
    }
    dirs.sort();
    Ok(dirs
        .into_iter()
        .map(|d| {
            let l = Lesson::load(&d).map_err(String::from);
            (d, l)
        })
        .collect())
}

fn print_lesson(lesson: &Lesson, progress: &Progress) -> Result<(), Failure> {
    let solved = progress.solved(lesson);
    let done = lesson
        .exercises
        .iter()
        .filter(|e| solved.contains(&e.id))
        .count();
    super::output::println(&format!(
        "{}  {}  ({done}/{} done)",
        lesson.dir.display(),
        lesson.title,
        lesson.exercises.len()
    ))?;
    super::output::println(&format!("    {}", lesson.summary.trim()))?;
    let mut notes = vec![];
    if let Some(v) = &lesson.variant {
        notes.push(format!("homework of {} (lesson {})", v.student, v.lesson));
    }
    if !lesson.vary.is_empty() {
        notes.push(format!(
            "varies per student: {}",
            lesson.vary.keys().cloned().collect::<Vec<_>>().join(", ")
        ));
    }
    if lesson.solutions == Solutions::Hidden {
        notes.push("solutions hidden".into());
    }
    if !notes.is_empty() {
        super::output::println(&format!("    ({})", notes.join("; ")))?;
    }
    for ex in &lesson.exercises {
        let q = ex.question.split_whitespace().collect::<Vec<_>>().join(" ");
        let mark = if solved.contains(&ex.id) { "✓" } else { "-" };
        super::output::println(&format!("    {mark} {:<24} {}", ex.id, q))?;
    }
    super::output::println("")?;
    Ok(())
}

fn lesson_json(lesson: &Lesson, progress: &Progress) -> serde_json::Value {
    let solved = progress.solved(lesson);
    let exercises: Vec<_> = lesson
        .exercises
        .iter()
        .map(|ex| {
            json!({
                "id": ex.id,
                "question": ex.question.split_whitespace().collect::<Vec<_>>().join(" "),
                "ask": ex.ask,
                "solved": solved.contains(&ex.id),
            })
        })
        .collect();
    let mut doc = json!({
        "id": lesson.id,
        "dir": lesson.dir.display().to_string(),
        "title": lesson.title,
        "summary": lesson.summary.trim(),
        "solutions": lesson.solutions,
        "vary": lesson.vary.keys().collect::<Vec<_>>(),
        "solved": exercises.iter().filter(|e| e["solved"] == true).count(),
        "total": exercises.len(),
        "exercises": exercises,
    });
    if let Some(v) = &lesson.variant {
        doc["variant"] = json!(v);
    }
    doc
}

fn run_validate(dir: &Path) -> Result<ExitCode, Failure> {
    let v = validate(dir)?;
    for p in &v.problems {
        super::output::println(&format!("✗ {p}"))?;
    }
    let checked = format!(
        "{} exercise{}, {} README answer{} compared",
        v.exercises,
        plural(v.exercises),
        v.answers,
        plural(v.answers)
    );
    if v.problems.is_empty() {
        super::output::println(&format!(
            "ok: {} lesson{}, {checked}; every exercise computable, every answer equal to raytree's",
            v.lessons,
            plural(v.lessons)
        ))?;
        return Ok(ExitCode::SUCCESS);
    }
    let mut found = vec![];
    if v.unreadable > 0 {
        found.push(format!(
            "{} lesson{} could not be read",
            v.unreadable,
            plural(v.unreadable)
        ));
    }
    if v.disagreements() > 0 {
        found.push(format!(
            "{} disagreement{}",
            v.disagreements(),
            plural(v.disagreements())
        ));
    }
    super::output::println(&format!(
        "{}; {} lesson{} checked: {checked}",
        found.join(", "),
        v.lessons,
        plural(v.lessons)
    ))?;
    Ok(ExitCode::from(1))
}

fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}
