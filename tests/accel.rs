//! The BVH changes how fast hits are found, never which: for random scenes and rays it returns
//! exactly the brute-force nearest hit. Rendering is identical for any number of threads.

use glam::DVec3;
use proptest::prelude::*;
use raytree::geometry::Ray;
use raytree::render::antialias::grid_offsets;
use raytree::render::film::Film;
use raytree::render::{render_simple, RenderOptions};
use raytree::scene::{parse, Accel, Limits, Scene};
use raytree::trace::sampling::Rng;
use raytree::trace::Stats;

fn random_scene(objects: &[(u8, [f64; 3], f64)]) -> Scene {
    let mut yaml = String::from(
        "camera: { eye: [0, 0, -30], look_at: [0, 0, 0], width: 24, height: 18 }\nambient: 0.1\nmax_depth: 3\nlights: [ { point: [10, 20, -20] } ]\nmaterials: { m: { ka: 0.2, kd: 0.6, kr: 0.3 } }\nobjects:\n",
    );
    yaml.push_str(
        "  - { name: floor, plane: { point: [0, -12, 0], normal: [0, 1, 0] }, material: m }\n",
    );
    for (i, (kind, c, r)) in objects.iter().enumerate() {
        let [x, y, z] = c;
        let shape = match kind % 4 {
            0 => format!("sphere: {{ center: [{x}, {y}, {z}], radius: {r} }}"),
            1 => format!(
                "box: {{ min: [{}, {}, {}], max: [{}, {}, {}] }}",
                x - r,
                y - r,
                z - r,
                x + r,
                y + r,
                z + r
            ),
            2 => format!(
                "cylinder: {{ base: [{x}, {y}, {z}], top: [{}, {}, {z}], radius: {} }}",
                x + r,
                y + r,
                r / 2.0
            ),
            _ => format!(
                "cone: {{ apex: [{x}, {}, {z}], base: [{x}, {y}, {z}], radius: {r} }}",
                y + 2.0 * r
            ),
        };
        yaml.push_str(&format!("  - {{ name: o{i}, {shape}, material: m }}\n"));
    }
    parse(&yaml, "random.yaml", None, &Limits::default()).unwrap()
}

fn objects() -> impl Strategy<Value = Vec<(u8, [f64; 3], f64)>> {
    prop::collection::vec(
        (
            any::<u8>(),
            prop::array::uniform3(-10.0..10.0f64),
            0.2..2.0f64,
        ),
        8..120,
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 60, ..ProptestConfig::default() })]

    #[test]
    fn bvh_finds_the_brute_force_nearest_hit(objs in objects(), rays in prop::collection::vec((prop::array::uniform3(-15.0..15.0f64), prop::array::uniform3(-1.0..1.0f64)), 50)) {
        let mut bvh = random_scene(&objs);
        let mut brute = bvh.clone();
        bvh.set_accel(Accel::Bvh);
        brute.set_accel(Accel::None);
        prop_assume!(bvh.bvh_nodes() > 0);
        for (o, d) in rays {
            let d = DVec3::from_array(d);
            if d.length() < 1e-3 {
                continue;
            }
            let ray = Ray::new(DVec3::from_array(o), d);
            let a = bvh.intersect(&ray, 0.0, f64::INFINITY, &mut Stats::default());
            let b = brute.intersect(&ray, 0.0, f64::INFINITY, &mut Stats::default());
            match (a, b) {
                (Some(a), Some(b)) => {
                    prop_assert!((a.t - b.t).abs() <= 1e-12 * a.t.abs().max(1.0), "{} vs {}", a.t, b.t);
                    // Equal t on two objects is a tie either may win; otherwise the same object.
                    prop_assert!(a.object == b.object || a.t == b.t);
                }
                (None, None) => {}
                (a, b) => prop_assert!(false, "bvh {a:?} vs brute force {b:?}"),
            }
            let sa = bvh.occluded(&ray, 0.0, f64::INFINITY, &mut Stats::default()).is_some();
            let sb = brute.occluded(&ray, 0.0, f64::INFINITY, &mut Stats::default()).is_some();
            prop_assert_eq!(sa, sb);
        }
    }
}

/// The packet search answers every ray exactly as the one-ray search does, hit for hit and
/// counter for counter, also for rays whose signs differ from the first ray's.
fn assert_packet_is_one_by_one(scene: &Scene, rays: &[Ray]) -> Result<(), TestCaseError> {
    let mut packet_stats = Stats::default();
    let mut hits = vec![None; rays.len()];
    scene.intersect_packet(rays, &mut hits, &mut packet_stats);
    let mut single_stats = Stats::default();
    for (ray, hit) in rays.iter().zip(&hits) {
        let single = scene.intersect(ray, 0.0, f64::INFINITY, &mut single_stats);
        prop_assert_eq!(*hit, single, "{:?}", ray);
    }
    prop_assert_eq!(packet_stats, single_stats);
    Ok(())
}

/// The packet's shadow rays are blocked exactly as each ray's own `occluded` says, and the
/// counters are those of asking ray by ray.
fn assert_shadow_packet_is_one_by_one(
    scene: &Scene,
    rays: &[Ray],
    reach: &[f64],
) -> Result<(), TestCaseError> {
    let mut packet_stats = Stats::default();
    let blocked = scene.occluded_packet(rays, reach, &mut packet_stats);
    let mut single_stats = Stats::default();
    for (i, (ray, t)) in rays.iter().zip(reach).enumerate() {
        let single = scene.occluded(ray, 0.0, *t, &mut single_stats).is_some();
        prop_assert_eq!(blocked & (1 << i) != 0, single, "ray {}: {:?}", i, ray);
    }
    prop_assert_eq!(blocked >> rays.len(), 0);
    prop_assert_eq!(packet_stats, single_stats);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 60, ..ProptestConfig::default() })]

    #[test]
    fn a_packet_finds_what_its_rays_find_one_by_one(
        objs in objects(),
        origin in prop::array::uniform3(-15.0..15.0f64),
        aim in prop::array::uniform3(-1.0..1.0f64),
        spread in prop::sample::select(vec![1e-3, 0.05, 2.0]),
        offsets in prop::collection::vec(prop::array::uniform3(-1.0..1.0f64), 1..=16),
    ) {
        let scene = random_scene(&objs);
        prop_assume!(scene.bvh_nodes() > 0);
        // A pixel's samples (a small spread) up to rays in every direction (a large one).
        let rays: Vec<Ray> = offsets
            .iter()
            .map(|o| {
                let d = DVec3::from_array(aim) + spread * DVec3::from_array(*o);
                Ray::new(DVec3::from_array(origin), d.try_normalize().unwrap_or(DVec3::Z))
            })
            .collect();
        assert_packet_is_one_by_one(&scene, &rays)?;
    }
}

/// A scene too small for a BVH: packets test each plain sphere and plane against four rays at
/// a time (`RayLanes`), and other objects ray by ray behind their boxes. Coordinates on a
/// coarse grid, so that tangents, shared centres and rays through centres come up. A plane
/// after sphere k (`planes_after`) breaks the run of spheres there: runs become groups of up
/// to four, a lone sphere its own probe. An object after sphere k (`boxed_after`), centred on
/// it, is one of: a box minus a sphere, a turned box, a cylinder, a lens (∩ of two spheres).
fn scene_without_bvh(
    spheres: &[([i8; 3], u8)],
    planes_after: &[usize],
    boxed_after: &[usize],
) -> Scene {
    let mut yaml = String::from(
        "camera: { eye: [0, 0, -30], look_at: [0, 0, 0], width: 8, height: 6 }\nlights: [ { point: [10, 20, -20] } ]\nmaterials: { m: { kd: 0.6 } }\nobjects:\n",
    );
    for (i, ([x, y, z], r)) in spheres.iter().enumerate() {
        let r = [0.5, 1.0, 1.5, 2.0][*r as usize % 4];
        yaml.push_str(&format!(
            "  - {{ name: s{i}, sphere: {{ center: [{x}, {y}, {z}], radius: {r} }}, material: m }}\n"
        ));
        if planes_after.contains(&i) {
            let (n, h) = [("[0, 1, 0]", -4), ("[1, 0, 0]", 6), ("[0.6, 0, 0.8]", 0)][i % 3];
            yaml.push_str(&format!(
                "  - {{ name: p{i}, plane: {{ point: [0, {h}, 0], normal: {n} }}, material: m }}\n"
            ));
        }
        if boxed_after.contains(&i) {
            let object = match i % 4 {
                0 => "difference: [ { box: { min: [-1, -1, -1], max: [1, 1, 1] } }, { sphere: { center: [0, 0, 0], radius: 1.3 } } ]",
                1 => "box: { min: [-1, -0.5, -1], max: [1, 0.5, 1] }",
                2 => "cylinder: { base: [0, -1, 0], top: [0, 1, 0], radius: 0.75 }",
                _ => "intersection: [ { sphere: { center: [0, 0, -0.5], radius: 1 } }, { sphere: { center: [0, 0, 0.5], radius: 1 } } ]",
            };
            // Turned about y (the box no longer lines up with the axes), then moved.
            yaml.push_str(&format!(
                "  - {{ name: b{i}, {object}, transform: [ {{ rotate_y: 35 }}, {{ translate: [{x}, {y}, {z}] }} ], material: m }}\n"
            ));
        }
    }
    let scene = parse(&yaml, "lanes.yaml", None, &Limits::default()).unwrap();
    assert_eq!(scene.bvh_nodes(), 0);
    scene
}

type ObjectsWithoutBvh = (Vec<([i8; 3], u8)>, Vec<usize>, Vec<usize>);

fn objects_without_bvh() -> impl Strategy<Value = ObjectsWithoutBvh> {
    (
        // Up to 15 bounded objects: 16 would get a BVH.
        prop::collection::vec((prop::array::uniform3(-4i8..=4), any::<u8>()), 1..12),
        prop::collection::vec(0usize..12, 0..4),
        prop::collection::vec(0usize..12, 0..4),
    )
}

/// Rays on the same coarse grid: from points on it, in directions through grid points; or a
/// pixel's samples, alike enough for the packet's hull to rule boxes out for all of them.
fn grid_rays() -> impl Strategy<Value = Vec<Ray>> {
    let scattered = prop::collection::vec(
        (
            prop::array::uniform3(-6i8..=6),
            prop::array::uniform3(-2i8..=2),
        ),
        1..=16,
    )
    .prop_map(|rays| {
        rays.into_iter()
            .map(|(o, d)| {
                let d = DVec3::from_array(d.map(f64::from));
                let d = d.try_normalize().unwrap_or(DVec3::Z);
                Ray::new(DVec3::from_array(o.map(|c| f64::from(c) * 0.5)), d)
            })
            .collect()
    });
    let alike = (
        prop::array::uniform3(-6i8..=6),
        prop::array::uniform3(-2i8..=2),
        prop::sample::select(vec![0.001, 0.05]),
        1..=16usize,
    )
        .prop_map(|(o, d, spread, n)| {
            let origin = DVec3::from_array(o.map(|c| f64::from(c) * 0.5));
            let aim = DVec3::from_array(d.map(f64::from)) + DVec3::new(0.013, 0.007, 0.011);
            (0..n)
                .map(|k| {
                    let (u, v) = ((k % 4) as f64 - 1.5, (k / 4) as f64 - 1.5);
                    Ray::new(origin, aim + spread * DVec3::new(u, v, 0.5 * u - v))
                })
                .collect()
        });
    prop_oneof![scattered, alike]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    /// Scenes without a BVH: the packet's nearest hits, tested four rays at a time, are every
    /// ray's own, to the last bit of t, and so are the counters.
    #[test]
    fn a_packet_of_rays_in_lanes_finds_what_they_find_one_by_one(
        (spheres, planes, boxed) in objects_without_bvh(),
        rays in grid_rays(),
    ) {
        let scene = scene_without_bvh(&spheres, &planes, &boxed);
        assert_packet_is_one_by_one(&scene, &rays)?;
    }

    /// Scenes without a BVH: shadow rays tested four at a time are blocked as one by one, with
    /// any reach, and count the same tests.
    #[test]
    fn shadow_rays_in_lanes_are_blocked_as_one_by_one(
        (spheres, planes, boxed) in objects_without_bvh(),
        rays in grid_rays(),
        reach in prop::sample::select(vec![0.0, 0.5, 3.0, 7.25, f64::INFINITY]),
    ) {
        let scene = scene_without_bvh(&spheres, &planes, &boxed);
        let reach = vec![reach; rays.len()];
        assert_shadow_packet_is_one_by_one(&scene, &rays, &reach)?;
    }
}

/// A CSG object of two operands, spheres, boxes, cylinders or cones on a coarse grid (so that
/// they are often equal, tangent, concentric, one inside the other, or share faces; the
/// cylinders and cones along an axis or tilted), under ∪, ∩ or −, and
/// sometimes turned and moved; with a plane behind it, so that rays that miss it have a limit.
/// Rays from grid points, from points on either operand's surface (rays leaving it, or
/// bouncing inside it), or a pixel's samples.
fn csg_pair_scene_and_rays() -> impl Strategy<Value = (Scene, Vec<Ray>)> {
    let grid = || (-4i32..=4).prop_map(|k| k as f64 * 0.5);
    let operand = move || {
        (
            grid(),
            grid(),
            grid(),
            prop::sample::select(vec![0.5, 1.0, 1.5, 2.0]),
            0..4u8,
            prop::sample::select(vec![DVec3::Y, DVec3::X, DVec3::new(1.0, 1.0, 0.0)]),
        )
            .prop_map(|(x, y, z, r, kind, axis)| (DVec3::new(x, y, z), r, kind, axis))
    };
    let ray = move || {
        (
            (grid(), grid(), grid()),
            prop::array::uniform3(-2i8..=2),
            0..3usize,
            prop::array::uniform3(-1.0..1.0f64),
        )
    };
    (
        operand(),
        operand(),
        prop::sample::select(vec!["intersection", "union", "difference"]),
        prop::sample::select(vec![
            "",
            ", transform: [ { rotate_y: 35 }, { translate: [0.5, 0, -0.5] } ]",
        ]),
        prop::collection::vec(ray(), 1..=16),
    )
        .prop_map(|(a, b, op, transform, rays)| {
            let yaml_of = |(c, r, kind, axis): (DVec3, f64, u8, DVec3)| {
                let v = |p: DVec3| format!("[{}, {}, {}]", p.x, p.y, p.z);
                let (lo, hi) = (c - r * axis, c + r * axis);
                match kind {
                    0 => format!("{{ sphere: {{ center: {}, radius: {r} }} }}", v(c)),
                    1 => format!("{{ box: {{ min: {}, max: {} }} }}", v(c - r), v(c + r)),
                    2 => format!(
                        "{{ cylinder: {{ base: {}, top: {}, radius: {} }} }}",
                        v(lo),
                        v(hi),
                        0.75 * r
                    ),
                    _ => format!(
                        "{{ cone: {{ apex: {}, base: {}, radius: {r} }} }}",
                        v(hi),
                        v(lo)
                    ),
                }
            };
            let yaml = format!(
                "camera: {{ eye: [0, 0, -30], look_at: [0, 0, 0] }}
lights: [ {{ point: [10, 20, -20] }} ]
materials: {{ m: {{ kd: 0.6 }} }}
objects:
  - {{ name: back, plane: {{ point: [0, 0, 6], normal: [0, 0, -1] }}, material: m }}
  - {{ name: pair, material: m, {op}: [ {}, {} ]{transform} }}
",
                yaml_of(a),
                yaml_of(b)
            );
            let scene = parse(&yaml, "pair.yaml", None, &Limits::default()).unwrap();
            let rays = rays
                .into_iter()
                .map(|((x, y, z), d, from, at)| {
                    let d = DVec3::from_array(d.map(f64::from))
                        .try_normalize()
                        .unwrap_or(DVec3::Z);
                    // A point of the operand's surface (of its ball, for a box: on its faces or inside).
                    let on = |(c, r, _, _): (DVec3, f64, u8, DVec3)| {
                        c + r * DVec3::from_array(at).try_normalize().unwrap_or(DVec3::X)
                    };
                    let origin = [DVec3::new(x, y, z), on(a), on(b)][from];
                    Ray::new(origin, d)
                })
                .collect();
            (scene, rays)
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, ..ProptestConfig::default() })]

    /// A CSG object of two spheres, boxes, cylinders or cones tested four rays at a time
    /// (`CsgLanes::hits`)
    /// finds what each ray's own evaluation finds, to the last bit of t and on the same face
    /// of the same operand, and counts the same tests and pruning; with the CSG boxes and
    /// pruning on or off; for nearest hits and for shadow rays of any reach.
    #[test]
    fn a_csg_pair_in_lanes_finds_what_its_rays_find_one_by_one(
        (scene, rays) in csg_pair_scene_and_rays(),
        pruning in prop::bool::ANY,
        reach in prop::sample::select(vec![0.0, 0.5, 1.0, 2.75, f64::INFINITY]),
    ) {
        let mut scene = scene;
        scene.csg_pruning = pruning;
        assert_packet_is_one_by_one(&scene, &rays)?;
        let reach = vec![reach; rays.len()];
        assert_shadow_packet_is_one_by_one(&scene, &rays, &reach)?;
    }
}

/// A peer scene of `benches/peers/` at 40×30, too small for a BVH.
fn small_peer_scene(name: &str) -> Scene {
    let yaml = std::fs::read_to_string(format!("benches/peers/{name}.yaml"))
        .unwrap()
        .replace("width: 800, height: 600", "width: 40, height: 30");
    let scene = parse(&yaml, name, None, &Limits::default()).unwrap();
    assert_eq!((scene.camera.width, scene.bvh_nodes()), (40, 0));
    scene
}

/// The Whitted peer scene (plain spheres and a plane, mirror and glass), small: every pixel,
/// traced in packets with its objects tested four rays at a time, is exactly its samples
/// traced one by one.
#[test]
fn every_pixel_of_a_plain_scene_traced_in_lanes_is_traced_sample_by_sample() {
    let scene = small_peer_scene("whitted");
    let total = assert_pixels_traced_in_packets_are_traced_sample_by_sample(&scene);
    assert!(
        total.shadow_rays > 0 && total.reflection_rays > 0 && total.refraction_rays > 0,
        "{total:?}"
    );
}

/// The CSG peer scene (a glass lens, a box carved by a sphere, a cylinder under a cone, on a
/// plane), small: its CSG objects are tested ray by ray inside the lanes, and every pixel is
/// exactly its samples traced one by one.
#[test]
fn every_pixel_of_the_csg_scene_traced_in_lanes_is_traced_sample_by_sample() {
    let scene = small_peer_scene("csg");
    let total = assert_pixels_traced_in_packets_are_traced_sample_by_sample(&scene);
    assert!(
        total.total_internal_reflections > 0 && total.csg_pruned > 0 && total.bounds_skipped > 0,
        "{total:?}"
    );
}

/// Every kind of light: point (attenuated), directional, an area light (its grid of shadow rays
/// goes one point at a time), a dark one, and one below most surfaces.
const EVERY_KIND_OF_LIGHT: &str = "lights:
  - { name: key, point: [-4, 6, -5], intensity: 0.8, attenuation: [1, 0.05, 0] }
  - { name: sun, direction: [0.3, -1, 0.4], intensity: 0.4 }
  - { name: panel, rect: { corner: [1, 5, -2], u: [1, 0, 0], v: [0, 0, 1] }, intensity: 0.5, samples: 2 }
  - { name: off, point: [0, 8, 0], intensity: 0 }
  - { name: below, point: [0, -5, 0], intensity: 0.3 }
";

/// The end of a `materials:` list (red Phong, mirror, Schlick glass) and the start of an
/// `objects:` list that uses them: a floor and three spheres on it.
const SPHERES_ON_A_FLOOR: &str = "  red: { color: [0.8, 0.1, 0.1], ka: 0.1, kd: 0.8, ks: 0.4, shininess: 40, highlight: phong }
  mirror: { color: 0.1, kd: 0.1, ks: 0.6, shininess: 200, kr: 0.8 }
  glass: { color: 1, kd: 0.05, ks: 0.6, shininess: 200, kr: 0.1, kt: 0.9, ior: 1.5, fresnel: schlick }
objects:
  - { name: floor, plane: { point: [0, 0, 0], normal: [0, 1, 0] }, material: floor }
  - { name: red, sphere: { center: [-1.8, 1, 0.5], radius: 1 }, material: red }
  - { name: mirror, sphere: { center: [0, 1, 1.5], radius: 1 }, material: mirror }
  - { name: glass, sphere: { center: [1.6, 1, -0.5], radius: 1 }, material: glass }
";

/// A plain scene with everything the secondary rays' waves must get right: Fresnel, glass
/// nested in glass (n1/n2 from the geometry), an air bubble inside glass (total internal
/// reflection), distance attenuation of secondary rays, the adaptive threshold and the depth
/// limit, under every kind of light. Every pixel is exactly its samples traced one by one.
#[test]
fn every_pixel_of_a_plain_scene_with_nested_glass_traced_in_waves_is_traced_sample_by_sample() {
    let yaml = [
        "camera: { eye: [0, 2, -9], look_at: [0, 0.8, 0], width: 24, height: 18 }
spp: 9
ambient: 0.2
max_depth: 6
adaptive_threshold: 0.01
secondary_attenuation: [1, 0.05, 0]
",
        EVERY_KIND_OF_LIGHT,
        "materials:
  floor: { color: 0.6, ka: 0.2, kd: 0.8, kr: 0.1 }
  air: { color: 1, kt: 1, kr: 0.2, ior: 1.0 }
  diamond: { color: 1, kd: 0.02, kr: 0.2, kt: 0.8, ior: 2.4 }
",
        SPHERES_ON_A_FLOOR,
        "  - { name: bubble, sphere: { center: [1.7, 1.1, -0.6], radius: 0.45 }, material: air }
  - { name: diamond, sphere: { center: [-0.6, 0.5, -1.5], radius: 0.5 }, material: diamond }
",
    ]
    .concat();
    let scene = parse(&yaml, "nested.yaml", None, &Limits::default()).unwrap();
    assert!(scene.tests_in_lanes());
    let total = assert_pixels_traced_in_packets_are_traced_sample_by_sample(&scene);
    assert!(
        total.total_internal_reflections > 0
            && total.adaptive_cutoffs > 0
            && total.max_depth_cutoffs > 0
            && total.shadow_skipped_dark > 0
            && total.shadow_skipped_backfacing > 0,
        "{total:?}"
    );
}

/// Exact ties: pairs of boxes that share their +x face, one shallow and one deep, so the
/// tree can part them along x. A ray through a shared face meets both at the same t, and the
/// one-ray search keeps whichever it visits first, nearer side first by the ray's own signs. In
/// each packet the first ray points the other way along x: a packet that ordered every ray's
/// visits by that one's signs would keep the other box.
#[test]
fn a_packet_breaks_ties_as_the_one_ray_search_does() {
    let mut yaml = String::from(
        "camera: { eye: [30, 0, 0], look_at: [0, 0, 0] }\nlights: [ { point: [30, 0, 0] } ]\nmaterials: { m: { kd: 1 } }\nobjects:\n",
    );
    for i in 0..24 {
        let (y, z) = ((i % 6) as f64 * 2.5 - 6.25, (i / 6) as f64 * 2.5 - 3.75);
        for (name, back) in [("shallow", 0.5), ("deep", -3.0 - i as f64)] {
            yaml.push_str(&format!(
                "  - {{ name: {name}{i}, box: {{ min: [{back}, {}, {}], max: [1.5, {}, {}] }}, material: m }}\n",
                y - 1.0,
                z - 1.0,
                y + 1.0,
                z + 1.0
            ));
        }
    }
    let scene = parse(&yaml, "ties.yaml", None, &Limits::default()).unwrap();
    assert!(scene.bvh_nodes() > 0);
    let mut ties = 0;
    for k in 0..64 {
        let rays: Vec<Ray> = (0..16)
            .map(|j| {
                let a = (k * 16 + j) as f64 * 0.618_033_988_75;
                let b = (k * 16 + j) as f64 * 0.414_213_562_37;
                let x = if j == 0 { 1.0 } else { -1.0 };
                let d = DVec3::new(x, 0.5 * (a.fract() - 0.5), 0.3 * (b.fract() - 0.5));
                Ray::new(DVec3::new(30.0, 0.0, 0.0), d.normalize())
            })
            .collect();
        assert_packet_is_one_by_one(&scene, &rays).unwrap();
        ties += rays
            .iter()
            .filter(|r| {
                let hit = scene.intersect(r, 0.0, f64::INFINITY, &mut Stats::default());
                hit.is_some_and(|h| (r.origin + h.t * r.dir).x == 1.5)
            })
            .count();
    }
    assert!(ties > 100, "only {ties} rays met a shared face");
}

/// Pixels whose grid samples are traced as packets (`Tracer::radiance_packet`: their nearest
/// hits, then every light's terms and shadow rays for all of them, then their secondary rays)
/// get exactly the value and the counters of tracing their samples one at a time, in order,
/// from the pixel's random numbers (glossy surfaces draw from them, so the order in which
/// samples are shaded matters too).
fn assert_pixels_traced_in_packets_are_traced_sample_by_sample(scene: &Scene) -> Stats {
    let options = RenderOptions::of(scene);
    let film = Film::new(scene, options);
    let no_corners = |_: u32, _: u32, _: &mut Stats| -> DVec3 { unreachable!("grid sampling") };
    let offsets = grid_offsets(options.spp);
    let mut total = Stats::default();
    let (w, h) = (scene.camera.width, scene.camera.height);
    for (x, y) in (0..h).flat_map(|y| (0..w).map(move |x| (x, y))) {
        let mut packed_stats = Stats::default();
        let packed = film.pixel(x, y, &no_corners, &mut packed_stats);
        let mut stats = Stats::default();
        let mut rng = Rng::for_pixel(options.seed, x, y);
        let sum: DVec3 = offsets
            .iter()
            .map(|o| film.sample(x as f64 + o.x, y as f64 + o.y, &mut rng, &mut stats))
            .sum();
        assert_eq!(packed, sum / offsets.len() as f64, "pixel ({x}, {y})");
        assert_eq!(packed_stats, stats, "pixel ({x}, {y})");
        total.add(&stats);
    }
    total
}

/// In a BVH scene: the primary rays and the shadow rays search it as packets.
#[test]
fn every_pixel_traced_in_packets_is_traced_sample_by_sample() {
    let mut yaml = String::from(
        "camera: { eye: [0, 0, -30], look_at: [0, 0, 0], width: 24, height: 18 }\nspp: 16\nmax_depth: 3\nlights: [ { point: [10, 20, -20] } ]\nmaterials: { m: { ka: 0.2, kd: 0.6, kr: 0.3, glossy: { spread: 8, samples: 3 } } }\nobjects:\n  - { name: floor, plane: { point: [0, -12, 0], normal: [0, 1, 0] }, material: m }\n",
    );
    for i in 0..40 {
        let (x, y, z) = (
            (i % 8) as f64 * 3.0 - 10.5,
            (i / 8) as f64 * 3.0 - 6.0,
            (i % 3) as f64,
        );
        yaml.push_str(&format!(
            "  - {{ name: s{i}, sphere: {{ center: [{x}, {y}, {z}], radius: 1.3 }}, material: m }}\n"
        ));
    }
    let scene = parse(&yaml, "packets.yaml", None, &Limits::default()).unwrap();
    assert!(scene.bvh_nodes() > 0);
    let total = assert_pixels_traced_in_packets_are_traced_sample_by_sample(&scene);
    // The pixels did meet the BVH and glossy surfaces, and cast shadow rays.
    assert!(
        total.glossy_rays > 0 && total.bvh_nodes_visited > 0 && total.shadow_rays > 0,
        "{total:?}"
    );
}

/// Without a BVH, and with every kind of light: point, directional, an area light (its grid of
/// shadow rays goes one point at a time), a dark one and one behind most surfaces, over glass,
/// a mirror and a CSG object.
#[test]
fn every_pixel_under_every_kind_of_light_traced_in_packets_is_traced_sample_by_sample() {
    let yaml = [
        "camera: { eye: [0, 2, -9], look_at: [0, 0.8, 0], width: 20, height: 15 }
spp: 9
ambient: 0.2
max_depth: 4
",
        EVERY_KIND_OF_LIGHT,
        "materials:
  floor: { color: 0.6, ka: 0.2, kd: 0.8 }
",
        SPHERES_ON_A_FLOOR,
        "  - name: lens
    intersection:
      - { sphere: { center: [0, 0, 0.5], radius: 1 } }
      - { sphere: { center: [0, 0, -0.5], radius: 1 } }
    transform: [ { translate: [0, 2.6, 0] } ]
    material: glass
",
    ]
    .concat();
    let scene = parse(&yaml, "lights.yaml", None, &Limits::default()).unwrap();
    assert_eq!(scene.bvh_nodes(), 0);
    let total = assert_pixels_traced_in_packets_are_traced_sample_by_sample(&scene);
    assert!(
        total.shadow_skipped_dark > 0
            && total.shadow_skipped_backfacing > 0
            && total.refraction_rays > 0
            && total.reflection_rays > 0,
        "{total:?}"
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 60, ..ProptestConfig::default() })]

    /// Shadow rays from anywhere, in any directions, with any reach: the packet's answer is
    /// every ray's own `occluded`, and so are the counters.
    #[test]
    fn shadow_rays_in_a_packet_are_blocked_as_one_by_one(
        objs in objects(),
        rays in prop::collection::vec(
            (prop::array::uniform3(-15.0..15.0f64), prop::array::uniform3(-1.0..1.0f64), 0.0..40.0f64),
            1..=16,
        ),
        directional in any::<bool>(),
    ) {
        let scene = random_scene(&objs);
        let (rays, reach): (Vec<Ray>, Vec<f64>) = rays
            .iter()
            .map(|(o, d, t)| {
                let d = DVec3::from_array(*d).try_normalize().unwrap_or(DVec3::Y);
                let t = if directional { f64::INFINITY } else { *t };
                (Ray::new(DVec3::from_array(*o), d), t)
            })
            .unzip();
        assert_shadow_packet_is_one_by_one(&scene, &rays, &reach)?;
    }
}

#[test]
fn images_are_identical_for_one_two_and_four_threads() {
    let objs: Vec<(u8, [f64; 3], f64)> = (0..60)
        .map(|i| {
            (
                i as u8,
                [
                    ((i * 7) % 19) as f64 - 9.0,
                    ((i * 5) % 17) as f64 - 8.0,
                    ((i * 3) % 13) as f64,
                ],
                1.0,
            )
        })
        .collect();
    let mut scene = random_scene(&objs);
    scene.camera = scene.camera.resized(64, 48);
    let images: Vec<_> = [1, 2, 4]
        .iter()
        .map(|&n| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap();
            pool.install(|| {
                render_simple(
                    &scene,
                    RenderOptions {
                        max_depth: 3,
                        spp: 4,
                        ..RenderOptions::of(&scene)
                    },
                )
            })
        })
        .collect();
    assert_eq!(images[0].0, images[1].0);
    assert_eq!(images[0].0, images[2].0);
    assert_eq!(images[0].1, images[2].1, "the same work, counted the same");
}

#[test]
fn rays_at_the_torus_mesh_edges_and_vertices_never_leak() {
    let scene = raytree::scene::load(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/examples/torus.yaml"),
        &Limits::default(),
    )
    .unwrap();
    let leaf = scene
        .leaves
        .iter()
        .find(|l| matches!(l.shape, raytree::geometry::Shape::Mesh(_)))
        .unwrap();
    let raytree::geometry::Shape::Mesh(mesh) = &leaf.shape else {
        unreachable!()
    };
    let mut aimed = 0;
    for t in mesh.triangles.iter().step_by(3) {
        for k in 0..3 {
            let (p, q) = (
                mesh.positions[t[k] as usize],
                mesh.positions[t[(k + 1) % 3] as usize],
            );
            for target in [p, 0.5 * (p + q)] {
                // From above, steeply, onto the torus's upper half: the ray must cross the
                // surface an even, non-zero number of times.
                if target.y < 0.05 {
                    continue;
                }
                let from = target + DVec3::new(0.13, 3.0, 0.07);
                let ray = Ray::new(from, target - from);
                let n = leaf.segments(0, &ray).len();
                assert!(n >= 2 && n % 2 == 0, "{n} crossings aiming at {target}");
                aimed += 1;
            }
        }
    }
    assert!(aimed > 1000);
}

/// Bounding boxes change how much work CSG takes, never the image: the CSG peer scene renders
/// the same with them on and off. On, rays skip whole objects by their boxes and subtrees by
/// theirs, and fewer primitives are tested; `--no-csg-pruning` turns every CSG box off, the
/// object's own box included.
#[test]
fn csg_bounding_boxes_skip_work_but_never_change_the_image() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/peers/csg.yaml");
    let mut scene = raytree::scene::load(&path, &Limits::default()).unwrap();
    scene.camera = scene.camera.resized(80, 60);
    let options = RenderOptions {
        spp: 1,
        ..RenderOptions::of(&scene)
    };
    let (boxed, with) = render_simple(&scene, options);
    scene.csg_pruning = false;
    let (unboxed, without) = render_simple(&scene, options);
    assert_eq!(boxed, unboxed);
    assert_eq!(with.rays(), without.rays());
    assert!(with.bounds_skipped > 0 && with.csg_pruned > 0);
    assert_eq!((without.bounds_skipped, without.csg_pruned), (0, 0));
    assert!(with.primitives_tested < without.primitives_tested);
}

/// A lens (the common part of two spheres) is bounded by the ball around its rim, far tighter
/// than its spheres' boxes, and no tighter than the lens: rays along its axis just inside the
/// rim still hit it, where the near sphere says.
#[test]
fn a_lens_is_bounded_by_its_rim_ball_and_still_hit_at_its_rim() {
    let yaml = "camera: { eye: [0, 0, -10], look_at: [0, 0, 0] }\nmaterials: { m: { kd: 1 } }\nobjects:\n  - { name: lens, material: m, intersection: [ { sphere: { center: [0, 0, -1.2], radius: 1.6 } }, { sphere: { center: [0, 0, 1.2], radius: 1.6 } } ], transform: [ { rotate_y: 30 }, { translate: [-2.6, 1.3, 0] } ] }\n";
    let scene = parse(yaml, "lens.yaml", None, &Limits::default()).unwrap();
    let centre = DVec3::new(-2.6, 1.3, 0.0);
    let axis = DVec3::new(30f64.to_radians().sin(), 0.0, 30f64.to_radians().cos());
    // The rim's radius by Pythagoras: √(1.6² − 1.2²). The turn about y keeps the rim's top
    // and bottom at y = 1.3 ± h, so the box's height is the rim's diameter (the spheres'
    // boxes would give 3.2).
    let h = (1.6f64 * 1.6 - 1.2 * 1.2).sqrt();
    let bounds = scene.objects[0].bounds;
    assert!(
        (bounds.max.y - bounds.min.y - 2.0 * h).abs() < 1e-6,
        "{bounds:?}"
    );
    for side in [1.0, -1.0] {
        for rho in [0.5 * h, 0.999 * h] {
            let origin = centre - 5.0 * axis + side * rho * DVec3::Y;
            let ray = Ray { origin, dir: axis };
            let hit = scene.intersect(&ray, 0.0, f64::INFINITY, &mut Stats::default());
            // Along the axis the lens is [1.2 − s, s − 1.2] from its centre, s = √(1.6² − ρ²):
            // it is entered through the far sphere's near side.
            let s = (1.6f64 * 1.6 - rho * rho).sqrt();
            let t = hit.expect("the lens is hit inside its rim").t;
            assert!((t - (5.0 + 1.2 - s)).abs() < 1e-9, "ρ = {rho}: t = {t}");
        }
    }
}
