//! Shading: materials, lights, the local illumination model and the optics of secondary rays.

mod light;
pub mod local;
mod material;
pub mod optics;

pub use light::{Light, LightKind, LightSample};
pub use material::{Fresnel, Highlight, Material};
