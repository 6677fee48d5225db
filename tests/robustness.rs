//! Numerical robustness: the same scene scaled from 1e−4 to 1e6 and moved far from the
//! origin renders exactly as an independent analytic computation says: no shadow acne, no
//! light leaking, no speckles.

use glam::DVec3;
use raytree::render::{render_simple, RenderOptions};
use raytree::scene::{parse, Limits, Scene};

/// A unit sphere resting on a floor, one point light, matte surfaces: everything a pixel
/// shows can be worked out in closed form.
fn scene(scale: f64, offset: DVec3) -> Scene {
    scene_seen_from(scale, offset, 1.0)
}

/// `scene`, its eye moved `away` times as far from the point it looks at, and its field of
/// view narrowed to frame the same (tan(fov/2) divided by `away`).
fn scene_seen_from(scale: f64, offset: DVec3, away: f64) -> Scene {
    let p = |v: DVec3| {
        let w = v * scale + offset;
        format!("[{:e}, {:e}, {:e}]", w.x, w.y, w.z)
    };
    let look_at = DVec3::new(0.0, 0.8, 0.0);
    let eye = look_at + away * (DVec3::new(0.0, 2.0, -6.0) - look_at);
    let fov = 2.0 * (20f64.to_radians().tan() / away).atan().to_degrees();
    let yaml = format!(
        "camera: {{ eye: {}, look_at: {}, fov: {fov:e}, width: 64, height: 48 }}\n\
         background: 0.1\nambient: 0.2\n\
         lights: [ {{ name: L, point: {}, intensity: 1 }} ]\n\
         materials: {{ m: {{ ka: 1, kd: 0.7 }} }}\n\
         objects:\n\
         \x20 - {{ name: ball, sphere: {{ center: {}, radius: {:e} }}, material: m }}\n\
         \x20 - {{ name: floor, plane: {{ point: {}, normal: [0, 1, 0] }}, material: m }}\n",
        p(eye),
        p(look_at),
        p(LIGHT),
        p(DVec3::new(0.0, 1.0, 0.0)),
        scale,
        p(DVec3::ZERO),
    );
    parse(&yaml, "robust.yaml", None, &Limits::default()).unwrap()
}

const LIGHT: DVec3 = DVec3::new(4.0, 6.0, -3.0);
const CENTER: DVec3 = DVec3::new(0.0, 1.0, 0.0);

/// Ray–unit-sphere in the unscaled frame: (the nearest hit point, |discriminant| as a margin).
/// The ray is first followed to 2 units short of the centre's distance along it, so that from
/// far away b² − c does not cancel: the quadratic is solved near the sphere.
fn sphere(o: DVec3, d: DVec3) -> (Option<DVec3>, f64) {
    let ahead = (d.dot(CENTER - o) - 2.0).max(0.0);
    let o = o + ahead * d;
    let oc = o - CENTER;
    let b = d.dot(oc);
    let disc = b * b - (oc.length_squared() - 1.0);
    if disc < 0.0 {
        return (None, -disc);
    }
    let t = -b - disc.sqrt();
    ((ahead + t > 0.0).then(|| o + t * d), disc)
}

/// The expected intensity of a ray, and how far it is from any edge (silhouette, shadow
/// boundary, terminator) where rounding may legitimately decide either way.
fn expected(o: DVec3, d: DVec3) -> (f64, f64) {
    let (ball, ball_margin) = sphere(o, d);
    let floor = (d.y < 0.0).then(|| -o.y / d.y);
    let shade = |p: DVec3, n: DVec3, lit: bool| {
        let l = (LIGHT - p).normalize();
        0.2 + if lit { 0.7 * n.dot(l).max(0.0) } else { 0.0 }
    };
    match (ball, floor) {
        (Some(p), _) => {
            let n = p - CENTER;
            let l = (LIGHT - p).normalize();
            (shade(p, n, true), ball_margin.min(n.dot(l).abs()))
        }
        (None, Some(t)) => {
            let p = o + t * d;
            let to_light = (LIGHT - p).normalize();
            let (blocker, margin) = sphere(p, to_light);
            (
                shade(p, DVec3::Y, blocker.is_none()),
                ball_margin.min(margin),
            )
        }
        (None, None) => (0.1, ball_margin.min(d.y.abs())),
    }
}

fn wrong_pixels(scale: f64, offset: DVec3) -> (usize, usize) {
    wrong_pixels_of(&scene(scale, offset), scale, offset)
}

fn wrong_pixels_of(s: &Scene, scale: f64, offset: DVec3) -> (usize, usize) {
    let (image, _) = render_simple(s, RenderOptions::of(s));
    let (mut wrong, mut judged) = (0, 0);
    for y in 0..s.camera.height {
        for x in 0..s.camera.width {
            let ray = s.camera.pixel_ray(x, y);
            // The same ray in the unscaled frame (directions are scale-invariant).
            let o = (ray.origin - offset) / scale;
            let (want, margin) = expected(o, ray.dir);
            if margin < 1e-6 {
                continue;
            }
            judged += 1;
            if (image.get(x, y).x - want).abs() > 1e-6 {
                wrong += 1;
            }
        }
    }
    (wrong, judged)
}

#[test]
fn no_acne_or_leaks_at_any_scale() {
    for scale in [1e-4, 1e-2, 1.0, 1e2, 1e4, 1e6] {
        let (wrong, judged) = wrong_pixels(scale, DVec3::ZERO);
        assert!(judged > 3000, "scale {scale}: only {judged} pixels judged");
        assert_eq!(wrong, 0, "scale {scale}: {wrong} of {judged} pixels wrong");
    }
}

#[test]
fn no_acne_or_leaks_far_from_the_origin() {
    for (scale, offset) in [(1.0, 1e6), (1e-2, 1e3), (1e3, 1e6), (1.0, -1e5)] {
        let (wrong, judged) = wrong_pixels(scale, DVec3::splat(offset));
        assert!(judged > 3000);
        assert_eq!(
            wrong, 0,
            "scale {scale} offset {offset}: {wrong} of {judged} pixels wrong"
        );
    }
}

/// A point found by a ray from far away carries that ray's rounding (a few ulps of its
/// origin's coordinates), so the rays leaving it, shadow rays as well as reflected ones, are
/// moved off the surface by a bias relative to that origin too: an eye 10⁷ times as far away,
/// through a telescope's field of view, sees the same ball with no shadow acne.
#[test]
fn no_acne_seen_from_far_away() {
    for away in [1e3, 1e5, 1e7] {
        let s = scene_seen_from(1.0, DVec3::ZERO, away);
        let (wrong, judged) = wrong_pixels_of(&s, 1.0, DVec3::ZERO);
        assert!(judged > 3000, "{away}: only {judged} pixels judged");
        assert_eq!(
            wrong, 0,
            "eye {away} times as far: {wrong} of {judged} pixels wrong"
        );
    }
}

#[test]
fn a_zero_bias_shows_acne() {
    // The same scene with shadow_bias 0: the lesson's deliberate mistake must be visible,
    // or the tests above would prove nothing about the bias.
    let mut s = scene(1.0, DVec3::splat(1e3));
    s.shadow_bias = Some(0.0);
    let (image, _) = render_simple(&s, RenderOptions::of(&s));
    let mut acne = 0;
    for y in 0..s.camera.height {
        for x in 0..s.camera.width {
            let ray = s.camera.pixel_ray(x, y);
            let (want, margin) = expected(ray.origin - DVec3::splat(1e3), ray.dir);
            if margin > 1e-6 && (image.get(x, y).x - want).abs() > 1e-6 {
                acne += 1;
            }
        }
    }
    assert!(acne > 50, "only {acne} acne pixels");
}
