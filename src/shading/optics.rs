//! Reflection, refraction and Fresnel weights.

use glam::DVec3;

use super::Fresnel;

/// Mirror direction (seed 000): v' = v − 2(v·n)n.
pub fn reflect(v: DVec3, n: DVec3) -> DVec3 {
    v - 2.0 * v.dot(n) * n
}

/// Snell's law in vector form, with n facing the incoming direction d (both unit):
/// η = n1/n2, c1 = −d·n, c2 = √(1 − η²(1 − c1²)), t = η·d + (η·c1 − c2)·n. t is a unit
/// vector as it stands, like the mirror direction: |t|² = η²|d|² − η²c1² + c2², so
/// |t|² − 1 = η²(|d|² − 1), and a rounding error in d's length is scaled, not compounded.
/// `None` is total internal reflection (the square root's argument is negative: beyond the
/// limiting angle sin θ = n2/n1).
pub fn refract(d: DVec3, n: DVec3, n1: f64, n2: f64) -> Option<DVec3> {
    let eta = n1 / n2;
    let c1 = -d.dot(n);
    let k = 1.0 - eta * eta * (1.0 - c1 * c1);
    if k < 0.0 {
        return None;
    }
    Some(eta * d + (eta * c1 - k.sqrt()) * n)
}

/// Schlick's approximation of the Fresnel reflectance: R0 = ((n1 − n2)/(n1 + n2))²,
/// R = R0 + (1 − R0)(1 − cos θ)^5 with θ the angle on the side of the lower index.
pub fn schlick(cos_incident: f64, n1: f64, n2: f64) -> f64 {
    let r0 = ((n1 - n2) / (n1 + n2)).powi(2);
    let cos = if n1 <= n2 {
        cos_incident
    } else {
        let sin2_t = (n1 / n2).powi(2) * (1.0 - cos_incident * cos_incident);
        if sin2_t >= 1.0 {
            return 1.0;
        }
        (1.0 - sin2_t).sqrt()
    };
    r0 + (1.0 - r0) * (1.0 - cos).powi(5)
}

/// kr and kt after the Fresnel term: with Schlick's R, kr·R and kt·(1 − R); without one, as
/// the material gives them.
#[inline(always)]
pub fn fresnel_weights(
    fresnel: Fresnel,
    cos_incident: f64,
    (n1, n2): (f64, f64),
    (kr, kt): (f64, f64),
) -> (f64, f64) {
    match fresnel {
        Fresnel::None => (kr, kt),
        Fresnel::Schlick => {
            let r = schlick(cos_incident, n1, n2);
            (kr * r, kt * (1.0 - r))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn snell_holds_and_the_limiting_angle_separates_refraction_from_tir() {
        let n = DVec3::Y;
        // 30° in glass (1.5) towards air: sin θt = 1.5·0.5 = 0.75.
        let d = DVec3::new(0.5, -(0.75f64).sqrt(), 0.0);
        let t = refract(d, n, 1.0, 1.5).unwrap();
        assert!((t.x - 0.5 / 1.5).abs() < 1e-15);
        let out = refract(DVec3::new(0.5, (0.75f64).sqrt(), 0.0), -n, 1.5, 1.0).unwrap();
        assert!((out.x - 0.75).abs() < 1e-15);
        // Limiting angle asin(1/1.5) = 41.81°: just below refracts, just above reflects.
        let crit = (1.0f64 / 1.5).asin();
        for (angle, tir) in [(crit - 1e-6, false), (crit + 1e-6, true)] {
            let d = DVec3::new(angle.sin(), angle.cos(), 0.0);
            assert_eq!(refract(d, -n, 1.5, 1.0).is_none(), tir);
        }
    }

    #[test]
    fn at_the_limiting_angle_itself_the_ray_still_refracts_along_the_surface() {
        // n1 = 1.25 → n2 = 1, sin θi = 0.8: sin θt = 1.25·0.8 = 1 exactly (1 − η²(1 − c1²) is
        // 0 in floating point too). TIR begins past this angle, where the root is imaginary:
        // the transmitted ray grazes the surface, t = η·d + η·c1·n = (1, 0, 0).
        let d = DVec3::new(0.8, -0.6, 0.0);
        let t = refract(d, DVec3::Y, 1.25, 1.0).expect("sin θt = 1 is not yet TIR");
        assert!((t - DVec3::X).length() < 1e-15, "{t}");
        // Equal indices never reflect totally, even at grazing incidence (c1 = 0, η = 1).
        assert_eq!(refract(DVec3::X, DVec3::Y, 1.5, 1.5), Some(DVec3::X));
    }

    #[test]
    fn the_refracted_direction_is_unit_without_normalising() {
        // Incidences from head-on to grazing, into and out of glass and water: |t| = 1 to a
        // few ulps wherever the ray refracts, as |t|² = η²|d|² − η²c1² + c2² = 1 says. It
        // refracts where Snell's sin θt = η·sin θi is at most 1, with sin θi = |d × n|.
        for (n1, n2) in [(1.0, 1.5), (1.5, 1.0), (1.0, 1.33), (1.33, 1.5)] {
            let (mut refracted, mut expected) = (0, 0);
            for step in 0..=1000 {
                let angle = step as f64 / 1000.0 * std::f64::consts::FRAC_PI_2;
                let d = DVec3::new(angle.sin(), -angle.cos(), 0.3 * angle.sin()).normalize();
                // Away from the limiting angle by more than rounding can blur.
                let sin_t = n1 / n2 * d.cross(DVec3::Y).length();
                if (sin_t - 1.0).abs() < 1e-9 {
                    continue;
                }
                expected += (sin_t < 1.0) as u32;
                let Some(t) = refract(d, DVec3::Y, n1, n2) else {
                    continue;
                };
                refracted += 1;
                assert!(
                    (t.length() - 1.0).abs() < 4.0 * f64::EPSILON,
                    "{n1}→{n2}: |t| = {}",
                    t.length()
                );
            }
            assert_eq!(refracted, expected, "{n1}→{n2}: rays refracted");
        }
    }

    #[test]
    fn schlick_is_r0_head_on_and_one_at_grazing() {
        assert!((schlick(1.0, 1.0, 1.5) - 0.04).abs() < 1e-15);
        assert!((schlick(0.0, 1.0, 1.5) - 1.0).abs() < 1e-15);
        assert_eq!(schlick(0.2, 1.5, 1.0), 1.0);
    }

    #[test]
    fn schlick_between_two_dense_media_uses_the_transmitted_angle() {
        // n1 = 1.6 → n2 = 1.2 (η = 4/3, neither index 1), sin θi = 0.6: sin θt = 0.8, so
        // cos θt = 0.6. R0 = (0.4/2.8)² = 1/49, R = 1/49 + (48/49)·0.4⁵ = 1.49152/49.
        let r = schlick(0.8, 1.6, 1.2);
        assert!((r - 1.49152 / 49.0).abs() < 1e-12, "{r}");
    }
}
