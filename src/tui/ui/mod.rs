//! Drawing: pure functions of `&App`, one per pane. Nothing here changes the model, and the
//! model never calls in here: what both need (pane geometry, wrapped rows) lives outside ui/.

mod csg;
mod details;
pub mod diagram;
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
use ratatui::text::Span;
use ratatui::widgets::{Block, BorderType, Paragraph, Wrap};
use ratatui::{Frame, Terminal};

pub(crate) use super::layout::inner;

use super::app::{App, Focus, Screen};
use crate::render::preview::{ansi256, ramp_char, rgb8, ColorMode};

pub use help::KEYS;

/// The smallest terminal (columns, rows) the explorer draws its panes in.
const MIN_SIZE: (u16, u16) = (30, 8);

/// Draws the whole screen.
pub fn draw(f: &mut Frame, app: &App) {
    let area = f.area();
    if area.width < MIN_SIZE.0 || area.height < MIN_SIZE.1 {
        // Wrapped, so that the sizes are read on the smallest screen too.
        let msg = format!(
            "The terminal is {} × {}: the explorer needs {} × {} at least. Enlarge it, or press q.",
            area.width, area.height, MIN_SIZE.0, MIN_SIZE.1
        );
        f.render_widget(Paragraph::new(msg).wrap(Wrap { trim: true }), area);
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
                if app.csg.shown() {
                    csg::draw(f, app, r);
                } else {
                    details::draw(f, app, r);
                }
            }
            if let Some(r) = p.lesson {
                lesson::draw(f, app, r);
            }
            if let Some(r) = p.diagram {
                diagram::draw(f, app, r);
            }
            status::draw(f, app, p.status, p.message);
        }
    }
    if app.show_help {
        help::draw(f, app, area);
    }
}

/// The screen as plain text (no colours), one line per row, trailing spaces trimmed.
pub fn screen_text(app: &App, width: u16, height: u16) -> String {
    let mut term = Terminal::new(TestBackend::new(width, height)).expect("a test terminal");
    term.draw(|f| draw(f, app)).expect("drawing to a buffer");
    buffer_text(term.backend().buffer())
}

/// The characters of a drawn buffer, one line per row, trailing spaces dropped.
fn buffer_text(buf: &Buffer) -> String {
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

/// A pane's frame for `area`, its title kept to whole parts that fit between the corners; the
/// focused pane's is drawn bold and thick.
pub(crate) fn pane(app: &App, title: &str, area: Rect, focus: Option<Focus>) -> Block<'static> {
    let title = crate::tui::wrap::title_to_fit(title, area.width.saturating_sub(2) as usize);
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

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::tui::{update, Msg};

    fn mirror(size: (u16, u16)) -> App {
        let path = Path::new("tests/scenes/explorer-mirror.yaml");
        let mut app = App::open(Some(path), ColorMode::TrueColor).expect("the test scene opens");
        update(&mut app, Msg::Resize(size.0, size.1));
        update(&mut app, Msg::Pick(20, 15));
        app
    }

    /// The model's scroll limit of the lower pane is the rows drawn there less its height.
    #[test]
    fn the_model_scrolls_as_far_as_the_drawing_goes() {
        for size in [(80, 24), (100, 30), (160, 48)] {
            let mut app = mirror(size);
            for _ in 0..2 {
                let r = inner(app.panes().lower.expect("a lower pane"));
                let drawn = if app.csg.shown() {
                    csg::lines(&app, r.width as usize).len()
                } else {
                    details::lines(&app, r.width as usize).len()
                };
                let expected = drawn.saturating_sub(r.height as usize) as u16;
                assert_eq!(app.scroll_limits().0, expected, "{size:?}");
                update(&mut app, Msg::ToggleCsg);
            }
        }
    }
}
