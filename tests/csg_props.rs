//! Property tests: CSG segment lists agree with point membership, and every shape's segment
//! list agrees with an independent inside test, for random solids and random rays.

use glam::DVec3;
use proptest::prelude::*;
use raytree::geometry::Ray;
use raytree::scene::Search;
use raytree::scene::{parse, Limits};
use raytree::stats::Stats;

/// A random solid, written as scene YAML and tested for membership independently.
#[derive(Clone, Debug)]
enum Solid {
    Sphere(DVec3, f64),
    Box(DVec3, DVec3),
    Cylinder(DVec3, DVec3, f64),
    Cone(DVec3, DVec3, f64),
    Op(&'static str, Vec<Solid>),
}

impl Solid {
    fn yaml(&self) -> String {
        let v = |p: DVec3| format!("[{}, {}, {}]", p.x, p.y, p.z);
        match self {
            Solid::Sphere(c, r) => format!("{{ sphere: {{ center: {}, radius: {r} }} }}", v(*c)),
            Solid::Box(a, b) => format!("{{ box: {{ min: {}, max: {} }} }}", v(*a), v(*b)),
            Solid::Cylinder(a, b, r) => format!(
                "{{ cylinder: {{ base: {}, top: {}, radius: {r} }} }}",
                v(*a),
                v(*b)
            ),
            Solid::Cone(a, b, r) => format!(
                "{{ cone: {{ apex: {}, base: {}, radius: {r} }} }}",
                v(*a),
                v(*b)
            ),
            Solid::Op(op, children) => {
                let inner: Vec<String> = children.iter().map(Solid::yaml).collect();
                format!("{{ {op}: [{}] }}", inner.join(", "))
            }
        }
    }

    /// Signed "depth" of membership: > 0 inside, < 0 outside, |value| a lower bound on how
    /// clearly (used to skip points within rounding of a surface).
    fn inside(&self, p: DVec3) -> f64 {
        match self {
            Solid::Sphere(c, r) => r - (p - *c).length(),
            Solid::Box(a, b) => (p - *a).min(*b - p).min_element(),
            Solid::Cylinder(a, b, r) => {
                let axis = (*b - *a).normalize();
                let h = (*b - *a).length();
                let y = (p - *a).dot(axis);
                let radial = r - (p - *a - y * axis).length();
                radial.min(y).min(h - y)
            }
            Solid::Cone(apex, base, r) => {
                let axis = (*base - *apex).normalize();
                let h = (*base - *apex).length();
                let y = (p - *apex).dot(axis);
                let radius_here = r * y / h;
                let radial =
                    (radius_here - (p - *apex - y * axis).length()) * h / (h * h + r * r).sqrt();
                radial.min(y).min(h - y)
            }
            Solid::Op(op, children) => {
                let mut it = children.iter().map(|c| c.inside(p));
                let first = it.next().unwrap();
                it.fold(first, |acc, x| match *op {
                    "union" => acc.max(x),
                    "intersection" => acc.min(x),
                    _ => acc.min(-x),
                })
            }
        }
    }
}

fn vec3(range: f64) -> impl Strategy<Value = DVec3> {
    (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

fn leaf() -> impl Strategy<Value = Solid> {
    prop_oneof![
        (vec3(2.0), 0.3..2.0f64).prop_map(|(c, r)| Solid::Sphere(c, r)),
        (vec3(2.0), vec3(1.0)).prop_map(|(c, e)| Solid::Box(c - e.abs() - 0.1, c + e.abs() + 0.1)),
        (vec3(2.0), vec3(2.0), 0.2..1.5f64)
            .prop_filter("axis", |(a, b, _)| (*a - *b).length() > 0.2)
            .prop_map(|(a, b, r)| Solid::Cylinder(a, b, r)),
        (vec3(2.0), vec3(2.0), 0.2..1.5f64)
            .prop_filter("axis", |(a, b, _)| (*a - *b).length() > 0.2)
            .prop_map(|(a, b, r)| Solid::Cone(a, b, r)),
    ]
}

fn solid() -> impl Strategy<Value = Solid> {
    leaf().prop_recursive(3, 12, 3, |inner| {
        (
            prop_oneof![Just("union"), Just("intersection"), Just("difference")],
            prop::collection::vec(inner, 2..4),
        )
            .prop_map(|(op, children)| Solid::Op(op, children))
    })
}

fn ray() -> impl Strategy<Value = Ray> {
    (vec3(6.0), vec3(1.0))
        .prop_filter("direction", |(_, d)| d.length() > 0.1)
        .prop_map(|(o, d)| Ray::new(o, d))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn segment_lists_agree_with_point_membership(s in solid(), r in ray()) {
        let yaml = format!(
            "camera: {{ eye: [0, 0, -10], look_at: [0, 0, 0] }}\nmaterials: {{ m: {{ kd: 1 }} }}\nobjects:\n  - {{ name: x, material: m, {} }}\n",
            &s.yaml()[2..s.yaml().len() - 2]
        );
        let scene = parse(&yaml, "prop.yaml", None, &Limits::default()).unwrap();
        let (list, _) = scene.object_trace(0, &r, true);
        // Ordered and non-overlapping.
        for w in list.windows(2) {
            prop_assert!(w[0].t_out < w[1].t_in, "{list:?}");
        }
        for g in &list {
            prop_assert!(g.t_in <= g.t_out);
        }
        // Every sample point along the ray is inside exactly when a segment covers it.
        for k in 0..200 {
            let t = -12.0 + 24.0 * (k as f64 + 0.5) / 200.0;
            let depth = s.inside(r.at(t));
            if depth.abs() < 1e-7 {
                continue;
            }
            let covered = list.iter().any(|g| g.t_in <= t && t <= g.t_out);
            prop_assert_eq!(covered, depth > 0.0, "t = {} depth = {} list = {:?}", t, depth, list);
        }
        // The nearest hit the renderer uses is the first crossing of the full list.
        let hit = scene.nearest(&r, 0.0, f64::INFINITY, &mut Stats::default());
        let first = list.iter().flat_map(|g| [g.t_in, g.t_out]).find(|&t| t > 0.0 && t.is_finite());
        match (hit, first) {
            (Some(h), Some(t)) => prop_assert!((h.t - t).abs() < 1e-9, "{} vs {}", h.t, t),
            (None, None) => {}
            (h, t) => prop_assert!(false, "intersect {:?} vs list {:?}", h, t),
        }
        // Normals at the hit are unit and the point lies on the list's boundary.
        if let Some(h) = hit {
            let si = scene.interaction(&r, &h);
            prop_assert!((si.normal.length() - 1.0).abs() < 1e-9);
            prop_assert!(si.normal.dot(r.dir) <= 1e-12, "shading normal faces the ray");
            prop_assert!(s.inside(si.point).abs() < 1e-6, "hit point off the surface: {}", s.inside(si.point));
        }
    }
}
