//! Fast paths must give exactly what the full routines give: the nearest-hit tests of spheres and
//! planes against their spans, and the scene's direct sphere/plane probes against the general
//! object → leaf → shape route (forced by giving every leaf an identity transform).

use glam::{DAffine3, DVec3};
use proptest::prelude::*;
use raytree::geometry::{Plane, Ray, Sphere, Transform};
use raytree::scene::{parse, Accel, Hit, Limits, Scene};
use raytree::trace::Stats;

/// What a nearest-hit search takes from a span: its first finite end inside (t_min, t_max).
fn from_span(span: Option<(f64, f64)>, t_min: f64, t_max: f64) -> Option<f64> {
    let (t_in, t_out) = span?;
    let t = if t_in > t_min { t_in } else { t_out };
    (t > t_min && t < t_max && t.is_finite()).then_some(t)
}

fn bits(t: Option<f64>) -> Option<u64> {
    t.map(f64::to_bits)
}

fn unit(v: [f64; 3]) -> Option<DVec3> {
    DVec3::from_array(v).try_normalize()
}

/// A ray from `origin` whose line passes the centre at (1 + offset) radii (0: tangent), the
/// hardest case for a miss test. None when the origin is inside that distance.
fn grazing_ray(s: &Sphere, origin: DVec3, side: DVec3, offset: f64) -> Option<Ray> {
    let to_centre = s.center - origin;
    let u = to_centre.try_normalize()?;
    let w = side.reject_from(u).try_normalize()?;
    let sin = s.radius * (1.0 + offset) / to_centre.length();
    if sin >= 1.0 {
        return None;
    }
    let dir = (u * (1.0 - sin * sin).sqrt() + w * sin).try_normalize()?;
    Some(Ray { origin, dir })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn sphere_hit_is_the_span_answer(
        scale_exp in -4i32..7,
        centre in prop::array::uniform3(-10.0..10.0f64),
        radius in 0.05..3.0f64,
        origin in prop::array::uniform3(-20.0..20.0f64),
        dir in prop::array::uniform3(-1.0..1.0f64),
        side in prop::array::uniform3(-1.0..1.0f64),
        offset_exp in -17i32..0,
        offset_sign in prop::bool::ANY,
        t_min in prop::sample::select(vec![0.0, 1e-9, 0.5, f64::NEG_INFINITY]),
        t_max in prop::sample::select(vec![f64::INFINITY, 3.0, 30.0]),
    ) {
        let k = 10f64.powi(scale_exp);
        let s = Sphere { center: DVec3::from_array(centre) * k, radius: radius * k };
        let origin = DVec3::from_array(origin) * k;
        let (t_min, t_max) = (t_min * k, t_max * k);
        let mut rays = vec![];
        if let Some(d) = unit(dir) {
            rays.push(Ray { origin, dir: d });
        }
        if let Some(side) = unit(side) {
            let offset = if offset_sign { 1.0 } else { -1.0 } * 10f64.powi(offset_exp);
            rays.extend(grazing_ray(&s, origin, side, offset));
            rays.extend(grazing_ray(&s, origin, side, 0.0));
        }
        for r in rays {
            let span = s.span(&r).map(|s| (s.t_in, s.t_out));
            prop_assert_eq!(
                bits(s.hit(&r, t_min, t_max)),
                bits(from_span(span, t_min, t_max)),
                "{:?} {:?}", s, r
            );
        }
    }

    #[test]
    fn plane_hit_is_the_span_answer(
        point in prop::array::uniform3(-10.0..10.0f64),
        normal in prop::array::uniform3(-1.0..1.0f64),
        origin in prop::array::uniform3(-20.0..20.0f64),
        dir in prop::array::uniform3(-1.0..1.0f64),
        parallel in prop::bool::ANY,
        t_min in prop::sample::select(vec![0.0, 1e-9, 0.5, f64::NEG_INFINITY]),
        t_max in prop::sample::select(vec![f64::INFINITY, 3.0, 30.0]),
    ) {
        let (Some(n), Some(mut d)) = (unit(normal), unit(dir)) else { return Ok(()) };
        if parallel {
            // Exactly parallel where it can be: in the plane spanned by two axes.
            let n = DVec3::Y;
            d = DVec3::new(d.x, 0.0, d.z).try_normalize().unwrap_or(DVec3::X);
            let p = Plane { point: DVec3::from_array(point), normal: n };
            let r = Ray { origin: DVec3::from_array(origin), dir: d };
            let span = p.span(&r).map(|s| (s.t_in, s.t_out));
            prop_assert_eq!(bits(p.hit(&r, t_min, t_max)), bits(from_span(span, t_min, t_max)));
            return Ok(());
        }
        let p = Plane { point: DVec3::from_array(point), normal: n };
        let r = Ray { origin: DVec3::from_array(origin), dir: d };
        let span = p.span(&r).map(|s| (s.t_in, s.t_out));
        prop_assert_eq!(bits(p.hit(&r, t_min, t_max)), bits(from_span(span, t_min, t_max)));
    }
}

fn scene(objects: &[([f64; 3], f64)], planes: &[[f64; 3]]) -> Scene {
    let mut yaml = String::from(
        "camera: { eye: [0, 0, -30], look_at: [0, 0, 0], width: 8, height: 6 }\nlights: [ { point: [10, 20, -20] } ]\nmaterials: { m: { kd: 0.6 } }\nobjects:\n",
    );
    for (i, [x, y, z]) in planes.iter().enumerate() {
        yaml.push_str(&format!(
            "  - {{ name: p{i}, plane: {{ point: [0, 0, 0], normal: [{x}, {y}, {z}] }}, material: m }}\n"
        ));
    }
    for (i, ([x, y, z], r)) in objects.iter().enumerate() {
        yaml.push_str(&format!(
            "  - {{ name: s{i}, sphere: {{ center: [{x}, {y}, {z}], radius: {r} }}, material: m }}\n"
        ));
    }
    parse(&yaml, "fast.yaml", None, &Limits::default()).unwrap()
}

/// The same scene with every leaf given an identity transform: the scene then tests every
/// object through the general route (carry the ray to object space, take the shape's span),
/// with the same arithmetic.
fn through_general_route(s: &Scene) -> Scene {
    let mut slow = s.clone();
    for leaf in &mut slow.leaves {
        leaf.transform = Some(Transform::new(DAffine3::IDENTITY));
    }
    slow
}

/// The hits, and how many objects were looked at: tested, or skipped by their bounding box
/// (the general route checks an object's box first; the direct probes need none).
fn hits(s: &Scene, rays: &[Ray]) -> Vec<(Option<Hit>, Option<Hit>, u64)> {
    let mut stats = Stats::default();
    rays.iter()
        .map(|r| {
            (
                s.intersect(r, 0.0, f64::INFINITY, &mut stats),
                s.occluded(r, 0.0, 25.0, &mut stats),
                stats.primitives_tested + stats.bounds_skipped,
            )
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 60, ..ProptestConfig::default() })]

    #[test]
    fn scene_probes_find_the_general_routes_hits(
        spheres in prop::collection::vec((prop::array::uniform3(-10.0..10.0f64), 0.2..3.0f64), 1..40),
        planes in prop::collection::vec(prop::array::uniform3(-1.0..1.0f64), 0..3),
        rays in prop::collection::vec((prop::array::uniform3(-15.0..15.0f64), prop::array::uniform3(-1.0..1.0f64)), 60),
    ) {
        let planes: Vec<[f64; 3]> = planes.into_iter().filter(|n| unit(*n).is_some()).collect();
        let rays: Vec<Ray> = rays
            .iter()
            .filter_map(|(o, d)| Some(Ray { origin: DVec3::from_array(*o), dir: unit(*d)? }))
            .collect();
        for accel in [Accel::None, Accel::Bvh] {
            let mut fast = scene(&spheres, &planes);
            fast.set_accel(accel);
            let mut slow = through_general_route(&fast);
            slow.set_accel(accel);
            prop_assert_eq!(hits(&fast, &rays), hits(&slow, &rays));
        }
    }
}

/// One primitive of a flat CSG object, as scene YAML. Grid coordinates make ends coincide
/// often (shared faces, equal spheres, rays along faces), the case the flat path must hand on.
fn csg_leaf() -> impl Strategy<Value = String> {
    let grid = || (-3i32..=3).prop_map(|k| k as f64 * 0.5);
    let point = move || (grid(), grid(), grid()).prop_map(|(x, y, z)| format!("[{x}, {y}, {z}]"));
    prop_oneof![
        (point(), prop::sample::select(vec![0.5, 1.0, 1.5]))
            .prop_map(|(c, r)| format!("{{ sphere: {{ center: {c}, radius: {r} }} }}")),
        (point(), prop::array::uniform3(1i32..=4)).prop_map(|(c, e)| {
            let c: Vec<f64> = c[1..c.len() - 1]
                .split(", ")
                .map(|v| v.parse().unwrap())
                .collect();
            let (lo, hi): (Vec<f64>, Vec<f64>) = (0..3)
                .map(|i| (c[i] - e[i] as f64 * 0.25, c[i] + e[i] as f64 * 0.25))
                .unzip();
            format!("{{ box: {{ min: {lo:?}, max: {hi:?} }} }}")
        }),
        (grid(), grid(), prop::sample::select(vec![0.5, 1.0])).prop_map(|(x, z, r)| format!(
            "{{ cylinder: {{ base: [{x}, -1, {z}], top: [{x}, 1, {z}], radius: {r} }} }}"
        )),
        (grid(), grid(), prop::sample::select(vec![0.5, 1.0])).prop_map(|(x, z, r)| format!(
            "{{ cone: {{ apex: [{x}, 1, {z}], base: [{x}, -1, {z}], radius: {r} }} }}"
        )),
        (prop::array::uniform3(-2.0..2.0f64), 0.3..1.8f64)
            .prop_map(|(c, r)| format!("{{ sphere: {{ center: {c:?}, radius: {r} }} }}")),
    ]
}

/// A flat CSG object: one operation over primitives (a difference of two), sometimes with a
/// repeated operand, sometimes moved by a transform.
fn flat_csg() -> impl Strategy<Value = String> {
    (
        prop::sample::select(vec!["union", "intersection", "difference"]),
        prop::collection::vec(csg_leaf(), 2..5),
        0..3usize,
        prop::sample::select(vec![
            "",
            ", transform: [ { rotate_y: 30 }, { translate: [0.5, 0, -0.5] } ]",
            ", transform: [ { translate: [0, 0.5, 0] } ]",
        ]),
    )
        .prop_map(|(op, mut leaves, repeat, transform)| {
            if repeat == 0 {
                leaves[1] = leaves[0].clone();
            }
            if op == "difference" {
                leaves.truncate(2);
            }
            format!(
                "{{ name: x, material: m, {op}: [{}]{transform} }}",
                leaves.join(", ")
            )
        })
}

/// A ray from a grid point (or anywhere) along an axis (or any direction).
fn csg_ray() -> impl Strategy<Value = Ray> {
    let grid = || (-6i32..=6).prop_map(|k| k as f64 * 0.5);
    (
        prop_oneof![
            (grid(), grid(), grid()).prop_map(|(x, y, z)| DVec3::new(x, y, z)),
            prop::array::uniform3(-4.0..4.0f64).prop_map(DVec3::from_array),
        ],
        prop_oneof![
            prop::sample::select(vec![
                DVec3::X,
                -DVec3::X,
                DVec3::Y,
                -DVec3::Y,
                DVec3::Z,
                -DVec3::Z
            ]),
            prop::array::uniform3(-1.0..1.0f64).prop_filter_map("direction", unit),
        ],
    )
        .prop_map(|(origin, dir)| Ray { origin, dir })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 3000, ..ProptestConfig::default() })]

    /// The nearest hit of a flat CSG object, read off its primitives' spans, is the first
    /// crossing of its segment list inside the window, to the bit, with the same surface; the
    /// pruning counted is the same, with CSG boxes and pruning on or off.
    #[test]
    fn flat_csg_hits_are_the_segment_lists_first_crossings(
        object in flat_csg(),
        r in csg_ray(),
        t_min in prop::sample::select(vec![0.0, 1e-9, 1.0, 2.5]),
        t_max in prop::sample::select(vec![f64::INFINITY, 3.0]),
        pruning in prop::bool::ANY,
    ) {
        let yaml = format!(
            "camera: {{ eye: [0, 0, -10], look_at: [0, 0, 0] }}\nmaterials: {{ m: {{ kd: 1 }} }}\nobjects:\n  - {object}\n"
        );
        let mut scene = parse(&yaml, "flat.yaml", None, &Limits::default()).unwrap();
        scene.csg_pruning = pruning;
        let mut reference = Stats::default();
        let boxed = !pruning || scene.objects[0].bounds.hit(&r, r.dir.recip(), t_min, t_max);
        let expected = boxed
            .then(|| {
                let list = scene.object_segments(0, &r, t_min, t_max, &mut reference);
                let (t, surface) = raytree::geometry::first_crossing(&list, t_min)?;
                (t > t_min && t < t_max && t.is_finite()).then_some((t.to_bits(), surface))
            })
            .flatten();
        let mut stats = Stats::default();
        let hit = scene.intersect(&r, t_min, t_max, &mut stats);
        prop_assert_eq!(hit.map(|h| (h.t.to_bits(), h.surface)), expected, "{}", object);
        prop_assert_eq!(stats.csg_pruned, reference.csg_pruned);
        let blocker = scene.occluded(&r, t_min, t_max, &mut Stats::default());
        prop_assert_eq!(blocker, hit);
    }
}
