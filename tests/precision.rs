//! How far from the origin can a scene be before floating point breaks it? raytree's own shadow
//! rays, with a fixed bias, on a floor moved ever further out; beside them the same computation
//! written in f32, which is what an f32 renderer with the usual fixed epsilon would do.
//! (`cargo test --test precision -- --nocapture` prints the table quoted in the README.)

mod common;

use raytree::render::{render_simple, RenderOptions};

/// The fixed bias both sides use: a typical f32 renderer's epsilon.
const EPS: f64 = 1e-4;

/// The fraction of raytree's floor pixels in their own shadow (acne: the shadow ray toward a
/// light straight above the floor starts below it and is blocked by it). The floor is tilted
/// (normal (0.6, 0.8, 0)), so that its points are not exact in any coordinate, and seen from 10
/// above along its normal. It is lit with kd = 1 and no ambient term, so a pixel is 0 exactly
/// when its shadow ray was blocked: nothing else is in the scene.
fn raytree_acne(offset: f64) -> f64 {
    let o = offset;
    let n = [0.6, 0.8, 0.0];
    let at = |k: f64| format!("[{:e}, {:e}, {o:e}]", o + k * n[0], o + k * n[1]);
    let yaml = format!(
        "camera: {{ eye: {}, look_at: {}, up: [0, 0, 1], fov: 90, width: 64, height: 64 }}
shadow_bias: {EPS:e}
lights: [ {{ point: {} }} ]
materials: {{ floor: {{ kd: 1 }} }}
objects:
  - {{ name: floor, plane: {{ point: {}, normal: [0.6, 0.8, 0] }}, material: floor }}
",
        at(10.0),
        at(0.0),
        at(100.0),
        at(0.0),
    );
    let scene = common::scene(&yaml);
    let (image, _) = render_simple(&scene, RenderOptions::of(&scene));
    let dark = image.pixels.iter().filter(|p| p.x == 0.0).count();
    dark as f64 / image.pixels.len() as f64
}

/// The same floor in f32, written out: the point on the floor, lifted by the epsilon, is
/// still on or below the floor when the spacing of f32 numbers there exceeds the epsilon.
fn f32_acne(offset: f64) -> f64 {
    let (d0, eps) = (offset as f32, EPS as f32);
    let mut bad = 0;
    for j in 0..64 {
        for i in 0..64 {
            let o = [d0, d0 + 10.0, d0];
            let d = [(i as f32 - 31.5) / 32.0, -1.0f32, (j as f32 - 31.5) / 32.0];
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let dy = d[1] / len;
            let t = (d0 - o[1]) / dy;
            let py = o[1] + t * dy;
            if py + eps - d0 <= 0.0 {
                bad += 1;
            }
        }
    }
    bad as f64 / 4096.0
}

#[test]
fn raytree_in_f64_keeps_a_fixed_bias_clean_until_the_spacing_of_doubles_exceeds_it() {
    println!("offset     f32 acne   raytree (f64) acne   (fixed bias {EPS})");
    let mut first = None;
    for k in 0..=14 {
        let offset = 10f64.powi(k);
        let (a, b) = (f32_acne(offset), raytree_acne(offset));
        println!("1e{k:<7} {:>8.1}%  {:>8.1}%", 100.0 * a, 100.0 * b);
        if b > 0.01 && first.is_none() {
            first = Some(k);
        }
    }
    // Doubles near x are x·2⁻⁵² apart: the bias 1e−4 is first smaller than that spacing for
    // x ≈ 4.5·10¹¹, so the first offset with acne is 10¹² (or, if the rounding of that one
    // happens to stay on the right side, 10¹³); none before.
    assert!(
        matches!(first, Some(12..=13)),
        "raytree first shows acne at 1e{first:?}"
    );
    // From there on, the hit points' rounding errors (up or down, about equally) exceed the
    // bias: a large share of the floor is in its own shadow.
    assert!(raytree_acne(1e14) > 0.25);
}
