//! `raytree grade LESSON --answers FILE.csv`: a class's answers graded, each student against
//! their own variant of the lesson; a report per student and per exercise.

use std::fmt::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use serde_json::json;

use super::Failure;
use crate::files::ReadError;
use crate::lessons::grade::{grade, read_answers, Report};
use crate::lessons::Lesson;

#[derive(clap::ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum GradeFormat {
    /// A report to read.
    #[default]
    Text,
    /// One row per student and exercise.
    Csv,
    /// One JSON document (with "raytree_version").
    Json,
}

#[derive(clap::Args, Debug)]
#[command(after_help = "Examples:
  raytree grade lessons/03-local-illumination --answers class.csv
  raytree grade lessons/03-local-illumination --answers class.csv --format json

Exit status: 0 when the answers were graded, 1 when no row of the file could be, 2 for a
usage error or a file that cannot be read.")]
pub struct Args {
    /// The lesson the homework was made from: its folder, or its name (`03-local-illumination`).
    lesson: PathBuf,
    /// The answers: CSV with the columns student,exercise,answer (a header line is optional;
    /// quote an answer with commas, "0.6, -0.8, 0").
    #[arg(long)]
    answers: PathBuf,
    /// Output: a report to read, CSV, or JSON.
    #[arg(long, value_enum, default_value_t = GradeFormat::Text)]
    format: GradeFormat,
}

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    let lesson = Lesson::named(&a.lesson)?;
    // A homework folder changed after it was written would grade the student's own edits.
    let edited = lesson.edited_scenes();
    if !edited.is_empty() {
        let lesson_id = lesson.variant.as_ref().map_or("", |v| v.lesson.as_str());
        return Err(Failure(format!(
            "{}: {} changed since `raytree homework` wrote it: grade against the lesson itself (raytree grade {lesson_id} --answers …), which works out each student's own variant",
            a.lesson.display(),
            edited.join(", ")
        )));
    }
    let shown = a.answers.display();
    let text = crate::files::read_text(&a.answers, crate::files::TEXT_BUDGET).map_err(|e| {
        Failure(match e {
            ReadError::NotUtf8 { line, column } => format!(
                "{shown}:{line}:{column}: not UTF-8 text: save the answers as UTF-8 \
                 (a spreadsheet's \"CSV UTF-8\")"
            ),
            e => format!("{shown}: {e}"),
        })
    })?;
    let (rows, problems) = read_answers(&text);
    let report = grade(&lesson, &rows, problems)?;
    let file = a.answers.display().to_string();
    match a.format {
        GradeFormat::Json => super::output::print_json(json_report(&report))?,
        GradeFormat::Csv => write_csv(&report)?,
        GradeFormat::Text => print_text(&report, &file)?,
    }
    // Whatever the format, the rows not graded are said on stderr too.
    if a.format != GradeFormat::Text {
        for p in &report.problems {
            super::output::eprintln(&format!("{file}:{}: {}", p.line, p.message));
        }
    }
    // A sheet where no row could be graded is a mistake a script must see (a wrong file,
    // another lesson's answers), not a class with no students.
    if report.students.is_empty() {
        let why = match report.problems.is_empty() {
            true => format!(
                "no row names a student and an exercise of lesson {}",
                report.lesson
            ),
            false => "every row was set aside (the rows not graded say why)".to_string(),
        };
        super::output::eprintln(&format!("{file}: no answer graded: {why}"));
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}

fn json_report(r: &Report) -> serde_json::Value {
    json!({
        "lesson": r.lesson,
        "students": r.students,
        "exercises": r.per_exercise().iter().map(|(id, right, of)| json!({ "exercise": id, "right": right, "students": of })).collect::<Vec<_>>(),
        "problems": r.problems,
    })
}

fn write_csv(r: &Report) -> Result<(), Failure> {
    let stdout = std::io::stdout();
    let mut w = csv::Writer::from_writer(stdout.lock());
    w.write_record([
        "student", "exercise", "answer", "correct", "expected", "hint",
    ])?;
    // Names and answers come from the class's file: their control characters are written
    // escaped, as in the other formats, so that the CSV shown on a terminal cannot drive it.
    let safe = |text: &str| super::output::escape(text, "");
    for s in &r.students {
        for g in &s.exercises {
            w.write_record([
                safe(&s.student),
                safe(&g.exercise),
                safe(g.answer.as_deref().unwrap_or("")),
                (if g.correct { "true" } else { "false" }).to_string(),
                safe(g.expected.as_deref().unwrap_or("")),
                safe(g.hint.as_deref().unwrap_or("")),
            ])?;
        }
    }
    w.flush()?;
    Ok(())
}

/// The report for a teacher to read. Names and answers come from the class's file: `print`
/// shows their control characters escaped.
fn print_text(r: &Report, file: &str) -> Result<(), Failure> {
    let mut out = String::new();
    let width = r
        .students
        .iter()
        .map(|s| s.student.chars().count())
        .max()
        .unwrap_or(7)
        .max(7);
    let _ = writeln!(
        out,
        "lesson {}: {} student{}",
        r.lesson,
        r.students.len(),
        if r.students.len() == 1 { "" } else { "s" }
    );
    let _ = writeln!(out);
    for s in &r.students {
        let _ = writeln!(out, "{:<width$}  {}/{}", s.student, s.score, s.total);
        for g in s.exercises.iter().filter(|g| !g.correct) {
            let expected = g.expected.as_deref().unwrap_or("?");
            let line = match &g.answer {
                None => format!("{}: not answered (expected {expected})", g.exercise),
                Some(a) => format!(
                    "{} = {a} (expected {expected}){}",
                    g.exercise,
                    g.hint
                        .as_deref()
                        .map_or(String::new(), |h| format!(": {h}"))
                ),
            };
            let _ = writeln!(out, "{:<width$}    ✗ {line}", "");
        }
    }
    let _ = writeln!(out);
    let _ = writeln!(out, "per exercise:");
    for (id, right, of) in r.per_exercise() {
        let _ = writeln!(out, "  {id:<24} {right}/{of} right");
    }
    if !r.problems.is_empty() {
        let _ = writeln!(out);
        let _ = writeln!(out, "rows not graded:");
        for p in &r.problems {
            let _ = writeln!(out, "  {file}:{}: {}", p.line, p.message);
        }
    }
    super::output::print(&out)
}
