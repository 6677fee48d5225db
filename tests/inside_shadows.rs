//! The rule that skips shadow rays from inside a convex solid: a bounded convex solid holds the
//! whole segment between two of its points, so the way from a point inside it to a light
//! outside it crosses its surface, and the shadow ray need not be cast. Here the real searches
//! confirm the rule wherever it is applied, and the scene applies it only where it holds.

use glam::DVec3;
use std::cell::Cell;

use proptest::prelude::*;
use proptest::test_runner::TestRunner;
use raytree::geometry::Ray;
use raytree::scene::Search;
use raytree::scene::{parse, Limits, Scene};
use raytree::stats::Stats;

fn scene(object: &str, light: &str) -> Scene {
    let yaml = format!(
        "camera: {{ eye: [0, 0, -30], look_at: [0, 0, 0] }}
lights: [ {light} ]
materials: {{ glass: {{ kd: 0.1, kt: 0.9, ior: 1.5 }} }}
objects:
  - {object}
"
    );
    parse(&yaml, "inside.yaml", None, &Limits::default()).unwrap()
}

fn point_light(p: DVec3) -> String {
    format!("{{ point: [{}, {}, {}] }}", p.x, p.y, p.z)
}

/// A convex primitive of about unit size near the origin.
fn convex_leaf() -> impl Strategy<Value = String> {
    let v = || prop::array::uniform3(-0.8..0.8f64);
    prop_oneof![
        (v(), 0.4..1.5f64)
            .prop_map(|(c, r)| format!("{{ sphere: {{ center: {c:?}, radius: {r} }} }}")),
        (v(), prop::array::uniform3(0.3..1.5f64)).prop_map(|(c, e)| {
            let lo: Vec<f64> = (0..3).map(|i| c[i] - e[i]).collect();
            let hi: Vec<f64> = (0..3).map(|i| c[i] + e[i]).collect();
            format!("{{ box: {{ min: {lo:?}, max: {hi:?} }} }}")
        }),
        (v(), 0.3..1.2f64, 0.5..2.0f64).prop_map(|(c, r, h)| format!(
            "{{ cylinder: {{ base: [{}, {}, {}], top: [{}, {}, {}], radius: {r} }} }}",
            c[0],
            c[1] - h,
            c[2],
            c[0],
            c[1] + h,
            c[2]
        )),
        (v(), 0.3..1.5f64, 0.5..2.0f64).prop_map(|(c, r, h)| format!(
            "{{ cone: {{ apex: [{}, {}, {}], base: [{}, {}, {}], radius: {r} }} }}",
            c[0],
            c[1] + h,
            c[2],
            c[0],
            c[1] - h,
            c[2]
        )),
    ]
}

/// A bounded convex solid: a primitive or the intersection of two or three, turned and moved
/// and scaled (from 1e−3 to 1e4) by a transform.
fn convex_object() -> impl Strategy<Value = String> {
    (
        prop::collection::vec(convex_leaf(), 1..4),
        -180.0..180.0f64,
        -30.0..30.0f64,
        prop::array::uniform3(-2.0..2.0f64),
        -3i32..5,
    )
        .prop_map(|(leaves, yaw, pitch, shift, scale)| {
            let geometry = match leaves.as_slice() {
                [one] => one[1..one.len() - 1].to_string(),
                many => format!("intersection: [{}]", many.join(", ")),
            };
            let k = 10f64.powi(scale);
            format!(
                "{{ name: solid, material: glass, {geometry}, transform: [ {{ rotate_y: {yaw} }}, {{ rotate_x: {pitch} }}, {{ translate: {shift:?} }}, {{ scale: {k} }} ] }}"
            )
        })
}

/// Wherever the scene says a solid hides a light from its inside, a ray from inside that meets
/// the surface has its shadow ray (as the tracer casts it) blocked by the search.
#[test]
fn a_shadow_ray_from_inside_a_convex_solid_is_blocked_wherever_the_rule_skips_it() {
    let cases = (
        convex_object(),
        prop::array::uniform3(-6.0..6.0f64),
        prop::collection::vec(
            (
                prop::array::uniform3(0.0..1.0f64),
                prop::array::uniform3(-1.0..1.0f64),
            ),
            24,
        ),
    );
    let mut runner = TestRunner::new(ProptestConfig {
        cases: 400,
        ..ProptestConfig::default()
    });
    let checked = Cell::new(0);
    let outcome = runner.run(&cases, |(object, light, starts)| {
        // The light at the solid's own scale.
        let probe = scene(&object, "{ point: [0, 100, 0] }");
        let bounds = probe.objects[0].bounds;
        if !bounds.is_finite() || bounds.is_empty() {
            return Ok(());
        }
        let size = bounds.max - bounds.min;
        let light = bounds.center() + DVec3::from_array(light) * size.max_element();
        let s = scene(&object, &point_light(light));
        let mut stats = Stats::default();
        let light_ray = Ray {
            origin: light,
            dir: DVec3::Y,
        };
        if s.contains(0, &light_ray, &mut stats) {
            prop_assert!(!s.features.hides_light_inside(0, 0));
            return Ok(());
        }
        prop_assert!(
            s.features.hides_light_inside(0, 0),
            "a convex solid with the light outside"
        );
        for (at, dir) in &starts {
            // A point inside: the middle of the solid's first segment along a line from far
            // outside through a point of its box.
            let target = bounds.min + DVec3::from_array(*at) * size;
            let Some(dir) = DVec3::from_array(*dir).try_normalize() else {
                continue;
            };
            let line = Ray {
                origin: target - dir * 10.0 * size.max_element(),
                dir,
            };
            let list = s.object_segments(0, &line, f64::NEG_INFINITY, f64::INFINITY, &mut stats);
            let Some(seg) = list.first() else { continue };
            let origin = line.at(0.5 * (seg.t_in + seg.t_out));
            // Leave it sideways, across the line.
            let across = dir.any_orthonormal_vector();
            let ray = Ray {
                origin,
                dir: (across + 0.3 * dir).normalize(),
            };
            let Some(hit) = s.nearest(&ray, 0.0, f64::INFINITY, &mut stats) else {
                continue;
            };
            let si = s.interaction(&ray, &hit);
            if !si.inside {
                // Only a sliver of a segment, where the middle is not clear of the surface.
                continue;
            }
            let to_light = light - si.point;
            let l = to_light.normalize();
            if si.normal.dot(l) <= 0.0 {
                continue;
            }
            let (from, moved) = s.offset(&si, l);
            let reach = to_light.length() - moved;
            let shadow = Ray {
                origin: from,
                dir: l,
            };
            prop_assert!(
                s.blocker(&shadow, 0.0, reach, &mut stats).is_some(),
                "the shadow ray from {from} toward {light} escaped {object}"
            );
            checked.set(checked.get() + 1);
        }
        Ok(())
    });
    if let Err(e) = outcome {
        panic!("{e}");
    }
    // Some solids are empty (disjoint operands) and half the exits face away from the light,
    // but thousands of shadow rays must have been checked: else the test looked at nothing.
    assert!(
        checked.get() > 2000,
        "only {} shadow rays checked",
        checked.get()
    );
}

#[test]
fn the_rule_holds_for_bounded_convex_solids_with_the_light_outside_only() {
    let lens = "{ name: lens, material: glass, intersection: [ { sphere: { center: [0, 0, -1.2], radius: 1.6 } }, { sphere: { center: [0, 0, 1.2], radius: 1.6 } } ], transform: [ { rotate_y: 30 } ] }";
    let ball = "{ name: ball, material: glass, sphere: { center: [0, 0, 0], radius: 1 } }";
    let outside = point_light(DVec3::new(0.0, 5.0, 0.0));
    let cases = [
        (ball, outside.clone(), true),
        (lens, outside.clone(), true),
        (ball, "{ direction: [0, -1, 0] }".to_string(), true),
        // In the lens's box but outside the lens (its rim is 1.06 from the axis).
        (lens, point_light(DVec3::new(0.0, 1.1, 0.0)), true),
        // The light inside: a shadow ray from inside may reach it.
        (ball, point_light(DVec3::new(0.2, 0.1, 0.0)), false),
        (lens, point_light(DVec3::ZERO), false),
        // Not convex: the way to the light may leave and come back.
        (
            "{ name: u, material: glass, union: [ { sphere: { center: [-1, 0, 0], radius: 1.2 } }, { sphere: { center: [1, 0, 0], radius: 1.2 } } ] }",
            outside.clone(),
            false,
        ),
        (
            "{ name: d, material: glass, difference: [ { sphere: { center: [0, 0, 0], radius: 2 } }, { sphere: { center: [0, 0, 0], radius: 1 } } ] }",
            outside.clone(),
            false,
        ),
        // Unbounded: a ray inside a half-space may never leave it.
        (
            "{ name: floor, material: glass, plane: { point: [0, 0, 0], normal: [0, 1, 0] } }",
            outside.clone(),
            false,
        ),
        // An area light that reaches into the solid's box.
        (
            ball,
            "{ rect: { corner: [-2, 0.5, -2], u: [4, 0, 0], v: [0, 0, 4] } }".to_string(),
            false,
        ),
        (
            ball,
            "{ rect: { corner: [-2, 3, -2], u: [4, 0, 0], v: [0, 0, 4] } }".to_string(),
            true,
        ),
    ];
    for (object, light, expected) in cases {
        let s = scene(object, &light);
        assert_eq!(
            s.features.hides_light_inside(0, 0),
            expected,
            "{object} under {light}"
        );
    }
}

/// The rule is visible in the stats: a glass ball's inside hits cast no shadow rays toward a
/// light outside. (That each skipped ray would have been blocked is the proptest above.)
#[test]
fn inside_hits_of_a_glass_ball_cast_no_shadow_rays() {
    let s = scene(
        "{ name: ball, material: glass, sphere: { center: [0, 0, 0], radius: 3 } }",
        "{ point: [4, 10, -20] }",
    );
    let mut tracer = raytree::trace::Tracer::new(&s);
    for k in 0..50 {
        let y = -2.5 + 0.1 * k as f64;
        let ray = Ray {
            origin: DVec3::new(0.3, y, -30.0),
            dir: DVec3::Z,
        };
        tracer.radiance(&ray);
    }
    let stats = tracer.stats;
    assert!(stats.shadow_skipped_inside > 0, "{stats:?}");
}
