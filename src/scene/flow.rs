//! Where YAML's flow collections (`[…]` and `{…}`) open and close, found by a scan of the text
//! without parsing it. The parallel loader (`split`) cuts a file only where no collection is
//! open, and a syntax error inside a collection that is never closed is reported at its
//! opening bracket rather than on the line after it.
//!
//! A bracket opens a collection only where a YAML node can start: at the start of a line's
//! content, after `- `, `? ` or `: `, after an anchor or a tag, and inside a collection after
//! `[`, `{`, `,` or `:`. Elsewhere in block context a bracket is an ordinary character of a
//! plain scalar (`name: x[` is the string "x["). Inside a collection every bracket counts
//! (plain scalars there cannot hold one). Quoted scalars, comments and block scalars (`|`,
//! `>`) are skipped.

/// An opening bracket: where it is (byte offset, line and column from 1) and which it is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Bracket {
    pub at: usize,
    pub line: u64,
    pub column: u64,
    pub open: char,
}

/// What a scan found.
#[derive(Debug, Default)]
pub struct Scan {
    /// For each line: the byte offset it starts at, and how many collections are open there.
    pub lines: Vec<(usize, usize)>,
    /// The collections still open at the end of the text, outermost first.
    pub unclosed: Vec<Bracket>,
}

/// Scans `text` for its flow collections.
pub fn scan(text: &str) -> Scan {
    scan_in_halves(text, PARALLEL_BYTES)
}

/// From this size a text is scanned in two halves on two threads.
const PARALLEL_BYTES: usize = 64 * 1024;

/// Where a scan stands at the start of a line.
#[derive(Debug, Default, PartialEq)]
struct State {
    /// The open brackets as (byte offset, the line's start, bracket): a line and column are
    /// counted only for those the text never closes.
    open: Vec<(usize, usize, u8)>,
    /// The quote a scalar spanning lines is in.
    quote: Option<u8>,
    /// The indentation of the line holding a block scalar's `|` or `>`: its content is every
    /// following line indented more (or blank).
    block_scalar: Option<usize>,
}

/// `scan`, in two halves on two threads from `min_bytes` on. The second half is scanned as if
/// it started outside any collection, quote or block scalar; where the first half does not end
/// so, the second half is scanned again from where the first one ends.
fn scan_in_halves(text: &str, min_bytes: usize) -> Scan {
    // The start of the first line after the middle byte.
    let middle = text.len() / 2;
    let halfway = (text.len() >= min_bytes)
        .then(|| text.as_bytes()[middle..].iter().position(|&b| b == b'\n'))
        .flatten()
        .map(|i| middle + i + 1);
    let (lines, end) = match halfway {
        Some(cut) => {
            let ((mut lines, state), (rest, rest_end)) = rayon::join(
                || scan_lines(text, 0..cut, State::default()),
                || scan_lines(text, cut..text.len(), State::default()),
            );
            let (rest, end) = if state == State::default() {
                (rest, rest_end)
            } else {
                scan_lines(text, cut..text.len(), state)
            };
            lines.extend(rest);
            (lines, end)
        }
        None => scan_lines(text, 0..text.len(), State::default()),
    };
    let unclosed = end
        .open
        .into_iter()
        .map(|(at, line_start, c)| Bracket {
            at,
            line: text[..line_start].bytes().filter(|&b| b == b'\n').count() as u64 + 1,
            column: text[line_start..at].chars().count() as u64 + 1,
            open: c as char,
        })
        .collect();
    Scan { lines, unclosed }
}

/// The lines of `text[range]` (which starts at a line) scanned from `state`: each line's start
/// and the collections open there, and the state after the last line.
fn scan_lines(
    text: &str,
    range: std::ops::Range<usize>,
    mut state: State,
) -> (Vec<(usize, usize)>, State) {
    let mut lines = Vec::new();
    let mut at = range.start;
    for line in text[range].split_inclusive('\n') {
        let start = at;
        at += line.len();
        lines.push((start, state.open.len()));
        let body = line.trim_end_matches(['\n', '\r']);
        let indent = body.len() - body.trim_start_matches(' ').len();
        if let Some(parent) = state.block_scalar {
            if body.trim().is_empty() || indent > parent {
                continue;
            }
            state.block_scalar = None;
        }
        // A node can start at the start of a line in block context, and anywhere a
        // collection's entry begins. Byte by byte: every character that matters is ASCII, and
        // a byte of a longer UTF-8 character is never one of them.
        let mut node_start = state.quote.is_none();
        let mut prev = b' ';
        let bytes = body.as_bytes();
        let bracket = |i: usize, c: u8| (start + i, start, c);
        let mut i = 0;
        while i < bytes.len() {
            let c = bytes[i];
            let next = bytes.get(i + 1).copied().unwrap_or(b' ');
            i += 1;
            if let Some(q) = state.quote {
                match (q, c) {
                    (b'"', b'\\') => i += 1,
                    (b'\'', b'\'') if next == b'\'' => i += 1,
                    (q, c) if q == c => state.quote = None,
                    _ => {}
                }
                prev = c;
                continue;
            }
            if c == b'#' && prev.is_ascii_whitespace() {
                break; // a comment: the rest of the line
            }
            let in_flow = !state.open.is_empty();
            let spaced = next.is_ascii_whitespace();
            if c.is_ascii_whitespace() {
                prev = c;
                continue;
            }
            if node_start {
                match c {
                    b'"' | b'\'' => {
                        state.quote = Some(c);
                        node_start = false;
                    }
                    b'[' | b'{' => state.open.push(bracket(i - 1, c)),
                    b'|' | b'>' if !in_flow => {
                        state.block_scalar = Some(indent);
                        break;
                    }
                    b'-' if spaced && !in_flow => {}
                    b'?' if spaced => {}
                    b'&' | b'!' => {
                        // An anchor or a tag: the node itself follows it.
                        while bytes.get(i).is_some_and(|n| !n.is_ascii_whitespace()) {
                            i += 1;
                        }
                    }
                    b']' | b'}' if in_flow => {
                        state.open.pop();
                        node_start = false;
                    }
                    b',' if in_flow => {}
                    _ => node_start = false,
                }
            } else if in_flow {
                match c {
                    b'[' | b'{' => {
                        state.open.push(bracket(i - 1, c));
                        node_start = true;
                    }
                    b']' | b'}' => {
                        state.open.pop();
                    }
                    b',' => node_start = true,
                    b':' if spaced
                        || matches!(next, b',' | b']' | b'}')
                        || matches!(prev, b'"' | b'\'') =>
                    {
                        node_start = true
                    }
                    _ => {}
                }
            } else if c == b':' && spaced {
                node_start = true;
            }
            prev = c;
        }
    }
    (lines, state)
}

/// The collection a syntax error on `line` most likely comes from: the last one opened on an
/// earlier line that the text never closes.
pub fn unclosed_before(text: &str, line: u64) -> Option<Bracket> {
    scan(text)
        .unclosed
        .into_iter()
        .rev()
        .find(|b| b.line < line)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Lines of the kinds the scan follows: collections opened and closed across lines,
    /// quotes spanning lines, block scalars, comments, brackets in plain scalars, text beyond
    /// ASCII.
    const LINES: &[&str] = &[
        "objects:\n",
        "  - { name: a, sphere: { center: [0, 1, 2], radius: 1 } }\n",
        "camera: { eye: [0, 0, -5],\n",
        "  look_at: [0, 0, 0] }\n",
        "lights: [\n",
        "]\n",
        "  - name: x[\n",
        "  - name: y] # ]\n",
        "note: \"a [ quote\n",
        "  spanning ] lines\"\n",
        "it: 'don''t {\n",
        "  stop'\n",
        "text: |\n",
        "  - [ not an item\n",
        "\n",
        "façade: { é: [1, 2],\r\n",
    ];

    proptest! {
        /// Scanned in halves or in one go, a text has the same lines, depths and unclosed
        /// brackets, wherever the halves meet.
        #[test]
        fn halves_scan_as_the_whole(picks in prop::collection::vec(0..LINES.len(), 0..40)) {
            let text: String = picks.iter().map(|&k| LINES[k]).collect();
            let whole = scan_in_halves(&text, usize::MAX);
            let halves = scan_in_halves(&text, 0);
            prop_assert_eq!(&halves.lines, &whole.lines);
            prop_assert_eq!(&halves.unclosed, &whole.unclosed);
        }
    }

    fn depths(text: &str) -> Vec<usize> {
        scan(text).lines.iter().map(|&(_, d)| d).collect()
    }

    #[test]
    fn brackets_in_plain_scalars_open_nothing() {
        let text = "objects:\n  - { name: a, sphere: [1, 2] }\n  - name: x[\n  - name: y]\n  - z\n";
        assert_eq!(depths(text), [0, 0, 0, 0, 0]);
        assert!(scan(text).unclosed.is_empty());
    }

    #[test]
    fn collections_open_across_lines_are_counted() {
        let text = "camera: { eye: [0, 0, -5],\n  look_at: [0, 0, 0] }\nlights: [\n  { point: [1, 2, 3] },\n]\nx: 1\n";
        assert_eq!(depths(text), [0, 1, 0, 1, 1, 0]);
        assert!(scan(text).unclosed.is_empty());
    }

    #[test]
    fn quotes_comments_and_block_scalars_are_skipped() {
        let text = "a: \"[ # not a comment\"\nb: '{ it''s }' # [ a comment\nc: |\n  [ text\n   { more\nd: [\n";
        assert_eq!(depths(text), [0, 0, 0, 0, 0, 0]);
        let unclosed = scan(text).unclosed;
        assert_eq!(unclosed.len(), 1);
        assert_eq!((unclosed[0].line, unclosed[0].column), (6, 4));
    }

    #[test]
    fn an_unclosed_list_is_found_before_the_error_it_causes() {
        let text =
            "camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nbackground: [0.4, 0.4\nspp: 4\n";
        let b = unclosed_before(text, 3).unwrap();
        assert_eq!((b.line, b.column, b.open), (2, 13, '['));
        assert!(
            unclosed_before(text, 2).is_none(),
            "not on the error's own line"
        );
    }

    #[test]
    fn a_multi_line_flow_value_in_a_list_item_is_followed() {
        let text = "- { cylinder: { base: [0, 0, 0], top: [0, 1, 0],\n radius: 0.25 }, material: m }\n- { a: [x, y] }\n";
        assert_eq!(depths(text), [0, 2, 0]);
    }
}
