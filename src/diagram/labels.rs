//! Where the figure's labels go: the names of objects and lights, the eye's and the image
//! plane's, and each ray's kind and intensity, placed where they stay inside their panel and
//! keep off the rays and off each other. A label's place is judged by the box it covers
//! (`Box2`, top-left and bottom-right corners in pixels), from its width in characters.

use glam::DVec2;
use svg::node::element::Text;

use super::frame::Frame;
use super::ink::{text, text_width, Panel};

/// A rectangle of the page: its top-left and bottom-right corners, in pixels.
pub(super) type Box2 = (DVec2, DVec2);

/// A label at `at` that stays inside the panel: anchored at its end when it would run off
/// the right edge.
pub(super) fn label_in(p: &Panel, at: DVec2, s: &str, size: f64, color: &str) -> Text {
    let (x, end) = anchor_in(p, at, s, size);
    anchored(DVec2::new(x, at.y), end, s, size, color)
}

/// Where `label_in` anchors a label meant for `at`: the x, and whether that is the label's
/// end.
pub(super) fn anchor_in(p: &Panel, at: DVec2, s: &str, size: f64) -> (f64, bool) {
    let right = p.origin.x + p.size.x - 4.0;
    if at.x + text_width(s, size) > right {
        (at.x.min(right), true)
    } else {
        (at.x, false)
    }
}

/// A label that starts at `at`, or (`end`) ends there.
pub(super) fn anchored(at: DVec2, end: bool, s: &str, size: f64, color: &str) -> Text {
    let t = text(at, s, size, color);
    if end {
        t.set("text-anchor", "end")
    } else {
        t
    }
}

/// The rectangle (top-left, bottom-right) a label drawn by `label_in` covers, roughly.
pub(super) fn label_box(p: &Panel, at: DVec2, s: &str, size: f64) -> Box2 {
    let width = text_width(s, size);
    let (x, end) = anchor_in(p, at, s, size);
    let x0 = if end { x - width } else { x };
    (
        DVec2::new(x0, at.y - size),
        DVec2::new(x0 + width, at.y + 2.0),
    )
}

/// How far the box must move to lie inside the panel, `margin` in from its edges; along an
/// axis where it is too large for that, its left or top edge is kept in.
pub(super) fn into_panel(p: &Panel, (lo, hi): Box2, margin: f64) -> DVec2 {
    let min = p.origin + DVec2::splat(margin);
    let max = p.origin + p.size - DVec2::splat(margin);
    let axis = |lo: f64, hi: f64, min: f64, max: f64| {
        if lo < min {
            min - lo
        } else if hi > max {
            (max - hi).max(min - lo)
        } else {
            0.0
        }
    };
    DVec2::new(
        axis(lo.x, hi.x, min.x, max.x),
        axis(lo.y, hi.y, min.y, max.y),
    )
}

/// A ray's label near `at`: the box it covers, reading on from `at` or, where that would lay
/// it across one of the rays `paths` (each from one end to the other) or over one of the
/// boxes `taken`, up to `at` (its end anchored there), whichever keeps it off those and inside
/// the panel; None where neither does.
pub(super) fn beside_rays(
    p: &Panel,
    at: DVec2,
    s: &str,
    size: f64,
    paths: &[(DVec2, DVec2)],
    taken: &[Box2],
) -> Option<(Box2, bool)> {
    let width = text_width(s, size);
    [false, true].into_iter().find_map(|end| {
        let x0 = if end { at.x - width } else { at.x };
        let bx = (
            DVec2::new(x0, at.y - size),
            DVec2::new(x0 + width, at.y + 2.0),
        );
        let clear = !paths.iter().any(|&(a, b)| crosses(&bx, a, b))
            && !taken.iter().any(|t| overlap(t, &bx));
        (into_panel(p, bx, 4.0) == DVec2::ZERO && clear).then_some((bx, end))
    })
}

/// Whether the segment from `a` to `b` passes through the box.
pub(super) fn crosses(&(min, max): &Box2, a: DVec2, b: DVec2) -> bool {
    Frame { min, max }.clip(a, b).is_some()
}

/// Where the eye's name goes (the baseline's middle), and the box it covers: on the side away
/// from the image plane, clear of the dot also when it sits beside it; where a ray passes
/// there (one that comes straight back through the eye), above the dot, else below it.
pub(super) fn eye_label(eye: DVec2, pix: DVec2, paths: &[(DVec2, DVec2)]) -> (DVec2, Box2) {
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

/// Whether two boxes cover some of the same page.
pub(super) fn overlap(a: &Box2, b: &Box2) -> bool {
    a.0.x < b.1.x && b.0.x < a.1.x && a.0.y < b.1.y && b.0.y < a.1.y
}

/// Where the image plane's label goes, and its anchor: beyond the end of the plane (as drawn,
/// the points of `hull`) that lies across the primary ray from the eye to the pixel, to the
/// right where the plane runs sideways and below where it runs up and down; the eye sits
/// behind the plane's middle, so the label stays clear of it and of the ray. Moved in where
/// that end lies at the panel's edge.
pub(super) fn image_plane_label(
    p: &Panel,
    hull: &[DVec2],
    eye: DVec2,
    pix: DVec2,
) -> (DVec2, &'static str) {
    let (at, anchor) = beyond_the_plane(hull, eye, pix);
    (at + into_panel(p, image_plane_box(at, anchor), 4.0), anchor)
}

/// The box the image plane's label covers at 12 px, drawn at `at` with `anchor`.
pub(super) fn image_plane_box(at: DVec2, anchor: &str) -> Box2 {
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

/// `image_plane_label`'s spot before it is moved into the panel.
fn beyond_the_plane(hull: &[DVec2], eye: DVec2, pix: DVec2) -> (DVec2, &'static str) {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn distance_to_box(q: DVec2, (lo, hi): Box2) -> f64 {
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
    fn sampled_through((lo, hi): Box2, a: DVec2, b: DVec2) -> bool {
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

    /// A box inside the panel stays; one across an edge moves in by as much as it crosses it,
    /// and one too wide for the panel keeps its left edge in.
    #[test]
    fn a_box_moves_into_the_panel() {
        let p = panel();
        let bx = |x0: f64, y0: f64, x1: f64, y1: f64| (DVec2::new(x0, y0), DVec2::new(x1, y1));
        assert_eq!(into_panel(&p, bx(10.0, 10.0, 50.0, 30.0), 4.0), DVec2::ZERO);
        assert_eq!(
            into_panel(&p, bx(-6.0, 590.0, 50.0, 599.0), 4.0),
            DVec2::new(10.0, -3.0)
        );
        assert_eq!(
            into_panel(&p, bx(100.0, -20.0, 650.0, 0.0), 4.0),
            DVec2::new(-54.0, 24.0)
        );
        assert_eq!(
            into_panel(&p, bx(-100.0, 0.0, 700.0, 10.0), 4.0),
            DVec2::new(104.0, 4.0)
        );
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
            let (at, anchor) = image_plane_label(&panel(), &plane, eye, pix);
            let bx = image_plane_box(at, anchor);
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
