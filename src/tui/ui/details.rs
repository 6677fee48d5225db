//! The node details pane: the selected ray's details (state/details.rs), styled.

use ratatui::layout::{Alignment, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;
use ratatui::Frame;

use super::{inner, pane, position_note, scroll_window, swatch, themed};
use crate::tui::app::{App, Focus};
use crate::tui::state::details::DetailKind;
use crate::tui::tree;

/// The details pane's lines at a width (wrapped, styled).
pub fn lines(app: &App, width: usize) -> Vec<Line<'static>> {
    app.tree
        .detail_rows(width)
        .into_iter()
        .map(|row| {
            let style = match row.kind {
                DetailKind::Title | DetailKind::Sum => Style::new().add_modifier(Modifier::BOLD),
                DetailKind::Formula => Style::new().fg(Color::Yellow),
                DetailKind::Plain => Style::new(),
            };
            let mut spans = vec![Span::styled(row.text, themed(app, style))];
            if let Some(c) = row.swatch {
                spans.push(Span::raw(" "));
                spans.push(swatch(app, c));
            }
            Line::from(spans)
        })
        .collect()
}

pub fn draw(f: &mut Frame, app: &App, area: Rect) {
    let Some(root) = app.tree.shown_tree() else {
        f.render_widget(pane(app, " details ", area, Some(Focus::Lower)), area);
        return;
    };
    let at = tree::kinds_of_path(root, app.tree.selected());
    let title = if at.is_empty() {
        " details · primary ray ".to_string()
    } else {
        format!(" details · {at} ")
    };
    let lines = lines(app, inner(area).width as usize);
    let h = inner(area).height;
    let total = lines.len();
    let (shown, start) = scroll_window(&lines, app.tree.details_scroll(), h);
    let mut block = pane(app, &title, area, Some(Focus::Lower));
    if let Some(note) = position_note(start, shown.len(), total) {
        block = block.title_bottom(Line::from(note).alignment(Alignment::Right));
    }
    f.render_widget(Paragraph::new(shown).block(block), area);
}
