//! Tracing: the recursive tracer, its recorders, the ray tree and statistics.

pub mod path;
pub mod recorder;
pub mod sampling;
mod stats;
pub mod text;
pub mod tracer;
pub mod tree;

pub use stats::Stats;
pub use tracer::Tracer;
pub use tree::{Inspection, RayKind, RayNode, Termination};
