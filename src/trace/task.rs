//! A ray to trace and its place in the ray tree: its kind, its depth, its weight (the product
//! of the coefficients kr, kt on its way from the eye) and the media it travels through.

use super::media::Media;
use super::recorder::{RayStart, Recorder};
use super::tree::{Indices, RayKind};
use crate::geometry::Ray;

/// A ray waiting to be traced, with its place in the ray tree.
#[derive(Clone, Copy, Debug)]
pub struct Task {
    /// The ray itself (world space, unit direction).
    pub ray: Ray,
    /// Primary, shadow, reflection or refraction.
    pub kind: RayKind,
    /// 0 for the primary ray, one more for each bounce.
    pub depth: u32,
    /// The product of the coefficients from the primary ray down to this ray: how much of the
    /// pixel it can still change (the adaptive depth control compares it with its threshold).
    pub weight: f64,
    /// The coefficient its intensity is multiplied by in its parent (kr or kt).
    pub coefficient: f64,
    /// The transparent solids the ray is inside.
    pub media: Media,
    /// n1 → n2 for a refraction ray.
    pub indices: Option<Indices>,
    /// A glossy or frosted surface above this ray already split the path into many rays:
    /// deeper ones send a single sampled ray, so the work grows linearly, not as nᵈ.
    pub split: bool,
}

impl Task {
    /// A primary ray: from the eye, with weight 1, in air.
    pub fn primary(ray: &Ray) -> Task {
        Task {
            ray: *ray,
            kind: RayKind::Primary,
            depth: 0,
            weight: 1.0,
            coefficient: 1.0,
            media: Media::default(),
            indices: None,
            split: false,
        }
    }

    /// The mirror ray of the surface this ray hit: one level deeper, weighted by kr.
    pub fn reflection(&self, ray: Ray, kr: f64) -> Task {
        Task {
            ray,
            kind: RayKind::Reflection,
            depth: self.depth + 1,
            weight: self.weight * kr,
            coefficient: kr,
            media: self.media,
            indices: None,
            split: self.split,
        }
    }

    /// The refracted ray of the surface this ray hit, from medium n1 into n2 (`media`: the
    /// solids it travels inside from there): one level deeper, weighted by kt.
    pub fn refraction(&self, ray: Ray, kt: f64, media: Media, indices: Indices) -> Task {
        Task {
            ray,
            kind: RayKind::Refraction,
            depth: self.depth + 1,
            weight: self.weight * kt,
            coefficient: kt,
            media,
            indices: Some(indices),
            split: self.split,
        }
    }

    /// Past the limiting angle at a surface that also reflects: the reflection ray, which
    /// the transmitted share follows too (there is no refracted ray), so that it weighs
    /// weight·(kr + kt) while its intensity is multiplied by kr and by kt.
    pub fn reflection_and_transmission(&self, ray: Ray, kr: f64, kt: f64) -> Task {
        Task {
            weight: self.weight * (kr + kt),
            ..self.reflection(ray, kr)
        }
    }

    /// Past the limiting angle, the mirror ray that stays inside: it carries the transmitted
    /// share kt in its weight, and its intensity goes to the (cut-off) refraction ray whole.
    pub fn mirror_inside(&self, ray: Ray, kt: f64) -> Task {
        Task {
            coefficient: 1.0,
            ..self.reflection(ray, kt)
        }
    }

    /// Announces this ray to the recorder.
    pub fn begin<R: Recorder>(&self, rec: &mut R) {
        rec.begin(RayStart {
            kind: self.kind,
            depth: self.depth,
            origin: self.ray.origin,
            direction: self.ray.dir,
            weight: self.weight,
            coefficient: self.coefficient,
        });
        if let Some(i) = self.indices {
            rec.indices(i);
        }
    }
}
