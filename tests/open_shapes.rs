//! Open cylinders and cones (`capped: false`) against The Ray Tracer Challenge's published
//! cases (chapter "Cylinders": misses, hits, tangents, truncated open cylinders; the cone's
//! hits, its apex and a ray parallel to its side), and as surfaces of a scene.

mod common;

use glam::DVec3;
use raytree::geometry::{Cone, Cylinder, Ray, Shape};
use raytree::scene::{parse, Limits};
use raytree::trace::Tracer;

fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
    Ray::new(DVec3::from(o), DVec3::from(d))
}

/// The crossings a ray makes with a surface without inside, in order (a tangent's once).
fn crossings(s: &Shape, r: &Ray) -> Vec<f64> {
    match s.span(r) {
        None => vec![],
        Some(span) if span.t_in == span.t_out => vec![span.t_in],
        Some(span) => vec![span.t_in, span.t_out],
    }
}

fn near(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-5)
}

/// The span's two ends, as the book lists t0 and t1 (equal for a tangent).
fn ends(s: &Shape, r: &Ray) -> Vec<f64> {
    s.span(r).map_or(vec![], |s| vec![s.t_in, s.t_out])
}

/// The book's cylinder of radius 1 round the y axis, unbounded: here from y = −100 to 100.
fn tube(min: f64, max: f64) -> Shape {
    Shape::OpenCylinder(Cylinder {
        base: DVec3::new(0.0, min, 0.0),
        top: DVec3::new(0.0, max, 0.0),
        radius: 1.0,
    })
}

/// "A ray misses a cylinder": along its surface, along its axis (inside), and past it.
#[test]
fn rays_that_miss_an_open_cylinder() {
    let c = tube(-100.0, 100.0);
    for (o, d) in [
        ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ([0.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
        ([0.0, 0.0, -5.0], [1.0, 1.0, 1.0]),
    ] {
        assert!(crossings(&c, &ray(o, d)).is_empty(), "{o:?} {d:?}");
    }
}

/// "A ray strikes a cylinder": a tangent (t0 = t1 = 5), through the middle (4, 6), and a
/// slanted ray (6.80798, 7.08872).
#[test]
fn rays_that_strike_an_open_cylinder() {
    let c = tube(-100.0, 100.0);
    for (o, d, ts) in [
        ([1.0, 0.0, -5.0], [0.0, 0.0, 1.0], [5.0, 5.0]),
        ([0.0, 0.0, -5.0], [0.0, 0.0, 1.0], [4.0, 6.0]),
        ([0.5, 0.0, -5.0], [0.1, 1.0, 1.0], [6.80798, 7.08872]),
    ] {
        let got = ends(&c, &ray(o, d));
        assert!(near(&got, &ts), "{o:?} {d:?}: {got:?}");
    }
}

/// "Normal vector on a cylinder": across the axis, whatever the height.
#[test]
fn normals_of_an_open_cylinder() {
    let c = tube(-100.0, 100.0);
    for (p, n) in [
        ([1.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
        ([0.0, 5.0, -1.0], [0.0, 0.0, -1.0]),
        ([0.0, -2.0, 1.0], [0.0, 0.0, 1.0]),
        ([-1.0, 1.0, 0.0], [-1.0, 0.0, 0.0]),
    ] {
        let got = c.normal(DVec3::from(p), 0);
        assert!((got - DVec3::from(n)).length() < 1e-12, "{p:?}: {got}");
    }
}

/// "Intersecting a constrained cylinder" (minimum 1, maximum 2, open): out through the open
/// top, above, below, exactly at each rim height (the rims are excluded), and through the
/// middle.
#[test]
fn a_truncated_open_cylinder_of_the_book() {
    let c = tube(1.0, 2.0);
    for (o, d, count) in [
        ([0.0, 1.5, 0.0], [0.1, 1.0, 0.0], 0),
        ([0.0, 3.0, -5.0], [0.0, 0.0, 1.0], 0),
        ([0.0, 0.0, -5.0], [0.0, 0.0, 1.0], 0),
        ([0.0, 2.0, -5.0], [0.0, 0.0, 1.0], 0),
        ([0.0, 1.0, -5.0], [0.0, 0.0, 1.0], 0),
        ([0.0, 1.5, -2.0], [0.0, 0.0, 1.0], 2),
    ] {
        assert_eq!(crossings(&c, &ray(o, d)).len(), count, "{o:?} {d:?}");
    }
    // The book's capped cylinder is hit twice by a ray down its axis (cap, cap); the open one
    // never.
    let along_axis = ray([0.0, 3.0, 0.0], [0.0, -1.0, 0.0]);
    assert!(crossings(&c, &along_axis).is_empty());
    let capped = Shape::Cylinder(Cylinder {
        base: DVec3::new(0.0, 1.0, 0.0),
        top: DVec3::new(0.0, 2.0, 0.0),
        radius: 1.0,
    });
    let s = capped.span(&along_axis).unwrap();
    assert_eq!((s.t_in, s.t_out), (1.0, 2.0));
}

/// The book's double cone x² + z² = y² is two of raytree's cones of 45°, apex at the origin:
/// one opening up (base at y = 100), one down.
fn cone(up: bool) -> Shape {
    let y = if up { 100.0 } else { -100.0 };
    Shape::OpenCone(Cone {
        apex: DVec3::ZERO,
        base: DVec3::new(0.0, y, 0.0),
        radius: 100.0,
    })
}

/// "Intersecting a cone with a ray": through the apex (5, 5), a tangent along a generator's
/// direction (8.66025 twice), and a ray through the lower nappe (4.55006, 49.44994).
#[test]
fn rays_that_strike_an_open_cone() {
    let through_apex = ray([0.0, 0.0, -5.0], [0.0, 0.0, 1.0]);
    assert!(near(&ends(&cone(true), &through_apex), &[5.0, 5.0]));
    let tangent = ray([0.0, 0.0, -5.0], [1.0, 1.0, 1.0]);
    let got = ends(&cone(true), &tangent);
    assert!(near(&got, &[8.66025, 8.66025]), "{got:?}");
    let lower = ray([1.0, 1.0, -5.0], [-0.5, -1.0, 1.0]);
    let got = ends(&cone(false), &lower);
    assert!(near(&got, &[4.55006, 49.44994]), "{got:?}");
    // Neither of those points is on the upper nappe.
    assert!(crossings(&cone(true), &lower).is_empty());
}

/// "Intersecting a cone with a ray parallel to one of its halves": one crossing. The book
/// prints t = 0.35355, which solves 2b·t + c = 0 with its b, already the full linear
/// coefficient; the root of b·t + c = 0 is 0.70711, where the ray, at (0, 0.5, −0.5), does lie
/// on the cone (x² + z² = 0.25 = y²).
#[test]
fn a_ray_parallel_to_a_side_of_the_cone_crosses_it_once() {
    let r = ray([0.0, 0.0, -1.0], [0.0, 1.0, 1.0]);
    let got = crossings(&cone(true), &r);
    // 0.70711 = 1/√2.
    assert!(near(&got, &[std::f64::consts::FRAC_1_SQRT_2]), "{got:?}");
    let p = r.at(got[0]);
    assert!((p.x * p.x + p.z * p.z - p.y * p.y).abs() < 1e-12, "{p}");
}

/// A ray up the axis of an open cone from below its apex meets the surface only at the apex;
/// from the base end it passes through the open base and leaves at the apex.
#[test]
fn rays_along_the_axis_of_an_open_cone() {
    let c = Shape::OpenCone(Cone {
        apex: DVec3::new(0.0, 3.0, 0.0),
        base: DVec3::new(0.0, 1.0, 0.0),
        radius: 1.0,
    });
    assert!(near(
        &crossings(&c, &ray([0.0, 5.0, 0.0], [0.0, -1.0, 0.0])),
        &[2.0]
    ));
    assert!(near(
        &crossings(&c, &ray([0.0, -1.0, 0.0], [0.0, 1.0, 0.0])),
        &[4.0]
    ));
}

/// "Computing the normal vector on a cone", at points of the cone itself: (1, √2, 1) on the
/// upper nappe has the normal (1, −√2, 1)/2, and (−1, −1, 0) on the lower one (−1, 1, 0)/√2.
#[test]
fn normals_of_an_open_cone() {
    let r2 = 2f64.sqrt();
    let n = cone(true).normal(DVec3::new(1.0, r2, 1.0), 0);
    assert!(
        (n - DVec3::new(1.0, -r2, 1.0) / 2.0).length() < 1e-12,
        "{n}"
    );
    let n = cone(false).normal(DVec3::new(-1.0, -1.0, 0.0), 0);
    assert!(
        (n - DVec3::new(-1.0, 1.0, 0.0) / r2).length() < 1e-12,
        "{n}"
    );
}

const TUBE_SCENE: &str = "camera: { eye: [0, 0, -10], look_at: [0, 0, 0], width: 8, height: 6 }
ambient: 0.2
lights: [ { name: L, point: [0, 0, 0] } ]
materials:
  m: { color: 1, ka: 0.2, kd: 0.8 }
objects:
  - { name: tube, cylinder: { base: [0, -1, 0], top: [0, 1, 0], radius: 1, capped: false }, material: m }
";

/// In a scene, a tube is a surface: a ray from outside hits its near wall from outside, a ray
/// from inside sees the inner wall, lit by a light inside the tube, with the normal facing it,
/// and neither is "inside" a solid.
#[test]
fn a_tube_is_a_surface_seen_from_both_sides() {
    let s = common::scene(TUBE_SCENE);
    let outside = Tracer::new(&s).inspect(&ray([0.0, 0.5, -5.0], [0.0, 0.0, 1.0]));
    let h = outside.hit.unwrap();
    assert!((h.t - 4.0).abs() < 1e-12 && !h.inside);
    assert!((h.normal - DVec3::new(0.0, 0.0, -1.0)).length() < 1e-12);
    // Its outer side faces away from the light at the centre: in shadow of itself (n·l < 0).
    assert_eq!(outside.local.as_ref().unwrap().lights[0].shadow, 0.0);
    let inner = Tracer::new(&s).inspect(&ray([0.0, 0.5, 0.0], [0.0, 0.0, 1.0]));
    let h = inner.hit.unwrap();
    assert!((h.t - 1.0).abs() < 1e-12 && !h.inside);
    assert!((h.normal - DVec3::new(0.0, 0.0, -1.0)).length() < 1e-12);
    assert_eq!(inner.local.as_ref().unwrap().lights[0].shadow, 1.0);
    // Looking into the open end, the ray passes the rim and meets the far inner wall.
    let into = Tracer::new(&s).inspect(&ray([0.0, 3.0, -0.5], [0.0, -1.0, 0.5]));
    let h = into.hit.unwrap();
    assert!((h.point.z.hypot(h.point.x) - 1.0).abs() < 1e-12 && h.point.z > 0.0);
}

/// Open shapes have no inside, so they cannot be CSG operands.
#[test]
fn open_shapes_cannot_take_part_in_csg() {
    let text = "camera: { eye: [0, 0, -10], look_at: [0, 0, 0] }
materials: { m: { kd: 1 } }
objects:
  - name: u
    material: m
    union:
      - { sphere: { center: [0, 0, 0], radius: 1 } }
      - { cone: { apex: [0, 2, 0], base: [0, 0, 0], radius: 1, capped: false } }
";
    let e = parse(text, "bad.yaml", None, &Limits::default()).unwrap_err();
    let shown = e.to_string();
    assert!(
        shown.starts_with("bad.yaml:8:9: ") && shown.contains("an open cone (capped: false)"),
        "{shown}"
    );
}

/// A sheet (an open tube, an open cone, a lone triangle) of water has no inside, so crossing
/// it changes no medium: a ray through the water tube's two walls, or through the sheet, meets
/// the glass ball beyond it from the air, 1 → 1.5 going in and 1.5 → 1 coming out, and passes
/// each wall unbent, 1 → 1. (A wall taken for a way into the water would have the ball entered
/// from n1 = 1.33.)
#[test]
fn crossing_a_sheet_changes_no_medium() {
    let sheets = [
        "{ name: sheet, cylinder: { base: [20, -1, 0], top: [20, 3, 0], radius: 1, capped: false }, material: water }",
        "{ name: sheet, cone: { apex: [20, 3, 0], base: [20, -1, 0], radius: 1.5, capped: false }, material: water }",
        "{ name: sheet, triangle: [[21, -3, -3], [21, 3, -3], [21, 0, 4]], material: water }",
    ];
    for sheet in sheets {
        let s = common::scene(&format!(
            "camera: {{ eye: [15, 1, -5], look_at: [20, 1, 0] }}
max_depth: 8
materials:
  water: {{ kt: 1, ior: 1.33 }}
  glass: {{ kt: 1, ior: 1.5 }}
objects:
  - {sheet}
  - {{ name: ball, sphere: {{ center: [25, 1, 0], radius: 1 }}, material: glass }}
"
        ));
        let tree = Tracer::new(&s).inspect(&ray([15.0, 1.0, 0.5], [1.0, 0.0, 0.0]));
        let crossings = common::refraction_crossings(&tree);
        let walls = crossings.iter().take_while(|c| c.0 == "sheet").count();
        assert!((1..=2).contains(&walls), "{sheet}: {crossings:?}");
        assert!(crossings[..walls].iter().all(|c| (c.1, c.2) == (1.0, 1.0)));
        let ball: Vec<(f64, f64)> = crossings[walls..].iter().map(|c| (c.1, c.2)).collect();
        assert_eq!(ball, [(1.0, 1.5), (1.5, 1.0)], "{sheet}: {crossings:?}");
    }
}
