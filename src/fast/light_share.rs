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
use crate::shading::{LightSample, Material};
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
    let sample = light.sample(si.point);
    let strength = sample.attenuation * light.intensity;
    let lit = light_terms(m, &si.paint, si.normal, -ray.dir, sample.l, strength, false);
    let skipped = t.no_shadow_ray(si, k, lit.n_dot_l, false).is_some();
    (sample, lit.diffuse + lit.specular, skipped)
}
