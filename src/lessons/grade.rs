//! Grading a class: a CSV file of answers (`student,exercise,answer`) checked exercise by
//! exercise, each student against their own variant of the lesson (the values `raytree
//! homework` drew for their ID). A row that cannot be read is reported with its line number and
//! the others are graded all the same.

use std::collections::BTreeMap;

use serde::Serialize;

use super::answer::{parse_answer, Answer};
use super::check::check;
use super::error::LessonError;
use super::exercise::Lesson;

/// One row of the answers file.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The row's line in the file (1 is the first).
    pub line: u64,
    /// The student's ID, as given to `raytree homework --student` (their variant is drawn
    /// from it).
    pub student: String,
    /// The exercise's id.
    pub exercise: String,
    /// The answer as written; the fields after the third are joined back with ", ".
    pub answer: String,
}

/// A row not graded, and why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Problem {
    /// The row's line in the file (1 is the first; 0 when a row that does not read has no
    /// known line).
    pub line: u64,
    /// What is wrong with the row, in words.
    pub message: String,
}

/// One exercise of one student.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Graded {
    /// The exercise's id.
    pub exercise: String,
    /// As written; None when the student gave no answer.
    pub answer: Option<String>,
    /// Within the exercise's tolerance of this student's expected answer; false when not
    /// answered.
    pub correct: bool,
    /// Why the answer is wrong: a common mistake, "not answered", an answer that does not
    /// read, or another student's expected answer.
    pub hint: Option<String>,
    /// This student's expected answer.
    pub expected: Option<String>,
}

/// One student's grades.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StudentReport {
    /// The student's ID.
    pub student: String,
    /// The exercises answered right.
    pub score: usize,
    /// The exercises of the lesson, answered or not.
    pub total: usize,
    /// Every exercise of the lesson, in the lesson's order.
    pub exercises: Vec<Graded>,
}

/// A class graded on one lesson (`raytree grade`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Report {
    /// The lesson's id (its folder name).
    pub lesson: String,
    /// One report per student, in the order they first appear in the answers file.
    pub students: Vec<StudentReport>,
    /// The rows not graded, and duplicate answers, by line.
    pub problems: Vec<Problem>,
}

/// The rows of an answers file, and the lines that are not rows. A first line
/// `student,exercise,answer` is a header; an answer with commas (a vector written without
/// quotes) keeps its parts.
pub fn read_answers(text: &str) -> (Vec<Row>, Vec<Problem>) {
    let mut rows = Vec::new();
    let mut problems = Vec::new();
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    for (k, record) in reader.records().enumerate() {
        let record = match record {
            Ok(r) => r,
            Err(e) => {
                let line = e.position().map_or(0, |p| p.line());
                problems.push(Problem {
                    line,
                    message: format!("not a CSV row: {e}"),
                });
                continue;
            }
        };
        let line = record.position().map_or(k as u64 + 1, |p| p.line());
        let fields: Vec<&str> = record.iter().collect();
        if fields.iter().all(|f| f.is_empty()) {
            continue;
        }
        let header = fields.len() == 3
            && fields[0].eq_ignore_ascii_case("student")
            && fields[1].eq_ignore_ascii_case("exercise")
            && fields[2].eq_ignore_ascii_case("answer");
        if header {
            continue;
        }
        match fields.as_slice() {
            [student, exercise, answer @ ..] if !student.is_empty() && !exercise.is_empty() => rows
                .push(Row {
                    line,
                    student: student.to_string(),
                    exercise: exercise.to_string(),
                    answer: answer.join(", "),
                }),
            [_, _, ..] => problems.push(Problem {
                line,
                message: "the student or the exercise is empty".into(),
            }),
            _ => problems.push(Problem {
                line,
                message: format!(
                    "expected student,exercise,answer; got {} field{}",
                    fields.len(),
                    if fields.len() == 1 { "" } else { "s" }
                ),
            }),
        }
    }
    (rows, problems)
}

/// Grades every student's rows: students in the order they first appear, every exercise of
/// the lesson in the lesson's order (unanswered ones count as wrong). A row for an exercise the
/// lesson does not have is a problem; of two rows for the same exercise, the later counts.
pub fn grade(
    lesson: &Lesson,
    rows: &[Row],
    mut problems: Vec<Problem>,
) -> Result<Report, LessonError> {
    let mut order: Vec<String> = Vec::new();
    let mut answers: BTreeMap<(String, String), &Row> = BTreeMap::new();
    for row in rows {
        if lesson.exercise(&row.exercise).is_err() {
            problems.push(Problem {
                line: row.line,
                message: format!("lesson {} has no exercise `{}`", lesson.id, row.exercise),
            });
            continue;
        }
        if !order.contains(&row.student) {
            order.push(row.student.clone());
        }
        let key = (row.student.clone(), row.exercise.clone());
        if let Some(earlier) = answers.insert(key, row) {
            problems.push(Problem {
                line: earlier.line,
                message: format!(
                    "{} answered {} again on line {}: the later answer counts",
                    row.student, row.exercise, row.line
                ),
            });
        }
    }
    let mut students = Vec::new();
    // Each student's expected answers, to tell a copied answer from a plain mistake.
    let mut expected_of: Vec<Vec<Option<Answer>>> = Vec::new();
    for student in order {
        let own = lesson.variant(&student)?;
        expected_of.push(
            own.exercises
                .iter()
                .map(|ex| super::check::work(&own, ex).ok().map(|w| w.expected))
                .collect(),
        );
        let mut exercises = Vec::new();
        for ex in &own.exercises {
            let row = answers.get(&(student.clone(), ex.id.clone()));
            let graded = match row.map(|r| r.answer.as_str()) {
                None | Some("") => Graded {
                    exercise: ex.id.clone(),
                    answer: None,
                    correct: false,
                    hint: Some("not answered".into()),
                    expected: expected(&own, ex),
                },
                Some(answer) => match check(&own, ex, answer) {
                    Ok(v) => Graded {
                        exercise: ex.id.clone(),
                        answer: Some(answer.to_string()),
                        correct: v.correct,
                        hint: v.hint,
                        expected: Some(v.expected.show()),
                    },
                    Err(e) => Graded {
                        exercise: ex.id.clone(),
                        answer: Some(answer.to_string()),
                        correct: false,
                        hint: Some(format!("the answer does not read: {e}")),
                        expected: expected(&own, ex),
                    },
                },
            };
            exercises.push(graded);
        }
        students.push(StudentReport {
            score: exercises.iter().filter(|g| g.correct).count(),
            total: exercises.len(),
            student,
            exercises,
        });
    }
    if !lesson.vary.is_empty() {
        name_copies(lesson, &mut students, &expected_of);
    }
    problems.sort_by_key(|p| p.line);
    Ok(Report {
        lesson: lesson.id.clone(),
        students,
        problems,
    })
}

/// A wrong answer that is another student's expected answer was worked out with that student's
/// values: the hint says whose.
fn name_copies(
    lesson: &Lesson,
    students: &mut [StudentReport],
    expected_of: &[Vec<Option<Answer>>],
) {
    let names: Vec<String> = students.iter().map(|s| s.student.clone()).collect();
    for (k, s) in students.iter_mut().enumerate() {
        for (j, g) in s.exercises.iter_mut().enumerate() {
            let (Some(answer), false) = (&g.answer, g.correct) else {
                continue;
            };
            let Ok(ex) = lesson.exercise(&g.exercise) else {
                continue;
            };
            let Ok(given) = parse_answer(answer, ex.ask == super::exercise::Ask::Segments) else {
                continue;
            };
            let other = (0..names.len()).find(|&o| {
                o != k
                    && expected_of[o][j]
                        .as_ref()
                        .is_some_and(|e| given.matches(e, &ex.tolerance))
            });
            if let Some(o) = other {
                g.hint = Some(format!(
                    "that is {}'s answer, worked out with {}'s values, not this student's",
                    names[o], names[o]
                ));
            }
        }
    }
}

fn expected(lesson: &Lesson, ex: &super::exercise::Exercise) -> Option<String> {
    super::check::work(lesson, ex)
        .ok()
        .map(|w| w.expected.show())
}

impl Report {
    /// Per exercise: how many students answered it right, of how many.
    pub fn per_exercise(&self) -> Vec<(String, usize, usize)> {
        let Some(first) = self.students.first() else {
            return Vec::new();
        };
        first
            .exercises
            .iter()
            .enumerate()
            .map(|(k, g)| {
                let right = self
                    .students
                    .iter()
                    .filter(|s| s.exercises.get(k).is_some_and(|g| g.correct))
                    .count();
                (g.exercise.clone(), right, self.students.len())
            })
            .collect()
    }
}
