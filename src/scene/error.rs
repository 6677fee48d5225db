//! Scene errors: one line naming the file, line and column, as compilers do.

use std::fmt;

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneError {
    pub file: String,
    pub line: u64,
    pub column: u64,
    pub message: String,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}:{}:{}: {}",
            self.file, self.line, self.column, self.message
        )
    }
}

impl std::error::Error for SceneError {}

/// A position in the scene file, for errors found after parsing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Pos {
    pub line: u64,
    pub column: u64,
}

impl Pos {
    pub fn of(loc: &serde_saphyr::Location) -> Pos {
        Pos {
            line: loc.line().max(1),
            column: loc.column().max(1),
        }
    }
}

/// A validation error not yet tied to a file name.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Invalid {
    pub pos: Pos,
    pub message: String,
}

pub fn invalid<T>(pos: Pos, message: impl Into<String>) -> Result<T, Invalid> {
    Err(Invalid {
        pos,
        message: message.into(),
    })
}
