//! Tests that catch a wrong formula: each pins one formula of the lecture's model with a value
//! worked out by hand, in a configuration where the plausible wrong formulas (r·n for r·v,
//! weights not multiplied by the Fresnel term, n1 and n2 swapped, c1 and c2 swapped, shadow
//! samples at the strata's corners) give other numbers.

mod common;

use glam::DVec3;
use raytree::geometry::csg::complement;
use raytree::geometry::{Mesh, Ray, Segment, Surface};
use raytree::shading::local::light_terms;
use raytree::shading::{Highlight, Material};
use raytree::trace::{RayKind, RayNode, Termination, Tracer};

const E: f64 = 1e-12;

fn child(node: &RayNode, kind: RayKind) -> &RayNode {
    node.children
        .iter()
        .find(|c| c.kind == kind)
        .unwrap_or_else(|| panic!("no {kind:?} child in {node:#?}"))
}

/// A viewer away from the normal: n = +y, the light 60° to one side (l in the xy plane), the
/// viewer 30° to the other side. Phong's r = 2(n·l)n − l lies 60° on the viewer's side, 30°
/// from v: (r·v)² = cos²30° = ¾ (r·n would give cos²60° = ¼). Blinn's h, halfway between l
/// and v, is 15° from n: (h·n)² = cos²15° = (1 + cos 30°)/2.
#[test]
fn highlights_with_the_viewer_off_the_normal() {
    let m = Material {
        ks: 0.4,
        shininess: 2.0,
        ..Material::matte("m", DVec3::ONE)
    };
    let n = DVec3::Y;
    let l = DVec3::new(60f64.to_radians().sin(), 60f64.to_radians().cos(), 0.0);
    let v = DVec3::new(-(30f64.to_radians().sin()), 30f64.to_radians().cos(), 0.0);
    let phong = Material {
        highlight: Highlight::Phong,
        ..m.clone()
    };
    let t = light_terms(&phong, &phong.paint(), n, v, l, DVec3::ONE, false);
    assert!(
        (t.highlight_cos - 0.75f64.sqrt()).abs() < E,
        "{}",
        t.highlight_cos
    );
    assert!((t.specular - DVec3::splat(0.4 * 0.75)).length() < E);
    let blinn = Material {
        highlight: Highlight::Blinn,
        ..m
    };
    let t = light_terms(&blinn, &blinn.paint(), n, v, l, DVec3::ONE, false);
    let cos15_squared = (1.0 + 0.75f64.sqrt()) / 2.0;
    assert!((t.specular - DVec3::splat(0.4 * cos15_squared)).length() < E);
}

/// A glass ball (kr = kt = 1, n = 1.5) with Schlick's Fresnel term: R0 = ((1 − 1.5)/2.5)² =
/// 0.04. Head on, the reflection ray carries kr·R0 = 0.04 and the refraction ray
/// kt·(1 − R0) = 0.96.
#[test]
fn schlick_weights_head_on() {
    let s = common::scene(GLASS_BALL);
    let tree = Tracer::new(&s).inspect(&Ray::new(DVec3::new(0.0, 0.0, -5.0), DVec3::Z));
    assert!((child(&tree, RayKind::Reflection).coefficient - 0.04).abs() < E);
    assert!((child(&tree, RayKind::Refraction).coefficient - 0.96).abs() < E);
}

/// Entering the same ball at 60° from the normal (cos θ = ½): R = R0 + (1 − R0)(1 − ½)⁵ =
/// 0.04 + 0.96/32 = 0.07. Inside, the refracted ray meets the far side at θt (sin θt =
/// sin 60°/1.5) and leaves at 60° again (a sphere is symmetric), so Schlick's cosine, taken
/// on the side of the lower index (air), is ½ there too: again 0.07 and 0.93. Taking the
/// inside cosine cos θt instead (n1 and n2 swapped) would give about 0.0402.
#[test]
fn schlick_weights_at_sixty_degrees_outside_and_inside() {
    let s = common::scene(GLASS_BALL);
    let y = 60f64.to_radians().sin();
    let tree = Tracer::new(&s).inspect(&Ray::new(DVec3::new(0.0, y, -5.0), DVec3::Z));
    let r = 0.04 + 0.96 / 32.0;
    assert!((child(&tree, RayKind::Reflection).coefficient - r).abs() < 1e-9);
    let inside = child(&tree, RayKind::Refraction);
    assert!((inside.coefficient - (1.0 - r)).abs() < 1e-9);
    let indices = inside.indices.expect("a refraction ray names its media");
    assert_eq!((indices.n1, indices.n2), (1.0, 1.5));
    assert!((child(inside, RayKind::Reflection).coefficient - r).abs() < 1e-9);
    let out = child(inside, RayKind::Refraction);
    assert!((out.coefficient - (1.0 - r)).abs() < 1e-9);
    let indices = out.indices.unwrap();
    assert_eq!((indices.n1, indices.n2), (1.5, 1.0));
}

/// An opaque varnished ball (kr = 1, kt = 0, n = 1.5, Schlick): its media still set the
/// Fresnel term, so head on the reflection carries R0 = 0.04 (with the media left out, n1 = n2
/// and R0 would be 0) and at 60° from the normal 0.07.
#[test]
fn schlick_weights_an_opaque_surface_by_its_index() {
    let s = common::scene(&GLASS_BALL.replace("kr: 1, kt: 1", "kr: 1, kt: 0"));
    let tree = Tracer::new(&s).inspect(&Ray::new(DVec3::new(0.0, 0.0, -5.0), DVec3::Z));
    assert!((child(&tree, RayKind::Reflection).coefficient - 0.04).abs() < E);
    assert!(tree.children.iter().all(|c| c.kind != RayKind::Refraction));
    let y = 60f64.to_radians().sin();
    let tree = Tracer::new(&s).inspect(&Ray::new(DVec3::new(0.0, y, -5.0), DVec3::Z));
    let r = 0.04 + 0.96 / 32.0;
    assert!((child(&tree, RayKind::Reflection).coefficient - r).abs() < 1e-9);
}

/// An air bubble (n = 1) in a glass block (n = 1.5), the bubble listed first in the file. A ray
/// along the x axis enters the block, then the bubble, leaves the bubble and then the block:
/// its refraction rays name n1 → n2 as 1 → 1.5, 1.5 → 1, 1 → 1.5, 1.5 → 1, whatever order the
/// file lists the solids in.
#[test]
fn nested_media_follow_the_geometry_not_the_file_order() {
    let s = common::scene(
        "camera: { eye: [-5, 0, 0], look_at: [0, 0, 0] }
max_depth: 6
materials:
  glass: { kt: 1, ior: 1.5 }
  air: { kt: 1, ior: 1 }
objects:
  - { name: bubble, sphere: { center: [0, 0, 0], radius: 0.5 }, material: air }
  - { name: block, box: { min: [-2, -2, -2], max: [2, 2, 2] }, material: glass }
",
    );
    let tree = Tracer::new(&s).inspect(&Ray::new(DVec3::new(-5.0, 0.0, 0.0), DVec3::X));
    let crossings = common::refraction_crossings(&tree);
    let expected = [
        ("block", 1.0, 1.5),
        ("bubble", 1.5, 1.0),
        ("bubble", 1.0, 1.5),
        ("block", 1.5, 1.0),
    ];
    let got: Vec<(&str, f64, f64)> = crossings
        .iter()
        .map(|(o, a, b)| (o.as_str(), *a, *b))
        .collect();
    assert_eq!(got, expected);
}

/// With kr = 0.3 and kt = 0.6 the weights kr·R + kt·(1 − R) lie between 0.3 and 0.6 at every
/// angle, inside the ball and out (0 ≤ R ≤ 1): the Fresnel term moves energy between the two
/// rays and never creates any.
#[test]
fn schlick_weights_add_no_energy() {
    let s = common::scene(&GLASS_BALL.replace("kr: 1, kt: 1", "kr: 0.3, kt: 0.6"));
    for k in 0..40 {
        let y = 0.999 * k as f64 / 40.0;
        let tree = Tracer::new(&s).inspect(&Ray::new(DVec3::new(0.0, y, -5.0), DVec3::Z));
        let mut nodes = vec![&tree];
        while let Some(node) = nodes.pop() {
            let sum: f64 = node
                .children
                .iter()
                .filter(|c| matches!(c.kind, RayKind::Reflection | RayKind::Refraction))
                .map(|c| c.coefficient)
                .sum();
            if node.hit.is_some() && node.terminated.is_none() {
                assert!(
                    (0.3 - 1e-12..=0.6 + 1e-12).contains(&sum),
                    "{sum} at y = {y}"
                );
            }
            nodes.extend(node.children.iter());
        }
    }
}

/// With Hall's weights a glass whose kr is below its kt loses (kt − kr)·R: past the limiting
/// angle (R = 1) a ray inside a kt = 1, kr = 0 ball is lost whole. The scene says so, at the
/// material; clear glass (kr = kt) and a glass without the Fresnel term do not warn. Under the
/// path tracer, whose expected weight is kd·O + kr + kt, a material above 1 is warned of.
#[test]
fn materials_that_lose_or_make_light_are_warned_of() {
    let warnings = |yaml: &str| common::scene(yaml).warnings.clone();
    let lossy = GLASS_BALL.replace("kr: 1, kt: 1", "kr: 0, kt: 1");
    let w = warnings(&lossy);
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!((w[0].0.line, w[0].0.column), (3, 21), "{w:?}");
    assert!(w[0].1.contains("material `glass`") && w[0].1.contains("(kt − kr)·R"));
    // Past the limiting angle the lossy glass sends nothing on: a ray inside the ball at 60°
    // from the normal (sin 60° > 1/1.5) has no refracted child and no reflected weight.
    let s = common::scene(&lossy);
    let y = 60f64.to_radians().sin();
    let inside = Tracer::new(&s).inspect(&Ray::new(DVec3::new(y, 0.0, 0.0), DVec3::Y));
    let sent: f64 = inside.children.iter().map(|c| c.coefficient).sum();
    assert_eq!(sent, 0.0, "{inside:#?}");
    assert!(warnings(GLASS_BALL).is_empty());
    assert!(warnings(
        &GLASS_BALL
            .replace(", fresnel: schlick", "")
            .replace("kr: 1", "kr: 0")
    )
    .is_empty());
    let path = |m: &str| {
        format!("camera: {{ eye: [0, 0, -5], look_at: [0, 0, 0] }}\nintegrator: path\nmaterials: {{ m: {m} }}\nobjects: [ {{ name: b, sphere: {{ center: [0, 0, 0], radius: 1 }}, material: m }} ]\n")
    };
    let w = warnings(&path("{ kr: 1, kt: 1, ior: 1.5 }"));
    assert!(
        w.len() == 1 && w[0].1.contains("kd·O + kr + kt = 2 is above 1"),
        "{w:?}"
    );
    assert!(warnings(&path("{ kt: 1, ior: 1.5 }")).is_empty());
    assert!(warnings(&path("{ color: 0.5, kd: 1, kr: 0.5 }")).is_empty());
}

const GLASS_BALL: &str = "camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }
max_depth: 3
materials: { glass: { kr: 1, kt: 1, ior: 1.5, fresnel: schlick } }
objects: [ { name: ball, sphere: { center: [0, 0, 0], radius: 1 }, material: glass } ]
";

/// A mirror (kr = 1, nothing else) at z = 0 reflects a wall 2 away that shines 1 (its ambient
/// term). With `secondary_attenuation: [1, 0.5, 0.25]` the reflected intensity is divided by
/// 1 + 0.5·2 + 0.25·2² = 3 (with c1 and c2 swapped it would be 1 + 0.25·2 + 0.5·4 = 3.5).
#[test]
fn secondary_attenuation_divides_by_the_quadratic_in_the_distance() {
    let s = common::scene(
        "camera: { eye: [0, 0, -1], look_at: [0, 0, 0] }
ambient: 1
secondary_attenuation: [1, 0.5, 0.25]
materials:
  mirror: { kr: 1 }
  wall: { ka: 1 }
objects:
  - { name: mirror, plane: { point: [0, 0, 0], normal: [0, 0, -1] }, material: mirror }
  - { name: wall, plane: { point: [0, 0, -2], normal: [0, 0, 1] }, material: wall }
",
    );
    let tree = Tracer::new(&s).inspect(&Ray::new(DVec3::new(0.0, 0.0, -1.0), DVec3::Z));
    assert_eq!(
        child(&tree, RayKind::Reflection)
            .hit
            .as_ref()
            .unwrap()
            .object,
        "wall"
    );
    // (d is 2 less the origin's offset off the mirror, a few 1e−10.)
    assert!(
        (tree.color - DVec3::splat(1.0 / 3.0)).length() < 1e-9,
        "{}",
        tree.color
    );
}

/// A rectangle light 2 × 2 at height 10 straight above the shaded point, sampled 4 × 4 at the
/// centres of its strata (x and z = −0.75, −0.25, 0.25, 0.75), with a box hiding every point
/// with x < 0 from the origin, or every point with z < 0: exactly half the shadow rays pass,
/// s = ½ (at the strata's corners, −1, −0.5, 0, 0.5, the ray to 0 grazes the box and 3 of 4
/// columns or rows are hidden); a box hiding the quarter x < 0, z < 0 leaves s = ¾ (a grid
/// that took one index for both axes would sample only its diagonal, and give ½). Its l is toward the rectangle's centre (0, 10, 0): straight up,
/// and from (3, 0, 0) along (−3, 10, 0)/√109.
#[test]
fn a_rectangle_light_half_hidden_gives_a_shadow_factor_of_one_half() {
    let panel = |blocker_max: &str| {
        common::scene(&format!(
            "camera: {{ eye: [0, 1, -3], look_at: [0, 0, 0] }}
lights: [ {{ name: panel, rect: {{ corner: [-1, 10, -1], u: [2, 0, 0], v: [0, 0, 2] }}, samples: 4 }} ]
materials: {{ floor: {{ kd: 1 }}, black: {{}} }}
objects:
  - {{ name: floor, plane: {{ point: [0, 0, 0], normal: [0, 1, 0] }}, material: floor }}
  - {{ name: blocker, box: {{ min: [-5, 4, -5], max: {blocker_max} }}, material: black }}
"
        ))
    };
    for (blocker_max, s) in [("[0, 5, 5]", 0.5), ("[5, 5, 0]", 0.5), ("[0, 5, 0]", 0.75)] {
        let scene = panel(blocker_max);
        let tree = Tracer::new(&scene).inspect(&Ray::new(DVec3::new(0.0, 1.0, 0.0), -DVec3::Y));
        let light = &tree.local.as_ref().unwrap().lights[0];
        assert_eq!(light.shadow, s, "blocker up to {blocker_max}");
        assert!((light.l - DVec3::Y).length() < E, "{}", light.l);
    }

    let s = panel("[0, 5, 5]");
    let tree = Tracer::new(&s).inspect(&Ray::new(DVec3::new(3.0, 1.0, 0.0), -DVec3::Y));
    let light = &tree.local.as_ref().unwrap().lights[0];
    let toward_centre = DVec3::new(-3.0, 10.0, 0.0) / 109f64.sqrt();
    assert!((light.l - toward_centre).length() < E, "{}", light.l);
}

/// A rectangle emits on the side of u × v only. The panel at height 2 with u = x, v = z faces
/// down (x × z = −y): the floor under it gets I = kd·Iℓ·(n·l) = 1 straight below its centre.
/// With u and v swapped it faces up, so the floor sees its back: fatt = 0, no shadow ray,
/// I = 0, and a point above the panel then sees its front and is lit, s = 1.
#[test]
fn a_rectangle_light_lights_only_the_side_of_u_cross_v() {
    let panel = |u: &str, v: &str| {
        common::scene(&format!(
            "camera: {{ eye: [0, 1, -3], look_at: [0, 0, 0] }}
lights: [ {{ name: panel, rect: {{ corner: [-1, 2, -1], u: {u}, v: {v} }}, samples: 2 }} ]
materials: {{ matte: {{ ka: 0, kd: 1 }} }}
objects:
  - {{ name: floor, plane: {{ point: [0, 0, 0], normal: [0, 1, 0] }}, material: matte }}
  - {{ name: roof, plane: {{ point: [0, 4, 0], normal: [0, -1, 0] }}, material: matte }}
"
        ))
    };
    let down_to_floor = Ray::new(DVec3::new(0.0, 1.0, 0.0), -DVec3::Y);
    let up_to_roof = Ray::new(DVec3::new(0.0, 3.0, 0.0), DVec3::Y);

    let facing_down = panel("[2, 0, 0]", "[0, 0, 2]");
    let floor = Tracer::new(&facing_down).inspect(&down_to_floor);
    let light = &floor.local.as_ref().unwrap().lights[0];
    assert_eq!((light.attenuation, light.shadow), (1.0, 1.0));
    assert!((floor.color - DVec3::ONE).length() < E, "{}", floor.color);
    let roof = Tracer::new(&facing_down).inspect(&up_to_roof);
    assert_eq!(roof.color, DVec3::ZERO);

    let facing_up = panel("[0, 0, 2]", "[2, 0, 0]");
    let floor = Tracer::new(&facing_up).inspect(&down_to_floor);
    let light = &floor.local.as_ref().unwrap().lights[0];
    assert_eq!((light.attenuation, floor.color), (0.0, DVec3::ZERO));
    assert!(light.skipped.as_deref().unwrap().contains("u × v"));
    assert_eq!(floor.children.len(), 0, "no shadow ray is cast");
    let roof = Tracer::new(&facing_up).inspect(&up_to_roof);
    assert!((roof.color - DVec3::ONE).length() < E, "{}", roof.color);
}

/// Adaptive depth control at its boundary: mirrors with kr = ½ facing each other, threshold
/// ¼. The first reflection weighs ½, the second exactly ¼: a ray whose weight equals the
/// threshold is still traced; the third, ⅛, is cut.
#[test]
fn a_ray_whose_weight_equals_the_adaptive_threshold_is_traced() {
    let s = common::scene(
        "camera: { eye: [0, 0, -1], look_at: [0, 0, 0] }
max_depth: 10
adaptive_threshold: 0.25
materials: { mirror: { kr: 0.5 } }
objects:
  - { name: front, plane: { point: [0, 0, 0], normal: [0, 0, -1] }, material: mirror }
  - { name: back, plane: { point: [0, 0, -2], normal: [0, 0, 1] }, material: mirror }
",
    );
    let tree = Tracer::new(&s).inspect(&Ray::new(DVec3::new(0.0, 0.0, -1.0), DVec3::Z));
    let first = child(&tree, RayKind::Reflection);
    let second = child(first, RayKind::Reflection);
    let third = child(second, RayKind::Reflection);
    assert_eq!(
        (first.weight, second.weight, third.weight),
        (0.5, 0.25, 0.125)
    );
    assert_eq!(second.terminated, None);
    assert!(second.hit.is_some(), "the ray at the threshold is traced");
    assert_eq!(third.terminated, Some(Termination::Adaptive));
}

/// Smooth shading interpolates the vertex normals with the barycentric coordinates (seed 002):
/// at p = (0.5, 0.25, 0) of the triangle (0,0,0), (1,0,0), (0,1,0) the coordinates are
/// (¼, ½, ¼), so n ∝ ¼·n_a + ½·n_b + ¼·n_c.
#[test]
fn smooth_normals_blend_the_vertex_normals_by_barycentric_weight() {
    let r = 0.5f64.sqrt();
    let (na, nb, nc) = (DVec3::Z, DVec3::new(r, 0.0, r), DVec3::new(0.0, r, r));
    let (mesh, dropped) = Mesh::new(
        vec![DVec3::ZERO, DVec3::X, DVec3::Y],
        vec![na, nb, nc],
        vec![[0, 1, 2]],
    );
    assert_eq!(dropped, 0);
    let n = mesh.normal(DVec3::new(0.5, 0.25, 0.0), 0);
    let expected = DVec3::new(0.5 * r, 0.25 * r, 0.25 + 0.75 * r).normalize();
    assert!((n - expected).length() < E, "{n} vs {expected}");
}

/// The complement of a segment list is its gaps out to ±∞, every surface facing the other
/// way: ¬([1, 2] ∪ [4, 5]) = (−∞, 1] ∪ [2, 4] ∪ [5, ∞).
#[test]
fn the_complement_of_a_list_is_its_gaps() {
    let seg = |a, b, leaf| Segment {
        t_in: a,
        t_out: b,
        enter: Surface::new(leaf, 0),
        exit: Surface::new(leaf, 1),
    };
    let c = complement(&[seg(1.0, 2.0, 7), seg(4.0, 5.0, 8)]);
    let ts: Vec<(f64, f64)> = c.iter().map(|s| (s.t_in, s.t_out)).collect();
    assert_eq!(
        ts,
        vec![(f64::NEG_INFINITY, 1.0), (2.0, 4.0), (5.0, f64::INFINITY)]
    );
    // The gap [2, 4] is entered where [1, 2] was left and left where [4, 5] was entered.
    assert_eq!(c[1].enter, Surface::new(7, 1).flipped());
    assert_eq!(c[1].exit, Surface::new(8, 0).flipped());
    assert_eq!(c[0].exit, Surface::new(7, 0).flipped());
    assert_eq!(c[2].enter, Surface::new(8, 1).flipped());
}
