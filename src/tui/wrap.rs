//! Word wrap: how many rows a line of text takes in a pane of a given width. The model asks
//! it for scroll limits and the drawing code for the rows it draws, so both count alike.

use ratatui::text::Span;

/// Display width of a string in terminal cells.
pub fn width(s: &str) -> usize {
    Span::raw(s).width()
}

/// The line cut to `max` cells, ending in "…" where it was cut.
pub fn cut(line: &str, max: usize) -> String {
    if width(line) <= max {
        return line.to_string();
    }
    let mut out = String::new();
    for c in line.chars() {
        if width(&out) + width(c.encode_utf8(&mut [0; 4])) + 1 > max {
            break;
        }
        out.push(c);
    }
    if max > 0 {
        out.push('…');
    }
    out
}

/// A pane's title (" name · part · part ") within `max` cells: whole parts, never a part cut
/// in the middle of a word. The first part, the pane's name, always stays; each later part
/// stays where it fits after those kept before it, in order. Parts are separated by " · "
/// outside brackets, so "(C: met only · c closes)" is one part. A name wider than `max` is cut
/// at a word's end, with "…".
pub fn title_to_fit(title: &str, max: usize) -> String {
    if width(title) <= max {
        return title.to_string();
    }
    let parts = title_parts(title.trim());
    let mut kept = format!(" {} ", parts[0]);
    if width(&kept) > max {
        return cut_at_word(&kept, max);
    }
    for part in &parts[1..] {
        let longer = format!("{}· {part} ", kept);
        if width(&longer) <= max {
            kept = longer;
        }
    }
    kept
}

/// How few cells a message's first part may be cut to before its key hints give way.
const SUBJECT_CELLS: usize = 24;

/// A one-line message ("subject · key hint · key hint") within `max` cells. The key hints are
/// what the student acts on next, so where the whole line does not fit, the subject is cut at
/// a word's end ("…") to keep every hint, down to `SUBJECT_CELLS` of it (or all of it, where
/// shorter); past that, the hints that do not fit are left out, as a title's parts are.
pub fn message_to_fit(message: &str, max: usize) -> String {
    if width(message) <= max {
        return message.to_string();
    }
    let parts = title_parts(message);
    let subject = parts[0];
    let hints: String = parts[1..].iter().map(|h| format!(" · {h}")).collect();
    let room = max.saturating_sub(width(&hints));
    if !hints.is_empty() && room >= width(subject).min(SUBJECT_CELLS) {
        return format!("{}{hints}", cut_at_word(subject, room));
    }
    let mut kept = cut_at_word(subject, max);
    for hint in &parts[1..] {
        let longer = format!("{kept} · {hint}");
        if width(&longer) <= max {
            kept = longer;
        }
    }
    kept
}

/// The " · "-separated parts of a title, not split inside brackets.
fn title_parts(title: &str) -> Vec<&str> {
    let (mut parts, mut depth, mut start) = (vec![], 0i32, 0);
    for (i, c) in title.char_indices() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            _ if depth == 0 && title[i..].starts_with(" · ") => {
                parts.push(&title[start..i]);
                start = i + " · ".len();
            }
            _ => {}
        }
    }
    parts.push(&title[start..]);
    parts
}

/// `line` cut to `max` cells at the end of a word, ending in "…" (mid-word only when its first
/// word alone is too wide).
fn cut_at_word(line: &str, max: usize) -> String {
    let cut = cut(line, max);
    let kept = cut.trim_end_matches('…');
    let next = line[kept.len()..].chars().next();
    if next.is_none_or(|c| c == ' ') {
        return cut;
    }
    match kept.trim_end().rfind(' ') {
        Some(i) if !kept[..i].trim().is_empty() => format!("{}…", &kept[..i]),
        _ => cut,
    }
}

/// Word-wraps a line to `max` cells; continuation lines keep the line's indentation (plus
/// two cells), so wrapped formulas stay readable.
pub fn wrap(line: &str, max: usize) -> Vec<String> {
    let indent_len = line.len() - line.trim_start().len();
    let hang = " ".repeat((indent_len + 2).min(max / 2));
    wrap_hang(line, max, &hang)
}

/// Word-wraps a line to `max` cells, starting continuation lines with `hang`.
pub fn wrap_hang(line: &str, max: usize, hang: &str) -> Vec<String> {
    if max == 0 {
        return vec![];
    }
    if width(line) <= max {
        return vec![line.to_string()];
    }
    let hang = if width(hang) > max / 2 { "" } else { hang };
    let indent_len = line.len() - line.trim_start().len();
    let mut out = Vec::new();
    let mut cur = line[..indent_len].to_string();
    let mut cur_w = width(&cur);
    let mut at_start = true;
    for word in line[indent_len..].split(' ') {
        let ww = width(word);
        let sep = if at_start { 0 } else { 1 };
        if !at_start && cur_w + sep + ww > max {
            out.push(std::mem::take(&mut cur));
            cur = hang.to_string();
            cur_w = width(&cur);
            at_start = true;
        }
        let sep = if at_start { 0 } else { 1 };
        if cur_w + sep + ww <= max {
            if sep == 1 {
                cur.push(' ');
            }
            cur.push_str(word);
            cur_w += sep + ww;
            at_start = false;
            continue;
        }
        // A word longer than a line: cut it.
        for ch in word.chars() {
            let cw = width(ch.encode_utf8(&mut [0; 4]));
            if cur_w + cw > max {
                out.push(std::mem::take(&mut cur));
                cur = hang.to_string();
                cur_w = width(&cur);
            }
            cur.push(ch);
            cur_w += cw;
        }
        at_start = false;
    }
    if !cur.trim().is_empty() {
        out.push(cur);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The words of a title, "…" marks aside.
    fn words(s: &str) -> Vec<&str> {
        s.split_whitespace()
            .map(|w| w.trim_end_matches('…'))
            .filter(|w| !w.is_empty())
            .collect()
    }

    /// A message too long for its line keeps its key hints and cuts its subject at a word;
    /// a subject that would be cut too short keeps its place and the hints that fit after it.
    #[test]
    fn a_message_keeps_its_key_hints() {
        let note = "exercise exit-point: ray (-3, 4, 0) → (0.6, -0.8, 0), the primary ray of \
                    pixel 3,7, node refraction · Enter: answer · w: worked solution · Esc: back";
        assert_eq!(message_to_fit(note, 200), note);
        let fitted = message_to_fit(note, 100);
        assert_eq!(
            fitted,
            "exercise exit-point: ray (-3, 4, 0) → (0.6,… · Enter: answer · w: worked \
             solution · Esc: back"
        );
        assert!(width(&fitted) <= 100);
        // At 70 cells the subject would keep 22: it stays, with the hints that fit after it.
        assert_eq!(
            message_to_fit(note, 70),
            "exercise exit-point: ray (-3, 4, 0) → (0.6, -0.8, 0), the primary ray…"
        );
        for max in 0..=width(note) {
            assert!(width(&message_to_fit(note, max)) <= max, "{max}");
        }
        // A line of key hints alone keeps those that fit, in order.
        let keys = "←↑↓→ pick a pixel · Tab tree · +/- depth · n/p levels · ? keys";
        assert_eq!(
            message_to_fit(keys, 40),
            "←↑↓→ pick a pixel · Tab tree · +/- depth"
        );
    }

    /// A title that fits is kept as it is; one that does not loses whole parts, from those
    /// that do not fit after the ones before them, and never a part cut mid-word.
    #[test]
    fn a_title_keeps_the_whole_parts_that_fit() {
        let title = " ray tree · pixel 30,30 · level 2 of 5 ";
        assert_eq!(width(title), 39);
        assert_eq!(title_to_fit(title, 39), title);
        assert_eq!(title_to_fit(title, 30), " ray tree · pixel 30,30 ");
        // A part that does not fit is left out; a shorter one after it still fits.
        assert_eq!(
            title_to_fit(" ray tree · pixel 130,130 · level 2 ", 22),
            " ray tree · level 2 "
        );
        assert_eq!(title_to_fit(title, 12), " ray tree ");
        // The name alone too wide: cut after a whole word.
        assert_eq!(title_to_fit(title, 7), " ray…");
        // Brackets hold their " · ".
        assert_eq!(title_to_fit(" a · b (c · d) · e ", 8), " a · e ");
        let csg = " CSG segment lists [t_in, t_out] · every object · C: met only · c closes ";
        assert_eq!(
            title_to_fit(csg, 60),
            " CSG segment lists [t_in, t_out] · every object · c closes "
        );
        for max in 0..=width(csg) {
            let fitted = title_to_fit(csg, max);
            assert!(width(&fitted) <= max, "{max}: {fitted:?}");
            for w in words(&fitted) {
                assert!(
                    csg.split_whitespace().any(|whole| whole == w)
                        || fitted.ends_with(&format!("{w}…")),
                    "{max}: {fitted:?} cuts {w:?}"
                );
            }
        }
    }
}
