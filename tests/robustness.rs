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

/// A face two solids share is found twice, once by each, and the two computations may differ
/// in their last bits. Seen from above, a hole drilled flush with the top of a can (a cylinder
/// minus a coaxial one reaching its top) or of a block (a box minus a cylinder) shows its own
/// red walls and floor wherever the line of sight enters the hole's circle at the top, and the
/// white top elsewhere (judged within a square of side 2 about the axis, off the rim): no film a
/// rounding error thick covers it. The fast wing and the core
/// agree to the bit.
#[test]
fn a_hole_flush_with_a_face_is_open() {
    let scene = |body: &str, top: f64| {
        let yaml = format!(
            "camera: {{ eye: [0.2, 6, 0.1], look_at: [0, 0, 0], up: [0, 0, 1], fov: 40, width: 48, height: 48 }}\n\
             ambient: 1\nmax_depth: 1\nlights: []\n\
             materials: {{ white: {{ color: 1, ka: 1 }}, red: {{ color: [1, 0, 0], ka: 1 }} }}\n\
             objects:\n\
             \x20 - name: cup\n    material: white\n    difference:\n\
             \x20     - {{ name: body, {body}, material: white }}\n\
             \x20     - {{ name: hole, cylinder: {{ base: [0, -0.4, 0], top: [0, {top}, 0], radius: 0.7 }}, material: red }}\n"
        );
        parse(&yaml, "hole.yaml", None, &Limits::default()).unwrap()
    };
    let cases = [
        (
            "cylinder: { base: [0, -1, 0], top: [0, 3, 0], radius: 1.5 }",
            3.0,
        ),
        ("box: { min: [-1.5, -1, -1.5], max: [1.5, 1, 1.5] }", 1.0),
    ];
    for (body, top) in cases {
        let s = scene(body, top);
        let (image, _) = render_simple(&s, RenderOptions::of(&s));
        let core = RenderOptions {
            engine: raytree::render::Engine::Core,
            ..RenderOptions::of(&s)
        };
        assert_eq!(render_simple(&s, core).0.pixels, image.pixels, "{body}");
        let (mut red, mut wrong) = (0, 0);
        for y in 0..s.camera.height {
            for x in 0..s.camera.width {
                let ray = s.camera.pixel_ray(x, y);
                // Where the line of sight crosses the top, and how far that is from the
                // hole's rim.
                let at = ray.at((top - ray.origin.y) / ray.dir.y);
                let from_rim = (at.x * at.x + at.z * at.z).sqrt() - 0.7;
                // Within the top of either body (and clear of the rim, where rounding decides).
                let on_top = at.x.abs().max(at.z.abs()) < 1.0;
                if from_rim.abs() < 0.02 || !on_top {
                    continue;
                }
                let want = if from_rim < 0.0 { DVec3::X } else { DVec3::ONE };
                let got = image.get(x, y);
                red += (want == DVec3::X) as usize;
                wrong += (got != want) as usize;
            }
        }
        assert!(red > 100, "{body}: only {red} pixels over the hole");
        assert_eq!(wrong, 0, "{body}: {wrong} pixels wrong");
    }
}

/// A solid minus itself written another way (a unit sphere scaled, and the same sphere turned
/// about its axis first, which changes nothing) is empty: the two computations of each face
/// are one face, and no speckle of either is left.
#[test]
fn a_solid_minus_itself_written_another_way_is_empty() {
    let yaml = "camera: { eye: [0, 0, -10], look_at: [0, 0, 0], fov: 30, width: 48, height: 48 }\n\
                background: 0\nambient: 1\nlights: []\nmaterials: { m: { ka: 1 } }\n\
                objects:\n\
                \x20 - name: nothing\n    material: m\n    difference:\n\
                \x20     - { sphere: { center: [0, 0, 0], radius: 1 }, transform: [ { scale: [1, 2, 1] } ] }\n\
                \x20     - { sphere: { center: [0, 0, 0], radius: 1 }, transform: [ { rotate_y: 30 }, { scale: [1, 2, 1] } ] }\n";
    let s = parse(yaml, "a-minus-a.yaml", None, &Limits::default()).unwrap();
    let (image, _) = render_simple(&s, RenderOptions::of(&s));
    let lit = image.pixels.iter().filter(|p| **p != DVec3::ZERO).count();
    assert_eq!(lit, 0, "{lit} pixels of an empty solid");
}

/// A smooth mesh's blended normal can lean past a ray that its triangle faces: an octahedron
/// (|x| + |y| + |z| = 1) with its vertex normals along the vertices, met near its rim by a ray
/// from outside. The triangle's own normal, ∝ (1, 1, −1), meets the ray's direction at a
/// negative cosine, so the ray enters the glass (n1 = 1, n2 = 1.5); the blended normal ∝ (0.5,
/// 0.45, −0.05) alone would say it leaves.
#[test]
fn a_ray_entering_a_smooth_mesh_enters_it() {
    let dir = std::env::temp_dir().join(format!("raytree-robust-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut obj = String::from("v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n");
    obj += "vn 1 0 0\nvn -1 0 0\nvn 0 1 0\nvn 0 -1 0\nvn 0 0 1\nvn 0 0 -1\n";
    // Each face (±x, ±y, ±z) wound counter-clockwise seen from outside.
    for (x, y, z) in [(1, 3, 5), (3, 2, 5), (2, 4, 5), (4, 1, 5)] {
        obj += &format!("f {x}//{x} {y}//{y} {z}//{z}\nf {y}//{y} {x}//{x} 6//6\n");
    }
    std::fs::write(dir.join("octa.obj"), obj).unwrap();
    let path = dir.join("octa.yaml");
    std::fs::write(
        &path,
        "camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmax_depth: 3\n\
         materials: { glass: { kd: 0, kt: 1, ior: 1.5 } }\n\
         objects: [ { name: O, mesh: { file: octa.obj, smooth: true }, material: glass } ]\n",
    )
    .unwrap();
    let s = raytree::scene::load(&path, &Limits::default()).unwrap();
    let ray = raytree::geometry::Ray::new(
        DVec3::new(-0.5, 0.45, -5.05),
        DVec3::new(0.2, 0.0, 1.0).normalize(),
    );
    let tree = raytree::trace::Tracer::new(&s).with_depth(3).inspect(&ray);
    let hit = tree.hit.as_ref().expect("the ray meets the octahedron");
    assert!(
        (hit.point - DVec3::new(0.5, 0.45, -0.05)).length() < 1e-9,
        "{}",
        hit.point
    );
    assert!(!hit.inside, "the ray enters the glass");
}

/// At the limiting angle Snell's law gives a refracted ray along the surface (k = 0): from
/// inside a glass ball of index 1.5, a ray meeting the surface at sin θ1 = 1/1.5 leaves along
/// the tangent. It starts on the far side of the surface, the side it goes through to, so it
/// meets the background and not the ball it has just left.
#[test]
fn a_ray_refracted_along_the_surface_leaves_it() {
    let yaml = "camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nbackground: 0.25\nmax_depth: 3\n\
                materials: { glass: { kd: 0, kt: 1, ior: 1.5 } }\n\
                objects: [ { name: G, sphere: { center: [0, 0, 0], radius: 1 }, material: glass } ]\n";
    let s = parse(yaml, "limiting.yaml", None, &Limits::default()).unwrap();
    let ray = raytree::geometry::Ray::new(DVec3::new(0.0, 2.0 / 3.0, -0.1), DVec3::Z);
    let tree = raytree::trace::Tracer::new(&s).with_depth(3).inspect(&ray);
    assert!(
        tree.hit.as_ref().unwrap().inside,
        "the ray starts inside the ball"
    );
    let refracted = tree
        .children
        .iter()
        .find(|c| c.kind == raytree::trace::RayKind::Refraction)
        .expect("a refracted ray, not total internal reflection");
    assert!(refracted.direction.z > 0.66 && refracted.direction.y < -0.74);
    assert!(refracted.hit.is_none(), "{:?}", refracted.hit);
    assert_eq!(refracted.color, DVec3::splat(0.25));
}

/// A whole scene scaled by k (eye, sphere, floor) renders the same image at any scale, up to
/// an eye 10⁶⁰ from the origin: the primary rays' directions are found from the camera's axes,
/// not as (e + offset) − e, which loses the offset once the spacing of doubles near e
/// outgrows the image plane (from 10¹⁶ on, where every ray came out NaN or sideways).
#[test]
fn a_scaled_scene_renders_alike_with_the_eye_far_out() {
    let image = |k: f64| {
        let yaml = format!(
            "camera: {{ eye: [0, 0, {:e}], look_at: [0, 0, 0], fov: 40, width: 40, height: 30 }}
lights: [ {{ direction: [0.3, -1, 0.5] }} ]
materials: {{ m: {{ kd: 0.8, ka: 0.1 }} }}
objects:
  - {{ sphere: {{ center: [0, 0, 0], radius: {:e} }}, material: m }}
  - {{ plane: {{ point: [0, {:e}, 0], normal: [0, 1, 0] }}, material: m }}
",
            -10.0 * k,
            k,
            -k
        );
        let s = parse(&yaml, "scaled.yaml", None, &Limits::default()).unwrap();
        render_simple(&s, RenderOptions::of(&s)).0.pixels
    };
    let unit = image(1.0);
    let lit = unit.iter().filter(|p| p.x > 0.0).count();
    assert!(lit > unit.len() / 2, "the ball and the floor fill the view");
    for k in [1e-20, 1e16, 1e20, 1e60] {
        let far = image(k);
        let off = unit
            .iter()
            .zip(&far)
            .filter(|(a, b)| (**a - **b).abs().max_element() > 1e-9)
            .count();
        assert_eq!(off, 0, "scale {k:e}: {off} pixels differ");
    }
}
