//! Hot paths: shape intersections, BVH traversal against brute force and the BVH's build, whole
//! paths of the path tracer, and a small render.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use glam::DVec3;
use raytree::accel::{Aabb, Bvh};
use raytree::bench;
use raytree::fast::simd::Wide;
use raytree::fast::{sphere_hit, DiffusePaths, FastScene, Footprints, Missed, SphereGroup, PACKET};
use raytree::geometry::{Aabox, Cone, Cylinder, Ray, Sphere, Triangle};
use raytree::render::antialias::grid_offsets;
use raytree::render::{render_simple, Engine, RenderOptions};
use raytree::sampling::{pixel_key, SamplePoint};
use raytree::scene::{parse, Accel, Hit, Limits, Scene, Search};
use raytree::stats::Stats;
use raytree::trace::path::PathTracer;
use std::hint::black_box;

fn rays(n: usize) -> Vec<Ray> {
    (0..n)
        .map(|i| {
            let a = i as f64 * 0.618_033_988_75;
            let b = i as f64 * 0.414_213_562_37;
            Ray::new(
                DVec3::new(a.fract() - 0.5, b.fract() - 0.5, -5.0),
                DVec3::new(0.1 * a.sin(), 0.1 * b.cos(), 1.0),
            )
        })
        .collect()
}

fn shapes(c: &mut Criterion) {
    let rs = rays(1024);
    let sphere = Sphere {
        center: DVec3::ZERO,
        radius: 0.5,
    };
    let aabox = Aabox {
        min: DVec3::splat(-0.5),
        max: DVec3::splat(0.5),
    };
    let cyl = Cylinder {
        base: DVec3::new(0.0, -0.5, 0.0),
        top: DVec3::new(0.0, 0.5, 0.0),
        radius: 0.4,
    };
    let cone = Cone {
        apex: DVec3::new(0.0, 0.5, 0.0),
        base: DVec3::new(0.0, -0.5, 0.0),
        radius: 0.4,
    };
    let tri = Triangle {
        a: DVec3::new(-0.5, -0.5, 0.0),
        b: DVec3::new(0.5, -0.5, 0.0),
        c: DVec3::new(0.0, 0.5, 0.0),
    };
    let mut g = c.benchmark_group("shape span, 1024 rays");
    g.bench_function("sphere", |b| {
        b.iter(|| {
            rs.iter()
                .filter(|r| sphere.span(black_box(r)).is_some())
                .count()
        })
    });
    g.bench_function("box", |b| {
        b.iter(|| {
            rs.iter()
                .filter(|r| aabox.span(black_box(r)).is_some())
                .count()
        })
    });
    g.bench_function("cylinder", |b| {
        b.iter(|| {
            rs.iter()
                .filter(|r| cyl.span(black_box(r)).is_some())
                .count()
        })
    });
    g.bench_function("cone", |b| {
        b.iter(|| {
            rs.iter()
                .filter(|r| cone.span(black_box(r)).is_some())
                .count()
        })
    });
    g.bench_function("triangle", |b| {
        b.iter(|| {
            rs.iter()
                .filter(|r| tri.intersect(black_box(r)).is_some())
                .count()
        })
    });
    g.finish();
}

/// Four spheres side by side against the same spheres one after another: the nearest hit of
/// 1024 rays of which 305 (30 %) hit one of them.
fn sphere_group(c: &mut Criterion) {
    let rs = rays(1024);
    let spheres: Vec<Sphere> = [(-0.3, -0.3), (0.3, -0.3), (-0.3, 0.3), (0.3, 0.3)]
        .iter()
        .map(|&(x, y)| Sphere {
            center: DVec3::new(x, y, 0.0),
            radius: 0.25,
        })
        .collect();
    let group = SphereGroup::new(&spheres);
    let mut g = c.benchmark_group("nearest of 4 spheres, 1024 rays");
    g.bench_function("one by one", |b| {
        b.iter(|| {
            rs.iter()
                .filter(|r| {
                    let mut limit = f64::INFINITY;
                    for s in &spheres {
                        if let Some(t) = sphere_hit(s, black_box(r), 0.0, limit) {
                            limit = t;
                        }
                    }
                    limit.is_finite()
                })
                .count()
        })
    });
    g.bench_function("group", |b| {
        b.iter(|| {
            rs.iter()
                .filter(|r| {
                    group
                        .nearest::<Wide>(black_box(r), 0.0, f64::INFINITY)
                        .is_some()
                })
                .count()
        })
    });
    g.finish();
}

/// N spheres scattered in a cube in front of the camera.
pub fn spheres(n: usize) -> Scene {
    let mut yaml = String::from(
        "camera: { eye: [0, 0, -30], look_at: [0, 0, 0], fov: 40, width: 64, height: 48 }\nlights: [ { point: [10, 20, -20] } ]\nmaterials: { m: { ka: 0.1, kd: 0.8 } }\nobjects:\n",
    );
    let side = 20.0;
    let r = 0.5 * side / (n as f64).cbrt() * 0.6;
    for i in 0..n {
        let h = |k: f64| ((i as f64 + 1.0) * k).fract() - 0.5;
        let c = DVec3::new(h(0.754_877_666), h(0.569_840_291), h(0.671_123_1)) * side;
        yaml.push_str(&format!(
            "  - {{ sphere: {{ center: [{}, {}, {}], radius: {r} }}, material: m }}\n",
            c.x, c.y, c.z
        ));
    }
    parse(&yaml, "spheres", None, &Limits::default()).unwrap()
}

fn bvh(c: &mut Criterion) {
    let mut g = c.benchmark_group("nearest hit per primary ray");
    for n in [4usize, 8, 16, 64, 1000] {
        let mut scene = spheres(n);
        let cam = scene.camera.clone();
        let rs: Vec<Ray> = (0..48)
            .flat_map(|y| (0..64).map(move |x| (x, y)))
            .map(|(x, y)| cam.pixel_ray(x, y))
            .collect();
        for accel in [Accel::None, Accel::Bvh] {
            scene.set_accel(accel);
            let name = if accel == Accel::None {
                "brute force"
            } else {
                "bvh"
            };
            g.bench_with_input(BenchmarkId::new(name, n), &n, |b, _| {
                b.iter(|| {
                    let mut stats = Stats::default();
                    rs.iter()
                        .filter(|r| scene.nearest(r, 0.0, f64::INFINITY, &mut stats).is_some())
                        .count()
                })
            });
        }
    }
    g.finish();
}

/// Building the hierarchy over the boxes of 10 000 small spheres (as `many.yaml` has), on one
/// thread and on two.
fn bvh_build(c: &mut Criterion) {
    let boxes: Vec<Aabb> = (0..10_000)
        .map(|i| {
            let h = |k: f64| ((i as f64 + 1.0) * k).fract() - 0.5;
            let c = DVec3::new(
                h(0.754_877_666) * 20.0,
                h(0.569_840_291) * 4.0,
                h(0.671_123_1) * 20.0,
            );
            Aabb::new(c - 0.12, c + 0.12)
        })
        .collect();
    let mut g = c.benchmark_group("bvh build, 10 000 boxes");
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        g.bench_with_input(BenchmarkId::new("threads", threads), &threads, |b, _| {
            b.iter(|| pool.install(|| Bvh::build(black_box(&boxes))))
        });
    }
    g.finish();
}

/// Packets of 16 rays in a plain scene (8 spheres, brute force): tested one ray at a time by the
/// fast search, and four rays at a time in lanes (`intersect_packet`, `occluded_packet`).
fn lanes(c: &mut Criterion) {
    let mut core = spheres(8);
    core.set_accel(Accel::None);
    let scene = FastScene::new(&core);
    assert!(scene.tests_in_lanes());
    let cam = core.camera.clone();
    let rs: Vec<Ray> = (0..48)
        .flat_map(|y| (0..64).map(move |x| (x, y)))
        .map(|(x, y)| cam.pixel_ray(x, y))
        .collect();
    let reach = vec![f64::INFINITY; rs.len()];
    let mut g = c.benchmark_group("8 spheres, 3072 rays in packets of 16");
    g.bench_function("nearest, one by one", |b| {
        b.iter(|| {
            let mut stats = Stats::default();
            rs.iter()
                .filter(|r| scene.nearest(r, 0.0, f64::INFINITY, &mut stats).is_some())
                .count()
        })
    });
    g.bench_function("nearest, in lanes", |b| {
        b.iter(|| {
            let mut stats = Stats::default();
            let mut hits = [None; 16];
            rs.chunks(16)
                .map(|p| {
                    scene.intersect_packet(p, &mut hits[..p.len()], &mut stats);
                    hits.iter().filter(|h| h.is_some()).count()
                })
                .sum::<usize>()
        })
    });
    g.bench_function("blocked, one by one", |b| {
        b.iter(|| {
            let mut stats = Stats::default();
            rs.iter()
                .filter(|r| scene.blocker(r, 0.0, f64::INFINITY, &mut stats).is_some())
                .count()
        })
    });
    g.bench_function("blocked, in lanes", |b| {
        b.iter(|| {
            let mut stats = Stats::default();
            rs.chunks(16)
                .zip(reach.chunks(16))
                .map(|(p, t)| {
                    scene
                        .occluded_packet(p, t, &mut None, &mut stats)
                        .count_ones() as usize
                })
                .sum::<usize>()
        })
    });
    g.finish();
}

/// The primary rays of a 64×48 camera at 16 samples a pixel (a 4×4 grid) into 1000 spheres,
/// pixel after pixel along the rows: one by one through the wing's one-ray search of the BVH,
/// and as packets walking its tree of four children a node (`intersect_packet`): two
/// neighbouring pixels' 32 samples (as the renderer traces them), a pixel's 16, or its rows of
/// four or pairs of rows. The time against the packet's size splits the packet search into
/// what each packet costs (its hull, its walk) and what each ray does (its tests at the
/// leaves).
fn primary_packets(c: &mut Criterion) {
    let scene = spheres(1000);
    let fast = FastScene::new(&scene);
    assert!(scene.bvh_nodes() > 0 && !fast.tests_in_lanes());
    let cam = scene.camera.clone();
    let rays: Vec<Ray> = (0..48)
        .flat_map(|y| (0..64).map(move |x| (x, y)))
        .flat_map(|(x, y)| {
            (0..16).map(move |k| {
                let (u, v) = ((k % 4) as f64 + 0.5, (k / 4) as f64 + 0.5);
                (x as f64 + u / 4.0, y as f64 + v / 4.0)
            })
        })
        .map(|(px, py)| cam.ray(px, py))
        .collect();
    let count = rays.len();
    let one_by_one = || {
        let mut stats = Stats::default();
        rays.iter()
            .filter(|r| fast.nearest(r, 0.0, f64::INFINITY, &mut stats).is_some())
            .count()
    };
    let in_packets = |size: usize| {
        let mut stats = Stats::default();
        let mut hits = [None; PACKET];
        rays.chunks(size)
            .map(|p| {
                fast.intersect_packet(p, &mut hits[..p.len()], &mut stats);
                hits[..p.len()].iter().filter(|h| h.is_some()).count()
            })
            .sum::<usize>()
    };
    // Before timing: every packet size finds each ray's very hit (t, object, surface) that
    // the one-ray search finds.
    let mut stats = Stats::default();
    let expected: Vec<_> = (rays.iter())
        .map(|r| fast.nearest(r, 0.0, f64::INFINITY, &mut stats))
        .collect();
    let hit = expected.iter().filter(|h| h.is_some()).count();
    assert!(hit > count / 10 && hit < count, "{hit} of {count} rays hit");
    let mut g = c.benchmark_group(format!("1000 spheres, {count} primary rays"));
    g.bench_function("one by one", |b| b.iter(one_by_one));
    for size in [4, 8, 16, 32] {
        let mut found = vec![];
        for p in rays.chunks(size) {
            let mut hits = [None; PACKET];
            fast.intersect_packet(p, &mut hits[..p.len()], &mut stats);
            found.extend_from_slice(&hits[..p.len()]);
        }
        assert!(found == expected, "packets of {size}: other hits");
        g.bench_with_input(BenchmarkId::new("packets of", size), &size, |b, &size| {
            b.iter(|| in_packets(size))
        });
    }
    g.finish();
}

/// Shadow rays toward the light from the surfaces 1000 spheres show a 64×48 camera at 16
/// samples a pixel (a 4×4 grid), each pixel's as a packet, pixel after pixel along the rows:
/// one by one (the core's search), as packets, and as packets that try the last blocker
/// first (`occluded_packet`), as the renderer traces them.
fn shadow_packets(c: &mut Criterion) {
    let scene = spheres(1000);
    let fast = FastScene::new(&scene);
    assert!(scene.bvh_nodes() > 0);
    let light = DVec3::new(10.0, 20.0, -20.0);
    let cam = scene.camera.clone();
    let mut stats = Stats::default();
    // Each pixel's shadow rays (from the samples that hit), with their lengths.
    let packets: Vec<(Vec<Ray>, Vec<f64>)> = (0..48)
        .flat_map(|y| (0..64).map(move |x| (x, y)))
        .map(|(x, y)| {
            (0..16)
                .filter_map(|k| {
                    let (u, v) = ((k % 4) as f64 + 0.5, (k / 4) as f64 + 0.5);
                    let ray = cam.ray(x as f64 + u / 4.0, y as f64 + v / 4.0);
                    let hit = scene.nearest(&ray, 0.0, f64::INFINITY, &mut stats)?;
                    // Just short of the surface, on the side the camera sees.
                    let p = ray.at(hit.t * (1.0 - 1e-9));
                    let to_light = light - p;
                    Some((Ray::new(p, to_light.normalize()), to_light.length()))
                })
                .unzip()
        })
        .filter(|(rays, _): &(Vec<Ray>, Vec<f64>)| !rays.is_empty())
        .collect();
    let count: usize = packets.iter().map(|(rays, _)| rays.len()).sum();
    let one_by_one = || {
        let mut stats = Stats::default();
        packets
            .iter()
            .flat_map(|(rays, reach)| rays.iter().zip(reach))
            .filter(|(r, t)| scene.blocker(r, 0.0, **t, &mut stats).is_some())
            .count()
    };
    let in_packets = |keep: bool| {
        let mut stats = Stats::default();
        let mut last = None;
        packets
            .iter()
            .map(|(rays, reach)| {
                if !keep {
                    last = None;
                }
                fast.occluded_packet(rays, reach, &mut last, &mut stats)
                    .count_ones() as usize
            })
            .sum::<usize>()
    };
    let blocked = one_by_one();
    assert!(blocked > count / 10, "only {blocked} of {count} blocked");
    assert_eq!((in_packets(false), in_packets(true)), (blocked, blocked));
    let mut g = c.benchmark_group(format!("1000 spheres, {count} shadow rays"));
    g.bench_function("one by one", |b| b.iter(one_by_one));
    g.bench_function("packets", |b| b.iter(|| in_packets(false)));
    g.bench_function("packets, last blocker first", |b| {
        b.iter(|| in_packets(true))
    });
    g.finish();
}

fn render(c: &mut Criterion) {
    let scene = raytree::scene::load(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/06-refraction/scene.yaml"),
        &Limits::default(),
    )
    .unwrap();
    let mut small = scene.clone();
    small.camera = scene.camera.resized(80, 60);
    c.bench_function("render refraction lesson 80×60", |b| {
        b.iter(|| render_simple(&small, RenderOptions::of(&small)))
    });
    // The Whitted peer scene at 16 samples per pixel: the core's recursion ray by ray, and the
    // wing's packets (the lights' terms and shadow rays of four surfaces at a time among them).
    let whitted = peer_scene_160x120("whitted");
    core_against_wing(c, "render the Whitted peer scene 160×120, 16 spp", &whitted);
    // The CSG peer scene: the wing tests its flat CSG objects four rays at a time and rules
    // out the boxes a packet of primary rays cannot meet by the pixels' place on the film.
    let csg = peer_scene_160x120("csg");
    core_against_wing(c, "render the CSG peer scene 160×120, 16 spp", &csg);
    // 10 000 spheres through the BVH, at 16 samples per pixel: the wing searches two pixels'
    // samples as one packet and lights four surfaces at a time, their shadow rays one packet.
    let mut many = parse(
        &bench::spheres(10_000),
        "spheres.yaml",
        None,
        &Limits::default(),
    )
    .unwrap();
    many.spp = 16;
    core_against_wing(c, "render 10 000 spheres 160×120, 16 spp", &many);
    // The CSG peer scene's floor and light alone: the wing shades the floor's hits four at a
    // time from hit to light, its checker and shadow rays included, without shading records.
    let floor = parse(
        "camera: { eye: [0, 3.0, -8.0], look_at: [0, 1.0, 0], fov: 38.55, width: 160, height: 120 }
spp: 16
lights: [ { point: [-5, 10, -7], intensity: 1 } ]
materials:
  floor: { color: { pattern: checker, colors: [0.75, 0.45] }, ka: 0.05, kd: 0.8, ks: 0.3 }
objects:
  - { plane: { point: [0, 0, 0], normal: [0, 1, 0] }, material: floor }
  - { sphere: { center: [0, 1, 0], radius: 1 }, material: floor }
",
        "floor.yaml",
        None,
        &Limits::default(),
    )
    .unwrap();
    core_against_wing(c, "render a checkered floor 160×120, 16 spp", &floor);
}

/// The whole render of `scene` by the core and by the fast wing, with the scene's own options.
fn core_against_wing(c: &mut Criterion, title: &str, scene: &Scene) {
    let mut g = c.benchmark_group(title);
    for (name, engine) in [("core", Engine::Core), ("wing", Engine::Fast)] {
        let options = RenderOptions {
            engine,
            ..RenderOptions::of(scene)
        };
        g.bench_function(name, |b| b.iter(|| render_simple(scene, options)));
    }
    g.finish();
}

/// A peer scene of `benches/peers/` at 160×120.
fn peer_scene_160x120(name: &str) -> Scene {
    let file = format!("{name}.yaml");
    let yaml = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("benches/peers")
            .join(&file),
    )
    .unwrap()
    .replace("width: 800, height: 600", "width: 160, height: 120");
    parse(&yaml, &file, None, &Limits::default()).unwrap()
}

/// A scene of one object (given as YAML) in front of the eye.
fn one_object(object: &str) -> Scene {
    let yaml = format!(
        "camera: {{ eye: [0, 0, -5], look_at: [0, 0, 0], fov: 40, width: 8, height: 8 }}\nmaterials: {{ m: {{ kd: 1 }} }}\nobjects:\n  - {{ {object}, material: m }}\n"
    );
    parse(&yaml, "one object", None, &Limits::default()).unwrap()
}

/// How many of the rays hit something, through `search`.
fn nearest_hits<S: Search + ?Sized>(search: &S, rays: &[Ray]) -> usize {
    let mut stats = Stats::default();
    rays.iter()
        .filter(|r| {
            search
                .nearest(black_box(r), 0.0, f64::INFINITY, &mut stats)
                .is_some()
        })
        .count()
}

/// How many of the rays something blocks before t_max, through `search`.
fn blocked_rays<S: Search + ?Sized>(search: &S, rays: &[Ray], t_max: f64) -> usize {
    let mut stats = Stats::default();
    rays.iter()
        .filter(|r| {
            search
                .blocker(black_box(r), 0.0, t_max, &mut stats)
                .is_some()
        })
        .count()
}

/// The CSG peer scene's lens (∩ of two spheres) against a sphere of its size: nearest hits of
/// rays that all meet its box, through `Scene::intersect`.
fn csg(c: &mut Criterion) {
    let rs = rays(1024);
    let lens = one_object("intersection: [ { sphere: { center: [0, 0, -0.4], radius: 0.6 } }, { sphere: { center: [0, 0, 0.4], radius: 0.6 } } ]");
    let sphere = one_object("sphere: { center: [0, 0, 0], radius: 0.5 }");
    let mut g = c.benchmark_group("nearest hit, 1024 rays");
    for (name, scene) in [("sphere", &sphere), ("lens", &lens)] {
        g.bench_function(name, |b| b.iter(|| nearest_hits(scene, &rs)));
    }
    g.finish();
}

/// The CSG and Whitted peer scenes' primary rays at 160×120, 16 samples a pixel (a 4×4 grid),
/// two pixels' samples a packet as the film traces them: every box and sphere tested but the
/// boxes the packet's hull rules out (`boxes_missed_by_all`, from its rays), or the boxes and
/// plain spheres the film's footprints rule out skipped (`Footprints::missed`, from the
/// pixels' place alone).
fn footprints(c: &mut Criterion) {
    for name in ["csg", "whitted"] {
        primary_packets_knowing(c, name);
    }
}

fn primary_packets_knowing(c: &mut Criterion, name: &str) {
    let scene = peer_scene_160x120(name);
    let fast = FastScene::new(&scene);
    let offsets = grid_offsets(16);
    let footprints = Footprints::new(&scene.camera, &offsets, &fast)
        .expect("the scene's boxes and spheres lie ahead of the eye");
    let cam = &scene.camera;
    let (width, height) = (cam.width, cam.height);
    // Each packet: its first pixel, its last and its row, and its rays.
    let packets: Vec<((u32, u32, u32), Vec<Ray>)> = (0..height)
        .flat_map(|y| {
            (0..width)
                .step_by(2)
                .map(move |x| (x, (x + 1).min(width - 1), y))
        })
        .map(|(x, last, y)| {
            let rays = (x..=last)
                .flat_map(|px| offsets.iter().map(move |o| (px, o)))
                .map(|(px, o)| cam.ray(px as f64 + o.x, y as f64 + o.y))
                .collect();
            ((x, last, y), rays)
        })
        .collect();
    // Every packet's hits, with the boxes ruled out by the footprints or by the hull.
    let search = |knowing: bool, found: &mut Vec<Option<Hit>>, stats: &mut Stats| {
        let mut hits = [None; PACKET];
        for ((x, last, y), rays) in &packets {
            let missed = if knowing {
                footprints.missed(*x, *last, *y)
            } else {
                Missed::UNKNOWN
            };
            let hits = &mut hits[..rays.len()];
            fast.intersect_packet_knowing(rays, missed, hits, stats);
            found.extend_from_slice(hits);
        }
    };
    // Before timing: both find every ray's very hit (t, object, surface), and the footprints
    // rule out boxes or spheres.
    let (mut by_hull, mut by_footprints) = (vec![], vec![]);
    search(false, &mut by_hull, &mut Stats::default());
    search(true, &mut by_footprints, &mut Stats::default());
    assert!(by_hull == by_footprints, "other hits with the footprints");
    assert!(packets.iter().any(|((x, last, y), _)| {
        let missed = footprints.missed(*x, *last, *y);
        missed.boxes.is_some_and(|b| b != 0) || missed.spheres != 0
    }));
    let timed = |knowing: bool| {
        let mut found = Vec::with_capacity(by_hull.len());
        search(knowing, &mut found, &mut Stats::default());
        found.len()
    };
    let title = format!("the {name} peer scene's primary packets at 160×120, 16 spp");
    let mut g = c.benchmark_group(title);
    g.bench_function("boxes ruled out by the packets' hull", |b| {
        b.iter(|| timed(false))
    });
    g.bench_function("boxes and spheres ruled out by the footprints", |b| {
        b.iter(|| timed(true))
    });
    g.finish();
}

/// A turned box (the Cornell box's blocks): nearest hits of 1024 rays through the core's
/// search and through the fast wing's, which tests box leaves where it tests the object.
fn boxes(c: &mut Criterion) {
    let rs = rays(1024);
    let scene = one_object(
        "box: { min: [-0.5, -0.5, -0.5], max: [0.5, 0.5, 0.5] }, transform: [ { rotate_y: -17 } ]",
    );
    let fast = FastScene::new(&scene);
    let mut g = c.benchmark_group("nearest hit of a turned box, 1024 rays");
    for (name, search) in [("core", &scene as &dyn Search), ("fast wing", &fast)] {
        g.bench_function(name, |b| b.iter(|| nearest_hits(search, &rs)));
    }
    g.finish();
}

/// The Cornell box (seven boxes, no BVH): nearest hits and blockers of 1024 rays from points in
/// the room, as its paths' bounces and shadow rays meet them, through the core's search and the
/// fast wing's.
fn room(c: &mut Criterion) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/lessons/examples/cornell.yaml");
    let scene = raytree::scene::load(std::path::Path::new(path), &Limits::default()).unwrap();
    let fast = FastScene::new(&scene);
    let rs: Vec<Ray> = (0..1024)
        .map(|i| {
            let a = i as f64 * 0.618_033_988_75;
            let b = i as f64 * 0.414_213_562_37;
            let c = i as f64 * 0.302_775_637_73;
            Ray::new(
                DVec3::new(
                    1.8 * a.fract() - 0.9,
                    1.8 * b.fract() - 0.9,
                    1.8 * c.fract() - 0.9,
                ),
                DVec3::new((7.0 * a).sin(), (5.0 * b).cos(), (3.0 * c).sin()),
            )
        })
        .collect();
    let mut g = c.benchmark_group("the Cornell box's seven boxes, 1024 rays");
    for (name, search) in [("core", &scene as &dyn Search), ("fast wing", &fast)] {
        g.bench_function(format!("nearest, {name}"), |b| {
            b.iter(|| nearest_hits(search, &rs))
        });
        g.bench_function(format!("blocker, {name}"), |b| {
            b.iter(|| blocked_rays(search, &rs, 1.0))
        });
    }
    g.finish();
}

/// The Cornell box's paths, 1024 of them (16 samples in each of 64 pixels at the image's
/// centre), each traced whole: by the core's path tracer with the fast wing's search, and by
/// the wing's path tracer for scenes of diffuse surfaces (`DiffusePaths`), which gives the same
/// values to the last bit.
fn paths(c: &mut Criterion) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/lessons/examples/cornell.yaml");
    let scene = raytree::scene::load(std::path::Path::new(path), &Limits::default()).unwrap();
    let fast = FastScene::new(&scene);
    let core = PathTracer::new(&scene, scene.max_depth).with_search(&fast);
    let wing = DiffusePaths::new(PathTracer::new(&scene, scene.max_depth)).unwrap();
    let samples: Vec<(Ray, SamplePoint)> = (0..1024u32)
        .map(|k| {
            let (x, y) = (124 + (k / 16) % 8, 124 + k / 128);
            let point = SamplePoint::new(pixel_key(0, x, y), k % 16);
            let [u, v] = point.pair(0);
            (scene.camera.ray(x as f64 + u, y as f64 + v), point)
        })
        .collect();
    let mut g = c.benchmark_group("the Cornell box's paths, 1024 samples");
    g.bench_function("core path tracer, fast search", |b| {
        b.iter(|| {
            let mut stats = Stats::default();
            samples
                .iter()
                .map(|(r, p)| core.radiance(black_box(r), p, &mut stats))
                .sum::<DVec3>()
        })
    });
    g.bench_function("fast wing (diffuse paths)", |b| {
        b.iter(|| {
            let mut stats = Stats::default();
            samples
                .iter()
                .map(|(r, p)| wing.radiance(&fast, black_box(r), p, &mut stats))
                .sum::<DVec3>()
        })
    });
    g.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20).measurement_time(std::time::Duration::from_secs(2));
    targets = shapes, sphere_group, bvh, bvh_build, lanes, primary_packets, shadow_packets, csg, footprints, boxes, room, paths, render
}
criterion_main!(benches);
