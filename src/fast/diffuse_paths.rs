//! The path tracer (`trace::path`) for scenes whose surfaces only scatter diffusely: the same
//! paths with the same numbers, to the last bit, for less work.
//!
//! In such a scene (no material with kr or kt, the Cornell box's kind) every bounce of a path
//! takes the Lambertian lobe, so the lobe choice, the mirror and glass branches and the
//! inspector's log fall away; and what the core works out from a rectangle light's corner and
//! sides at every ray and every light sample (its normal u × v, that normal's length, the
//! area, and its unit normal; the sides' squared lengths) is worked out once, with the same
//! operations, so to the same bits. Sphere, point and directional lights are asked as the core
//! asks them (`Light::emitter_hit`, `Light::sample_emitter`). A bounce draws its numbers for its
//! first light and its direction before its search, not after: the same numbers, ready sooner.

use std::f64::consts::PI;

use glam::DVec3;

use super::search::FastScene;
use crate::geometry::Ray;
use crate::sampling::{cosine_hemisphere, cosine_pdf, rectangle, SamplePoint};
use crate::scene::{Interaction, Search};
use crate::shading::{Light, LightKind};
use crate::stats::Stats;
use crate::trace::path::{power_heuristic, Bounce, Draw, PathTracer};

/// The core's path tracer for a scene in which every surface is diffuse only.
pub struct DiffusePaths<'s> {
    /// The core's tracer: its scene, maximum depth and rules.
    tracer: PathTracer<'s>,
    /// The scene's lights, in order, rectangles with their derived quantities.
    lights: Vec<Emitter<'s>>,
}

/// A light as the path tracer meets and samples it.
enum Emitter<'s> {
    /// A rectangle, with what the core derives from its corner and sides.
    Rect {
        light: &'s Light,
        corner: DVec3,
        u: DVec3,
        v: DVec3,
        /// |u × v|
        area: f64,
        /// (u × v)/|u × v|
        normal: DVec3,
        /// |u|², |v|²
        u2: f64,
        v2: f64,
    },
    /// Any other light, asked as the core asks it.
    Other(&'s Light),
}

/// Where a ray meets an emitter, as the core's `light_hit` finds it.
struct LightHit<'s> {
    t: f64,
    light: &'s Light,
    pdf: f64,
    normal: DVec3,
}

/// A bounce's random numbers, its first light's drawn ahead (see `DiffusePaths::radiance`).
#[derive(Clone, Copy)]
struct Ahead<'p> {
    bounce: Bounce<'p>,
    first_light: Option<[f64; 2]>,
}

impl Ahead<'_> {
    /// The pair light i's sample takes, as `PathTracer::draw` gives it.
    #[inline(always)]
    fn light(&self, pt: &PathTracer, i: usize) -> [f64; 2] {
        match self.first_light {
            Some(pair) if i == 0 => pair,
            _ => pt.draw(self.bounce, Draw::Light(i)),
        }
    }
}

impl<'s> DiffusePaths<'s> {
    /// The fast form of `tracer`, when its scene's surfaces all scatter diffusely only (no
    /// material with kr or kt, none with patterns, no albedo so small that it is subnormal);
    /// None otherwise.
    pub fn new(tracer: PathTracer<'s>) -> Option<DiffusePaths<'s>> {
        let scene = tracer.scene;
        let diffuse_only = scene.materials.iter().all(|m| {
            // Diffuse weights that are 0 or normal numbers: for them the core's pick of a lobe,
            // u · weight with u < 1, always falls below the weight, on the Lambertian lobe.
            let weight = (m.kd * m.color).max_element();
            let weight_normal = weight == 0.0 || (weight.is_normal() && weight > 0.0);
            m.kr == 0.0 && m.kt == 0.0 && m.patterns.is_none() && weight_normal
        });
        if !diffuse_only {
            return None;
        }
        let lights = scene
            .lights
            .iter()
            .map(|light| match &light.kind {
                LightKind::Rect { corner, u, v, .. } => {
                    let normal = u.cross(*v);
                    let area = normal.length();
                    Emitter::Rect {
                        light,
                        corner: *corner,
                        u: *u,
                        v: *v,
                        area,
                        normal: normal / area,
                        u2: u.length_squared(),
                        v2: v.length_squared(),
                    }
                }
                _ => Emitter::Other(light),
            })
            .collect();
        Some(DiffusePaths { tracer, lights })
    }

    /// `PathTracer::radiance`: one sample of the radiance along `primary`, the path drawn from
    /// `point`, its hits found by `fast`.
    pub fn radiance(
        &self,
        fast: &FastScene,
        primary: &Ray,
        point: &SamplePoint,
        stats: &mut Stats,
    ) -> DVec3 {
        let pt = &self.tracer;
        let scene = pt.scene;
        let mut ray = *primary;
        let mut throughput = DVec3::ONE;
        let mut sum = DVec3::ZERO;
        let mut bsdf_pdf: Option<f64> = None;
        stats.primary_rays += 1;
        for depth in 0..pt.max_depth {
            let bounce = Bounce { point, depth };
            // The bounce's numbers for its first light and its direction, drawn before its
            // search: they depend on nothing the search finds, and the processor works out
            // their chains of hashes while the search runs.
            let numbers = Ahead {
                bounce,
                first_light: (!self.lights.is_empty()).then(|| pt.draw(bounce, Draw::Light(0))),
            };
            let direction = pt.draw(bounce, Draw::Direction);
            let hit = fast.nearest(&ray, 0.0, f64::INFINITY, stats);
            let t_hit = hit.map_or(f64::INFINITY, |h| h.t);
            let si = if let Some(lh) = self.light_hit(&ray, t_hit) {
                let weight = match bsdf_pdf {
                    Some(p) if pt.next_event => power_heuristic(p, lh.pdf),
                    _ => 1.0,
                };
                sum += throughput * lh.light.intensity * weight;
                let Some(material) = lh.light.surface else {
                    break;
                };
                Interaction {
                    point: ray.at(lh.t),
                    normal: lh.normal,
                    inside: false,
                    leaf: 0,
                    face: 0,
                    object: 0,
                    material,
                    paint: scene.material(material).paint(),
                    origin_size: ray.origin.abs().max_element(),
                }
            } else {
                let Some(hit) = hit else {
                    sum += throughput * scene.background;
                    break;
                };
                let si = scene.interaction(&ray, &hit);
                sum += throughput * scene.material(si.material).emission;
                si
            };
            // The Lambertian lobe's weight is the only one: the core's choice among lobes
            // always falls on it, and kr = kt = 0 leave its sum of weights as it is.
            let at = si.paint;
            let diffuse = at.kd * at.color;
            let total = diffuse.max_element();
            if total <= 0.0 || depth + 1 >= pt.max_depth {
                if total > 0.0 && pt.local_at_max_depth {
                    let p = si.point + scene.bias(ray.origin, si.point) * si.normal;
                    sum += throughput
                        * diffuse
                        * self.lights_at(fast, p, si.normal, numbers, stats, false);
                }
                break;
            }
            // The lobe pair's second number decides Russian roulette; its first, the lobe, has
            // nothing to choose.
            let roulette = (pt.roulette && depth >= 3).then(|| pt.draw(bounce, Draw::Lobe)[1]);
            let n = si.normal;
            let offset = scene.bias(ray.origin, si.point);
            // The core's throughput · albedo · (total / weight): the one weight is the total,
            // a finite positive number, and x · (w / w) = x · 1 = x exactly.
            let lobe = throughput * diffuse;
            if pt.next_event {
                let p = si.point + offset * n;
                sum += lobe * self.lights_at(fast, p, n, numbers, stats, true);
            }
            let [u1, u2] = direction;
            let dir = cosine_hemisphere(n, u1, u2);
            bsdf_pdf = Some(cosine_pdf(n, dir));
            throughput = lobe;
            ray = Ray {
                origin: si.point + offset * n,
                dir,
            };
            stats.reflection_rays += 1;
            if let Some(survive) = roulette {
                let q = throughput.max_element().clamp(0.05, 0.95);
                if survive >= q {
                    break;
                }
                throughput /= q;
            }
        }
        sum
    }

    /// The nearest emitter the ray meets before t_max: the core's `light_hit`.
    #[inline(always)]
    fn light_hit(&self, ray: &Ray, t_max: f64) -> Option<LightHit<'s>> {
        let mut best: Option<LightHit> = None;
        for emitter in &self.lights {
            let limit = best.as_ref().map_or(t_max, |b| b.t);
            let hit = match emitter {
                Emitter::Rect {
                    light,
                    corner,
                    u,
                    v,
                    area,
                    normal,
                    u2,
                    v2,
                } => {
                    // `Light::emitter_hit` for a rectangle.
                    let facing = ray.dir.dot(*normal);
                    if facing >= 0.0 {
                        continue;
                    }
                    let t = (*corner - ray.origin).dot(*normal) / facing;
                    if t <= 0.0 || t >= limit {
                        continue;
                    }
                    let q = ray.at(t) - *corner;
                    let (a, b) = (q.dot(*u) / u2, q.dot(*v) / v2);
                    if !((0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b)) {
                        continue;
                    }
                    LightHit {
                        t,
                        light,
                        pdf: t * t / (-facing * area),
                        normal: *normal,
                    }
                }
                Emitter::Other(light) => {
                    let Some(h) = light.emitter_hit(ray, limit) else {
                        continue;
                    };
                    LightHit {
                        t: h.t,
                        light,
                        pdf: h.pdf,
                        normal: h.normal,
                    }
                }
            };
            best = Some(hit);
        }
        best
    }

    /// One sample of the light from each light at p, per unit albedo, weighted against the
    /// cosine sample that follows when `mis`: the core's `lights_at`.
    #[inline(always)]
    fn lights_at(
        &self,
        fast: &FastScene,
        p: DVec3,
        n: DVec3,
        numbers: Ahead,
        stats: &mut Stats,
        mis: bool,
    ) -> DVec3 {
        let mut sum = DVec3::ZERO;
        for (i, emitter) in self.lights.iter().enumerate() {
            let [u1, u2] = numbers.light(&self.tracer, i);
            // `Light::sample_emitter`: a direction, the distance, the density per solid angle.
            let (light, wi, distance, pdf) = match emitter {
                Emitter::Rect {
                    light,
                    corner,
                    u,
                    v,
                    area,
                    normal,
                    ..
                } => {
                    let to = rectangle(*corner, *u, *v, u1, u2) - p;
                    let distance = to.length();
                    let wi = to / distance;
                    let cos_l = -normal.dot(wi);
                    if cos_l <= 0.0 || cos_l.is_nan() {
                        continue;
                    }
                    (*light, wi, distance, distance * distance / (cos_l * area))
                }
                Emitter::Other(light) => {
                    let Some(e) = light.sample_emitter(p, u1, u2) else {
                        continue;
                    };
                    (*light, e.wi, e.distance, e.pdf)
                }
            };
            let cos_s = n.dot(wi);
            if cos_s <= 0.0 {
                continue;
            }
            stats.shadow_rays += 1;
            let shadow = Ray { origin: p, dir: wi };
            if fast
                .blocker(&shadow, 0.0, distance * (1.0 - 1e-9), stats)
                .is_some()
            {
                continue;
            }
            let weight = if mis {
                power_heuristic(pdf, cosine_pdf(n, wi))
            } else {
                1.0
            };
            sum += light.intensity * (cos_s / PI) / pdf * weight;
        }
        sum
    }
}
