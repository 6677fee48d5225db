//! The left panel of the `raytree diagram` figure: the scene cut by the plane of the view,
//! drawn in layers. First the objects' silhouettes and names, then the eye with the image
//! plane, then the lights, then the rays with their normals, and on top the labels.

use glam::DVec2;
use svg::node::element::{Group, Polygon, Rectangle, Text};

use super::drawing::{Eye, LightMark};
use super::figure::Figure;
use super::frame::Frame;
use super::ink::{arrowhead, dot, line, points, r, ray_color, text, text_width, Panel};
use super::ink::{FILL, INK, NORMAL, OUTLINE};
use super::labels::Box2;
use super::labels::{anchor_in, anchored, into_panel};
use super::labels::{beside_rays, crosses, eye_label, image_plane_label};
use super::labels::{label_box, label_in, overlap};
use super::outline::{LeafOutline, Outline};
use super::rays::{SegKind, Segment};

/// Where a light's name goes from its centre.
const LIGHT_LABEL: DVec2 = DVec2::new(14.0, -10.0);

/// How far a directional light's arrow reaches past its ends, in pixels: its arrowhead's
/// half width (4.5) and more than its round cap (1.25).
const ARROW_REACH: f64 = 5.0;

/// A light far away (a directional light) as drawn: three parallel arrows coming in from the
/// edge its light comes from, and its name beside them, moved into the panel together.
struct FarLight {
    arrows: Vec<(DVec2, DVec2)>,
    name: String,
    /// The name's anchor, and whether it is the name's end.
    at: DVec2,
    end: bool,
    /// The box the name covers.
    covers: Box2,
}

/// The eye and the pixel on the image plane, as drawn.
#[derive(Clone, Copy)]
struct EyeDot {
    eye: DVec2,
    pixel: DVec2,
}

impl Figure<'_> {
    /// The scene cut by the view's plane, with the rays.
    pub(super) fn section(&self, p: &Panel) -> Group {
        let d = self.drawing;
        let g = Group::new().set("clip-path", "url(#section)");
        // Every ray's ends on the page: a label keeps off all of them where it can.
        let paths: Vec<(DVec2, DVec2)> = (d.segments.iter())
            .map(|s| {
                let (a, b) = d.ends(s, &p.frame);
                (p.px(a), p.px(b))
            })
            .collect();
        // The lights' names are placed first: the objects' names make way for them.
        let far: Vec<Option<FarLight>> = (d.lights.iter())
            .map(|l| self.far_light(p, l, &paths))
            .collect();
        let lights: Vec<Box2> = (d.lights.iter())
            .filter_map(|l| self.light_spot(p, l))
            .map(|(c, name)| label_box(p, c + LIGHT_LABEL, &name, 14.0))
            .chain(far.iter().flatten().map(|f| f.covers))
            .collect();
        let (g, named) = self.objects(g, p, &lights);
        let (mut g, eye) = match &d.eye {
            Some(e) => {
                let (g, eye) = self.eye(g, p, e);
                (g, Some(eye))
            }
            None => (g, None),
        };
        for (l, far) in d.lights.iter().zip(&far) {
            g = self.light(g, p, l, far.as_ref());
        }
        // The objects' and lights' names are there first: a ray's label keeps off them.
        let taken = named.into_iter().chain(lights).collect();
        self.rays(g, p, eye, &paths, taken)
    }

    /// Objects: silhouettes filled light grey, planes as lines, each named where its name
    /// does not cover an earlier one (objects that coincide, as a lesson's CSG variants of
    /// the same spheres do, are named by the first of them) and, a line higher if need be,
    /// makes way for a light's. The names go on top of all the silhouettes; the boxes they
    /// cover are returned.
    fn objects(&self, mut g: Group, p: &Panel, lights: &[Box2]) -> (Group, Vec<Box2>) {
        let mut named: Vec<Box2> = vec![];
        let mut names = vec![];
        for o in &self.drawing.outlines {
            g = silhouette(g, p, &o.outline);
            let Some(anchor) = name_anchor(p, &o.outline) else {
                continue;
            };
            let name = object_name(o);
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
        (g, named)
    }

    /// The eye, the image plane and the pixel on it. The eye's name waits for the rays
    /// (`eye_label` keeps it off them).
    fn eye(&self, mut g: Group, p: &Panel, e: &Eye) -> (Group, EyeDot) {
        let d = self.drawing;
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
        let pixel = p.px(d.at(e.pixel));
        let (at, anchor) = image_plane_label(p, &hull, eye, pixel);
        g = g
            .add(text(at, "image plane", 12.0, "#666666").set("text-anchor", anchor))
            .add(dot(eye, 5.0, INK))
            .add(
                Rectangle::new()
                    .set("x", r(pixel.x - 3.0))
                    .set("y", r(pixel.y - 3.0))
                    .set("width", 6)
                    .set("height", 6)
                    .set("fill", "#888888"),
            );
        (g, EyeDot { eye, pixel })
    }

    /// The rays, shadow rays first, then by depth, so that the ray a label belongs to is on
    /// top; then, over all of them, the eye's name and the rays' labels, each kept off the
    /// boxes `taken` and off the labels placed before it.
    fn rays(
        &self,
        mut g: Group,
        p: &Panel,
        eye: Option<EyeDot>,
        paths: &[(DVec2, DVec2)],
        mut taken: Vec<Box2>,
    ) -> Group {
        let d = self.drawing;
        let mut order: Vec<usize> = (0..d.segments.len()).collect();
        order.sort_by_key(|&i| (!is_shadow(d.segments[i].kind), d.segments[i].depth));
        let labelled = d.segments.len() <= 40;
        let mut labels = vec![];
        if let Some(EyeDot { eye, pixel }) = eye {
            let (at, bx) = eye_label(eye, pixel, paths);
            // Inside the panel, where the eye sits at its edge.
            let half = (bx.1.x - bx.0.x) / 2.0;
            let inside =
                at.x.clamp(p.origin.x + 4.0 + half, p.origin.x + p.size.x - 4.0 - half);
            let shift = DVec2::new(inside - at.x, 0.0);
            taken.push((bx.0 + shift, bx.1 + shift));
            let at = DVec2::new(inside, at.y);
            labels.push(text(at, "eye", 13.0, INK).set("text-anchor", "middle"));
        }
        // What a label had best keep off: the rays, and the objects' outlines.
        let lines: Vec<(DVec2, DVec2)> = (paths.iter().copied())
            .chain(d.outlines.iter().flat_map(|o| edges(p, &o.outline)))
            .collect();
        for i in order {
            let s = &d.segments[i];
            g = self.ray(g, p, s, paths[i]);
            let few = !is_shadow(s.kind) || d.segments.len() <= 16;
            if labelled && few {
                if let Some((label, bx)) = ray_label(p, s, paths[i], &lines, &taken) {
                    taken.push(bx);
                    labels.push(label);
                }
            }
        }
        for t in labels {
            g = g.add(t);
        }
        g
    }

    /// One ray from `pa` to `pb` on the page: a line in its kind's colour with an arrowhead,
    /// a cross where a blocker stops a shadow ray, and the dashed normal at the point it hit.
    fn ray(&self, mut g: Group, p: &Panel, s: &Segment, (pa, pb): (DVec2, DVec2)) -> Group {
        let d = self.drawing;
        let color = ray_color(s.kind);
        let shadow = is_shadow(s.kind);
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
            let size = if shadow { 9.0 } else { 12.0 };
            g = g.add(arrowhead(pa + dir * at, dir, size, &color));
        }
        if s.kind == SegKind::ShadowBlocked {
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
            let tip = d.at(hit + n * 0.07 * p.frame.size().length());
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
        g
    }

    /// Where a light at a point is drawn, and its name there (one off the figure is drawn at
    /// the edge, on the first shadow ray that reaches it, else towards it from the figure's
    /// middle, and says so).
    fn light_spot(&self, p: &Panel, l: &LightMark) -> Option<(DVec2, String)> {
        let q = self.drawing.at(l.at?);
        if p.frame.contains(q) {
            return Some((p.px(q), l.name.clone()));
        }
        let d = self.drawing;
        let (from, toward) = match l.reached_by.map(|(a, b)| (d.at(a), d.at(b))) {
            Some((a, b)) if p.frame.contains(a) && a != b => (a, b),
            _ => (p.frame.center(), q),
        };
        let edge = p.frame.exit(from, toward - from);
        let inward = (from - edge).normalize_or_zero() * 0.03 * p.frame.size().length();
        Some((p.px(edge + inward), format!("{} (off the figure)", l.name)))
    }

    /// A light: a sun with its name where it has a place, else (a directional light, `far`)
    /// three parallel arrows coming in from far away.
    fn light(&self, g: Group, p: &Panel, l: &LightMark, far: Option<&FarLight>) -> Group {
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
        if let Some(far) = far {
            let mut g = g;
            for &(a, b) in &far.arrows {
                g = g
                    .add(line(a, b, sun, 2.5))
                    .add(arrowhead(b, b - a, 10.0, sun));
            }
            return g
                .add(anchored(far.at, far.end, &far.name, 14.0, INK).set("font-weight", "bold"));
        }
        match l.direction {
            // Along the view: no arrow shows which way it goes.
            Some(_) => g.add(text(
                p.origin + DVec2::new(8.0, 18.0),
                &format!("{}: along the view", l.name),
                13.0,
                INK,
            )),
            None => g,
        }
    }

    /// A directional light's arrows, entering near the corner the light comes from, and its
    /// name beside them, on the first side and at the first spot along them where the name
    /// lies across none of the rays `paths` (else where the first would have it). None for a
    /// light with a place, or one whose light travels along the view.
    fn far_light(&self, p: &Panel, l: &LightMark, paths: &[(DVec2, DVec2)]) -> Option<FarLight> {
        let d = self.drawing;
        if l.at.is_some() {
            return None;
        }
        let v = d.view.project(l.direction?).normalize_or_zero();
        if v == DVec2::ZERO {
            return None;
        }
        let centre = p.frame.center();
        let size = p.frame.size().length();
        let from_edge = p.frame.exit(centre, -v) + v * 0.02 * size;
        let arrows: Vec<(DVec2, DVec2)> = [-1.0, 0.0, 1.0]
            .into_iter()
            .map(|k| {
                let start = from_edge + v.perp() * k * 0.035 * size;
                (p.px(start), p.px(start + v * 0.12 * size))
            })
            .collect();
        let name = format!("{} (far away)", l.name);
        let placed = |along: f64, side: f64| {
            let at = p.px(from_edge + v * along * size + v.perp() * side * size);
            let (x, end) = anchor_in(p, at, &name, 14.0);
            let (mut lo, mut hi) = label_box(p, at, &name, 14.0);
            // Bold letters are about 0.64 em wide, not `label_box`'s 0.6: the name reaches
            // further from its anchor.
            let bold = 0.04 * 14.0 * name.chars().count() as f64;
            if end {
                lo.x -= bold;
            } else {
                hi.x += bold;
            }
            // Started at the frame's edge, the outer arrows and the name beside them can
            // reach past it, where the panel's clip would cut them: arrows and name move in
            // together, so that the name stays beside its arrows.
            let reach = DVec2::splat(ARROW_REACH);
            let all = (arrows.iter()).fold((lo, hi), |(lo, hi), &(a, b)| {
                (lo.min(a.min(b) - reach), hi.max(a.max(b) + reach))
            });
            let shift = into_panel(p, all, 4.0);
            (
                shift,
                DVec2::new(x, at.y) + shift,
                end,
                (lo + shift, hi + shift),
            )
        };
        let spots = [
            (0.06, 0.07),
            (0.06, -0.07),
            (0.0, 0.07),
            (0.0, -0.07),
            (0.12, 0.07),
            (0.12, -0.07),
        ];
        let clear = |covers: &Box2| !paths.iter().any(|&(a, b)| crosses(covers, a, b));
        let (shift, at, end, covers) = (spots.iter())
            .map(|&(along, side)| placed(along, side))
            .find(|(_, _, _, covers)| clear(covers))
            .unwrap_or_else(|| placed(spots[0].0, spots[0].1));
        Some(FarLight {
            arrows: (arrows.iter())
                .map(|&(a, b)| (a + shift, b + shift))
                .collect(),
            name,
            at,
            end,
            covers,
        })
    }
}

fn is_shadow(kind: SegKind) -> bool {
    matches!(kind, SegKind::ShadowClear | SegKind::ShadowBlocked)
}

/// An object's name as the figure writes it: the leaf's after the object's for a part of a
/// CSG object.
fn object_name(o: &LeafOutline) -> String {
    if o.leaf == o.object {
        o.object.clone()
    } else {
        format!("{}/{}", o.object, o.leaf)
    }
}

/// An object's outline: a filled polygon, a thick line where it is seen edge on, or (a plane)
/// a line across the frame.
fn silhouette(g: Group, p: &Panel, outline: &Outline) -> Group {
    match outline {
        Outline::Polygon(pts) if pts.len() >= 3 => {
            let px: Vec<DVec2> = pts.iter().map(|q| p.px(*q)).collect();
            g.add(
                Polygon::new()
                    .set("points", points(&px))
                    .set("fill", FILL)
                    .set("fill-opacity", 0.7)
                    .set("stroke", OUTLINE)
                    .set("stroke-width", 1.5),
            )
        }
        Outline::Polygon(pts) if pts.len() == 2 => {
            g.add(line(p.px(pts[0]), p.px(pts[1]), OUTLINE, 3.0))
        }
        Outline::Line { point, dir } => match plane_line(p, *point, *dir) {
            Some((a, b)) => g.add(line(p.px(a), p.px(b), OUTLINE, 3.0)),
            None => g,
        },
        _ => g,
    }
}

/// A plane's line, through `point` along `dir` in the view's plane, as far as the frame
/// shows it (None where it misses the frame).
fn plane_line(p: &Panel, point: DVec2, dir: DVec2) -> Option<(DVec2, DVec2)> {
    // Four diagonals each way reach past the frame from any point in or near it.
    let reach = 4.0 * p.frame.size().length();
    p.frame.clip(point - dir * reach, point + dir * reach)
}

/// The sides of an object's outline on the page (a plane's line as far as the frame shows
/// it).
fn edges(p: &Panel, outline: &Outline) -> Vec<(DVec2, DVec2)> {
    match outline {
        Outline::Polygon(pts) if pts.len() >= 2 => {
            let px: Vec<DVec2> = pts.iter().map(|q| p.px(*q)).collect();
            let closed = if px.len() >= 3 { px.len() } else { 1 };
            (0..closed)
                .map(|i| (px[i], px[(i + 1) % px.len()]))
                .collect()
        }
        Outline::Line { point, dir } => (plane_line(p, *point, *dir).into_iter())
            .map(|(a, b)| (p.px(a), p.px(b)))
            .collect(),
        _ => vec![],
    }
}

/// Where an object's name goes: for a plane, near where its line enters the frame on the
/// left (None where it misses the frame); else the outline's own anchor.
fn name_anchor(p: &Panel, outline: &Outline) -> Option<DVec2> {
    match outline {
        Outline::Line { point, dir } => {
            let (a, b) = plane_line(p, *point, *dir)?;
            let (left, right) = if a.x <= b.x { (a, b) } else { (b, a) };
            Some(left + (right - left) * 0.04)
        }
        o => Some(o.anchor()),
    }
}

/// A ray's label, "kind I = value", and the box it covers: above the ray, else below it;
/// off every line of `lines` (the rays and the outlines) where it can be, at its middle or
/// elsewhere along it, else off its own; where both spots would cover another
/// label (or a name), the same a quarter of the ray nearer either end; None where none is
/// free, or where the ray is too short on the page to carry one.
fn ray_label(
    p: &Panel,
    s: &Segment,
    (pa, pb): (DVec2, DVec2),
    lines: &[(DVec2, DVec2)],
    taken: &[Box2],
) -> Option<(Text, Box2)> {
    // The label goes along the part of the ray the panel shows: a shadow ray toward a light
    // off the figure runs on far past its edge.
    let (pa, pb) = Frame {
        min: p.origin,
        max: p.origin + p.size,
    }
    .clip(pa, pb)?;
    let dir = pb - pa;
    let room = if s.kind == SegKind::Primary {
        30.0
    } else {
        60.0
    };
    if dir.length() <= room {
        return None;
    }
    let along = match (is_shadow(s.kind), s.to.is_some()) {
        (true, _) => 0.25,
        (false, true) => 0.5,
        (false, false) => 0.35,
    };
    let mut label = s.label();
    // "(background)" says where a ray went, where the panel is wide enough to say it.
    let long = format!("{label} (background)");
    if s.kind == SegKind::Missed && text_width(&long, 12.0) <= p.size.x - 8.0 {
        label = long;
    }
    let off = dir.perp().normalize_or_zero() * 10.0;
    let above = if off.y > 0.0 { -off } else { off };
    let beside = |mid: DVec2| [mid + above, mid - above + DVec2::new(0.0, 10.0)];
    let spots = beside(pa + dir * along);
    let free = |spots: &[DVec2], paths: &[(DVec2, DVec2)]| {
        spots.iter().find_map(|&at| {
            let (bx, end) = beside_rays(p, at, &label, 12.0, paths, taken)?;
            Some((at, bx, end))
        })
    };
    let anywhere = |spots: &[DVec2]| {
        spots.iter().find_map(|&at| {
            let bx = label_box(p, at, &label, 12.0);
            let inside = into_panel(p, bx, 0.0).y == 0.0;
            (inside && !taken.iter().any(|b| overlap(b, &bx))).then_some((at, bx, false))
        })
    };
    let further: Vec<DVec2> = [along + 0.25, along - 0.25]
        .into_iter()
        .filter(|t| (0.1..=0.9).contains(t))
        .flat_map(|t| beside(pa + dir * t))
        .collect();
    // Off every line anywhere along the ray before it may lie across another ray, where it
    // would read as that ray's label.
    let along_it: Vec<DVec2> = [0.3, 0.45, 0.6, 0.75]
        .into_iter()
        .flat_map(|t| beside(pa + dir * t))
        .collect();
    let (at, bx, end) = free(&spots, lines)
        .or_else(|| free(&along_it, lines))
        .or_else(|| free(&spots, &[(pa, pb)]))
        .or_else(|| anywhere(&spots))
        .or_else(|| free(&further, &[(pa, pb)]))
        .or_else(|| anywhere(&further))?;
    let t = label_in(p, at, &label, 12.0, &ray_color(s.kind));
    Some((if end { t.set("text-anchor", "end") } else { t }, bx))
}
