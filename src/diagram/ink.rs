//! The pens of the `raytree diagram` figure: its colours, the SVG elements every part of it
//! is drawn with (lines, labels, dots, arrowheads), and `Panel`, which maps the view's plane
//! onto a rectangle of the page.

use glam::DVec2;
use svg::node::element::{Circle, Line, Polygon, Text};

use super::frame::Frame;
use super::rays::SegKind;

pub(super) const INK: &str = "#222222";
pub(super) const OUTLINE: &str = "#555555";
pub(super) const FILL: &str = "#e4e4e4";
pub(super) const NORMAL: &str = "#2e7d32";
const FONT: &str = "DejaVu Sans, Helvetica, Arial, sans-serif";

fn hex([r, g, b]: [u8; 3]) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// The colour of a kind of ray in figures.
pub fn ray_color(kind: SegKind) -> String {
    hex(kind.rgb())
}

/// World units of the view's plane to pixels of a panel.
pub(super) struct Panel {
    pub frame: Frame,
    pub origin: DVec2,
    pub size: DVec2,
}

impl Panel {
    pub fn new(frame: Frame, origin: DVec2, size: DVec2) -> Panel {
        Panel {
            frame: frame.with_aspect(size.x / size.y),
            origin,
            size,
        }
    }

    pub fn px(&self, p: DVec2) -> DVec2 {
        let f = &self.frame;
        let u = (p - f.min) / f.size();
        DVec2::new(
            self.origin.x + u.x * self.size.x,
            self.origin.y + (1.0 - u.y) * self.size.y,
        )
    }
}

pub(super) fn line(a: DVec2, b: DVec2, color: &str, width: f64) -> Line {
    Line::new()
        .set("x1", r(a.x))
        .set("y1", r(a.y))
        .set("x2", r(b.x))
        .set("y2", r(b.y))
        .set("stroke", color)
        .set("stroke-width", width)
        .set("stroke-linecap", "round")
}

pub(super) fn text(at: DVec2, s: &str, size: f64, color: &str) -> Text {
    Text::new(s)
        .set("x", r(at.x))
        .set("y", r(at.y))
        .set("font-size", size)
        .set("font-family", FONT)
        .set("fill", color)
        // A white halo keeps labels readable over lines.
        .set("stroke", "white")
        .set("stroke-width", 3)
        .set("stroke-linejoin", "round")
        .set("paint-order", "stroke")
}

/// A filled circle of `radius` at `at`.
pub(super) fn dot(at: DVec2, radius: f64, fill: &str) -> Circle {
    Circle::new()
        .set("cx", r(at.x))
        .set("cy", r(at.y))
        .set("r", radius)
        .set("fill", fill)
}

/// About how wide a label is drawn: 0.6 em a character (DejaVu Sans and its kin).
pub(super) fn text_width(s: &str, size: f64) -> f64 {
    0.6 * size * s.chars().count() as f64
}

/// Two decimals are plenty for pixel coordinates.
pub(super) fn r(x: f64) -> f64 {
    (x * 100.0).round() / 100.0
}

pub(super) fn points(ps: &[DVec2]) -> String {
    ps.iter()
        .map(|p| format!("{},{}", r(p.x), r(p.y)))
        .collect::<Vec<_>>()
        .join(" ")
}

/// An arrowhead with its tip at `tip`, pointing along `dir`.
pub(super) fn arrowhead(tip: DVec2, dir: DVec2, size: f64, color: &str) -> Polygon {
    let d = dir.normalize_or_zero();
    let side = d.perp() * size * 0.45;
    let back = tip - d * size;
    Polygon::new()
        .set("points", points(&[tip, back + side, back - side]))
        .set("fill", color)
}
