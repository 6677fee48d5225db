//! What the exercises view says: the list of exercises (fixed at the top) and the selected
//! exercise's question, the answer given and its verdict, the worked solution (scrolled), as
//! rows at the pane's width tagged with how they are drawn.

use ratatui::layout::Rect;

use super::lesson::LessonPanel;
use crate::lessons::Ask;
use crate::trace::text::vec3;
use crate::tui::layout::list_offset;
use crate::tui::wrap::{width, wrap, wrap_hang};

/// How a row of the exercises view is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExKind {
    /// An exercise of the list; `selected` is the one the text below is about.
    Item {
        selected: bool,
    },
    /// The line under the list.
    Rule,
    Text,
    /// What the exercise asks and how to answer: secondary.
    Dim,
    /// The answer given (the row holds the answer alone).
    Given,
    /// A right verdict.
    Good,
    /// A wrong verdict, or an error.
    Bad,
    Heading,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ExRow {
    pub text: String,
    pub kind: ExKind,
}

fn row(text: impl Into<String>, kind: ExKind) -> ExRow {
    ExRow {
        text: text.into(),
        kind,
    }
}

/// The exercises view's rows in a `body` area: the list (fixed) and the selected exercise's
/// text (scrolled).
pub fn rows(l: &LessonPanel, body: Rect) -> (Vec<ExRow>, Vec<ExRow>) {
    let width = body.width as usize;
    let exs = &l.lesson.exercises;
    let list_h = exs.len().min((body.height as usize / 3).max(3));
    let off = list_offset(l.exercise, list_h);
    let mut head = Vec::new();
    for (i, ex) in exs.iter().enumerate().skip(off).take(list_h) {
        let mark = match &l.answers[i] {
            Some(a) => match &a.result {
                Ok(v) if v.correct => "✓",
                Ok(_) => "✗",
                Err(_) => "?",
            },
            None if l.solved.contains(&ex.id) => "✓",
            None => " ",
        };
        let selected = i == l.exercise;
        let text = format!(
            "{}{} {}  {}",
            if selected { "▶" } else { " " },
            mark,
            ex.id,
            first_words(&ex.question, width.saturating_sub(ex.id.len() + 6))
        );
        head.push(row(text, ExKind::Item { selected }));
    }
    head.push(row("─".repeat(width), ExKind::Rule));
    let mut rows = Vec::new();
    if let Some(ex) = exs.get(l.exercise) {
        let question = ex.question.split_whitespace().collect::<Vec<_>>().join(" ");
        for part in wrap_hang(&format!("{}: {question}", ex.id), width, "") {
            rows.push(row(part, ExKind::Text));
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
                vec3(r.origin),
                vec3(r.direction)
            ));
        }
        if let Some(light) = &ex.light {
            about.push_str(&format!(" · light {light}"));
        }
        if let Some(object) = &ex.object {
            about.push_str(&format!(" · object {object}"));
        }
        about.push_str(&format!(" · tolerance {}", ex.tolerance.describe()));
        for part in wrap(&about, width) {
            rows.push(row(part, ExKind::Dim));
        }
        rows.push(row("", ExKind::Text));
        if let Some(a) = &l.answers[l.exercise] {
            rows.push(row(a.given.clone(), ExKind::Given));
            let (text, kind) = match &a.result {
                Ok(v) => (
                    v.message(),
                    if v.correct { ExKind::Good } else { ExKind::Bad },
                ),
                Err(e) => (e.to_string(), ExKind::Bad),
            };
            for t in text.lines() {
                for part in wrap(t, width) {
                    rows.push(row(part, kind));
                }
            }
        } else {
            let how = format!("Enter: answer as {}", answer_format(ex.ask));
            for part in wrap_hang(&how, width, "") {
                rows.push(row(part, ExKind::Dim));
            }
        }
    }
    match &l.work {
        Some(Ok(work)) => {
            rows.push(row("", ExKind::Text));
            rows.push(row("worked solution (w hides):", ExKind::Heading));
            for t in work {
                for part in wrap(t, width) {
                    rows.push(row(part, ExKind::Text));
                }
            }
        }
        Some(Err(e)) => {
            for part in wrap(&e.to_string(), width) {
                rows.push(row(part, ExKind::Bad));
            }
        }
        None => {}
    }
    (head, rows)
}

/// The start of a text, cut at a word boundary to fit `max` cells.
fn first_words(s: &str, max: usize) -> String {
    let s = s.split_whitespace().collect::<Vec<_>>().join(" ");
    if width(&s) <= max {
        return s;
    }
    let mut out = String::new();
    for w in s.split(' ') {
        if width(&out) + w.len() + 2 > max {
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
        Ask::Intensity
        | Ask::Local
        | Ask::Diffuse
        | Ask::Specular
        | Ask::PixelValue
        | Ask::SurfaceColor => "a number (or r, g, b for a colour)",
        Ask::HitT | Ask::ShadowFactor | Ask::U | Ask::V => "a number",
        Ask::PrimaryRays | Ask::SquaresSplit | Ask::LeavesEvaluated => "a whole number",
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
