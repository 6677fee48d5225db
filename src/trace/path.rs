//! The path tracer (seed 002): one random path per sample, diffuse bounces sampled by cos θ/π,
//! perfect mirrors and glass, emitters, Russian roulette, and next-event estimation on area
//! lights combined with BSDF sampling by multiple importance sampling (power heuristic).
//!
//! The same materials are read physically: diffuse albedo kd·O, mirror reflectance kr,
//! transmission kt with ior, `emission` for glowing surfaces, the background as a uniform
//! environment, rectangle lights as emitters of radiance `intensity`.

use std::f64::consts::PI;

use glam::DVec3;

use super::sampling::{cosine_hemisphere, cosine_pdf, rectangle, Rng};
use super::Stats;
use crate::geometry::Ray;
use crate::scene::Scene;
use crate::shading::optics::{reflect, refract, schlick};
use crate::shading::Light;

pub struct PathTracer<'s> {
    pub scene: &'s Scene,
    /// Path segments at most (the primary ray counts).
    pub max_depth: u32,
    /// Sample the lights directly at diffuse hits (off only to test that it changes nothing).
    pub next_event: bool,
    /// Stop paths at random, unbiasedly, after three bounces (off only for tests).
    pub roulette: bool,
}

/// One vertex of a recorded path, for `inspect` on a path-traced pixel.
#[derive(Clone, Debug, serde::Serialize)]
pub struct PathVertex {
    /// What happened here: light, background, diffuse, mirror, refraction, reflection,
    /// absorbed (no lobe), max_depth, roulette.
    pub event: &'static str,
    /// The object (or light) met.
    pub object: Option<String>,
    pub point: DVec3,
    /// The path's throughput after this vertex.
    pub throughput: DVec3,
    /// Radiance this vertex added to the estimate (emission, next-event estimation, a light or
    /// the background reached).
    pub added: DVec3,
}

/// Where a ray meets an area light: distance, the light, its unit normal and area.
struct LightHit<'a> {
    t: f64,
    light: &'a Light,
    normal: DVec3,
    area: f64,
}

/// The power heuristic for two strategies (β = 2).
fn power_heuristic(a: f64, b: f64) -> f64 {
    let (a2, b2) = (a * a, b * b);
    if a2 + b2 == 0.0 {
        0.0
    } else {
        a2 / (a2 + b2)
    }
}

impl<'s> PathTracer<'s> {
    pub fn new(scene: &'s Scene, max_depth: u32) -> PathTracer<'s> {
        PathTracer {
            scene,
            max_depth,
            next_event: true,
            roulette: true,
        }
    }

    /// The nearest front face of an area light the ray meets before t_max.
    fn light_hit(&self, ray: &Ray, t_max: f64) -> Option<LightHit<'s>> {
        let mut best: Option<LightHit> = None;
        for light in &self.scene.lights {
            let Some((corner, u, v, n, area)) = light.rect() else {
                continue;
            };
            let facing = ray.dir.dot(n);
            if facing >= 0.0 {
                continue; // lights emit on one side only
            }
            let t = (corner - ray.origin).dot(n) / facing;
            if t <= 0.0 || t >= best.as_ref().map_or(t_max, |b| b.t) {
                continue;
            }
            let q = ray.at(t) - corner;
            let (a, b) = (q.dot(u) / u.length_squared(), q.dot(v) / v.length_squared());
            if (0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b) {
                best = Some(LightHit {
                    t,
                    light,
                    normal: n,
                    area,
                });
            }
        }
        best
    }

    /// One sample of the radiance arriving along a primary ray.
    pub fn radiance(&self, primary: &Ray, rng: &mut Rng, stats: &mut Stats) -> DVec3 {
        self.sample(primary, rng, stats, None)
    }

    /// The same sample, writing down every vertex of the path when `log` is given.
    pub fn sample(
        &self,
        primary: &Ray,
        rng: &mut Rng,
        stats: &mut Stats,
        mut log: Option<&mut Vec<PathVertex>>,
    ) -> DVec3 {
        let mut note = |event: &'static str,
                        object: Option<&str>,
                        point: DVec3,
                        throughput: DVec3,
                        added: DVec3| {
            if let Some(log) = log.as_deref_mut() {
                log.push(PathVertex {
                    event,
                    object: object.map(str::to_string),
                    point,
                    throughput,
                    added,
                });
            }
        };
        let scene = self.scene;
        let mut ray = *primary;
        let mut throughput = DVec3::ONE;
        let mut sum = DVec3::ZERO;
        // Density of the BSDF sample that produced `ray` (for MIS), or None after a specular
        // bounce or for the camera ray, which light sampling could not have produced.
        let mut bsdf_pdf: Option<f64> = None;
        stats.primary_rays += 1;
        for depth in 0..self.max_depth {
            let before = sum;
            let hit = scene.intersect(&ray, 0.0, f64::INFINITY, stats);
            let t_hit = hit.map_or(f64::INFINITY, |h| h.t);
            if let Some(lh) = self.light_hit(&ray, t_hit) {
                let weight = match bsdf_pdf {
                    Some(p) if self.next_event => {
                        let cos_l = -ray.dir.dot(lh.normal);
                        power_heuristic(p, lh.t * lh.t / (cos_l * lh.area))
                    }
                    _ => 1.0,
                };
                sum += throughput * lh.light.intensity * weight;
                note(
                    "light",
                    Some(&lh.light.name),
                    ray.at(lh.t),
                    throughput,
                    sum - before,
                );
                break;
            }
            let Some(hit) = hit else {
                sum += throughput * scene.background;
                note("background", None, ray.at(1.0), throughput, sum - before);
                break;
            };
            let si = scene.interaction(&ray, &hit);
            let m = scene.material(si.material);
            sum += throughput * m.emission;

            // Choose a lobe in proportion to its weight.
            let diffuse = m.kd * m.color;
            let weights = [diffuse.max_element(), m.kr, m.kt];
            let total: f64 = weights.iter().sum();
            let object = &scene.objects[si.object as usize].name;
            if total <= 0.0 || depth + 1 >= self.max_depth {
                let why = if total <= 0.0 {
                    "absorbed"
                } else {
                    "max_depth"
                };
                note(why, Some(object), si.point, throughput, sum - before);
                break;
            }
            let pick = rng.uniform() * total;
            let n = si.normal;
            let offset = scene.bias(ray.origin, si.point);
            if pick < weights[0] {
                // Lambertian: f = albedo/π. Next-event estimation first, then a cosine sample
                // (f·cos/pdf = albedo).
                let lobe = throughput * diffuse * (total / weights[0]);
                if self.next_event {
                    sum += lobe * self.direct(si.point + offset * n, n, rng, stats);
                }
                let dir = cosine_hemisphere(n, rng.uniform(), rng.uniform());
                bsdf_pdf = Some(cosine_pdf(n, dir));
                throughput = lobe;
                note("diffuse", Some(object), si.point, throughput, sum - before);
                ray = Ray {
                    origin: si.point + offset * n,
                    dir,
                };
                stats.reflection_rays += 1;
            } else if pick < weights[0] + weights[1] {
                throughput *= m.kr * (total / weights[1]);
                bsdf_pdf = None;
                note("mirror", Some(object), si.point, throughput, sum - before);
                ray = Ray {
                    origin: si.point + offset * n,
                    dir: reflect(ray.dir, n),
                };
                stats.reflection_rays += 1;
            } else {
                throughput *= m.kt * (total / weights[2]);
                bsdf_pdf = None;
                let (n1, n2) = if si.inside {
                    (m.ior, 1.0)
                } else {
                    (1.0, m.ior)
                };
                let r = schlick(-ray.dir.dot(n), n1, n2);
                let refracted = refract(ray.dir, n, n1, n2).filter(|_| rng.uniform() >= r);
                let event = if refracted.is_some() {
                    "refraction"
                } else {
                    "reflection"
                };
                note(event, Some(object), si.point, throughput, sum - before);
                ray = match refracted {
                    Some(dir) => {
                        stats.refraction_rays += 1;
                        Ray {
                            origin: si.point - offset * n,
                            dir,
                        }
                    }
                    None => {
                        stats.reflection_rays += 1;
                        Ray {
                            origin: si.point + offset * n,
                            dir: reflect(ray.dir, n),
                        }
                    }
                };
            }
            if self.roulette && depth >= 3 {
                let q = throughput.max_element().clamp(0.05, 0.95);
                if rng.uniform() >= q {
                    note("roulette", None, ray.origin, DVec3::ZERO, DVec3::ZERO);
                    break;
                }
                throughput /= q;
            }
        }
        sum
    }

    /// Light arriving directly from the area lights at p, per unit albedo (i.e. the integral of
    /// Le·cos/π), one sample per light, weighted against BSDF sampling.
    fn direct(&self, p: DVec3, n: DVec3, rng: &mut Rng, stats: &mut Stats) -> DVec3 {
        let mut sum = DVec3::ZERO;
        for light in &self.scene.lights {
            let Some((corner, u, v, ln, area)) = light.rect() else {
                continue;
            };
            let q = rectangle(corner, u, v, rng.uniform(), rng.uniform());
            let to = q - p;
            let dist = to.length();
            let wi = to / dist;
            let (cos_s, cos_l) = (n.dot(wi), -ln.dot(wi));
            if cos_s <= 0.0 || cos_l <= 0.0 {
                continue;
            }
            stats.shadow_rays += 1;
            if self
                .scene
                .occluded(&Ray { origin: p, dir: wi }, 0.0, dist * (1.0 - 1e-9), stats)
                .is_some()
            {
                continue;
            }
            let light_pdf = dist * dist / (cos_l * area);
            let weight = power_heuristic(light_pdf, cosine_pdf(n, wi));
            sum += light.intensity * (cos_s / PI) / light_pdf * weight;
        }
        sum
    }
}
