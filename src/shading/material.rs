//! Materials: the coefficients of the lecture's illumination model. The colour O and the
//! coefficients kd, ks, kr, kt may vary over a surface (patterns, textures): what they are at
//! one point is its `Paint`, looked up once per shaded hit (`Scene::interaction`).

use glam::DVec3;
use serde::Serialize;

use super::pattern::{Pattern, PatternPoint};
use super::Lobe;

/// Which highlight term the local model uses: Blinn's (h·n)^m or Phong's (r·v)^m.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Highlight {
    /// (h·n)^m with the half vector h = (l + v)/|l + v| (seed 004).
    #[default]
    Blinn,
    /// (r·v)^m with r the mirror direction of l (seed 003).
    Phong,
}

impl Highlight {
    /// The model with its term: "Blinn's (h·n)^m", "Phong's (r·v)^m".
    pub fn name(self) -> &'static str {
        match self {
            Highlight::Blinn => "Blinn's (h·n)^m",
            Highlight::Phong => "Phong's (r·v)^m",
        }
    }
}

/// Whether kr and kt are weighted by the Fresnel reflectance.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, serde::Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Fresnel {
    /// kr and kt as given, whatever the angle (the notes' constant coefficients).
    #[default]
    None,
    /// Schlick's approximation R = R0 + (1 − R0)(1 − cos θ)^5 weights kr by R and kt by 1 − R.
    Schlick,
}

/// The surface properties of the local model and of Whitted's recursion.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Name in the scene file, for the ray tree and messages.
    pub name: String,
    /// O, the object's colour. For this and the coefficients kd, ks, kr and kt: the value
    /// everywhere, or, where a pattern varies it, the largest value the pattern takes.
    pub color: DVec3,
    /// Ambient coefficient ka: the ambient term is ka·Ia·O.
    pub ka: f64,
    /// Diffuse coefficient kd: Lambert's term kd·O·(n·l) per light.
    pub kd: f64,
    /// Specular coefficient ks: the highlight term ks·(h·n)^m per light.
    pub ks: f64,
    /// The specular exponent m.
    pub shininess: f64,
    /// Blinn's or Phong's highlight.
    pub highlight: Highlight,
    /// Reflection coefficient kr: the share of the reflected ray's intensity in this surface's
    /// (Whitted's kr·I_r).
    pub kr: f64,
    /// Transmission coefficient kt: the share of the refracted ray's intensity in this surface's
    /// (Whitted's kt·I_t).
    pub kt: f64,
    /// Index of refraction of the material (1 for vacuum, about 1.5 for glass), for Snell's law.
    pub ior: f64,
    /// Constant kr and kt, or weighted by Schlick's Fresnel term.
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
    /// The patterns that vary O, kd, ks, kr or kt over the surface; None (most materials) for
    /// the same values everywhere.
    pub patterns: Option<Box<Patterns>>,
}

/// What a pattern may vary, as it is at one point of a surface: the colour O and the
/// coefficients kd, ks, kr, kt.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Paint {
    /// The colour O at the point.
    pub color: DVec3,
    /// kd at the point.
    pub kd: f64,
    /// ks at the point.
    pub ks: f64,
    /// kr at the point.
    pub kr: f64,
    /// kt at the point.
    pub kt: f64,
}

impl Paint {
    /// Whether a surface painted so sends rays on: a reflection ray where kr > 0, a refraction
    /// ray where kt > 0.
    pub fn sends_rays(&self) -> bool {
        self.kr > 0.0 || self.kt > 0.0
    }
}

/// A material's patterns, one for each value that varies. A coefficient's pattern has grey
/// values: its first channel is the coefficient.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Patterns {
    /// The pattern of the colour O, if it varies.
    pub color: Option<Pattern>,
    /// The pattern of kd, if it varies.
    pub kd: Option<Pattern>,
    /// The pattern of ks, if it varies.
    pub ks: Option<Pattern>,
    /// The pattern of kr, if it varies.
    pub kr: Option<Pattern>,
    /// The pattern of kt, if it varies.
    pub kt: Option<Pattern>,
    /// Whether one of them reads the surface's own (u, v): found once (`Patterns::noting_uv`),
    /// not at every hit.
    uv: bool,
}

impl Patterns {
    /// The values at a point: each value with a pattern is the pattern's there; the others keep
    /// the constants `paint` holds.
    pub fn paint(&self, paint: &mut Paint, at: &PatternPoint) {
        // Written in place, field by field: a whole Paint returned and copied in would be read
        // back wide while its narrow stores are still on their way.
        if let Some(p) = &self.color {
            paint.color = p.value(at);
        }
        for (pattern, k) in [
            (&self.kd, &mut paint.kd),
            (&self.ks, &mut paint.ks),
            (&self.kr, &mut paint.kr),
            (&self.kt, &mut paint.kt),
        ] {
            if let Some(p) = pattern {
                *k = p.value(at).x;
            }
        }
    }

    /// The patterns with the name of what each varies, O first.
    pub fn named(&self) -> impl Iterator<Item = (&'static str, &Pattern)> {
        [
            ("O", &self.color),
            ("kd", &self.kd),
            ("ks", &self.ks),
            ("kr", &self.kr),
            ("kt", &self.kt),
        ]
        .into_iter()
        .filter_map(|(name, p)| p.as_ref().map(|p| (name, p)))
    }

    /// The patterns, noting whether one of them reads the surface's own (u, v).
    pub fn noting_uv(self) -> Patterns {
        let uv = self.named().any(|(_, p)| p.needs_uv());
        Patterns { uv, ..self }
    }

    /// Whether one of them reads the surface's own (u, v) (as `noting_uv` found).
    pub fn need_uv(&self) -> bool {
        self.uv
    }
}
impl Material {
    /// A diffuse material of colour O = `color` (kd = 1, nothing else) named `name`.
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
            patterns: None,
        }
    }

    /// The values of a material without patterns (the constants of one with them).
    #[inline(always)]
    pub fn paint(&self) -> Paint {
        Paint {
            color: self.color,
            kd: self.kd,
            ks: self.ks,
            kr: self.kr,
            kt: self.kt,
        }
    }

    /// Whether kr > 0: a hit spawns a reflection ray.
    pub fn reflective(&self) -> bool {
        self.kr > 0.0
    }

    /// Whether kt > 0: a hit spawns a refraction ray.
    pub fn transparent(&self) -> bool {
        self.kt > 0.0
    }

    /// Whether shading it draws random numbers: a glossy or frosted lobe sends sampled rays.
    pub fn sampled(&self) -> bool {
        self.glossy.is_some() || self.frosted.is_some()
    }
}
