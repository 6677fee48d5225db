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
    /// A line wider than `SNIPPET_WIDTH` columns is cut to a window around the column, with
    /// `…` where it was cut. None when the line is not known (or is empty).
    pub fn snippet(&self) -> Option<String> {
        let line = self
            .source_line
            .as_deref()
            .filter(|l| !l.trim().is_empty())?;
        let number = self.line.to_string();
        let gutter = " ".repeat(number.len());
        let chars: Vec<char> = line.chars().collect();
        let at = (self.column.saturating_sub(1) as usize).min(chars.len());
        let (start, end) = window(&chars, at, SNIPPET_WIDTH);
        let mut shown = String::new();
        let mut pad = String::new();
        if start > 0 {
            shown.push('…');
            pad.push(' ');
        }
        shown.extend(&chars[start..end]);
        if end < chars.len() {
            shown.push('…');
        }
        // The caret sits under the column's character: a character two columns wide (CJK, most
        // emoji) takes two spaces, and a tab stays a tab so that it lines up however wide the
        // terminal draws it.
        for &c in &chars[start..at] {
            if c == '\t' {
                pad.push('\t');
            } else {
                pad.extend(std::iter::repeat_n(' ', display_width(c)));
            }
        }
        Some(format!("  {number} | {shown}\n  {gutter} | {pad}^"))
    }
}

/// The widest a snippet's line is shown, in terminal columns: a line of a one-line scene can
/// be many thousands of columns, which a terminal would wrap into a screenful.
pub const SNIPPET_WIDTH: usize = 100;

/// Columns a character takes on a terminal; a tab counts as a full tab stop's worth, the most
/// it can take.
fn display_width(c: char) -> usize {
    if c == '\t' {
        8
    } else {
        unicode_width::UnicodeWidthChar::width(c).unwrap_or(1)
    }
}

/// The characters `start..end` of `chars` to show so that the one at `at` (or the end of the
/// line, when `at` is its length) is among them and they take at most `width` columns: about
/// a third of the width before the caret, the rest after it, and whatever one side does not
/// use given to the other.
fn window(chars: &[char], at: usize, width: usize) -> (usize, usize) {
    let total: usize = chars.iter().map(|&c| display_width(c)).sum();
    if total <= width {
        return (0, chars.len());
    }
    // Two columns go to the `…` marks; the caret's own character always shows.
    let budget = width.saturating_sub(2).max(1);
    let mut used = chars.get(at).map_or(1, |&c| display_width(c));
    let (mut start, mut end) = (at, (at + 1).min(chars.len()));
    while start > 0 && used + display_width(chars[start - 1]) <= budget / 3 {
        start -= 1;
        used += display_width(chars[start]);
    }
    while end < chars.len() && used + display_width(chars[end]) <= budget {
        used += display_width(chars[end]);
        end += 1;
    }
    while start > 0 && used + display_width(chars[start - 1]) <= budget {
        start -= 1;
        used += display_width(chars[start]);
    }
    (start, end)
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

    /// The character the caret points at in a snippet, found by counting terminal columns
    /// (tabs are only ever in the same places in both lines, so they are skipped together).
    fn under_caret(snippet: &str) -> char {
        let (shown, caret) = snippet.split_once('\n').unwrap();
        let shown = shown.split_once(" | ").unwrap().1;
        let pad = caret
            .split_once(" | ")
            .unwrap()
            .1
            .strip_suffix('^')
            .unwrap();
        let mut columns = pad.chars().filter(|&c| c == ' ').count();
        let mut tabs = pad.chars().filter(|&c| c == '\t').count();
        for c in shown.chars() {
            if c == '\t' {
                assert!(tabs > 0, "a tab in the line the pad lacks: {snippet:?}");
                tabs -= 1;
                continue;
            }
            if columns == 0 && tabs == 0 {
                return c;
            }
            let w = unicode_width::UnicodeWidthChar::width(c).unwrap();
            assert!(
                columns >= w,
                "the caret falls inside a character: {snippet:?}"
            );
            columns -= w;
        }
        panic!("the caret is past the line: {snippet:?}");
    }

    fn at(line: &str, column: u64) -> SceneError {
        SceneError::new("s.yaml", Pos { line: 1, column }, "x").quoting(line)
    }

    #[test]
    fn a_wide_character_takes_two_columns_before_the_caret() {
        // `n: "` (4), the emoji (2), `", r: ` (6): the `-` is on the 13th column, after 12
        // columns of padding, though it is the 12th character.
        let e = at("n: \"😀\", r: -1", 12);
        assert_eq!(
            e.snippet().unwrap(),
            format!("  1 | n: \"😀\", r: -1\n    | {}^", " ".repeat(12))
        );
        let greek = at("- { name: \"σφαίρα😀\", sphere: { radius: -1 } }", 40);
        assert_eq!(under_caret(&greek.snippet().unwrap()), '-');
    }

    #[test]
    fn a_long_line_is_cut_to_a_window_around_the_column() {
        let line = format!("{}R{}", "a".repeat(1000), "b".repeat(16000));
        let snippet = at(&line, 1001).snippet().unwrap();
        let (shown, _) = snippet.split_once('\n').unwrap();
        let shown = shown.split_once(" | ").unwrap().1;
        assert!(shown.starts_with('…') && shown.ends_with('…'), "{shown}");
        assert!(shown.chars().count() <= SNIPPET_WIDTH, "{}", shown.len());
        assert!(
            shown.chars().count() >= SNIPPET_WIDTH - 2,
            "{}",
            shown.len()
        );
        assert_eq!(under_caret(&snippet), 'R');

        // Near either end of the line only the other end is cut.
        let start = at(&line, 3).snippet().unwrap();
        assert!(start.starts_with("  1 | aaa") && start.lines().next().unwrap().ends_with('…'));
        assert_eq!(under_caret(&start), 'a');
        let end = at(&line, line.len() as u64).snippet().unwrap();
        assert!(end.starts_with("  1 | …") && end.lines().next().unwrap().ends_with('b'));
        assert_eq!(under_caret(&end), 'b');

        // Wide characters and tabs inside the window keep the caret in place.
        let wide = format!(
            "{}\t{}R{}",
            "😀".repeat(500),
            "σ".repeat(20),
            "😀".repeat(500)
        );
        assert_eq!(under_caret(&at(&wide, 522).snippet().unwrap()), 'R');
        let narrow = format!("{}\tR", "x".repeat(30));
        assert_eq!(
            at(&narrow, 32).snippet().unwrap(),
            format!("  1 | {narrow}\n    | {}\t^", " ".repeat(30))
        );
    }
}
