//! Rendering: images from many rays (antialiasing patterns, the parallel film loop), image
//! output and terminal previews.

pub mod antialias;
mod error;
pub mod film;
mod image;
pub mod preview;

pub use error::{ImageError, WriteError};
pub use film::{render, render_simple, render_through, Engine, RenderOptions};
pub use image::{check_output, encode, write_atomically, Encoding, Format as ImageFormat, Image};

/// The instruction set of the fast wing's copy that renders on this processor: "x86-64-v4"
/// (AVX-512), "x86-64-v3" (AVX2) or "x86-64" (SSE2, or another processor's own vectors).
pub fn instruction_level() -> &'static str {
    crate::fast::level().name()
}
