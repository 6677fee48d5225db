//! The lesson pane: the README beside the scene, or the exercises with the answers given and
//! their verdicts.

use ratatui::layout::{Alignment, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;
use ratatui::Frame;

use super::{inner, pane, position_note, scroll_window, themed, wrap};
use crate::tui::app::{list_offset, App, Focus, LessonPanel, LessonView};

pub fn draw(f: &mut Frame, app: &App, area: Rect) {
    let Some(l) = &app.lesson else { return };
    match l.view {
        LessonView::Readme => readme(f, app, l, area),
        LessonView::Exercises => exercises(f, app, l, area),
    }
}

fn readme(f: &mut Frame, app: &App, l: &LessonPanel, area: Rect) {
    let width = inner(area).width as usize;
    let mut lines: Vec<Line> = Vec::new();
    let mut in_code = false;
    for raw in l.lesson.readme.lines() {
        if raw.trim_start().starts_with("```") {
            in_code = !in_code;
            continue;
        }
        let style = if in_code {
            Style::new().fg(Color::Green)
        } else if raw.starts_with('#') {
            Style::new().add_modifier(Modifier::BOLD).fg(Color::Yellow)
        } else if raw.trim_start().starts_with("**Answer") {
            Style::new().add_modifier(Modifier::BOLD)
        } else {
            Style::new()
        };
        let text = if in_code {
            raw.to_string()
        } else {
            raw.trim_start_matches('#').trim_start().to_string()
        };
        let text = if raw.starts_with('#') {
            text.to_uppercase()
        } else {
            text
        };
        if text.is_empty() {
            lines.push(Line::from(""));
            continue;
        }
        for part in wrap(&text, width.max(10)) {
            lines.push(Line::styled(part, themed(app, style)));
        }
    }
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

fn exercises(f: &mut Frame, app: &App, l: &LessonPanel, area: Rect) {
    let body = inner(area);
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
    if let Some(ex) = exs.get(l.exercise) {
        for part in wrap(&format!("{}: {}", ex.id, ex.question.trim()), width) {
            lines.push(Line::from(part));
        }
        let mut about = format!("ask: {:?}", ex.ask).to_lowercase();
        if let Some([x, y]) = ex.pixel {
            about.push_str(&format!(" · pixel {x},{y}"));
        }
        if !ex.node.is_empty() {
            about.push_str(&format!(" · node {}", ex.node));
        }
        if let Some(s) = &ex.scene {
            about.push_str(&format!(" · scene {s}"));
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
            lines.push(Line::styled(
                "Enter: type your answer (a number, x, y, z, or t_in, t_out; …)",
                themed(app, Style::new().fg(Color::DarkGray)),
            ));
        }
    }
    let title = format!(
        " {} · exercises (↑↓ choose · Enter answer · Esc back) ",
        l.lesson.id
    );
    let (shown, _) = scroll_window(&lines, 0, body.height);
    f.render_widget(
        Paragraph::new(shown).block(pane(app, title, Some(Focus::Lesson))),
        area,
    );
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
