//! Random numbers and the sampling routines of the Monte Carlo integrators. Every pixel gets
//! its own generator seeded from (seed, x, y), so images do not depend on the thread count;
//! the path tracer's samples draw from well-spread sample points instead (`sobol`).

use std::f64::consts::PI;

use glam::DVec3;
use rand::{Rng as _, SeedableRng};
use rand_pcg::Pcg64Mcg;

pub mod sobol;

pub use sobol::{pixel_key, SamplePoint};

/// The random number generator of a pixel's samples: PCG-64, seeded per pixel so that images do not
/// depend on thread scheduling.
#[derive(Clone, Debug)]
pub struct Rng(Pcg64Mcg);

impl Rng {
    /// The generator of pixel (x, y) for a given seed.
    pub fn for_pixel(seed: u64, x: u32, y: u32) -> Rng {
        Rng(Pcg64Mcg::seed_from_u64(pixel_key(seed, x, y)))
    }

    /// Uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        self.0.random::<f64>()
    }
}

/// An orthonormal basis (t, b, n) around a unit normal (Duff et al. 2017).
pub fn basis(n: DVec3) -> (DVec3, DVec3) {
    let sign = 1f64.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        DVec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        DVec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

/// A direction on the hemisphere around n with density cos θ / π (Malley: a uniform point on
/// the unit disc, lifted onto the hemisphere).
pub fn cosine_hemisphere(n: DVec3, u1: f64, u2: f64) -> DVec3 {
    let r = u1.sqrt();
    let phi = 2.0 * PI * u2;
    let (sin_phi, cos_phi) = sin_cos(phi);
    let (t, b) = basis(n);
    let z = (1.0 - u1).max(0.0).sqrt();
    (r * cos_phi * t + r * sin_phi * b + z * n).normalize()
}

/// (sin x, cos x) for the angles the samplers draw, from the `libm` crate (musl's routines,
/// in Rust) rather than the system's C library: the same bits on every machine, and quicker
/// than glibc's `sincos` here (a diffuse bounce takes one).
pub fn sin_cos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

/// The density of `cosine_hemisphere` for direction w.
pub fn cosine_pdf(n: DVec3, w: DVec3) -> f64 {
    n.dot(w).max(0.0) / PI
}

/// A point on the rectangle corner + a·u + b·v, uniform in area.
pub fn rectangle(corner: DVec3, u: DVec3, v: DVec3, u1: f64, u2: f64) -> DVec3 {
    corner + u1 * u + u2 * v
}

/// Pearson's χ² of histogram counts against equal expected counts (the samplers' tests bin
/// so that every bin is equally likely).
#[cfg(test)]
pub(crate) fn chi_square_uniform(counts: &[f64]) -> f64 {
    let expected = counts.iter().sum::<f64>() / counts.len() as f64;
    counts
        .iter()
        .map(|c| (c - expected).powi(2) / expected)
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `sin_cos` is (sin x, cos x) in that order, within a relative 2ε of the C library's,
    /// over the angles the samplers draw: the quadrant boundaries, where one of the two is
    /// zero, and anywhere in between.
    #[test]
    fn sin_cos_is_the_sine_and_the_cosine() {
        let quarter = std::f64::consts::FRAC_PI_2;
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        let mut rng = Rng::for_pixel(3, 1, 4);
        let angles = (0..=4)
            .map(|k| k as f64 * quarter)
            .chain((0..100_000).map(|_| 2.0 * PI * rng.uniform()));
        for x in angles {
            let (s, c) = sin_cos(x);
            let close = |a: f64, b: f64| (a - b).abs() <= 2.0 * f64::EPSILON * b.abs().max(1e-16);
            assert!(close(s, x.sin()) && close(c, x.cos()), "x {x}: {s} {c}");
        }
        // A quarter turn: the sine is 1 and the cosine the rounding of π/2 (about 6e−17).
        let (s, c) = sin_cos(quarter);
        assert_eq!(s, 1.0);
        assert!(c > 0.0 && c < 1e-16, "{c}");
    }

    /// Chi-square goodness of fit of the cosine-weighted hemisphere sampler: bins in
    /// (cos θ, φ), expected counts from the integrated density.
    #[test]
    fn cosine_hemisphere_passes_chi_square() {
        let n = DVec3::new(0.3, -0.5, 0.8).normalize();
        let (t, b) = basis(n);
        let (bins_theta, bins_phi, samples) = (10usize, 12usize, 200_000usize);
        let mut counts = vec![0f64; bins_theta * bins_phi];
        let mut rng = Rng::for_pixel(7, 1, 2);
        for _ in 0..samples {
            let w = cosine_hemisphere(n, rng.uniform(), rng.uniform());
            let cos = w.dot(n);
            let phi = w.dot(b).atan2(w.dot(t)).rem_euclid(2.0 * PI);
            // cos²θ is uniform under this density: bin on it.
            let i = ((cos * cos) * bins_theta as f64).min(bins_theta as f64 - 1.0) as usize;
            let j = (phi / (2.0 * PI) * bins_phi as f64).min(bins_phi as f64 - 1.0) as usize;
            counts[i * bins_phi + j] += 1.0;
        }
        let chi2 = chi_square_uniform(&counts);
        // 119 degrees of freedom: the 99.9 % point is about 172.
        assert!(chi2 < 172.0, "chi² = {chi2}");
    }

    #[test]
    fn rectangle_samples_are_uniform_in_area() {
        let mut rng = Rng::for_pixel(3, 4, 5);
        let (k, samples) = (8usize, 64_000usize);
        let mut counts = vec![0f64; k * k];
        for _ in 0..samples {
            let p = rectangle(
                DVec3::ZERO,
                DVec3::new(2.0, 0.0, 0.0),
                DVec3::new(0.0, 0.0, 1.0),
                rng.uniform(),
                rng.uniform(),
            );
            let (i, j) = (((p.x / 2.0) * k as f64) as usize, (p.z * k as f64) as usize);
            counts[i.min(k - 1) * k + j.min(k - 1)] += 1.0;
        }
        let chi2 = chi_square_uniform(&counts);
        // 63 degrees of freedom: the 99.9 % point is about 104.
        assert!(chi2 < 104.0, "chi² = {chi2}");
    }

    #[test]
    fn generators_differ_per_pixel_and_repeat_per_seed() {
        let a: Vec<f64> = (0..4)
            .map({
                let mut r = Rng::for_pixel(1, 2, 3);
                move |_| r.uniform()
            })
            .collect();
        let b: Vec<f64> = (0..4)
            .map({
                let mut r = Rng::for_pixel(1, 2, 3);
                move |_| r.uniform()
            })
            .collect();
        let c: Vec<f64> = (0..4)
            .map({
                let mut r = Rng::for_pixel(1, 3, 2);
                move |_| r.uniform()
            })
            .collect();
        assert_eq!(a, b);
        assert_ne!(a, c);
    }
}
