//! Acceleration: bounding boxes and the bounding volume hierarchy.

mod aabb;
mod ball;
pub mod bvh;
mod hull;

pub use aabb::{Aabb, SlabLanes};
pub use ball::Ball;
pub use bvh::Bvh;
