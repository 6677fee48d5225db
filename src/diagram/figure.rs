//! The `raytree diagram` figure, in the style of the lecture slides (seed 004): on the left
//! the scene cut by the plane of the view, with the rays as arrows coloured and labelled by
//! their kind and intensity, the normals dashed, the lights and the eye; on the right the ray
//! tree as a graph, its edges labelled with the coefficients. Written as SVG through the `svg`
//! crate; `raster.rs` turns it into PNG.
//!
//! This file lays the page out (the title, the two panels, the legend); `section.rs` draws
//! the scene's panel, `tree_panel.rs` the graph's, both with the pens of `ink.rs`, and
//! `labels.rs` finds where the labels go.

use glam::{DVec2, DVec3};
use svg::node::element::{ClipPath, Definitions, Group, Rectangle, Title};
use svg::Document;

use super::drawing::Drawing;
use super::ink::{line, ray_color, text, text_width, Panel, INK, NORMAL};
use super::rays::SegKind;
use crate::scene::Scene;
use crate::trace::RayNode;

/// What the figure shows, besides the drawing itself.
pub struct Figure<'a> {
    /// The scene the tree was traced in.
    pub scene: &'a Scene,
    /// The ray tree drawn.
    pub tree: &'a RayNode,
    /// The tree laid out in its view.
    pub drawing: &'a Drawing,
    /// The title line: scene, pixel or ray, view.
    pub title: String,
    /// The figure's size in pixels.
    pub width: u32,
    /// The figure's height in pixels.
    pub height: u32,
}

/// The title's least height, the legend's (one row), a legend row's, and the share of the
/// width the section takes.
const TOP: f64 = 40.0;
const LEGEND: f64 = 30.0;
const LEGEND_ROW: f64 = 18.0;
const SPLIT: f64 = 0.58;
/// The narrowest figure drawn: below it the legend's rows would leave the section no room on
/// the least height, and the graph's boxes no room for a word.
pub const MIN_WIDTH: u32 = 400;
/// A wrapped title's font size.
const WRAPPED_TITLE: f64 = 10.0;

/// How wide a bold title is drawn: about 0.64 em a character.
fn title_width(s: &str, size: f64) -> f64 {
    0.64 * size * s.chars().count() as f64
}

/// Where the figure's bands go at its size.
struct Layout {
    /// The title's lines, and their font size.
    title: Vec<String>,
    title_size: f64,
    /// The title's band, from the top.
    top: f64,
    /// The legend's entries (a kind of ray, or None for the normal) and where each starts.
    legend: Vec<(Option<SegKind>, DVec2)>,
    /// The legend's band, at the bottom.
    legend_h: f64,
    /// The x where the section ends and the graph begins.
    split: f64,
}

/// The title on one line, 16 px or smaller down to 8 where it is long; where it does not fit
/// even at 8, in lines of `WRAPPED_TITLE` px broken between words.
fn title_lines(title: &str, room: f64) -> (Vec<String>, f64) {
    let size = (room / title_width(title, 1.0)).clamp(8.0, 16.0);
    if title_width(title, size) <= room {
        return (vec![title.to_string()], size);
    }
    let mut lines: Vec<String> = vec![];
    for word in title.split(' ') {
        match lines.last_mut() {
            Some(l) if title_width(&format!("{l} {word}"), WRAPPED_TITLE) <= room => {
                l.push(' ');
                l.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    // A word longer than the line (a long path) keeps its start and says it is cut.
    let most = (room / title_width("x", WRAPPED_TITLE)).floor() as usize;
    for l in &mut lines {
        if l.chars().count() > most {
            *l = l
                .chars()
                .take(most.saturating_sub(1))
                .chain(['…'])
                .collect();
        }
    }
    (lines, WRAPPED_TITLE)
}

/// The legend's entries laid out from `left` in rows no wider than `right`: each entry's
/// start, and the number of rows.
fn legend_rows(left: f64, right: f64) -> (Vec<(Option<SegKind>, DVec2)>, usize) {
    let entries = SegKind::ALL
        .iter()
        .map(|&k| (Some(k), k.name()))
        .chain([(None, "normal")]);
    let (mut x, mut row) = (left, 0usize);
    let mut out = vec![];
    for (kind, name) in entries {
        // The swatch, the gap and the name, then a gap before the next entry.
        let drawn = 27.0 + text_width(name, 12.0);
        if x > left && x + drawn > right {
            (x, row) = (left, row + 1);
        }
        out.push((kind, DVec2::new(x, row as f64 * LEGEND_ROW)));
        x += drawn + 9.0;
    }
    (out, row + 1)
}

impl Figure<'_> {
    /// The bands at this figure's size.
    fn layout(&self) -> Layout {
        let w = self.width as f64;
        let split = (w * SPLIT).round();
        let (title, title_size) = title_lines(&self.title, w - 24.0);
        // The first baseline 26 px below the top, the band 14 px below the last.
        let last = 26.0 + 1.25 * title_size * (title.len() - 1) as f64;
        let top = TOP.max(last + 14.0);
        let (legend, rows) = legend_rows(12.0, split - 12.0);
        Layout {
            title,
            title_size,
            top,
            legend,
            legend_h: LEGEND + LEGEND_ROW * (rows - 1) as f64,
            split,
        }
    }

    /// Where the section is drawn.
    fn scene_panel(&self) -> Panel {
        let l = self.layout();
        let h = self.height as f64;
        Panel::new(
            self.drawing.frame,
            DVec2::new(12.0, l.top),
            DVec2::new(l.split - 24.0, h - l.top - l.legend_h - 12.0),
        )
    }

    /// Where a world point is drawn in the figure, in pixels.
    pub fn pixel_of(&self, p: DVec3) -> DVec2 {
        self.scene_panel().px(self.drawing.at(p))
    }

    /// The SVG document.
    pub fn svg(&self) -> Document {
        let (w, h) = (self.width as f64, self.height as f64);
        let layout = self.layout();
        let panel = self.scene_panel();
        let (scene_origin, scene_size) = (panel.origin, panel.size);
        let split = layout.split;
        let mut doc = Document::new()
            .set("width", self.width)
            .set("height", self.height)
            .set("viewBox", (0, 0, self.width, self.height))
            .add(Title::new(self.title.clone()))
            .add(
                Rectangle::new()
                    .set("width", "100%")
                    .set("height", "100%")
                    .set("fill", "white"),
            )
            .add(
                Definitions::new().add(
                    ClipPath::new().set("id", "section").add(
                        Rectangle::new()
                            .set("x", scene_origin.x)
                            .set("y", scene_origin.y)
                            .set("width", scene_size.x)
                            .set("height", scene_size.y),
                    ),
                ),
            );
        let size = layout.title_size;
        for (i, line) in layout.title.iter().enumerate() {
            let at = DVec2::new(12.0, 26.0 + 1.25 * size * i as f64);
            doc = doc.add(text(at, line, size, INK).set("font-weight", "bold"));
        }
        doc = doc
            .add(
                Rectangle::new()
                    .set("x", scene_origin.x)
                    .set("y", scene_origin.y)
                    .set("width", scene_size.x)
                    .set("height", scene_size.y)
                    .set("fill", "none")
                    .set("stroke", "#cccccc"),
            )
            .add(self.section(&panel))
            .add(legend(&layout.legend, h - layout.legend_h + 8.0));
        let graph_origin = DVec2::new(split + 8.0, layout.top);
        let graph_size = DVec2::new(w - split - 20.0, h - layout.top - 12.0);
        doc = doc.add(self.graph(graph_origin, graph_size));
        doc
    }
}

/// The legend: each entry a swatch of its colour and its name, its row from `top`.
fn legend(entries: &[(Option<SegKind>, DVec2)], top: f64) -> Group {
    let mut g = Group::new();
    for &(kind, at) in entries {
        let at = at + DVec2::new(0.0, top);
        let swatch = match kind {
            Some(k) => line(at, at + DVec2::new(22.0, 0.0), &ray_color(k), 3.0),
            None => {
                line(at, at + DVec2::new(22.0, 0.0), NORMAL, 1.6).set("stroke-dasharray", "5 4")
            }
        };
        let name = kind.map_or("normal", SegKind::name);
        g = g
            .add(swatch)
            .add(text(at + DVec2::new(27.0, 4.0), name, 12.0, INK));
    }
    g
}
