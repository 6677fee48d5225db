//! Adaptive antialiasing, explained: a pixel's square is split in four while its corners differ
//! by more than the threshold, and a square not split takes the mean of its corners. Pixel
//! corners are traced once and shared with the neighbours, so the rays an image takes are its
//! corners plus 5 for every split.

use glam::DVec3;

use super::image::Rendering;
use crate::render::antialias::{Square, Step};
use crate::stats::Stats;
use crate::trace::text;

/// The work of the whole image: its shared corners, then the splits of every pixel.
pub(super) fn whole_image(
    r: &Rendering,
    threshold: f64,
    [nc, nr]: [u32; 2],
    stats: &Stats,
) -> Vec<String> {
    let corners = (nc + 1) * (nr + 1);
    let mut out = vec![
        format!(
            "adaptive antialiasing, threshold {}: squares halved at most {} times (spp {})",
            text::num(threshold),
            r.levels,
            r.spp
        ),
        format!(
            "first the corners of all pixels, each traced once and shared: ({nc} + 1)·({nr} + 1) = {corners} primary rays"
        ),
    ];
    for py in 0..nr {
        for px in 0..nc {
            let mut t = r.film.tracer();
            r.film.lone_pixel(&mut t, px, py);
            let s = t.stats;
            if s.aa_splits > 0 {
                out.push(format!(
                    "pixel ({px}, {py}): {} square{} split",
                    s.aa_splits,
                    if s.aa_splits == 1 { "" } else { "s" }
                ));
            }
        }
    }
    out.push(format!(
        "squares split in the image: {}; every split traces 5 new rays (the 4 edge midpoints and the centre)",
        stats.aa_splits
    ));
    out.push(format!(
        "primary rays = {corners} + 5·{} = {}",
        stats.aa_splits, stats.primary_rays
    ));
    out
}

/// One pixel, square by square as the film takes them; returns the pixel's value.
pub(super) fn pixel(
    r: &Rendering,
    threshold: f64,
    [x, y]: [u32; 2],
    out: &mut Vec<String>,
) -> DVec3 {
    out.push(format!(
        "adaptive antialiasing, threshold {}: a square whose corners differ by more than that (Σ|Δr| + |Δg| + |Δb|) is split in four, at most {} times (spp {}: up to {side} × {side} squares)",
        text::num(threshold),
        r.levels,
        r.spp,
        side = 1u32 << r.levels
    ));
    let mut t = r.film.tracer();
    let corners = [
        r.film.corner(&mut t, x, y),
        r.film.corner(&mut t, x + 1, y),
        r.film.corner(&mut t, x, y + 1),
        r.film.corner(&mut t, x + 1, y + 1),
    ];
    out.push(format!(
        "corners (shared with the neighbours): top-left {}, top-right {}, bottom-left {}, bottom-right {}",
        text::color(corners[0]),
        text::color(corners[1]),
        text::color(corners[2]),
        text::color(corners[3])
    ));
    r.film.adaptive(&mut t, x, y, corners, &mut |step| {
        out.push(step_line(step, threshold))
    })
}

/// One step of adaptive antialiasing: a square kept, split or merged.
fn step_line(step: &Step, threshold: f64) -> String {
    match step {
        Step::Kept {
            square,
            smallest: false,
            value,
        } => format!(
            "{}: {} differ by at most {} ≤ {}: not split, value = mean of the corners = {}",
            name(square),
            corners(square),
            text::num(square.largest),
            text::num(threshold),
            text::color(*value)
        ),
        Step::Kept {
            square,
            smallest: true,
            value,
        } => format!(
            "{}: {} differ by {} > {}, but it is the smallest square allowed: value = mean of the corners = {}",
            name(square),
            corners(square),
            text::num(square.largest),
            text::num(threshold),
            text::color(*value)
        ),
        Step::Split { square, new } => {
            let [top, left, centre, right, bottom] = new.map(text::color);
            format!(
                "{}: {} differ by {} > {}: split; 5 new rays: top {top}, left {left}, centre {centre}, right {right}, bottom {bottom}",
                name(square),
                corners(square),
                text::num(square.largest),
                text::num(threshold),
            )
        }
        Step::Merged {
            square,
            quarters,
            value,
        } => format!(
            "{} = mean of its quarters ({}) / 4 = {}",
            name(square),
            quarters
                .iter()
                .map(|v| text::color(*v))
                .collect::<Vec<_>>()
                .join(" + "),
            text::color(*value)
        ),
    }
}

/// The square's place in the pixel, indented by how many times it was halved.
fn name(q: &Square) -> String {
    format!(
        "{}square u ∈ [{}, {}], v ∈ [{}, {}]",
        "  ".repeat(q.level as usize),
        text::num(q.u0),
        text::num(q.u0 + q.side),
        text::num(q.v0),
        text::num(q.v0 + q.side)
    )
}

fn corners(q: &Square) -> String {
    let [tl, tr, bl, br] = q.corners;
    format!(
        "corners {}, {}, {}, {}",
        text::color(tl),
        text::color(tr),
        text::color(bl),
        text::color(br)
    )
}
