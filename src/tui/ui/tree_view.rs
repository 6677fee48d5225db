//! The ray tree pane: one line per ray, with its kind, what it hit (or why it stopped), its
//! intensity and a swatch of that intensity.

use ratatui::layout::{Alignment, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::Paragraph;
use ratatui::Frame;

use super::{pane, position_note, swatch, themed};
use crate::trace::{text, RayKind, Termination};
use crate::tui::app::{App, Focus};
use crate::tui::tree::{self, intensity_text, label, short_color};
use crate::tui::wrap::{cut, width};

pub fn draw(f: &mut Frame, app: &App, area: Rect) {
    let t = &app.tree;
    let (x, y) = t.pixel();
    let at = match t.aimed_ray() {
        Some(r) => format!("ray {} → {}", text::point(r.origin), text::vec3(r.dir)),
        None => format!("pixel {x},{y}"),
    };
    let title = match t.level() {
        Some(k) => format!(" ray tree · {at} · level {k} of {} ", t.depth()),
        None => format!(" ray tree · {at} · {} ", t.depth_label()),
    };
    let Some(root) = t.shown_tree() else {
        f.render_widget(
            Paragraph::new("no scene").block(pane(app, &title, area, Some(Focus::Tree))),
            area,
        );
        return;
    };
    let rows = t.rows();
    let body = app.tree_body_height();
    let start = t.offset().min(rows.len());
    let shown = &rows[start..(start + body).min(rows.len())];
    let mut block = pane(app, &title, area, Some(Focus::Tree));
    if let Some(note) = position_note(start, shown.len(), rows.len()) {
        block = block.title_bottom(Line::from(note).alignment(Alignment::Right));
    }
    let mut lines: Vec<Line> = Vec::new();
    let yellow = themed(app, Style::new().fg(Color::Yellow));
    if let Some(p) = t.paths() {
        let estimate = if t.hidden() {
            vec![Span::styled("path traced: estimate ? ", yellow)]
        } else {
            vec![
                Span::styled(
                    format!("path traced: estimate {} ", short_color(p.estimate)),
                    yellow,
                ),
                swatch(app, p.estimate),
            ]
        };
        lines.push(Line::from(
            [estimate, vec![Span::raw(format!(" of {} paths", p.spp))]].concat(),
        ));
        for (k, (value, steps)) in p.shown.iter().enumerate() {
            let value = if t.hidden() {
                "?".to_string()
            } else {
                short_color(*value)
            };
            let head = format!(" path {}: {value} ", k + 1);
            let room = (area.width.saturating_sub(2) as usize).saturating_sub(width(&head));
            lines.push(Line::from(vec![
                Span::raw(head),
                Span::styled(
                    cut(&format!("eye → {steps}"), room),
                    themed(app, Style::new().fg(Color::DarkGray)),
                ),
            ]));
        }
        lines.push(Line::styled(
            "▼ Whitted reading of the centre ray, not the estimate:",
            yellow,
        ));
    }
    if let Some((value, how)) = t.pixel_value().filter(|_| !t.hidden()) {
        lines.push(Line::from(vec![
            Span::styled(
                format!("pixel = {} ", short_color(*value)),
                themed(app, Style::new().fg(Color::Yellow)),
            ),
            swatch(app, *value),
            Span::raw(format!(" {how}")),
        ]));
    }
    if let Some(k) = t.level() {
        let levels: Vec<String> = t
            .partials()
            .iter()
            .enumerate()
            .take(k as usize)
            .map(|(i, c)| {
                let c = if t.hidden() {
                    "?".to_string()
                } else {
                    short_color(*c)
                };
                format!("{}: {c}", i + 1)
            })
            .collect();
        let room = area.width.saturating_sub(2) as usize;
        lines.push(Line::from(vec![
            Span::styled("levels: ", themed(app, Style::new().fg(Color::Yellow))),
            Span::raw(latest_that_fit(&levels, room - room.min(width("levels: ")))),
        ]));
    }
    for row in shown {
        let n = tree::node_at(root, &row.path).expect("row of this tree");
        let selected = row.path == t.selected();
        let icon = match (row.has_children, row.open) {
            (true, true) => "▾ ",
            (true, false) => "▸ ",
            _ => "· ",
        };
        let mut spans = vec![
            Span::raw(if selected { "▶" } else { " " }),
            Span::styled(
                row.guides.clone(),
                themed(app, Style::new().fg(Color::DarkGray)),
            ),
            Span::raw(icon),
        ];
        let kind_color = match n.kind {
            RayKind::Primary => Color::White,
            RayKind::Shadow => Color::DarkGray,
            RayKind::Reflection => Color::Cyan,
            RayKind::Refraction => Color::Magenta,
        };
        let mut text = label(n);
        if n.terminated == Some(Termination::MaxDepth) && n.depth < t.depth() {
            // Cut by the level being stepped, not by the maximum depth.
            text = text.replace("not traced: max depth", "not yet revealed");
        }
        let value = if n.kind != RayKind::Shadow && t.hidden() {
            vec![Span::raw("  I = ?")]
        } else if let Some(i) = intensity_text(n) {
            vec![Span::raw(i), swatch(app, n.color)]
        } else {
            vec![]
        };
        // A row too long for the pane gives up its label's end, never its intensity.
        let room = (area.width as usize).saturating_sub(2);
        let taken = 1 + width(&row.guides) + width(icon);
        let value_width: usize = value.iter().map(Span::width).sum();
        let text = cut(&text, room.saturating_sub(taken + value_width));
        spans.push(Span::styled(text, themed(app, Style::new().fg(kind_color))));
        spans.extend(value);
        let mut line = Line::from(spans);
        if selected {
            let style = if app.focus == Focus::Tree {
                Style::new().bg(Color::Blue).add_modifier(Modifier::BOLD)
            } else {
                Style::new().add_modifier(Modifier::BOLD)
            };
            line = line.style(themed(app, style));
        }
        lines.push(line);
    }
    f.render_widget(Paragraph::new(lines).block(block), area);
}

/// The levels' partial intensities joined by " → " within `room` cells: the latest ones, the
/// level being stepped last, with "… → " in place of the earlier ones that do not fit.
fn latest_that_fit(levels: &[String], room: usize) -> String {
    let whole = levels.join(" → ");
    if width(&whole) <= room {
        return whole;
    }
    (1..levels.len())
        .map(|first| format!("… → {}", levels[first..].join(" → ")))
        .find(|line| width(line) <= room)
        .unwrap_or_else(|| cut(levels.last().map_or("", String::as_str), room))
}
