//! The primitive shapes and the one routine each provides: where a ray is inside it.

use glam::DVec3;

use std::sync::Arc;

use super::{Aabox, Cone, Cylinder, Mesh, Plane, Ray, Sphere, Transform, Triangle};
use crate::accel::Aabb;

/// Where a ray is inside a convex primitive: one interval with the faces it enters and leaves
/// through. A triangle, which has no inside, gives the degenerate interval `[t, t]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Span {
    /// Where the ray enters the primitive.
    pub t_in: f64,
    /// Where the ray leaves the primitive (≥ `t_in`).
    pub t_out: f64,
    /// The face crossed at `t_in` (numbering per shape).
    pub face_in: u8,
    /// The face crossed at `t_out`.
    pub face_out: u8,
}

impl Span {
    /// The interval `[t_in, t_out]` with its entry and exit faces (argument order: t, face, t,
    /// face).
    pub fn new(t_in: f64, face_in: u8, t_out: f64, face_out: u8) -> Span {
        Span {
            t_in,
            t_out,
            face_in,
            face_out,
        }
    }

    /// The first end of the span past t_min, with its face: where the ray enters, or, from
    /// inside, where it leaves.
    pub fn first_end_past(&self, t_min: f64) -> (f64, u8) {
        if self.t_in > t_min {
            (self.t_in, self.face_in)
        } else {
            (self.t_out, self.face_out)
        }
    }
}

/// A primitive shape in its object space, as the scene file names it.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A sphere (solid).
    Sphere(Sphere),
    /// An infinite plane (a half-space solid).
    Plane(Plane),
    /// An axis-aligned box (solid).
    Box(Aabox),
    /// A capped cylinder (solid).
    Cylinder(Cylinder),
    /// A cone with its base cap (solid).
    Cone(Cone),
    /// A cylinder without its caps (`capped: false`): a tube, a surface with no inside.
    OpenCylinder(Cylinder),
    /// A cone without its base (`capped: false`): a surface with no inside.
    OpenCone(Cone),
    /// A single triangle: a surface with no inside.
    Triangle(Triangle),
    /// A triangle mesh, shared between objects that load the same file.
    Mesh(Arc<Mesh>),
}

impl Shape {
    /// The interval of the (object-space) ray inside the shape, over the whole line. A surface
    /// without inside (a triangle, an open cylinder or cone) gives its crossings instead: the
    /// span runs from the first to the last.
    pub fn span(&self, ray: &Ray) -> Option<Span> {
        match self {
            Shape::Sphere(s) => s.span(ray),
            Shape::Plane(s) => s.span(ray),
            Shape::Box(s) => s.span(ray),
            Shape::Cylinder(s) => s.span(ray),
            Shape::Cone(s) => s.span(ray),
            Shape::OpenCylinder(s) => s.open_span(ray),
            Shape::OpenCone(s) => s.open_span(ray),
            Shape::Triangle(s) => s.span(ray),
            // A mesh is not convex, so it has no single span: the scene asks it for its
            // nearest hit (`Mesh::hit`) or all its crossings (`Mesh::crossings`) instead.
            Shape::Mesh(_) => None,
        }
    }

    /// The outward unit normal (object space) at a point on `face`.
    #[inline]
    pub fn normal(&self, p: DVec3, face: u32) -> DVec3 {
        match self {
            Shape::Sphere(s) => s.normal(p),
            Shape::Plane(s) => s.normal,
            Shape::Box(s) => s.normal(face as u8),
            Shape::Cylinder(s) | Shape::OpenCylinder(s) => s.normal(p, face as u8),
            Shape::Cone(s) | Shape::OpenCone(s) => s.normal(p, face as u8),
            Shape::Triangle(s) => s.normal(),
            Shape::Mesh(m) => m.normal(p, face),
        }
    }

    /// The shape carried to world space by `tf`, when the result is a shape of the same kind:
    /// then the renderer can intersect it in world space and skip carrying every ray into
    /// object space. Spheres, cylinders and cones stay themselves under similarities (moves,
    /// turns, uniform scales), boxes under scales along the axes and moves, planes under any
    /// transform, triangles under any that keeps their orientation. Meshes keep their
    /// transform (their inner BVH is built in object space).
    pub fn moved(&self, tf: &Transform) -> Option<Shape> {
        let m = &tf.to_world;
        let p = |v: DVec3| m.transform_point3(v);
        let scale = tf.similarity_scale();
        let moved = match self {
            Shape::Sphere(s) => Shape::Sphere(Sphere {
                center: p(s.center),
                radius: s.radius * scale?,
            }),
            Shape::Cylinder(s) => Shape::Cylinder(Cylinder {
                base: p(s.base),
                top: p(s.top),
                radius: s.radius * scale?,
            }),
            Shape::OpenCylinder(s) => Shape::OpenCylinder(Cylinder {
                base: p(s.base),
                top: p(s.top),
                radius: s.radius * scale?,
            }),
            Shape::Cone(s) => Shape::Cone(Cone {
                apex: p(s.apex),
                base: p(s.base),
                radius: s.radius * scale?,
            }),
            Shape::OpenCone(s) => Shape::OpenCone(Cone {
                apex: p(s.apex),
                base: p(s.base),
                radius: s.radius * scale?,
            }),
            Shape::Box(b) => {
                let l = m.matrix3;
                let diagonal = [
                    l.x_axis.y, l.x_axis.z, l.y_axis.x, l.y_axis.z, l.z_axis.x, l.z_axis.y,
                ]
                .iter()
                .all(|&v| v == 0.0);
                if !diagonal {
                    return None;
                }
                let (a, c) = (p(b.min), p(b.max));
                Shape::Box(Aabox {
                    min: a.min(c),
                    max: a.max(c),
                })
            }
            Shape::Plane(s) => Shape::Plane(Plane {
                point: p(s.point),
                normal: tf.normal_to_world(s.normal),
            }),
            Shape::Triangle(t) if m.matrix3.determinant() > 0.0 => Shape::Triangle(Triangle {
                a: p(t.a),
                b: p(t.b),
                c: p(t.c),
            }),
            Shape::Triangle(_) | Shape::Mesh(_) => return None,
        };
        // Nothing may overflow, underflow to a point or collapse a box or an axis.
        let b = moved.bounds();
        let sound = match &moved {
            Shape::Sphere(s) => s.radius.is_normal() && s.center.is_finite(),
            Shape::Cylinder(s) | Shape::OpenCylinder(s) => {
                s.radius.is_normal()
                    && s.axis().is_finite()
                    && b.min.is_finite()
                    && b.max.is_finite()
            }
            Shape::Cone(s) | Shape::OpenCone(s) => {
                s.radius.is_normal()
                    && s.axis().is_finite()
                    && b.min.is_finite()
                    && b.max.is_finite()
            }
            Shape::Box(s) => s.min.is_finite() && s.max.is_finite() && s.min.cmplt(s.max).all(),
            Shape::Plane(s) => s.point.is_finite() && s.normal.is_finite(),
            Shape::Triangle(t) => {
                t.normal() != DVec3::ZERO && b.min.is_finite() && b.max.is_finite()
            }
            Shape::Mesh(_) => false,
        };
        sound.then_some(moved)
    }

    /// Object-space bounds (infinite for a plane).
    pub fn bounds(&self) -> Aabb {
        match self {
            Shape::Sphere(s) => Aabb::new(s.center - s.radius, s.center + s.radius),
            Shape::Plane(_) => Aabb::everything(),
            Shape::Box(s) => Aabb::new(s.min, s.max),
            Shape::Cylinder(s) | Shape::OpenCylinder(s) => Aabb::around_disc(
                s.base,
                s.axis(),
                s.radius,
            )
            .union(&Aabb::around_disc(s.top, s.axis(), s.radius)),
            Shape::Cone(s) | Shape::OpenCone(s) => {
                Aabb::around_disc(s.base, s.axis(), s.radius).grow(s.apex)
            }
            Shape::Triangle(s) => Aabb::point(s.a).grow(s.b).grow(s.c),
            Shape::Mesh(m) => m.bounds(),
        }
    }

    /// A solid has an inside: a ray can be in it, and it can carry a refractive medium.
    /// (A closed mesh counts; a single triangle, an open tube or cone does not.)
    pub fn is_solid(&self) -> bool {
        !matches!(
            self,
            Shape::Triangle(_) | Shape::OpenCylinder(_) | Shape::OpenCone(_)
        )
    }

    /// Shapes whose segment list along any ray is one interval can take part in CSG.
    pub fn is_convex_solid(&self) -> bool {
        self.is_solid() && !matches!(self, Shape::Mesh(_))
    }

    /// The shape's name as written in scene files (`sphere`, `plane`, `box`, …).
    pub fn kind(&self) -> &'static str {
        match self {
            Shape::Sphere(_) => "sphere",
            Shape::Plane(_) => "plane",
            Shape::Box(_) => "box",
            Shape::Cylinder(_) | Shape::OpenCylinder(_) => "cylinder",
            Shape::Cone(_) | Shape::OpenCone(_) => "cone",
            Shape::Triangle(_) => "triangle",
            Shape::Mesh(_) => "mesh",
        }
    }
}
