//! The status line (scene, image size, picked pixel, depth, render progress, rays) and the
//! message line below it (a prompt, a scene error, or the last message).

use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::Frame;

use super::themed;
use crate::tui::app::App;
use crate::tui::state::prompt::Prompt;
use crate::tui::state::Tone;
use crate::tui::wrap::{message_to_fit, wrap_hang};

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

/// The status line: as much as fits, the least useful parts dropped first.
pub fn status_text(app: &App) -> String {
    let (w, h) = app.image_size();
    let (x, y) = app.tree.pixel();
    let depth = match app.tree.level() {
        Some(k) => format!("{} (level {k})", app.tree.depth_label()),
        None => app.tree.depth_label(),
    };
    let p = &app.preview;
    let progress = if p.running {
        let (done, total) = p.rows;
        format!(
            "rendering {}%",
            (100 * done).checked_div(total).unwrap_or(0)
        )
    } else if p.image.is_some() {
        "preview 100%".into()
    } else {
        "preview —".into()
    };
    let count = |n: u64| format!("{} {}", grouped(n), if n == 1 { "ray" } else { "rays" });
    let rays = p.stats.map(|s| count(s.rays())).unwrap_or_default();
    let tree = format!("tree {}", count(app.tree.stats().rays()));
    let path = app.file.name();
    let file = app
        .file
        .path
        .as_ref()
        .and_then(|p| p.file_name())
        .map_or(String::new(), |f| f.to_string_lossy().into_owned());
    let core = [
        format!("{w}×{h}"),
        match app.tree.aimed_ray() {
            Some(_) => "an exercise's ray".to_string(),
            None => format!("pixel {x},{y}"),
        },
        depth,
        progress,
    ];
    let room = app.size.0 as usize;
    // From the most to the least complete.
    let candidates = [
        (path.clone(), vec![rays.clone(), tree.clone()]),
        (path.clone(), vec![rays.clone()]),
        (file.clone(), vec![rays.clone(), tree]),
        (file.clone(), vec![rays]),
        (path, vec![]),
        (file, vec![]),
    ];
    let mut last = String::new();
    for (name, extra) in candidates {
        let mut parts = vec![name];
        parts.extend(core.iter().cloned());
        parts.extend(extra.into_iter().filter(|e| !e.is_empty()));
        last = format!(" {}", parts.join(" │ "));
        if last.chars().count() <= room {
            break;
        }
    }
    last
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
        None => {
            let Some((text, tone)) = app.message_text() else {
                return;
            };
            let style = match tone {
                Tone::Info => Style::new().fg(Color::Gray),
                Tone::Good => Style::new().fg(Color::Green),
                Tone::Bad => Style::new().fg(Color::Red).add_modifier(Modifier::BOLD),
            };
            let style = themed(app, style);
            // A message of one row keeps its key hints; a scene error has the rows it wraps to
            // (`App::message_rows`).
            let lines = if message.height == 1 {
                vec![message_to_fit(&text, message.width as usize)]
            } else {
                wrap_hang(&text, message.width as usize, "  ")
            };
            for (i, l) in lines.iter().take(message.height as usize).enumerate() {
                buf.set_stringn(
                    message.x,
                    message.y + i as u16,
                    l,
                    message.width as usize,
                    style,
                );
            }
            return;
        }
    };
    buf.set_line(message.x, message.y, &line, message.width);
}
