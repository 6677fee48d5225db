//! The primitive shapes and the one routine each provides: where a ray is inside it.

use glam::DVec3;

use std::sync::Arc;

use super::{Aabox, Cone, Cylinder, Mesh, Plane, Ray, Sphere, Triangle};
use crate::accel::Aabb;

/// Where a ray is inside a convex primitive: one interval with the faces it enters and leaves
/// through. A triangle, which has no inside, gives the degenerate interval `[t, t]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Span {
    pub t_in: f64,
    pub t_out: f64,
    pub face_in: u8,
    pub face_out: u8,
}

impl Span {
    pub fn new(t_in: f64, face_in: u8, t_out: f64, face_out: u8) -> Span {
        Span {
            t_in,
            t_out,
            face_in,
            face_out,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    Sphere(Sphere),
    Plane(Plane),
    Box(Aabox),
    Cylinder(Cylinder),
    Cone(Cone),
    Triangle(Triangle),
    Mesh(Arc<Mesh>),
}

impl Shape {
    /// The interval of the (object-space) ray inside the shape, over the whole line.
    pub fn span(&self, ray: &Ray) -> Option<Span> {
        match self {
            Shape::Sphere(s) => s.span(ray),
            Shape::Plane(s) => s.span(ray),
            Shape::Box(s) => s.span(ray),
            Shape::Cylinder(s) => s.span(ray),
            Shape::Cone(s) => s.span(ray),
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
            Shape::Cylinder(s) => s.normal(p, face as u8),
            Shape::Cone(s) => s.normal(p, face as u8),
            Shape::Triangle(s) => s.normal(),
            Shape::Mesh(m) => m.normal(p, face),
        }
    }

    /// Object-space bounds (infinite for a plane).
    pub fn bounds(&self) -> Aabb {
        match self {
            Shape::Sphere(s) => Aabb::new(s.center - s.radius, s.center + s.radius),
            Shape::Plane(_) => Aabb::everything(),
            Shape::Box(s) => Aabb::new(s.min, s.max),
            Shape::Cylinder(s) => Aabb::around_disc(s.base, s.axis(), s.radius)
                .union(&Aabb::around_disc(s.top, s.axis(), s.radius)),
            Shape::Cone(s) => Aabb::around_disc(s.base, s.axis(), s.radius).grow(s.apex),
            Shape::Triangle(s) => Aabb::point(s.a).grow(s.b).grow(s.c),
            Shape::Mesh(m) => m.bounds(),
        }
    }

    /// A solid has an inside: a ray can be in it, and it can carry a refractive medium.
    /// (A closed mesh counts; a single triangle does not.)
    pub fn is_solid(&self) -> bool {
        !matches!(self, Shape::Triangle(_))
    }

    /// Shapes whose segment list along any ray is one interval can take part in CSG.
    pub fn is_convex_solid(&self) -> bool {
        !matches!(self, Shape::Triangle(_) | Shape::Mesh(_))
    }

    pub fn kind(&self) -> &'static str {
        match self {
            Shape::Sphere(_) => "sphere",
            Shape::Plane(_) => "plane",
            Shape::Box(_) => "box",
            Shape::Cylinder(_) => "cylinder",
            Shape::Cone(_) => "cone",
            Shape::Triangle(_) => "triangle",
            Shape::Mesh(_) => "mesh",
        }
    }
}
