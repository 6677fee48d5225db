//! What the exercises view says: the list of exercises (fixed at the top) and the selected
//! exercise's question, the answer given and its verdict, the worked solution (scrolled), as
//! rows at the pane's width tagged with how they are drawn.

use ratatui::layout::Rect;

use super::lesson::LessonPanel;
use crate::lessons::{Ask, Exercise};
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

/// The exercises view laid out in a `body` area: the list at the top, the selected exercise's
/// text scrolled below it, and, where that text would push it out of sight, the prompt (how
/// to answer, or the answer given and its verdict) pinned at the bottom. Drawing and the
/// scroll limit both read it, so they agree.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ExView {
    /// The list (or the part of it around the selected exercise) and the rule under it.
    pub head: Vec<ExRow>,
    /// The text scrolled in `room` rows under the head.
    pub text: Vec<ExRow>,
    /// The prompt's rows pinned under the text; empty where the text holds the prompt.
    pub foot: Vec<ExRow>,
    /// How many rows the text has.
    pub room: usize,
    /// How many exercises the list shows, of how many.
    pub listed: (usize, usize),
}

/// The exercises view in a `body` area. The prompt is the last thing a small pane gives up:
/// where the list, the question and the prompt do not all fit, the prompt is pinned at the
/// bottom, the list shrinks to the selected exercise, and the rule and the text go first; a
/// long verdict gives up its last rows before the selected exercise's row.
pub fn view(l: &LessonPanel, body: Rect) -> ExView {
    let (width, height) = (body.width as usize, body.height as usize);
    let exs = &l.lesson.exercises;
    let full_list = exs.len().min((height / 3).max(3));
    let (question, prompt) = match exs.get(l.exercise) {
        Some(ex) => (question_rows(ex, width), prompt_rows(l, ex, width)),
        None => (vec![], vec![]),
    };
    let work = work_rows(l, width);
    let (list_h, rule, text, foot) = if full_list + 1 + question.len() + prompt.len() <= height {
        let text = question.into_iter().chain(prompt).chain(work).collect();
        (full_list, true, text, vec![])
    } else {
        // All of the prompt but for a row kept for the selected exercise, where there are two.
        let foot_h = if height >= 2 { height - 1 } else { height };
        let foot: Vec<ExRow> = prompt.into_iter().take(foot_h).collect();
        let rest = height - foot.len();
        // The selected exercise, then the rest of the list once two rows of text fit below.
        let list_h = full_list.min(rest.saturating_sub(3)).max(1).min(rest);
        let rule = rest >= list_h + 2;
        (
            list_h,
            rule,
            question.into_iter().chain(work).collect(),
            foot,
        )
    };
    let mut head = list_rows(l, width, list_h);
    let listed = head.len();
    if rule {
        head.push(row("─".repeat(width), ExKind::Rule));
    }
    let room = height.saturating_sub(head.len() + foot.len());
    ExView {
        head,
        text,
        foot,
        room,
        listed: (listed, exs.len()),
    }
}

impl ExView {
    /// The pane's footer, for the text scrolled to `start` with `shown` rows on screen, in
    /// `cells` cells: which exercise of how many where the list does not show them all, and
    /// which lines of the text where it does not fit; shorter forms where the long one does not
    /// fit, none where nothing does or nothing is hidden.
    pub fn footer(
        &self,
        exercise: usize,
        start: usize,
        shown: usize,
        cells: usize,
    ) -> Option<String> {
        let (listed, count) = self.listed;
        let total = self.text.len();
        let list_cut = listed < count;
        let text_cut = shown > 0 && total > shown;
        let (e, a, b) = (exercise + 1, start + 1, start + shown);
        let forms = match (list_cut, text_cut) {
            (false, false) => return None,
            (true, false) => vec![format!("exercise {e} of {count}"), format!("{e}/{count}")],
            (false, true) => vec![
                format!("lines {a}–{b} of {total}"),
                format!("{a}–{b}/{total}"),
            ],
            (true, true) => vec![
                format!("exercise {e} of {count} · lines {a}–{b} of {total}"),
                format!("{e}/{count} · {a}–{b}/{total}"),
                format!("{e}/{count}"),
            ],
        };
        forms
            .into_iter()
            .map(|f| format!(" {f} "))
            .find(|f| width(f) <= cells)
    }
}

/// The list's rows, `list_h` of them around the selected exercise.
fn list_rows(l: &LessonPanel, width: usize, list_h: usize) -> Vec<ExRow> {
    let exs = &l.lesson.exercises;
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
    head
}

/// The question, what it asks about, and a blank row.
fn question_rows(ex: &Exercise, width: usize) -> Vec<ExRow> {
    let mut rows = Vec::new();
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
    rows
}

/// The prompt: the answer given and its verdict, or how to answer.
fn prompt_rows(l: &LessonPanel, ex: &Exercise, width: usize) -> Vec<ExRow> {
    let mut rows = Vec::new();
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
    rows
}

/// The worked solution, when shown.
fn work_rows(l: &LessonPanel, width: usize) -> Vec<ExRow> {
    let mut rows = Vec::new();
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
    rows
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

#[cfg(test)]
mod tests {
    use super::*;

    fn view_of(listed: (usize, usize), text: usize) -> ExView {
        ExView {
            head: vec![],
            text: vec![row("", ExKind::Text); text],
            foot: vec![],
            room: 0,
            listed,
        }
    }

    /// The footer names the exercise where the list is cut and the lines where the text is,
    /// in the longest form that fits, and never a range of no lines.
    #[test]
    fn the_footer_says_what_is_hidden_in_the_room_it_has() {
        let cut = view_of((1, 9), 8);
        let footer = |v: &ExView, e, start, shown, cells| v.footer(e, start, shown, cells);
        assert_eq!(
            footer(&cut, 0, 0, 3, 38).as_deref(),
            Some(" exercise 1 of 9 · lines 1–3 of 8 ")
        );
        assert_eq!(footer(&cut, 0, 0, 3, 20).as_deref(), Some(" 1/9 · 1–3/8 "));
        assert_eq!(footer(&cut, 0, 0, 3, 10).as_deref(), Some(" 1/9 "));
        assert_eq!(footer(&cut, 0, 0, 3, 4), None);
        assert_eq!(
            footer(&cut, 4, 0, 0, 38).as_deref(),
            Some(" exercise 5 of 9 ")
        );
        let listed = view_of((9, 9), 8);
        assert_eq!(footer(&listed, 0, 0, 8, 38), None);
        assert_eq!(
            footer(&listed, 0, 2, 3, 38).as_deref(),
            Some(" lines 3–5 of 8 ")
        );
    }
}
