//! The help overlay: every key.

use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, Clear, Paragraph};
use ratatui::Frame;

use super::themed;
use crate::tui::app::{App, Screen};

/// (keys, what they do); a key of "" starts a section named by the description.
pub const KEYS: &[(&str, &str)] = &[
    ("", "pick a pixel"),
    ("←↓↑→ hjkl", "move the picked pixel (preview focused)"),
    ("shift+arrows HJKL", "move 10 pixels"),
    ("g", "go to pixel: type x,y then Enter"),
    ("mouse", "click the preview to pick, the tree to select"),
    ("", "ray tree"),
    ("Tab shift+Tab", "focus preview → tree → panels"),
    ("↑↓ jk", "select a ray (tree focused); scroll a panel"),
    ("→ l  ← h", "open / close a ray (or go to child / parent)"),
    ("Enter space", "open or close the selected ray"),
    ("e", "open every ray / close all"),
    ("+ - ] [", "raise / lower the maximum depth"),
    ("n p", "step levels: next / previous (partial I)"),
    ("", "panels"),
    ("c C", "CSG segment lists of the rays (C: every object)"),
    (
        "d v b m < >",
        "rays drawn · view · BVH boxes · hit marks · zoom",
    ),
    ("r s o", "lesson README · its next scene · lesson list"),
    ("a", "lesson exercises: ↑↓ choose, Enter answer"),
    ("w", "the selected exercise's worked solution"),
    (
        "PgUp PgDn ← →",
        "scroll the panel · ← →: a README's figures sideways",
    ),
    ("Esc", "back: out of the exercises, close a panel, quit"),
    ("? q ^Z", "this help · quit · stop until fg"),
];

/// The lesson list's keys.
pub const LIST_KEYS: &[(&str, &str)] = &[
    ("", "lesson list"),
    ("↑↓ jk PgUp PgDn", "choose a lesson"),
    ("Enter → l", "open it"),
    ("Esc", "back to the scene shown before (else quit)"),
    ("? q", "this help · quit"),
];

pub fn draw(f: &mut Frame, app: &App, area: Rect) {
    let keys = if app.screen == Screen::Lessons {
        LIST_KEYS
    } else {
        KEYS
    };
    let key_w = keys
        .iter()
        .map(|(k, _)| k.chars().count())
        .max()
        .unwrap_or(0)
        + 2;
    let mut lines: Vec<Line> = Vec::new();
    for (k, what) in keys {
        if k.is_empty() {
            lines.push(Line::styled(
                what.to_uppercase(),
                themed(
                    app,
                    Style::new().fg(Color::Yellow).add_modifier(Modifier::BOLD),
                ),
            ));
        } else {
            lines.push(Line::from(vec![
                Span::styled(
                    format!("  {k:<key_w$}"),
                    themed(app, Style::new().fg(Color::Cyan)),
                ),
                Span::raw(*what),
            ]));
        }
    }
    let content_w = lines.iter().map(|l| l.width()).max().unwrap_or(0) as u16;
    let w = (content_w + 4)
        .min(area.width.saturating_sub(2))
        .max(20.min(area.width));
    // Too few rows for every key: the last row says how many are left out.
    let rows = area.height.saturating_sub(2) as usize;
    if lines.len() > rows && rows > 0 {
        let left_out = lines.len() - (rows - 1);
        lines.truncate(rows - 1);
        lines.push(Line::styled(
            format!("… {left_out} more rows: a taller terminal shows every key"),
            themed(app, Style::new().fg(Color::DarkGray)),
        ));
    }
    let h = (lines.len() as u16 + 2).min(area.height);
    let r = Rect::new(
        area.x + (area.width - w) / 2,
        area.y + (area.height - h) / 2,
        w,
        h,
    );
    f.render_widget(Clear, r);
    let block = Block::bordered()
        .title(" keys (any key closes, q quits) ")
        .border_style(themed(app, Style::new().fg(Color::Cyan)));
    f.render_widget(Paragraph::new(lines).block(block), r);
}
