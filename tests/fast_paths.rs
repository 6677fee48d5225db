//! The fast wing's contract: everything it computes equals, bit for bit, what the textbook
//! core computes, and so do the counters of rays and of skipped shading. The counters of the
//! searches' work may differ: a packet of shadow rays tries the last blocker toward its light
//! first, and is spared walks of the BVH.
//!
//! - Whole images: every lesson scene and peer scene rendered by both engines.
//! - Pixels traced as packets against the core tracing their samples one by one, on scenes
//!   built to reach every branch of the packet code (BVH and lanes, every kind of light, nested
//!   glass, total internal reflection, the adaptive threshold, glossy surfaces).
//! - The searches: the fast one-ray search, the packet search (BVH packets and SIMD lanes) and
//!   the flat-CSG shortcut against the core's `Scene::nearest` and `Scene::blocker`, and the
//!   direct sphere and plane tests against their shapes' spans, under property tests.

mod common;

use glam::DVec3;
use proptest::prelude::*;
use raytree::fast::{plane_hit, sphere_hit, DiffusePaths, FastScene};
use raytree::geometry::{Plane, Ray, Sphere};
use raytree::render::film::Film;
use raytree::render::{render_simple, render_through, Engine, RenderOptions};
use raytree::scene::{parse, Accel, Hit, Limits, Scene, Search};
use raytree::shading::LightKind;
use raytree::stats::Stats;
use raytree::trace::path::PathTracer;
use raytree::trace::{TraceOptions, Tracer};

// --- Whole images ---

/// Renders the scene with both engines: the same pixels to the last bit, the same counters
/// of rays and shading, and no more BVH nodes visited. Answers both engines' counters.
fn assert_engines_agree(name: &str, scene: &Scene, spp: u32) -> (Stats, Stats) {
    let fast = RenderOptions {
        spp,
        ..RenderOptions::of(scene)
    };
    let core = RenderOptions {
        engine: Engine::Core,
        ..fast
    };
    let (a, sa) = render_simple(scene, fast);
    let (b, sb) = render_simple(scene, core);
    for (i, (p, q)) in a.pixels.iter().zip(&b.pixels).enumerate() {
        assert_eq!(
            p.to_array().map(f64::to_bits),
            q.to_array().map(f64::to_bits),
            "{name} at {spp} spp: pixel {} differs: fast {p} core {q}",
            i
        );
    }
    assert_eq!(
        rays_and_shading(sa),
        rays_and_shading(sb),
        "{name} at {spp} spp: counters differ"
    );
    assert!(
        sa.bvh_nodes_visited <= sb.bvh_nodes_visited,
        "{name} at {spp} spp: {} BVH nodes against the core's {}",
        sa.bvh_nodes_visited,
        sb.bvh_nodes_visited
    );
    (sa, sb)
}

/// The counters of rays and of skipped shading; the counters of the searches' own work (BVH
/// nodes, objects tested, boxes missed, CSG subtrees pruned) set to zero.
fn rays_and_shading(stats: Stats) -> Stats {
    Stats {
        bvh_nodes_visited: 0,
        primitives_tested: 0,
        bounds_skipped: 0,
        csg_pruned: 0,
        ..stats
    }
}

/// Every scene of every lesson, small, at 1 and 16 samples per pixel (and the scene's own).
#[test]
fn every_lesson_scene_renders_the_same_with_both_engines() {
    let mut count = 0;
    for path in common::lesson_scene_files() {
        let mut scene = raytree::scene::load(&path, &Limits::default()).unwrap();
        let (w, h) = (scene.camera.width.min(48), scene.camera.height.min(36));
        scene.camera = scene.camera.resized(w, h);
        let name = path.display().to_string();
        for spp in [1, 16, scene.spp] {
            assert_engines_agree(&name, &scene, spp);
        }
        count += 1;
    }
    assert!(count >= 40, "only {count} lesson scenes found");
}

/// The peer scenes of `benches/peers/` (mirror and glass spheres; CSG; 10 000 spheres in a
/// BVH), small.
#[test]
fn every_peer_scene_renders_the_same_with_both_engines() {
    for name in ["whitted", "csg"] {
        let scene = common::scene_file_resized(&format!("benches/peers/{name}.yaml"), 64, 48);
        for spp in [1, 16] {
            assert_engines_agree(name, &scene, spp);
        }
    }
    let many = common::scene(&common::many_spheres(10_000));
    // 31 columns: the last packet of a row holds fewer pixels than the others.
    let many = Scene {
        camera: many.camera.resized(31, 24),
        ..many
    };
    assert!(many.bvh_nodes() > 0);
    for spp in [1, 4, 16] {
        assert_engines_agree("many", &many, spp);
    }
}

/// Seventy boxes searched without a BVH (`--accel none`), the first far off, so that every
/// packet rules its box out at once: the packet's verdicts are kept one bit per object for
/// the first 64, and the boxes beyond them are each tested, not mistaken for the first.
#[test]
fn boxes_beyond_the_sixty_fourth_without_a_bvh_are_the_cores() {
    let mut yaml = String::from(
        "camera: { eye: [0, 5, -30], look_at: [0, 0, 0], width: 40, height: 30 }\n\
         lights: [ { point: [10, 20, -10] } ]\nmaterials: { m: { kd: 0.8 } }\nobjects:\n\
         - { box: { min: [100, 100, 100], max: [101, 101, 101] }, material: m }\n",
    );
    for i in 0..69 {
        let (x, y) = (
            f64::from(i % 10) * 2.2 - 10.0,
            f64::from(i / 10) * 2.2 - 7.0,
        );
        yaml.push_str(&format!(
            "- {{ box: {{ min: [{x}, {y}, 0], max: [{}, {}, 1.5] }}, material: m }}\n",
            x + 1.5,
            y + 1.5
        ));
    }
    let mut scene = common::scene(&yaml);
    scene.set_accel(Accel::None);
    let (fast, _) = assert_engines_agree("70 boxes", &scene, 16);
    assert!(fast.shadow_rays > 0);
}

/// Under a canopy of spheres, the shadow rays of neighbouring pixels toward a light are
/// blocked by the same sphere: a packet of them tries the last blocker toward that light
/// first, and is spared most of its walks of the BVH, with the same image.
#[test]
fn shadow_packets_try_the_last_blocker_first() {
    let mut yaml = String::from(
        "camera: { eye: [0, 6, -10], look_at: [0, 0, 0], fov: 40, width: 48, height: 36 }
lights:
  - { name: sun, point: [1, 30, -2] }
  - { name: lamp, point: [-20, 12, -5], intensity: 0.5 }
materials:
  m: { color: 0.7, ka: 0.1, kd: 0.8 }
objects:
  - { name: floor, plane: { point: [0, 0, 0], normal: [0, 1, 0] }, material: m }
",
    );
    // Sixteen spheres in a row: a BVH; and three wide ones high above, the canopy.
    for k in 0..16 {
        let x = k as f64 * 0.5 - 4.0;
        yaml.push_str(&format!(
            "  - {{ sphere: {{ center: [{x}, 0.2, 3], radius: 0.2 }}, material: m }}\n"
        ));
    }
    for x in [-3.0, 0.0, 3.0] {
        yaml.push_str(&format!(
            "  - {{ sphere: {{ center: [{x}, 5, 0], radius: 1.5 }}, material: m }}\n"
        ));
    }
    let scene = common::scene(&yaml);
    assert!(scene.bvh_nodes() > 0);
    let (fast, core) = assert_engines_agree("canopy", &scene, 16);
    assert!(
        (fast.bvh_nodes_visited as f64) < 0.9 * core.bvh_nodes_visited as f64,
        "{} BVH nodes against the core's {}",
        fast.bvh_nodes_visited,
        core.bvh_nodes_visited
    );
}

/// A room of diffuse boxes lit by `lights`, path traced to `depth` with `rules`.
fn diffuse_room(lights: &str, depth: u32, rules: &str) -> Scene {
    common::scene(&format!(
        r#"
integrator: path
camera: {{ eye: [0, 0, 3.9], look_at: [0, 0, 0], up: [0, 1, 0], fov: 40, width: 24, height: 20 }}
background: 0.05
max_depth: {depth}
stop_rules: [{rules}]
spp: 4
lights:
{lights}
materials:
  white: {{ color: [0.8, 0.7, 0.6], kd: 1 }}
  red: {{ color: [0.6, 0.05, 0.05], kd: 0.9 }}
  black: {{ color: 0, kd: 0 }}
  glow: {{ color: 0.5, kd: 0.5, emission: [0.3, 0.2, 0.1] }}
objects:
  - {{ name: floor, box: {{ min: [-1, -1.1, -1], max: [1, -1, 1] }}, material: white }}
  - {{ name: ceiling, box: {{ min: [-1, 1, -1], max: [1, 1.1, 1] }}, material: white }}
  - {{ name: back, box: {{ min: [-1, -1, -1.1], max: [1, 1, -1] }}, material: glow }}
  - {{ name: left, box: {{ min: [-1.1, -1, -1], max: [-1, 1, 1] }}, material: red }}
  - {{ name: soot, sphere: {{ center: [0.5, -0.7, 0.2], radius: 0.3 }}, material: black }}
  - name: block
    box: {{ min: [-1, -1, -1], max: [1, 1, 1] }}
    transform: [ {{ scale: 0.3 }}, {{ rotate_y: -17.0 }}, {{ translate: [-0.3, -0.7, 0.1] }} ]
    material: white
"#
    ))
}

/// Path-traced scenes of diffuse surfaces only, which the wing traces with its own path tracer
/// (`DiffusePaths`): rectangle lights (one facing away, one that reflects), a sphere light, a
/// point light (which a path tracer ignores), emitting and black surfaces, a short and a long
/// maximum depth (roulette from the fourth bounce), and seed 002's local light at the maximum
/// depth: the same pixels and counters as the core's path tracer.
#[test]
fn diffuse_scenes_path_traced_by_the_wing_are_the_cores() {
    let ceiling = "  - { name: lamp, rect: { corner: [-0.23, 0.99, -0.18], u: [0.46, 0, 0], v: [0, 0, 0.38] }, intensity: [18, 14, 7], surface: white }";
    let floor = "  - { name: up, rect: { corner: [-0.5, -0.98, 0.5], u: [0.3, 0, 0], v: [0, 0, 0.2] }, intensity: 3 }";
    let ball =
        "  - { name: ball, sphere: { center: [0.6, 0.6, -0.5], radius: 0.15 }, intensity: 6 }";
    let point = "  - { name: bulb, point: [0, 0.5, 0.5], intensity: 1 }";
    let cases = [
        (vec![ceiling], 8, ""),
        (vec![ceiling, floor, ball, point], 8, ""),
        (vec![point, ball, ceiling], 2, ""),
        (vec![ceiling, ball], 3, "local_at_max_depth"),
        (vec![ceiling], 1, "local_at_max_depth"),
    ];
    for (lights, depth, rules) in cases {
        let scene = diffuse_room(&lights.join("\n"), depth, rules);
        let name = format!("{} lights, depth {depth}, rules [{rules}]", lights.len());
        assert!(
            DiffusePaths::new(PathTracer::new(&scene, depth)).is_some(),
            "{name}: the wing's diffuse path tracer should take this scene"
        );
        for spp in [1, 16] {
            assert_engines_agree(&name, &scene, spp);
        }
    }
}

/// A surface that reflects or transmits (kr, kt, or a pattern) keeps the scene with the core's
/// path tracer, whose mirror and glass lobes the wing's diffuse one does not have.
#[test]
fn scenes_with_mirrors_glass_or_patterns_keep_the_cores_path_tracer() {
    let lamp = "  - { name: lamp, rect: { corner: [-0.23, 0.99, -0.18], u: [0.46, 0, 0], v: [0, 0, 0.38] }, intensity: 10 }";
    let plain = diffuse_room(lamp, 8, "");
    assert!(DiffusePaths::new(PathTracer::new(&plain, 8)).is_some());
    for (what, material) in [
        ("a mirror", "{ color: 1, kd: 0.2, kr: 0.5 }"),
        ("glass", "{ color: 1, kt: 0.9, ior: 1.5 }"),
        (
            "a checker",
            "{ color: { pattern: checker, colors: [0.9, 0.1] }, kd: 1 }",
        ),
    ] {
        let yaml = format!(
            "integrator: path\ncamera: {{ eye: [0, 0, 3], look_at: [0, 0, 0], up: [0, 1, 0], fov: 40, width: 8, height: 8 }}\nlights:\n{lamp}\nmaterials:\n  m: {material}\nobjects:\n  - {{ name: s, sphere: {{ center: [0, 0, 0], radius: 0.5 }}, material: m }}\n"
        );
        let scene = common::scene(&yaml);
        assert!(
            DiffusePaths::new(PathTracer::new(&scene, 8)).is_none(),
            "{what}: the wing's diffuse path tracer must not take it"
        );
        assert_engines_agree(what, &scene, 4);
    }
}

// --- Pixels traced as packets ---

/// Pixels whose grid samples the fast wing traces as packets (their nearest hits, then every
/// light's terms and shadow rays for all of them, then their secondary rays in waves) get
/// exactly the value and the counters of the core tracing their samples one at a time, in
/// order, from the pixel's random numbers (glossy surfaces draw from them, so the order in
/// which samples are shaded matters too). Without a BVH, where the packets test every object
/// four rays at a time, the counters of the searches' work (objects tested, boxes missed, CSG
/// subtrees pruned) are the core's too.
fn assert_pixels_traced_in_packets_are_traced_sample_by_sample(scene: &Scene) -> Stats {
    assert_pixels_traced_in_packets_with(scene, |_| {})
}

/// As `assert_pixels_traced_in_packets_are_traced_sample_by_sample`, both tracers' options set
/// by `options`.
fn assert_pixels_traced_in_packets_with(scene: &Scene, options: fn(&mut TraceOptions)) -> Stats {
    let fast = Film::new(scene, RenderOptions::of(scene));
    let core = Film::new(
        scene,
        RenderOptions {
            engine: Engine::Core,
            ..RenderOptions::of(scene)
        },
    );
    let no_corners = |_: &mut Tracer, _: u32, _: u32| -> DVec3 { unreachable!("grid sampling") };
    let mut total = Stats::default();
    let (w, h) = (scene.camera.width, scene.camera.height);
    for (x, y) in (0..h).flat_map(|y| (0..w).map(move |x| (x, y))) {
        let (mut packed, mut one_by_one) = (fast.tracer(), core.tracer());
        options(&mut packed.options);
        options(&mut one_by_one.options);
        let value = fast.pixel(&mut packed, x, y, &no_corners);
        let expected = core.pixel(&mut one_by_one, x, y, &no_corners);
        assert_eq!(
            value.to_array().map(f64::to_bits),
            expected.to_array().map(f64::to_bits),
            "pixel ({x}, {y})"
        );
        assert_eq!(
            rays_and_shading(packed.stats),
            rays_and_shading(one_by_one.stats),
            "pixel ({x}, {y})"
        );
        if scene.bvh_nodes() == 0 {
            assert_eq!(packed.stats, one_by_one.stats, "pixel ({x}, {y})");
        }
        // A packet of shadow rays tries the last blocker toward the light first, which spares
        // it walks of the BVH (and its few tests can make the objects tested more or fewer).
        assert!(
            packed.stats.bvh_nodes_visited <= one_by_one.stats.bvh_nodes_visited,
            "pixel ({x}, {y})"
        );
        total.add(&one_by_one.stats);
    }
    total
}

/// The grid samples of neighbouring pixels of a row go into one packet (as many pixels as fill
/// it): each pixel gets, to the bit, the value the core gives it sample by sample, and the
/// packet the counters of rays and shading of the core's pixels together. In a BVH scene a
/// packet is 32 rays: at 1, 4, 9 and 16 samples a pixel, 32, 8, 3 and 2 pixels; a row of 16
/// pixels is a shorter packet at 1, and ends in one at 9.
#[test]
fn neighbouring_pixels_traced_as_one_packet_are_the_cores_pixels() {
    let mut scene = common::scene(&common::many_spheres(400));
    scene.camera = scene.camera.resized(16, 12);
    assert!(scene.bvh_nodes() > 0);
    let reflected = assert_packed_pixels_are_the_cores(&scene, &[(1, 32), (4, 8), (9, 3), (16, 2)]);
    assert!(reflected > 0, "the mirror spheres were seen");
}

/// Where the objects are tested four rays at a time (no BVH) a packet is the 32 rays shaded
/// together: at 1, 2, 4, 9 and 16 samples a pixel, 32, 16, 8, 3 and 2 pixels of the Whitted
/// peer scene (a row of 40 ends in a shorter packet at 1, 9 and 16); 25 samples fill a packet
/// alone.
#[test]
fn neighbouring_pixels_tested_in_lanes_as_one_packet_are_the_cores_pixels() {
    let scene = small_peer_scene("whitted");
    let groups = [(1, 32), (2, 16), (4, 8), (9, 3), (16, 2)];
    let reflected = assert_packed_pixels_are_the_cores(&scene, &groups);
    assert!(reflected > 0, "the mirror and the glass were seen");
    let film = Film::new(
        &scene,
        RenderOptions {
            spp: 25,
            ..RenderOptions::of(&scene)
        },
    );
    assert_eq!(film.pixels_per_packet(), 1, "25 spp");
}

/// A corridor of two facing mirrors, as deep as a scene may ask (64 levels): every primary
/// ray bounces from one mirror to the other until the depth limit, so each sample traces 63
/// reflection rays and 64 shadow rays (the light hangs between the mirrors, and a plane cannot
/// shadow a point on its own side), and its 64th reflection is cut off. Both engines render it
/// alike on threads with stacks of 1 MiB, half the platform's default: 64 levels of waves of
/// secondary rays outgrow no stack (in an optimised build a level of waves takes tens of
/// kilobytes, and deeper levels go on a stack of their own).
#[test]
fn a_corridor_of_mirrors_64_levels_deep_outgrows_no_stack() {
    let scene = common::scene_file("tests/scenes/mirror-corridor.yaml");
    let small_stacks = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .stack_size(1 << 20)
        .build()
        .unwrap();
    let (fast, _) = small_stacks.install(|| assert_engines_agree("corridor", &scene, 16));
    let samples = 16 * 12 * 16;
    assert_eq!(fast.primary_rays, samples);
    assert_eq!(fast.reflection_rays, 63 * samples);
    assert_eq!(fast.shadow_rays, 64 * samples);
    assert_eq!(fast.max_depth_cutoffs, samples);
}

/// Each row of `scene` traced `group` pixels at a time at each (spp, group), against the core
/// pixel by pixel; the reflection rays traced.
fn assert_packed_pixels_are_the_cores(scene: &Scene, groups: &[(u32, usize)]) -> u64 {
    let (width, height) = (scene.camera.width, scene.camera.height);
    let no_corners = |_: &mut Tracer, _: u32, _: u32| -> DVec3 { unreachable!("grid sampling") };
    let mut reflected = 0;
    for &(spp, group) in groups {
        let fast = RenderOptions {
            spp,
            ..RenderOptions::of(scene)
        };
        let core = RenderOptions {
            engine: Engine::Core,
            ..fast
        };
        let (fast, core) = (Film::new(scene, fast), Film::new(scene, core));
        assert_eq!(fast.pixels_per_packet(), group, "{spp} spp");
        assert_eq!(
            core.pixels_per_packet(),
            1,
            "the core traces pixels one by one"
        );
        for y in 0..height {
            for x0 in (0..width).step_by(group) {
                let pixels = group.min((width - x0) as usize);
                let mut packed = fast.tracer();
                let mut values = vec![DVec3::NAN; pixels];
                fast.grid_pixels(&mut packed, x0, y, &mut values);
                let mut one_by_one = core.tracer();
                for (k, value) in values.iter().enumerate() {
                    let x = x0 + k as u32;
                    let expected = core.pixel(&mut one_by_one, x, y, &no_corners);
                    assert_eq!(
                        value.to_array().map(f64::to_bits),
                        expected.to_array().map(f64::to_bits),
                        "{spp} spp: pixel ({x}, {y}): {value} against {expected}"
                    );
                }
                assert_eq!(
                    rays_and_shading(packed.stats),
                    rays_and_shading(one_by_one.stats),
                    "{spp} spp: pixels {x0}.. of row {y}"
                );
                reflected += packed.stats.reflection_rays;
            }
        }
    }
    reflected
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

/// With a BVH, under every kind of light: the usual point light lights four surfaces at a
/// time and its shadow rays go through the BVH as one packet, beside surfaces the lanes leave
/// to `light_share` (Hall's transmitted highlight, a fractional exponent) and lights they
/// cannot take.
#[test]
fn every_pixel_of_a_bvh_scene_under_every_kind_of_light_is_traced_sample_by_sample() {
    let mut yaml = [
        "camera: { eye: [0, 2, -9], look_at: [0, 0.8, 0], width: 20, height: 15 }
spp: 9
ambient: 0.2
max_depth: 4
",
        EVERY_KIND_OF_LIGHT,
        "  - { name: lamp, point: [3, 6, -4], intensity: 0.6 }
materials:
  floor: { color: 0.6, ka: 0.2, kd: 0.8 }
  hall: { color: 1, kd: 0.05, ks: 0.5, shininess: 20, kr: 0.1, kt: 0.85, ior: 1.5, transmitted_highlight: true }
  satin: { color: [0.2, 0.5, 0.9], kd: 0.7, ks: 0.5, shininess: 12.5 }
",
        SPHERES_ON_A_FLOOR,
        "  - { name: hall, sphere: { center: [-3.4, 0.6, -1.2], radius: 0.6 }, material: hall }
",
    ]
    .concat();
    // A row of small spheres behind the others: enough objects for a BVH.
    for i in 0..16 {
        let x = i as f64 * 0.6 - 4.5;
        yaml.push_str(&format!(
            "  - {{ name: bead{i}, sphere: {{ center: [{x}, 0.25, 3.5], radius: 0.25 }}, material: satin }}\n"
        ));
    }
    let scene = parse(&yaml, "lights.yaml", None, &Limits::default()).unwrap();
    assert!(scene.bvh_nodes() > 0);
    let total = assert_pixels_traced_in_packets_are_traced_sample_by_sample(&scene);
    assert!(
        total.shadow_skipped_dark > 0
            && total.shadow_skipped_backfacing > 0
            && total.refraction_rays > 0
            && total.reflection_rays > 0
            && total.bvh_nodes_visited > 0,
        "{total:?}"
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 60, ..ProptestConfig::default() })]

    /// Shadow rays from anywhere, in any directions, with any reach: the packet's answer is
    /// every ray's own `occluded`, and so are the counters.
    #[test]
    fn shadow_rays_in_a_packet_are_blocked_as_one_by_one(
        objs in common::objects(),
        rays in prop::collection::vec(
            (prop::array::uniform3(-15.0..15.0f64), prop::array::uniform3(-1.0..1.0f64), 0.0..40.0f64),
            1..=16,
        ),
        directional in any::<bool>(),
    ) {
        let scene = common::random_scene(&objs);
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

/// The usual point lights lit four surfaces at a time, beside everything the lanes leave to the
/// core's own step: surfaces whose highlight exponents differ within a group of four (a whole
/// exponent of 0, 1024, 2000 and a fractional one), no highlight, Hall's transmitted highlight,
/// a light at no finite distance, surfaces inside a glass sphere (whose shadow rays the solid
/// hides), a box tested ray by ray, and a fixed shadow bias as well as the automatic one. Every
/// pixel is exactly its samples traced one by one.
#[test]
fn every_pixel_lit_in_lanes_is_lit_as_its_samples_one_by_one() {
    for bias in ["", "shadow_bias: 0.25\n"] {
        let yaml = [
            "camera: { eye: [0, 3, -8], look_at: [0, 0.6, 0], width: 32, height: 24 }
spp: 16
ambient: 0.2
max_depth: 3
",
            bias,
            "lights:
  - { name: key, point: [-4, 6, -5], intensity: 0.8 }
  - { name: fill, point: [5, 4, -3], intensity: [0.2, 0.3, 0.4] }
  - { name: far, point: [0, 50, 0], intensity: 0.3 }
materials:
  floor: { color: [0.6, 0.5, 0.4], ka: 0.2, kd: 0.8, ks: 0.3, shininess: 10, kr: 0.3 }
  odd: { color: [0.9, 0.4, 0.4], ks: 0.5, shininess: 7.5 }
  flat: { color: 0.7, ks: 0.5, shininess: 0 }
  tight: { color: [0.2, 0.9, 0.3], kd: 0.6, ks: 0.8, shininess: 1024, highlight: phong }
  tighter: { color: [0.9, 0.9, 0.2], kd: 0.6, ks: 0.8, shininess: 2000 }
  matte: { color: [0.3, 0.3, 0.9], kd: 0.9, ks: 0.4, shininess: 3, highlight: phong }
  hall: { color: 1, kd: 0.05, ks: 0.5, shininess: 20, kr: 0.1, kt: 0.85, ior: 1.5, transmitted_highlight: true }
  glass: { color: 1, kd: 0.05, ks: 0.6, shininess: 200, kr: 0.1, kt: 0.9, ior: 1.5 }
objects:
  - { name: floor, plane: { point: [0, 0, 0], normal: [0, 1, 0] }, material: floor }
  - { name: odd, sphere: { center: [-2.6, 0.4, -1.5], radius: 0.4 }, material: odd }
  - { name: flat, sphere: { center: [-2.4, 0.6, 0.5], radius: 0.6 }, material: flat }
  - { name: tight, sphere: { center: [-1.2, 0.6, 1.2], radius: 0.6 }, material: tight }
  - { name: tighter, sphere: { center: [0, 0.6, 1.6], radius: 0.6 }, material: tighter }
  - { name: crate, box: { min: [0.2, 0, -0.6], max: [1.1, 0.9, 0.3] }, material: matte }
  - { name: hall, sphere: { center: [2.2, 0.8, -0.6], radius: 0.8 }, material: hall }
  - { name: glass, sphere: { center: [1.2, 0.9, -2.4], radius: 0.9 }, material: glass }
",
        ]
        .concat();
        let mut scene = parse(&yaml, "lanes.yaml", None, &Limits::default()).unwrap();
        // Beyond the range of a scene file: the distance to the light overflows to ∞.
        scene.lights[2].kind = LightKind::Point {
            position: DVec3::new(1e300, 1e300, -1e300),
            attenuation: [1.0, 0.0, 0.0],
        };
        assert!(FastScene::new(&scene).tests_in_lanes());
        let total = assert_pixels_traced_in_packets_are_traced_sample_by_sample(&scene);
        assert!(
            total.shadow_rays > 0
                && total.shadow_skipped_backfacing > 0
                && total.shadow_skipped_inside > 0
                && total.refraction_rays > 0,
            "{bias}: {total:?}"
        );
    }
}

/// Checkered surfaces: the usual ones (a checker of two colours on an untransformed leaf)
/// painted four at a time, beside those the core paints: two floors of different colours in
/// one packet (a plane, and a box whose top is seen through the other's cells), a checker on a
/// moved sphere, a checker turned and scaled by its own transform, a checker with a nested
/// pattern, a checker of kd, stripes. The camera looks along the floor's cell boundaries (x and
/// z whole), and a mirror and a glass sphere send packets of secondary rays onto the floors.
/// Every pixel is exactly its samples traced one by one, and both engines render one image.
#[test]
fn checkered_surfaces_painted_in_lanes_are_painted_as_the_core_paints_them() {
    let yaml = "camera: { eye: [0, 2, -6], look_at: [0, 0.5, 2], width: 40, height: 30 }
spp: 4
ambient: 0.3
max_depth: 3
lights:
  - { name: key, point: [-3, 6, -4], intensity: 0.9 }
materials:
  floor: { color: { pattern: checker, colors: [[0.9, 0.8, 0.7], [0.2, 0.3, 0.1]] }, ka: 0.2, kd: 0.8 }
  tiles: { color: { pattern: checker, colors: [0.1, 0.95] }, ka: 0.2, kd: 0.7, ks: 0.3, shininess: 20 }
  ball: { color: { pattern: checker, colors: [[0.9, 0.1, 0.1], [0.9, 0.9, 0.9]] }, kd: 0.9 }
  turned: { color: { pattern: checker, colors: [0.8, 0.3], transform: [ { scale: 0.5 }, { rotate_y: 30 } ] }, kd: 0.9 }
  nested: { color: { pattern: checker, colors: [0.8, { pattern: stripes, colors: [0.1, 0.5] }] }, kd: 0.9 }
  spotty: { color: { pattern: checker, colors: [0.8, 0.3] }, kd: { pattern: checker, colors: [0.2, 0.9] } }
  striped: { color: { pattern: stripes, colors: [0.8, 0.3] }, kd: 0.9 }
  mirror: { color: 0.1, kd: 0.1, kr: 0.8 }
  glass: { color: 1, kd: 0.05, kr: 0.1, kt: 0.9, ior: 1.5 }
objects:
  - { name: floor, plane: { point: [0, 0, 0], normal: [0, 1, 0] }, material: floor }
  - { name: dais, box: { min: [-3, 0, 3], max: [3, 0.25, 6] }, material: tiles }
  - name: ball
    sphere: { center: [0, 0, 0], radius: 0.5 }
    transform: [ { translate: [-2, 0.5, 0] } ]
    material: ball
  - { name: turned, sphere: { center: [-1, 0.5, 2], radius: 0.5 }, material: turned }
  - { name: nested, sphere: { center: [1, 0.5, 2], radius: 0.5 }, material: nested }
  - { name: spotty, sphere: { center: [2, 0.5, 0], radius: 0.5 }, material: spotty }
  - { name: striped, sphere: { center: [0, 1.5, 4], radius: 0.5 }, material: striped }
  - { name: mirror, sphere: { center: [-0.7, 0.6, -1], radius: 0.6 }, material: mirror }
  - { name: glass, sphere: { center: [0.8, 0.6, -1.5], radius: 0.6 }, material: glass }
";
    let scene = parse(yaml, "checkers.yaml", None, &Limits::default()).unwrap();
    assert!(FastScene::new(&scene).tests_in_lanes());
    let total = assert_pixels_traced_in_packets_are_traced_sample_by_sample(&scene);
    assert!(
        total.reflection_rays > 0 && total.refraction_rays > 0,
        "{total:?}"
    );
    assert_engines_agree("checkers", &scene, 16);
}

/// Planes shaded in lanes from hit to light, without records: a checkered floor with Blinn's
/// highlight, a plain wall leaning over it with Phong's, a ceiling seen from inside its
/// half-space, a sixth plane beyond the most the lanes take, a plane of a fractional exponent
/// and a mirror plane (both shaded as usual), beside a mirror and a glass sphere whose rays
/// fall on them, under two lights; then with a third light at no finite distance, where every
/// plane's surfaces go back to the usual shading; and without shadows. Every pixel is exactly
/// its samples traced one by one.
#[test]
fn planes_shaded_in_lanes_are_shaded_as_the_core_shades_them() {
    let yaml = "camera: { eye: [0, 2, -6], look_at: [0, 1.5, 2], width: 40, height: 30 }
spp: 4
ambient: 0.3
max_depth: 3
lights:
  - { name: key, point: [-3, 3.5, -4], intensity: 0.9 }
  - { name: fill, point: [2, 1, -5], intensity: [0.3, 0.2, 0.1] }
materials:
  floor: { color: { pattern: checker, colors: [[0.9, 0.8, 0.7], [0.2, 0.3, 0.1]] }, ka: 0.2, kd: 0.8, ks: 0.4, shininess: 30 }
  wall: { color: [0.4, 0.6, 0.8], ka: 0.1, kd: 0.7, ks: 0.5, shininess: 12, highlight: phong }
  ceiling: { color: 0.9, ka: 0.5, kd: 0.5 }
  odd: { color: [0.8, 0.8, 0.3], kd: 0.6, ks: 0.5, shininess: 7.5 }
  shiny: { color: 0.2, kd: 0.3, kr: 0.5 }
  mirror: { color: 0.1, kd: 0.1, kr: 0.8 }
  glass: { color: 1, kd: 0.05, kr: 0.1, kt: 0.9, ior: 1.5 }
objects:
  - { name: floor, plane: { point: [0, 0, 0], normal: [0, 1, 0] }, material: floor }
  - { name: wall, plane: { point: [0, 0, 6], normal: [0.2, 0.3, -1] }, material: wall }
  - { name: ceiling, plane: { point: [0, 4, 0], normal: [0, 1, 0] }, material: ceiling }
  - { name: left, plane: { point: [-5, 0, 0], normal: [1, 0, 0.1] }, material: ceiling }
  - { name: right, plane: { point: [5, 0, 0], normal: [-1, 0, 0] }, material: wall }
  - { name: sixth, plane: { point: [0, 0, -9], normal: [0, 0, 1] }, material: floor }
  - { name: odd, plane: { point: [-4.5, 0, 0], normal: [1, 0, -0.2] }, material: odd }
  - { name: shiny, plane: { point: [4.5, 0, 0], normal: [-1, 0.1, 0] }, material: shiny }
  - { name: mirror, sphere: { center: [-0.7, 0.6, -1], radius: 0.6 }, material: mirror }
  - { name: glass, sphere: { center: [0.8, 0.6, -1.5], radius: 0.6 }, material: glass }
";
    let mut scene = parse(yaml, "planes.yaml", None, &Limits::default()).unwrap();
    assert_eq!(FastScene::new(&scene).planes_in_lanes(), 4);
    let total = assert_pixels_traced_in_packets_are_traced_sample_by_sample(&scene);
    assert!(
        total.reflection_rays > 0
            && total.refraction_rays > 0
            && total.shadow_skipped_backfacing > 0,
        "{total:?}"
    );
    assert_engines_agree("planes", &scene, 16);

    // Beyond the range of a scene file: the distance to the light overflows to ∞.
    let mut far = scene.lights[0].clone();
    far.kind = LightKind::Point {
        position: DVec3::new(1e300, 1e300, -1e300),
        attenuation: [1.0, 0.0, 0.0],
    };
    scene.lights.push(far);
    scene.features = raytree::scene::Features::of(&scene);
    assert_eq!(FastScene::new(&scene).planes_in_lanes(), 4);
    assert_pixels_traced_in_packets_are_traced_sample_by_sample(&scene);

    assert_pixels_traced_in_packets_with(&scene, |options| options.shadows = false);
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

/// A plain scene with everything the secondary rays' waves must get right: Fresnel (on glass,
/// and on a metal that transmits nothing: kr·R there as well), glass nested in glass (n1/n2
/// from the geometry), an air bubble inside glass (total internal reflection), distance
/// attenuation of secondary rays, the adaptive threshold and the depth limit, under every
/// kind of light. Every pixel is exactly its samples traced one by one.
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
  metal: { color: [0.9, 0.8, 0.5], kd: 0.1, kr: 0.9, ior: 1.8, fresnel: schlick }
",
        SPHERES_ON_A_FLOOR,
        "  - { name: bubble, sphere: { center: [1.7, 1.1, -0.6], radius: 0.45 }, material: air }
  - { name: diamond, sphere: { center: [-0.6, 0.5, -1.5], radius: 0.5 }, material: diamond }
  - { name: metal, sphere: { center: [-2.6, 0.6, -1.2], radius: 0.6 }, material: metal }
",
    ]
    .concat();
    let scene = parse(&yaml, "nested.yaml", None, &Limits::default()).unwrap();
    assert!(FastScene::new(&scene).tests_in_lanes());
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

/// Past the limiting angle a glass that also reflects sends one mirror ray for both shares,
/// of weight w·(kr + kt): with kr = kt = 0.3 and a threshold of 0.05, rays deep inside the
/// turned glass block are cut off where their transmitted share alone (w·kt) would be, and
/// traced for both. Every pixel is exactly its samples traced one by one, counters included.
#[test]
fn a_mirror_ray_carrying_both_shares_is_cut_off_by_its_own_weight_in_the_wing_too() {
    let yaml = "camera: { eye: [0, 1.5, -6], look_at: [0, 1, 0], width: 24, height: 18 }
spp: 4
ambient: 0.2
max_depth: 8
adaptive_threshold: 0.05
lights: [ { name: key, point: [-4, 6, -5], intensity: 1 } ]
materials:
  floor: { color: 0.6, ka: 0.2, kd: 0.8 }
  glass: { color: 1, kd: 0.05, ks: 0.5, shininess: 60, kr: 0.3, kt: 0.3, ior: 1.5 }
objects:
  - { name: floor, plane: { point: [0, 0, 0], normal: [0, 1, 0] }, material: floor }
  - name: block
    box: { min: [-1, 0, -1], max: [1, 2, 1] }
    transform: [ { rotate_y: 40 }, { rotate_x: 12 }, { translate: [0, 0.3, 0] } ]
    material: glass
";
    let scene = parse(yaml, "shared-mirror.yaml", None, &Limits::default()).unwrap();
    assert!(FastScene::new(&scene).tests_in_lanes());
    let total = assert_pixels_traced_in_packets_are_traced_sample_by_sample(&scene);
    assert!(
        total.total_internal_reflections > 0 && total.adaptive_cutoffs > 0,
        "{total:?}"
    );
}

/// A lone triangle, an open tube or an open cone of glass is a sheet with no inside: a ray
/// passes it unbent (n2 = n1) and stays in the medium it was in, and being no medium it leaves
/// at most one transparent solid in the scene (a glass ball), so the wing's own copy of
/// `Tracer::across` answers there and must say so too. Every pixel is exactly its samples
/// traced one by one, and both engines render the same image.
#[test]
fn a_glass_sheet_bends_no_ray_in_the_wing_either() {
    let sheets = [
        "triangle: [[-2.5, 0, -1], [2.5, 0, -1.5], [0, 3, -2.5]]",
        "cylinder: { base: [0.5, 0, 1.5], top: [0.5, 2.5, 1.5], radius: 1.4, capped: false }",
        "cone: { apex: [0.5, 3, 1.5], base: [0.5, 0, 1.5], radius: 1.8, capped: false }",
    ];
    for (ball, sheet) in ["matte", "glass"]
        .into_iter()
        .flat_map(|b| sheets.map(|s| (b, s)))
    {
        let yaml = format!(
            "camera: {{ eye: [0, 1.5, -6], look_at: [0, 1, 0], width: 24, height: 18 }}
spp: 4
ambient: 0.2
max_depth: 4
lights: [ {{ name: key, point: [-4, 6, -5], intensity: 1 }} ]
materials:
  floor: {{ color: 0.6, ka: 0.2, kd: 0.8 }}
  matte: {{ color: [0.8, 0.2, 0.2], kd: 0.8 }}
  glass: {{ color: 1, kd: 0.05, kr: 0.1, kt: 0.9, ior: 1.5 }}
objects:
  - {{ name: floor, plane: {{ point: [0, 0, 0], normal: [0, 1, 0] }}, material: floor }}
  - {{ name: sheet, {sheet}, material: glass }}
  - {{ name: ball, sphere: {{ center: [0.5, 1, 1.5], radius: 1 }}, material: {ball} }}
"
        );
        let scene = parse(&yaml, "sheet.yaml", None, &Limits::default()).unwrap();
        let media = usize::from(ball == "glass");
        assert_eq!(scene.features.transparent_objects.len(), media);
        assert_engines_agree(&format!("{sheet} and a {ball} ball"), &scene, 4);
        let total = assert_pixels_traced_in_packets_are_traced_sample_by_sample(&scene);
        assert!(total.refraction_rays > 0, "{total:?}");
    }
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
                let hit = scene.nearest(r, 0.0, f64::INFINITY, &mut Stats::default());
                hit.is_some_and(|h| (r.origin + h.t * r.dir).x == 1.5)
            })
            .count();
    }
    assert!(ties > 100, "only {ties} rays met a shared face");
}

/// Spheres in a row along the rays: the nearest one's hit lowers every ray's t_max before the
/// leaves behind it come off the packet's stack, which were tested when their node was entered
/// (t_max still ∞). Tested again then, they are passed over as the core's walk passes them:
/// the packet tests the very objects the core tests, no more.
#[test]
fn leaves_behind_a_nearer_hit_are_tested_again() {
    let mut yaml = String::from(
        "camera: { eye: [0, 0, -10], look_at: [0, 0, 0] }\nmaterials: { m: { kd: 1 } }\nobjects:\n",
    );
    for i in 0..32 {
        let (x, z) = ((i % 2) as f64 * 0.5, (i / 2) as f64 * 3.0);
        yaml.push_str(&format!(
            "  - {{ sphere: {{ center: [{x}, 0, {z}], radius: 1 }}, material: m }}\n"
        ));
    }
    let scene = parse(&yaml, "row.yaml", None, &Limits::default()).unwrap();
    assert!(scene.bvh_nodes() > 0);
    let rays: Vec<Ray> = (0..16)
        .map(|j| {
            let d = DVec3::new(0.002 * (j % 4) as f64, 0.002 * (j / 4) as f64, 1.0);
            Ray::new(DVec3::new(0.1, 0.0, -10.0), d.normalize())
        })
        .collect();
    assert_packet_is_one_by_one(&scene, &rays).unwrap();
    // The core's walk tests few of the 32 spheres: the row behind the first is pruned.
    let mut stats = Stats::default();
    for r in &rays {
        assert!(scene.nearest(r, 0.0, f64::INFINITY, &mut stats).is_some());
    }
    assert!(stats.primitives_tested < 16 * 8, "{stats:?}");
}

// --- Searches: packets ---

/// Every counter but the BVH nodes visited: a packet walks the fast wing's tree of four children
/// a node (fewer nodes than the core's binary tree), but tests each ray against exactly the
/// objects the core's walk tests.
fn same_items(stats: Stats) -> Stats {
    Stats {
        bvh_nodes_visited: 0,
        ..stats
    }
}

/// The fast wing's packet search answers every ray exactly as the core's one-ray search does,
/// hit for hit, testing the same objects, also for rays whose signs differ from the first ray's.
fn assert_packet_is_one_by_one(scene: &Scene, rays: &[Ray]) -> Result<(), TestCaseError> {
    let fast = FastScene::new(scene);
    let mut packet_stats = Stats::default();
    let mut hits = vec![None; rays.len()];
    fast.intersect_packet(rays, &mut hits, &mut packet_stats);
    let mut single_stats = Stats::default();
    for (ray, hit) in rays.iter().zip(&hits) {
        let single = scene.nearest(ray, 0.0, f64::INFINITY, &mut single_stats);
        prop_assert_eq!(*hit, single, "{:?}", ray);
    }
    prop_assert_eq!(same_items(packet_stats), same_items(single_stats));
    prop_assert!(packet_stats.bvh_nodes_visited <= single_stats.bvh_nodes_visited);
    Ok(())
}

/// The packet's shadow rays are blocked exactly as the core's `blocker` says ray by ray, and
/// without a last blocker to try first, the counters are those of asking ray by ray (but
/// for the BVH nodes: see `same_items`). With
/// one (the blocker the packet noted, then each BVH item in turn, whether it blocks or not),
/// the answers stay the same.
fn assert_shadow_packet_is_one_by_one(
    scene: &Scene,
    rays: &[Ray],
    reach: &[f64],
) -> Result<(), TestCaseError> {
    let fast = FastScene::new(scene);
    let mut packet_stats = Stats::default();
    let mut noted = None;
    let blocked = fast.occluded_packet(rays, reach, &mut noted, &mut packet_stats);
    let mut single_stats = Stats::default();
    for (i, (ray, t)) in rays.iter().zip(reach).enumerate() {
        let single = scene.blocker(ray, 0.0, *t, &mut single_stats).is_some();
        prop_assert_eq!(blocked & (1 << i) != 0, single, "ray {}: {:?}", i, ray);
    }
    prop_assert_eq!(blocked >> rays.len(), 0);
    prop_assert_eq!(same_items(packet_stats), same_items(single_stats));
    prop_assert!(packet_stats.bvh_nodes_visited <= single_stats.bvh_nodes_visited);
    let items = scene.index.bvh.items().len() as u32;
    for hint in noted.into_iter().chain(0..items) {
        let mut last = Some(hint);
        let again = fast.occluded_packet(rays, reach, &mut last, &mut Stats::default());
        prop_assert_eq!(again, blocked, "trying item {} first", hint);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 60, ..ProptestConfig::default() })]

    #[test]
    fn a_packet_finds_what_its_rays_find_one_by_one(
        objs in common::objects(),
        origin in prop::array::uniform3(-15.0..15.0f64),
        aim in prop::array::uniform3(-1.0..1.0f64),
        spread in prop::sample::select(vec![1e-3, 0.05, 2.0]),
        offsets in prop::collection::vec(prop::array::uniform3(-1.0..1.0f64), 1..=16),
    ) {
        let scene = common::random_scene(&objs);
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

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    /// The same from origins far back along the rays (hundreds to a million times the pair's
    /// size), where cylinders and cones form their quadratics from the point of each ray
    /// nearest them (`cylinder::near_start`): the lanes move their origins as the one-ray
    /// evaluation does, to the last bit.
    #[test]
    fn a_csg_pair_in_lanes_finds_what_its_rays_find_from_far_away(
        (scene, rays) in csg_pair_scene_and_rays(),
        back in prop::sample::select(vec![300.0, 1e4, 1e6]),
    ) {
        let rays: Vec<Ray> = rays
            .iter()
            .map(|r| Ray { origin: r.origin - back * r.dir, dir: r.dir })
            .collect();
        assert_packet_is_one_by_one(&scene, &rays)?;
        let reach = vec![f64::INFINITY; rays.len()];
        assert_shadow_packet_is_one_by_one(&scene, &rays, &reach)?;
    }
}

// --- Searches: one ray ---

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
                bits(sphere_hit(&s, &r, t_min, t_max)),
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
            prop_assert_eq!(bits(plane_hit(&p, &r, t_min, t_max)), bits(from_span(span, t_min, t_max)));
            return Ok(());
        }
        let p = Plane { point: DVec3::from_array(point), normal: n };
        let r = Ray { origin: DVec3::from_array(origin), dir: d };
        let span = p.span(&r).map(|s| (s.t_in, s.t_out));
        prop_assert_eq!(bits(plane_hit(&p, &r, t_min, t_max)), bits(from_span(span, t_min, t_max)));
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

/// The hits, and how many objects were looked at: tested, or skipped by their bounding box.
fn hits(s: &dyn Search, rays: &[Ray]) -> Vec<(Option<Hit>, Option<Hit>, Stats)> {
    rays.iter()
        .map(|r| {
            let mut stats = Stats::default();
            (
                s.nearest(r, 0.0, f64::INFINITY, &mut stats),
                s.blocker(r, 0.0, 25.0, &mut stats),
                stats,
            )
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 60, ..ProptestConfig::default() })]

    /// Spheres (tested directly, and in groups of four) and planes: the fast search finds the
    /// core's hits and counts the same work, with and without a BVH.
    #[test]
    fn the_fast_search_finds_the_cores_hits(
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
            let mut core = scene(&spheres, &planes);
            core.set_accel(accel);
            let fast = FastScene::new(&core);
            prop_assert_eq!(hits(&fast, &rays), hits(&core, &rays));
        }
    }
}

/// A box leaf as scene YAML: on a half-unit grid (faces shared between boxes, rays along
/// faces), plain or turned, scaled and moved.
fn box_object() -> impl Strategy<Value = String> {
    let grid = || (-6i32..=6).prop_map(|k| k as f64 * 0.5);
    let corner = move || (grid(), grid(), grid());
    (corner(), (1i32..=6, 1i32..=6, 1i32..=6), 0..3u8, -90.0..90.0f64).prop_map(
        |((x, y, z), (w, h, d), turn, angle)| {
            let (w, h, d) = (w as f64 * 0.5, h as f64 * 0.5, d as f64 * 0.5);
            let aabox = format!(
                "box: {{ min: [{x}, {y}, {z}], max: [{}, {}, {}] }}",
                x + w,
                y + h,
                z + d
            );
            match turn {
                0 => aabox,
                1 => format!("{aabox}, transform: [ {{ rotate_y: {angle} }} ]"),
                _ => format!(
                    "{aabox}, transform: [ {{ scale: [1, 0.5, 2] }}, {{ rotate_x: {angle} }}, {{ translate: [0.5, 0, -1] }} ]"
                ),
            }
        },
    )
}

/// Rays from a half-unit grid (inside boxes, on their faces) in any direction, or along an
/// axis (parallel to two of a box's slabs).
fn box_ray() -> impl Strategy<Value = Ray> {
    let grid = || (-8i32..=8).prop_map(|k| k as f64 * 0.5);
    let axis = prop::sample::select(vec![
        DVec3::X,
        DVec3::NEG_X,
        DVec3::Y,
        DVec3::NEG_Y,
        DVec3::Z,
        DVec3::NEG_Z,
    ]);
    let any = prop::array::uniform3(-1.0..1.0f64).prop_filter_map("not zero", unit);
    ((grid(), grid(), grid()), prop_oneof![axis, any]).prop_map(|((x, y, z), dir)| Ray {
        origin: DVec3::new(x, y, z),
        dir,
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 60, ..ProptestConfig::default() })]

    /// Boxes, plain and turned, tested in the wing's copy: the fast search finds the core's
    /// hits, faces included, and counts the same work, with and without a BVH.
    #[test]
    fn the_fast_search_finds_the_cores_box_hits(
        boxes in prop::collection::vec(box_object(), 1..12),
        rays in prop::collection::vec(box_ray(), 40),
    ) {
        let mut yaml = String::from(
            "camera: { eye: [0, 0, -30], look_at: [0, 0, 0], width: 8, height: 6 }\nlights: [ { point: [10, 20, -20] } ]\nmaterials: { m: { kd: 0.6 } }\nobjects:\n",
        );
        for (i, b) in boxes.iter().enumerate() {
            yaml.push_str(&format!("  - {{ name: b{i}, {b}, material: m }}\n"));
        }
        for accel in [Accel::None, Accel::Bvh] {
            let mut core = parse(&yaml, "boxes.yaml", None, &Limits::default()).unwrap();
            core.set_accel(accel);
            let fast = FastScene::new(&core);
            prop_assert_eq!(hits(&fast, &rays), hits(&core, &rays));
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

/// The fast search's nearest hit of a flat CSG object, read off its primitives' spans, is the
/// core's (the first crossing of its segment list inside the window), to the bit, with the
/// same surface and the same pruning counted, with CSG boxes and pruning on or off; and so is
/// its blocker.
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
    let fast = FastScene::new(&scene);
    let (mut core_stats, mut fast_stats) = (Stats::default(), Stats::default());
    let expected = scene.nearest(r, t_min, t_max, &mut core_stats);
    let hit = fast.nearest(r, t_min, t_max, &mut fast_stats);
    prop_assert_eq!(
        hit.map(|h| (h.t.to_bits(), h.surface)),
        expected.map(|h| (h.t.to_bits(), h.surface)),
        "{}",
        object
    );
    prop_assert_eq!(fast_stats, core_stats, "{}", object);
    let blocker = fast.blocker(r, t_min, t_max, &mut Stats::default());
    prop_assert_eq!(
        blocker,
        scene.blocker(r, t_min, t_max, &mut Stats::default())
    );
    Ok(())
}

/// A ray that grazes a cone's base rim (parallel to its axis, at the base's radius) meets it
/// in a span of no thickness; as one of three operands of a union or of two, and four rays
/// at a time, the fast search leaves it to the segment lists, which keep it as a segment.
#[test]
fn a_span_of_no_thickness_is_the_segment_lists_to_settle() {
    let cone = "{ cone: { apex: [0.5, 1, -0.5], base: [0.5, -1, -0.5], radius: 0.5 } }";
    let objects = [
        format!("{{ name: x, material: m, union: [{{ box: {{ min: [-0.5, -0.25, -0.25], max: [0.5, 0.25, 0.25] }} }}, {{ sphere: {{ center: [0, 0, 0], radius: 0.5 }} }}, {cone}], transform: [ {{ translate: [0, 0.5, 0] }} ] }}"),
        format!("{{ name: x, material: m, union: [{{ sphere: {{ center: [0, 0, 0], radius: 0.5 }} }}, {cone}], transform: [ {{ translate: [0, 0.5, 0] }} ] }}"),
        format!("{{ name: x, material: m, union: [{cone}, {{ sphere: {{ center: [0, 0, 0], radius: 0.5 }} }}] }}"),
    ];
    let ray = Ray {
        origin: DVec3::new(0.5, -1.0, 0.0),
        dir: DVec3::Y,
    };
    for object in &objects {
        for pruning in [false, true] {
            assert_flat_hit_is_the_lists_first_crossing(object, &ray, 0.0, f64::INFINITY, pruning)
                .unwrap();
        }
    }
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

/// The explorer's preview renders the scene through a smaller camera without copying the
/// scene: the image is the one of the same scene file written at that size, bit for bit.
#[test]
fn a_scene_rendered_through_a_resized_camera_is_the_scene_at_that_size() {
    for name in ["whitted", "csg"] {
        let small = small_peer_scene(name);
        let yaml = std::fs::read_to_string(format!("benches/peers/{name}.yaml")).unwrap();
        let full = parse(&yaml, name, None, &Limits::default()).unwrap();
        assert_eq!(full.camera.width, 800);
        let options = RenderOptions {
            spp: 4,
            ..RenderOptions::of(&small)
        };
        let cancel = std::sync::atomic::AtomicBool::new(false);
        let (a, sa) = raytree::render::render(&small, options, &|_| {}, &cancel).unwrap();
        let camera = full.camera.resized(40, 30);
        let (b, sb) = render_through(&full, camera, options, &|_| {}, &cancel).unwrap();
        assert_eq!((b.width, b.height), (40, 30));
        assert_eq!(sa, sb, "{name}: counters differ");
        for (i, (p, q)) in a.pixels.iter().zip(&b.pixels).enumerate() {
            let bits = |c: &DVec3| c.to_array().map(f64::to_bits);
            assert_eq!(bits(p), bits(q), "{name}: pixel {i}: {p} against {q}");
        }
    }
}
