//! Groups against The Ray Tracer Challenge's chapter "Groups" (a transformed group, nested
//! groups whose transforms compose with the child's, the normal on a child) and chapter
//! "Bounding boxes and hierarchies" (a group's box holds its children's), and as objects of a
//! scene (materials inherited, an inner hierarchy that finds what brute force finds).

mod common;

use glam::DVec3;
use raytree::geometry::Ray;
use raytree::render::{render_simple, Engine, RenderOptions};
use raytree::scene::{Accel, Geometry, Scene};
use raytree::trace::Tracer;

fn scene(objects: &str) -> Scene {
    common::scene(&format!(
        "camera: {{ eye: [0, 0, -20], look_at: [0, 0, 0], width: 16, height: 12 }}
ambient: 0.3
lights: [ {{ name: L, point: [-10, 10, -10] }} ]
materials:
  red: {{ color: [1, 0, 0], ka: 0.3, kd: 0.7 }}
  blue: {{ color: [0, 0, 1], ka: 0.3, kd: 0.7 }}
objects:
{objects}"
    ))
}

fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
    Ray::new(DVec3::from(o), DVec3::from(d))
}

/// "Intersecting a transformed group": a group scaled by 2 holding a sphere moved by
/// (5, 0, 0) (so a sphere of radius 2 about (10, 0, 0)); the ray from (10, 0, −10) along +z
/// meets it at t = 8 and 12.
#[test]
fn a_transformed_group_moves_its_members() {
    let s = scene(
        "  - name: g
    transform: [ { scale: 2 } ]
    material: red
    group:
      - { name: s, sphere: { center: [0, 0, 0], radius: 1 }, transform: [ { translate: [5, 0, 0] } ] }
",
    );
    let n = Tracer::new(&s).inspect(&ray([10.0, 0.0, -10.0], [0.0, 0.0, 1.0]));
    let h = n.hit.unwrap();
    assert_eq!((h.object.as_str(), h.leaf.as_str()), ("g", "s"));
    assert!((h.t - 8.0).abs() < 1e-12, "{}", h.t);
    let (list, _) = s.object_trace(0, &ray([10.0, 0.0, -10.0], [0.0, 0.0, 1.0]), true);
    assert_eq!(list.len(), 1);
    assert!((list[0].t_in - 8.0).abs() < 1e-12 && (list[0].t_out - 12.0).abs() < 1e-12);
}

/// "Finding the normal on a child object": group g1 turned by 90° about y holds group g2
/// scaled by (1, 2, 3), which holds a sphere moved by (5, 0, 0). At the point
/// (1.7321, 1.1547, −5.5774) of the sphere (the image of the point (√3/3, √3/3, √3/3) of the
/// unit sphere), the normal is (0.2857, 0.4286, −0.8571).
#[test]
fn nested_transforms_compose_with_the_childs_own() {
    let s = scene(
        "  - name: g1
    transform: [ { rotate_y: 90 } ]
    material: red
    group:
      - name: g2
        transform: [ { scale: [1, 2, 3] } ]
        group:
          - { name: s, sphere: { center: [0, 0, 0], radius: 1 }, transform: [ { translate: [5, 0, 0] } ] }
",
    );
    let r3 = 3f64.sqrt();
    // The point, by hand: (5 + √3/3, √3/3, √3/3) → scaled (5 + √3/3, 2√3/3, √3) → turned
    // (x, z) → (z, −x).
    let p = DVec3::new(r3, 2.0 * r3 / 3.0, -(5.0 + r3 / 3.0));
    assert!((p - DVec3::new(1.7321, 1.1547, -5.5774)).length() < 1e-4);
    let normal = DVec3::new(0.2857, 0.4286, -0.8571);
    let n = Tracer::new(&s).inspect(&Ray::new(p + 3.0 * normal, -normal));
    let h = n.hit.unwrap();
    assert_eq!((h.object.as_str(), h.leaf.as_str()), ("g1", "s"));
    assert!((h.point - p).length() < 1e-3, "{}", h.point);
    assert!((h.normal - normal).length() < 1e-4, "{}", h.normal);
}

/// "Intersecting a ray with a nonempty group": spheres at the origin, at (0, 0, −3) and at
/// (5, 0, 0); the ray from (0, 0, −5) along +z meets the second at 1 and 3, the first at 4
/// and 6, and misses the third.
#[test]
fn a_group_lists_its_members_crossings() {
    let s = scene(
        "  - name: g
    material: red
    group:
      - { name: s1, sphere: { center: [0, 0, 0], radius: 1 } }
      - { name: s2, sphere: { center: [0, 0, 0], radius: 1 }, transform: [ { translate: [0, 0, -3] } ] }
      - { name: s3, sphere: { center: [0, 0, 0], radius: 1 }, transform: [ { translate: [5, 0, 0] } ] }
",
    );
    let r = ray([0.0, 0.0, -5.0], [0.0, 0.0, 1.0]);
    let (list, trace) = s.object_trace(0, &r, true);
    let ts: Vec<(f64, f64)> = list.iter().map(|s| (s.t_in, s.t_out)).collect();
    assert_eq!(ts, [(1.0, 3.0), (4.0, 6.0)]);
    assert_eq!(trace.children.len(), 3);
    let h = Tracer::new(&s).inspect(&r).hit.unwrap();
    assert_eq!(h.leaf, "s2");
    assert_eq!(h.t, 1.0);
}

/// Members without a material take the group's; a member's own wins; a nested group passes
/// its material on.
#[test]
fn members_inherit_the_groups_material() {
    let s = scene(
        "  - name: g
    material: red
    group:
      - { name: plain, sphere: { center: [-3, 0, 0], radius: 1 } }
      - { name: own, sphere: { center: [0, 0, 0], radius: 1 }, material: blue }
      - name: inner
        group:
          - { name: deep, sphere: { center: [3, 0, 0], radius: 1 } }
",
    );
    let material = |x: f64| {
        let n = Tracer::new(&s).inspect(&ray([x, 0.0, -10.0], [0.0, 0.0, 1.0]));
        n.hit.unwrap().material
    };
    assert_eq!(material(-3.0), "red");
    assert_eq!(material(0.0), "blue");
    assert_eq!(material(3.0), "red");
    // Without a material anywhere: an error at the member.
    let text = "camera: { eye: [0, 0, -20], look_at: [0, 0, 0] }
materials: { m: { kd: 1 } }
objects:
  - name: g
    group:
      - { name: lost, sphere: { center: [0, 0, 0], radius: 1 } }
";
    let e = raytree::scene::parse(text, "bad.yaml", None, &raytree::scene::Limits::default())
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("bad.yaml:6:9: ") && e.contains("object `lost` has no `material`"),
        "{e}"
    );
}

/// "A group has a bounding box that contains its children": a sphere scaled by 2 and moved to
/// (2, 5, −3), and a cylinder from y = −2 to 2 scaled by (0.5, 1, 0.5) and moved to
/// (−4, −1, 4): the group's box runs from (−4.5, −3, −5) to (4, 7, 4.5).
#[test]
fn a_groups_box_holds_its_members() {
    let s = scene(
        "  - name: g
    material: red
    group:
      - { sphere: { center: [0, 0, 0], radius: 1 }, transform: [ { scale: 2 }, { translate: [2, 5, -3] } ] }
      - { cylinder: { base: [0, -2, 0], top: [0, 2, 0], radius: 1 }, transform: [ { scale: [0.5, 1, 0.5] }, { translate: [-4, -1, 4] } ] }
",
    );
    let b = s.objects[0].bounds;
    assert!(
        (b.min - DVec3::new(-4.5, -3.0, -5.0)).length() < 1e-12,
        "{b:?}"
    );
    assert!(
        (b.max - DVec3::new(4.0, 7.0, 4.5)).length() < 1e-12,
        "{b:?}"
    );
    let Geometry::Group(g) = &s.objects[0].geometry else {
        panic!("a group")
    };
    assert_eq!(g.members[0].name, "g.sphere1");
    assert_eq!(g.members[1].name, "g.cylinder2");
}

/// A group of 400 spheres is one object of the scene (with one box), searched through its own
/// hierarchy: the image equals the one found by testing every member, and by the fast wing.
#[test]
fn a_groups_hierarchy_finds_what_brute_force_finds() {
    let mut members = String::new();
    for k in 0..400 {
        let (x, y) = ((k % 20) as f64 - 9.5, (k / 20) as f64 - 9.5);
        let m = if k % 3 == 0 { "blue" } else { "red" };
        members.push_str(&format!(
            "      - {{ sphere: {{ center: [{x}, {y}, 0], radius: 0.45 }}, material: {m} }}\n"
        ));
    }
    let s = scene(&format!(
        "  - name: wall\n    transform: [ {{ rotate_y: 20 }}, {{ scale: 0.8 }} ]\n    group:\n{members}"
    ));
    assert_eq!(s.objects.len(), 1);
    let Geometry::Group(g) = &s.objects[0].geometry else {
        panic!("a group")
    };
    assert!(g.bvh.node_count() > 100, "{}", g.bvh.node_count());
    let options = RenderOptions::of(&s);
    let (with_bvh, stats) = render_simple(&s, options);
    let mut brute = s.clone();
    brute.set_accel(Accel::None);
    let (without, brute_stats) = render_simple(&brute, options);
    assert_eq!(with_bvh.pixels, without.pixels);
    // The hierarchy tests far fewer spheres than the 400 per ray brute force does.
    assert!(
        stats.primitives_tested * 10 < brute_stats.primitives_tested,
        "{} vs {}",
        stats.primitives_tested,
        brute_stats.primitives_tested
    );
    let core = RenderOptions {
        engine: Engine::Core,
        ..options
    };
    assert_eq!(render_simple(&s, core).0.pixels, with_bvh.pixels);
}

/// A leaf is named as the tree shows it: an object that is one shape by the object's name
/// (given, or `object` and its place in the list), a CSG child by its own name or its
/// object's name, its kind and its place, a group member as the member.
#[test]
fn every_leaf_is_named_as_the_tree_shows_it() {
    let s = scene(
        "  - { sphere: { center: [0, 0, 0], radius: 1 }, material: red }
  - { name: a, sphere: { center: [3, 0, 0], radius: 1 }, material: red }
  - name: lens
    material: blue
    intersection:
      - { sphere: { center: [6, 0, 0], radius: 1 } }
      - { name: right, sphere: { center: [6.5, 0, 0], radius: 1 } }
  - name: g
    material: red
    group:
      - { sphere: { center: [9, 0, 0], radius: 1 } }
",
    );
    let names: Vec<&str> = s.leaves.iter().map(|l| l.name.as_str()).collect();
    assert_eq!(
        names,
        ["object1", "a", "lens.sphere1", "right", "g.sphere1"]
    );
    assert_eq!(s.objects[0].name, "object1");
}
