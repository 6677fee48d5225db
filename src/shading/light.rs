//! Light sources.

use glam::DVec3;

#[derive(Clone, Debug, PartialEq)]
pub enum LightKind {
    /// A point light at a position, dimmed by fatt = 1/(c0 + c1·d + c2·d²).
    Point {
        position: DVec3,
        attenuation: [f64; 3],
    },
    /// Parallel light travelling along `direction` (unit), from infinitely far away.
    Directional { direction: DVec3 },
    /// A rectangle `corner + a·u + b·v` (0 ≤ a, b ≤ 1) emitting from the side of u × v.
    /// Whitted shading treats it as a point light at its centre whose shadow factor is the
    /// fraction of `samples × samples` points on it that are visible (soft shadows); the path
    /// tracer samples it as an area emitter of radiance `intensity`.
    Rect {
        corner: DVec3,
        u: DVec3,
        v: DVec3,
        samples: u32,
    },
}

#[derive(Clone, Debug, PartialEq)]
pub struct Light {
    pub name: String,
    pub kind: LightKind,
    /// Iℓ
    pub intensity: DVec3,
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

impl Light {
    pub fn sample(&self, p: DVec3) -> LightSample {
        match &self.kind {
            LightKind::Point {
                position,
                attenuation: [c0, c1, c2],
            } => {
                let to_light = *position - p;
                let d = to_light.length();
                LightSample {
                    l: to_light / d,
                    distance: d,
                    attenuation: 1.0 / (c0 + c1 * d + c2 * d * d),
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
                LightSample {
                    l: to_light / d,
                    distance: d,
                    attenuation: 1.0,
                }
            }
        }
    }

    /// How many shadow rays a shaded point sends to this light: 1, or n × n for an area light.
    pub fn shadow_rays(&self) -> u32 {
        match &self.kind {
            LightKind::Rect { samples, .. } => samples.max(&1).pow(2),
            _ => 1,
        }
    }

    /// Target k of an area light's shadow rays: the centre of stratum k of its n × n grid
    /// (deterministic, so soft shadows need no random numbers). None for other lights.
    pub fn shadow_point(&self, k: u32) -> Option<DVec3> {
        match &self.kind {
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
            _ => None,
        }
    }

    /// The rectangle of an area light: (corner, u, v, unit normal, area).
    pub fn rect(&self) -> Option<(DVec3, DVec3, DVec3, DVec3, f64)> {
        match &self.kind {
            LightKind::Rect { corner, u, v, .. } => {
                let n = u.cross(*v);
                Some((*corner, *u, *v, n.normalize(), n.length()))
            }
            _ => None,
        }
    }

    pub fn is_dark(&self) -> bool {
        self.intensity == DVec3::ZERO
    }
}
