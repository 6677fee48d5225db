//! The BVH changes how fast hits are found, never which: for random scenes and rays it returns
//! exactly the brute-force nearest hit. Rendering is identical for any number of threads.

mod common;

use glam::DVec3;
use proptest::prelude::*;
use raytree::geometry::Ray;
use raytree::render::{render_simple, RenderOptions};
use raytree::scene::{parse, Accel, Limits, Search};
use raytree::stats::Stats;

proptest! {
    #![proptest_config(ProptestConfig { cases: 60, ..ProptestConfig::default() })]

    #[test]
    fn bvh_finds_the_brute_force_nearest_hit(objs in common::objects(), rays in prop::collection::vec((prop::array::uniform3(-15.0..15.0f64), prop::array::uniform3(-1.0..1.0f64)), 50)) {
        let mut bvh = common::random_scene(&objs);
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
            let a = bvh.nearest(&ray, 0.0, f64::INFINITY, &mut Stats::default());
            let b = brute.nearest(&ray, 0.0, f64::INFINITY, &mut Stats::default());
            match (a, b) {
                (Some(a), Some(b)) => {
                    prop_assert!((a.t - b.t).abs() <= 1e-12 * a.t.abs().max(1.0), "{} vs {}", a.t, b.t);
                    // Equal t on two objects is a tie either may win; otherwise the same object.
                    prop_assert!(a.object == b.object || a.t == b.t);
                }
                (None, None) => {}
                (a, b) => prop_assert!(false, "bvh {a:?} vs brute force {b:?}"),
            }
            let sa = bvh.blocker(&ray, 0.0, f64::INFINITY, &mut Stats::default()).is_some();
            let sb = brute.blocker(&ray, 0.0, f64::INFINITY, &mut Stats::default()).is_some();
            prop_assert_eq!(sa, sb);
        }
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
    let mut scene = common::random_scene(&objs);
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
            let hit = scene.nearest(&ray, 0.0, f64::INFINITY, &mut Stats::default());
            // Along the axis the lens is [1.2 − s, s − 1.2] from its centre, s = √(1.6² − ρ²):
            // it is entered through the far sphere's near side.
            let s = (1.6f64 * 1.6 - rho * rho).sqrt();
            let t = hit.expect("the lens is hit inside its rim").t;
            assert!((t - (5.0 + 1.2 - s)).abs() < 1e-9, "ρ = {rho}: t = {t}");
        }
    }
}
