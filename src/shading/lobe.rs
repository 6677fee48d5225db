//! Lobes of glossy reflection and frosted refraction: how sampled rays spread about the
//! principal (mirror or refracted) direction.
//!
//! - `Normal`: seed 000's "normally distributed about the centre": the angle θ between a
//!   sampled ray and the principal direction is the length of a 2-D normal deviate of standard
//!   deviation σ (so θ is Rayleigh-distributed), its azimuth φ uniform.
//!   Density over solid angle: p(ω) = θ/σ² · e^(−θ²/2σ²) / (2π sin θ).
//! - `Phong`: p(ω) = (n + 1)/(2π) · cosⁿ θ, drawn by cos θ = u^(1/(n+1)).

use std::f64::consts::PI;

use glam::DVec3;

use crate::sampling::{basis, sin_cos};

/// The distribution of sampled directions about the principal one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LobeShape {
    /// Seed 000's normal spread: the angle to the principal direction is Rayleigh-distributed.
    Normal {
        /// σ, the standard deviation of the angle, in radians.
        sigma: f64,
    },
    /// Density (n + 1)/(2π)·cosⁿ θ about the principal direction.
    Phong {
        /// The Phong exponent n.
        exponent: f64,
    },
}

/// How rays spread about a principal direction, and how many a surface sends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lobe {
    /// How the sampled directions spread.
    pub shape: LobeShape,
    /// How many rays the surface sends in place of the single mirror or refracted ray.
    pub samples: u32,
}

impl LobeShape {
    /// For display: "normal σ = 4°", "phong n = 200".
    pub fn describe(self) -> String {
        match self {
            LobeShape::Normal { sigma } => format!("normal σ = {}°", sigma.to_degrees()),
            LobeShape::Phong { exponent } => format!("phong n = {exponent}"),
        }
    }
}

/// A unit direction drawn from the lobe about the unit `axis`, from two uniform numbers.
pub fn sample(shape: LobeShape, axis: DVec3, u1: f64, u2: f64) -> DVec3 {
    let cos_theta = match shape {
        LobeShape::Normal { sigma } => {
            // Inverse of the Rayleigh distribution function 1 − e^(−θ²/2σ²).
            let theta = (sigma * (-2.0 * (1.0 - u1).ln()).sqrt()).min(PI);
            theta.cos()
        }
        LobeShape::Phong { exponent } => u1.powf(1.0 / (exponent + 1.0)),
    };
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let (sin_phi, cos_phi) = sin_cos(2.0 * PI * u2);
    let (t, b) = basis(axis);
    (sin_theta * cos_phi * t + sin_theta * sin_phi * b + cos_theta * axis).normalize()
}

/// A ray drawn from the lobe about `principal`, kept on the side of the surface (normal n) that
/// `principal` leaves by: a ray drawn into the wrong side is mirrored back across the surface,
/// so a grazing lobe keeps its energy.
pub fn spread(shape: LobeShape, principal: DVec3, n: DVec3, u1: f64, u2: f64) -> DVec3 {
    let side = principal.dot(n).signum();
    let dir = sample(shape, principal, u1, u2);
    if dir.dot(n) * side <= 0.0 {
        dir - 2.0 * dir.dot(n) * n
    } else {
        dir
    }
}

/// The density of `sample` over solid angle at direction w.
pub fn pdf(shape: LobeShape, axis: DVec3, w: DVec3) -> f64 {
    let cos_theta = axis.dot(w).clamp(-1.0, 1.0);
    match shape {
        LobeShape::Normal { sigma } => {
            let theta = cos_theta.acos();
            let s2 = sigma * sigma;
            let sin_theta = theta.sin();
            if sin_theta <= 0.0 {
                // The limit θ → 0: θ / sin θ → 1.
                return 1.0 / (2.0 * PI * s2);
            }
            theta / s2 * (-theta * theta / (2.0 * s2)).exp() / (2.0 * PI * sin_theta)
        }
        LobeShape::Phong { exponent } => {
            (exponent + 1.0) / (2.0 * PI) * cos_theta.max(0.0).powf(exponent)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng;

    /// Chi-square goodness of fit, the way pbrt-v4 and Mitsuba test their samplers: bin the
    /// sampled directions in (θ, φ) and compare with the density integrated over each bin
    /// (numerically, independently of the sampling code).
    fn chi_square(drawn: LobeShape, judged: LobeShape, theta_max: f64) -> (f64, usize) {
        let shape = judged;
        let axis = DVec3::new(-0.2, 0.9, 0.4).normalize();
        let (t, b) = basis(axis);
        let (nt, np, samples) = (16usize, 8usize, 200_000usize);
        let mut counts = vec![0f64; nt * np];
        let mut rng = Rng::for_pixel(11, 3, 4);
        let mut outside = 0.0;
        for _ in 0..samples {
            let w = sample(drawn, axis, rng.uniform(), rng.uniform());
            let theta = axis.dot(w).clamp(-1.0, 1.0).acos();
            if theta >= theta_max {
                outside += 1.0;
                continue;
            }
            let phi = w.dot(b).atan2(w.dot(t)).rem_euclid(2.0 * PI);
            let i = ((theta / theta_max) * nt as f64) as usize;
            let j = ((phi / (2.0 * PI)) * np as f64) as usize;
            counts[i.min(nt - 1) * np + j.min(np - 1)] += 1.0;
        }
        // Expected counts: ∫∫ p(ω) sin θ dθ dφ over each bin, by Simpson's rule in θ.
        let mut chi2 = 0.0;
        let mut inside = 0.0;
        for i in 0..nt {
            let (a, z) = (
                i as f64 * theta_max / nt as f64,
                (i + 1) as f64 * theta_max / nt as f64,
            );
            let steps = 64;
            let h = (z - a) / steps as f64;
            let f = |th: f64| {
                let w = th.cos() * axis + th.sin() * t;
                pdf(shape, axis, w) * th.sin()
            };
            let mut integral = f(a) + f(z);
            for k in 1..steps {
                integral += f(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
            }
            integral *= h / 3.0;
            let per_bin = integral * 2.0 * PI / np as f64;
            for j in 0..np {
                let expected = per_bin * samples as f64;
                inside += per_bin;
                chi2 += (counts[i * np + j] - expected).powi(2) / expected;
            }
        }
        // The tail beyond θ_max is one more bin.
        let expected_out = (1.0 - inside) * samples as f64;
        if expected_out > 5.0 {
            chi2 += (outside - expected_out).powi(2) / expected_out;
        }
        (chi2, nt * np)
    }

    #[test]
    fn normal_lobe_passes_chi_square() {
        let sigma = 8f64.to_radians();
        let shape = LobeShape::Normal { sigma };
        let (chi2, bins) = chi_square(shape, shape, 4.0 * sigma);
        // 128 bins (+ tail) → ~128 degrees of freedom: the 99.9 % point is about 180.
        assert!(chi2 < 180.0, "chi² = {chi2} over {bins} bins");
    }

    #[test]
    fn phong_lobe_passes_chi_square() {
        let exponent = 50.0;
        // cos^50 θ has fallen to 1e-3 by θ ≈ 0.53 rad.
        let shape = LobeShape::Phong { exponent };
        let (chi2, bins) = chi_square(shape, shape, 0.6);
        assert!(chi2 < 180.0, "chi² = {chi2} over {bins} bins");
    }

    #[test]
    fn a_slightly_wrong_density_fails_the_test() {
        // Samples judged against lobes 10 % wider or a smaller exponent must be rejected:
        // the test has the power to see a small error.
        let sigma = 8f64.to_radians();
        let (chi2, _) = chi_square(
            LobeShape::Normal { sigma },
            LobeShape::Normal { sigma: 1.1 * sigma },
            4.0 * sigma,
        );
        assert!(chi2 > 1000.0, "chi² = {chi2}");
        let (chi2, _) = chi_square(
            LobeShape::Phong { exponent: 50.0 },
            LobeShape::Phong { exponent: 45.0 },
            0.6,
        );
        assert!(chi2 > 300.0, "chi² = {chi2}");
    }

    #[test]
    fn densities_integrate_to_one() {
        for shape in [
            LobeShape::Normal {
                sigma: 5f64.to_radians(),
            },
            LobeShape::Phong { exponent: 20.0 },
        ] {
            let axis = DVec3::Z;
            let steps = 20_000;
            let h = PI / steps as f64;
            let total: f64 = (0..steps)
                .map(|k| {
                    let th = (k as f64 + 0.5) * h;
                    pdf(shape, axis, DVec3::new(th.sin(), 0.0, th.cos())) * th.sin() * h
                })
                .sum::<f64>()
                * 2.0
                * PI;
            assert!((total - 1.0).abs() < 1e-3, "{shape:?}: {total}");
        }
    }
}
