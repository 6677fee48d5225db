//! Why lessons cannot be found or written out, why an answer does not read, and why an
//! exercise cannot be checked.

use std::path::PathBuf;

use crate::scene::SceneError;

/// An error of the lessons' files, naming the path and what was being done to it.
#[derive(Debug, thiserror::Error)]
pub enum LessonError {
    /// Reading or writing a file or folder failed.
    #[error("{}: cannot {action}: {source}", path.display())]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// What was being done, as a verb phrase ("create the folder").
        action: &'static str,
        /// The system's reason.
        source: std::io::Error,
    },
    /// A lesson file that is not valid YAML of its format, at a line and column.
    #[error("{}:{line}:{column}: {message}", file.display())]
    Format {
        /// The file (a lesson's exercises.yaml).
        file: PathBuf,
        /// The line, from 1.
        line: u64,
        /// The column, from 1.
        column: u64,
        /// What is wrong there.
        message: String,
    },
    /// A lesson file that parses but says something impossible (a duplicate exercise id, an
    /// exercise without a pixel or a ray, a variation of a value no scene writes).
    #[error("{}: {message}", file.display())]
    Invalid {
        /// The file (a lesson's exercises.yaml).
        file: PathBuf,
        /// What is wrong in it.
        message: String,
    },
    /// A lesson's scene files cannot be read as its variations need them: a scene that is not
    /// YAML, a varied value that is not a number, a variation no scene writes.
    #[error("{0}")]
    Scenes(String),
    /// The platform gives no cache folder to write the built-in lessons to.
    #[error("no cache folder to write the built-in lessons to: set RAYTREE_LESSONS, or run `raytree lessons export DIR`")]
    NoCacheDir,
    /// An export would overwrite a folder that already has files in it.
    #[error("{}: the folder is not empty; export the lessons to a new or empty folder", .0.display())]
    NotEmpty(PathBuf),
    /// A lesson has no exercise of that id.
    #[error("lesson {lesson} has no exercise `{id}` (exercises: {})", exercises.join(", "))]
    UnknownExercise {
        /// The lesson's id.
        lesson: String,
        /// The id asked for.
        id: String,
        /// The ids the lesson has, in its order.
        exercises: Vec<String>,
    },
    /// A variant asked for a student whose ID is empty (or blank).
    #[error("a student ID must not be empty")]
    EmptyStudent,
    /// A student's variant asked of another student's homework folder, which holds only the
    /// values drawn for its owner.
    #[error(
        "this folder is {owner}'s homework of lesson {lesson}: {student}'s values are drawn from the lesson itself (give `{lesson}` instead of the folder)"
    )]
    OtherStudentsHomework {
        /// The lesson the folder was made from.
        lesson: String,
        /// The student whose homework the folder is.
        owner: String,
        /// The student asked for.
        student: String,
    },
    /// A student's variant whose values make one of the lesson's scenes fail to load: the
    /// lesson's `vary` ranges reach values the scene refuses.
    #[error(
        "student {student}'s variant does not load ({values}): {error}; the lesson's `vary` ranges must keep its scenes loadable (`raytree lessons validate` tries them)"
    )]
    VariantDoesNotLoad {
        /// The student.
        student: String,
        /// The values drawn for them, `path = value` each.
        values: String,
        /// The scene's error, at its line and column (the variant's lines are the lesson's).
        error: String,
    },
    /// A homework folder would be written over a folder that has files in it.
    #[error("{}: already exists (remove it, or choose another folder)", .0.display())]
    Exists(PathBuf),
    /// A lesson's scene reads a file from outside the lesson's folder, which a homework folder
    /// (a copy of the lesson's folder) would not hold.
    #[error(
        "{}: reads {}, outside the lesson's folder: a homework folder holds the lesson's own files only (keep the scene's meshes and images in the lesson's folder)",
        scene.display(),
        input.display()
    )]
    Outside {
        /// The scene file.
        scene: PathBuf,
        /// The file it reads, as the scene names it from its folder.
        input: PathBuf,
    },
    /// A homework folder given as a path that names no folder (`..`, `/`).
    #[error("{}: not a folder name", .0.display())]
    NotAFolderName(PathBuf),
    /// A folder validated holds no lesson, and is not one.
    #[error("{}: no lessons (folders with an exercises.yaml)", .0.display())]
    NoLessons(PathBuf),
    /// A lesson named on the command line that is neither a folder nor a lesson's name.
    #[error("no lesson `{}`: not a folder here and {among} (`raytree lessons` lists them)", name.display())]
    NoLesson {
        /// The name as given.
        name: PathBuf,
        /// Where it was looked for, as a phrase ("not a built-in lesson").
        among: String,
    },
    /// The platform gives no data folder to keep a student's progress in.
    #[error("no data folder (set RAYTREE_DATA)")]
    NoDataDir,
    /// The progress file is there but does not read as progress; it is left as it is.
    #[error("{}: not a progress file ({reason}); left as it is: move it away to start afresh", path.display())]
    ProgressUnreadable {
        /// The file.
        path: PathBuf,
        /// What the JSON reader said.
        reason: String,
    },
}

impl LessonError {
    /// An I/O error on `path` while doing `action`.
    pub fn io(path: impl Into<PathBuf>, action: &'static str, source: std::io::Error) -> Self {
        LessonError::Io {
            path: path.into(),
            action,
            source,
        }
    }
}

/// The error's one-line message, for the callers that report errors as text.
impl From<LessonError> for String {
    fn from(e: LessonError) -> String {
        e.to_string()
    }
}

/// An answer as a student typed it that does not read as one.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum AnswerError {
    /// A part that is not a number (shown cut short when long).
    #[error("`{0}` is not a number")]
    NotANumber(String),
    /// A number too large for a double (`1e999`), which is not read as ∞.
    #[error("`{0}` is too large to be an answer")]
    TooLarge(String),
    /// ∞ where the answer is a finite number (∞ only ends segments).
    #[error("`{0}`: this answer is a finite number (∞ only ends segments)")]
    Infinite(String),
    /// No answer at all (an empty line), and the form an answer takes here.
    #[error("no answer given: give {0}")]
    Empty(&'static str),
    /// An answer without a number in it, where a number or a vector is asked.
    #[error("`{0}` holds no numbers: give a number, or three (x, y, z)")]
    NoNumbers(String),
    /// An answer without a number in it, where a segment list is asked.
    #[error("`{0}` holds no numbers: give pairs t_in, t_out (e.g. `13, 16; 22, 23`), or `none` for an empty list")]
    NoSegments(String),
}

/// An exercise that cannot be checked or worked out.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CheckError {
    /// The student's answer does not read.
    #[error(transparent)]
    Answer(#[from] AnswerError),
    /// The exercise's scene does not load.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The exercise asks what its scene cannot answer: its ray hits nothing, its pixel is
    /// outside the image, its tree has no node it names. The message names the exercise.
    #[error("{0}")]
    Unworkable(String),
    /// The worked solution was asked of a lesson whose solutions are hidden.
    #[error("lesson {lesson}: the worked solutions are hidden (solutions: hidden)")]
    Hidden {
        /// The lesson's id.
        lesson: String,
    },
}

/// A `vary:` range that cannot be drawn from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum RangeError {
    /// Empty, reversed, not finite, or a step ≤ 0.
    #[error("a range is [lo, hi] with lo ≤ hi, [[x, y, z], [x, y, z]], {{ between: [lo, hi], step: s > 0 }} or {{ one_of: [...] }} (not empty)")]
    Shape,
    /// A step finer than the values are written with.
    #[error("the step is finer than the values drawn are written with (six decimals, seven significant digits from 10¹⁵ on): students would get values off its grid, or all the same one")]
    StepTooFine,
}
