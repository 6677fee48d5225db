//! The local illumination model of the lecture notes:
//! I_local = ka·Ia·O + Σ_ℓ s·fatt·Iℓ·(kd·O·(n·l) + ks·(h·n)^m).

use glam::DVec3;

use super::{Highlight, Material};

/// The diffuse and specular terms of one light, before the shadow factor.
#[derive(Clone, Copy, Debug)]
pub struct LightTerms {
    /// n·l
    pub n_dot_l: f64,
    /// h·n (Blinn) or r·v (Phong), clamped at 0.
    pub highlight_cos: f64,
    /// fatt·Iℓ·kd·O·(n·l)
    pub diffuse: DVec3,
    /// fatt·Iℓ·ks·(h·n)^m
    pub specular: DVec3,
}

/// Ambient term ka·Ia·O.
pub fn ambient(m: &Material, ia: DVec3) -> DVec3 {
    m.ka * ia * m.color
}

/// Diffuse (Lambert) and specular terms for a light seen along l with strength fatt·Iℓ = `light`.
/// n faces the viewer, v points from the surface towards the viewer. Both terms are 0 for a
/// light behind the surface (n·l ≤ 0).
///
/// Always inlined: where the caller ignores `highlight_cos` (the tracer with its recorder off),
/// the compiler then computes the half vector's square root and division only for the lights
/// that produce a highlight (ks > 0 and n·l > 0), not for every light on a matte surface.
#[inline(always)]
pub fn light_terms(m: &Material, n: DVec3, v: DVec3, l: DVec3, light: DVec3) -> LightTerms {
    let n_dot_l = n.dot(l);
    let highlight_cos = match m.highlight {
        Highlight::Blinn => (l + v).normalize_or_zero().dot(n),
        Highlight::Phong => (2.0 * n_dot_l * n - l).dot(v),
    }
    .max(0.0);
    let diffuse = light * m.kd * m.color * n_dot_l.max(0.0);
    let specular = if m.ks > 0.0 && n_dot_l > 0.0 {
        light * m.ks * highlight_power(highlight_cos, m.shininess)
    } else {
        // No highlight from a light behind the surface: it does not light this side at all
        // (the tracer's shadow factor is 0 there anyway, so this only saves the power).
        DVec3::ZERO
    };
    LightTerms {
        n_dot_l,
        highlight_cos,
        diffuse,
        specular,
    }
}

/// cos^m, skipping `powf` where its answer is known exactly: a cosine clamped to 0 (most of a
/// surface, away from the highlight) gives 0 for any positive exponent.
#[inline]
fn highlight_power(cos: f64, m: f64) -> f64 {
    if cos == 0.0 && m > 0.0 {
        0.0
    } else {
        cos.powf(m)
    }
}
