//! A light's share at the surfaces of a packet: the core's `Tracer::light_share`, for the
//! packet loop (`packet_trace::shade_packet`), which asks it for every surface and every light.
//! No tree is filled here, so the highlight's cosine is computed only where a highlight is
//! lit, and the step is compiled into the loop; a surface seen through Hall's transmitted
//! highlight takes the core's own step. The terms and the counters are the core's to the bit.

use std::borrow::Cow;

use glam::DVec3;

use crate::geometry::Ray;
use crate::scene::Interaction;
use crate::shading::local::light_terms;
use crate::shading::{Light, LightKind, LightSample, Material};
use crate::trace::{Task, Tracer};

/// Light k's diffuse plus specular term at `si`, seen along `ray`, before the shadow factor,
/// and whether its shadow ray is skipped (then s = 0). The ray's whole task is asked for only
/// where Hall's highlight needs its media (a primary ray's task is built on demand).
#[inline(always)]
pub(super) fn light_share<'a>(
    t: &mut Tracer,
    m: &Material,
    si: &Interaction,
    ray: &Ray,
    task: impl FnOnce() -> Cow<'a, Task>,
    k: usize,
) -> (LightSample, DVec3, bool) {
    if m.transmitted_highlight {
        let (sample, lit, skipped) = t.light_share(m, si, &task(), k, false);
        return (sample, lit.diffuse + lit.specular, skipped.is_some());
    }
    let light = &t.scene.lights[k];
    let sample = sample(light, si.point);
    let strength = sample.attenuation * light.intensity;
    let lit = light_terms(m, &si.paint, si.normal, -ray.dir, sample.l, strength, false);
    let skipped = t
        .no_shadow_ray(si, k, &sample, lit.n_dot_l, false)
        .is_some();
    (sample, lit.diffuse + lit.specular, skipped)
}

/// `Light::sample`, to the bit (l = (light − p)·(1/d)), with one division fewer for a
/// point light that does not fade (c0, c1, c2 = 1, 0, 0, the default): there
/// fatt = 1/(1 + 0·d + 0·d·d) is exactly 1 wherever d is finite. Where d is not (a point
/// beyond f64's range, or NaN), fatt is NaN and the core answers `AT_THE_POINT`, as this does.
#[inline(always)]
fn sample(light: &Light, p: DVec3) -> LightSample {
    match &light.kind {
        LightKind::Point {
            position,
            attenuation,
        } if *attenuation == [1.0, 0.0, 0.0] => {
            let to_light = *position - p;
            let d = to_light.length();
            if d == 0.0 || !d.is_finite() {
                return LightSample::AT_THE_POINT;
            }
            LightSample {
                l: to_light * (1.0 / d),
                distance: d,
                attenuation: 1.0,
            }
        }
        _ => light.sample(p),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::Rng;

    /// The shortcut gives `Light::sample`'s answer to the bit, for lights that fade and lights
    /// that do not, at points near, far, on the light and beyond f64's range of distances.
    #[test]
    fn a_point_lights_sample_is_the_cores() {
        let mut rng = Rng::for_pixel(31, 0, 0);
        let position = DVec3::new(-6.0, 10.0, -6.0);
        let far = DVec3::splat(1e308);
        for attenuation in [
            [1.0, 0.0, 0.0],
            [1.0, -0.0, -0.0],
            [0.0, 1.0, 0.0],
            [1.0, 0.5, 0.25],
        ] {
            let light = Light {
                name: "key".into(),
                kind: LightKind::Point {
                    position,
                    attenuation,
                },
                intensity: DVec3::splat(0.8),
                surface: None,
            };
            let mut points = vec![position, -far, far, DVec3::splat(f64::NAN)];
            for _ in 0..2000 {
                let scale = 10f64.powf(rng.uniform() * 40.0 - 20.0);
                let r = DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()) - 0.5;
                points.push(position + scale * r);
            }
            for p in points {
                let core = light.sample(p);
                let own = sample(&light, p);
                let bits = |s: &LightSample| {
                    (
                        s.l.to_array().map(f64::to_bits),
                        s.distance.to_bits(),
                        s.attenuation.to_bits(),
                    )
                };
                assert_eq!(bits(&own), bits(&core), "{attenuation:?} at {p}");
            }
        }
    }
}
