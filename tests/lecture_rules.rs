//! Options of the core that teach rules of the notes beyond the default Whitted recursion:
//! Hall's transmitted highlight (seed 004), distance attenuation of secondary rays shown in
//! the printed sum (seeds 000, 004), and the stop rules of seeds 000 and 002. Expected numbers
//! are worked by hand from the scenes' geometry.

mod common;

use common::scene;
use glam::DVec3;
use raytree::geometry::Ray;
use raytree::trace::{text, RayKind, Termination, TraceOptions, Tracer};

fn ray(o: [f64; 3], d: [f64; 3]) -> Ray {
    Ray {
        origin: DVec3::from(o),
        dir: DVec3::from(d).normalize(),
    }
}

/// A lamp in a glass half-space (y < 0, η = 1.5) seen from the air along (0.6, −0.8, 0) at the
/// origin: l = (0.6, −0.8, 0), h′ = −(1.5·l + v)/0.5 = (−0.6, 0.8, 0), h′·n = 0.8.
fn lamp(highlight: bool, extra: &str) -> raytree::scene::Scene {
    scene(&format!(
        "camera: {{ eye: [-3, 4, 0], look_at: [0, 0, 0], up: [0, 1, 0], fov: 60, width: 8, height: 6 }}
background: 0.1
max_depth: 3
lights:
  - {{ name: L, point: [3, -4, 0], intensity: 1 }}
materials:
  glass: {{ color: 1, ks: 0.5, shininess: 10, kt: 0.9, ior: 1.5, transmitted_highlight: {highlight} }}
  dark: {{ color: 1, kd: 0.5 }}
objects:
  - {{ name: surface, plane: {{ point: [0, 0, 0], normal: [0, 1, 0] }}, material: glass }}
{extra}"
    ))
}

#[test]
fn a_light_behind_glass_makes_the_transmitted_highlight_through_a_cast_shadow_ray() {
    let view = ray([-3.0, 4.0, 0.0], [0.6, -0.8, 0.0]);
    let on = lamp(true, "");
    let tree = Tracer::new(&on).inspect(&view);
    let term = &tree.local.as_ref().unwrap().lights[0];
    assert_eq!(term.skipped, None);
    assert!((term.n_dot_l + 0.8).abs() < 1e-12);
    assert!((term.highlight_cos - 0.8).abs() < 1e-12);
    assert!((term.specular.x - 0.5 * 0.8f64.powi(10)).abs() < 1e-12);
    assert_eq!(term.diffuse, DVec3::ZERO);
    assert_eq!(term.shadow, 1.0);
    let shadow = tree
        .children
        .iter()
        .find(|c| c.kind == RayKind::Shadow)
        .expect("the shadow ray through the surface is cast");
    assert!(shadow.direction.y < 0.0, "it goes down through the surface");
    assert!((tree.color.x - (0.5 * 0.8f64.powi(10) + 0.9 * 0.1)).abs() < 1e-12);

    // Off (the default), the lamp behind the surface gives nothing and no shadow ray is cast.
    let off = lamp(false, "");
    let tree = Tracer::new(&off).inspect(&view);
    let term = &tree.local.as_ref().unwrap().lights[0];
    assert!(term.skipped.is_some());
    assert_eq!(term.specular, DVec3::ZERO);
    assert!(tree.children.iter().all(|c| c.kind != RayKind::Shadow));

    // An opaque slab between the surface and the lamp blocks the shadow ray: s = 0.
    let blocked = lamp(
        true,
        "  - { name: slab, box: { min: [-5, -2, -5], max: [5, -1, 5] }, material: dark }\n",
    );
    let tree = Tracer::new(&blocked).inspect(&view);
    let term = &tree.local.as_ref().unwrap().lights[0];
    assert_eq!(term.shadow, 0.0);
    assert_eq!(term.specular, DVec3::ZERO);
}

/// A glass half-space (y < 0, η = 1.5) with a lamp in the air at (0, 5, 0), seen from inside
/// the glass along (0.6, 0.8, 0) at the origin: the viewer's side has the index 1.5, the
/// light's 1, so η = 1/1.5 and H′ ∝ −(η·l + v)/(η − 1) with l = (0, 1, 0), v = (−0.6, −0.8, 0):
/// −((0, ⅔, 0) + v)/(−⅓) = (−1.8, −0.4, 0). With n = (0, −1, 0) toward the viewer,
/// h′·n = 0.4/√3.4, and with m = 2 the highlight is ks·0.16/3.4.
#[test]
fn the_transmitted_highlight_seen_from_inside_the_glass_takes_eta_as_light_over_viewer() {
    let s = scene(
        "camera: { eye: [-3, -4, 0], look_at: [0, 0, 0], up: [0, 1, 0], fov: 60, width: 8, height: 6 }
background: 0.1
max_depth: 1
lights:
  - { name: L, point: [0, 5, 0], intensity: 1 }
materials:
  glass: { color: 1, ks: 0.5, shininess: 2, kt: 0.9, ior: 1.5, transmitted_highlight: true }
objects:
  - { name: surface, plane: { point: [0, 0, 0], normal: [0, 1, 0] }, material: glass }
",
    );
    let tree = Tracer::new(&s).inspect(&ray([-3.0, -4.0, 0.0], [0.6, 0.8, 0.0]));
    let term = &tree.local.as_ref().unwrap().lights[0];
    assert_eq!(term.skipped, None);
    assert!((term.n_dot_l + 1.0).abs() < 1e-12, "{}", term.n_dot_l);
    assert!(
        (term.highlight_cos - 0.4 / 3.4f64.sqrt()).abs() < 1e-12,
        "{}",
        term.highlight_cos
    );
    assert!((term.specular.x - 0.5 * 0.16 / 3.4).abs() < 1e-12);
}

/// The transmitted highlight is for transparent surfaces, and for lights behind them: an
/// opaque surface (kt = 0) that asks for it gets nothing from a light behind it, and a light in
/// the surface's own plane (n·l = 0 exactly) lights neither side; neither casts a shadow ray.
#[test]
fn no_transmitted_highlight_through_an_opaque_surface_or_from_the_horizon() {
    let setup = |kt: f64, light: &str| {
        scene(&format!(
            "camera: {{ eye: [0, 4, 0], look_at: [0, 0, 0], up: [0, 0, 1], fov: 60, width: 8, height: 6 }}
background: 0.1
max_depth: 1
lights:
  - {{ name: L, point: {light}, intensity: 1 }}
materials:
  m: {{ color: 1, ks: 0.5, shininess: 1, kt: {kt}, ior: 1.5, transmitted_highlight: true }}
objects:
  - {{ name: surface, plane: {{ point: [0, 0, 0], normal: [0, 1, 0] }}, material: m }}
"
        ))
    };
    let down = ray([0.0, 4.0, 0.0], [0.0, -1.0, 0.0]);
    for (kt, light, n_dot_l) in [(0.0, "[0, -5, 0]", -1.0), (0.9, "[3, 0, 0]", 0.0)] {
        let tree = Tracer::new(&setup(kt, light)).inspect(&down);
        let term = &tree.local.as_ref().unwrap().lights[0];
        assert_eq!(term.n_dot_l, n_dot_l, "kt {kt}");
        assert!(term.skipped.is_some(), "kt {kt}: {term:?}");
        assert_eq!(term.specular, DVec3::ZERO);
        assert!(tree.children.iter().all(|c| c.kind != RayKind::Shadow));
    }
}

/// With `secondary_attenuation: [1, 0, 0.25]` a mirror at y = 0 reflects the ray from
/// (−3, 4, 0) along (0.6, −0.8, 0) to a matte wall x = 3, d = 5 away (from (0, 0, 0) along
/// (0.6, 0.8, 0) to (3, 4, 0)): I_r is divided by 1 + 0.25·25 = 7.25, and the printed terms add
/// up to the printed I.
#[test]
fn the_distance_attenuation_is_shown_in_the_secondary_term() {
    let s = scene(
        "camera: { eye: [-3, 4, 0], look_at: [0, 0, 0], up: [0, 1, 0], fov: 60, width: 8, height: 6 }
background: 0
ambient: 1
max_depth: 2
secondary_attenuation: [1, 0, 0.25]
materials:
  mirror: { color: 1, ka: 0.1, kr: 0.8 }
  wall: { color: 1, ka: 0.58 }
objects:
  - { name: mirror, plane: { point: [0, 0, 0], normal: [0, 1, 0] }, material: mirror }
  - { name: wall, plane: { point: [3, 0, 0], normal: [-1, 0, 0] }, material: wall }
",
    );
    let tree = Tracer::new(&s).inspect(&ray([-3.0, 4.0, 0.0], [0.6, -0.8, 0.0]));
    let r = &tree.children[0];
    assert_eq!(r.kind, RayKind::Reflection);
    assert!((r.color.x - 0.58).abs() < 1e-12);
    assert!((r.attenuation.unwrap() - 7.25).abs() < 1e-12);
    let expected = 0.1 + 0.8 * 0.58 / 7.25;
    assert!((tree.color.x - expected).abs() < 1e-12);
    let details = text::node_details(&tree, text::tree_scale(&tree)).join("\n");
    assert!(
        details.contains("0.8 × 0.58 / 7.25 = 0.064"),
        "the factor is in the term:\n{details}"
    );
    assert!(
        details.contains("I = local 0.1 + secondary = 0.164"),
        "{details}"
    );
}

/// A mirror floor and a ball of light: the mirror ray that meets the ball stops there under
/// seed 000's rule and brings back the light's intensity; without the rule it passes through
/// the light to the background. A diffuse mirror stops under seed 002's rule; a matte surface,
/// which sends no secondary ray, is not marked as stopped.
#[test]
fn stop_rules_end_rays_at_lights_and_at_diffuse_surfaces() {
    let yaml_kr = |rules: &str, kd: f64, kr: f64| {
        scene(&format!(
            "camera: {{ eye: [-3, 4, 0], look_at: [0, 0, 0], up: [0, 1, 0], fov: 60, width: 8, height: 6 }}
background: 0.2
ambient: 0
max_depth: 3
stop_rules: [{rules}]
lights:
  - {{ name: ball, sphere: {{ center: [3, 4, 0], radius: 0.5 }}, intensity: 2 }}
materials:
  floor: {{ color: 1, kd: {kd}, kr: {kr} }}
objects:
  - {{ name: floor, plane: {{ point: [0, 0, 0], normal: [0, 1, 0] }}, material: floor }}
"
        ))
    };
    let yaml = |rules: &str, kd: f64| yaml_kr(rules, kd, 0.5);
    let view = ray([-3.0, 4.0, 0.0], [0.6, -0.8, 0.0]);

    let s = yaml("light", 0.0);
    let tree = Tracer::new(&s).inspect(&view);
    let r = &tree
        .children
        .iter()
        .find(|c| c.kind == RayKind::Reflection)
        .unwrap();
    assert_eq!(r.terminated, Some(Termination::Light));
    assert_eq!(r.light.as_deref(), Some("ball"));
    assert_eq!(r.color, DVec3::splat(2.0));
    assert!((tree.color.x - 0.5 * 2.0).abs() < 1e-12);
    assert_eq!(Tracer::new(&s).radiance(&view), tree.color);

    let s = yaml("", 0.0);
    let tree = Tracer::new(&s).inspect(&view);
    let r = &tree
        .children
        .iter()
        .find(|c| c.kind == RayKind::Reflection)
        .unwrap();
    assert_eq!(r.terminated, Some(Termination::Background));
    assert!((tree.color.x - 0.5 * 0.2).abs() < 1e-12);

    let s = yaml("diffuse", 0.3);
    let tree = Tracer::new(&s).inspect(&view);
    assert_eq!(tree.terminated, Some(Termination::Diffuse));
    assert!(tree.secondary().next().is_none());
    let with = Tracer::new(&yaml("", 0.3)).inspect(&view);
    assert!(with.secondary().next().is_some());
    // A matte floor sends no secondary ray at all: the rule has nothing to stop.
    let matte = Tracer::new(&yaml_kr("diffuse", 0.3, 0.0)).inspect(&view);
    assert_eq!(matte.terminated, None);

    // Options of the tracer: the scene's rules are its default, and a caller can override them.
    let s = yaml("light, diffuse", 0.3);
    let o = TraceOptions::of(&s);
    assert!(o.stop_at_lights && o.stop_at_diffuse);
    let tree = Tracer::new(&s)
        .with_options(TraceOptions {
            stop_at_diffuse: false,
            ..o
        })
        .inspect(&view);
    assert!(tree.secondary().next().is_some());
}

/// Seed 002's path-tracing rule: a path cut by the maximum depth "contributes just its local
/// illumination". A matte floor (albedo 0.5) at the origin under a ball of light (radiance 4,
/// radius 0.5, centre 2 above): the ball subtends sin²α = (0.5/2)², so the light reflected
/// toward the eye is albedo·Le·sin²α = 0.5·4/16 = 0.125. With one bounce allowed and the rule
/// on, the mean of many one-sample estimates is that within four standard errors; off, the
/// cut path brings back 0.
#[test]
fn a_path_at_the_maximum_depth_can_contribute_its_local_illumination() {
    use raytree::sampling::{pixel_key, SamplePoint};
    use raytree::stats::Stats;
    use raytree::trace::path::PathTracer;
    let yaml = |rules: &str| {
        scene(&format!(
            "integrator: path
camera: {{ eye: [-3, 4, 0], look_at: [0, 0, 0], up: [0, 1, 0], fov: 60, width: 8, height: 6 }}
background: 0
max_depth: 1
stop_rules: [{rules}]
lights:
  - {{ name: ball, sphere: {{ center: [0, 2, 0], radius: 0.5 }}, intensity: 4 }}
materials:
  floor: {{ color: 0.5, kd: 1 }}
objects:
  - {{ name: floor, plane: {{ point: [0, 0, 0], normal: [0, 1, 0] }}, material: floor }}
"
        ))
    };
    let view = ray([-3.0, 4.0, 0.0], [0.6, -0.8, 0.0]);
    let estimates = |s: &raytree::scene::Scene| -> Vec<f64> {
        let pt = PathTracer::new(s, 1);
        let mut stats = Stats::default();
        (0..20_000)
            .map(|k| {
                let point = SamplePoint::new(pixel_key(k, 0, 7), 0);
                pt.radiance(&view, &point, &mut stats).x
            })
            .collect()
    };
    let on = estimates(&yaml("local_at_max_depth"));
    let n = on.len() as f64;
    let mean = on.iter().sum::<f64>() / n;
    let var = on.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    let se = (var / n).sqrt();
    assert!((mean - 0.125).abs() < 4.0 * se, "mean {mean} ± {se}");
    assert!(se < 0.01 * 0.125, "the test can tell: se {se}");
    assert!(estimates(&yaml("")).iter().all(|&x| x == 0.0));
}
