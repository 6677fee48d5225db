//! Rendering: cameras, the parallel film loop, image output and terminal previews.

pub mod antialias;
mod camera;
pub mod film;
mod image;
pub mod preview;

pub use camera::{Camera, Projection};
pub use film::{render, render_simple, RenderOptions};
pub use image::{encode, write_atomically, Encoding, Image};
