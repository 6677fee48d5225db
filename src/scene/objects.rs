//! The scene's objects as the tracer sees them: every primitive (a plain object, or a leaf of
//! a CSG tree) with its shape, transform, material and world-space bounds, and the objects that
//! hold them: a primitive, a CSG tree, or a group of objects with a hierarchy of its own.

use glam::DVec3;

use crate::accel::{Aabb, Bvh};
use crate::geometry::csg::CsgNode;
use crate::geometry::{Mesh, Ray, Segment, SegmentList, Shape, Span, Sphere, Surface, Transform};

/// A primitive in the scene: a plain object, or a leaf of a CSG tree.
#[derive(Clone, Debug)]
pub struct Leaf {
    /// The leaf's own name (for a plain object, the object's name).
    pub name: String,
    /// The object it belongs to.
    pub object: u32,
    /// The CSG operations from the object's root down to this leaf ("union/difference").
    pub path: Vec<String>,
    /// The primitive, in its own space when `transform` is set, else in world space.
    pub shape: Shape,
    /// From the shape's own space to the world, when the shape is not stored in world space
    /// (a transform that changes its kind, or a material with patterns, which are looked up
    /// in the object's own space). Boxed: most leaves have none, and a leaf is read in
    /// every pass over a scene's leaves.
    pub transform: Option<Box<Transform>>,
    /// Index of its material in `Scene::materials`.
    pub material: u32,
    /// World-space bounds.
    pub bounds: Aabb,
}

impl Leaf {
    /// The leaf as a sphere in world space, if it is one.
    pub fn world_sphere(&self) -> Option<&Sphere> {
        match (&self.shape, &self.transform) {
            (Shape::Sphere(s), None) => Some(s),
            _ => None,
        }
    }

    /// The interval of the world-space ray inside the primitive (over the whole line), or None; the
    /// ray is taken into the shape's space when it has one, keeping t.
    pub fn span(&self, ray: &Ray) -> Option<Span> {
        match &self.transform {
            Some(tf) => self.shape.span(&tf.ray_to_local(ray)),
            None => self.shape.span(ray),
        }
    }

    /// The leaf's segment list; its surfaces are named by `id`, its index in the scene.
    pub fn segments(&self, id: u32, ray: &Ray) -> SegmentList {
        let mut list = SegmentList::new();
        if matches!(self.shape, Shape::OpenCylinder(_) | Shape::OpenCone(_)) {
            // A surface without inside: each crossing a zero-length segment.
            if let Some(s) = self.span(ray) {
                for t in [s.t_in, s.t_out] {
                    if list.last().is_none_or(|l: &Segment| l.t_in != t) {
                        let surface = Surface::new(id, s.face_in as u32);
                        list.push(Segment {
                            t_in: t,
                            t_out: t,
                            enter: surface,
                            exit: surface,
                        });
                    }
                }
            }
            return list;
        }
        if let Shape::Mesh(mesh) = &self.shape {
            // Every crossing of a mesh's surface, as a zero-length segment.
            let local = self
                .transform
                .as_ref()
                .map_or(*ray, |tf| tf.ray_to_local(ray));
            for (t, face) in mesh.crossings(&local) {
                let s = Surface::new(id, face);
                list.push(Segment {
                    t_in: t,
                    t_out: t,
                    enter: s,
                    exit: s,
                });
            }
            return list;
        }
        // A span of NaN (arithmetic overflow on absurd input) is no intersection.
        if let Some(s) = self
            .span(ray)
            .filter(|s| !s.t_in.is_nan() && !s.t_out.is_nan())
        {
            list.push(Segment {
                t_in: s.t_in,
                t_out: s.t_out,
                enter: Surface::new(id, s.face_in as u32),
                exit: Surface::new(id, s.face_out as u32),
            });
        }
        list
    }

    /// The outward unit normal in world space at a world point on `face`. A plain sphere's or
    /// plane's is found here, inline: it is wanted at every shaded hit. `facing` stands in
    /// where the point has no normal (a sphere smaller than the point's rounding, which it
    /// rounds to the centre of): the hit record passes −d, the surface facing the ray.
    #[inline(always)]
    pub fn normal(&self, p: DVec3, face: u32, facing: DVec3) -> DVec3 {
        match (&self.transform, &self.shape) {
            (None, Shape::Sphere(s)) => s.normal_facing(p, facing),
            (None, Shape::Plane(s)) => s.normal,
            (Some(tf), shape) => {
                tf.normal_to_world(shape.normal(tf.to_local.transform_point3(p), face))
            }
            (None, shape) => shape.normal(p, face),
        }
    }

    /// The outward normal of a smooth mesh's triangle `face` itself (world space), turned to
    /// the side of its blended shading normal `shading`: the surface a ray actually crosses,
    /// which says whether it enters or leaves. None for every other shape, whose shading
    /// normal is its surface's. (Asked at every hit: the test is inlined, the mesh's work not.)
    #[inline(always)]
    pub fn facet_normal(&self, face: u32, shading: DVec3) -> Option<DVec3> {
        match &self.shape {
            Shape::Mesh(mesh) if !mesh.normals.is_empty() => {
                Some(self.mesh_facet_normal(mesh, face, shading))
            }
            _ => None,
        }
    }

    #[inline(never)]
    fn mesh_facet_normal(&self, mesh: &Mesh, face: u32, shading: DVec3) -> DVec3 {
        let own = mesh.triangle(face).normal();
        let n = self
            .transform
            .as_ref()
            .map_or(own, |tf| tf.normal_to_world(own));
        if n.dot(shading) < 0.0 {
            -n
        } else {
            n
        }
    }
}

/// What an object is made of.
#[derive(Clone, Debug)]
pub enum Geometry {
    /// A single primitive (index into `Scene::leaves`).
    Leaf(u32),
    /// A CSG tree over primitives in `Scene::leaves`.
    Csg(CsgNode),
    /// A group of objects moved and searched as one.
    Group(Box<Group>),
}

/// Objects moved together and searched as one: the scene's hierarchy holds the group's box,
/// and the group a hierarchy of its members' boxes, so a ray that misses the group's box skips
/// all of them.
#[derive(Clone, Debug)]
pub struct Group {
    /// The member objects.
    pub members: Vec<Object>,
    /// The hierarchy over the members with a box; its item i is member `bounded[i]`.
    pub bvh: Bvh,
    /// The members with a finite box, in the hierarchy's item order.
    pub bounded: Vec<u32>,
    /// The members without a box (planes), tested by every ray that reaches the group.
    pub unbounded: Vec<u32>,
}

impl Group {
    /// A group of `members`, with the hierarchy over those with a finite box.
    pub fn new(members: Vec<Object>) -> Group {
        let (bounded, unbounded): (Vec<u32>, Vec<u32>) =
            (0..members.len() as u32).partition(|&i| members[i as usize].bounds.is_finite());
        let boxes: Vec<Aabb> = bounded
            .iter()
            .map(|&i| members[i as usize].bounds)
            .collect();
        Group {
            bvh: Bvh::build(&boxes),
            members,
            bounded,
            unbounded,
        }
    }

    /// The box around all members (everything, if one has none).
    pub fn bounds(&self) -> Aabb {
        self.members
            .iter()
            .fold(Aabb::empty(), |b, m| b.union(&m.bounds))
    }
}

/// A named object of the scene: the thing a ray hits (a primitive, a CSG tree or a group).
#[derive(Clone, Debug)]
pub struct Object {
    /// Name in the scene file (or a generated one), for the ray tree and messages.
    pub name: String,
    /// Its primitive, CSG tree or group.
    pub geometry: Geometry,
    /// World-space box around it (infinite for planes).
    pub bounds: Aabb,
}
