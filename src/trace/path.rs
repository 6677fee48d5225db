//! The path tracer (seed 002): one random path per sample, diffuse bounces sampled by cos θ/π,
//! perfect mirrors and glass, emitters, Russian roulette, and next-event estimation on area
//! lights combined with BSDF sampling by multiple importance sampling (power heuristic).
//!
//! The same materials are read physically: diffuse albedo kd·O, mirror reflectance kr,
//! transmission kt with ior, `emission` for glowing surfaces, the background as a uniform
//! environment, rectangle lights as emitters of radiance `intensity`.
//!
//! A path draws its random numbers from its sample point (`sampling::sobol`), a pair for each
//! decision of each bounce (`Draw`), so that a pixel's samples spread evenly over every one.

use std::f64::consts::PI;

use glam::DVec3;

use crate::geometry::Ray;
use crate::sampling::{cosine_hemisphere, cosine_pdf, SamplePoint};
use crate::scene::{Interaction, Scene, Search};
use crate::shading::lobe::spread;
use crate::shading::optics::{reflect, refract, schlick};
use crate::shading::Light;
use crate::stats::Stats;

/// A Monte Carlo path tracer over a scene: each sample follows one random path from the eye, with
/// next-event estimation and Russian roulette.
#[derive(Clone, Copy)]
pub struct PathTracer<'s> {
    /// The scene traced.
    pub scene: &'s Scene,
    /// Where rays find their hits: the scene's own search, or the fast wing's.
    pub search: &'s dyn Search,
    /// Path segments at most (the primary ray counts).
    pub max_depth: u32,
    /// Sample the lights directly at diffuse hits (off only to test that it changes nothing).
    pub next_event: bool,
    /// Stop paths at random, unbiasedly, from the fourth bounce on (off only for tests).
    pub roulette: bool,
    /// Seed 002's rule for a path at the maximum depth: it "contributes just its local
    /// illumination", the direct light at its last surface. Off (the scene's `stop_rules`
    /// names `local_at_max_depth` to turn it on), the last surface adds only its emission.
    pub local_at_max_depth: bool,
}

/// One vertex of a recorded path, for `inspect` on a path-traced pixel.
#[derive(Clone, Debug, serde::Serialize)]
pub struct PathVertex {
    /// What happened here: light, background, diffuse, mirror, glossy, refraction, reflection,
    /// absorbed (no lobe), max_depth, roulette.
    pub event: &'static str,
    /// The object (or light) met.
    pub object: Option<String>,
    /// Where the path met the surface (world space); for the background, where the ray that
    /// left the scene started.
    pub point: DVec3,
    /// The direction in which the path left the scene (the background only).
    pub toward: Option<DVec3>,
    /// The path's throughput after this vertex.
    pub throughput: DVec3,
    /// Radiance this vertex added to the estimate (emission, next-event estimation, a light or
    /// the background reached).
    pub added: DVec3,
}

/// The vertices of a path as `PathTracer::sample` meets them, when they are asked for.
struct PathLog<'a>(Option<&'a mut Vec<PathVertex>>);

impl PathLog<'_> {
    /// A vertex on a surface (or a light), or where the path ended there.
    fn at(
        &mut self,
        event: &'static str,
        object: Option<&str>,
        point: DVec3,
        throughput: DVec3,
        added: DVec3,
    ) {
        self.push(event, object, point, None, throughput, added);
    }

    /// The path leaving the scene along `ray`: it meets no point.
    fn leaving(&mut self, ray: &Ray, throughput: DVec3, added: DVec3) {
        self.push(
            "background",
            None,
            ray.origin,
            Some(ray.dir),
            throughput,
            added,
        );
    }

    fn push(
        &mut self,
        event: &'static str,
        object: Option<&str>,
        point: DVec3,
        toward: Option<DVec3>,
        throughput: DVec3,
        added: DVec3,
    ) {
        if let Some(log) = self.0.as_deref_mut() {
            log.push(PathVertex {
                event,
                object: object.map(str::to_string),
                point,
                toward,
                throughput,
                added,
            });
        }
    }
}

/// Where a ray meets an emitter: distance, the light, and the density light sampling would
/// have given that direction.
struct LightHit<'a> {
    t: f64,
    light: &'a Light,
    pdf: f64,
    /// The emitter's normal at the hit, facing the ray.
    normal: DVec3,
}

/// What a bounce draws random numbers for, each from its own pair of the sample point.
#[derive(Clone, Copy)]
pub(crate) enum Draw {
    /// Which lobe scatters the path, and whether Russian roulette stops it.
    Lobe,
    /// The direction the lobe scatters to (cosine, glossy or frosted).
    Direction,
    /// Reflection or refraction, by Fresnel's weights.
    Fresnel,
    /// A point on light number i, for next-event estimation.
    Light(usize),
}

/// Where one bounce of a path takes its random numbers: the path's sample point, at the
/// bounce's depth.
#[derive(Clone, Copy)]
pub(crate) struct Bounce<'p> {
    pub(crate) point: &'p SamplePoint,
    pub(crate) depth: u32,
}

/// The power heuristic for two strategies (β = 2).
pub(crate) fn power_heuristic(a: f64, b: f64) -> f64 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 == 0.0 {
        0.0
    } else {
        a2 / (a2 + b2)
    }
}

impl<'s> PathTracer<'s> {
    /// A path tracer of `scene` with paths of at most `max_depth` segments, searching the scene
    /// itself, with next-event estimation and roulette on and the scene's stop rule at the maximum
    /// depth.
    pub fn new(scene: &'s Scene, max_depth: u32) -> PathTracer<'s> {
        PathTracer {
            scene,
            search: scene,
            max_depth,
            next_event: true,
            roulette: true,
            local_at_max_depth: scene.stop_rules.local_at_max_depth,
        }
    }

    /// The same path tracer, finding its hits through `search`.
    pub fn with_search(self, search: &'s dyn Search) -> PathTracer<'s> {
        PathTracer { search, ..self }
    }

    /// The nearest emitter (rectangle front or sphere light) the ray meets before t_max.
    fn light_hit(&self, ray: &Ray, t_max: f64) -> Option<LightHit<'s>> {
        let mut best: Option<LightHit> = None;
        for light in &self.scene.lights {
            let limit = best.as_ref().map_or(t_max, |b| b.t);
            if let Some(h) = light.emitter_hit(ray, limit) {
                best = Some(LightHit {
                    t: h.t,
                    light,
                    pdf: h.pdf,
                    normal: h.normal,
                });
            }
        }
        best
    }

    /// The pair of random numbers the bounce `at` draws for `draw`: each bounce has pairs of
    /// its own, after pair 0, the film's point in the pixel.
    pub(crate) fn draw(&self, at: Bounce, draw: Draw) -> [f64; 2] {
        let slot = match draw {
            Draw::Lobe => 0,
            Draw::Direction => 1,
            Draw::Fresnel => 2,
            Draw::Light(i) => 3 + i as u32,
        };
        let per_bounce = 3 + self.scene.lights.len() as u32;
        // Wrapping: a pair's number only seeds its scramble, and wraps for no real path.
        at.point
            .pair(at.depth.wrapping_mul(per_bounce).wrapping_add(1 + slot))
    }

    /// One sample of the radiance arriving along a primary ray, the path drawn from `point`.
    pub fn radiance(&self, primary: &Ray, point: &SamplePoint, stats: &mut Stats) -> DVec3 {
        self.sample(primary, point, stats, None)
    }

    /// The same sample, writing down every vertex of the path when `log` is given.
    pub fn sample(
        &self,
        primary: &Ray,
        point: &SamplePoint,
        stats: &mut Stats,
        log: Option<&mut Vec<PathVertex>>,
    ) -> DVec3 {
        let mut log = PathLog(log);
        let scene = self.scene;
        let mut ray = *primary;
        let mut throughput = DVec3::ONE;
        let mut sum = DVec3::ZERO;
        // Density of the BSDF sample that produced `ray` (for MIS), or None after a specular
        // bounce or for the camera ray, which light sampling could not have produced.
        let mut bsdf_pdf: Option<f64> = None;
        stats.primary_rays += 1;
        for depth in 0..self.max_depth {
            let bounce = Bounce { point, depth };
            let before = sum;
            let hit = self.search.nearest(&ray, 0.0, f64::INFINITY, stats);
            let t_hit = hit.map_or(f64::INFINITY, |h| h.t);
            // Where the path is now: on an emitter (which may reflect too) or an object.
            let (si, object) = if let Some(lh) = self.light_hit(&ray, t_hit) {
                let weight = match bsdf_pdf {
                    Some(p) if self.next_event => power_heuristic(p, lh.pdf),
                    _ => 1.0,
                };
                sum += throughput * lh.light.intensity * weight;
                let point = ray.at(lh.t);
                log.at(
                    "light",
                    Some(&lh.light.name),
                    point,
                    throughput,
                    sum - before,
                );
                let Some(material) = lh.light.surface else {
                    break;
                };
                // The light is no object: only point, normal and material are read below.
                let si = Interaction {
                    point,
                    normal: lh.normal,
                    inside: false,
                    leaf: 0,
                    face: 0,
                    object: 0,
                    material,
                    paint: scene.material(material).paint(),
                    origin_size: ray.origin.abs().max_element(),
                };
                (si, lh.light.name.as_str())
            } else {
                let Some(hit) = hit else {
                    sum += throughput * scene.background;
                    log.leaving(&ray, throughput, sum - before);
                    break;
                };
                let si = scene.interaction(&ray, &hit);
                sum += throughput * scene.material(si.material).emission;
                (si, scene.objects[si.object as usize].name.as_str())
            };
            let m = scene.material(si.material);

            // Choose a lobe in proportion to its weight.
            let at = si.paint;
            let diffuse = at.kd * at.color;
            let weights = [diffuse.max_element(), at.kr, at.kt];
            let total: f64 = weights.iter().sum();
            if total <= 0.0 || depth + 1 >= self.max_depth {
                let why = if total <= 0.0 {
                    "absorbed"
                } else {
                    "max_depth"
                };
                if why == "max_depth" && self.local_at_max_depth {
                    // Seed 002: the path "contributes just its local illumination".
                    let p = si.point + scene.bias(ray.origin, si.point) * si.normal;
                    sum += throughput * diffuse * self.local(p, si.normal, bounce, stats);
                }
                log.at(why, Some(object), si.point, throughput, sum - before);
                break;
            }
            // The lobe pair only where it decides something: between lobes, or for roulette.
            let lobes = weights.iter().filter(|&&w| w > 0.0).count();
            let roulette = self.roulette && depth >= 3;
            let [pick, survive] = if lobes > 1 || roulette {
                self.draw(bounce, Draw::Lobe)
            } else {
                [0.5, 0.5]
            };
            let pick = pick * total;
            let n = si.normal;
            let offset = scene.bias(ray.origin, si.point);
            if pick < weights[0] {
                // Lambertian: f = albedo/π. Next-event estimation first, then a cosine sample
                // (f·cos/pdf = albedo).
                let lobe = throughput * diffuse * (total / weights[0]);
                if self.next_event {
                    sum += lobe * self.direct(si.point + offset * n, n, bounce, stats);
                }
                let [u1, u2] = self.draw(bounce, Draw::Direction);
                let dir = cosine_hemisphere(n, u1, u2);
                bsdf_pdf = Some(cosine_pdf(n, dir));
                throughput = lobe;
                log.at("diffuse", Some(object), si.point, throughput, sum - before);
                ray = Ray {
                    origin: si.point + offset * n,
                    dir,
                };
                stats.reflection_rays += 1;
            } else if pick < weights[0] + weights[1] {
                throughput *= at.kr * (total / weights[1]);
                bsdf_pdf = None;
                let mirror = reflect(ray.dir, n);
                let [u1, u2] = self.draw(bounce, Draw::Direction);
                let dir = match m.glossy {
                    None => mirror,
                    Some(l) => spread(l.shape, mirror, n, u1, u2),
                };
                let event = if m.glossy.is_some() {
                    "glossy"
                } else {
                    "mirror"
                };
                log.at(event, Some(object), si.point, throughput, sum - before);
                ray = Ray {
                    origin: si.point + offset * n,
                    dir,
                };
                stats.reflection_rays += 1;
            } else {
                throughput *= at.kt * (total / weights[2]);
                bsdf_pdf = None;
                let (n1, n2) = if si.inside {
                    (m.ior, 1.0)
                } else {
                    (1.0, m.ior)
                };
                let r = schlick(-ray.dir.dot(n), n1, n2);
                let [fresnel, _] = self.draw(bounce, Draw::Fresnel);
                let refracted = refract(ray.dir, n, n1, n2).filter(|_| fresnel >= r);
                let event = if refracted.is_some() {
                    "refraction"
                } else {
                    "reflection"
                };
                log.at(event, Some(object), si.point, throughput, sum - before);
                // A frosted face spreads the light it turns back (Fresnel's share, or all of
                // it past the limiting angle) as it spreads the light it lets through.
                let frosted = |principal: DVec3| match m.frosted {
                    None => principal,
                    Some(l) => {
                        let [u1, u2] = self.draw(bounce, Draw::Direction);
                        spread(l.shape, principal, n, u1, u2)
                    }
                };
                ray = match refracted {
                    Some(dir) => {
                        stats.refraction_rays += 1;
                        Ray {
                            origin: si.point - offset * n,
                            dir: frosted(dir),
                        }
                    }
                    None => {
                        stats.reflection_rays += 1;
                        Ray {
                            origin: si.point + offset * n,
                            dir: frosted(reflect(ray.dir, n)),
                        }
                    }
                };
            }
            if roulette {
                let q = throughput.max_element().clamp(0.05, 0.95);
                if survive >= q {
                    log.at("roulette", None, ray.origin, DVec3::ZERO, DVec3::ZERO);
                    break;
                }
                throughput /= q;
            }
        }
        sum
    }

    /// Light arriving directly from the area lights at p, per unit albedo (i.e. the integral of
    /// Le·cos/π), one sample per light, weighted against BSDF sampling.
    fn direct(&self, p: DVec3, n: DVec3, at: Bounce, stats: &mut Stats) -> DVec3 {
        self.lights_at(p, n, at, stats, true)
    }

    /// The direct light at the last surface of a path cut by the maximum depth, per unit
    /// albedo: one light sample per light, unweighted, since no bounce follows to find the
    /// lights the other way.
    fn local(&self, p: DVec3, n: DVec3, at: Bounce, stats: &mut Stats) -> DVec3 {
        self.lights_at(p, n, at, stats, false)
    }

    /// One sample of the light arriving from each area light at p, per unit albedo; with
    /// `mis`, weighted against the BSDF sample that follows (power heuristic).
    fn lights_at(&self, p: DVec3, n: DVec3, at: Bounce, stats: &mut Stats, mis: bool) -> DVec3 {
        let mut sum = DVec3::ZERO;
        for (i, light) in self.scene.lights.iter().enumerate() {
            let [u1, u2] = self.draw(at, Draw::Light(i));
            let Some(e) = light.sample_emitter(p, u1, u2) else {
                continue;
            };
            let cos_s = n.dot(e.wi);
            if cos_s <= 0.0 {
                continue;
            }
            stats.shadow_rays += 1;
            let shadow = Ray {
                origin: p,
                dir: e.wi,
            };
            if self
                .search
                .blocker(&shadow, 0.0, e.distance * (1.0 - 1e-9), stats)
                .is_some()
            {
                continue;
            }
            let weight = if mis {
                power_heuristic(e.pdf, cosine_pdf(n, e.wi))
            } else {
                1.0
            };
            sum += light.intensity * (cos_s / PI) / e.pdf * weight;
        }
        sum
    }
}
