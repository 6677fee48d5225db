//! Drawing: pure functions of `&App`, one per pane. Nothing here changes the model.

mod csg;
mod details;
mod help;
mod lesson;
mod lessons;
mod preview;
mod status;
mod tree_view;

use glam::DVec3;
use ratatui::backend::TestBackend;
use ratatui::buffer::Buffer;
use ratatui::layout::Rect;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::{Line, Span};
use ratatui::widgets::{Block, BorderType};
use ratatui::{Frame, Terminal};

use super::app::{App, Focus, LessonView, Screen};
use crate::render::preview::{ansi256, ramp_char, rgb8, ColorMode};

pub use details::details_lines;
pub use help::KEYS;

/// Draws the whole screen.
pub fn draw(f: &mut Frame, app: &App) {
    let area = f.area();
    if area.width < 30 || area.height < 8 {
        let msg = Line::from("raytree explore: the terminal is too small (30 × 8 at least)");
        f.buffer_mut().set_line(0, 0, &msg, area.width);
        return;
    }
    match app.screen {
        Screen::Lessons => lessons::draw(f, app, area),
        Screen::Scene => {
            // The frame's own size: right even before a resize reaches the model.
            let p = app.panes_in(area);
            preview::draw(f, app, &p);
            tree_view::draw(f, app, p.tree);
            if let Some(r) = p.lower {
                if app.show_csg {
                    csg::draw(f, app, r);
                } else {
                    details::draw(f, app, r);
                }
            }
            if let Some(r) = p.lesson {
                lesson::draw(f, app, r);
            }
            status::draw(f, app, p.status, p.message);
        }
    }
    if app.show_help {
        help::draw(f, app, area);
    }
}

/// How far the lower pane (details or CSG) and the lesson pane can scroll, in rows.
pub fn max_scroll(app: &App) -> (u16, u16) {
    let p = app.panes();
    let lower = p.lower.map_or(0, |r| {
        let i = inner(r);
        let n = if app.show_csg {
            csg::lines(app, i.width as usize).0.len()
        } else {
            details::lines(app, i.width as usize).len()
        };
        n.saturating_sub(i.height as usize)
    });
    let lesson = match (p.lesson, &app.lesson) {
        (Some(r), Some(l)) if l.view == LessonView::Exercises => {
            let (head, body) = lesson::exercise_lines(app, l, inner(r));
            body.len()
                .saturating_sub((inner(r).height as usize).saturating_sub(head.len()))
        }
        (Some(r), Some(l)) => {
            let i = inner(r);
            lesson::markdown(&l.lesson.readme, (i.width as usize).max(10))
                .len()
                .saturating_sub(i.height as usize)
        }
        _ => 0,
    };
    (
        lower.min(u16::MAX as usize) as u16,
        lesson.min(u16::MAX as usize) as u16,
    )
}

/// The row of the CSG pane where the selected ray's section starts.
pub fn csg_section_row(app: &App) -> Option<usize> {
    let r = app.panes().lower?;
    csg::lines(app, inner(r).width as usize).1
}

/// The screen as plain text (no colours), one line per row, trailing spaces trimmed.
pub fn screen_text(app: &App, width: u16, height: u16) -> String {
    let mut term = Terminal::new(TestBackend::new(width, height)).expect("a test terminal");
    term.draw(|f| draw(f, app)).expect("drawing to a buffer");
    buffer_text(term.backend().buffer())
}

pub fn buffer_text(buf: &Buffer) -> String {
    let a = buf.area;
    let mut out = String::new();
    for y in a.top()..a.bottom() {
        let mut line = String::new();
        for x in a.left()..a.right() {
            line.push_str(buf[(x, y)].symbol());
        }
        out.push_str(line.trim_end());
        out.push('\n');
    }
    out
}

/// A style with its colours dropped when colours are off (NO_COLOR, dumb terminals).
pub(crate) fn themed(app: &App, style: Style) -> Style {
    if app.color == ColorMode::Ascii {
        Style {
            fg: None,
            bg: None,
            ..style
        }
    } else {
        style
    }
}

/// A terminal colour for a linear intensity.
pub(crate) fn term_color(app: &App, c: DVec3) -> Option<Color> {
    let rgb = rgb8(c);
    match app.color {
        ColorMode::TrueColor => Some(Color::Rgb(rgb[0], rgb[1], rgb[2])),
        ColorMode::Ansi256 => Some(Color::Indexed(ansi256(rgb))),
        ColorMode::Ascii => None,
    }
}

/// A small sample of a colour, drawn beside intensities.
pub(crate) fn swatch(app: &App, c: DVec3) -> Span<'static> {
    match term_color(app, c) {
        Some(color) => Span::styled("██", Style::new().fg(color)),
        None => Span::raw(format!("[{}]", ramp_char(c))),
    }
}

/// A pane's frame; the focused pane's is drawn bold and thick.
pub(crate) fn pane<'a>(app: &App, title: impl Into<Line<'a>>, focus: Option<Focus>) -> Block<'a> {
    let focused = focus.is_some_and(|f| f == app.focus);
    let (style, kind) = if focused {
        (
            Style::new().fg(Color::Cyan).add_modifier(Modifier::BOLD),
            BorderType::Thick,
        )
    } else {
        (Style::new().fg(Color::DarkGray), BorderType::Plain)
    };
    Block::bordered()
        .border_type(kind)
        .border_style(themed(app, style))
        .title(title)
}

/// Display width of a string in terminal cells.
pub(crate) fn width(s: &str) -> usize {
    Span::raw(s).width()
}

/// Word-wraps a line to `max` cells; continuation lines keep the line's indentation (plus
/// two cells), so wrapped formulas stay readable.
pub fn wrap(line: &str, max: usize) -> Vec<String> {
    let indent_len = line.len() - line.trim_start().len();
    let hang = " ".repeat((indent_len + 2).min(max / 2));
    wrap_hang(line, max, &hang)
}

/// Word-wraps a line to `max` cells, starting continuation lines with `hang`.
pub fn wrap_hang(line: &str, max: usize, hang: &str) -> Vec<String> {
    if max == 0 {
        return vec![];
    }
    if width(line) <= max {
        return vec![line.to_string()];
    }
    let hang = if width(hang) > max / 2 { "" } else { hang };
    let indent_len = line.len() - line.trim_start().len();
    let mut out = Vec::new();
    let mut cur = line[..indent_len].to_string();
    let mut cur_w = width(&cur);
    let mut at_start = true;
    for word in line[indent_len..].split(' ') {
        let ww = width(word);
        let sep = if at_start { 0 } else { 1 };
        if !at_start && cur_w + sep + ww > max {
            out.push(std::mem::take(&mut cur));
            cur = hang.to_string();
            cur_w = width(&cur);
            at_start = true;
        }
        let sep = if at_start { 0 } else { 1 };
        if cur_w + sep + ww <= max {
            if sep == 1 {
                cur.push(' ');
            }
            cur.push_str(word);
            cur_w += sep + ww;
            at_start = false;
            continue;
        }
        // A word longer than a line: cut it.
        for ch in word.chars() {
            let cw = width(ch.encode_utf8(&mut [0; 4]));
            if cur_w + cw > max {
                out.push(std::mem::take(&mut cur));
                cur = hang.to_string();
                cur_w = width(&cur);
            }
            cur.push(ch);
            cur_w += cw;
        }
        at_start = false;
    }
    if !cur.trim().is_empty() {
        out.push(cur);
    }
    out
}

/// The rows of `lines` shown in an area of `height` rows scrolled by `scroll` (clamped so the
/// last page stays full).
pub(crate) fn scroll_window<T: Clone>(lines: &[T], scroll: u16, height: u16) -> (Vec<T>, usize) {
    let h = height as usize;
    let start = (scroll as usize).min(lines.len().saturating_sub(h));
    (lines[start..(start + h).min(lines.len())].to_vec(), start)
}

/// "12/40" when a pane's content does not fit.
pub(crate) fn position_note(start: usize, shown: usize, total: usize) -> Option<String> {
    (total > shown).then(|| {
        format!(
            " {}–{} of {} ",
            start + 1,
            (start + shown).min(total),
            total
        )
    })
}

/// The inner area of a bordered pane.
pub(crate) fn inner(r: Rect) -> Rect {
    r.inner(ratatui::layout::Margin::new(1, 1))
}
