//! The preview pane: the scene in half-block cells (upper pixel as foreground of ▀, lower as
//! background), 256 colours, or an ASCII ramp; the picked pixel marked.

use ratatui::layout::Alignment;
use ratatui::style::{Color, Modifier, Style};
use ratatui::text::Line;
use ratatui::Frame;

use super::{pane, themed};
use crate::diagram::marks::hit_marks;
use crate::render::preview::{ramp_char, ColorMode};
use crate::tui::app::{App, Focus};
use crate::tui::layout::{pixel_cell, Panes};
use crate::tui::worker::Pass;

use super::diagram::kind_color;

pub fn draw(f: &mut Frame, app: &App, p: &Panes) {
    let title = format!(" preview {}×{} ", p.image_px.0, p.image_px.1);
    let note = if app.preview.running || app.preview.pass == Some(Pass::Draft) {
        " rendering… "
    } else {
        ""
    };
    let mut block = pane(app, &title, p.preview, Some(Focus::Preview))
        .title_bottom(Line::from(note).alignment(Alignment::Right));
    if app.preview.marks {
        block = block.title_bottom(Line::from(" ◆ hits ").alignment(Alignment::Left));
    }
    f.render_widget(block, p.preview);
    draw_image(f, app, p);
    let (w, h) = app.image_size();
    if app.preview.marks && w > 0 && h > 0 {
        marks(f, app, p, (w, h));
    }
    cursor(f, app, p);
}

/// The image in half-block cells (or the ASCII ramp).
fn draw_image(f: &mut Frame, app: &App, p: &Panes) {
    let buf = f.buffer_mut();
    let r = p.image;
    let (pw, ph) = p.image_px;
    let Some(img) = &app.preview.image else {
        let msg = "rendering…";
        if r.width as usize >= msg.len() && r.height > 0 {
            buf.set_string(
                r.x + (r.width - msg.len() as u16) / 2,
                r.y + r.height / 2,
                msg,
                Style::new(),
            );
        }
        return;
    };
    if pw == 0 || ph == 0 || img.width == 0 || img.height == 0 {
        return;
    }
    // The image may be a draft or from before a resize: sample it at the pane's resolution.
    let sample = |px: u32, py: u32| {
        let ix = (px as u64 * img.width as u64 / pw as u64) as u32;
        let iy = (py as u64 * img.height as u64 / ph as u64) as u32;
        img.get(ix.min(img.width - 1), iy.min(img.height - 1))
    };
    for cy in 0..r.height {
        for cx in 0..r.width {
            let (px, py) = (cx as u32, 2 * cy as u32);
            let top = sample(px, py);
            let bottom = (py + 1 < ph).then(|| sample(px, py + 1));
            let Some(cell) = buf.cell_mut((r.x + cx, r.y + cy)) else {
                continue;
            };
            match app.color {
                ColorMode::Ascii => {
                    let c = bottom.map_or(top, |b| 0.5 * (top + b));
                    cell.set_char(ramp_char(c));
                }
                _ => {
                    cell.set_char('▀');
                    cell.set_fg(super::term_color(app, top).unwrap_or(Color::Reset));
                    cell.set_bg(
                        bottom
                            .and_then(|b| super::term_color(app, b))
                            .unwrap_or(Color::Reset),
                    );
                }
            }
        }
    }
}

/// The picked pixel, marked.
fn cursor(f: &mut Frame, app: &App, p: &Panes) {
    let (w, h) = app.image_size();
    let r = p.image;
    let buf = f.buffer_mut();
    // An exercise's ray that is no pixel's has no place on the image to mark.
    if w > 0 && h > 0 && app.tree.aimed_ray().is_none() {
        if let Some((cx, cy)) = pixel_cell(p, (w, h), app.tree.pixel()) {
            if let (true, Some(cell)) = (
                r.contains(ratatui::layout::Position::new(cx, cy)),
                buf.cell_mut((cx, cy)),
            ) {
                let style = themed(
                    app,
                    Style::new()
                        .fg(Color::Black)
                        .bg(Color::Yellow)
                        .add_modifier(Modifier::BOLD),
                );
                if app.color == ColorMode::Ascii {
                    cell.set_char('X');
                    cell.set_style(style.add_modifier(Modifier::REVERSED));
                } else {
                    cell.set_char('+');
                    cell.set_style(style);
                }
            }
        }
    }
}

/// Where the tree's reflection and refraction rays landed, marked on the image: ◆ in the
/// ray's colour (the selected ray's in yellow).
fn marks(f: &mut Frame, app: &App, p: &Panes, (w, h): (u32, u32)) {
    let (Some(scene), Some(root)) = (app.file.scene.as_deref(), app.tree.shown_tree()) else {
        return;
    };
    let (pw, ph) = p.image_px;
    let r = p.image;
    let buf = f.buffer_mut();
    for m in hit_marks(&scene.camera, root) {
        let (sx, sy) = (m.at.x / w as f64 * pw as f64, m.at.y / h as f64 * ph as f64);
        if !(sx >= 0.0 && sy >= 0.0 && sx < pw as f64 && sy < ph as f64) {
            continue;
        }
        let (cx, cy) = (r.x + sx as u16, r.y + (sy / 2.0) as u16);
        let color = if m.path == app.tree.selected() {
            Color::LightYellow
        } else {
            kind_color(m.kind)
        };
        if let Some(cell) = buf.cell_mut((cx, cy)) {
            if app.color == ColorMode::Ascii {
                cell.set_char('o');
            } else {
                cell.set_char('◆');
                cell.set_fg(color);
            }
        }
    }
}
