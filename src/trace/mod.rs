//! Tracing: the Whitted recursion (`whitted.rs`, the textbook core), the path tracer, the
//! recorders that watch them, and the ray tree they record.

pub mod budget;
mod media;
pub mod path;
pub mod recorder;
mod task;
pub mod text;
pub mod tracer;
pub mod tree;
pub mod whitted;

pub use media::{Across, Media};
pub use task::Task;
pub use tracer::{TraceOptions, Tracer};
pub use tree::{Inspection, RayKind, RayNode, Termination};
pub use whitted::shadow_reach;
