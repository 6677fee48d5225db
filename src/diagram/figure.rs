//! The `raytree diagram` figure, in the style of the lecture slides (seed 004): on the left
//! the scene cut by the plane of the view, with the rays as arrows coloured and labelled by
//! their kind and intensity, the normals dashed, the lights and the eye; on the right the ray
//! tree as a graph, its edges labelled with the coefficients. Written as SVG through the `svg`
//! crate; `raster.rs` turns it into PNG.

use glam::{DVec2, DVec3};
use svg::node::element::{
    Circle, ClipPath, Definitions, Group, Line, Polygon, Rectangle, Text, Title,
};
use svg::Document;

use super::drawing::Drawing;
use super::frame::Frame;
use super::graph::{layout, GraphNode};
use super::outline::Outline;
use super::rays::SegKind;
use crate::scene::Scene;
use crate::trace::{RayKind, RayNode};

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

const INK: &str = "#222222";
const OUTLINE: &str = "#555555";
const FILL: &str = "#e4e4e4";
const NORMAL: &str = "#2e7d32";
/// Where a light's name goes from its centre.
const LIGHT_LABEL: DVec2 = DVec2::new(14.0, -10.0);
const FONT: &str = "DejaVu Sans, Helvetica, Arial, sans-serif";

fn hex([r, g, b]: [u8; 3]) -> String {
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// The colour of a kind of ray in figures.
pub fn ray_color(kind: SegKind) -> String {
    hex(kind.rgb())
}

/// World units of the view's plane to pixels of a panel.
struct Panel {
    frame: Frame,
    origin: DVec2,
    size: DVec2,
}

impl Panel {
    fn new(frame: Frame, origin: DVec2, size: DVec2) -> Panel {
        Panel {
            frame: frame.with_aspect(size.x / size.y),
            origin,
            size,
        }
    }

    fn px(&self, p: DVec2) -> DVec2 {
        let f = &self.frame;
        let u = (p - f.min) / f.size();
        DVec2::new(
            self.origin.x + u.x * self.size.x,
            self.origin.y + (1.0 - u.y) * self.size.y,
        )
    }
}

fn line(a: DVec2, b: DVec2, color: &str, width: f64) -> Line {
    Line::new()
        .set("x1", r(a.x))
        .set("y1", r(a.y))
        .set("x2", r(b.x))
        .set("y2", r(b.y))
        .set("stroke", color)
        .set("stroke-width", width)
        .set("stroke-linecap", "round")
}

fn text(at: DVec2, s: &str, size: f64, color: &str) -> Text {
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
fn dot(at: DVec2, radius: f64, fill: &str) -> Circle {
    Circle::new()
        .set("cx", r(at.x))
        .set("cy", r(at.y))
        .set("r", radius)
        .set("fill", fill)
}

/// About how wide a label is drawn: 0.6 em a character (DejaVu Sans and its kin).
fn text_width(s: &str, size: f64) -> f64 {
    0.6 * size * s.chars().count() as f64
}

/// A label at `at` that stays inside the panel: anchored at its end when it would run off
/// the right edge.
fn label_in(p: &Panel, at: DVec2, s: &str, size: f64, color: &str) -> Text {
    let width = text_width(s, size);
    let right = p.origin.x + p.size.x - 4.0;
    let t = text(at, s, size, color);
    if at.x + width > right {
        t.set("x", r(at.x.min(right))).set("text-anchor", "end")
    } else {
        t
    }
}

/// The rectangle (top-left, bottom-right) a label drawn by `label_in` covers, roughly.
fn label_box(p: &Panel, at: DVec2, s: &str, size: f64) -> (DVec2, DVec2) {
    let width = text_width(s, size);
    let right = p.origin.x + p.size.x - 4.0;
    let x0 = if at.x + width > right {
        at.x.min(right) - width
    } else {
        at.x
    };
    (
        DVec2::new(x0, at.y - size),
        DVec2::new(x0 + width, at.y + 2.0),
    )
}

/// A ray's label near `at`: the box it covers, reading on from `at` or, where that would lay
/// it across one of the rays `paths` (each from one end to the other) or over one of the
/// boxes `taken`, up to `at` (its end anchored there), whichever keeps it off those and inside
/// the panel; None where neither does.
fn beside_rays(
    p: &Panel,
    at: DVec2,
    s: &str,
    size: f64,
    paths: &[(DVec2, DVec2)],
    taken: &[(DVec2, DVec2)],
) -> Option<((DVec2, DVec2), bool)> {
    let width = text_width(s, size);
    let (left, right) = (p.origin.x + 4.0, p.origin.x + p.size.x - 4.0);
    [false, true].into_iter().find_map(|end| {
        let x0 = if end { at.x - width } else { at.x };
        let bx = (
            DVec2::new(x0, at.y - size),
            DVec2::new(x0 + width, at.y + 2.0),
        );
        let clear = !paths.iter().any(|&(a, b)| crosses(&bx, a, b))
            && !taken.iter().any(|t| overlap(t, &bx));
        (x0 >= left && x0 + width <= right && clear).then_some((bx, end))
    })
}

/// Whether the segment from `a` to `b` passes through the box.
fn crosses(&(min, max): &(DVec2, DVec2), a: DVec2, b: DVec2) -> bool {
    Frame { min, max }.clip(a, b).is_some()
}

/// Where the eye's name goes (the baseline's middle), and the box it covers: on the side away
/// from the image plane, clear of the dot also when it sits beside it; where a ray passes
/// there (one that comes straight back through the eye), above the dot, else below it.
fn eye_label(eye: DVec2, pix: DVec2, paths: &[(DVec2, DVec2)]) -> (DVec2, (DVec2, DVec2)) {
    let (size, half) = (13.0, text_width("eye", 13.0) / 2.0);
    let back = (eye - pix).normalize_or(DVec2::NEG_Y);
    let behind = eye + back * (16.0 + 8.0 * back.x.abs()) + DVec2::new(0.0, 4.0);
    let spots = [
        behind,
        eye - DVec2::new(0.0, 12.0),
        eye + DVec2::new(0.0, 22.0),
    ];
    let covers = |at: DVec2| (at - DVec2::new(half, size), at + DVec2::new(half, 2.0));
    let spot = (spots.iter().copied())
        .find(|&at| !paths.iter().any(|&(a, b)| crosses(&covers(at), a, b)))
        .unwrap_or(behind);
    (spot, covers(spot))
}

fn overlap(a: &(DVec2, DVec2), b: &(DVec2, DVec2)) -> bool {
    a.0.x < b.1.x && b.0.x < a.1.x && a.0.y < b.1.y && b.0.y < a.1.y
}

/// Where the image plane's label goes, and its anchor: beyond the end of the plane (as drawn,
/// the points of `hull`) that lies across the primary ray from the eye to the pixel, to the
/// right where the plane runs sideways and below where it runs up and down; the eye sits
/// behind the plane's middle, so the label stays clear of it and of the ray.
fn image_plane_label(hull: &[DVec2], eye: DVec2, pix: DVec2) -> (DVec2, &'static str) {
    let across = (pix - eye).normalize_or(DVec2::NEG_Y).perp();
    let sideways = across.x.abs() >= 0.5;
    let across = if (sideways && across.x < 0.0) || (!sideways && across.y < 0.0) {
        -across
    } else {
        across
    };
    let end = hull
        .iter()
        .copied()
        .max_by(|a, b| a.dot(across).total_cmp(&b.dot(across)))
        .unwrap_or(pix);
    if sideways {
        (end + across * 8.0 + DVec2::new(0.0, 4.0), "start")
    } else {
        (end + across * 8.0 + DVec2::new(0.0, 12.0), "middle")
    }
}

/// Two decimals are plenty for pixel coordinates.
fn r(x: f64) -> f64 {
    (x * 100.0).round() / 100.0
}

fn points(ps: &[DVec2]) -> String {
    ps.iter()
        .map(|p| format!("{},{}", r(p.x), r(p.y)))
        .collect::<Vec<_>>()
        .join(" ")
}

/// An arrowhead with its tip at `tip`, pointing along `dir`.
fn arrowhead(tip: DVec2, dir: DVec2, size: f64, color: &str) -> Polygon {
    let d = dir.normalize_or_zero();
    let side = d.perp() * size * 0.45;
    let back = tip - d * size;
    Polygon::new()
        .set("points", points(&[tip, back + side, back - side]))
        .set("fill", color)
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

    /// The scene cut by the view's plane, with the rays.
    fn section(&self, p: &Panel) -> Group {
        let d = self.drawing;
        let mut g = Group::new().set("clip-path", "url(#section)");
        let diag = p.frame.size().length();
        // Objects: silhouettes filled light grey, planes as lines, each named where its name
        // does not cover an earlier one (objects that coincide, as a lesson's CSG variants of
        // the same spheres do, are named by the first of them) and, a line higher if need be,
        // makes way for a light's. The names go on top of all the silhouettes.
        let lights: Vec<(DVec2, DVec2)> = (d.lights.iter())
            .filter_map(|l| self.light_spot(p, l))
            .map(|(c, name)| label_box(p, c + LIGHT_LABEL, &name, 14.0))
            .collect();
        let mut named: Vec<(DVec2, DVec2)> = vec![];
        let mut names = vec![];
        for o in &d.outlines {
            let name = if o.leaf == o.object {
                o.object.clone()
            } else {
                format!("{}/{}", o.object, o.leaf)
            };
            match &o.outline {
                Outline::Polygon(pts) if pts.len() >= 3 => {
                    let px: Vec<DVec2> = pts.iter().map(|q| p.px(*q)).collect();
                    g = g.add(
                        Polygon::new()
                            .set("points", points(&px))
                            .set("fill", FILL)
                            .set("fill-opacity", 0.7)
                            .set("stroke", OUTLINE)
                            .set("stroke-width", 1.5),
                    );
                }
                Outline::Polygon(pts) if pts.len() == 2 => {
                    g = g.add(line(p.px(pts[0]), p.px(pts[1]), OUTLINE, 3.0));
                }
                Outline::Line { point, dir } => {
                    let (a, b) = (*point - *dir * 4.0 * diag, *point + *dir * 4.0 * diag);
                    if let Some((a, b)) = p.frame.clip(a, b) {
                        g = g.add(line(p.px(a), p.px(b), OUTLINE, 3.0));
                    }
                }
                _ => {}
            }
            let anchor = match &o.outline {
                Outline::Line { point, dir } => {
                    // Near where the line enters the frame on the left.
                    let (a, b) = (*point - *dir * 4.0 * diag, *point + *dir * 4.0 * diag);
                    match p.frame.clip(a, b) {
                        Some((a, b)) => {
                            let left = if a.x <= b.x { a } else { b };
                            let right = if a.x <= b.x { b } else { a };
                            left + (right - left) * 0.04
                        }
                        None => continue,
                    }
                }
                o => o.anchor(),
            };
            let width = text_width(&name, 14.0);
            let covers = |at: DVec2| (at - DVec2::new(0.0, 14.0), at + DVec2::new(width, 2.0));
            let mut at = p.px(anchor) + DVec2::new(4.0, -6.0);
            // Inside the panel: a name at its right edge reads up to it.
            at.x = at.x.min(p.origin.x + p.size.x - 4.0 - width);
            if lights.iter().any(|b| overlap(b, &covers(at))) {
                at.y -= 16.0;
            }
            let taken = lights.iter().chain(&named).any(|b| overlap(b, &covers(at)));
            if !taken {
                named.push(covers(at));
                names.push(text(at, &name, 14.0, OUTLINE).set("font-style", "italic"));
            }
        }
        for name in names {
            g = g.add(name);
        }
        // The eye, the image plane and the pixel on it; the eye's name waits for the rays
        // (`eye_label` keeps it off them).
        let mut eye_dot = None;
        if let Some(e) = &d.eye {
            let corners: Vec<DVec2> = e.image_plane.iter().map(|q| p.px(d.at(*q))).collect();
            let hull = super::outline::hull(corners);
            if hull.len() >= 3 {
                g = g.add(
                    Polygon::new()
                        .set("points", points(&hull))
                        .set("fill", "none")
                        .set("stroke", "#888888")
                        .set("stroke-width", 1.5)
                        .set("stroke-dasharray", "5 3"),
                );
            } else if hull.len() == 2 {
                g = g.add(line(hull[0], hull[1], "#888888", 2.0).set("stroke-dasharray", "5 3"));
            }
            let eye = p.px(d.at(e.at));
            let pix = p.px(d.at(e.pixel));
            let (at, anchor) = image_plane_label(&hull, eye, pix);
            g = g.add(text(at, "image plane", 12.0, "#666666").set("text-anchor", anchor));
            eye_dot = Some((eye, pix));
            g = g.add(dot(eye, 5.0, INK));
            g = g.add(
                Rectangle::new()
                    .set("x", r(pix.x - 3.0))
                    .set("y", r(pix.y - 3.0))
                    .set("width", 6)
                    .set("height", 6)
                    .set("fill", "#888888"),
            );
        }
        // Lights.
        for l in &d.lights {
            g = self.light(g, p, l);
        }
        // Rays: shadow rays first, then by depth, so the ray a label belongs to is on top.
        let mut order: Vec<usize> = (0..d.segments.len()).collect();
        order.sort_by_key(|&i| {
            let s = &d.segments[i];
            (
                !matches!(s.kind, SegKind::ShadowClear | SegKind::ShadowBlocked),
                s.depth,
            )
        });
        let labelled = d.segments.len() <= 40;
        let mut labels = vec![];
        // The objects' and lights' names are there first: a ray's label keeps off them.
        let mut taken: Vec<(DVec2, DVec2)> = named.iter().chain(&lights).copied().collect();
        // Every ray's ends on the page: a label keeps off all of them where it can.
        let paths: Vec<(DVec2, DVec2)> = (d.segments.iter())
            .map(|s| {
                let (a, b) = d.ends(s, &p.frame);
                (p.px(a), p.px(b))
            })
            .collect();
        if let Some((eye, pix)) = eye_dot {
            let (at, bx) = eye_label(eye, pix, &paths);
            // Inside the panel, where the eye sits at its edge.
            let half = (bx.1.x - bx.0.x) / 2.0;
            let inside =
                at.x.clamp(p.origin.x + 4.0 + half, p.origin.x + p.size.x - 4.0 - half);
            let (at, bx) = (
                DVec2::new(inside, at.y),
                (
                    bx.0 + DVec2::new(inside - at.x, 0.0),
                    bx.1 + DVec2::new(inside - at.x, 0.0),
                ),
            );
            taken.push(bx);
            labels.push(text(at, "eye", 13.0, INK).set("text-anchor", "middle"));
        }
        for i in order {
            let s = &d.segments[i];
            let (pa, pb) = paths[i];
            let color = ray_color(s.kind);
            let shadow = matches!(s.kind, SegKind::ShadowClear | SegKind::ShadowBlocked);
            let width = match s.kind {
                SegKind::Primary => 3.0,
                SegKind::ShadowClear | SegKind::ShadowBlocked => 1.6,
                _ => 2.4,
            };
            g = g.add(line(pa, pb, &color, width));
            let dir = pb - pa;
            if dir.length() > 12.0 {
                // The arrow in the middle of a ray that ends, near the edge of one that does not.
                let at = if s.to.is_some() { 0.55 } else { 0.8 };
                g = g.add(arrowhead(
                    pa + dir * at,
                    dir,
                    if shadow { 9.0 } else { 12.0 },
                    &color,
                ));
            }
            if s.kind == SegKind::ShadowBlocked {
                // A cross where the blocker stops it.
                let k = 5.0;
                g = g
                    .add(line(
                        pb + DVec2::new(-k, -k),
                        pb + DVec2::new(k, k),
                        &color,
                        2.0,
                    ))
                    .add(line(
                        pb + DVec2::new(-k, k),
                        pb + DVec2::new(k, -k),
                        &color,
                        2.0,
                    ));
            }
            if let Some((hit, n)) = s.normal {
                let tip = d.at(hit + n * 0.07 * diag);
                let (ph, pt) = (p.px(d.at(hit)), p.px(tip));
                if (pt - ph).length() > 4.0 {
                    g = g
                        .add(line(ph, pt, NORMAL, 1.6).set("stroke-dasharray", "5 4"))
                        .add(
                            text(pt + DVec2::new(3.0, -3.0), "n", 12.0, NORMAL)
                                .set("font-style", "italic"),
                        );
                }
                g = g.add(dot(ph, 3.2, INK));
            }
            let room = if s.kind == SegKind::Primary {
                30.0
            } else {
                60.0
            };
            if labelled && dir.length() > room && (!shadow || d.segments.len() <= 16) {
                let along = match (shadow, s.to.is_some()) {
                    (true, _) => 0.25,
                    (false, true) => 0.5,
                    (false, false) => 0.35,
                };
                let mid = pa + dir * along;
                let off = dir.perp().normalize_or_zero() * 10.0;
                let mut label = s.label();
                if s.kind == SegKind::Missed {
                    label = format!("{label} (background)");
                }
                // Above the ray, else below it: off every ray where it can be, else off its
                // own; where both spots would cover another label (or a name), the same a
                // quarter of the ray nearer either end; left out where none is free.
                let above = if off.y > 0.0 { -off } else { off };
                let beside = |mid: DVec2| [mid + above, mid - above + DVec2::new(0.0, 10.0)];
                let spots = beside(mid);
                let free = |spots: &[DVec2], paths: &[(DVec2, DVec2)]| {
                    spots.iter().find_map(|&at| {
                        let (bx, end) = beside_rays(p, at, &label, 12.0, paths, &taken)?;
                        Some((at, bx, end))
                    })
                };
                let anywhere = |spots: &[DVec2]| {
                    spots.iter().find_map(|&at| {
                        let bx = label_box(p, at, &label, 12.0);
                        (!taken.iter().any(|b| overlap(b, &bx))).then_some((at, bx, false))
                    })
                };
                let further: Vec<DVec2> = [along + 0.25, along - 0.25]
                    .into_iter()
                    .filter(|t| (0.1..=0.9).contains(t))
                    .flat_map(|t| beside(pa + dir * t))
                    .collect();
                let place = free(&spots, &paths)
                    .or_else(|| free(&spots, &[(pa, pb)]))
                    .or_else(|| anywhere(&spots))
                    .or_else(|| free(&further, &[(pa, pb)]))
                    .or_else(|| anywhere(&further));
                if let Some((at, bx, end)) = place {
                    taken.push(bx);
                    let t = label_in(p, at, &label, 12.0, &color);
                    labels.push(if end { t.set("text-anchor", "end") } else { t });
                }
            }
        }
        for t in labels {
            g = g.add(t);
        }
        g
    }

    /// Where a light at a point is drawn, and its name there (one off the figure is drawn at
    /// the edge, towards it, and says so).
    fn light_spot(&self, p: &Panel, l: &super::drawing::LightMark) -> Option<(DVec2, String)> {
        let q = self.drawing.at(l.at?);
        if p.frame.contains(q) {
            return Some((p.px(q), l.name.clone()));
        }
        let centre = p.frame.center();
        let edge = p.frame.exit(centre, q - centre);
        let inward = (centre - edge).normalize_or_zero() * 0.03 * p.frame.size().length();
        Some((p.px(edge + inward), format!("{} (off the figure)", l.name)))
    }

    fn light(&self, g: Group, p: &Panel, l: &super::drawing::LightMark) -> Group {
        let d = self.drawing;
        let sun = "#f2b705";
        if let Some((c, name)) = self.light_spot(p, l) {
            let mut g = g;
            for k in 0..8 {
                let a = k as f64 * std::f64::consts::TAU / 8.0;
                let u = DVec2::new(a.cos(), a.sin());
                g = g.add(line(c + u * 9.0, c + u * 14.0, sun, 2.0));
            }
            return g
                .add(dot(c, 7.0, sun).set("stroke", "#b07d00"))
                .add(label_in(p, c + LIGHT_LABEL, &name, 14.0, INK).set("font-weight", "bold"));
        }
        let Some(dir) = l.direction else {
            return g;
        };
        // Parallel arrows from far away, entering near the corner the light comes from.
        let v = d.view.project(dir).normalize_or_zero();
        if v == DVec2::ZERO {
            return g.add(text(
                p.origin + DVec2::new(8.0, 18.0),
                &format!("{}: along the view", l.name),
                13.0,
                INK,
            ));
        }
        let centre = p.frame.center();
        let size = p.frame.size().length();
        let from_edge = p.frame.exit(centre, -v) + v * 0.02 * size;
        let mut g = g;
        for k in [-1.0, 0.0, 1.0] {
            let start = from_edge + v.perp() * k * 0.035 * size;
            let end = start + v * 0.12 * size;
            let (a, b) = (p.px(start), p.px(end));
            g = g
                .add(line(a, b, sun, 2.5))
                .add(arrowhead(b, b - a, 10.0, sun));
        }
        let at = p.px(from_edge + v * 0.06 * size + v.perp() * 0.07 * size);
        g.add(
            label_in(p, at, &format!("{} (far away)", l.name), 14.0, INK)
                .set("font-weight", "bold"),
        )
    }

    /// The ray tree as a graph in the rectangle at `origin` of `size`.
    fn graph(&self, origin: DVec2, area: DVec2) -> Group {
        let size = area;
        let nodes = layout(self.tree, Some(self.scene));
        let mut g = Group::new().add(
            text(origin + DVec2::new(0.0, 12.0), "ray tree", 14.0, INK).set("font-weight", "bold"),
        );
        let cols = nodes.iter().map(|n| n.pos.x).fold(0.0, f64::max) + 1.0;
        let rows = nodes.iter().map(|n| n.pos.y).fold(0.0, f64::max) + 1.0;
        let top = origin.y + 30.0;
        let col_w = size.x / cols;
        let row_h = ((size.y - 30.0) / rows).min(110.0);
        let chars = nodes
            .iter()
            .map(|n| {
                node_lines(n)
                    .iter()
                    .map(|l| l.chars().count())
                    .max()
                    .unwrap_or(1)
            })
            .max()
            .unwrap_or(1) as f64;
        // Small enough that the widest node fits its column, and that a row holds a node's
        // three lines (3.75 em and 6 px of box) and, in the gap below, an edge's label.
        let font = (0.92 * col_w / (0.62 * chars))
            .min((row_h - 6.0) / 5.1)
            .clamp(6.0, 13.0);
        let box_w = |n: &GraphNode| {
            let c = node_lines(n)
                .iter()
                .map(|l| l.chars().count())
                .max()
                .unwrap_or(1) as f64;
            (c * 0.62 * font + 8.0).min(col_w * 0.98).max(font * 4.0)
        };
        // A short figure with a deep tree keeps a node's first lines, as many as a row holds;
        // one that cannot hold a line a row says so instead of drawing boxes over each other.
        let Some(kept) = (1..=3usize)
            .rev()
            .find(|&k| k as f64 * font * 1.25 + 6.0 <= row_h)
        else {
            return g
                .add(text(
                    origin + DVec2::new(0.0, 32.0),
                    &format!("{rows} levels: too deep"),
                    11.0,
                    INK,
                ))
                .add(text(
                    origin + DVec2::new(0.0, 46.0),
                    "for this height",
                    11.0,
                    INK,
                ));
        };
        let box_h = kept as f64 * font * 1.25 + 6.0;
        let centre = |n: &GraphNode| {
            DVec2::new(
                origin.x + (n.pos.x + 0.5) * col_w,
                top + n.pos.y * row_h + box_h / 2.0,
            )
        };
        // Edges first, under the boxes, with their coefficients.
        for n in &nodes {
            let Some(pi) = n.parent else { continue };
            let (a, b) = (centre(&nodes[pi]), centre(n));
            let (a, b) = (
                a + DVec2::new(0.0, box_h / 2.0),
                b - DVec2::new(0.0, box_h / 2.0),
            );
            let color = node_color(self.tree, n);
            g = g.add(line(a, b, &color, 1.4));
            if let Some(e) = &n.edge {
                // Centred in the gap between the boxes (a baseline 0.35 em below the middle).
                let size = font * 0.95;
                let mid = (a + b) / 2.0 + DVec2::new(3.0, 0.35 * size);
                // Kept inside the graph's right edge.
                let right = origin.x + area.x - text_width(e, size);
                let mid = DVec2::new(mid.x.min(right), mid.y);
                g = g.add(text(mid, e, size, "#444444"));
            }
        }
        for n in &nodes {
            let c = centre(n);
            let bw = box_w(n);
            let color = node_color(self.tree, n);
            let shadow = n.kind == RayKind::Shadow;
            let mut rect = Rectangle::new()
                .set("x", r(c.x - bw / 2.0))
                .set("y", r(c.y - box_h / 2.0))
                .set("width", r(bw))
                .set("height", r(box_h))
                .set("rx", if shadow { box_h / 2.0 } else { 5.0 })
                .set("fill", "white")
                .set("stroke", color.as_str())
                .set("stroke-width", if n.path.is_empty() { 2.5 } else { 1.6 });
            if n.untraced {
                rect = rect
                    .set("stroke-dasharray", "4 3")
                    .set("stroke-opacity", 0.6);
            }
            g = g.add(rect);
            // Where the box is narrower than a line (its column is), the line is cut.
            let most = ((bw - 4.0) / (0.62 * font)).floor().max(1.0) as usize;
            for (i, l) in node_lines(n).iter().take(kept).enumerate() {
                let y = c.y - box_h / 2.0 + 3.0 + font * (1.0 + 1.25 * i as f64);
                let l = if l.chars().count() > most {
                    l.chars().take(most - 1).chain(['…']).collect()
                } else {
                    l.clone()
                };
                let t = text(
                    DVec2::new(c.x, y),
                    &l,
                    font,
                    if i == 0 { color.as_str() } else { INK },
                )
                .set("text-anchor", "middle")
                .set("stroke-width", 0);
                g = g.add(if i == 0 {
                    t.set("font-weight", "bold")
                } else {
                    t
                });
            }
        }
        g
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

/// A graph node's three lines: the kind, what it reached, the value.
fn node_lines(n: &GraphNode) -> [String; 3] {
    let (kind, to) = n
        .title
        .split_once(" → ")
        .map_or((n.title.clone(), String::new()), |(a, b)| {
            (a.to_string(), b.to_string())
        });
    [kind, format!("→ {to}"), n.value.clone()]
}

fn node_color(root: &RayNode, n: &GraphNode) -> String {
    ray_color(super::node_at(root, &n.path).map_or(SegKind::Missed, SegKind::of))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The box "image plane" covers at 12 px, from where `image_plane_label` puts it.
    fn covered(at: DVec2, anchor: &str) -> (DVec2, DVec2) {
        let width = text_width("image plane", 12.0);
        let x0 = if anchor == "middle" {
            at.x - width / 2.0
        } else {
            at.x
        };
        (
            DVec2::new(x0, at.y - 12.0),
            DVec2::new(x0 + width, at.y + 2.0),
        )
    }

    fn distance_to_box(q: DVec2, (lo, hi): (DVec2, DVec2)) -> f64 {
        (q.clamp(lo, hi) - q).length()
    }

    fn panel() -> Panel {
        Panel::new(
            Frame {
                min: DVec2::ZERO,
                max: DVec2::new(10.0, 10.0),
            },
            DVec2::ZERO,
            DVec2::new(600.0, 600.0),
        )
    }

    /// Whether a point of the segment a–b, at every half pixel along it, lies in the box.
    fn sampled_through((lo, hi): (DVec2, DVec2), a: DVec2, b: DVec2) -> bool {
        let steps = (2.0 * (b - a).length()).ceil() as usize;
        (0..=steps).any(|k| {
            let q = a + (b - a) * (k as f64 / steps as f64);
            q.cmpge(lo).all() && q.cmple(hi).all()
        })
    }

    /// A label above a ray that rises to the right reads up to its spot (anchored at its end),
    /// one above a ray that falls reads on from it, one left of an upright ray reads up to it:
    /// either way the ray does not run through the label, and where the label read on from
    /// its spot the rising and upright rays would.
    #[test]
    fn a_rays_label_keeps_off_the_ray() {
        let p = panel();
        let label = "primary I = 0.282";
        for (a, b, turned) in [
            (DVec2::new(130.0, 510.0), DVec2::new(560.0, 385.0), true),
            (DVec2::new(130.0, 385.0), DVec2::new(560.0, 510.0), false),
            (DVec2::new(300.0, 580.0), DVec2::new(310.0, 20.0), true),
        ] {
            let mid = (a + b) / 2.0;
            let off = (b - a).perp().normalize() * 10.0;
            let above = if off.y > 0.0 { -off } else { off };
            let naive = label_box(&p, mid + above, label, 12.0);
            assert_eq!(sampled_through(naive, a, b), turned, "{a} → {b}");
            let (bx, end) =
                beside_rays(&p, mid + above, label, 12.0, &[(a, b)], &[]).expect("room");
            assert_eq!(end, turned, "{a} → {b}");
            assert!(!sampled_through(bx, a, b), "{a} → {b}: {bx:?}");
        }
        let square = (DVec2::new(0.0, 0.0), DVec2::new(10.0, 10.0));
        assert!(crosses(
            &square,
            DVec2::new(-5.0, 5.0),
            DVec2::new(15.0, 5.0)
        ));
        assert!(!crosses(
            &square,
            DVec2::new(-5.0, 15.0),
            DVec2::new(15.0, 11.0)
        ));
    }

    /// Eye, pixel and image plane as the top view of a lesson draws them (the eye a few pixels
    /// behind a plane that runs sideways), as a side view does (the plane upright, the ray
    /// level), and tilted: the label keeps clear of the eye's dot (radius 5) and of the primary
    /// ray, from the eye through the pixel and on.
    #[test]
    fn the_image_plane_label_stays_clear_of_the_eye_and_the_ray() {
        let cases = [
            // Plane sideways (its left end a little lower), the ray going up the page, the eye
            // 13 px behind the plane.
            (
                [DVec2::new(405.0, 546.0), DVec2::new(425.0, 544.0)],
                DVec2::new(415.0, 558.0),
                DVec2::new(414.0, 545.0),
            ),
            // Plane upright, the ray level and to the right.
            (
                [DVec2::new(118.0, 398.0), DVec2::new(118.0, 444.0)],
                DVec2::new(58.0, 410.0),
                DVec2::new(118.0, 421.0),
            ),
            // Tilted by 40°, the ray going down to the left.
            (
                [DVec2::new(300.0, 300.0), DVec2::new(330.0, 275.0)],
                DVec2::new(330.0, 305.0),
                DVec2::new(315.0, 287.5),
            ),
        ];
        for (k, (plane, eye, pix)) in cases.into_iter().enumerate() {
            let (at, anchor) = image_plane_label(&plane, eye, pix);
            let bx = covered(at, anchor);
            assert!(
                distance_to_box(eye, bx) > 5.0,
                "case {k}: label at {at} ({anchor}) covers the eye at {eye}"
            );
            let dir = (pix - eye).normalize();
            for step in 0..200 {
                let q = eye + dir * step as f64;
                assert!(
                    distance_to_box(q, bx) > 1.0,
                    "case {k}: label at {at} ({anchor}) lies on the ray at {q}"
                );
            }
        }
    }
}
