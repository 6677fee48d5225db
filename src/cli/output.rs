//! Writing to standard output and standard error without ever panicking (`print!` panics when
//! the write fails). A reader that has gone away (`raytree lessons | head -1`) ends the output
//! quietly, as other command-line tools do; any other write error (`> /dev/full`) is one line
//! on stderr and exit status 2. Text from scene files (names, paths, values echoed in errors)
//! may hold control characters: they are shown escaped, so a name can neither send escape
//! sequences to the terminal nor fake a line of output.

use std::io::{self, IsTerminal, Write};

use super::Failure;

/// Writes text to stdout, its control characters escaped (line breaks and tabs kept).
pub fn print(text: &str) -> Result<(), Failure> {
    write_stdout(escape(text, "\n\t").as_bytes())
}

/// `print` with a line break after the text.
pub fn println(text: &str) -> Result<(), Failure> {
    print(&format!("{text}\n"))
}

/// Writes bytes to stdout as they are (the preview's own colour escapes).
pub fn print_raw(bytes: &[u8]) -> Result<(), Failure> {
    write_stdout(bytes)
}

fn write_stdout(bytes: &[u8]) -> Result<(), Failure> {
    let mut out = io::stdout().lock();
    match out.write_all(bytes).and_then(|()| out.flush()) {
        Ok(()) => Ok(()),
        // The reader has gone: nothing more is wanted.
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => Ok(()),
        Err(e) => Err(Failure(format!("cannot write to standard output: {e}"))),
    }
}

/// One line on stderr, its control characters (line breaks too) escaped; a failure to write
/// it is ignored, as there is nowhere left to report it.
pub fn eprintln(line: &str) {
    let _ = writeln!(io::stderr().lock(), "{}", escape(line, ""));
}

/// Lines on stderr shown only on a terminal (a scene error's snippet), control characters
/// escaped line by line.
pub fn eprint_block(text: &str) {
    let mut err = io::stderr().lock();
    for line in text.lines() {
        let _ = writeln!(err, "{}", escape(line, "\t"));
    }
}

pub fn stderr_is_terminal() -> bool {
    io::stderr().is_terminal()
}

/// `text` with every control character but those in `keep` written as an escape (`\u{1b}`,
/// `\n`): visible, and inert in a terminal.
pub fn escape(text: &str, keep: &str) -> String {
    if !text.chars().any(|c| c.is_control() && !keep.contains(c)) {
        return text.to_string();
    }
    text.chars()
        .map(|c| {
            if c.is_control() && !keep.contains(c) {
                c.escape_default().to_string()
            } else {
                c.to_string()
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::escape;

    #[test]
    fn control_characters_are_shown_not_sent() {
        assert_eq!(escape("a\u{1b}[2Jb", ""), "a\\u{1b}[2Jb");
        assert_eq!(escape("one\ntwo", ""), "one\\ntwo");
        assert_eq!(escape("one\ntwo\tx\u{7}", "\n\t"), "one\ntwo\tx\\u{7}");
        assert_eq!(escape("σ = 0.5 → ∞", ""), "σ = 0.5 → ∞");
        // C1 controls (U+0080..U+009F) reach terminals too.
        assert_eq!(escape("\u{9b}2J", ""), "\\u{9b}2J");
    }
}
