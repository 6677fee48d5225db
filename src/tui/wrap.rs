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
