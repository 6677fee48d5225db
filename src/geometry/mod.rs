//! Geometry: rays, the primitive shapes, transforms, segment lists and CSG.

mod aabox;
pub mod cone;
pub mod csg;
pub mod csg_crossing;
pub mod csg_lanes;
pub mod cylinder;
mod mesh;
mod plane;
mod ray;
mod segment;
mod shape;
pub mod span_lanes;
mod sphere;
pub mod sphere_group;
mod transform;
mod triangle;

pub use aabox::Aabox;
pub use cone::Cone;
pub use csg_lanes::{CsgLanes, LanesHits};
pub use cylinder::Cylinder;
pub use mesh::Mesh;
pub use plane::Plane;
pub use ray::{lane_mask, Ray, RayLanes};
pub use segment::{first_crossing, Segment, SegmentList, Surface};
pub use shape::{Shape, Span};
pub use sphere::Sphere;
pub use sphere_group::SphereGroup;
pub use transform::Transform;
pub use triangle::{Triangle, TriangleHit};
