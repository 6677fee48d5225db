//! Acceleration: bounding volumes (boxes, balls) and the bounding volume hierarchy, the
//! structures that let a ray skip everything it cannot hit (seed 002, "fewer ray-object
//! intersections"). They know points, vectors and boxes only, so the shapes can describe their
//! extent with them.

pub mod aabb;
mod ball;
pub mod bvh;

pub use aabb::{Aabb, SlabRay};
pub use ball::Ball;
pub use bvh::{Bvh, Visits};
