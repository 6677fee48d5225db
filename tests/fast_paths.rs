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
