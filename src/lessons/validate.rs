//! A teacher's check of a folder of lessons: every lesson loads, every exercise can be worked
//! out, and every answer its README states (`**Answer (ID):** value`) is the one raytree
//! computes. A homework folder states no answers, so only the first two are asked of it.

use std::path::Path;

use super::check::{check, work};
use super::error::LessonError;
use super::exercise::Lesson;

/// What a validation found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Validation {
    /// Lessons that loaded and were checked.
    pub lessons: usize,
    /// Exercises of those lessons; each is worked out, one that cannot be is a problem.
    pub exercises: usize,
    /// README answers compared.
    pub answers: usize,
    /// Lesson folders whose files could not be read (each is one of the problems).
    pub unreadable: usize,
    /// One line per problem: a lesson that could not be read, naming its file, or a
    /// disagreement, naming the lesson and the exercise.
    pub problems: Vec<String>,
}

impl Validation {
    /// The problems found in the lessons that were read: exercises that cannot be worked out
    /// and README answers that are missing or differ from raytree's.
    pub fn disagreements(&self) -> usize {
        self.problems.len() - self.unreadable
    }
}

/// Validates a lesson folder, or every lesson folder in a folder.
pub fn validate(dir: &Path) -> Result<Validation, LessonError> {
    let lessons: Vec<Result<Lesson, String>> = if crate::lessons::is_lesson_folder(dir) {
        vec![Lesson::load(dir).map_err(String::from)]
    } else {
        let found = all_lessons_or_errors(dir)?;
        if found.is_empty() {
            return Err(LessonError::NoLessons(dir.to_path_buf()));
        }
        found
    };
    let mut v = Validation::default();
    for lesson in lessons {
        match lesson {
            Ok(l) => validate_lesson(&l, &mut v),
            Err(e) => {
                v.unreadable += 1;
                v.problems.push(e);
            }
        }
    }
    Ok(v)
}

/// A folder meant as a lesson whose exercises file is named `.yml`: not read, but not passed
/// over in silence either.
fn misnamed(dir: &Path) -> bool {
    !crate::lessons::is_lesson_folder(dir) && dir.join("exercises.yml").is_file()
}

/// Every lesson folder of `root`, each loaded or with the reason it does not load.
fn all_lessons_or_errors(root: &Path) -> Result<Vec<Result<Lesson, String>>, LessonError> {
    // Unlike `all_lessons`, which stops at the first lesson that does not load, a validation
    // reports them all.
    let mut dirs: Vec<_> = std::fs::read_dir(root)
        .map_err(|e| LessonError::io(root, "list lessons", e))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| crate::lessons::is_lesson_folder(p) || misnamed(p))
        .collect();
    dirs.sort();
    Ok(dirs
        .iter()
        .map(|d| match misnamed(d) {
            true => Err(format!(
                "{}: exercises.yml: a lesson's exercises are read from exercises.yaml (rename it)",
                d.display()
            )),
            false => Lesson::load(d).map_err(String::from),
        })
        .collect())
}

fn validate_lesson(l: &Lesson, v: &mut Validation) {
    v.lessons += 1;
    let name = l.dir.display();
    let stated = l.stated_answer_lines();
    let readme = l.dir.join("README.md");
    let readme = readme.display();
    let homework = l.variant.is_some();
    if !homework {
        match l.check_variations() {
            Ok(variations) => {
                v.problems.extend(
                    variations
                        .unloadable
                        .into_iter()
                        .map(|p| format!("{name}: {p}")),
                );
                // A value that loads may still leave an exercise without an answer (its ray
                // now misses the ball): that student's row could not be graded.
                for (value, variant) in &variations.loading {
                    let failed: Vec<(&str, String)> = variant
                        .exercises
                        .iter()
                        .filter_map(|ex| {
                            work(variant, ex)
                                .err()
                                .map(|e| (ex.id.as_str(), e.to_string()))
                        })
                        .collect();
                    let Some((first, why)) = failed.first() else {
                        continue;
                    };
                    let others: Vec<&str> = failed[1..].iter().map(|(id, _)| *id).collect();
                    let also = match others.is_empty() {
                        true => String::new(),
                        false => format!(" (and {})", others.join(", ")),
                    };
                    let why = why
                        .strip_prefix(&format!("exercise `{first}`: "))
                        .unwrap_or(why);
                    v.problems.push(format!(
                        "{name}: with {value}, exercise `{first}`{also} cannot be worked out: {why}"
                    ));
                }
            }
            Err(e) => v.problems.push(format!("{name}: {e}")),
        }
    }
    for ex in &l.exercises {
        v.exercises += 1;
        if let Err(e) = work(l, ex) {
            v.problems
                .push(format!("{name}/{}: cannot be worked out: {e}", ex.id));
            continue;
        }
        if homework {
            continue;
        }
        let lines: Vec<_> = stated.iter().filter(|(_, id, _)| *id == ex.id).collect();
        if lines.is_empty() {
            v.problems.push(format!(
                "{name}/{}: the README states no answer (a line **Answer ({}):** value)",
                ex.id, ex.id
            ));
            continue;
        }
        // Every line that states the answer: a second one that says otherwise is as wrong as
        // a first.
        for (line, _, value) in lines {
            v.answers += 1;
            match check(l, ex, value) {
                Ok(verdict) if verdict.correct => {}
                Ok(verdict) => v.problems.push(format!(
                    "{readme}:{line}: exercise `{}`: the README says {value}, raytree computes {} (tolerance {})",
                    ex.id,
                    verdict.expected.show(),
                    verdict.tolerance.describe()
                )),
                Err(e) => v.problems.push(format!(
                    "{readme}:{line}: exercise `{}`: the README's answer `{value}` does not read: {e}",
                    ex.id
                )),
            }
        }
    }
    for (line, id, _) in &stated {
        if l.exercise(id).is_err() {
            v.problems.push(format!(
                "{readme}:{line}: the README states an answer for `{id}`, which is not an exercise"
            ));
        }
    }
}
