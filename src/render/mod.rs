//! Rendering: images from many rays (antialiasing patterns, the parallel film loop), image
//! output and terminal previews.

pub mod antialias;
mod error;
pub mod film;
mod image;
pub mod preview;

pub use error::{ImageError, WriteError};
pub use film::{render, render_simple, render_through, Engine, RenderOptions};
pub use image::{encode, write_atomically, Encoding, Format as ImageFormat, Image};
