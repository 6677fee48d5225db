//! Large scene files parse on all threads: the `objects:` list is cut between its items into
//! pieces, and each piece is parsed on its own as the whole file with everything but that
//! piece blanked to spaces. Lines, columns and byte offsets stay the file's own, so positions
//! in values and in errors are exactly those of parsing the file in one go.
//!
//! Only plain YAML is cut: without quotes, block scalars, anchors, aliases, tags or tabs, a
//! line at the list's indentation that starts with `- ` outside any flow collection (see
//! `flow`) begins the next item and nothing else can. Any other file parses in one piece.
//! Whatever the pieces say, the answer is the one-piece parse's: a file whose pieces do not
//! all parse is parsed again in one piece, so its error is the one a single thread reports.

/// Below this size a file parses in one piece: a thread would cost more than it saves.
pub const MIN_SPLIT_BYTES: usize = 64 * 1024;

/// A scene file cut into pieces that parse independently.
#[derive(Debug)]
pub struct Split {
    /// The file with every piece but the first blanked: the settings before and after the
    /// list, and the list's first items. It parses as the scene file.
    pub head: String,
    /// The other pieces, in order. Each is the file with everything before the piece blanked
    /// and everything after it left out; it parses as a list of objects.
    pub pieces: Vec<String>,
}

/// Characters that make YAML more than plain nested blocks and brackets: quotes and block
/// scalars (whose text may look like a list item), anchors, aliases and tags (which tie
/// items together), directives, reserved indicators, complex keys and tabs.
const NOT_PLAIN: &[u8] = b"\"'|>&*!%@`?\t";

/// `NOT_PLAIN` as a table by byte: the check runs on every byte of the list.
const IS_NOT_PLAIN: [bool; 256] = {
    let mut table = [false; 256];
    let mut i = 0;
    while i < NOT_PLAIN.len() {
        table[NOT_PLAIN[i] as usize] = true;
        i += 1;
    }
    table
};

/// Cuts a large file into at most `pieces` pieces, or says it is not worth it or cannot.
pub fn split(text: &str, pieces: usize) -> Option<Split> {
    if text.len() < MIN_SPLIT_BYTES {
        return None;
    }
    cut(text, pieces)
}

/// Cuts `text` into at most `pieces` pieces of roughly equal size, or says it cannot.
fn cut(text: &str, pieces: usize) -> Option<Split> {
    if pieces < 2 {
        return None;
    }
    let list = object_list(text)?;
    if list.items.len() < 2 {
        return None;
    }
    // Cut at the item nearest each equal share of the list's bytes.
    let (first, rest) = (list.items[0], &list.items[1..]);
    let mut cuts: Vec<usize> = (1..pieces)
        .filter_map(|k| {
            let share = first + (list.end - first) * k / pieces;
            rest.iter().copied().min_by_key(|at| at.abs_diff(share))
        })
        .collect();
    cuts.dedup();
    let head = format!(
        "{}{}{}",
        &text[..cuts[0]],
        blank(&text[cuts[0]..list.end])?,
        &text[list.end..]
    );
    let ends = cuts.iter().skip(1).copied().chain([list.end]);
    let pieces = cuts
        .iter()
        .zip(ends)
        .map(|(&from, to)| Some(format!("{}{}", blank(&text[..from])?, &text[from..to])))
        .collect::<Option<_>>()?;
    Some(Split { head, pieces })
}

/// Whole lines of text blanked, keeping every line's characters and bytes (positions count
/// both): an ASCII line becomes spaces, a line with other characters a comment of itself
/// (`#` for its first byte). None where a line starts with a character beyond ASCII.
pub(super) fn blank(text: &str) -> Option<String> {
    let mut out = String::with_capacity(text.len());
    for line in text.split_inclusive('\n') {
        if line.is_ascii() {
            out.extend(line.bytes().map(|b| if b == b'\n' { '\n' } else { ' ' }));
        } else if line.as_bytes()[0].is_ascii() {
            out.push('#');
            out.push_str(&line[1..]);
        } else {
            return None;
        }
    }
    Some(out)
}

/// Where the top-level `objects:` block list's items start, and where the list ends.
pub(super) struct ObjectList {
    pub items: Vec<usize>,
    pub end: usize,
}

/// Finds the block list under a top-level `objects:` key, if the file is plain enough to cut.
pub(super) fn object_list(text: &str) -> Option<ObjectList> {
    // Flow collections may span lines; a line inside one is neither the key nor an item.
    let flow = super::flow::scan(text);
    // The lines with how many collections are open at each (the scan's lines are the text's),
    // read once: up to the key, the list, the rest.
    let mut lines = lines(text).zip(flow.lines.iter().map(|&(_, open)| open));
    let is_key = |code: &str, open| code.trim_end() == "objects:" && open == 0;
    let key_at = loop {
        let ((at, line), open) = lines.next()?;
        let code = content(line);
        if is_key(code, open) {
            break at;
        }
        if code.contains(['"', '\'']) {
            return None; // a quoted string could span lines, hiding the key or the list
        }
    };

    let mut items = Vec::new();
    let mut indent = None;
    let mut end = text.len();
    for ((at, line), depth) in lines.by_ref() {
        let code = content(line);
        if code.trim().is_empty() {
            continue;
        }
        let this_indent = code.len() - code.trim_start_matches(' ').len();
        let starts_item = |indent: usize| {
            let rest = &code[indent..];
            this_indent == indent && (rest == "-" || rest.starts_with("- "))
        };
        if code.bytes().any(|b| IS_NOT_PLAIN[b as usize]) {
            return None;
        }
        let list_indent = *indent.get_or_insert(this_indent);
        if depth == 0 && starts_item(list_indent) {
            items.push(at);
        } else if depth == 0 && this_indent <= list_indent {
            // `-1`, `--`: not an item, but too close to one to trust; a second key: the
            // parser reports it.
            if code[this_indent..].starts_with('-') || is_key(code, depth) {
                return None;
            }
            end = at; // the next key, or a line the parser will reject in context
            break;
        }
    }
    // A second key further on (a top-level line ends the list, so none is inside it).
    if lines.any(|((_, line), open)| is_key(content(line), open)) {
        return None;
    }
    // A collection left open inside the list would swallow what follows it.
    let open_inside = flow.unclosed.iter().any(|b| b.at > key_at && b.at < end);
    (!open_inside).then_some(ObjectList { items, end })
}

/// The file's lines with the byte offset each starts at (line breaks kept).
fn lines(text: &str) -> impl Iterator<Item = (usize, &str)> + Clone {
    text.split_inclusive('\n').scan(0, |at, line| {
        let start = *at;
        *at += line.len();
        Some((start, line))
    })
}

/// A line without its comment and line break. Before the first quote in the file (a cut file
/// has none up to the end of its list), `#` starts a comment at the start of a line or after
/// a space.
pub(super) fn content(line: &str) -> &str {
    let line = line.trim_end_matches(['\n', '\r']);
    let bytes = line.as_bytes();
    let comment = (0..bytes.len()).find(|&i| bytes[i] == b'#' && (i == 0 || bytes[i - 1] == b' '));
    &line[..comment.unwrap_or(line.len())]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::format::{ObjectSpec, SceneFile};
    use crate::scene::load::{from_yaml, parse_in_pieces, parse_split};
    use proptest::prelude::*;
    use serde_saphyr::Spanned;

    /// One item of the object list at indentation `pad`, in one of the styles scene files use.
    fn item(style: u8, pad: &str, i: usize) -> String {
        let (x, y) = (i as f64 * 0.25, -(i as f64) / 7.0);
        match style % 10 {
            0 => format!(
                "{pad}- {{ sphere: {{ center: [{x}, {y}, 1], radius: 0.5 }}, material: m }}\n"
            ),
            1 => format!(
                "{pad}- name: s{i}\n{pad}  sphere:\n{pad}    center: [{x}, {y}, 2]\n\
                 {pad}    radius: 1e-3\n{pad}  material: m\n"
            ),
            // A CSG object whose children are a list of their own, deeper in.
            2 => format!(
                "{pad}- difference:\n{pad}    - box: {{ min: [0, 0, 0], max: [1, 1, {x}] }}\n\
                 {pad}    - sphere:\n{pad}        center: [0.5, 0.5, 0.5]\n\
                 {pad}        radius: 0.6\n{pad}  transform: [ {{ rotate_y: {y} }} ]\n"
            ),
            // A bracket left open across lines, the next line under-indented.
            3 => format!(
                "{pad}- {{ cylinder: {{ base: [0, 0, 0], top: [0, {x}, 0],\n\
                 {pad} radius: 0.25 }}, material: m }}\n"
            ),
            // Comments, one of them looking like an item, and blank lines.
            4 => format!(
                "{pad}# - {{ sphere: {{ center: [0, 0, 0], radius: 1 }} }}\n\n\
                 {pad}- {{ cone: {{ apex: [0, 1, 0], base: [0, 0, 0], radius: {x} }} }} # a#b, ×\n\
                 # a comment at the margin\n   \n"
            ),
            5 => format!("{pad}-\n{pad}  triangle: [[0, 0, 0], [1, 0, {x}], [0, 1, 0]]\n"),
            6 => format!(
                "{pad}- complement: {{ plane: {{ point: [0, {y}, 0], normal: [0, 1, 0] }} }}\n"
            ),
            7 => format!("{pad}- {{ icosphere: {{ subdivisions: {i}, smooth: false }} }}\n"),
            // Brackets inside plain scalars: names, not collections.
            8 => format!(
                "{pad}- name: x[{i}\n{pad}  sphere: {{ center: [0, {y}, 0], radius: 1 }}\n{pad}  material: m\n"
            ),
            _ => format!("{pad}- name: y]{i} {{ z\n{pad}  box: {{ min: [0, 0, 0], max: [1, 1, 1] }}\n"),
        }
    }

    /// A scene file: settings, the object list (indented by `pad`), perhaps settings after it.
    fn scene(styles: &[u8], pad: &str, after: bool, crlf: bool) -> String {
        let mut text = String::from(
            "# a scene — façade\ncamera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\n\
             materials:\n  m: { color: [1, 0, 0], kd: 0.8 }\nobjects:   # the list\n",
        );
        for (i, &style) in styles.iter().enumerate() {
            text += &item(style, pad, i);
        }
        if after {
            text += "lights:\n  - { point: [0, 5, 0], intensity: 1 }\n  - name: y]\n    point: [0, 5, 0]\nspp: 4\n";
        }
        if crlf {
            text = text.replace('\n', "\r\n");
        }
        text
    }

    /// Mistakes a scene's author makes, one of them at the `nth` place it can be made.
    fn spoil(text: &str, nth: usize, how: u8) -> String {
        let (from, to) = [
            ("radius", "radious"),
            ("0", "0.0.1"),
            ("0]", "0}"),
            ("]", ""),
            ("material: m", "material: m, material: m"),
            ("center: ", ""),
            (": ", ":: "),
        ][how as usize % 7];
        let places: Vec<usize> = text.match_indices(from).map(|(at, _)| at).collect();
        match places.get(nth % places.len().max(1)) {
            Some(&at) => format!("{}{to}{}", &text[..at], &text[at + from.len()..]),
            None => text.to_string(),
        }
    }

    fn objects(text: &str) -> Vec<Spanned<ObjectSpec>> {
        from_yaml::<SceneFile>(text, "f").unwrap().objects
    }

    /// Blanked lines keep their characters and bytes: ASCII lines become spaces, others a
    /// comment of themselves; a line that starts beyond ASCII cannot be blanked so.
    #[test]
    fn blanking_keeps_characters_and_bytes() {
        let text = "  - { name: a }\n\n  - { name: café } # ×\r\n";
        let blanked = blank(text).expect("every line starts in ASCII");
        assert_eq!(blanked, "               \n\n# - { name: café } # ×\r\n");
        assert_eq!(blanked.len(), text.len());
        assert_eq!(blanked.chars().count(), text.chars().count());
        assert_eq!(blank("é: 1\n"), None);
    }

    #[test]
    fn pieces_start_at_items_and_keep_every_position() {
        let text = scene(&[0, 1, 2, 3, 4, 5, 6, 7, 0, 1], "  ", true, false);
        let split = cut(&text, 3).expect("plain enough to cut");
        assert_eq!(split.pieces.len(), 2);
        assert_eq!(split.head.len(), text.len());
        for piece in &split.pieces {
            // Blanked: spaces, and lines beyond ASCII as comments of themselves.
            let from = piece.find("\n  - ").expect("an item") + 3;
            for line in piece[..from].lines() {
                assert!(line.starts_with('#') || line.bytes().all(|b| b == b' '));
            }
            let chars = |s: &str| s.chars().count();
            assert_eq!(chars(&piece[..from]), chars(&text[..from]));
            assert_eq!(&piece[from..], &text[from..piece.len()]);
            assert!(
                text[..from].ends_with("\n  "),
                "cut at the start of an item's line"
            );
            assert!(piece[from..].starts_with("- "));
        }
        let whole = format!("{:?}", objects(&text));
        let parsed = format!("{:?}", parse_split(split, text.len(), "f").unwrap().objects);
        assert_eq!(parsed, whole);
    }

    #[test]
    fn files_that_are_not_plain_or_have_no_block_list_parse_whole() {
        let list = scene(&[0; 40], "  ", false, false);
        assert!(cut(&list, 2).is_some());
        assert!(cut(&list, 1).is_none(), "one thread: nothing to cut");
        assert!(split(&list, 2).is_none(), "small files parse whole");
        for spoiler in [
            "  - &a { sphere: { center: [0, 0, 0], radius: 1 } }\n  - *a\n",
            "  - { name: \"quoted\", sphere: { center: [0, 0, 0], radius: 1 } }\n",
            "  - { name: 'quoted', sphere: { center: [0, 0, 0], radius: 1 } }\n",
            "  - name: |\n      - looks like an item\n",
            "  - !tagged { sphere: { center: [0, 0, 0], radius: 1 } }\n",
            "  -\t{ sphere: { center: [0, 0, 0], radius: 1 } }\n",
            "  - { sphere: { center: [0, 0, 0], radius: 1 }\n",
        ] {
            let text = format!("{list}{spoiler}");
            assert!(cut(&text, 2).is_none(), "{spoiler}");
        }
        let quoted = list.replace("# a scene — façade\n", "integrator: 'whitted'\n");
        assert!(cut(&quoted, 2).is_none(), "a string before the list");
        let flow = list.replace("objects:   # the list\n", "objects: [\n") + "]\n";
        assert!(cut(&flow, 2).is_none(), "a flow list");
        let twice =
            format!("{list}objects:\n  - {{ sphere: {{ center: [0, 0, 0], radius: 1 }} }}\n");
        assert!(cut(&twice, 2).is_none(), "a duplicate key");
        let later = twice.replacen("\nobjects:\n  - {", "\nspp: 4\nobjects:\n  - {", 1);
        assert!(later.contains("spp: 4\nobjects:"));
        assert!(
            cut(&later, 2).is_none(),
            "a duplicate key after other settings"
        );
    }

    /// An object named `x[` near the end of a large list and a light named `y]` after the
    /// list: plain scalars, not a collection spanning the end of the list.
    #[test]
    fn brackets_in_names_do_not_move_the_end_of_the_list() {
        let mut text = scene(&[0; 2000], "  ", false, false);
        text += "  - { name: z, sphere: { center: [0, 0, 0], radius: 1 }, material: m }\n";
        text += "  - name: x[\n    sphere: { center: [0, 0, 0], radius: 2 }\n    material: m\n";
        text += "lights:\n  - name: y]\n    point: [0, 5, 0]\n";
        assert!(text.len() > MIN_SPLIT_BYTES);
        let whole = format!("{:?}", from_yaml::<SceneFile>(&text, "f").unwrap());
        let split = cut(&text, 2).expect("plain enough to cut");
        assert!(split.head.contains("lights:"), "the lights follow the list");
        for pieces in 1..5 {
            let parsed = parse_in_pieces(&text, "f", pieces).unwrap();
            assert_eq!(parsed.lights.len(), 1);
            assert_eq!(format!("{parsed:?}"), whole, "{pieces} pieces");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        /// Cut or not, a file parses to the same objects at the same positions.
        #[test]
        fn cutting_changes_nothing(
            styles in prop::collection::vec(any::<u8>(), 2..40),
            margin in any::<bool>(),
            after in any::<bool>(),
            crlf in any::<bool>(),
            pieces in 2usize..5,
        ) {
            let text = scene(&styles, if margin { "" } else { "  " }, after, crlf);
            let split = cut(&text, pieces).expect("plain enough to cut");
            prop_assert!(split.pieces.len() < pieces);
            let whole = format!("{:?}", from_yaml::<SceneFile>(&text, "f").unwrap());
            prop_assert_eq!(format!("{:?}", parse_split(split, text.len(), "f").unwrap()), whole);
        }

        /// Mistakes anywhere: the first is reported, where reading the file in one go reports it.
        #[test]
        fn the_first_mistake_is_reported_where_it_is(
            styles in prop::collection::vec(any::<u8>(), 2..40),
            margin in any::<bool>(),
            mistakes in prop::collection::vec((any::<usize>(), any::<u8>()), 1..3),
            pieces in 2usize..5,
        ) {
            let mut text = scene(&styles, if margin { "" } else { "  " }, true, false);
            for (nth, how) in mistakes {
                text = spoil(&text, nth, how);
            }
            let whole = from_yaml::<SceneFile>(&text, "f").map(|s| format!("{s:?}"));
            // Below the size the loader cuts at, nothing would be cut: pad with a comment.
            let padded = format!("{text}#{}\n", " ".repeat(MIN_SPLIT_BYTES));
            let whole_padded = from_yaml::<SceneFile>(&padded, "f").map(|s| format!("{s:?}"));
            prop_assert_eq!(&whole_padded, &whole);
            let parsed = parse_in_pieces(&padded, "f", pieces).map(|s| format!("{s:?}"));
            prop_assert_eq!(parsed, whole);
        }
    }
}
