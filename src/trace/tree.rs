//! The ray tree: every ray traced for one pixel, with the numbers that coloured it.
//! Serialised as the `inspect --format json` contract.

use glam::{DVec2, DVec3};
use serde::Serialize;

use crate::geometry::uv::Edges;

/// What a ray of the ray tree is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RayKind {
    /// From the eye through a pixel (depth 0).
    Primary,
    /// From a hit point towards a light: is the light visible (the shadow factor s)?
    Shadow,
    /// In the mirror direction, weighted by kr.
    Reflection,
    /// Through the surface by Snell's law, weighted by kt.
    Refraction,
}

impl RayKind {
    /// The kind's name (`primary`, `shadow`, `reflection`, `refraction`).
    pub fn name(self) -> &'static str {
        match self {
            RayKind::Primary => "primary",
            RayKind::Shadow => "shadow",
            RayKind::Reflection => "reflection",
            RayKind::Refraction => "refraction",
        }
    }
}

/// Why a ray produced no further rays.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Termination {
    /// It hit nothing: its colour is the background.
    Background,
    /// The path reached the maximum depth, so this ray was not traced.
    MaxDepth,
    /// Its weight fell below the adaptive threshold, so it was not traced.
    Adaptive,
    /// Refraction was impossible: the energy went into a mirror ray instead.
    TotalInternalReflection,
    /// It hit a light source (seed 000's stop rule): it brings back the light's intensity.
    Light,
    /// It hit a diffuse surface (seed 002's stop rule): local illumination only, no
    /// reflection or refraction ray.
    Diffuse,
}

impl Termination {
    /// The reason's name as shown and serialised (`background`, `max_depth`, …).
    pub fn name(self) -> &'static str {
        match self {
            Termination::Background => "background",
            Termination::MaxDepth => "max_depth",
            Termination::Adaptive => "adaptive",
            Termination::TotalInternalReflection => "total_internal_reflection",
            Termination::Light => "light",
            Termination::Diffuse => "diffuse",
        }
    }
}

/// Where a ray hit, and what: the record of a node's intersection.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HitInfo {
    /// The object hit.
    pub object: String,
    /// The primitive hit: the object itself, or the CSG leaf.
    pub leaf: String,
    /// CSG operations from the object's root down to the leaf.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub csg_path: Vec<String>,
    /// Name of the surface's material.
    pub material: String,
    /// Distance along the ray to the hit.
    pub t: f64,
    /// The hit point, world space.
    pub point: DVec3,
    /// Unit normal facing the incoming ray.
    pub normal: DVec3,
    /// True when the ray arrives from inside the solid.
    pub inside: bool,
    /// (λ1, λ2, λ3) for a triangle.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub barycentric: Option<DVec3>,
    /// The texture coordinates (u, v) an image texture or a uv checker was read at (the
    /// colour's, if it has them).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub uv: Option<DVec2>,
}

/// One light's term of the local model at a hit: s·fatt·Iℓ·(kd·O·(n·l) + ks·(h·n)^m).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LightTerm {
    /// Name of the light.
    pub light: String,
    /// s: 1 lit, 0 in shadow.
    pub shadow: f64,
    /// Unit vector towards the light.
    pub l: DVec3,
    /// n·l, the cosine of the angle of incidence.
    pub n_dot_l: f64,
    /// fatt (1 for a directional light).
    pub attenuation: f64,
    /// h·n (Blinn) or r·v (Phong), clamped at 0.
    pub highlight_cos: f64,
    /// s·fatt·Iℓ·kd·O·(n·l)
    pub diffuse: DVec3,
    /// s·fatt·Iℓ·ks·(h·n)^m
    pub specular: DVec3,
    /// Why no shadow ray was cast, when none was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub skipped: Option<String>,
}

/// The local illumination at a hit, term by term: I_local = ka·Ia·O + Σ_ℓ (light terms).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Local {
    /// ka·Ia·O
    pub ambient: DVec3,
    /// One term per light of the scene.
    pub lights: Vec<LightTerm>,
    /// O at the hit, when the material has patterns.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub color: Option<DVec3>,
    /// kd, ks, kr and kt at the hit, when a pattern varies one of them.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub coefficients: Option<Coefficients>,
    /// Each pattern looked up at the hit.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub patterns: Vec<PatternLookup>,
}

/// The coefficients a pattern may vary, as they are at one point.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Coefficients {
    /// Diffuse coefficient kd.
    pub kd: f64,
    /// Specular coefficient ks.
    pub ks: f64,
    /// Reflection coefficient kr.
    pub kr: f64,
    /// Transmission coefficient kt.
    pub kt: f64,
}

/// One pattern or texture, looked up at a hit.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PatternLookup {
    /// What it varies: "O" (the colour), "kd", "ks", "kr" or "kt".
    pub varies: String,
    /// What it is: "checker", "image wood.png, spherical mapping", …
    pub pattern: String,
    /// Where its formula is evaluated: the hit point in the object's own space, through the
    /// inverse of the pattern's transform.
    pub point: DVec3,
    /// The texture coordinates of an image or a uv checker.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub uv: Option<DVec2>,
    /// Which of those end at the image's edges, where it does not wrap round.
    #[serde(skip)]
    pub edges: Edges,
    /// Its value there (a coefficient's is grey).
    pub value: DVec3,
}

impl Local {
    /// I_local: the ambient term plus every light's diffuse and specular terms, shadowed.
    pub fn total(&self) -> DVec3 {
        self.ambient
            + self
                .lights
                .iter()
                .map(|l| l.diffuse + l.specular)
                .sum::<DVec3>()
    }
}

/// Media on each side of a refracting surface.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Indices {
    /// Index of refraction of the medium the ray leaves.
    pub n1: f64,
    /// Index of refraction of the medium the ray enters.
    pub n2: f64,
}

/// Which of a material's Monte Carlo lobes a cone of sampled rays is drawn from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LobeKind {
    /// About the mirror direction (`glossy`).
    Glossy,
    /// About the refracted direction (`frosted`), or past the limiting angle about the mirror
    /// ray that stays inside.
    Frosted,
}

/// A node of the ray tree: one ray, what it hit, the local terms there, and its child rays.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RayNode {
    /// Primary, shadow, reflection or refraction.
    pub kind: RayKind,
    /// 0 for the primary ray; a child is one deeper than its parent.
    pub depth: u32,
    /// Where the ray starts (world space).
    pub origin: DVec3,
    /// Unit direction of the ray.
    pub direction: DVec3,
    /// Product of the kr/kt coefficients from the primary ray down to this ray.
    pub weight: f64,
    /// The coefficient this ray's intensity is multiplied by in its parent (kr, kt, or with
    /// Fresnel kr·R, kt·(1 − R)); 1 for the primary ray and shadow rays.
    pub coefficient: f64,
    /// n1 → n2 for a refraction ray.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub indices: Option<Indices>,
    /// The shadow ray's light, and how far it looked (the distance to the light); for a ray
    /// stopped at a light source, that light.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub light: Option<String>,
    /// How far a shadow ray looked for blockers (up to its light; ∞ for a directional one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub t_max: Option<f64>,
    /// The shadow factor s found by a shadow ray.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shadow: Option<f64>,
    /// How many shadow rays s is the fraction of, for a light sampled by more than one (area
    /// and sphere lights).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shadow_rays: Option<u32>,
    /// A glossy reflection or frosted refraction: this node stands for the cone about the
    /// principal direction, its colour the mean of its `samples` children (the sampled rays,
    /// each with coefficient 1/n).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub samples: Option<u32>,
    /// The material's lobe the cone's rays are drawn from (the frosted one also for the
    /// reflection that stays inside past the limiting angle).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lobe: Option<LobeKind>,
    /// With `secondary_attenuation`: the c0 + c1·d + c2·d² (d the distance to this ray's hit)
    /// its intensity was divided by before its parent weighted it (seeds 000, 004).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub attenuation: Option<f64>,
    /// What the ray hit, or None when it reached the background or was not traced.
    pub hit: Option<HitInfo>,
    /// The local illumination at the hit, when the surface was shaded.
    pub local: Option<Local>,
    /// This node's intensity: local + coefficient-weighted children (linear).
    pub color: DVec3,
    /// Why the ray stopped before its children, if it did.
    pub terminated: Option<Termination>,
    /// The reflection, refraction and shadow rays it spawned, in the order traced.
    pub children: Vec<RayNode>,
}

impl RayNode {
    /// For a glossy or frosted cone: its name and how many rays it averages.
    pub fn cone(&self) -> Option<(&'static str, u32)> {
        let name = match (self.lobe, self.kind) {
            (Some(LobeKind::Frosted), RayKind::Reflection) => "frosted reflection",
            (Some(LobeKind::Frosted), _) => "frosted refraction",
            _ => "glossy reflection",
        };
        self.samples.map(|k| (name, k))
    }

    /// Follows a path of child kinds ("reflection/refraction") from this node.
    pub fn find(&self, path: &str) -> Option<&RayNode> {
        let mut node = self;
        for step in path.split('/').filter(|s| !s.is_empty()) {
            node = node.children.iter().find(|c| c.kind.name() == step)?;
        }
        Some(node)
    }

    /// Number of nodes in the tree.
    pub fn size(&self) -> usize {
        1 + self.children.iter().map(RayNode::size).sum::<usize>()
    }

    /// The reflection and refraction children (not shadow rays).
    pub fn secondary(&self) -> impl Iterator<Item = &RayNode> {
        self.children.iter().filter(|c| c.kind != RayKind::Shadow)
    }
}

/// The `inspect --format json` document.
#[derive(Clone, Debug, Serialize)]
pub struct Inspection {
    /// The pixel inspected, when a pixel was named.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pixel: Option<[u32; 2]>,
    /// The intensity reported: the root's, or the rendered pixel's when `inspect` rendered it.
    pub color: DVec3,
    /// The ray tree of the inspected primary ray.
    pub tree: RayNode,
}
