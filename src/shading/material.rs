//! Materials: the coefficients of the lecture's illumination model.

use glam::DVec3;
use serde::Serialize;

use super::Lobe;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Highlight {
    /// (h·n)^m with the half vector h = (l + v)/|l + v| (seed 004).
    #[default]
    Blinn,
    /// (r·v)^m with r the mirror direction of l (seed 003).
    Phong,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Fresnel {
    #[default]
    None,
    /// Schlick's approximation R = R0 + (1 − R0)(1 − cos θ)^5 weights kr by R and kt by 1 − R.
    Schlick,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    pub name: String,
    /// O, the object's colour.
    pub color: DVec3,
    pub ka: f64,
    pub kd: f64,
    pub ks: f64,
    /// The specular exponent m.
    pub shininess: f64,
    pub highlight: Highlight,
    pub kr: f64,
    pub kt: f64,
    pub ior: f64,
    pub fresnel: Fresnel,
    /// Hall's transmitted highlight: a light behind the (transparent) surface makes a
    /// highlight with H′ in place of H (seed 004, "direct specular transmission").
    pub transmitted_highlight: bool,
    /// Light emitted by the surface (used by the path tracer).
    pub emission: DVec3,
    /// Glossy reflection: the reflection ray becomes n rays drawn from this lobe.
    pub glossy: Option<Lobe>,
    /// Frosted refraction: the refraction ray becomes n rays drawn from this lobe.
    pub frosted: Option<Lobe>,
}

impl Material {
    pub fn matte(name: &str, color: DVec3) -> Material {
        Material {
            name: name.into(),
            color,
            ka: 0.0,
            kd: 1.0,
            ks: 0.0,
            shininess: 1.0,
            highlight: Highlight::Blinn,
            kr: 0.0,
            kt: 0.0,
            ior: 1.0,
            fresnel: Fresnel::None,
            transmitted_highlight: false,
            emission: DVec3::ZERO,
            glossy: None,
            frosted: None,
        }
    }

    pub fn reflective(&self) -> bool {
        self.kr > 0.0
    }

    pub fn transparent(&self) -> bool {
        self.kt > 0.0
    }

    /// Whether shading it draws random numbers: a glossy or frosted lobe sends sampled rays.
    pub fn sampled(&self) -> bool {
        self.glossy.is_some() || self.frosted.is_some()
    }
}
