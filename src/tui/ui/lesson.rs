//! The lesson pane: the README beside the scene, or the exercises with the answers given and
//! their verdicts; the rows come from the lesson panel (markdown.rs, state/exercises.rs).

use ratatui::layout::{Alignment, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;
use ratatui::Frame;

use super::{inner, pane, position_note, scroll_window, themed};
use crate::tui::app::{App, Focus};
use crate::tui::markdown::{markdown, overhang, window, Md};
use crate::tui::state::exercises::{self, ExKind, ExRow};
use crate::tui::state::lesson::{LessonPanel, LessonView};
use crate::tui::wrap::width as cells;

pub fn draw(f: &mut Frame, app: &App, area: Rect) {
    let Some(l) = &app.lesson else { return };
    match l.view {
        LessonView::Readme => readme(f, app, l, area),
        LessonView::Exercises => exercises(f, app, l, area),
    }
}

fn readme(f: &mut Frame, app: &App, l: &LessonPanel, area: Rect) {
    let width = (inner(area).width as usize).max(10);
    let rows = markdown(&l.lesson.readme, width);
    // A wider pane (or a README changed on disk) may need less of a shift than was asked.
    let pan = (l.pan as usize).min(overhang(&rows, width));
    let lines: Vec<Line> = rows
        .iter()
        .map(|row| {
            Line::from(
                window(row, pan, width)
                    .into_iter()
                    .map(|(text, kind)| Span::styled(text, themed(app, md_style(kind))))
                    .collect::<Vec<_>>(),
            )
        })
        .collect();
    let total = lines.len();
    let (shown, start) = scroll_window(&lines, l.scroll, inner(area).height);
    // A figure on screen is cut: say how to see the rest.
    let cut = overhang(&rows[start..start + shown.len()], width) > 0;
    let title = format!(
        " {} · {} · README (r closes, a: exercises) ",
        l.lesson.id, l.lesson.title
    );
    let mut block = pane(app, &title, area, Some(Focus::Lesson));
    let note = position_note(start, shown.len(), total);
    if cut {
        let keys = if app.focus == Focus::Lesson {
            " ← →: the figures sideways "
        } else {
            " Tab, ← →: the figures sideways "
        };
        let room = (area.width as usize).saturating_sub(note.as_ref().map_or(0, |n| cells(n)) + 3);
        if let Some(keys) = [keys, " ← → "].into_iter().find(|k| cells(k) <= room) {
            block = block.title_bottom(Line::from(keys).alignment(Alignment::Left));
        }
    }
    if let Some(note) = note {
        block = block.title_bottom(Line::from(note).alignment(Alignment::Right));
    }
    f.render_widget(Paragraph::new(shown).block(block), area);
}

/// How each kind of README text is drawn.
fn md_style(kind: Md) -> Style {
    match kind {
        Md::Heading => Style::new().add_modifier(Modifier::BOLD).fg(Color::Yellow),
        Md::Code | Md::Figure | Md::InlineCode => Style::new().fg(Color::Green),
        Md::Answer | Md::Strong => Style::new().add_modifier(Modifier::BOLD),
        Md::Emphasis => Style::new().add_modifier(Modifier::ITALIC),
        Md::Link => Style::new()
            .fg(Color::Cyan)
            .add_modifier(Modifier::UNDERLINED),
        Md::Rule => Style::new().fg(Color::DarkGray),
        Md::Text => Style::new(),
    }
}

fn exercises(f: &mut Frame, app: &App, l: &LessonPanel, area: Rect) {
    let view = exercises::view(l, inner(area));
    let title = format!(" {} · exercises (Enter answer · w worked) ", l.lesson.id);
    let (text, start) = scroll_window(&view.text, l.exercise_scroll, view.room as u16);
    let mut block = pane(app, &title, area, Some(Focus::Lesson));
    let width = (area.width as usize).saturating_sub(2);
    if let Some(note) = view.footer(l.exercise, start, text.len(), width) {
        block = block.title_bottom(Line::from(note).alignment(Alignment::Right));
    }
    let rows = view.head.into_iter().chain(text).chain(view.foot);
    let shown = exercise_lines(app, rows.collect());
    f.render_widget(Paragraph::new(shown).block(block), area);
}

fn exercise_lines(app: &App, rows: Vec<ExRow>) -> Vec<Line<'static>> {
    let dim = Style::new().fg(Color::DarkGray);
    rows.into_iter()
        .map(|row| match row.kind {
            ExKind::Item { selected: true } => Line::styled(
                row.text,
                themed(
                    app,
                    Style::new().add_modifier(Modifier::BOLD).bg(Color::Blue),
                ),
            ),
            ExKind::Item { selected: false } => Line::styled(row.text, themed(app, Style::new())),
            ExKind::Rule | ExKind::Dim => Line::styled(row.text, themed(app, dim)),
            ExKind::Text => Line::from(row.text),
            ExKind::Given => Line::from(vec![
                Span::raw("your answer: "),
                Span::styled(row.text, Style::new().add_modifier(Modifier::BOLD)),
            ]),
            ExKind::Good => Line::styled(row.text, themed(app, Style::new().fg(Color::Green))),
            ExKind::Bad => Line::styled(row.text, themed(app, Style::new().fg(Color::Red))),
            ExKind::Heading => Line::styled(
                row.text,
                themed(app, Style::new().add_modifier(Modifier::BOLD)),
            ),
        })
        .collect()
}
