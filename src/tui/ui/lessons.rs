//! The lesson list (`raytree explore` without an argument).

use ratatui::layout::{Margin, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::Line;
use ratatui::widgets::{Block, Paragraph};
use ratatui::Frame;

use super::themed;
use crate::tui::app::App;
use crate::tui::layout::{list_offset, list_panes};
use crate::tui::wrap::{wrap, wrap_hang};

pub fn draw(f: &mut Frame, app: &App, area: Rect) {
    let (list_area, info_area, status, message) = list_panes(area);
    let Some(list) = &app.list else { return };
    let inner = list_area.inner(Margin::new(1, 1));
    let off = list_offset(list.selected, inner.height as usize);
    let mut lines = Vec::new();
    for (i, e) in list
        .entries
        .iter()
        .enumerate()
        .skip(off)
        .take(inner.height as usize)
    {
        let name = e
            .dir
            .file_name()
            .map_or(String::new(), |n| n.to_string_lossy().into_owned());
        let title = match &e.lesson {
            Ok(l) => {
                let done = l
                    .exercises
                    .iter()
                    .filter(|x| e.solved.contains(&x.id))
                    .count();
                let mark = if done == l.exercises.len() {
                    "✓"
                } else {
                    " "
                };
                format!("{done:>2}/{:<2} {mark} {}", l.exercises.len(), l.title)
            }
            Err(_) => "(does not load)".into(),
        };
        let sel = i == list.selected;
        let style = if sel {
            Style::new().bg(Color::Blue).add_modifier(Modifier::BOLD)
        } else {
            Style::new()
        };
        lines.push(Line::styled(
            format!("{} {name:<22} {title}", if sel { "▶" } else { " " }),
            themed(app, style),
        ));
    }
    let block = Block::bordered()
        .title(format!(" lessons · folder {}/ ", list.root.display()))
        .border_style(themed(app, Style::new().fg(Color::Cyan)));
    f.render_widget(Paragraph::new(lines).block(block), list_area);

    let w = info_area.width.saturating_sub(2) as usize;
    let mut info: Vec<Line> = Vec::new();
    if let Some(e) = list.entries.get(list.selected) {
        match &e.lesson {
            Ok(l) => {
                info.push(Line::styled(
                    l.title.clone(),
                    themed(
                        app,
                        Style::new().add_modifier(Modifier::BOLD).fg(Color::Yellow),
                    ),
                ));
                info.push(Line::from(""));
                for p in wrap_hang(&l.summary, w, "") {
                    info.push(Line::from(p));
                }
                info.push(Line::from(""));
                info.push(Line::from(format!("{} exercises:", l.exercises.len())));
                for ex in &l.exercises {
                    let mark = if e.solved.contains(&ex.id) {
                        "✓"
                    } else {
                        " "
                    };
                    info.push(Line::from(format!(" {mark} {}", ex.id)));
                }
            }
            Err(err) => {
                for p in wrap(err, w) {
                    info.push(Line::styled(p, themed(app, Style::new().fg(Color::Red))));
                }
            }
        }
    }
    f.render_widget(
        Paragraph::new(info).block(Block::bordered().title(" lesson ")),
        info_area,
    );
    let hint = "↑↓/jk choose · Enter open · ? help · q quit";
    f.buffer_mut().set_string(
        status.x,
        status.y,
        format!(
            " raytree explore · {} lesson{}",
            list.entries.len(),
            if list.entries.len() == 1 { "" } else { "s" }
        ),
        themed(app, Style::new().add_modifier(Modifier::REVERSED)),
    );
    let (text, style) = match &list.error {
        Some(e) => (e.as_str(), Style::new().fg(Color::Red)),
        None => (hint, Style::new().fg(Color::DarkGray)),
    };
    f.buffer_mut().set_stringn(
        message.x,
        message.y,
        text,
        message.width as usize,
        themed(app, style),
    );
}
