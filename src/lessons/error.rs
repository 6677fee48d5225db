//! Why lessons cannot be found or written out.

use std::path::PathBuf;

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
    /// A lesson's scene files cannot be read as its variations need them.
    #[error("{0}")]
    Scenes(String),
    /// The platform gives no cache folder to write the built-in lessons to.
    #[error("no cache folder to write the built-in lessons to: set RAYTREE_LESSONS, or run `raytree lessons export DIR`")]
    NoCacheDir,
    /// An export would overwrite a folder that already has files in it.
    #[error("{}: the folder is not empty; export the lessons to a new or empty folder", .0.display())]
    NotEmpty(PathBuf),
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
