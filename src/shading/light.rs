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
        }
    }

    pub fn is_dark(&self) -> bool {
        self.intensity == DVec3::ZERO
    }
}
