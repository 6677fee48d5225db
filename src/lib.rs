//! raytree: a step-by-step Whitted ray tracer whose every pixel can be inspected as a ray tree.
//!
//! The modules form layers; each imports only from the layers below it
//! (`tests/architecture.rs` keeps it so, `docs/architecture.md` maps each concept of the
//! lecture notes to its file):
//!
//! 1. `sampling`, `stats`, `files`, `signals`: random numbers, the counters of work, reading
//!    input files, stopping cleanly on a signal;
//! 2. `accel`: bounding volumes and the BVH;
//! 3. `geometry`: rays, shapes, transforms, segment lists, CSG;
//! 4. `shading`: materials, lights, the local model, optics;
//! 5. `scene`: the scene file, its compilation, the hit search;
//! 6. `trace`: the Whitted recursion (the textbook core), the path tracer, ray trees;
//! 7. `fast`: the fast wing, an optimisation of the core that equals it bit for bit;
//! 8. `render`: images from many rays, in parallel;
//! 9. `diagram`: a pixel's rays drawn in the scene (beside `fast` and `render`, above `trace`);
//! 10. `lessons`, `bench`, `tui`, `cli`: what users run.
//!
//! `bench`, `tui` and `cli` are cargo features of the same names (on by default); without
//! them (`--no-default-features`) the library builds without clap, ratatui, crossterm and
//! indicatif.

pub mod accel;
#[cfg(feature = "bench")]
pub mod bench;
#[cfg(feature = "cli")]
pub mod cli;
pub mod diagram;
pub mod fast;
pub mod files;
pub mod geometry;
pub mod lessons;
#[cfg(feature = "bench")]
mod plot_font;
pub mod render;
pub mod sampling;
pub mod scene;
pub mod shading;
pub mod signals;
pub mod stats;
pub mod trace;
#[cfg(feature = "tui")]
pub mod tui;
