//! The local illumination model of the lecture notes:
//! I_local = ka·Ia·O + Σ_ℓ s·fatt·Iℓ·(kd·O·(n·l) + ks·(h·n)^m).
//!
//! O, kd and ks are the surface's at the shaded point (`Paint`: a material's constants, or its
//! patterns looked up there); ka, the exponent m and the kind of highlight are the material's.

use glam::DVec3;

use super::{Highlight, Material, Paint};

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
pub fn ambient(m: &Material, at: &Paint, ia: DVec3) -> DVec3 {
    m.ka * ia * at.color
}

/// Diffuse (Lambert) and specular terms for a light seen along l with strength fatt·Iℓ = `light`.
/// n faces the viewer, v points from the surface towards the viewer. Both terms are 0 for a
/// light behind the surface (n·l ≤ 0).
///
/// The highlight's cosine costs a square root and a division (Blinn) on the shading's critical
/// path, so it is computed only where it makes a highlight (ks > 0 and n·l > 0), or where the
/// caller `shows` it (a recorded ray tree lists it for every light); elsewhere it is left 0.
#[inline(always)]
pub fn light_terms(
    m: &Material,
    at: &Paint,
    n: DVec3,
    v: DVec3,
    l: DVec3,
    light: DVec3,
    shows: bool,
) -> LightTerms {
    let n_dot_l = n.dot(l);
    let lights_highlight = at.ks > 0.0 && n_dot_l > 0.0;
    let highlight_cos = if lights_highlight || shows {
        highlight_cos(m, n, v, l, n_dot_l)
    } else {
        0.0
    };
    let diffuse = light * at.kd * at.color * n_dot_l.max(0.0);
    let specular = if lights_highlight {
        light * at.ks * highlight_power(highlight_cos, m.shininess)
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

/// The terms of a light *behind* a transparent surface (n·l < 0), with Hall's transmitted
/// highlight (seed 004, "direct specular transmission"): no diffuse term, and the specular
/// term ks·(h′·n)^m with H′ in place of H.
///
/// H′ is the normal a facet would need to refract the light arriving from l into v. Snell's law
/// keeps the tangential part of η·direction across a surface, so η_l·(−l) and η_v·v differ by
/// a multiple of that normal: H′ ∝ −(η·l + v), η = η_l/η_v the index on the light's side over
/// the index on the viewer's. Divided by η − 1 it points to the viewer's side for both η > 1
/// and η < 1; h′·n = 1 exactly where the view ray, refracted, points at the light. With η = 1
/// nothing bends and there is no such facet: no highlight.
pub fn transmitted_terms(
    m: &Material,
    at: &Paint,
    n: DVec3,
    v: DVec3,
    l: DVec3,
    eta: f64,
    light: DVec3,
) -> LightTerms {
    let n_dot_l = n.dot(l);
    let h = (-(eta * l + v) / (eta - 1.0)).normalize_or_zero();
    let highlight_cos = h.dot(n).max(0.0);
    let specular = if at.ks > 0.0 && highlight_cos > 0.0 {
        light * at.ks * highlight_power(highlight_cos, m.shininess)
    } else {
        DVec3::ZERO
    };
    LightTerms {
        n_dot_l,
        highlight_cos,
        diffuse: DVec3::ZERO,
        specular,
    }
}

/// h·n (Blinn) or r·v (Phong), clamped at 0.
#[inline(always)]
fn highlight_cos(m: &Material, n: DVec3, v: DVec3, l: DVec3, n_dot_l: f64) -> f64 {
    match m.highlight {
        Highlight::Blinn => {
            // h·n = (l + v)·n / |l + v|: the square root only where the cosine is positive.
            let h = l + v;
            let hn = h.dot(n);
            if hn > 0.0 {
                hn / h.length()
            } else {
                0.0
            }
        }
        Highlight::Phong => (2.0 * n_dot_l * n - l).dot(v),
    }
    .max(0.0)
}

/// cos^m, skipping `powf` where a cheaper answer is good enough: a cosine clamped to 0 (most of a
/// surface, away from the highlight) gives 0 for any positive exponent, and a whole exponent up
/// to 1024 (the usual shininess values) is raised by repeated squaring, with a relative error
/// below m·2⁻⁵², far under anything an image can show.
#[inline]
fn highlight_power(cos: f64, m: f64) -> f64 {
    if cos == 0.0 && m > 0.0 {
        0.0
    } else if let Some(e) = whole_exponent(m) {
        powi_by_squaring(cos, e)
    } else {
        cos.powf(m)
    }
}

/// The exponent m as a whole number, if it is one from 0 to 1024: the exponents
/// `highlight_power` raises by repeated squaring.
pub fn whole_exponent(m: f64) -> Option<u32> {
    (m.fract() == 0.0 && (0.0..=1024.0).contains(&m)).then_some(m as u32)
}

/// aᵉ by repeated squaring: a, a², a⁴, … multiplied in where e has a one bit. The same
/// multiplications in the same order as `f64::powi` (compiler-builtins' `__powidf2`, so images
/// do not depend on which is used), written out so that the compiler can inline them.
#[inline]
fn powi_by_squaring(mut a: f64, mut e: u32) -> f64 {
    let mut product = 1.0;
    loop {
        if e & 1 != 0 {
            product *= a;
        }
        e >>= 1;
        if e == 0 {
            return product;
        }
        a *= a;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The squaring shortcut agrees with `powf` for the exponents scenes use, and fractional
    /// or huge exponents take `powf` itself.
    #[test]
    fn highlight_power_matches_powf() {
        for m in [
            0.5, 1.0, 2.0, 7.5, 20.0, 40.0, 100.0, 200.0, 1000.0, 1024.0, 5000.0,
        ] {
            for k in 0..=1000 {
                let cos = k as f64 / 1000.0;
                let (fast, exact) = (highlight_power(cos, m), cos.powf(m));
                assert!(
                    (fast - exact).abs() <= 1e-12 * exact,
                    "{cos}^{m}: {fast} vs {exact}"
                );
            }
        }
        assert_eq!(highlight_power(0.0, 40.0), 0.0);
        assert_eq!(highlight_power(0.7, 0.0), 1.0);
    }

    /// Squaring by hand multiplies as `powi` does, to the last bit.
    #[test]
    fn powi_by_squaring_is_powi() {
        for e in 0..=1024u32 {
            for k in 0..=200 {
                let a = k as f64 / 200.0 + 1e-3 * (e as f64).sin();
                assert_eq!(
                    powi_by_squaring(a, e).to_bits(),
                    a.powi(e as i32).to_bits(),
                    "{a}^{e}"
                );
            }
        }
    }

    /// A light exactly at the horizon (n·l = 0) lights neither term: no diffuse, and no
    /// highlight either, though the halfway vector between it and the viewer leans toward n
    /// (Blinn's h·n = cos 22.5° here, Phong's r·v = cos 45°).
    #[test]
    fn a_light_at_the_horizon_makes_no_highlight() {
        for highlight in [Highlight::Blinn, Highlight::Phong] {
            let m = Material {
                ks: 0.5,
                shininess: 2.0,
                highlight,
                ..Material::matte("shiny", DVec3::ONE)
            };
            let v = DVec3::new(-1.0, 1.0, 0.0).normalize();
            let t = light_terms(&m, &m.paint(), DVec3::Y, v, DVec3::X, DVec3::ONE, true);
            assert_eq!(t.n_dot_l, 0.0);
            assert!(t.highlight_cos > 0.38, "{highlight:?}: {}", t.highlight_cos);
            assert_eq!(
                (t.diffuse, t.specular),
                (DVec3::ZERO, DVec3::ZERO),
                "{highlight:?}"
            );
        }
    }

    /// With m = 0 the highlight is ks wherever the light reaches, cos⁰ = 1, also where the
    /// cosine itself is 0: Phong with the light on the normal (r = n) and the viewer at the
    /// horizon (r·v = 0). Any m > 0 makes no highlight there.
    #[test]
    fn shininess_zero_makes_a_uniform_highlight() {
        for (shininess, expected) in [(0.0, 0.5), (1.0, 0.0), (0.5, 0.0)] {
            let m = Material {
                ks: 0.5,
                shininess,
                highlight: Highlight::Phong,
                ..Material::matte("flat", DVec3::ONE)
            };
            let t = light_terms(
                &m,
                &m.paint(),
                DVec3::Y,
                DVec3::X,
                DVec3::Y,
                DVec3::ONE,
                true,
            );
            assert_eq!(t.highlight_cos, 0.0);
            assert_eq!(t.specular, DVec3::splat(expected), "m = {shininess}");
        }
    }

    /// H′ facing away from the viewer's side (h′·n ≤ 0) makes no transmitted highlight, even
    /// with m = 0, where cos⁰ would be 1: from air into glass (η = 1.5), viewer on the normal,
    /// light behind at l = (−0.8, −0.6, 0): H′ ∝ −(η·l + v)/(η − 1) = (2.4, −0.2, 0)/0.5.
    #[test]
    fn no_transmitted_highlight_from_a_facet_facing_away() {
        let m = Material {
            ks: 0.5,
            kt: 0.9,
            shininess: 0.0,
            ..Material::matte("glass", DVec3::ONE)
        };
        let l = DVec3::new(-0.8, -0.6, 0.0);
        let t = transmitted_terms(&m, &m.paint(), DVec3::Y, DVec3::Y, l, 1.5, DVec3::ONE);
        assert_eq!((t.highlight_cos, t.specular), (0.0, DVec3::ZERO));
    }

    /// Hall's transmitted highlight peaks (h′·n = 1) exactly where the refracted view ray
    /// points at the light, from air into glass (η = 1.5) and from glass into air (η = 1/1.5);
    /// with η = 1 nothing bends and there is no highlight.
    #[test]
    fn transmitted_highlight_peaks_along_the_refracted_view_ray() {
        use crate::shading::optics::refract;
        let m = Material {
            ks: 0.5,
            kt: 0.9,
            shininess: 50.0,
            ..Material::matte("glass", DVec3::ONE)
        };
        let n = DVec3::Y;
        for (n_view, n_light, tilt) in [(1.0, 1.5, 0.6f64), (1.5, 1.0, 0.3), (1.0, 1.33, 1.2)] {
            let v = DVec3::new(tilt.sin(), tilt.cos(), 0.0);
            let refracted = refract(-v, n, n_view, n_light).expect("no total internal reflection");
            let eta = n_light / n_view;
            let paint = m.paint();
            let at = |l: DVec3| transmitted_terms(&m, &paint, n, v, l, eta, DVec3::ONE);
            let peak = at(refracted);
            assert!(
                (peak.highlight_cos - 1.0).abs() < 1e-12,
                "{}",
                peak.highlight_cos
            );
            assert!((peak.specular.x - m.ks).abs() < 1e-9);
            assert_eq!(peak.diffuse, DVec3::ZERO);
            // Sweep lights behind the surface, in the plane of incidence and out of it: none
            // gives more, and the best of the sweep sits next to the refracted ray.
            let mut best = (f64::NEG_INFINITY, DVec3::ZERO);
            for i in 1..720 {
                for j in -20..=20 {
                    let a = std::f64::consts::PI * i as f64 / 720.0;
                    let b = 0.05 * j as f64;
                    let l = DVec3::new(a.cos() * b.cos(), -a.sin() * b.cos(), b.sin());
                    let s = at(l).specular.x;
                    assert!(s <= peak.specular.x + 1e-12);
                    if s > best.0 {
                        best = (s, l);
                    }
                }
            }
            assert!(
                best.1.angle_between(refracted) < 0.01,
                "peak at {:?}, refracted {refracted:?}",
                best.1
            );
            // The light straight behind (the view ray unbent) is off the peak.
            assert!(at(-v).highlight_cos < 0.999);
        }
        let flat = transmitted_terms(&m, &m.paint(), n, DVec3::Y, -DVec3::Y, 1.0, DVec3::ONE);
        assert_eq!(flat.specular, DVec3::ZERO);
    }
}
