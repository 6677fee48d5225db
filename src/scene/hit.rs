//! A hit and what is built from it. The search finds the cheap record (t, object, surface);
//! the shading record (point, normal, inside, and the material's colour and coefficients
//! there) is built only for the hit that is shaded. Every
//! secondary ray leaves a surface through `offset`, the one place its origin is moved off the
//! surface so that it cannot hit that surface again (seed 004's "self-intersection").

use glam::DVec3;

use super::{Leaf, Scene};
use crate::geometry::{Ray, Surface};
use crate::shading::{Material, Paint, PatternPoint};

/// Cosines of the normal and the ray within this of zero are a tangent's, rounded: the error
/// of a unit normal computed at a point far from the ray's origin (t ≈ 10⁶ radii) is about
/// 10⁻¹⁰.
pub const TANGENT_COSINE: f64 = 1e-9;

/// The cheap record of an intersection: enough to find everything else later.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// Distance along the ray (world space, unit direction).
    pub t: f64,
    /// Index of the object hit in `Scene::objects`.
    pub object: u32,
    /// The primitive surface hit (leaf, face, and whether CSG flipped its normal).
    pub surface: Surface,
}

/// The shading record, built only for the hit that is shaded.
#[derive(Clone, Copy, Debug, Default)]
pub struct Interaction {
    /// The hit point, world space.
    pub point: DVec3,
    /// Unit normal facing the incoming ray (the one the formulas use).
    pub normal: DVec3,
    /// True when the ray arrives from inside the solid (it is leaving it).
    pub inside: bool,
    /// Index of the primitive in `Scene::leaves`.
    pub leaf: u32,
    /// The leaf's face (a mesh's triangle).
    pub face: u32,
    /// Index of the object in `Scene::objects`.
    pub object: u32,
    /// Index of the surface's material in `Scene::materials`.
    pub material: u32,
    /// O, kd, ks, kr and kt here: the material's own, or its patterns looked up at the point.
    pub paint: Paint,
    /// The largest |coordinate| of the origin of the ray that found the point: with the
    /// point's own, the size of the numbers the point was computed from, which the bias of
    /// every ray leaving it (shadow rays too) is relative to (`Scene::bias`).
    pub origin_size: f64,
}

impl Scene {
    /// The shading record of a hit.
    #[inline(always)]
    pub fn interaction(&self, ray: &Ray, hit: &Hit) -> Interaction {
        let mut si = Interaction::default();
        self.record_interaction(ray, hit, &mut si);
        si
    }

    /// The shading record of a hit, written into `si`: the surface there, then its colour.
    /// Inlined, with the normal's dispatch, into the tracer: it runs once per shaded hit. The
    /// fast wing keeps a packet's records in an array and has each written where it stays: a
    /// record built elsewhere and copied in is read back, wide, from narrower stores still in
    /// flight, which stalls the processor.
    #[inline(always)]
    pub fn record_interaction(&self, ray: &Ray, hit: &Hit, si: &mut Interaction) {
        let material = self.record_surface(ray, hit, si);
        self.paint_patterns(material, si);
    }

    /// The record of a hit without its patterns: the point, the normal facing the ray, whether
    /// the ray leaves the solid, and the material's constant colour and coefficients. Returns
    /// the material, whose patterns `paint_patterns` looks up.
    #[inline(always)]
    pub fn record_surface(&self, ray: &Ray, hit: &Hit, si: &mut Interaction) -> &Material {
        let leaf = &self.leaves[hit.surface.leaf as usize];
        let point = ray.at(hit.t);
        let outward = leaf.normal(point, hit.surface.face, -ray.dir);
        self.record_with_normal(ray, hit, point, outward, si)
    }

    /// `record_surface` with the hit's point and the leaf's outward normal there already
    /// found.
    #[inline(always)]
    pub fn record_with_normal(
        &self,
        ray: &Ray,
        hit: &Hit,
        point: DVec3,
        mut outward: DVec3,
        si: &mut Interaction,
    ) -> &Material {
        let leaf = &self.leaves[hit.surface.leaf as usize];
        if hit.surface.flip {
            outward = -outward;
        }
        // The ray leaves the solid where it meets the outward normal at a positive cosine. A
        // tangent ray's cosine is zero up to rounding, of either sign, and it touches the solid
        // from outside (a ray inside a convex solid leaves it at an angle), so only a cosine
        // clearly above zero means leaving. A smooth mesh's blended normal can lean past the
        // ray where its triangle does not: the triangle itself decides.
        let crossed = leaf
            .facet_normal(hit.surface.face, outward)
            .unwrap_or(outward);
        let leaving = crossed.dot(ray.dir) > TANGENT_COSINE;
        // A triangle has no inside: it is seen from whichever side the ray comes.
        let inside = leaf.shape.is_solid() && leaving;
        let normal = if leaving { -outward } else { outward };
        // Field by field, into `si`: a record built whole would be assembled in a stack slot
        // and copied in.
        si.point = point;
        si.origin_size = ray.origin.abs().max_element();
        si.normal = normal;
        si.inside = inside;
        si.leaf = hit.surface.leaf;
        si.face = hit.surface.face;
        si.object = hit.object;
        si.material = leaf.material;
        let m = &self.materials[leaf.material as usize];
        si.paint = m.paint();
        m
    }

    /// The patterns of the record's material `m` looked up at its point: the one place a
    /// surface's colour is looked up (a material without patterns, most, keeps its constants).
    #[inline(always)]
    pub fn paint_patterns(&self, m: &Material, si: &mut Interaction) {
        if let Some(patterns) = &m.patterns {
            let leaf = &self.leaves[si.leaf as usize];
            let at = self.pattern_point(leaf, si.point, si.face, patterns.need_uv());
            patterns.paint(&mut si.paint, &at);
        }
    }

    /// Where a leaf's patterns are looked up for a world point on its `face`: the point in the
    /// object's own space (a patterned leaf keeps its shape there, with its transform), and,
    /// when `uv`, the surface's own (u, v) at it.
    pub fn pattern_point(&self, leaf: &Leaf, point: DVec3, face: u32, uv: bool) -> PatternPoint {
        let own = leaf
            .transform
            .as_ref()
            .map_or(point, |tf| tf.to_local.transform_point3(point));
        if !uv {
            return PatternPoint::at(own);
        }
        PatternPoint {
            point: own,
            uv: leaf.shape.uv(own, face),
            edges: leaf.shape.uv_edges(face),
        }
    }

    /// Offset of secondary-ray origins off a surface hit from `origin`. The automatic bias is
    /// relative: a computed hit point is off by a few ulps of the coordinates involved
    /// (|o| + |p|), so 1e−10 of them clears it by a factor of ~10⁶ while staying far below the
    /// size of any feature a scene at that scale can have (tests/robustness.rs sweeps scales
    /// 1e−4…1e6 and offsets to 1e6).
    #[inline]
    pub fn bias(&self, origin: DVec3, point: DVec3) -> f64 {
        self.bias_of_sizes(origin.abs().max_element(), point)
    }

    /// `bias` with the origin's largest |coordinate| already found.
    #[inline]
    fn bias_of_sizes(&self, origin_size: f64, point: DVec3) -> f64 {
        self.shadow_bias
            .unwrap_or_else(|| (1e-10 * (origin_size + point.abs().max_element())).max(1e-300))
    }

    /// The hit point moved off the surface to the side `dir` leaves by (so a ray from there
    /// cannot hit the surface again), and how far it moved: by the bias of the ray that found
    /// the point, whose error it must clear, whether the new ray is a shadow ray or a child.
    #[inline(always)]
    pub fn offset(&self, si: &Interaction, dir: DVec3) -> (DVec3, f64) {
        self.offset_to(si, dir.dot(si.normal) >= 0.0)
    }

    /// The hit point moved off the surface by the bias: to the side the normal faces (the
    /// incoming ray's), or `through` to the other.
    #[inline(always)]
    pub fn offset_to(&self, si: &Interaction, facing: bool) -> (DVec3, f64) {
        let bias = self.bias_of_sizes(si.origin_size, si.point);
        let side = if facing { bias } else { -bias };
        (si.point + side * si.normal, bias)
    }
}
