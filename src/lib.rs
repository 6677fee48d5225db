//! raytree: a step-by-step Whitted ray tracer whose every pixel can be inspected as a ray tree.

pub mod accel;
pub mod bench;
pub mod cli;
pub mod geometry;
pub mod lessons;
mod plot_font;
pub mod render;
pub mod scene;
pub mod shading;
pub mod trace;
pub mod tui;
