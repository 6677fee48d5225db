//! ⌊x⌋ without a library call. On an x86-64 without SSE4.1's rounding instruction (the
//! baseline raytree is built for) `f64::floor` is a call into a software routine, which costs a
//! checker or a texture lookup more than its own arithmetic does.

/// ⌊x⌋, bit for bit as `f64::floor` gives it. Below 2⁵² in size, x ± 2⁵² (the sign of x) has no
/// bits left for a fraction, so the sum is rounded to a whole number, and subtracting 2⁵² again
/// gives x rounded to the nearest whole number, exactly; ⌊x⌋ is that, or one less where that is
/// above x. A nearest of zero takes the sign of x, so that ⌊−0⌋ = −0 as in `f64::floor`. From
/// 2⁵² on every f64 is whole, ±∞ are their own floor, and NaN stays NaN.
#[inline]
pub fn floor(x: f64) -> f64 {
    const NO_FRACTION: f64 = 4_503_599_627_370_496.0; // 2⁵²
    if cfg!(target_feature = "sse4.1") {
        return x.floor();
    }
    if x.abs() >= NO_FRACTION {
        return x;
    }
    let m = NO_FRACTION.copysign(x);
    let nearest = ((x + m) - m).copysign(x);
    nearest - if nearest > x { 1.0 } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ⌊x⌋ by its definition, the whole number r with r ≤ x < r + 1, at fractions either side
    /// of zero, next to 2⁵² where f64s stop having fractions, and past it; and the same bits as
    /// `f64::floor` (the sign of a zero included) over sweeps of steps of 1/8 and of 0.1 (which
    /// are not exact in binary) and at the values next to each whole number.
    #[test]
    fn floor_is_the_whole_number_at_or_below() {
        let big = 2f64.powi(52);
        for (x, want) in [
            (2.5, 2.0),
            (-2.5, -3.0),
            (-2.0, -2.0),
            (0.0, 0.0),
            (1e-300, 0.0),
            (-1e-300, -1.0),
            (1.0 - f64::EPSILON, 0.0),
            (-(big - 0.5), -big),
            (big - 0.5, big - 1.0),
            (-big, -big),
            (big + 1.0, big + 1.0),
            (-1e300, -1e300),
            (f64::INFINITY, f64::INFINITY),
            (f64::NEG_INFINITY, f64::NEG_INFINITY),
        ] {
            assert_eq!(floor(x), want, "⌊{x}⌋");
        }
        assert!(floor(f64::NAN).is_nan());
        let same_bits = |x: f64| assert_eq!(floor(x).to_bits(), x.floor().to_bits(), "⌊{x:e}⌋");
        for i in -400..=400 {
            for x in [i as f64 / 8.0, i as f64 * 0.1] {
                same_bits(x);
            }
            let whole = i as f64;
            same_bits(whole.next_down());
            same_bits(whole.next_up());
        }
        for x in [-0.0, -0.25, -0.5, -0.75, 0.25, 0.5, 0.75] {
            same_bits(x);
        }
    }
}
