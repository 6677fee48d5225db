//! Shading: materials (with their patterns and textures), lights, the local illumination model
//! and the optics of secondary rays.

mod light;
pub mod lobe;
pub mod local;
mod material;
pub mod optics;
pub mod pattern;
pub mod texture;

pub use light::{Light, LightKind, LightSample};
pub use lobe::{Lobe, LobeShape};
pub use material::{Fresnel, Highlight, Material, Paint, Patterns};
pub use pattern::{Pattern, PatternPoint};
