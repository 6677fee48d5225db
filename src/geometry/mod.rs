//! Geometry: rays, the primitive shapes (each with one routine that intersects it with a
//! ray, giving its span), transforms, segment lists and CSG; and the surfaces' own (u, v) and
//! the ⌊x⌋ that patterns, uv and textures look cells up with.

mod aabox;
pub mod cone;
pub mod csg;
pub mod cylinder;
pub mod floor;
mod mesh;
mod plane;
mod ray;
mod segment;
mod shape;
pub mod sphere;
mod transform;
mod triangle;
pub mod uv;

pub use aabox::Aabox;
pub use cone::Cone;
pub use cylinder::Cylinder;
#[cfg(test)]
pub(crate) use mesh::tests as mesh_tests;
pub use mesh::{Mesh, MeshMemory, ObjBudget};
pub use plane::Plane;
pub use ray::Ray;
pub use segment::{first_crossing, Segment, SegmentList, Surface};
pub use shape::{Shape, Span};
pub use sphere::Sphere;
pub use transform::Transform;
pub use triangle::{Triangle, TriangleHit};

/// The largest magnitude accepted for any number of a scene or a mesh file: squares of
/// coordinates, met in every intersection test, must not overflow.
pub const MAX_MAGNITUDE: f64 = 1e100;
