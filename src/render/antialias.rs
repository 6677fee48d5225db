//! Antialiasing: where inside a pixel the primary rays go, and how their values are averaged
//! into the pixel (seed 004: "sample point is typically the centre of a pixel, but
//! alternatively supersample pixels").
//!
//! - `Grid`: n × n rays on a regular grid (a non-square count uses the R2 sequence).
//! - `Jittered`: the same strata, each ray at a random point inside its cell (stratified).
//! - `Adaptive`: rays at the pixel's corners; a square whose corners differ by more than a
//!   threshold is split into four, recursively, as POV-Ray's adaptive antialiasing does.

use glam::{DVec2, DVec3};

use crate::sampling::Rng;

/// Sample positions inside a pixel, in [0, 1)². A square count is a regular n × n grid (seed
/// 004's supersampling); any other count uses the R2 low-discrepancy sequence.
pub fn grid_offsets(spp: u32) -> Vec<DVec2> {
    let n = (spp as f64).sqrt().round() as u32;
    if n * n == spp {
        let step = 1.0 / n as f64;
        (0..spp)
            .map(|k| DVec2::new(((k % n) as f64 + 0.5) * step, ((k / n) as f64 + 0.5) * step))
            .collect()
    } else {
        // Roberts' R2 sequence: the plastic number's powers.
        let g = 1.324_717_957_244_746;
        let (a1, a2) = (1.0 / g, 1.0 / (g * g));
        (0..spp)
            .map(|k| DVec2::new((0.5 + a1 * k as f64).fract(), (0.5 + a2 * k as f64).fract()))
            .collect()
    }
}

/// A grid offset moved to a random point of its cell (stratified sampling); `cell` is the
/// side of a cell, 1/⌈√spp⌉.
pub fn jitter(o: DVec2, cell: f64, rng: &mut Rng) -> DVec2 {
    let jx = (o.x + (rng.uniform() - 0.5) * cell).clamp(0.0, 0.999_999);
    let jy = (o.y + (rng.uniform() - 0.5) * cell).clamp(0.0, 0.999_999);
    DVec2::new(jx, jy)
}

/// The side of a jitter cell for `spp` samples.
pub fn cell(spp: usize) -> f64 {
    1.0 / (spp as f64).sqrt().ceil()
}

/// The Gaussian filter's radius in pixels: a sample reaches pixels whose centres lie closer
/// than this along both axes.
pub const GAUSS_RADIUS: f64 = 2.0;
const GAUSS_SIGMA: f64 = 0.5;

/// g(r) = exp(−r²/2σ²) = e⁻⁸ at the radius, which f subtracts so that it reaches 0 there.
const GAUSS_AT_RADIUS: f64 = 0.000_335_462_627_902_511_85;

/// f(x) = g(x) − g(r) of the Gaussian filter, g(x) = exp(−x²/2σ²); 0 at and beyond the
/// radius.
pub fn gaussian_weight(x: f64) -> f64 {
    if x.abs() >= GAUSS_RADIUS {
        return 0.0;
    }
    (-x * x / (2.0 * GAUSS_SIGMA * GAUSS_SIGMA)).exp() - GAUSS_AT_RADIUS
}

/// exp(−2a) for a = 1/2σ²: the ratio of successive steps of `gaussian_weights`.
const GAUSS_STEP_RATIO: f64 = 0.018_315_638_888_734_18;

/// f(x₀), f(x₀ + 1), …, f(x₀ + N − 1): the weights of a row of pixel centres one apart, as a
/// sample splats them. Two exponentials instead of N: with a = 1/2σ²,
/// g(x + 1) = g(x) · exp(−a(2x + 1)), and each step's factor is the last one's times exp(−2a).
/// Equal to `gaussian_weight` but for rounding (a few ulps).
pub fn gaussian_weights<const N: usize>(x0: f64) -> [f64; N] {
    let a = 1.0 / (2.0 * GAUSS_SIGMA * GAUSS_SIGMA);
    let mut g = (-a * x0 * x0).exp();
    let mut step = (-a * (2.0 * x0 + 1.0)).exp();
    let mut weights = [0.0; N];
    for (k, w) in weights.iter_mut().enumerate() {
        if (x0 + k as f64).abs() < GAUSS_RADIUS {
            *w = (g - GAUSS_AT_RADIUS).max(0.0);
        }
        g *= step;
        step *= GAUSS_STEP_RATIO;
    }
    weights
}

/// How many times a pixel may be halved: the finest squares are 2^levels to a side, the
/// power of two at or above √spp (16 samples → 4 × 4 → 2 levels).
pub fn adaptive_levels(spp: u32) -> u32 {
    let side = (spp.max(1) as f64).sqrt().ceil() as u32;
    side.next_power_of_two().trailing_zeros()
}

/// The colour difference POV-Ray compares with its threshold: Σ |Δ| over r, g, b of the
/// displayed (clamped) values.
pub fn difference(a: DVec3, b: DVec3) -> f64 {
    let clamp = |c: DVec3| c.clamp(DVec3::ZERO, DVec3::ONE);
    let d = (clamp(a) - clamp(b)).abs();
    d.x + d.y + d.z
}

/// A square of a pixel under adaptive antialiasing: (u0, v0) its top-left corner in the pixel,
/// `side` its size, `level` how many times its pixel was halved to reach it.
#[derive(Clone, Copy, Debug)]
pub struct Square {
    /// Left edge of the square, as a fraction of the pixel's width.
    pub u0: f64,
    /// Top edge of the square, as a fraction of the pixel's height.
    pub v0: f64,
    /// Side of the square, as a fraction of the pixel's side (1 for the whole pixel).
    pub side: f64,
    /// How many times the pixel was halved to reach it (0 for the pixel).
    pub level: u32,
    /// Top-left, top-right, bottom-left, bottom-right.
    pub corners: [DVec3; 4],
    /// The largest difference between two of its corners.
    pub largest: f64,
}

/// What adaptive antialiasing did with one square, as it happens (the lessons explain a pixel
/// from these; the renderer ignores them).
#[derive(Clone, Copy, Debug)]
pub enum Step {
    /// Its corners agree (or it is as small as allowed): its value is their mean.
    Kept {
        /// The square kept.
        square: Square,
        /// True when it was kept only because it reached the smallest size, its corners still
        /// differing.
        smallest: bool,
        /// The mean of its corners.
        value: DVec3,
    },
    /// Its corners differ: five new rays (top, left, centre, right and bottom midpoints).
    Split {
        /// The square split.
        square: Square,
        /// The values of the five new rays, in the order above.
        new: [DVec3; 5],
    },
    /// A split square's value: the mean of its quarters.
    Merged {
        /// The square merged.
        square: Square,
        /// The values of its four quarters (top-left, top-right, bottom-left, bottom-right).
        quarters: [DVec3; 4],
        /// The mean of the quarters.
        value: DVec3,
    },
}

/// Adaptive supersampling of one pixel. `corners` are the values at the pixel's corners
/// (top-left, top-right, bottom-left, bottom-right), shared with the neighbouring pixels;
/// `sample(u, v)` traces a ray through the point (u, v) ∈ [0, 1]² of the pixel. Returns the
/// pixel's value and the number of squares split.
pub fn adaptive_pixel(
    corners: [DVec3; 4],
    levels: u32,
    threshold: f64,
    sample: &mut dyn FnMut(f64, f64) -> DVec3,
) -> (DVec3, u32) {
    adaptive_pixel_observed(corners, levels, threshold, sample, &mut |_| {})
}

/// `adaptive_pixel`, telling `observe` every step.
pub fn adaptive_pixel_observed(
    corners: [DVec3; 4],
    levels: u32,
    threshold: f64,
    sample: &mut dyn FnMut(f64, f64) -> DVec3,
    observe: &mut dyn FnMut(&Step),
) -> (DVec3, u32) {
    let mut splits = 0;
    let mut walk = Walk {
        levels,
        threshold,
        sample,
        observe,
        splits: &mut splits,
    };
    let value = walk.square(corners, (0.0, 0.0, 1.0), 0);
    (value, splits)
}

struct Walk<'a> {
    levels: u32,
    threshold: f64,
    sample: &'a mut dyn FnMut(f64, f64) -> DVec3,
    observe: &'a mut dyn FnMut(&Step),
    splits: &'a mut u32,
}

impl Walk<'_> {
    /// One square (u0, v0, side) of a pixel: the mean of its corners if they agree, otherwise
    /// the mean of its four quarters.
    fn square(&mut self, c: [DVec3; 4], (u0, v0, side): (f64, f64, f64), level: u32) -> DVec3 {
        let [tl, tr, bl, br] = c;
        let largest = [(tl, tr), (tl, bl), (tr, br), (bl, br), (tl, br), (tr, bl)]
            .iter()
            .map(|&(a, b)| difference(a, b))
            .fold(0.0, f64::max);
        let square = Square {
            u0,
            v0,
            side,
            level,
            corners: c,
            largest,
        };
        if level >= self.levels || largest <= self.threshold {
            let value = (tl + tr + bl + br) / 4.0;
            (self.observe)(&Step::Kept {
                square,
                smallest: largest > self.threshold,
                value,
            });
            return value;
        }
        *self.splits += 1;
        let h = side / 2.0;
        let top = (self.sample)(u0 + h, v0);
        let left = (self.sample)(u0, v0 + h);
        let centre = (self.sample)(u0 + h, v0 + h);
        let right = (self.sample)(u0 + side, v0 + h);
        let bottom = (self.sample)(u0 + h, v0 + side);
        (self.observe)(&Step::Split {
            square,
            new: [top, left, centre, right, bottom],
        });
        let quarters = [
            ([tl, top, left, centre], (u0, v0)),
            ([top, tr, centre, right], (u0 + h, v0)),
            ([left, centre, bl, bottom], (u0, v0 + h)),
            ([centre, right, bottom, br], (u0 + h, v0 + h)),
        ]
        .map(|(cs, (u, v))| self.square(cs, (u, v, h), level + 1));
        let value = quarters.iter().sum::<DVec3>() / 4.0;
        (self.observe)(&Step::Merged {
            square,
            quarters,
            value,
        });
        value
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_follow_the_sample_count() {
        assert_eq!(adaptive_levels(1), 0);
        assert_eq!(adaptive_levels(4), 1);
        assert_eq!(adaptive_levels(9), 2);
        assert_eq!(adaptive_levels(16), 2);
        assert_eq!(adaptive_levels(64), 3);
    }

    #[test]
    fn a_flat_pixel_costs_only_its_corners() {
        let mut calls = 0;
        let (v, splits) = adaptive_pixel([DVec3::splat(0.5); 4], 3, 0.1, &mut |_, _| {
            calls += 1;
            DVec3::ZERO
        });
        assert_eq!((v, splits, calls), (DVec3::splat(0.5), 0, 0));
    }

    /// A vertical edge at u = 0.3 (white left of it): the split squares follow the edge, and
    /// the value converges to the covered fraction 0.3 as the levels grow.
    #[test]
    fn an_edge_is_refined_where_it_is() {
        let edge = |u: f64, _v: f64| if u < 0.3 { DVec3::ONE } else { DVec3::ZERO };
        let corners = [
            edge(0.0, 0.0),
            edge(1.0, 0.0),
            edge(0.0, 1.0),
            edge(1.0, 1.0),
        ];
        let mut errors = vec![];
        for levels in 1..=6 {
            let mut calls = 0;
            let (v, splits) = adaptive_pixel(corners, levels, 0.1, &mut |u, v| {
                calls += 1;
                edge(u, v)
            });
            // Only the column of squares that holds the edge is split: 2^k squares at level k.
            assert_eq!(splits, (1 << levels) - 1, "levels {levels}");
            assert!(calls < 5 * (1 << levels), "levels {levels}: {calls} rays");
            errors.push((v.x - 0.3).abs());
        }
        assert!(errors[5] < 0.02, "{errors:?}");
        assert!(errors[5] < errors[0], "{errors:?}");
    }

    #[test]
    fn the_gaussian_filter_is_mitsubas() {
        let g = |x: f64| (-x * x / (2.0 * GAUSS_SIGMA * GAUSS_SIGMA)).exp();
        assert_eq!(GAUSS_AT_RADIUS, g(GAUSS_RADIUS));
        assert_eq!(gaussian_weight(2.0), 0.0);
        assert_eq!(gaussian_weight(-2.5), 0.0);
        // e^0 − e^(−8) at the centre; e^(−0.5) − e^(−8) one σ out.
        assert!((gaussian_weight(0.0) - (1.0 - (-8f64).exp())).abs() < 1e-15);
        assert!((gaussian_weight(0.5) - ((-0.5f64).exp() - (-8f64).exp())).abs() < 1e-15);
    }

    #[test]
    fn a_row_of_weights_is_the_filter_at_each_centre() {
        let a = 1.0 / (2.0 * GAUSS_SIGMA * GAUSS_SIGMA);
        assert_eq!(GAUSS_STEP_RATIO, (-2.0 * a).exp());
        let mut rng = Rng::for_pixel(4, 5, 6);
        for _ in 0..100_000 {
            let x0 = -2.5 + 3.0 * rng.uniform();
            let row: [f64; 5] = gaussian_weights(x0);
            for (k, w) in row.iter().enumerate() {
                let exact = gaussian_weight(x0 + k as f64);
                assert!(
                    (w - exact).abs() <= 16.0 * f64::EPSILON,
                    "x0 {x0}, k {k}: {w} {exact}"
                );
            }
        }
        // At and beyond the radius on either side nothing, and something inside it.
        let left: [f64; 5] = gaussian_weights(-4.0);
        assert_eq!(left[..3], [0.0, 0.0, 0.0]);
        assert!(left[3] > 0.0 && left[4] > 0.0);
        let right: [f64; 5] = gaussian_weights(0.0);
        assert!(right[0] > 0.0 && right[1] > 0.0);
        assert_eq!(right[2..], [0.0, 0.0, 0.0]);
    }

    #[test]
    fn jittered_samples_stay_in_their_cells() {
        let grid = grid_offsets(16);
        let mut rng = Rng::for_pixel(1, 2, 3);
        for o in &grid {
            let j = jitter(*o, cell(16), &mut rng);
            assert!((o.x - j.x).abs() <= 0.125 && (o.y - j.y).abs() <= 0.125);
        }
    }
}
