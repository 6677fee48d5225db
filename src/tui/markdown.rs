//! A lesson README reflowed to a pane's width, each row tagged with how it is drawn. The
//! lesson panel scrolls through these rows and the drawing code styles them.

use super::wrap::wrap_hang;

/// How a README line is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Md {
    Heading,
    Code,
    Text,
    Answer,
}

/// A README reflowed to `width` cells: paragraphs, list items and quotes re-wrapped, code
/// blocks and tables kept line for line, `**` markers dropped.
pub fn markdown(text: &str, width: usize) -> Vec<(String, Md)> {
    struct Para {
        first: String,
        hang: String,
        text: String,
        quote: bool,
    }
    let mut out: Vec<(String, Md)> = Vec::new();
    let mut para: Option<Para> = None;
    let flush = |para: &mut Option<Para>, out: &mut Vec<(String, Md)>| {
        if let Some(p) = para.take() {
            let kind = if p.text.starts_with("Answer (") {
                Md::Answer
            } else {
                Md::Text
            };
            for l in wrap_hang(&format!("{}{}", p.first, p.text), width, &p.hang) {
                out.push((l, kind));
            }
        }
    };
    let mut in_code = false;
    for raw in text.lines() {
        let line = raw.trim_end().replace("**", "");
        if line.trim_start().starts_with("```") {
            flush(&mut para, &mut out);
            in_code = !in_code;
            continue;
        }
        if in_code {
            out.push((line, Md::Code));
            continue;
        }
        let body = line.trim_start();
        let indent = &line[..line.len() - body.len()];
        if body.is_empty() {
            flush(&mut para, &mut out);
            out.push((String::new(), Md::Text));
            continue;
        }
        if body.starts_with('#') {
            flush(&mut para, &mut out);
            let h = body.trim_start_matches('#').trim_start();
            for l in wrap_hang(h, width, "") {
                out.push((l, Md::Heading));
            }
            continue;
        }
        if body.starts_with('|') {
            flush(&mut para, &mut out);
            for l in wrap_hang(&line, width, "    ") {
                out.push((l, Md::Text));
            }
            continue;
        }
        let numbered = body
            .split_once(". ")
            .is_some_and(|(n, _)| !n.is_empty() && n.chars().all(|c| c.is_ascii_digit()));
        let marker = if ["* ", "- ", "+ "].iter().any(|m| body.starts_with(m)) {
            Some(2)
        } else if numbered {
            body.find(". ").map(|i| i + 2)
        } else {
            None
        };
        if let Some(m) = marker {
            flush(&mut para, &mut out);
            para = Some(Para {
                first: format!("{indent}{}", &body[..m]),
                hang: " ".repeat(indent.len() + m),
                text: body[m..].to_string(),
                quote: false,
            });
            continue;
        }
        if let Some(q) = body.strip_prefix('>') {
            let q = q.trim_start();
            match &mut para {
                Some(p) if p.quote => {
                    p.text.push(' ');
                    p.text.push_str(q);
                }
                _ => {
                    flush(&mut para, &mut out);
                    para = Some(Para {
                        first: "│ ".into(),
                        hang: "│ ".into(),
                        text: q.to_string(),
                        quote: true,
                    });
                }
            }
            continue;
        }
        match &mut para {
            Some(p) if !p.quote => {
                p.text.push(' ');
                p.text.push_str(body);
            }
            _ => {
                flush(&mut para, &mut out);
                para = Some(Para {
                    first: indent.to_string(),
                    hang: indent.to_string(),
                    text: body.to_string(),
                    quote: false,
                });
            }
        }
    }
    flush(&mut para, &mut out);
    out
}
