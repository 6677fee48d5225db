//! Numerical stress: grazing and tangent rays, rays through edges and vertices, rays starting
//! on a surface, refraction up to and beyond the critical angle, nested dielectrics, Fresnel
//! energy, and coincident CSG faces at every scale.

mod common;

use common::scene;

use glam::DVec3;
use proptest::prelude::*;
use raytree::geometry::{Aabox, Ray, Shape, Sphere};
use raytree::scene::Search;
use raytree::shading::optics::{refract, schlick};
use raytree::stats::Stats;
use raytree::trace::{RayKind, Tracer};

proptest! {
    #![proptest_config(ProptestConfig { cases: 500, ..ProptestConfig::default() })]

    /// A ray tangent to a sphere touches it at the tangent point or (within rounding) misses;
    /// never a NaN, never a far-off hit.
    #[test]
    fn tangent_rays_touch_the_sphere_where_they_should(theta in 0.0..std::f64::consts::TAU, phi in 0.1..3.04f64, r in 1e-3..1e3f64, s in -5.0..5.0f64) {
        let sphere = Sphere { center: DVec3::new(1.0, -2.0, 3.0) * r, radius: r };
        let n = DVec3::new(phi.sin() * theta.cos(), phi.cos(), phi.sin() * theta.sin());
        let p = sphere.center + r * n;
        let tangent = n.any_orthonormal_vector();
        let ray = Ray::new(p - (5.0 + s) * r * tangent, tangent);
        if let Some(span) = sphere.span(&ray) {
            prop_assert!(span.t_in.is_finite() && span.t_out.is_finite());
            let mid = ray.at(0.5 * (span.t_in + span.t_out));
            prop_assert!((mid - p).length() < 1e-5 * r, "touches at {mid}, tangent point {p}");
        }
    }

    /// Rays starting exactly on a sphere: outward they leave it, inward they cross to the far
    /// side at the chord length 2r·cos θ.
    #[test]
    fn rays_starting_on_the_surface(theta in 0.0..std::f64::consts::TAU, phi in 0.1..3.04f64, a in 0.05..1.5f64) {
        let s = scene("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmaterials: { m: { kd: 1 } }\nobjects: [ { name: s, sphere: { center: [0, 0, 0], radius: 2 }, material: m } ]");
        let n = DVec3::new(phi.sin() * theta.cos(), phi.cos(), phi.sin() * theta.sin());
        let p = 2.0 * n;
        let t = n.any_orthonormal_vector();
        let inward = Ray::new(p, -(a.cos() * n) + a.sin() * t);
        let bias = s.bias(p, p);
        let hit = s.nearest(&inward, bias, f64::INFINITY, &mut Stats::default()).expect("crosses to the far side");
        prop_assert!((hit.t - 4.0 * a.cos()).abs() < 1e-9, "{} vs {}", hit.t, 4.0 * a.cos());
        let outward = Ray::new(p, a.cos() * n + a.sin() * t);
        prop_assert!(s.nearest(&outward, bias, f64::INFINITY, &mut Stats::default()).is_none());
    }

    /// Snell's law holds to rounding for every angle below the critical angle, the direction
    /// changes continuously, and beyond it there is total internal reflection.
    #[test]
    fn refraction_is_continuous_up_to_the_critical_angle(n1 in 1.0..2.5f64, n2 in 1.0..2.5f64, x in 0.0..1.0f64) {
        let normal = DVec3::Y;
        let critical = if n1 > n2 { (n2 / n1).asin() } else { std::f64::consts::FRAC_PI_2 };
        let theta = x * std::f64::consts::FRAC_PI_2 * 0.999;
        let d = DVec3::new(theta.sin(), -theta.cos(), 0.0);
        match refract(d, normal, n1, n2) {
            Some(t) => {
                prop_assert!(theta <= critical + 1e-12);
                prop_assert!((t.length() - 1.0).abs() < 1e-12);
                prop_assert!((n1 * theta.sin() - n2 * t.x).abs() < 1e-12, "n1 sin θ1 = n2 sin θ2");
                prop_assert!(t.y < 0.0, "goes on through the surface");
                let d2 = DVec3::new((theta + 1e-7).sin(), -(theta + 1e-7).cos(), 0.0);
                if let Some(t2) = refract(d2, normal, n1, n2) {
                    // A 1e−7 turn of the incoming ray turns the refracted one by a bounded amount
                    // (the derivative n1 cos θ1 / (n2 cos θ2) is finite below the critical angle).
                    let bound = 1e-7 * n1 * theta.cos() / (n2 * (-t.y)).max(1e-3) * 1.01 + 1e-12;
                    prop_assert!((t2 - t).length() <= bound);
                }
            }
            None => prop_assert!(theta >= critical - 1e-12, "TIR only beyond {}", critical),
        }
    }

    /// Schlick's reflectance is a fraction: 0 ≤ R ≤ 1 (`tests/formulas.rs` checks what that
    /// gives the tracer's weights: kr·R + kt·(1 − R) between kr and kt).
    #[test]
    fn schlick_weights_stay_between_zero_and_one(c in 0.0..1.0f64, n1 in 1.0..3.0f64, n2 in 1.0..3.0f64) {
        let r = schlick(c, n1, n2);
        prop_assert!((0.0..=1.0).contains(&r), "{r}");
    }
}

#[test]
fn rays_through_box_edges_and_vertices() {
    let b = Shape::Box(Aabox {
        min: DVec3::splat(-1.0),
        max: DVec3::splat(1.0),
    });
    // Through two opposite vertices: enters at (−1,−1,−1), leaves at (1,1,1).
    let r = Ray::new(DVec3::splat(-3.0), DVec3::ONE);
    let s = b.span(&r).unwrap();
    assert!(
        (s.t_in - 2.0 * 3f64.sqrt()).abs() < 1e-12 && (s.t_out - 4.0 * 3f64.sqrt()).abs() < 1e-12
    );
    // Along an edge (x = 1, y = 1): the closed box contains its edges.
    let s = b
        .span(&Ray::new(DVec3::new(1.0, 1.0, -5.0), DVec3::Z))
        .unwrap();
    assert_eq!((s.t_in, s.t_out), (4.0, 6.0));
    // Touching only the vertex (1, 1, 1): from (−1, 3, 2) along (2, −2, −1)/3 the ray reaches
    // it at t = 3 and is outside the box on both sides of it (x > 1 after, y and z > 1
    // before). The closed box holds its vertices: a zero-length span exactly there.
    let touch = b
        .span(&Ray::new(
            DVec3::new(-1.0, 3.0, 2.0),
            DVec3::new(2.0, -2.0, -1.0),
        ))
        .expect("the ray touches a vertex of the closed box");
    assert!(
        (touch.t_in - 3.0).abs() < 1e-12 && (touch.t_out - 3.0).abs() < 1e-12,
        "{touch:?}"
    );
    // Just outside an edge: a miss.
    assert!(b
        .span(&Ray::new(DVec3::new(1.0 + 1e-12, 1.0, -5.0), DVec3::Z))
        .is_none());
}

#[test]
fn nested_dielectrics_keep_the_right_indices() {
    // A glass ball (1.5) holding a water ball (1.33): through the centre the ray meets
    // 1 → 1.5, 1.5 → 1.33, 1.33 → 1.5, 1.5 → 1.
    let s = scene(
        "camera: { eye: [0, 0, -10], look_at: [0, 0, 0] }\nmax_depth: 8\nmaterials:\n  glass: { kt: 1, ior: 1.5 }\n  water: { kt: 1, ior: 1.33 }\nobjects:\n  - { name: glass, sphere: { center: [0, 0, 0], radius: 3 }, material: glass }\n  - { name: water, sphere: { center: [0, 0, 0], radius: 1 }, material: water }\n",
    );
    let tree = Tracer::new(&s).inspect(&Ray::new(DVec3::new(0.0, 0.0, -10.0), DVec3::Z));
    let mut indices = vec![];
    let mut node = &tree;
    while let Some(next) = node.children.iter().find(|c| c.kind == RayKind::Refraction) {
        if let Some(i) = next.indices {
            indices.push((i.n1, i.n2));
        }
        node = next;
    }
    assert_eq!(
        indices,
        vec![(1.0, 1.5), (1.5, 1.33), (1.33, 1.5), (1.5, 1.0)]
    );
}

#[test]
fn touching_slabs_refract_as_one_stack() {
    // Two slabs of different glass share the face z = 1. Across parallel layers n·sin θ is
    // conserved, so the ray leaves the stack parallel to how it entered.
    let s = scene(
        "camera: { eye: [0, 0, -10], look_at: [0, 0, 0] }\nmax_depth: 8\nmaterials:\n  a: { kt: 1, ior: 1.5 }\n  b: { kt: 1, ior: 1.2 }\nobjects:\n  - { name: A, box: { min: [-50, -50, 0], max: [50, 50, 1] }, material: a }\n  - { name: B, box: { min: [-50, -50, 1], max: [50, 50, 2] }, material: b }\n",
    );
    let d = DVec3::new(0.3, 0.1, 1.0).normalize();
    let tree = Tracer::new(&s).inspect(&Ray::new(DVec3::new(0.0, 0.0, -5.0), d));
    let mut node = &tree;
    while let Some(next) = node.children.iter().find(|c| c.kind == RayKind::Refraction) {
        node = next;
    }
    assert!(
        (node.direction - d).length() < 1e-9,
        "{} vs {d}",
        node.direction
    );
    assert!(node.origin.z > 2.0 - 1e-6, "left the stack at its far face");
}

#[test]
fn coincident_csg_faces_give_the_documented_result_at_every_scale() {
    for scale in [1e-4, 1e-2, 1.0, 1e2, 1e4, 1e6] {
        let v =
            |x: f64, y: f64, z: f64| format!("[{:e}, {:e}, {:e}]", x * scale, y * scale, z * scale);
        let yaml = format!(
            "camera: {{ eye: {}, look_at: [0, 0, 0] }}\nmaterials: {{ m: {{ kd: 1 }} }}\nobjects:\n\
             \x20 - {{ name: face, intersection: [ {{ box: {{ min: {}, max: {} }} }}, {{ box: {{ min: {}, max: {} }} }} ], material: m }}\n\
             \x20 - {{ name: merged, union: [ {{ box: {{ min: {}, max: {} }} }}, {{ box: {{ min: {}, max: {} }} }} ], material: m }}\n\
             \x20 - {{ name: flush, difference: [ {{ box: {{ min: {}, max: {} }} }}, {{ box: {{ min: {}, max: {} }} }} ], material: m }}\n",
            v(0.0, 0.0, -10.0),
            v(-1.0, -1.0, 0.0), v(1.0, 1.0, 1.0), v(-1.0, -1.0, 1.0), v(1.0, 1.0, 2.0),
            v(-1.0, -1.0, 0.0), v(1.0, 1.0, 1.0), v(-1.0, -1.0, 1.0), v(1.0, 1.0, 2.0),
            v(-1.0, -1.0, 0.0), v(1.0, 1.0, 2.0), v(-1.0, -1.0, 1.0), v(1.0, 1.0, 2.0),
        );
        let s = scene(&yaml);
        let ray = Ray::new(DVec3::new(0.3, 0.2, -10.0) * scale, DVec3::Z);
        let lists: Vec<Vec<(f64, f64)>> = (0..3)
            .map(|o| {
                s.object_trace(o, &ray, true)
                    .0
                    .iter()
                    .map(|g| (g.t_in / scale, g.t_out / scale))
                    .collect()
            })
            .collect();
        assert!(
            lists[0].is_empty(),
            "scale {scale}: a shared face has no volume: {:?}",
            lists[0]
        );
        assert_eq!(lists[1].len(), 1, "scale {scale}: touching boxes merge");
        assert!((lists[1][0].0 - 10.0).abs() < 1e-9 && (lists[1][0].1 - 12.0).abs() < 1e-9);
        assert_eq!(
            lists[2].len(),
            1,
            "scale {scale}: a flush cut leaves one box"
        );
        assert!((lists[2][0].0 - 10.0).abs() < 1e-9 && (lists[2][0].1 - 11.0).abs() < 1e-9);
    }
}

#[test]
fn a_hollow_glass_sphere_is_entered_and_left_twice() {
    // A CSG shell: glass between radius 1 and 2. Through the centre: air → glass → air (the
    // cavity, bounded by the carved surface with its normal flipped) → glass → air.
    let s = scene(
        "camera: { eye: [0, 0, -10], look_at: [0, 0, 0] }\nmax_depth: 8\nmaterials:\n  glass: { kt: 1, ior: 1.5 }\nobjects:\n  - name: shell\n    difference:\n      - { name: outer, sphere: { center: [0, 0, 0], radius: 2 } }\n      - { name: cavity, sphere: { center: [0, 0, 0], radius: 1 } }\n    material: glass\n",
    );
    let tree = Tracer::new(&s).inspect(&Ray::new(DVec3::new(0.0, 0.0, -10.0), DVec3::Z));
    let mut steps = vec![];
    let mut node = &tree;
    while let Some(next) = node.children.iter().find(|c| c.kind == RayKind::Refraction) {
        let h = node.hit.as_ref().unwrap();
        steps.push((
            h.leaf.clone(),
            h.inside,
            h.t,
            next.indices.map(|i| (i.n1, i.n2)),
        ));
        node = next;
    }
    let expected = [
        ("outer", false, 8.0, (1.0, 1.5)),
        ("cavity", true, 1.0, (1.5, 1.0)),
        ("cavity", false, 2.0, (1.0, 1.5)),
        ("outer", true, 1.0, (1.5, 1.0)),
    ];
    assert_eq!(steps.len(), 4, "{steps:?}");
    for (got, want) in steps.iter().zip(expected) {
        assert_eq!(got.0, want.0);
        assert_eq!(got.1, want.1, "inside flag at {}", want.0);
        assert!((got.2 - want.2).abs() < 1e-6, "t {} vs {}", got.2, want.2);
        assert_eq!(got.3, Some(want.3));
    }
}

/// The lecture's tangent example (lesson 02): the ray from (−3, 1, 0) along (0.8, −0.6, 0)
/// touches the unit sphere at t = 3, at p = (−0.6, −0.8, 0), from outside. Its normal there is
/// the outward one, p itself, and the ray is not inside the ball: n·d is 0 up to rounding, of
/// either sign, and a ray inside a sphere would leave it at an angle.
#[test]
fn a_tangent_ray_touches_the_sphere_from_outside() {
    let s = scene(
        "camera: { eye: [0, 0, -6], look_at: [0, 0, 0] }
lights: [ { name: L, point: [-4, 6, -6] } ]
materials: { chalk: { ka: 0.3, kd: 0.7 } }
objects: [ { name: ball, sphere: { center: [0, 0, 0], radius: 1 }, material: chalk } ]
",
    );
    let tree = Tracer::new(&s).inspect(&Ray::new(
        DVec3::new(-3.0, 1.0, 0.0),
        DVec3::new(0.8, -0.6, 0.0),
    ));
    let h = tree.hit.expect("the tangent ray touches the ball");
    assert!((h.t - 3.0).abs() < 1e-6, "t = {}", h.t);
    assert!(!h.inside, "{h:?}");
    assert!(
        (h.normal - DVec3::new(-0.6, -0.8, 0.0)).length() < 1e-6,
        "{h:?}"
    );
}

/// A sphere far smaller than the rounding of the points around it (radius 10⁻¹² to 10⁻³⁰⁰,
/// seen from 6 away, where a point is known to some 10⁻¹⁵): the hit point rounds off the
/// surface, or onto the centre itself, yet the normal is the unit one facing the eye, and the
/// intensity is the one worked by hand for a point at the origin with n = (0, 0, −1):
/// l = (−4, 6, −6)/√88, n·l = 6/√88; h = (l + v)/|l + v| with v = (0, 0, −1);
/// I = ka·Ia·O + kd·O·(n·l) + ks·(h·n)^20.
#[test]
fn a_sphere_smaller_than_its_points_rounding_keeps_a_unit_normal() {
    let l = DVec3::new(-4.0, 6.0, -6.0).normalize();
    let (n, v) = (DVec3::new(0.0, 0.0, -1.0), DVec3::new(0.0, 0.0, -1.0));
    let h = (l + v).normalize();
    let by_hand = 0.3 * 0.3 * 0.9 + 0.7 * 0.9 * n.dot(l) + 0.5 * h.dot(n).powi(20);
    for radius in ["1e-10", "1e-12", "1e-15", "1e-16", "1e-300"] {
        let s = scene(&format!(
            "camera: {{ eye: [0, 0, -6], look_at: [0, 0, 0] }}
ambient: 0.3
lights: [ {{ name: L, point: [-4, 6, -6] }} ]
materials: {{ chalk: {{ color: 0.9, ka: 0.3, kd: 0.7, ks: 0.5, shininess: 20 }} }}
objects: [ {{ name: s, sphere: {{ center: [0, 0, 0], radius: {radius} }}, material: chalk }} ]
"
        ));
        let tree = Tracer::new(&s).inspect(&Ray::new(DVec3::new(0.0, 0.0, -6.0), DVec3::Z));
        let hit = tree.hit.as_ref().expect("the ray hits the sphere");
        assert_eq!(hit.normal, n, "radius {radius}");
        assert!(
            (tree.color.x - by_hand).abs() < 1e-9,
            "radius {radius}: I = {} against {by_hand}",
            tree.color.x
        );
    }
}

/// A ray from 10¹⁰⁰ away meets the unit sphere where its point rounds to the centre (the
/// point's rounding is 10⁸⁴): the normal still faces the ray.
#[test]
fn a_ray_from_far_beyond_a_sphere_sees_a_normal_facing_it() {
    let s = scene(
        "camera: { eye: [0, 0, -6], look_at: [0, 0, 0] }
lights: [ { point: [-4, 6, -6] } ]
materials: { chalk: { kd: 0.7 } }
objects: [ { name: ball, sphere: { center: [0, 0, 0], radius: 1 }, material: chalk } ]
",
    );
    let tree = Tracer::new(&s).inspect(&Ray::new(DVec3::new(1e100, 0.0, 0.0), -DVec3::X));
    let hit = tree.hit.expect("the ray hits the ball");
    assert_eq!(hit.normal, DVec3::X, "{hit:?}");
    assert!(!hit.inside, "{hit:?}");
}

/// A sphere much larger than the distance to it, met from 6 units off its surface: t = 6
/// within the README's bounds for radii up to 10¹², as the quadratic's c = |o − c|² − r²
/// cancels ever more, and always from outside.
#[test]
fn a_huge_sphere_is_met_within_the_documented_error() {
    for (radius, error) in [(1e3, 1e-12), (1e6, 1e-9), (1e9, 1e-7), (1e12, 1e-5)] {
        let s = scene(&format!(
            "camera: {{ eye: [0, 0, -6], look_at: [0, 0, 0] }}
materials: {{ m: {{ kd: 0.5 }} }}
objects: [ {{ name: s, sphere: {{ center: [0, 0, {radius:e}], radius: {radius:e} }}, material: m }} ]
"
        ));
        let tree = Tracer::new(&s).inspect(&Ray::new(DVec3::new(0.0, 0.0, -6.0), DVec3::Z));
        let hit = tree.hit.expect("the ray meets the sphere");
        assert!(
            (hit.t - 6.0).abs() < error,
            "radius {radius:e}: t = {}",
            hit.t
        );
        assert!(!hit.inside, "radius {radius:e}: met from outside");
    }
}

/// A cylinder and a cone of unit size met by rays from 10³ to 10⁹ away, parallel to z: t is
/// D − √(r(y)² − x²) (r(y) the radius at the ray's height) to the rounding of D, and the
/// point lies on the side. Formed from the far origin, the quadratic's qb² − qa·qc cancelled
/// all but a few digits: at D = 10⁶ the point of x = 0.99999 came out at z = 0, 10⁻⁵ inside.
#[test]
fn a_cylinder_and_a_cone_far_off_are_met_on_their_sides() {
    let shapes = [
        (
            "cylinder: { base: [0, -1, 0], top: [0, 1, 0], radius: 1 }",
            1.0,
        ),
        // At y = 0 the cone from apex y = 1 to a base of radius 1 at y = −1 has radius 1/2.
        (
            "cone: { apex: [0, 1, 0], base: [0, -1, 0], radius: 1 }",
            0.5,
        ),
    ];
    for (shape, r) in shapes {
        let s = scene(&format!(
            "camera: {{ eye: [0, 0, -6], look_at: [0, 0, 0] }}
materials: {{ m: {{ kd: 0.5 }} }}
objects: [ {{ name: s, {shape}, material: m }} ]
"
        ));
        for d in [1e3, 1e6, 1e9] {
            for x in [0.0, 0.5 * r, 0.9999 * r, 0.99999 * r] {
                let ray = Ray::new(DVec3::new(x, 0.0, -d), DVec3::Z);
                let hit = Tracer::new(&s)
                    .inspect(&ray)
                    .hit
                    .expect("the ray meets the side");
                let depth = (r * r - x * x).sqrt();
                let rounding = 4.0 * d * f64::EPSILON;
                assert!(
                    (hit.t - (d - depth)).abs() <= rounding,
                    "{shape} from {d:e}, x = {x}: t = {}, not {}",
                    hit.t,
                    d - depth
                );
                assert!(
                    (hit.point.z + depth).abs() <= rounding,
                    "{shape} from {d:e}, x = {x}: z = {}, not {}",
                    hit.point.z,
                    -depth
                );
            }
        }
    }
}

/// A ray at a cone's tip sees the apex's normal, −a, however the cone was placed: turned by
/// 90° about z, its tip's point is the rounding of cos 90° away from the apex, and the normal
/// used to take that leftover's direction, 90° off the one the cone written in place gives.
#[test]
fn a_cones_tip_has_one_normal_however_the_cone_is_placed() {
    let placed = [
        "cone: { apex: [0, 1, 0], base: [0, -1, 0], radius: 1 }, transform: [ { rotate_z: 90 } ]",
        "cone: { apex: [-1, 0, 0], base: [1, 0, 0], radius: 1 }",
    ];
    for shape in placed {
        let s = scene(&format!(
            "camera: {{ eye: [-1, 0, -5], look_at: [-1, 0, 0] }}
materials: {{ m: {{ kd: 0.5 }} }}
objects: [ {{ name: k, {shape}, material: m }} ]
"
        ));
        let ray = Ray::new(DVec3::new(-1.0, 0.0, -5.0), DVec3::Z);
        let hit = Tracer::new(&s)
            .inspect(&ray)
            .hit
            .expect("the ray meets the tip");
        assert!(
            (hit.normal - DVec3::NEG_X).length() < 1e-12,
            "{shape}: normal {}",
            hit.normal
        );
    }
}
