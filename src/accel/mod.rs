//! Acceleration: bounding boxes and the bounding volume hierarchy.

mod aabb;
mod ball;
pub mod bvh;
mod hull;

pub use aabb::Aabb;
pub use ball::Ball;
pub use bvh::Bvh;
pub(crate) use hull::{Hull, Verdict};
