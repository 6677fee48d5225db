//! Fast paths must give exactly what the full routines give: the nearest-hit tests of spheres and
//! planes against their spans, and the scene's direct sphere/plane probes against the general
//! object → leaf → shape route (forced by giving every leaf an identity transform).

use glam::{DAffine3, DMat3, DQuat, DVec3};
use proptest::prelude::*;
use raytree::geometry::{Aabox, Cone, Cylinder, Plane, Ray, Shape, Sphere, Transform, Triangle};
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

/// The nearest hit of a flat CSG object, read off its primitives' spans, is the first
/// crossing of its segment list inside the window, to the bit, with the same surface; the
/// pruning counted is the same, with CSG boxes and pruning on or off.
fn assert_flat_hit_is_the_lists_first_crossing(
    object: &str,
    r: &Ray,
    t_min: f64,
    t_max: f64,
    pruning: bool,
) -> Result<(), TestCaseError> {
    let yaml = format!(
        "camera: {{ eye: [0, 0, -10], look_at: [0, 0, 0] }}\nmaterials: {{ m: {{ kd: 1 }} }}\nobjects:\n  - {object}\n"
    );
    let mut scene = parse(&yaml, "flat.yaml", None, &Limits::default()).unwrap();
    scene.csg_pruning = pruning;
    let mut reference = Stats::default();
    let boxed = !pruning || scene.objects[0].bounds.hit(r, r.dir.recip(), t_min, t_max);
    let expected = boxed
        .then(|| {
            let list = scene.object_segments(0, r, t_min, t_max, &mut reference);
            let (t, surface) = raytree::geometry::first_crossing(&list, t_min)?;
            (t > t_min && t < t_max && t.is_finite()).then_some((t.to_bits(), surface))
        })
        .flatten();
    let mut stats = Stats::default();
    let hit = scene.intersect(r, t_min, t_max, &mut stats);
    prop_assert_eq!(
        hit.map(|h| (h.t.to_bits(), h.surface)),
        expected,
        "{}",
        object
    );
    prop_assert_eq!(stats.csg_pruned, reference.csg_pruned, "{}", object);
    let blocker = scene.occluded(r, t_min, t_max, &mut Stats::default());
    prop_assert_eq!(blocker, hit);
    Ok(())
}

/// Two overlapping spheres (or one inside the other, or apart), and a ray from a point of
/// one sphere's surface, or from anywhere, in any direction: rays that leave a lens outward,
/// pass it by or cross it.
fn lens_and_ray() -> impl Strategy<Value = (String, Ray)> {
    (
        prop::array::uniform3(-1.0..1.0f64),
        0.3..1.5f64,
        prop::array::uniform3(-1.0..1.0f64),
        0.3..1.5f64,
        prop::array::uniform3(-1.0..1.0f64).prop_filter_map("direction", unit),
        prop::array::uniform3(-1.0..1.0f64).prop_filter_map("direction", unit),
        prop::bool::ANY,
    )
        .prop_map(|(a, ra, b, rb, at, dir, on_surface)| {
            let (a, b) = (DVec3::from_array(a), DVec3::from_array(b));
            let sphere = |c: DVec3, r: f64| {
                format!(
                    "{{ sphere: {{ center: [{}, {}, {}], radius: {r} }} }}",
                    c.x, c.y, c.z
                )
            };
            let object = format!(
                "{{ name: lens, material: m, intersection: [ {}, {} ] }}",
                sphere(a, ra),
                sphere(b, rb)
            );
            let origin = if on_surface { a + ra * at } else { 3.0 * at };
            (object, Ray { origin, dir })
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 3000, ..ProptestConfig::default() })]

    #[test]
    fn flat_csg_hits_are_the_segment_lists_first_crossings(
        object in flat_csg(),
        r in csg_ray(),
        t_min in prop::sample::select(vec![0.0, 1e-9, 1.0, 2.5]),
        t_max in prop::sample::select(vec![f64::INFINITY, 3.0]),
        pruning in prop::bool::ANY,
    ) {
        assert_flat_hit_is_the_lists_first_crossing(&object, &r, t_min, t_max, pruning)?;
    }

    /// The same for lenses, whose two spheres are tested side by side and which are left
    /// early where one sphere is missed or lies behind the ray.
    #[test]
    fn lens_hits_are_the_segment_lists_first_crossings(
        (object, r) in lens_and_ray(),
        t_min in prop::sample::select(vec![0.0, 1e-9, 0.5]),
        pruning in prop::bool::ANY,
    ) {
        assert_flat_hit_is_the_lists_first_crossing(&object, &r, t_min, f64::INFINITY, pruning)?;
    }
}

/// A box around c, at least 0.1 from it on every side.
fn box_around(c: DVec3, e: DVec3) -> Shape {
    let e = e.abs() + 0.1;
    Shape::Box(Aabox {
        min: c - e,
        max: c + e,
    })
}

/// A shape, and a transform of the kind it keeps (or any transform, for `keeps = false`).
fn moved_case() -> impl Strategy<Value = (Shape, DAffine3, bool)> {
    let v = |r: f64| prop::array::uniform3(-r..r).prop_map(DVec3::from_array);
    let turn = (v(1.0), -3.2..3.2f64).prop_filter_map("axis", |(a, angle)| {
        Some(DQuat::from_axis_angle(a.try_normalize()?, angle))
    });
    let similarity = (turn, 0.1..10.0f64, prop::bool::ANY, v(5.0)).prop_map(|(q, s, mirror, t)| {
        let m = if mirror { -1.0 } else { 1.0 };
        DAffine3::from_scale_rotation_translation(DVec3::new(m * s, s, s), q, t)
    });
    let axis_scale = (v(3.0), v(5.0)).prop_filter_map("scale", |(s, t)| {
        (s.abs().min_element() > 0.05)
            .then(|| DAffine3::from_scale_rotation_translation(s, DQuat::IDENTITY, t))
    });
    let any = (v(2.0), v(2.0), v(2.0), v(5.0)).prop_filter_map("invertible", |(a, b, c, t)| {
        let m = DAffine3::from_mat3_translation(DMat3::from_cols(a, b, c), t);
        (m.matrix3.determinant().abs() > 0.1).then_some(m)
    });
    let round =
        (v(2.0), 0.2..2.0f64, v(2.0)).prop_filter("axis", |(a, _, b)| (*a - *b).length() > 0.2);
    prop_oneof![
        (v(2.0), 0.2..2.0f64, similarity.clone()).prop_map(|(c, r, m)| (
            Shape::Sphere(Sphere {
                center: c,
                radius: r
            }),
            m,
            true
        )),
        (round.clone(), similarity.clone()).prop_map(|((a, r, b), m)| (
            Shape::Cylinder(Cylinder {
                base: a,
                top: b,
                radius: r
            }),
            m,
            true
        )),
        (round, similarity.clone()).prop_map(|((a, r, b), m)| (
            Shape::Cone(Cone {
                apex: a,
                base: b,
                radius: r
            }),
            m,
            true
        )),
        (v(2.0), v(1.0), axis_scale).prop_map(|(c, e, m)| (box_around(c, e), m, true)),
        (v(2.0), v(1.0), any.clone()).prop_filter_map("normal", |(p, n, m)| {
            Some((
                Shape::Plane(Plane {
                    point: p,
                    normal: n.try_normalize()?,
                }),
                m,
                true,
            ))
        }),
        (v(2.0), v(2.0), v(2.0), any.clone()).prop_filter_map("triangle", |(a, b, c, m)| {
            ((b - a).cross(c - a).length() > 0.1).then_some((
                Shape::Triangle(Triangle { a, b, c }),
                m,
                m.matrix3.determinant() > 0.0,
            ))
        }),
        (v(2.0), 0.2..2.0f64, any.clone()).prop_map(|(c, r, m)| {
            (
                Shape::Sphere(Sphere {
                    center: c,
                    radius: r,
                }),
                m,
                false,
            )
        }),
        (v(2.0), v(1.0), any).prop_map(|(c, e, m)| (box_around(c, e), m, false)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    /// A shape carried to world space (`Shape::moved`) is the shape seen through its
    /// transform: the same span along every ray (t to 1e−9 relative) and the same outward
    /// normals; and the shapes a transform would not keep of their kind are left alone.
    #[test]
    fn shapes_moved_to_world_space_are_the_transformed_shapes(
        (shape, m, keeps) in moved_case(),
        origin in prop::array::uniform3(-12.0..12.0f64),
        aim in prop::array::uniform3(-1.0..1.0f64),
    ) {
        let tf = Transform::new(m);
        let moved = shape.moved(&tf);
        if !keeps {
            // A general transform turns spheres into ellipsoids and boxes into parallelepipeds.
            // Rarely, a random one is close enough to a similarity or a scaling to be kept.
            let kept_of_kind = tf.similarity_scale().is_some()
                || matches!(shape, Shape::Box(_)) && m.matrix3 == DMat3::from_diagonal(DVec3::new(m.matrix3.x_axis.x, m.matrix3.y_axis.y, m.matrix3.z_axis.z));
            prop_assert_eq!(moved.is_some(), kept_of_kind);
            return Ok(());
        }
        let moved = moved.expect("kept of its kind");
        let origin = DVec3::from_array(origin);
        // Aim near the shape (most rays at a random point would miss it).
        let b = shape.bounds();
        let anchor = match &shape {
            Shape::Plane(p) => p.point,
            _ => (b.min + b.max) / 2.0,
        };
        let target = m.transform_point3(anchor + DVec3::from_array(aim));
        let Some(dir) = (target - origin).try_normalize() else {
            return Ok(());
        };
        let ray = Ray { origin, dir };
        let world = moved.span(&ray);
        let local = shape.span(&tf.ray_to_local(&ray));
        match (world, local) {
            (Some(w), Some(l)) => {
                let scale = 1.0 + l.t_in.abs().min(1e6) + l.t_out.abs().min(1e6);
                let close = |a: f64, b: f64| a == b || (a - b).abs() <= 1e-9 * scale;
                prop_assert!(close(w.t_in, l.t_in) && close(w.t_out, l.t_out), "{:?} vs {:?}", w, l);
                // Normals where the ray enters and leaves (faces may differ only at edges,
                // where the two ends' t nearly tie with another face's).
                for (t, wf, lf) in [(w.t_in, w.face_in, l.face_in), (w.t_out, w.face_out, l.face_out)] {
                    if !t.is_finite() || wf != lf {
                        continue;
                    }
                    let p = ray.at(t);
                    let n_world = moved.normal(p, wf as u32);
                    let n_local = tf.normal_to_world(shape.normal(tf.to_local.transform_point3(p), lf as u32));
                    prop_assert!((n_world - n_local).length() < 1e-7, "{} vs {}", n_world, n_local);
                }
            }
            (None, None) => {}
            // A ray that grazes the surface may be a tangent on one side and a miss on the other.
            (w, l) => {
                let width = w.or(l).map(|s| (s.t_out - s.t_in).abs()).unwrap();
                prop_assert!(width < 1e-6 * (1.0 + w.or(l).unwrap().t_in.abs()), "{:?} vs {:?}", w, l);
            }
        }
    }
}
