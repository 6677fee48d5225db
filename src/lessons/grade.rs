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
    /// The answer as written, without its quotes.
    pub answer: String,
}

/// A row not graded, and why.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Problem {
    /// The row's line in the file (1 is the first).
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

/// The rows of an answers file, and the lines that are not rows. A row is one line of three
/// fields, `student,exercise,answer`; an answer with commas is quoted (`"0.6, -0.8, 0"`). A
/// first line that names the three columns (`student,exercise,answer`, or in another order)
/// is a header, and the rows follow its order. A line with fewer or more fields, or with a
/// quote left open, is a problem: guessing what it meant could grade an answer the student did
/// not give. So is a quoted field that a later line closes (a cell with a line break): its
/// lines are one record, set aside whole.
pub fn read_answers(text: &str) -> (Vec<Row>, Vec<Problem>) {
    let mut rows = Vec::new();
    let mut problems = Vec::new();
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut first = true;
    // Where each of student, exercise and answer stands in a row: as a header line puts
    // them, else in that order.
    let mut order = [0, 1, 2];
    // How many fields a row has: three, or as many as a header names.
    let mut width = 3;
    // Line by line, so that a quote left open costs its own row and not every row after it.
    let lines: Vec<&str> = text.lines().collect();
    let mut k = 0;
    while k < lines.len() {
        let line = k as u64 + 1;
        let raw = lines[k];
        k += 1;
        let mut fields = match split_row(raw) {
            Ok(fields) => fields,
            Err(message) => {
                // A cell with a line break in it (CSV lets a quoted field run over lines): the
                // whole record is set aside, not read as rows of its own from the break on.
                match spans_lines(&lines[k - 1..]) {
                    Some(more) => {
                        let last = line + more as u64;
                        problems.push(Problem {
                            line,
                            message: format!(
                                "a quoted field runs on to line {last} (a line break in a \
                                 cell): answers hold none, so lines {line}–{last} are not graded"
                            ),
                        });
                        k += more;
                    }
                    None => problems.push(Problem { line, message }),
                }
                first = false;
                continue;
            }
        };
        // Spreadsheets write empty rows as `,,`.
        if fields.iter().all(|f| f.is_empty()) {
            continue;
        }
        if std::mem::replace(&mut first, false) {
            // A sheet saved for a decimal comma separates its fields with semicolons: every
            // row would be read wrong.
            if fields[0].contains(';') {
                problems.push(Problem {
                    line,
                    message: "the fields are separated by semicolons (a spreadsheet's CSV for \
                              decimal commas): save the sheet as comma-separated CSV, with \
                              decimal points; no row is graded"
                        .into(),
                });
                return (Vec::new(), problems);
            }
            if let Some(columns) = header(&fields) {
                (order, width) = columns;
                continue;
            }
        }
        // Spreadsheets pad rows with empty cells to the sheet's width (`s1,dir,0.5,,`).
        while fields.len() > width && fields.last().is_some_and(String::is_empty) {
            fields.pop();
        }
        let fits = fields.len() <= width && order.iter().all(|&i| i < fields.len());
        let in_order = match fits {
            true => Ok(order.map(|i| std::mem::take(&mut fields[i]))),
            false => Err(fields),
        };
        match in_order {
            Ok([student, exercise, answer]) if !student.is_empty() && !exercise.is_empty() => rows
                .push(Row {
                    line,
                    student: super::exercise::student_id(&student),
                    exercise,
                    answer,
                }),
            Ok(_) => problems.push(Problem {
                line,
                message: "the student or the exercise is empty".into(),
            }),
            Err(fields) => problems.push(Problem {
                line,
                message: format!(
                    "{} field{}, expected {width}: student,exercise,answer{}",
                    fields.len(),
                    if fields.len() == 1 { "" } else { "s" },
                    if fields.len() > width {
                        " (quote an answer with commas: \"0.6, -0.8, 0\")"
                    } else {
                        ""
                    }
                ),
            }),
        }
    }
    (rows, problems)
}

/// How many lines after the first of `lines` a record runs on for, when the first line leaves
/// a quote open that a later line closes (the quotes in them together are even in number) and
/// the lines joined read as a record: a quoted field with line breaks in it. None when no line
/// closes the quote so: then the quote is a mistake of the first line alone.
fn spans_lines(lines: &[&str]) -> Option<usize> {
    let quotes = |l: &str| l.matches('"').count();
    let mut open = quotes(lines[0]) % 2 == 1;
    for more in 1..lines.len() {
        open ^= quotes(lines[more]) % 2 == 1;
        if !open {
            return split_row(&lines[..=more].join("\n")).ok().map(|_| more);
        }
    }
    None
}

/// Where student, exercise and answer stand, if the row is a header: those three names, in
/// any order and any case, among other columns or none (a sheet may keep notes beside them);
/// and how many columns it names (empty ones past the last named are the sheet's padding).
fn header(fields: &[String]) -> Option<([usize; 3], usize)> {
    let at = |name: &str| fields.iter().position(|f| f.eq_ignore_ascii_case(name));
    let columns = [at("student")?, at("exercise")?, at("answer")?];
    let named = fields
        .iter()
        .rposition(|f| !f.is_empty())
        .map_or(0, |i| i + 1);
    Some((columns, named))
}

/// The fields of one line of CSV, each trimmed: separated by commas; a field in double quotes
/// may hold commas, and `""` in it stands for one quote.
fn split_row(line: &str) -> Result<Vec<String>, String> {
    let mut fields = Vec::new();
    let mut rest = line;
    loop {
        let field = rest.trim_start();
        let Some(quoted) = field.strip_prefix('"') else {
            match field.split_once(',') {
                Some((value, next)) => {
                    fields.push(value.trim().to_string());
                    rest = next;
                    continue;
                }
                None => {
                    fields.push(field.trim().to_string());
                    return Ok(fields);
                }
            }
        };
        let column = line[..line.len() - field.len()].chars().count() + 1;
        let mut value = String::new();
        let mut chars = quoted.char_indices().peekable();
        let after = loop {
            match chars.next() {
                Some((_, '"')) if chars.peek().is_some_and(|&(_, c)| c == '"') => {
                    chars.next();
                    value.push('"');
                }
                Some((i, '"')) => break quoted[i + 1..].trim_start(),
                Some((_, c)) => value.push(c),
                None => return Err(format!("the quote at column {column} is never closed")),
            }
        };
        fields.push(value.trim().to_string());
        match after.strip_prefix(',') {
            Some(next) => rest = next,
            None if after.is_empty() => return Ok(fields),
            None => {
                return Err(format!(
                    "text after the quoted field at column {column}: a comma should follow its closing quote"
                ))
            }
        }
    }
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
        let own = match lesson.variant(&student) {
            Ok(own) => own,
            // The lesson's fault, not the student's: their rows are set aside, not marked wrong.
            Err(e @ LessonError::VariantDoesNotLoad { .. }) => {
                let rows = answers.values().filter(|r| r.student == student);
                problems.extend(rows.map(|r| Problem {
                    line: r.line,
                    message: format!("{}, {}: not graded: {e}", r.student, r.exercise),
                }));
                continue;
            }
            Err(e) => return Err(e),
        };
        // Each exercise worked out once for this student: its answer, or why it cannot be.
        let worked: Vec<_> = own
            .exercises
            .iter()
            .map(|ex| super::check::work(&own, ex).map(|w| w.expected))
            .collect();
        expected_of.push(worked.iter().map(|w| w.as_ref().ok().cloned()).collect());
        let mut exercises = Vec::new();
        for (ex, worked) in own.exercises.iter().zip(&worked) {
            let row = answers.get(&(student.clone(), ex.id.clone()));
            // An exercise this student's values make impossible (the varied scene's ray
            // hits nothing) is the lesson's fault: set aside, not counted against them.
            if let Err(e) = worked {
                problems.extend(row.map(|r| Problem {
                    line: r.line,
                    message: format!(
                        "{}, {}: not graded: with this student's values the exercise cannot be worked out: {e}",
                        r.student, r.exercise
                    ),
                }));
                continue;
            }
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
    /// Per exercise: how many students answered it right, of how many were graded on it (an
    /// exercise a student's values make impossible is set aside for that student).
    pub fn per_exercise(&self) -> Vec<(String, usize, usize)> {
        let mut ids: Vec<&str> = Vec::new();
        for g in self.students.iter().flat_map(|s| &s.exercises) {
            if !ids.contains(&g.exercise.as_str()) {
                ids.push(&g.exercise);
            }
        }
        ids.into_iter()
            .map(|id| {
                let graded = self
                    .students
                    .iter()
                    .filter_map(|s| s.exercises.iter().find(|g| g.exercise == id));
                let (right, of) = graded.fold((0, 0), |(r, n), g| (r + g.correct as usize, n + 1));
                (id.to_string(), right, of)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(problems: &[Problem]) -> Vec<u64> {
        problems.iter().map(|p| p.line).collect()
    }

    #[test]
    fn a_row_of_three_fields_is_read_and_a_quoted_answer_keeps_its_commas() {
        let (rows, problems) = read_answers(
            "student,exercise,answer\ns1,pixel-p, 0.87\n\ns2,dir,\" 0.6, -0.8, 0 \"\n",
        );
        assert_eq!(problems, vec![]);
        let read: Vec<_> = rows
            .iter()
            .map(|r| {
                (
                    r.line,
                    r.student.as_str(),
                    r.exercise.as_str(),
                    r.answer.as_str(),
                )
            })
            .collect();
        assert_eq!(
            read,
            vec![
                (2, "s1", "pixel-p", "0.87"),
                (4, "s2", "dir", "0.6, -0.8, 0")
            ]
        );
    }

    #[test]
    fn a_row_missing_a_field_is_reported_not_graded_as_unanswered() {
        let (rows, problems) = read_answers("s1,pixel-p\ns2,pixel-p,0.87\n");
        assert_eq!(rows.len(), 1);
        assert_eq!(lines(&problems), vec![1]);
        assert!(problems[0].message.contains("2 fields"), "{problems:?}");
    }

    #[test]
    fn a_row_with_too_many_fields_is_reported() {
        let (rows, problems) = read_answers("s1,dir,0.6,-0.8,0\n");
        assert_eq!(rows, vec![]);
        assert_eq!(lines(&problems), vec![1]);
        assert!(problems[0].message.contains("5 fields"), "{problems:?}");
        assert!(problems[0].message.contains("quote"), "{problems:?}");
    }

    #[test]
    fn a_quote_left_open_is_reported_and_the_next_rows_are_read() {
        let (rows, problems) = read_answers("s5,pixel-p,\"0.87\ns6,pixel-p,0.87\n");
        assert_eq!(lines(&problems), vec![1]);
        assert!(problems[0].message.contains("never closed"), "{problems:?}");
        assert_eq!(rows.len(), 1);
        assert_eq!((rows[0].line, rows[0].student.as_str()), (2, "s6"));
    }

    /// A cell with a line break (RFC 4180 lets a quoted field hold one) is one record over
    /// several lines: it is set aside whole, and its second line is no row of a student "x\"".
    #[test]
    fn a_quoted_field_over_two_lines_is_one_record_set_aside() {
        let (rows, problems) = read_answers("\"s1\nx\",diffuse,0.5\ns2,diffuse,0.5\n");
        assert_eq!(lines(&problems), vec![1]);
        assert!(
            problems[0].message.contains("lines 1–2 are not graded"),
            "{problems:?}"
        );
        assert_eq!(rows.len(), 1, "{rows:?}");
        assert_eq!((rows[0].line, rows[0].student.as_str()), (3, "s2"));
    }

    /// Spreadsheets pad rows with empty cells (`s1,dir,0.5,`), and a sheet may keep a notes
    /// column beside the three a header names: both are read. A cell filled past the sheet's
    /// columns is still a problem.
    #[test]
    fn padded_rows_and_a_notes_column_are_read() {
        let (rows, problems) = read_answers(
            "student,exercise,answer,\r\ns1,diffuse,0.185764,\r\ns2,diffuse,0.2,,\r\n",
        );
        assert_eq!(problems, vec![]);
        assert_eq!(rows.len(), 2, "{rows:?}");
        assert_eq!(rows[0].answer, "0.185764");
        let (rows, problems) =
            read_answers("answer,student,notes,exercise\n0.5,s1,late,diffuse\n0.4,s2,,diffuse\n0.3,s3,x,diffuse,9\n");
        assert_eq!(
            rows.iter()
                .map(|r| (r.student.as_str(), r.answer.as_str()))
                .collect::<Vec<_>>(),
            [("s1", "0.5"), ("s2", "0.4")]
        );
        assert_eq!(lines(&problems), vec![4]);
        assert!(
            problems[0].message.contains("5 fields, expected 4"),
            "{problems:?}"
        );
    }

    /// A sheet saved for decimal commas separates its fields with semicolons: it is refused
    /// whole, saying so, rather than read with its answers in the wrong columns.
    #[test]
    fn a_sheet_separated_by_semicolons_is_refused_whole() {
        let (rows, problems) =
            read_answers("alice;local-color;\"0.436303, 0.270201, 0.187149\"\nbob;diffuse;0,5\n");
        assert_eq!(rows, vec![]);
        assert_eq!(lines(&problems), vec![1]);
        assert!(
            problems[0].message.contains("separated by semicolons"),
            "{problems:?}"
        );
    }

    #[test]
    fn text_after_a_closing_quote_is_reported() {
        let (rows, problems) = read_answers("s1,dir,\"0.6, -0.8\", 0\"\n");
        assert_eq!(rows, vec![]);
        assert_eq!(lines(&problems), vec![1]);
    }

    #[test]
    fn a_doubled_quote_is_one_quote_and_only_the_first_line_is_a_header() {
        let (rows, problems) =
            read_answers("\u{feff}s1,\"a\"\"b\",1\r\nstudent,exercise,answer\r\n");
        assert_eq!(problems, vec![]);
        assert_eq!(rows.len(), 2);
        assert_eq!(rows[0].exercise, "a\"b");
        assert_eq!(rows[1].student, "student");
    }

    /// A header that names the columns in another order (any case) sets the order of the
    /// rows after it.
    #[test]
    fn a_header_in_another_order_is_followed() {
        let (rows, problems) = read_answers("Exercise,STUDENT,answer\ndiffuse,s1,0.16846\n");
        assert_eq!(problems, vec![]);
        assert_eq!(rows.len(), 1);
        let r = &rows[0];
        let got = (r.student.as_str(), r.exercise.as_str(), r.answer.as_str());
        assert_eq!(got, ("s1", "diffuse", "0.16846"));
        assert_eq!(r.line, 2);
        // Two names and a third word is no header: it is a row.
        let (rows, _) = read_answers("exercise,student,mark\n");
        assert_eq!(rows.len(), 1);
    }
}
