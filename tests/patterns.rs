//! Patterns and textures against published values: The Ray Tracer Challenge's chapter
//! "Patterns" (stripes, gradient, rings, checkers; transformed objects and patterns; lighting
//! with a pattern) and chapter "Texture mapping" (uv at the poles and on the seam), posed as
//! scenes and read off the ray tree.

mod common;

use glam::{DVec2, DVec3};
use raytree::geometry::Ray;
use raytree::scene::{parse, Limits, Scene};
use raytree::trace::{RayNode, Tracer};

const WHITE: DVec3 = DVec3::ONE;
const BLACK: DVec3 = DVec3::ZERO;

/// A scene with one object and one material `m`, lit from the front, the ambient 1.
fn scene(material: &str, object: &str) -> Scene {
    common::scene(&format!(
        "camera: {{ eye: [0, 0, -10], look_at: [0, 0, 0], width: 8, height: 6 }}
ambient: 1
lights: [ {{ name: L, point: [0, 0, -10] }} ]
materials:
  m: {material}
objects:
  - {object}
"
    ))
}

fn trace(s: &Scene, origin: [f64; 3], dir: [f64; 3]) -> RayNode {
    Tracer::new(s).inspect(&Ray::new(DVec3::from(origin), DVec3::from(dir)))
}

/// O at the hit of a ray straight down onto a floor at (x, 0, z).
fn floor_color(s: &Scene, x: f64, z: f64) -> DVec3 {
    let n = trace(s, [x, 5.0, z], [0.0, -1.0, 0.0]);
    n.local.expect("a hit").color.expect("a patterned surface")
}

const FLOOR: &str = "{ name: floor, plane: { point: [0, 0, 0], normal: [0, 1, 0] }, material: m }";

/// Stripes on a floor: constant in z, alternating in x (the book's stripe_at cases that lie on
/// the plane y = 0).
#[test]
fn stripes_alternate_in_x_only() {
    let s = scene(
        "{ color: { pattern: stripes, colors: [1, 0] }, ka: 1 }",
        FLOOR,
    );
    for (x, z, c) in [
        (0.0, 0.0, WHITE),
        (0.0, 1.0, WHITE),
        (0.0, 2.0, WHITE),
        (0.9, 0.0, WHITE),
        (1.0, 0.0, BLACK),
        (-0.1, 0.0, BLACK),
        (-1.0, 0.0, BLACK),
        (-1.1, 0.0, WHITE),
    ] {
        assert_eq!(floor_color(&s, x, z), c, "({x}, 0, {z})");
    }
}

#[test]
fn gradient_rings_and_checkers_of_the_book() {
    let g = scene(
        "{ color: { pattern: gradient, colors: [1, 0] }, ka: 1 }",
        FLOOR,
    );
    for (x, c) in [(0.0, 1.0), (0.25, 0.75), (0.5, 0.5), (0.75, 0.25)] {
        assert!(
            (floor_color(&g, x, 0.3) - DVec3::splat(c)).length() < 1e-12,
            "gradient at x = {x}"
        );
    }
    let r = scene(
        "{ color: { pattern: rings, colors: [1, 0] }, ka: 1 }",
        FLOOR,
    );
    assert_eq!(floor_color(&r, 0.0, 0.0), WHITE);
    assert_eq!(floor_color(&r, 1.0, 0.0), BLACK);
    assert_eq!(floor_color(&r, 0.0, 1.0), BLACK);
    assert_eq!(floor_color(&r, 0.708, 0.708), BLACK);
    let c = scene(
        "{ color: { pattern: checker, colors: [1, 0] }, ka: 1 }",
        FLOOR,
    );
    for (x, z, want) in [
        (0.0, 0.0, WHITE),
        (0.99, 0.0, WHITE),
        (1.01, 0.0, BLACK),
        (0.0, 0.99, WHITE),
        (0.0, 1.01, BLACK),
    ] {
        assert_eq!(floor_color(&c, x, z), want, "({x}, 0, {z})");
    }
    // The book's checks in y, on a wall x = 0.5 facing −x.
    let wall = scene(
        "{ color: { pattern: checker, colors: [1, 0] }, ka: 1 }",
        "{ name: wall, plane: { point: [0.5, 0, 0], normal: [-1, 0, 0] }, material: m }",
    );
    let at = |y: f64| {
        trace(&wall, [-5.0, y, 0.5], [1.0, 0.0, 0.0])
            .local
            .unwrap()
            .color
    };
    assert_eq!(at(0.99), Some(WHITE));
    assert_eq!(at(1.01), Some(BLACK));
}

/// "Stripes with an object transformation" (object scaling(2, 2, 2), point (1.5, 0, 0) →
/// white), "with a pattern transformation" (the same from the pattern) and "with both an
/// object and a pattern transformation" (object scaling(2, 2, 2), pattern translation
/// (0.5, 0, 0), point (2.5, 0, 0) → white), on a floor through those points.
#[test]
fn transformed_objects_and_patterns_of_the_book() {
    let stripes = "{ pattern: stripes, colors: [1, 0] }";
    let scaled_object = scene(
        &format!("{{ color: {stripes}, ka: 1 }}"),
        "{ name: floor, plane: { point: [0, 0, 0], normal: [0, 1, 0] }, material: m, transform: [ { scale: 2 } ] }",
    );
    assert_eq!(floor_color(&scaled_object, 1.5, 0.0), WHITE);
    // Without the object's scale, x = 1.5 lies in a black stripe: the scale is what counts.
    let plain = scene(&format!("{{ color: {stripes}, ka: 1 }}"), FLOOR);
    assert_eq!(floor_color(&plain, 1.5, 0.0), BLACK);
    assert_eq!(floor_color(&scaled_object, 2.5, 0.0), BLACK);

    let scaled_pattern = scene(
        "{ color: { pattern: stripes, colors: [1, 0], transform: [ { scale: 2 } ] }, ka: 1 }",
        FLOOR,
    );
    assert_eq!(floor_color(&scaled_pattern, 1.5, 0.0), WHITE);

    let both = scene(
        "{ color: { pattern: stripes, colors: [1, 0], transform: [ { translate: [0.5, 0, 0] } ] }, ka: 1 }",
        "{ name: floor, plane: { point: [0, 0, 0], normal: [0, 1, 0] }, material: m, transform: [ { scale: 2 } ] }",
    );
    assert_eq!(floor_color(&both, 2.5, 0.0), WHITE);
    // 2.5 → 1.25 in the object → 0.75 in the pattern; 3.5 → 1.75 → 1.25: black.
    assert_eq!(floor_color(&both, 3.5, 0.0), BLACK);
}

/// The pattern lives in the object's own space: a sphere moved and turned carries its stripes
/// with it (a moved sphere is otherwise stored in world space; a patterned one is not).
#[test]
fn a_moved_object_carries_its_pattern() {
    let s = scene(
        "{ color: { pattern: stripes, colors: [1, 0] }, ka: 1 }",
        "{ name: ball, sphere: { center: [0, 0, 0], radius: 1 }, material: m, transform: [ { rotate_z: 90 }, { translate: [10, 0, 0] } ] }",
    );
    // Turned by 90° about z, the stripes (across x) run across y: the point (10, 0.5, −r) is at
    // x' = 0.5 in the sphere's own space (white), (10, −0.5, ·) at x' = −0.5 (black).
    let at = |y: f64| {
        let n = trace(&s, [10.0, y, -10.0], [0.0, 0.0, 1.0]);
        n.local.unwrap().color.unwrap()
    };
    assert_eq!(at(0.5), WHITE);
    assert_eq!(at(-0.5), BLACK);
}

/// "Lighting with a pattern applied": ambient 1, diffuse 0, specular 0, the light and the eye
/// in front; at (0.9, 0, 0) the colour is white, at (1.1, 0, 0) black.
#[test]
fn lighting_with_a_pattern_applied() {
    let s = scene(
        "{ color: { pattern: stripes, colors: [1, 0] }, ka: 1, kd: 0, ks: 0 }",
        "{ name: wall, plane: { point: [0, 0, 0], normal: [0, 0, -1] }, material: m }",
    );
    let i = |x: f64| trace(&s, [x, 0.0, -1.0], [0.0, 0.0, 1.0]).color;
    assert_eq!(i(0.9), WHITE);
    assert_eq!(i(1.1), BLACK);
}

/// Nested patterns: stripes whose first value is a checker, looked up at the same point.
#[test]
fn a_pattern_may_hold_patterns() {
    let s = scene(
        "{ color: { pattern: stripes, colors: [ { pattern: checker, colors: [[1, 0, 0], [0, 0, 1]], transform: [ { scale: 0.25 } ] }, [0, 1, 0] ] }, ka: 1 }",
        FLOOR,
    );
    // x in [0, 1): the checker of quarter cells; (0.1, 0.1) and (0.3, 0.1) are in cells
    // (0, 0, 0) and (1, 0, 0).
    assert_eq!(floor_color(&s, 0.1, 0.1), DVec3::X);
    assert_eq!(floor_color(&s, 0.3, 0.1), DVec3::Z);
    assert_eq!(floor_color(&s, 1.5, 0.1), DVec3::Y);
}

/// Coefficients vary too: a checker of kr makes every other cell a mirror.
#[test]
fn coefficients_take_patterns() {
    let s = scene(
        "{ color: 0.5, ka: 1, kr: { pattern: checker, colors: [0, 0.8] } }",
        FLOOR,
    );
    let at = |x: f64| trace(&s, [x, 5.0, 0.5], [0.0, -1.0, 0.0]);
    let matte = at(0.5);
    assert!(matte.children.iter().all(|c| c.kind.name() == "shadow"));
    let mirror = at(1.5);
    let reflection = mirror.find("reflection").expect("a reflection ray");
    assert_eq!(reflection.coefficient, 0.8);
    let local = mirror.local.unwrap();
    assert_eq!(local.coefficients.unwrap().kr, 0.8);
    assert_eq!(local.patterns[0].varies, "kr");
}

/// Pattern acne: a floor at y = 0 or y = −1 lies on a boundary between cells of the solid
/// checker, and the computed y of its hit points is off by rounding either way. Every hit
/// must take the cell above (y counts as 0, or −1), so the colour follows x and z alone.
#[test]
fn a_floor_on_a_cell_boundary_gets_one_cell() {
    for y in [0.0, -1.0] {
        let s = common::scene(&format!(
            "camera: {{ eye: [0.3, 2.7, -7.1], look_at: [0.2, {y}, 4], fov: 70, width: 64, height: 48 }}
ambient: 1
materials:
  m: {{ color: {{ pattern: checker, colors: [1, 0], transform: [ {{ scale: 0.7 }} ] }}, ka: 1 }}
objects:
  - {{ name: floor, plane: {{ point: [0, {y}, 0], normal: [0, 1, 0] }}, material: m }}
"
        ));
        let mut checked = 0;
        for py in 24..48 {
            for px in 0..64 {
                let ray = s.camera.pixel_ray(px, py);
                let n = Tracer::new(&s).inspect(&ray);
                let Some(h) = &n.hit else { continue };
                let (cx, cz) = ((h.point.x / 0.7).floor(), (h.point.z / 0.7).floor());
                let cy = (y / 0.7f64).floor();
                let near_edge = |v: f64| {
                    let f = v / 0.7 - (v / 0.7).floor();
                    !(1e-6..1.0 - 1e-6).contains(&f)
                };
                if near_edge(h.point.x) || near_edge(h.point.z) {
                    continue;
                }
                let even = (cx + cy + cz).rem_euclid(2.0) == 0.0;
                let want = if even { WHITE } else { BLACK };
                assert_eq!(n.color, want, "y = {y}: pixel ({px}, {py}) at {}", h.point);
                checked += 1;
            }
        }
        assert!(checked > 500, "{checked}");
    }
}

// --- Texture mapping: uv at known points ---

/// A unit sphere with a uv checker, and the (u, v) at the hit of a ray aimed at `target` (a
/// point of the sphere) from outside along its normal.
fn sphere_uv(target: [f64; 3]) -> DVec2 {
    let s = scene(
        "{ color: { pattern: uv_checker, width: 2, height: 2, colors: [0, 1] }, ka: 1 }",
        "{ name: ball, sphere: { center: [0, 0, 0], radius: 1 }, material: m }",
    );
    let t = DVec3::from(target);
    let n = trace(&s, (3.0 * t).to_array(), (-t).to_array());
    let h = n.hit.expect("a hit");
    assert!((h.point - t).length() < 1e-12);
    h.uv.expect("texture coordinates")
}

/// The book's spherical mapping, read from hits on a sphere: the seam (u = 0 at −z), the
/// quarter turns, and both poles (u = ½ there, v = 0 and 1).
#[test]
fn spherical_uv_at_the_poles_and_the_seam() {
    let h = 2f64.sqrt() / 2.0;
    for (p, u, v) in [
        ([0.0, 0.0, -1.0], 0.0, 0.5),
        ([1.0, 0.0, 0.0], 0.25, 0.5),
        ([0.0, 0.0, 1.0], 0.5, 0.5),
        ([-1.0, 0.0, 0.0], 0.75, 0.5),
        ([0.0, 1.0, 0.0], 0.5, 1.0),
        ([0.0, -1.0, 0.0], 0.5, 0.0),
        ([h, h, 0.0], 0.25, 0.75),
    ] {
        let got = sphere_uv(p);
        assert!(
            (got - DVec2::new(u, v)).length() < 1e-12,
            "{p:?}: {got}, want ({u}, {v})"
        );
    }
}

/// A sphere's own uv is the spherical mapping about its centre, whatever its radius and
/// wherever it is.
#[test]
fn a_sphere_maps_about_its_own_centre() {
    let s = scene(
        "{ color: { pattern: uv_checker, width: 2, height: 2, colors: [0, 1] }, ka: 1 }",
        "{ name: ball, sphere: { center: [3, 4, 5], radius: 2 }, material: m }",
    );
    let n = trace(&s, [3.0 + 2f64.sqrt(), 4.0, -10.0], [0.0, 0.0, 1.0]);
    // Hit at (3 + √2, 4, 5 − √2): direction (1, 0, −1)/√2 from the centre, u = 1/8.
    let uv = n.hit.unwrap().uv.unwrap();
    assert!((uv - DVec2::new(0.125, 0.5)).length() < 1e-12, "{uv}");
}

/// Projections from the pattern's space: the book's planar and cylindrical cases on a floor
/// and on a tube round the y axis.
#[test]
fn planar_and_cylindrical_mappings() {
    let planar = scene(
        "{ color: { pattern: uv_checker, width: 2, height: 2, colors: [0, 1], mapping: planar }, ka: 1 }",
        FLOOR,
    );
    for (x, z, u, v) in [
        (0.25, 0.5, 0.25, 0.5),
        (0.25, -0.25, 0.25, 0.75),
        (1.25, 0.5, 0.25, 0.5),
        (0.25, -1.75, 0.25, 0.25),
        (1.0, -1.0, 0.0, 0.0),
    ] {
        let uv = trace(&planar, [x, 5.0, z], [0.0, -1.0, 0.0])
            .hit
            .unwrap()
            .uv
            .unwrap();
        assert!((uv - DVec2::new(u, v)).length() < 1e-12, "({x}, {z}): {uv}");
    }
    let tube = scene(
        "{ color: { pattern: uv_checker, width: 2, height: 2, colors: [0, 1], mapping: cylindrical }, ka: 1 }",
        "{ name: tube, cylinder: { base: [0, -5, 0], top: [0, 5, 0], radius: 1, capped: false }, material: m }",
    );
    let h = std::f64::consts::FRAC_1_SQRT_2;
    for (p, u, v) in [
        ([0.0, 0.5, -1.0], 0.0, 0.5),
        ([h, 0.5, -h], 0.125, 0.5),
        ([1.0, 0.5, 0.0], 0.25, 0.5),
        ([0.0, -0.25, 1.0], 0.5, 0.75),
        ([-1.0, 1.25, 0.0], 0.75, 0.25),
    ] {
        let t = DVec3::from(p);
        let out = DVec3::new(t.x, 0.0, t.z);
        let uv = trace(&tube, (t + 3.0 * out).to_array(), (-out).to_array())
            .hit
            .unwrap()
            .uv
            .unwrap();
        assert!((uv - DVec2::new(u, v)).length() < 1e-9, "{p:?}: {uv}");
    }
}

/// A cylinder's own uv: u round its axis (0 towards −z, as the cylindrical mapping), v up it
/// from 0 at the base to 1 at the top, whatever its height.
#[test]
fn a_cylinder_maps_round_its_axis() {
    let s = scene(
        "{ color: { pattern: uv_checker, width: 2, height: 2, colors: [0, 1] }, ka: 1 }",
        "{ name: can, cylinder: { base: [2, 1, 0], top: [2, 5, 0], radius: 0.5 }, material: m }",
    );
    // The side facing +x, halfway up (y = 3): u = ¼, v = ½; three quarters up, v = ¾.
    for (y, v) in [(3.0, 0.5), (4.0, 0.75)] {
        let uv = trace(&s, [10.0, y, 0.0], [-1.0, 0.0, 0.0])
            .hit
            .unwrap()
            .uv
            .unwrap();
        assert!((uv - DVec2::new(0.25, v)).length() < 1e-12, "{uv}");
    }
}

/// A plane's own uv: from its point, u along n × y and v along u × n; for a wall facing −z
/// that is x and y, for a floor x and z.
#[test]
fn a_plane_maps_along_its_own_axes() {
    let wall = scene(
        "{ color: { pattern: uv_checker, width: 1, height: 1, colors: [0, 1] }, ka: 1 }",
        "{ name: wall, plane: { point: [1, 2, 8], normal: [0, 0, -1] }, material: m }",
    );
    let uv = trace(&wall, [3.3, 3.7, 0.0], [0.0, 0.0, 1.0])
        .hit
        .unwrap()
        .uv
        .unwrap();
    assert!((uv - DVec2::new(2.3, 1.7)).length() < 1e-12, "{uv}");
}

/// The uv checker "Checker pattern in 2D" on a sphere: the four quarters of the (u, v) square.
#[test]
fn uv_checker_of_the_book_on_a_sphere() {
    let s = scene(
        "{ color: { pattern: uv_checker, width: 2, height: 2, colors: [0, 1] }, ka: 1 }",
        "{ name: ball, sphere: { center: [0, 0, 0], radius: 1 }, material: m }",
    );
    // (u, v) = (0.125, 0.304), (0.625, 0.304), (0.375, 0.696), (0.625, 0.696): the quarters
    // (0, 0) and (½, ½) of the book black, (½, 0) and (0, ½) white.
    let at = |p: DVec3| {
        let n = trace(&s, (3.0 * p).to_array(), (-p).to_array());
        n.local.unwrap().color.unwrap()
    };
    assert_eq!(at(DVec3::new(0.5, -0.5, -0.5).normalize()), BLACK);
    assert_eq!(at(DVec3::new(-0.5, -0.5, 0.5).normalize()), WHITE);
    assert_eq!(at(DVec3::new(0.5, 0.5, 0.5).normalize()), WHITE);
    assert_eq!(at(DVec3::new(-0.5, 0.5, 0.5).normalize()), BLACK);
}

// --- Image textures ---

/// Writes a 2×2 PNG: sRGB values 255, 128 (top row), 0, 64 (bottom row), grey.
fn grey_png(path: &std::path::Path) {
    let img = image::GrayImage::from_raw(2, 2, vec![255, 128, 0, 64]).unwrap();
    img.save(path).unwrap();
}

fn srgb(c: f64) -> f64 {
    let c = c / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// An image on a wall (its own uv: x and y from its point), read at texel centres and between
/// them: sRGB values decoded to linear, blended bilinearly.
#[test]
fn an_image_texture_is_decoded_and_filtered() {
    let dir = std::env::temp_dir().join(format!("raytree-texture-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    grey_png(&dir.join("grey.png"));
    let text = "camera: { eye: [0, 0, -10], look_at: [0, 0, 0], width: 8, height: 6 }
ambient: 1
materials:
  m: { color: { image: grey.png }, ka: 1 }
objects:
  - { name: wall, plane: { point: [0, 0, 0], normal: [0, 0, -1] }, material: m }
";
    let path = dir.join("scene.yaml");
    std::fs::write(&path, text).unwrap();
    let s = raytree::scene::load(&path, &Limits::default()).unwrap();
    let at = |u: f64, v: f64| trace(&s, [u, v, -1.0], [0.0, 0.0, 1.0]).color.x;
    // Texel centres: (¼, ¾) is the top left texel, (¾, ¼) the bottom right one.
    assert!((at(0.25, 0.75) - 1.0).abs() < 1e-6);
    assert!((at(0.75, 0.75) - srgb(128.0)).abs() < 1e-6);
    assert!((at(0.25, 0.25) - 0.0).abs() < 1e-6);
    assert!((at(0.75, 0.25) - srgb(64.0)).abs() < 1e-6);
    // (0.4, 0.6): 0.3 of the way from the left centres to the right, and from the top
    // centres down.
    let top = 1.0 + 0.3 * (srgb(128.0) - 1.0);
    let bottom = 0.3 * srgb(64.0);
    assert!((at(0.4, 0.6) - (top + 0.3 * (bottom - top))).abs() < 1e-6);
    // The tree names the texture and the (u, v) it was read at.
    let n = trace(&s, [0.4, 0.6, -1.0], [0.0, 0.0, 1.0]);
    let local = n.local.unwrap();
    assert_eq!(local.patterns[0].pattern, "image grey.png, uv mapping");
    assert!((n.hit.unwrap().uv.unwrap() - DVec2::new(0.4, 0.6)).length() < 1e-12);
    std::fs::remove_dir_all(&dir).ok();
}

/// An image two texels high, red on top and blue below, on a globe and a can: the texels do
/// not wrap round where v ends. The north pole (v = 1) and every point within half a texel of
/// it (v ≥ ¾, the top row's centre) are red, the south pole blue; half a texel below the
/// can's top rim too. Where v wraps, as on a wall, v = 1 reads as v = 0: between the bottom
/// row and the next copy's top row, half and half.
#[test]
fn an_image_on_a_sphere_keeps_its_top_row_at_the_north_pole() {
    let dir = std::env::temp_dir().join(format!("raytree-poles-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let pixels = [[255, 0, 0]; 4]
        .into_iter()
        .chain([[0, 0, 255]; 4])
        .flatten()
        .collect();
    image::RgbImage::from_raw(4, 2, pixels)
        .unwrap()
        .save(dir.join("tb.png"))
        .unwrap();
    let text = "camera: { eye: [0, 0, -10], look_at: [0, 0, 0], width: 8, height: 6 }
ambient: 1
materials:
  m: { color: { image: tb.png }, ka: 1 }
objects:
  - { name: globe, sphere: { center: [0, 0, 0], radius: 1 }, material: m }
  - { name: can, cylinder: { base: [3, -1, 0], top: [3, 1, 0], radius: 1 }, material: m }
  - { name: wall, plane: { point: [0, 0, 5], normal: [0, 0, -1] }, material: m }
";
    let path = dir.join("scene.yaml");
    std::fs::write(&path, text).unwrap();
    let s = raytree::scene::load(&path, &Limits::default()).unwrap();
    let color = |o: [f64; 3], d: [f64; 3]| trace(&s, o, d).color;
    let (red, blue) = (DVec3::X, DVec3::Z);
    let close = |a: DVec3, b: DVec3| (a - b).length() < 1e-9;
    // The poles, along the axis.
    assert!(close(color([0.0, 5.0, 0.0], [0.0, -1.0, 0.0]), red));
    assert!(close(color([0.0, -5.0, 0.0], [0.0, 1.0, 0.0]), blue));
    // y = 0.97 on the globe: v = 1 − acos(0.97)/π = 0.922, above the top row's centre.
    assert!(close(color([0.0, 0.97, -5.0], [0.0, 0.0, 1.0]), red));
    // y = 0.95 on the can: v = 1.95/2 = 0.975.
    assert!(close(color([3.0, 0.95, -5.0], [0.0, 0.0, 1.0]), red));
    // The wall at y = 1 (its own v = 1, wrapped to 0): half red, half blue.
    assert!(close(
        color([-3.0, 1.0, -5.0], [0.0, 0.0, 1.0]),
        (red + blue) / 2.0
    ));
    std::fs::remove_dir_all(&dir).ok();
}

/// A missing or unreadable image is an error at the `image:` key, never a panic.
#[test]
fn missing_and_unreadable_images_are_scene_errors() {
    let dir = std::env::temp_dir().join(format!("raytree-badtexture-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("junk.png"), "not a png").unwrap();
    for (file, fragment) in [
        ("nothing-here.png", "cannot read `nothing-here.png`"),
        ("junk.png", "cannot read `junk.png`"),
        (".", "cannot read `.`"),
    ] {
        let text = format!(
            "camera: {{ eye: [0, 0, -10], look_at: [0, 0, 0] }}
materials:
  m: {{ color: {{ image: {file} }}, ka: 1 }}
objects: []
"
        );
        let path = dir.join("scene.yaml");
        std::fs::write(&path, &text).unwrap();
        let e = raytree::scene::load(&path, &Limits::default()).unwrap_err();
        let shown = e.to_string();
        assert!(
            shown.contains(":3:")
                && shown.contains(":3:24: ")
                && shown.contains(fragment)
                && !shown.contains('\n'),
            "{shown}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A floating-point image with an infinite or NaN texel is refused at the `image:` key,
/// naming the texel: the colour it would give is no colour, and the pixels it reached would
/// come out NaN. (A negative texel, a filter's ringing, counts as no light.)
#[test]
fn an_image_with_a_texel_that_is_no_number_is_a_scene_error() {
    let dir = std::env::temp_dir().join(format!("raytree-inftexture-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (value, shown_value) in [
        (f32::INFINITY, "is inf"),
        (f32::NEG_INFINITY, "is -inf"),
        (f32::NAN, "is NaN"),
    ] {
        let mut texels = image::Rgb32FImage::from_pixel(3, 2, image::Rgb([0.5, 0.5, 0.5]));
        texels.put_pixel(2, 1, image::Rgb([0.5, value, 0.5]));
        image::DynamicImage::ImageRgb32F(texels)
            .save(dir.join("t.exr"))
            .unwrap();
        let path = dir.join("scene.yaml");
        std::fs::write(
            &path,
            "camera: { eye: [0, 0, -10], look_at: [0, 0, 0] }
materials:
  m: { color: { image: t.exr }, ka: 1 }
objects: []
",
        )
        .unwrap();
        let shown = raytree::scene::load(&path, &Limits::default())
            .unwrap_err()
            .to_string();
        assert!(
            shown.contains(":3:24: ")
                && shown.contains("column 2, row 1")
                && shown.contains(shown_value),
            "{shown}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Bad pattern specifications name their place.
#[test]
fn bad_patterns_name_line_and_column() {
    // Columns count from the start of line 2, `materials: { m: ` (16 characters) first.
    let cases = [
        (
            "{ color: { pattern: checker } }",
            "2:37",
            "needs its two values",
        ),
        (
            "{ color: { pattern: checker, colors: [1] } }",
            "2:54",
            "two values A and B, got 1",
        ),
        (
            "{ color: { pattern: plaid, colors: [1, 0] } }",
            "2:37",
            "unknown variant `plaid`",
        ),
        ("{ color: { colors: [1, 0] } }", "2:26", "needs `pattern"),
        (
            "{ color: { pattern: checker, colors: [1, -1] } }",
            "2:58",
            "color must be ≥ 0",
        ),
        (
            "{ kd: { pattern: checker, colors: [1, [1, 0, 0]] } }",
            "2:55",
            "kd must be a number",
        ),
        ("{ kd: [1, 0, 0] }", "2:23", "kd must be a number"),
        ("{ kd: -0.5 }", "2:23", "kd must be ≥ 0, got -0.5"),
        (
            "{ color: { pattern: uv_checker, colors: [1, 0] } }",
            "2:26",
            "needs `width`",
        ),
        (
            "{ color: { pattern: checker, colors: [1, 0], mapping: planar } }",
            "2:71",
            "`mapping` belongs",
        ),
        (
            "{ color: { pattern: checker, colors: [1, 0], colour: 3 } }",
            "2:62",
            "unknown field `colour`",
        ),
        (
            "{ color: { pattern: checker, colors: [1, 0], transform: [ { scale: 0 } ] } }",
            "2:75",
            "scale must not be zero",
        ),
        (
            "{ color: { pattern: checker, image: a.png, colors: [1, 0] } }",
            "2:53",
            "not both",
        ),
        (
            "{ color: { pattern: blend, colors: [1, 0], weight: 2 } }",
            "2:68",
            "weight lies in [0, 1]",
        ),
    ];
    let mut failures = vec![];
    for (material, at, fragment) in cases {
        let text = format!(
            "camera: {{ eye: [0, 0, -10], look_at: [0, 0, 0] }}\nmaterials: {{ m: {material} }}\n"
        );
        match parse(&text, "bad.yaml", None, &Limits::default()) {
            Ok(_) => failures.push(format!("accepted: {material}")),
            Err(e) => {
                let shown = e.to_string();
                if !(shown.starts_with(&format!("bad.yaml:{at}: ")) && shown.contains(fragment)) {
                    failures.push(format!(
                        "{material}\n  got: {shown}\n  want {at} …{fragment}…"
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `inspect --format json`: the hit's `uv` and the local terms' `color` (with the patterns
/// looked up); a missing image exits with status 2 and one line naming file:line:col.
#[test]
fn the_json_tree_and_the_command_line() {
    let dir = std::env::temp_dir().join(format!("raytree-texture-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("globe.yaml");
    std::fs::write(
        &scene,
        "camera: { eye: [0, 0, -10], look_at: [0, 0, 0], width: 8, height: 6 }
ambient: 1
materials:
  m: { color: { pattern: uv_checker, width: 2, height: 2, colors: [0, [1, 0.5, 0]] }, ka: 1 }
objects:
  - { name: ball, sphere: { center: [0, 0, 0], radius: 1 }, material: m }
",
    )
    .unwrap();
    let bin = env!("CARGO_BIN_EXE_raytree");
    let out = std::process::Command::new(bin)
        .args(["inspect", scene.to_str().unwrap()])
        .args(["--ray", "1,0,-5:-0.1,0,1", "--format", "json"])
        .output()
        .unwrap();
    assert!(out.status.success());
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let tree = &doc["tree"];
    let uv = tree["hit"]["uv"].as_array().expect("hit.uv");
    assert_eq!(uv.len(), 2);
    let color = tree["local"]["color"].as_array().expect("local.color");
    assert_eq!(color.len(), 3);
    assert_eq!(tree["local"]["patterns"][0]["varies"], "O");
    assert_eq!(
        tree["local"]["patterns"][0]["pattern"],
        "uv_checker 2×2, uv mapping"
    );
    // A plain material adds none of these fields.
    let plain = dir.join("plain.yaml");
    std::fs::write(
        &plain,
        "camera: { eye: [0, 0, -10], look_at: [0, 0, 0], width: 8, height: 6 }
materials: { m: { color: 1, kd: 1 } }
objects: [ { name: ball, sphere: { center: [0, 0, 0], radius: 1 }, material: m } ]
",
    )
    .unwrap();
    let out = std::process::Command::new(bin)
        .args(["inspect", plain.to_str().unwrap(), "--pixel", "4,3"])
        .args(["--format", "json"])
        .output()
        .unwrap();
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(doc["tree"]["hit"].get("uv").is_none());
    assert!(doc["tree"]["local"].get("color").is_none());

    let missing = dir.join("missing.yaml");
    std::fs::write(
        &missing,
        "camera: { eye: [0, 0, -10], look_at: [0, 0, 0] }
materials:
  m: { color: { image: earth.png, mapping: spherical }, ka: 1 }
",
    )
    .unwrap();
    let out = std::process::Command::new(bin)
        .args(["render", missing.to_str().unwrap(), "-o"])
        .arg(dir.join("out.png"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(
        err.contains("missing.yaml:3:24: ") && err.contains("cannot read `earth.png`"),
        "{err}"
    );
    assert!(!dir.join("out.png").exists());
    std::fs::remove_dir_all(&dir).ok();
}

/// Whitted's picture: a ray through the glass sphere refracts twice and lands on the board,
/// whose checker gives O there: ⌊−0.75⌋ + ⌊0⌋ + ⌊4.25⌋ = −1 + 0 + 4 = 3, odd, the red cell.
/// The tree, with the pattern's line at the board, is pinned.
#[test]
fn a_checker_seen_through_glass_in_whitteds_picture() {
    let s = common::scene_file("lessons/examples/whitted-1980.yaml");
    let tree = Tracer::new(&s).with_depth(3).inspect_pixel(250, 200).tree;
    let board = tree
        .find("refraction/refraction")
        .expect("through the glass");
    let h = board.hit.as_ref().unwrap();
    assert_eq!(h.object, "board");
    assert!((h.point.x + 0.751938).abs() < 1e-6 && (h.point.z - 4.254888).abs() < 1e-6);
    assert_eq!(
        board.local.as_ref().unwrap().color,
        Some(DVec3::new(0.85, 0.12, 0.1))
    );
    insta::assert_snapshot!(
        "whitted_1980_through_glass",
        raytree::trace::text::tree(&tree)
    );
}

/// A mesh's texture coordinates (OBJ `vt`) are blended with the hit's barycentric coordinates:
/// at (0.5, 0.5, 0) of the triangle (0, 0, 0), (2, 0, 0), (0, 2, 0) the weights are
/// (0.5, 0.25, 0.25), so (u, v) = 0.5·(0.1, 0.2) + 0.25·(0.9, 0.3) + 0.25·(0.4, 0.8)
/// = (0.375, 0.375). Moved by a transform, the mesh keeps them.
#[test]
fn a_meshs_vt_coordinates_are_blended_barycentrically() {
    let dir = std::env::temp_dir().join(format!("raytree-vt-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("tri.obj"),
        "v 0 0 0\nv 2 0 0\nv 0 2 0\nvt 0.1 0.2\nvt 0.9 0.3\nvt 0.4 0.8\nf 1/1 2/2 3/3\n",
    )
    .unwrap();
    let path = dir.join("scene.yaml");
    std::fs::write(
        &path,
        "camera: { eye: [0, 0, -10], look_at: [0, 0, 0], width: 8, height: 6 }
ambient: 1
materials:
  m: { color: { pattern: uv_checker, width: 2, height: 2, colors: [0, 1] }, ka: 1 }
objects:
  - { name: tri, mesh: { file: tri.obj }, material: m }
  - { name: moved, mesh: { file: tri.obj }, material: m, transform: [ { translate: [10, 0, 0] } ] }
",
    )
    .unwrap();
    let s = raytree::scene::load(&path, &Limits::default()).unwrap();
    for x in [0.5, 10.5] {
        let uv = trace(&s, [x, 0.5, -1.0], [0.0, 0.0, 1.0])
            .hit
            .unwrap()
            .uv
            .unwrap();
        // The OBJ reader keeps single-precision numbers: 0.1 is 0.1 to 1e-8.
        assert!((uv - DVec2::new(0.375, 0.375)).length() < 1e-7, "{uv}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
