//! The CSG pane: the CSG panel's rows (state/csg.rs), pruned nodes greyed, the selected ray's
//! section marked.

use ratatui::layout::{Alignment, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;
use ratatui::Frame;

use super::{inner, pane, position_note, scroll_window, themed};
use crate::tui::app::{App, Focus};
use crate::tui::state::csg::CsgKind;

/// The CSG pane's lines at a width.
pub fn lines(app: &App, width: usize) -> Vec<Line<'static>> {
    let (rows, _) = app.csg.rows(app.tree.selected(), width);
    rows.into_iter()
        .map(|row| {
            let style = match row.kind {
                CsgKind::Header => Style::new().add_modifier(Modifier::BOLD).fg(Color::Yellow),
                CsgKind::Pruned => Style::new()
                    .fg(Color::DarkGray)
                    .add_modifier(Modifier::ITALIC),
                CsgKind::Plain => Style::new(),
            };
            let mark = if row.marked { "▶ " } else { "  " };
            Line::from(vec![
                Span::raw(mark),
                Span::styled(row.text, themed(app, style)),
            ])
        })
        .collect()
}

pub fn draw(f: &mut Frame, app: &App, area: Rect) {
    let lines = lines(app, inner(area).width as usize);
    let total = lines.len();
    let (shown, start) = scroll_window(&lines, app.csg.scroll(), inner(area).height);
    let title = if app.csg.all() {
        " CSG segment lists [t_in, t_out] · every object · C: met only · c closes "
    } else {
        " CSG segment lists [t_in, t_out] · C: every object · c closes "
    };
    let mut block = pane(app, title, area, Some(Focus::Lower));
    if let Some(note) = position_note(start, shown.len(), total) {
        block = block.title_bottom(Line::from(note).alignment(Alignment::Right));
    }
    f.render_widget(Paragraph::new(shown).block(block), area);
}
