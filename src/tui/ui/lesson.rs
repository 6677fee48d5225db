//! The lesson pane: the README beside the scene, or the exercises with the answers given and
//! their verdicts.

use ratatui::layout::{Alignment, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;
use ratatui::Frame;

use super::{inner, pane, position_note, scroll_window, themed, wrap, wrap_hang};
use crate::lessons::Ask;
use crate::tui::app::{list_offset, App, Focus, LessonPanel, LessonView};

pub fn draw(f: &mut Frame, app: &App, area: Rect) {
    let Some(l) = &app.lesson else { return };
    match l.view {
        LessonView::Readme => readme(f, app, l, area),
        LessonView::Exercises => exercises(f, app, l, area),
    }
}

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

fn readme(f: &mut Frame, app: &App, l: &LessonPanel, area: Rect) {
    let width = inner(area).width as usize;
    let lines: Vec<Line> = markdown(&l.lesson.readme, width.max(10))
        .into_iter()
        .map(|(text, kind)| {
            let style = match kind {
                Md::Heading => Style::new().add_modifier(Modifier::BOLD).fg(Color::Yellow),
                Md::Code => Style::new().fg(Color::Green),
                Md::Answer => Style::new().add_modifier(Modifier::BOLD),
                Md::Text => Style::new(),
            };
            Line::styled(text, themed(app, style))
        })
        .collect();
    let total = lines.len();
    let (shown, start) = scroll_window(&lines, l.scroll, inner(area).height);
    let title = format!(
        " {} · {} · README (r closes, a: exercises) ",
        l.lesson.id, l.lesson.title
    );
    let mut block = pane(app, title, Some(Focus::Lesson));
    if let Some(note) = position_note(start, shown.len(), total) {
        block = block.title_bottom(Line::from(note).alignment(Alignment::Right));
    }
    f.render_widget(Paragraph::new(shown).block(block), area);
}

/// The exercises view's lines in a `body` area: the list (fixed) and the selected
/// exercise's text (scrolled).
pub fn exercise_lines(
    app: &App,
    l: &LessonPanel,
    body: Rect,
) -> (Vec<Line<'static>>, Vec<Line<'static>>) {
    let width = body.width as usize;
    let exs = &l.lesson.exercises;
    let list_h = exs.len().min((body.height as usize / 3).max(3));
    let off = list_offset(l.exercise, list_h);
    let mut lines: Vec<Line> = Vec::new();
    for (i, ex) in exs.iter().enumerate().skip(off).take(list_h) {
        let mark = match &l.answers[i] {
            Some(a) => match &a.result {
                Ok(v) if v.correct => "✓",
                Ok(_) => "✗",
                Err(_) => "?",
            },
            None => " ",
        };
        let sel = i == l.exercise;
        let text = format!(
            "{}{} {}  {}",
            if sel { "▶" } else { " " },
            mark,
            ex.id,
            first_words(&ex.question, width.saturating_sub(ex.id.len() + 6))
        );
        let style = if sel {
            Style::new().add_modifier(Modifier::BOLD).bg(Color::Blue)
        } else {
            Style::new()
        };
        lines.push(Line::styled(text, themed(app, style)));
    }
    lines.push(Line::styled(
        "─".repeat(width),
        themed(app, Style::new().fg(Color::DarkGray)),
    ));
    // The list stays; the selected exercise's text below it scrolls.
    let head = std::mem::take(&mut lines);
    if let Some(ex) = exs.get(l.exercise) {
        let question = ex.question.split_whitespace().collect::<Vec<_>>().join(" ");
        for part in wrap_hang(&format!("{}: {question}", ex.id), width, "") {
            lines.push(Line::from(part));
        }
        let mut about = format!("ask: {}", snake_case(&format!("{:?}", ex.ask)));
        if let Some([x, y]) = ex.pixel {
            about.push_str(&format!(" · pixel {x},{y}"));
        }
        if !ex.node.is_empty() {
            about.push_str(&format!(" · node {}", ex.node));
        }
        if let Some(s) = &ex.scene {
            about.push_str(&format!(" · scene {s}"));
        }
        if let Some(r) = &ex.ray {
            about.push_str(&format!(
                " · ray {} → {}",
                crate::trace::text::vec3(r.origin),
                crate::trace::text::vec3(r.direction)
            ));
        }
        if let Some(light) = &ex.light {
            about.push_str(&format!(" · light {light}"));
        }
        if let Some(object) = &ex.object {
            about.push_str(&format!(" · object {object}"));
        }
        about.push_str(&format!(
            " · tolerance {}",
            crate::trace::text::num(ex.tolerance)
        ));
        for part in wrap(&about, width) {
            lines.push(Line::styled(
                part,
                themed(app, Style::new().fg(Color::DarkGray)),
            ));
        }
        if let Some(a) = &l.answers[l.exercise] {
            lines.push(Line::from(""));
            lines.push(Line::from(vec![
                Span::raw("your answer: "),
                Span::styled(a.given.clone(), Style::new().add_modifier(Modifier::BOLD)),
            ]));
            let (text, color) = match &a.result {
                Ok(v) => (
                    v.message(),
                    if v.correct { Color::Green } else { Color::Red },
                ),
                Err(e) => (e.clone(), Color::Red),
            };
            for t in text.lines() {
                for part in wrap(t, width) {
                    lines.push(Line::styled(part, themed(app, Style::new().fg(color))));
                }
            }
        } else {
            lines.push(Line::from(""));
            let how = format!("Enter: answer as {}", answer_format(ex.ask));
            for part in wrap_hang(&how, width, "") {
                lines.push(Line::styled(
                    part,
                    themed(app, Style::new().fg(Color::DarkGray)),
                ));
            }
        }
    }
    match &l.work {
        Some(Ok(work)) => {
            lines.push(Line::from(""));
            lines.push(Line::styled(
                "worked solution (w hides):",
                themed(app, Style::new().add_modifier(Modifier::BOLD)),
            ));
            for t in work {
                for part in wrap(t, width) {
                    lines.push(Line::from(part));
                }
            }
        }
        Some(Err(e)) => {
            for part in wrap(e, width) {
                lines.push(Line::styled(part, themed(app, Style::new().fg(Color::Red))));
            }
        }
        None => {}
    }
    (head, lines)
}

fn exercises(f: &mut Frame, app: &App, l: &LessonPanel, area: Rect) {
    let body = inner(area);
    let (head, lines) = exercise_lines(app, l, body);
    let title = format!(" {} · exercises (Enter answer · w worked) ", l.lesson.id);
    let room = body.height.saturating_sub(head.len() as u16);
    let total = lines.len();
    let (rest, start) = scroll_window(&lines, l.exercise_scroll, room);
    let mut block = pane(app, title, Some(Focus::Lesson));
    if let Some(note) = position_note(start, rest.len(), total) {
        block = block.title_bottom(Line::from(note).alignment(Alignment::Right));
    }
    let shown: Vec<Line> = head.into_iter().chain(rest).collect();
    f.render_widget(Paragraph::new(shown).block(block), area);
}

/// The start of a text, cut at a word boundary to fit `max` cells.
fn first_words(s: &str, max: usize) -> String {
    let s = s.split_whitespace().collect::<Vec<_>>().join(" ");
    if super::width(&s) <= max {
        return s;
    }
    let mut out = String::new();
    for w in s.split(' ') {
        if super::width(&out) + w.len() + 2 > max {
            break;
        }
        if !out.is_empty() {
            out.push(' ');
        }
        out.push_str(w);
    }
    out.push('…');
    out
}

/// "PixelValue" → "pixel_value", as exercises.yaml spells it.
fn snake_case(name: &str) -> String {
    let mut out = String::new();
    for (i, c) in name.chars().enumerate() {
        if c.is_uppercase() && i > 0 {
            out.push('_');
        }
        out.push(c.to_ascii_lowercase());
    }
    out
}

/// How an answer to this kind of question is typed.
pub fn answer_format(ask: Ask) -> &'static str {
    match ask {
        Ask::Segments => "t_in, t_out; t_in, t_out … (or none)",
        Ask::Intensity | Ask::Local | Ask::Diffuse | Ask::Specular | Ask::PixelValue => {
            "a number (or r, g, b for a colour)"
        }
        Ask::HitT | Ask::ShadowFactor => "a number",
        Ask::PrimaryRays | Ask::SquaresSplit => "a whole number",
        Ask::RefractedDirection => "x, y, z (or tir for total internal reflection)",
        Ask::WindowPoint
        | Ask::RayDirection
        | Ask::RayOrigin
        | Ask::HitPoint
        | Ask::Normal
        | Ask::ReflectedDirection => "x, y, z",
        Ask::Barycentric => "λ1, λ2, λ3",
    }
}
