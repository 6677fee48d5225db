//! A ray to trace and its place in the ray tree: its kind, its depth, its weight (the product
//! of the coefficients kr, kt on its way from the eye) and the media it travels through.

use super::media::Media;
use super::recorder::{RayStart, Recorder};
use super::tree::{Indices, RayKind};
use crate::geometry::Ray;

#[derive(Clone, Copy, Debug)]
pub struct Task {
    pub ray: Ray,
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
