//! The ray diagram pane: the picked pixel's rays in the scene, drawn with braille on a ratatui
//! canvas (the geometry is the `diagram` module's, shared with `raytree diagram`). Objects are
//! grey outlines, rays coloured by kind, normals dashed, the selected ray in yellow; the BVH
//! boxes its search visited under them when `b` is on; a legend on the last line.

use glam::DVec2;
use ratatui::layout::{Alignment, Rect};
use ratatui::style::{Color, Modifier, Style};
use ratatui::symbols::Marker;
use ratatui::text::{Line, Span};
use ratatui::widgets::canvas::{Canvas, Context, Line as CLine, Points};
use ratatui::widgets::Paragraph;
use ratatui::Frame;

use super::{pane, themed};
use crate::diagram::outline::Outline;
use crate::diagram::{Drawing, Frame as View2, SegKind};
use crate::tui::app::{App, Focus};
use crate::tui::state::diagram::visited;

/// The terminal colour of a kind of ray (the hues of the figures; the tree pane's kinds).
pub fn kind_color(k: SegKind) -> Color {
    match k {
        SegKind::Primary => Color::LightBlue,
        SegKind::Reflection => Color::Cyan,
        SegKind::Refraction => Color::Magenta,
        SegKind::ShadowClear => Color::Yellow,
        SegKind::ShadowBlocked => Color::Red,
        SegKind::Missed => Color::DarkGray,
    }
}

const SELECTED: Color = Color::LightYellow;
const NORMAL: Color = Color::Green;
const OUTLINE: Color = Color::Gray;

/// The drawing of the picked pixel's tree as shown now (the level being stepped, framed
/// around the whole tree), if there is a scene.
pub fn drawing(app: &App) -> Option<Drawing> {
    let scene = app.file.scene.as_deref()?;
    let shown = app.tree.shown_tree()?;
    let whole = app.tree.full_tree().unwrap_or(shown);
    Some(Drawing::new(
        scene,
        shown,
        whole,
        app.diagram.view,
        Some(app.tree.pixel()),
    ))
}

/// Draws the ray diagram pane of the picked pixel's tree into `area` ("no scene" without one).
pub fn draw(f: &mut Frame, app: &App, area: Rect) {
    let Some(d) = drawing(app) else {
        f.render_widget(
            Paragraph::new("no scene").block(pane(app, " rays ", area, Some(Focus::Diagram))),
            area,
        );
        return;
    };
    let zoom = if app.diagram.zoom == 1.0 {
        String::new()
    } else {
        format!(" · zoom ×{:.2}", app.diagram.zoom)
    };
    let title = format!(" rays · {}{zoom} ", d.view.caption());
    let mut block = pane(app, &title, area, Some(Focus::Diagram));
    // The BVH boxes the selected ray's search visited.
    let boxes = app.diagram.bvh.then(|| {
        let scene = app.file.scene.as_deref().expect("a drawing has a scene");
        let node = app.tree.selected_node().expect("a drawing has a tree");
        visited(scene, node)
    });
    if let Some(v) = &boxes {
        let entered = v.boxes.iter().filter(|b| b.1).count();
        let note = if v.total == 0 {
            " no BVH: every object tested ".to_string()
        } else if area.width < 70 {
            format!(
                " BVH {}/{} boxes, {entered} entered ",
                v.boxes.len(),
                v.total
            )
        } else {
            let tested = v.objects_tested;
            let s = if tested == 1 { "" } else { "s" };
            format!(
                " BVH: {} of {} boxes visited, {entered} entered · {tested} object{s} tested ",
                v.boxes.len(),
                v.total,
            )
        };
        block = block.title_bottom(Line::from(note).alignment(Alignment::Right));
    }
    let body = block.inner(area);
    f.render_widget(block, area);
    if body.width < 4 || body.height < 3 {
        return;
    }
    let canvas_area = Rect::new(body.x, body.y, body.width, body.height - 1);
    let legend_area = Rect::new(body.x, body.bottom() - 1, body.width, 1);
    let frame = app.diagram.frame(&d, canvas_area.width, canvas_area.height);
    // One character's width and height, in the drawing's units.
    let cell = frame.size() / DVec2::new(canvas_area.width as f64, canvas_area.height as f64);
    let selected = app.tree.selected().to_vec();
    let color = |c: Color| {
        if app.color == crate::render::preview::ColorMode::Ascii {
            Color::Reset
        } else {
            c
        }
    };
    let canvas = Canvas::default()
        .marker(Marker::Braille)
        .x_bounds([frame.min.x, frame.max.x])
        .y_bounds([frame.min.y, frame.max.y])
        .paint(|ctx| {
            paint(ctx, &d, &frame, cell, &selected, boxes.as_ref(), &color);
        });
    f.render_widget(canvas, canvas_area);
    f.render_widget(Paragraph::new(legend(app, legend_area.width)), legend_area);
}

fn seg(ctx: &mut Context, a: DVec2, b: DVec2, c: Color) {
    ctx.draw(&CLine::new(a.x, a.y, b.x, b.y, c));
}

/// A dashed line: dashes of a fortieth of the frame, with gaps as long.
fn dashed(ctx: &mut Context, a: DVec2, b: DVec2, frame: &View2, c: Color) {
    let len = (b - a).length();
    let dash = frame.size().length() / 40.0;
    if len <= 0.0 || dash <= 0.0 {
        return;
    }
    let n = (len / dash).ceil() as usize;
    for i in (0..n).step_by(2) {
        let t0 = i as f64 / n as f64;
        let t1 = ((i + 1) as f64 / n as f64).min(1.0);
        seg(ctx, a + (b - a) * t0, a + (b - a) * t1, c);
    }
}

fn paint(
    ctx: &mut Context,
    d: &Drawing,
    frame: &View2,
    cell: DVec2,
    selected: &[usize],
    boxes: Option<&crate::scene::Visited>,
    color: &dyn Fn(Color) -> Color,
) {
    let diag = frame.size().length();
    // Objects.
    for o in &d.outlines {
        match &o.outline {
            Outline::Polygon(p) if p.len() >= 2 => {
                // Outlines far outside the frame cost nothing to skip.
                let (lo, hi) = o.outline.bounds().expect("a polygon has bounds");
                if hi.x < frame.min.x
                    || lo.x > frame.max.x
                    || hi.y < frame.min.y
                    || lo.y > frame.max.y
                {
                    continue;
                }
                for i in 0..p.len() {
                    let j = (i + 1) % p.len();
                    if p.len() == 2 && j == 0 {
                        break;
                    }
                    seg(ctx, p[i], p[j], color(OUTLINE));
                }
            }
            Outline::Line { point, dir } => {
                seg(
                    ctx,
                    *point - *dir * 4.0 * diag,
                    *point + *dir * 4.0 * diag,
                    color(OUTLINE),
                );
            }
            _ => {}
        }
    }
    // The BVH boxes: entered green, rejected red.
    if let Some(v) = boxes {
        for (b, entered) in &v.boxes {
            let (lo, hi) = (d.at(b.min), d.at(b.max));
            let c = color(if *entered { Color::Green } else { Color::Red });
            let (a, bb, cc, dd) = (lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y));
            seg(ctx, a, bb, c);
            seg(ctx, bb, cc, c);
            seg(ctx, cc, dd, c);
            seg(ctx, dd, a, c);
        }
    }
    // The eye and the image plane.
    if let Some(e) = &d.eye {
        let corners: Vec<DVec2> = e.image_plane.iter().map(|p| d.at(*p)).collect();
        for i in 0..4 {
            seg(
                ctx,
                corners[i],
                corners[(i + 1) % 4],
                color(Color::DarkGray),
            );
        }
    }
    ctx.layer();
    // Rays, the shadow rays under the others; normals dashed.
    let mut order: Vec<_> = d.segments.iter().collect();
    order.sort_by_key(|s| {
        (
            !matches!(s.kind, SegKind::ShadowClear | SegKind::ShadowBlocked),
            s.depth,
        )
    });
    for s in &order {
        let (a, b) = d.ends(s, frame);
        seg(ctx, a, b, color(kind_color(s.kind)));
        if let Some((p, n)) = s.normal {
            let h = d.at(p);
            dashed(ctx, h, d.at(p + n * 0.08 * diag), frame, color(NORMAL));
        }
    }
    ctx.layer();
    // The selected ray on top, with its hit point.
    if let Some(s) = d.segment(selected) {
        let (a, b) = d.ends(s, frame);
        seg(ctx, a, b, color(SELECTED));
        ctx.draw(&Points {
            coords: &[(b.x, b.y)],
            color: color(SELECTED),
        });
    }
    // Names: objects, lights, the eye.
    let dim = Style::new()
        .fg(color(OUTLINE))
        .add_modifier(Modifier::ITALIC);
    // The cells a name printed at `at` covers: its row and its first and last column.
    let cells = |at: DVec2, name: &str| {
        let col = ((at.x - frame.min.x) / cell.x).floor() as i64;
        let row = ((frame.max.y - at.y) / cell.y).floor() as i64;
        (row, col, col + name.chars().count() as i64 - 1)
    };
    let clash = |a: (i64, i64, i64), b: &(i64, i64, i64)| a.0 == b.0 && a.1 <= b.2 && b.1 <= a.2;
    // Lights' names are printed last, on top; an object's name does not go under one, nor over
    // an earlier object's (objects that coincide are named by the first of them).
    let mut printed: Vec<(i64, i64, i64)> = (d.lights.iter())
        .filter_map(|l| Some((d.at(l.at?), l)))
        .filter(|(q, _)| frame.contains(*q))
        .map(|(q, l)| cells(q, &format!("☀{}", l.name)))
        .collect();
    let mut named: Vec<&str> = vec![];
    // Hundreds of names would hide the drawing.
    let few = d.outlines.len() <= 24;
    for o in d.outlines.iter().filter(|_| few) {
        if named.contains(&o.object.as_str()) {
            continue;
        }
        let at = match &o.outline {
            Outline::Line { point, dir } => {
                match frame.clip(*point - *dir * 4.0 * diag, *point + *dir * 4.0 * diag) {
                    Some((a, b)) => {
                        if a.x <= b.x {
                            a
                        } else {
                            b
                        }
                    }
                    None => continue,
                }
            }
            other => other.anchor(),
        };
        let covers = cells(at, &o.object);
        if frame.contains(at) && !printed.iter().any(|p| clash(covers, p)) {
            printed.push(covers);
            named.push(&o.object);
            ctx.print(at.x, at.y, Span::styled(o.object.clone(), dim));
        }
    }
    let bright = Style::new()
        .fg(color(Color::LightYellow))
        .add_modifier(Modifier::BOLD);
    for l in &d.lights {
        if let Some(p) = l.at {
            let q = d.at(p);
            if frame.contains(q) {
                ctx.print(q.x, q.y, Span::styled(format!("☀{}", l.name), bright));
            }
        } else if let Some(dir) = l.direction {
            // Far away: named where its light comes in.
            let v = d.view.project(dir);
            if v.length() > 0.0 {
                let at = frame.exit(frame.center(), -v);
                let inside = at + (frame.center() - at) * 0.1;
                ctx.print(
                    inside.x,
                    inside.y,
                    Span::styled(format!("☀{}", l.name), bright),
                );
            }
        }
    }
    if let Some(e) = &d.eye {
        let q = d.at(e.at);
        if frame.contains(q) {
            ctx.print(
                q.x,
                q.y,
                Span::styled("◉eye", Style::new().add_modifier(Modifier::BOLD)),
            );
        }
    }
}

/// The legend: each kind in its colour, the words shortened when the line is narrow.
fn legend(app: &App, width: u16) -> Line<'static> {
    let full: usize = SegKind::ALL
        .iter()
        .map(|k| k.name().len() + 3)
        .sum::<usize>()
        + 9;
    let short = width as usize <= full;
    let mut spans = vec![];
    for k in SegKind::ALL {
        let word = if short { k.short() } else { k.name() };
        spans.push(Span::styled(
            format!("━{word} "),
            themed(app, Style::new().fg(kind_color(k))),
        ));
    }
    spans.push(Span::styled(
        if short {
            "┄n".to_string()
        } else {
            "┄normal".to_string()
        },
        themed(app, Style::new().fg(NORMAL)),
    ));
    Line::from(spans)
}
