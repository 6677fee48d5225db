//! What a scene uses, found once when it is compiled, so that the tracer does no work for what
//! is absent (DESIGN principle 4): reflective or transparent materials, CSG, materials that draw
//! random numbers, the media a refracted ray can be in, and the lights a convex solid hides
//! from the points inside it.

use glam::DVec3;

use super::objects::{Geometry, Object};
use super::Scene;
use crate::accel::Aabb;
use crate::geometry::csg::{CsgNode, CsgOp};
use crate::geometry::Ray;
use crate::shading::{LightKind, Material};
use crate::stats::Stats;

/// What a compiled scene uses, to skip work it does not need (no reflection rays without kr, …) and
/// to tell the user.
#[derive(Clone, Debug, Default)]
pub struct Features {
    /// Some material has kr > 0.
    pub reflective: bool,
    /// Some material has kt > 0.
    pub transparent: bool,
    /// Some object is a CSG tree.
    pub csg: bool,
    /// Some material draws random numbers (glossy or frosted lobes).
    pub sampled: bool,
    /// Number of lights.
    pub lights: usize,
    /// Objects with a transparent material (kt > 0) and that material (the first such of
    /// the object's leaves), whose index of refraction holds inside: the media a refracted
    /// ray can be in.
    pub transparent_objects: Vec<(u32, u32)>,
    /// Per object and light (`object · lights + light`): the object is a bounded convex solid
    /// and the light lies outside it, so a shadow ray from a point inside it is blocked by it.
    hides_light_inside: Vec<bool>,
}

impl Features {
    /// The features of a scene whose lights, materials and objects are in place.
    pub fn of(scene: &Scene) -> Features {
        let used = |f: fn(&Material) -> bool| {
            scene
                .leaves
                .iter()
                .any(|l| f(&scene.materials[l.material as usize]))
        };
        let mut transparent_objects: Vec<(u32, u32)> = vec![];
        for l in &scene.leaves {
            let m = &scene.materials[l.material as usize];
            if l.shape.is_solid()
                && m.transparent()
                && transparent_objects.iter().all(|x| x.0 != l.object)
            {
                transparent_objects.push((l.object, l.material));
            }
        }
        let hides_light_inside = (0..scene.objects.len() as u32)
            .flat_map(|o| (0..scene.lights.len()).map(move |k| (o, k)))
            .map(|(o, k)| is_bounded_convex(scene, o) && light_outside(scene, o, k))
            .collect();
        Features {
            reflective: used(Material::reflective),
            transparent: used(Material::transparent),
            csg: scene.objects.iter().any(has_csg),
            sampled: used(Material::sampled),
            lights: scene.lights.len(),
            transparent_objects,
            hides_light_inside,
        }
    }

    /// Whether a shadow ray toward light k from a point inside object o is surely blocked by
    /// o: a bounded convex solid holds the whole segment between any two of its points, so
    /// the segment from a point inside it to a light outside it must cross its surface.
    #[inline]
    pub fn hides_light_inside(&self, object: u32, light: usize) -> bool {
        self.hides_light_inside[object as usize * self.lights + light]
    }
}

/// A bounded convex solid: a sphere, box, cylinder or cone (moved as a transform says), or a
/// CSG intersection of such solids.
fn is_bounded_convex(scene: &Scene, object: u32) -> bool {
    fn convex(scene: &Scene, node: &CsgNode) -> bool {
        match node {
            CsgNode::Leaf { leaf, .. } => scene.leaves[*leaf as usize].shape.is_convex_solid(),
            CsgNode::Op { op, children, .. } => {
                *op == CsgOp::Intersection && children.iter().all(|c| convex(scene, c))
            }
        }
    }
    let o = &scene.objects[object as usize];
    o.bounds.is_finite()
        && match &o.geometry {
            Geometry::Leaf(leaf) => scene.leaves[*leaf as usize].shape.is_convex_solid(),
            Geometry::Csg(root) => convex(scene, root),
            Geometry::Group(_) => false,
        }
}

/// Whether the object is a CSG tree or a group holding one.
fn has_csg(o: &Object) -> bool {
    match &o.geometry {
        Geometry::Csg(_) => true,
        Geometry::Group(g) => g.members.iter().any(has_csg),
        Geometry::Leaf(_) => false,
    }
}

/// Whether light k lies wholly outside object o: a point light not in it, any directional
/// light (a bounded object cannot hold infinity), an area light whose box does not meet the
/// object's.
fn light_outside(scene: &Scene, object: u32, light: usize) -> bool {
    let bounds = &scene.objects[object as usize].bounds;
    let apart = |b: Aabb| bounds.intersection(&b).is_empty();
    match &scene.lights[light].kind {
        LightKind::Directional { .. } => true,
        LightKind::Point { position, .. } => {
            let probe = Ray {
                origin: *position,
                dir: DVec3::Y,
            };
            apart(Aabb::point(*position)) || !scene.contains(object, &probe, &mut Stats::default())
        }
        LightKind::Rect { corner, u, v, .. } => apart(
            Aabb::point(*corner)
                .grow(*corner + *u)
                .grow(*corner + *v)
                .grow(*corner + *u + *v),
        ),
        LightKind::Sphere { center, radius, .. } => {
            apart(Aabb::new(*center - *radius, *center + *radius))
        }
    }
}
