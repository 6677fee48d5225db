//! How far from the origin can a scene be before floating point breaks it? The same shadow-ray
//! computation in f32 and in f64, with the fixed epsilon an f32 renderer typically uses.
//! (`cargo test --test precision -- --nocapture` prints the table quoted in the README.)

/// The fraction of floor pixels whose shadow ray starts below the floor (self-shadowing:
/// acne), for a floor at height `offset` seen from 10 units above, the whole scene moved
/// `offset` from the origin along every axis, shadow rays lifted by `eps`.
macro_rules! acne_fraction {
    ($name:ident, $f:ty) => {
        fn $name(offset: f64, eps: f64) -> f64 {
            let d0 = offset as $f;
            let eps = eps as $f;
            let (mut bad, mut total) = (0u32, 0u32);
            for j in 0..64 {
                for i in 0..64 {
                    // Eye 10 above the floor, looking down through a 2 × 2 window.
                    let o = [d0, d0 + 10.0, d0];
                    let d = [(i as $f - 31.5) / 32.0, -1.0 as $f, (j as $f - 31.5) / 32.0];
                    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                    let d = [d[0] / len, d[1] / len, d[2] / len];
                    // Plane y = d0: t = (d0 − o.y)/d.y, p = o + t·d, shadow ray from p + eps·n.
                    let t = (d0 - o[1]) / d[1];
                    let py = o[1] + t * d[1];
                    let start = py + eps;
                    // The shadow ray toward a light above re-hits the floor when it starts
                    // on or below it.
                    if start - d0 <= 0.0 {
                        bad += 1;
                    }
                    total += 1;
                }
            }
            bad as f64 / total as f64
        }
    };
}

acne_fraction!(acne_f32, f32);
acne_fraction!(acne_f64, f64);

#[test]
fn f32_breaks_thousands_of_units_out_f64_does_not() {
    let eps = 1e-4;
    println!("offset     f32 acne   f64 acne   (fixed epsilon {eps})");
    let mut first_f32 = None;
    let mut first_f64 = None;
    for k in 0..=13 {
        let offset = 10f64.powi(k);
        let (a, b) = (acne_f32(offset, eps), acne_f64(offset, eps));
        println!("1e{k:<7} {:>8.1}%  {:>8.1}%", 100.0 * a, 100.0 * b);
        if a > 0.01 && first_f32.is_none() {
            first_f32 = Some(k);
        }
        if b > 0.01 && first_f64.is_none() {
            first_f64 = Some(k);
        }
    }
    // f32 has 24 bits: at 10^4 the spacing of floats (≈ 0.001) exceeds the epsilon.
    assert!(
        matches!(first_f32, Some(3..=4)),
        "f32 first fails at 1e{first_f32:?}"
    );
    // f64 has 53 bits: the same epsilon lasts until about 10^12.
    assert!(
        matches!(first_f64, Some(11..=13)),
        "f64 first fails at 1e{first_f64:?}"
    );
}
