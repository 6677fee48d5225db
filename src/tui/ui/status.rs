//! The status line (scene, image size, picked pixel, depth, render progress, rays) and the
//! message line below it (a prompt, a scene error, or the last message).

use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::Frame;

use super::themed;
use crate::tui::app::{App, Prompt, Tone};

/// 1234567 → "1,234,567".
pub fn grouped(n: u64) -> String {
    let s = n.to_string();
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

pub fn status_text(app: &App) -> String {
    let (w, h) = app.image_size();
    let (x, y) = app.cursor;
    let mut parts = vec![
        format!("{w}×{h}"),
        format!("pixel {x},{y}"),
        match app.level {
            Some(k) => format!("depth {} (level {k})", app.depth),
            None => format!("depth {}", app.depth),
        },
    ];
    let p = &app.preview;
    parts.push(if p.running {
        let (done, total) = p.rows;
        let pct = (100 * done).checked_div(total).unwrap_or(0);
        format!("rendering {pct}%")
    } else if p.image.is_some() {
        "preview 100%".into()
    } else {
        "preview —".into()
    });
    if let Some(s) = &p.stats {
        parts.push(format!("{} rays", grouped(s.rays())));
    }
    parts.push(format!("tree {} rays", grouped(app.tree_stats.rays())));
    let rest = parts.join(" │ ");
    let name = app.name();
    let room = (app.size.0 as usize).saturating_sub(rest.chars().count() + 4);
    let name = if name.chars().count() > room {
        let keep: String = name
            .chars()
            .rev()
            .take(room.saturating_sub(1))
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .collect();
        format!("…{keep}")
    } else {
        name
    };
    format!(" {name} │ {rest}")
}

pub fn draw(f: &mut Frame, app: &App, status: Rect, message: Rect) {
    let buf = f.buffer_mut();
    let bar = themed(app, Style::new().bg(Color::DarkGray).fg(Color::White));
    let bar = if app.color == crate::render::preview::ColorMode::Ascii {
        bar.add_modifier(Modifier::REVERSED)
    } else {
        bar
    };
    buf.set_style(status, bar);
    buf.set_stringn(
        status.x,
        status.y,
        status_text(app),
        status.width as usize,
        bar,
    );
    let line = match &app.prompt {
        Some(Prompt::Goto(s)) => Line::from(vec![
            Span::styled(
                "go to pixel x,y: ",
                themed(app, Style::new().fg(Color::Yellow)),
            ),
            Span::raw(format!("{s}▏")),
            Span::styled(
                "   (Enter go · Esc cancel)",
                themed(app, Style::new().fg(Color::DarkGray)),
            ),
        ]),
        Some(Prompt::Answer { exercise, text }) => {
            let id = app
                .lesson
                .as_ref()
                .and_then(|l| l.lesson.exercises.get(*exercise))
                .map_or("?", |e| e.id.as_str());
            Line::from(vec![
                Span::styled(
                    format!("answer to {id}: "),
                    themed(app, Style::new().fg(Color::Yellow)),
                ),
                Span::raw(format!("{text}▏")),
                Span::styled(
                    "   (Enter check · Esc cancel)",
                    themed(app, Style::new().fg(Color::DarkGray)),
                ),
            ])
        }
        None => match (&app.error, &app.message) {
            (Some(e), _) => Line::styled(
                format!("✗ {e} (showing the last good scene)"),
                themed(
                    app,
                    Style::new().fg(Color::Red).add_modifier(Modifier::BOLD),
                ),
            ),
            (None, Some((m, tone))) => {
                let c = match tone {
                    Tone::Info => Color::Gray,
                    Tone::Good => Color::Green,
                    Tone::Bad => Color::Red,
                };
                Line::styled(m.clone(), themed(app, Style::new().fg(c)))
            }
            (None, None) => Line::from(""),
        },
    };
    buf.set_line(message.x, message.y, &line, message.width);
}
