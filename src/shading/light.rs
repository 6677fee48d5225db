//! Light sources.

use glam::DVec3;

use crate::sampling::sin_cos;

/// What kind of emitter a light is, with where it sits and how it falls off.
#[derive(Clone, Debug, PartialEq)]
pub enum LightKind {
    /// A point light at a position, dimmed by fatt = 1/(c0 + c1·d + c2·d²).
    Point {
        /// Where the light is, world space.
        position: DVec3,
        /// The attenuation coefficients [c0, c1, c2] of fatt = 1/(c0 + c1·d + c2·d²), d the
        /// distance to the light.
        attenuation: [f64; 3],
    },
    /// Parallel light travelling along `direction` (unit), from infinitely far away.
    Directional {
        /// Unit direction the light travels in (from the light towards the scene), world space.
        direction: DVec3,
    },
    /// A rectangle `corner + a·u + b·v` (0 ≤ a, b ≤ 1) emitting from the side of u × v.
    /// Whitted shading treats it as a point light at its centre whose shadow factor is the
    /// fraction of `samples × samples` points on it that are visible (soft shadows); the path
    /// tracer samples it as an area emitter of radiance `intensity`.
    Rect {
        /// One corner of the rectangle, world space.
        corner: DVec3,
        /// First edge from `corner` (its length is the side's length).
        u: DVec3,
        /// Second edge from `corner`.
        v: DVec3,
        /// Shadow rays per side: `samples × samples` points on the rectangle (1 gives a hard
        /// shadow).
        samples: u32,
    },
    /// A glowing ball. Whitted shading treats it as a point light at its centre (with the
    /// point light's attenuation) whose shadow factor is the fraction of `samples × samples`
    /// points on the disc it shows the shaded point that are visible; the path tracer samples
    /// it as an emitter of radiance `intensity`.
    Sphere {
        /// Centre of the ball, world space.
        center: DVec3,
        /// Radius of the ball, in scene units.
        radius: f64,
        /// The attenuation coefficients [c0, c1, c2] of fatt = 1/(c0 + c1·d + c2·d²), d the
        /// distance to the centre.
        attenuation: [f64; 3],
        /// Shadow rays per side: `samples × samples` points on the visible disc.
        samples: u32,
    },
}

/// Where a ray meets an emitter, and the density with which light sampling would have chosen
/// that direction (per solid angle, seen from the ray's origin).
pub struct EmitterHit {
    pub t: f64,
    pub pdf: f64,
    /// The emitter's unit normal at the hit, facing the ray.
    pub normal: DVec3,
}

/// A direction toward an emitter chosen by light sampling.
pub struct EmitterSample {
    pub wi: DVec3,
    pub distance: f64,
    /// Density per solid angle.
    pub pdf: f64,
}

/// A light source ℓ of the scene: its kind and its intensity Iℓ.
#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    /// Name in the scene file (or a generated one), for the ray tree and messages.
    pub name: String,
    /// Point, directional, rectangle or sphere, with its placement.
    pub kind: LightKind,
    /// Iℓ
    pub intensity: DVec3,
    /// Path tracer: the material of an area light's surface (it reflects as well as emits).
    pub surface: Option<u32>,
}

/// What a surface point sees of a light.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// Unit vector from the point towards the light.
    pub l: DVec3,
    /// Distance to the light (∞ for a directional light): a shadow ray is blocked by hits
    /// with 0 < t < distance.
    pub distance: f64,
    /// fatt
    pub attenuation: f64,
}

impl LightSample {
    /// A light exactly at the shaded point (d = 0), or so near it that c0 + c1·d + c2·d²
    /// rounds to 0. There l = (light − p)/d is undefined and fatt = 1/(c1·d + c2·d²) infinite,
    /// so the light's share is taken as its limit along a flat surface through the light,
    /// where l lies in the surface and n·l = 0: the light adds nothing at that point (its
    /// diffuse and specular terms are 0, and no shadow ray is cast, as for n·l ≤ 0).
    pub const AT_THE_POINT: LightSample = LightSample {
        l: DVec3::ZERO,
        distance: 0.0,
        attenuation: 0.0,
    };
}

impl Light {
    /// What the point p sees of the light: l, the distance d and fatt (see
    /// `LightSample::AT_THE_POINT` for a light at p itself).
    #[inline]
    pub fn sample(&self, p: DVec3) -> LightSample {
        match &self.kind {
            LightKind::Point {
                position,
                attenuation: [c0, c1, c2],
            }
            | LightKind::Sphere {
                center: position,
                attenuation: [c0, c1, c2],
                ..
            } => {
                let to_light = *position - p;
                let d = to_light.length();
                let attenuation = 1.0 / (c0 + c1 * d + c2 * d * d);
                if d == 0.0 || !attenuation.is_finite() {
                    return LightSample::AT_THE_POINT;
                }
                LightSample {
                    // l = (light − p)/d, as (light − p)·(1/d): one division, not three.
                    l: to_light * (1.0 / d),
                    distance: d,
                    attenuation,
                }
            }
            LightKind::Directional { direction } => LightSample {
                l: -*direction,
                distance: f64::INFINITY,
                attenuation: 1.0,
            },
            LightKind::Rect { corner, u, v, .. } => {
                let to_light = *corner + 0.5 * (*u + *v) - p;
                let d = to_light.length();
                if d == 0.0 {
                    return LightSample::AT_THE_POINT;
                }
                // A rectangle emits on the side of u × v only: seen from behind, or edge on,
                // it sends the point nothing (fatt = 0).
                let in_front = (p - *corner).dot(u.cross(*v)) > 0.0;
                LightSample {
                    l: to_light * (1.0 / d),
                    distance: d,
                    attenuation: if in_front { 1.0 } else { 0.0 },
                }
            }
        }
    }

    /// How many shadow rays a shaded point sends to this light: 1, or n × n for an area light.
    #[inline]
    pub fn shadow_rays(&self) -> u32 {
        match &self.kind {
            LightKind::Rect { samples, .. } | LightKind::Sphere { samples, .. } => {
                samples.max(&1).pow(2)
            }
            _ => 1,
        }
    }

    /// Target k of an area light's shadow rays from the point p: the centre of stratum k of
    /// an n × n grid on the rectangle, or on the disc the sphere shows p (mapped by Shirley
    /// and Chiu's concentric map). Deterministic, so soft shadows need no random numbers.
    /// None for point and directional lights.
    #[inline]
    pub fn shadow_point(&self, k: u32, p: DVec3) -> Option<DVec3> {
        match &self.kind {
            LightKind::Point { .. } | LightKind::Directional { .. } => None,
            LightKind::Sphere {
                center,
                radius,
                samples,
                ..
            } => {
                let n = (*samples).max(1);
                let step = 1.0 / n as f64;
                let (a, b) = (((k % n) as f64 + 0.5) * step, ((k / n) as f64 + 0.5) * step);
                let (dx, dy) = concentric_disc(a, b);
                let axis = (*center - p).try_normalize().unwrap_or(DVec3::Z);
                let (t, bt) = crate::sampling::basis(axis);
                Some(*center + *radius * (dx * t + dy * bt))
            }
            LightKind::Rect {
                corner,
                u,
                v,
                samples,
            } => {
                let n = (*samples).max(1);
                let step = 1.0 / n as f64;
                Some(
                    *corner
                        + ((k % n) as f64 + 0.5) * step * *u
                        + ((k / n) as f64 + 0.5) * step * *v,
                )
            }
        }
    }

    /// The emitter a path can hit: the front of a rectangle, or a sphere light.
    pub fn emitter_hit(&self, ray: &crate::geometry::Ray, t_max: f64) -> Option<EmitterHit> {
        match &self.kind {
            LightKind::Rect { corner, u, v, .. } => {
                let normal = u.cross(*v);
                let area = normal.length();
                let n = normal / area;
                let facing = ray.dir.dot(n);
                if facing >= 0.0 {
                    return None; // a rectangle emits on one side only
                }
                let t = (*corner - ray.origin).dot(n) / facing;
                if t <= 0.0 || t >= t_max {
                    return None;
                }
                let q = ray.at(t) - *corner;
                let (a, b) = (
                    q.dot(*u) / u.length_squared(),
                    q.dot(*v) / v.length_squared(),
                );
                ((0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b)).then(|| EmitterHit {
                    t,
                    normal: n,
                    // Area density 1/A turned into solid angle: d²/(cos θ_l · A).
                    pdf: t * t / (-facing * area),
                })
            }
            LightKind::Sphere { center, radius, .. } => {
                let oc = ray.origin - *center;
                let b = oc.dot(ray.dir);
                let c = oc.length_squared() - radius * radius;
                let disc = b * b - c;
                if disc < 0.0 || c <= 0.0 {
                    return None; // missed, or the path starts inside the light
                }
                let t = -b - disc.sqrt();
                (t > 0.0 && t < t_max).then(|| EmitterHit {
                    t,
                    normal: (oc + t * ray.dir) / *radius,
                    pdf: cone_pdf(*radius, oc.length()),
                })
            }
            _ => None,
        }
    }

    /// Light sampling from p: a point on a rectangle uniform in area, or a direction in the
    /// cone a sphere subtends, uniform in solid angle.
    pub fn sample_emitter(&self, p: DVec3, u1: f64, u2: f64) -> Option<EmitterSample> {
        match &self.kind {
            LightKind::Rect { corner, u, v, .. } => {
                let normal = u.cross(*v);
                let area = normal.length();
                let q = crate::sampling::rectangle(*corner, *u, *v, u1, u2);
                let to = q - p;
                let distance = to.length();
                let wi = to / distance;
                let cos_l = -(normal / area).dot(wi);
                (cos_l > 0.0).then(|| EmitterSample {
                    wi,
                    distance,
                    pdf: distance * distance / (cos_l * area),
                })
            }
            LightKind::Sphere { center, radius, .. } => {
                let to = *center - p;
                let d = to.length();
                let spread = one_minus_cos_max(*radius, d);
                if d <= *radius || spread == 0.0 {
                    // Inside the light, or the light so small from here that the cone it
                    // subtends is below what f64 can hold (its density would be 1/0).
                    return None;
                }
                let cos_theta = 1.0 - u1 * spread;
                let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
                let (sin_phi, cos_phi) = sin_cos(2.0 * std::f64::consts::PI * u2);
                let axis = to / d;
                let (t, b) = crate::sampling::basis(axis);
                let wi = (sin_theta * cos_phi * t + sin_theta * sin_phi * b + cos_theta * axis)
                    .normalize();
                // Where that direction meets the sphere (the near root).
                let bq = -to.dot(wi);
                let disc = (bq * bq - (d * d - radius * radius)).max(0.0);
                Some(EmitterSample {
                    wi,
                    distance: -bq - disc.sqrt(),
                    pdf: cone_pdf(*radius, d),
                })
            }
            _ => None,
        }
    }

    /// Whether Iℓ = 0: the light adds nothing and needs no shadow rays.
    pub fn is_dark(&self) -> bool {
        self.intensity == DVec3::ZERO
    }
}

/// The density of directions uniform in the cone a sphere of radius r subtends from distance d:
/// 1 / (2π (1 − cos θmax)).
fn cone_pdf(r: f64, d: f64) -> f64 {
    1.0 / (2.0 * std::f64::consts::PI * one_minus_cos_max(r, d))
}

/// 1 − cos θmax = 1 − √(1 − (r/d)²), written so that it does not cancel to 0 for a small or
/// distant sphere.
fn one_minus_cos_max(r: f64, d: f64) -> f64 {
    let s2 = (r / d).powi(2).min(1.0);
    s2 / (1.0 + (1.0 - s2).sqrt())
}

/// Shirley and Chiu's concentric map of the unit square onto the unit disc (keeps strata
/// compact, so a grid on the square becomes rings of even area on the disc).
fn concentric_disc(a: f64, b: f64) -> (f64, f64) {
    let (x, y) = (2.0 * a - 1.0, 2.0 * b - 1.0);
    if x == 0.0 && y == 0.0 {
        return (0.0, 0.0);
    }
    let quarter = std::f64::consts::FRAC_PI_4;
    let (r, theta) = if x.abs() > y.abs() {
        (x, quarter * (y / x))
    } else {
        (y, 2.0 * quarter - quarter * (x / y))
    };
    let (sin, cos) = sin_cos(theta);
    (r * cos, r * sin)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::{basis, Rng};
    use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_8};

    fn ball() -> Light {
        Light {
            name: "ball".into(),
            kind: LightKind::Sphere {
                center: DVec3::new(1.0, 3.0, -2.0),
                radius: 0.8,
                attenuation: [1.0, 0.0, 0.0],
                samples: 1,
            },
            intensity: DVec3::ONE,
            surface: None,
        }
    }

    /// Chi-square goodness of fit of sphere-light sampling: directions must be uniform in the
    /// cone the sphere subtends, so (1 − cos θ)/(1 − cos θmax) and φ are uniform.
    #[test]
    fn sphere_light_sampling_passes_chi_square() {
        let light = ball();
        let p = DVec3::new(0.2, -0.5, 0.3);
        let LightKind::Sphere { center, radius, .. } = light.kind else {
            unreachable!()
        };
        let axis = (center - p).normalize();
        let d = (center - p).length();
        let cos_max = (1.0 - (radius / d).powi(2)).sqrt();
        let (t, b) = basis(axis);
        let (nt, np, samples) = (10usize, 12usize, 120_000usize);
        let mut counts = vec![0f64; nt * np];
        let mut rng = Rng::for_pixel(4, 5, 6);
        for _ in 0..samples {
            let e = light
                .sample_emitter(p, rng.uniform(), rng.uniform())
                .unwrap();
            // The sampled point lies on the sphere, and the density is the cone's.
            let q = p + e.distance * e.wi;
            assert!(((q - center).length() - radius).abs() < 1e-9);
            assert!((e.pdf * 2.0 * std::f64::consts::PI * (1.0 - cos_max) - 1.0).abs() < 1e-9);
            let u = (1.0 - e.wi.dot(axis)) / (1.0 - cos_max);
            let phi =
                e.wi.dot(b)
                    .atan2(e.wi.dot(t))
                    .rem_euclid(2.0 * std::f64::consts::PI);
            let i = ((u * nt as f64) as usize).min(nt - 1);
            let j = ((phi / (2.0 * std::f64::consts::PI) * np as f64) as usize).min(np - 1);
            counts[i * np + j] += 1.0;
        }
        let chi2 = crate::sampling::chi_square_uniform(&counts);
        // 119 degrees of freedom: the 99.9 % point is about 172.
        assert!(chi2 < 172.0, "chi² = {chi2}");
    }

    /// Shirley and Chiu's map, by hand: in the wedge |x| > |y| (x = 2a − 1, y = 2b − 1) the
    /// point goes to radius x at angle (π/4)·(y/x); otherwise to radius y at π/2 − (π/4)·(x/y).
    #[test]
    fn the_concentric_map_takes_squares_to_circles_and_their_edges_to_angles() {
        let close = |(x, y): (f64, f64), (u, v): (f64, f64)| (x - u).abs() + (y - v).abs() < 1e-15;
        let (c8, s8) = (FRAC_PI_8.cos(), FRAC_PI_8.sin());
        let h = FRAC_1_SQRT_2;
        for ((a, b), p) in [
            ((0.5, 0.5), (0.0, 0.0)),
            ((1.0, 0.5), (1.0, 0.0)),
            ((0.75, 0.5), (0.5, 0.0)),
            ((0.5, 1.0), (0.0, 1.0)),
            ((0.0, 0.5), (-1.0, 0.0)),
            ((0.5, 0.0), (0.0, -1.0)),
            ((1.0, 1.0), (h, h)),
            ((0.0, 0.0), (-h, -h)),
            ((1.0, 0.75), (c8, s8)),
            ((0.75, 1.0), (s8, c8)),
            ((0.0, 0.25), (-c8, -s8)),
            ((0.25, 0.0), (-s8, -c8)),
            ((0.75, 0.0), (s8, -c8)),
            ((0.75, 0.625), (0.5 * c8, 0.5 * s8)),
            ((0.625, 0.75), (0.5 * s8, 0.5 * c8)),
        ] {
            assert!(close(concentric_disc(a, b), p), "({a}, {b}) → {p:?}");
        }
        // The square of half side ρ around the centre goes onto the circle of radius ρ, so
        // equal areas stay equal: the inner square [¼, ¾]² (a quarter) onto the disc of radius ½.
        for k in 0..40 {
            let s = 0.25 + 0.5 * k as f64 / 40.0;
            for (a, b) in [(s, 0.25), (0.75, s), (s, 0.75), (0.25, s)] {
                let (x, y) = concentric_disc(a, b);
                assert!((x.hypot(y) - 0.5).abs() < 1e-15, "({a}, {b})");
            }
        }
    }

    /// A point light on the surface with fatt = 1/d: the limit along the surface is 0 (n·l = 0
    /// there), not ∞ · 0 = NaN.
    #[test]
    fn a_light_at_the_shaded_point_adds_nothing() {
        let on = DVec3::new(1.0, 0.0, 2.0);
        for attenuation in [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]] {
            let light = Light {
                name: "on".into(),
                kind: LightKind::Point {
                    position: on,
                    attenuation,
                },
                intensity: DVec3::ONE,
                surface: None,
            };
            let s = light.sample(on);
            assert_eq!((s.l, s.attenuation, s.distance), (DVec3::ZERO, 0.0, 0.0));
            // So near that c2·d² underflows: the same.
            let s = light.sample(on + DVec3::new(1e-200, 0.0, 0.0));
            assert!(s.l.is_finite() && s.attenuation.is_finite(), "{s:?}");
            // Near but not at it: the ordinary formula.
            let s = light.sample(on + DVec3::new(0.5, 0.0, 0.0));
            let c = attenuation;
            assert_eq!(s.attenuation, 1.0 / (c[0] + c[1] * 0.5 + c[2] * 0.25));
            assert_eq!(s.l, DVec3::new(-1.0, 0.0, 0.0));
        }
    }

    #[test]
    fn a_ray_at_a_sphere_light_finds_it_with_the_sampling_density() {
        let light = ball();
        let origin = DVec3::new(0.2, -0.5, 0.3);
        let mut rng = Rng::for_pixel(1, 2, 3);
        for _ in 0..100 {
            let e = light
                .sample_emitter(origin, rng.uniform(), rng.uniform())
                .unwrap();
            let ray = crate::geometry::Ray { origin, dir: e.wi };
            let hit = light.emitter_hit(&ray, f64::INFINITY).unwrap();
            assert!((hit.t - e.distance).abs() < 1e-9);
            assert!((hit.pdf - e.pdf).abs() < 1e-9 * e.pdf);
        }
    }

    /// Fuzzing finding (a mutated Cornell box): a sphere light of radius 1e−308 subtends a cone
    /// whose 1 − cos θmax underflows to 0, and its density 1/0 = ∞ made the path tracer's
    /// weights ∞/∞ = NaN. Such a light cannot be sampled: no sample, never an infinite density.
    #[test]
    fn a_sphere_light_too_small_to_subtend_a_cone_gives_no_sample() {
        let mut light = ball();
        if let LightKind::Sphere { radius, .. } = &mut light.kind {
            *radius = 1e-308;
        }
        let mut rng = Rng::for_pixel(0, 0, 0);
        for _ in 0..100 {
            let pdf = light
                .sample_emitter(DVec3::ZERO, rng.uniform(), rng.uniform())
                .map(|e| e.pdf);
            assert!(pdf.is_none_or(f64::is_finite), "{pdf:?}");
        }
    }
}
