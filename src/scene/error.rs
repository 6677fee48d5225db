//! Scene errors: one line naming the file, line and column, as compilers do; and, for a
//! terminal, the line of the file they point at with a caret under the column.

use std::fmt;

/// An error in a scene file, located at a line and column, shown with the offending line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneError {
    /// The scene file's name as given to the loader.
    pub file: String,
    /// Line of the error, from 1.
    pub line: u64,
    /// Column of the error, from 1.
    pub column: u64,
    /// What is wrong, for the user.
    pub message: String,
    /// The text of the line the error points at, when the scene's text is known.
    pub source_line: Option<String>,
}

impl SceneError {
    /// An error in `file` at `pos`; the source line is added later, when the text is at hand.
    pub fn new(file: &str, pos: Pos, message: impl Into<String>) -> SceneError {
        SceneError {
            file: file.into(),
            line: pos.line,
            column: pos.column,
            message: message.into(),
            source_line: None,
        }
    }

    /// An error of a scene built in code (`SceneBuilder`), which has no file or position.
    pub fn built(message: impl Into<String>) -> SceneError {
        SceneError {
            file: super::builder::BUILDER.into(),
            line: 0,
            column: 0,
            message: message.into(),
            source_line: None,
        }
    }

    /// The error with the line it points at, taken from the scene's text.
    pub fn quoting(mut self, text: &str) -> SceneError {
        self.source_line = text
            .lines()
            .nth(self.line.saturating_sub(1) as usize)
            .map(|l| l.trim_end_matches('\r').to_string());
        self
    }

    /// The line the error points at and a caret under its column, as rustc shows them:
    ///
    /// ```text
    ///   11 | background: [0.4, 0.4
    ///      |             ^
    /// ```
    ///
    /// None when the line is not known (or is empty).
    pub fn snippet(&self) -> Option<String> {
        let line = self
            .source_line
            .as_deref()
            .filter(|l| !l.trim().is_empty())?;
        let number = self.line.to_string();
        let gutter = " ".repeat(number.len());
        // The caret sits under the column's character; tabs before it stay tabs so that it
        // lines up however wide the terminal draws them.
        let pad: String = line
            .chars()
            .take(self.column.saturating_sub(1) as usize)
            .map(|c| if c == '\t' { '\t' } else { ' ' })
            .collect();
        Some(format!("  {number} | {line}\n  {gutter} | {pad}^"))
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line == 0 {
            return write!(f, "{}: {}", self.file, self.message);
        }
        write!(
            f,
            "{}:{}:{}: {}",
            self.file, self.line, self.column, self.message
        )
    }
}

impl std::error::Error for SceneError {}

/// A position in the scene file (line and column from 1), for errors found after parsing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Pos {
    /// Line, from 1.
    pub line: u64,
    /// Column, from 1.
    pub column: u64,
}

/// The start of the file: where an error about the file as a whole points.
impl Default for Pos {
    fn default() -> Pos {
        Pos { line: 1, column: 1 }
    }
}

impl Pos {
    /// The position of a YAML parser location (line and column clamped to at least 1).
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_snippet_puts_the_caret_under_the_column() {
        let text = "camera: {}\n\tbackground: [0.4, 0.4\nspp: 4\n";
        let e = SceneError::new(
            "s.yaml",
            Pos {
                line: 2,
                column: 14,
            },
            "never closed",
        )
        .quoting(text);
        assert_eq!(
            e.snippet().unwrap(),
            "  2 | \tbackground: [0.4, 0.4\n    | \t            ^"
        );
        assert_eq!(e.to_string(), "s.yaml:2:14: never closed");
        let beyond = SceneError::new("s.yaml", Pos { line: 9, column: 1 }, "x").quoting(text);
        assert!(beyond.snippet().is_none());
    }
}
