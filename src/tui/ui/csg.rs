//! The CSG pane: for every ray of the picked pixel's tree, the segment list at every node of
//! every object it meets, pruned nodes marked; the selected ray's section is marked.

use ratatui::layout::{Alignment, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;
use ratatui::Frame;

use super::{inner, pane, position_note, scroll_window, themed, wrap};
use crate::tui::app::{App, Focus};

/// The section of the CSG panel that belongs to the selected ray (or to the ray a shadow ray
/// leaves from).
fn section(app: &App) -> Vec<usize> {
    let mut section = app.selected.clone();
    while !section.is_empty() && !app.csg.iter().any(|l| l.header && l.node == section) {
        section.pop();
    }
    section
}

/// The CSG pane's lines at a width, and the row where the selected ray's section starts.
pub fn lines(app: &App, width: usize) -> (Vec<Line<'static>>, Option<usize>) {
    let section = section(app);
    let mut lines: Vec<Line> = Vec::new();
    let mut start = None;
    for l in &app.csg {
        let mine = l.node == section;
        if l.header && mine && start.is_none() {
            start = Some(lines.len());
        }
        let style = if l.header {
            Style::new().add_modifier(Modifier::BOLD).fg(Color::Yellow)
        } else if l.text.contains("pruned:") {
            Style::new()
                .fg(Color::DarkGray)
                .add_modifier(Modifier::ITALIC)
        } else {
            Style::new()
        };
        for (j, part) in wrap(&l.text, width.saturating_sub(2).max(10))
            .into_iter()
            .enumerate()
        {
            let mark = if l.header && mine && j == 0 {
                "▶ "
            } else {
                "  "
            };
            lines.push(Line::from(vec![
                Span::raw(mark),
                Span::styled(part, themed(app, style)),
            ]));
        }
    }
    if lines.is_empty() {
        lines.push(Line::from("  no rays"));
    }
    (lines, start)
}

pub fn draw(f: &mut Frame, app: &App, area: Rect) {
    let (lines, _) = lines(app, inner(area).width as usize);
    let total = lines.len();
    let (shown, start) = scroll_window(&lines, app.csg_scroll, inner(area).height);
    let mut block = pane(
        app,
        " CSG segment lists [t_in, t_out] (c closes) ",
        Some(Focus::Lower),
    );
    if let Some(note) = position_note(start, shown.len(), total) {
        block = block.title_bottom(Line::from(note).alignment(Alignment::Right));
    }
    f.render_widget(Paragraph::new(shown).block(block), area);
}
