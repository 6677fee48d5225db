//! Why a measurement cannot be made, or its plot drawn.

use super::sweep::Knob;
use crate::scene::SceneError;

/// A sweep or a scaling measurement refused or failed.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    /// A knob's value outside the whole numbers the setting it turns takes.
    #[error("--knob {}: {value} is not a whole number between {lo} and {hi} ({what})", knob.name())]
    NotWhole {
        /// The knob turned.
        knob: Knob,
        /// The value refused.
        value: f64,
        /// The least value allowed.
        lo: u32,
        /// The greatest value allowed.
        hi: u32,
        /// The setting whose bounds these are.
        what: &'static str,
    },
    /// A knob's value outside the interval the setting it turns takes.
    #[error("--knob {}: {value} is not between {lo} and {hi} ({what})", knob.name())]
    OutOfRange {
        /// The knob turned.
        knob: Knob,
        /// The value refused.
        value: f64,
        /// The least value allowed.
        lo: f64,
        /// The greatest value allowed.
        hi: f64,
        /// The setting whose bounds these are.
        what: &'static str,
    },
    /// A knob that cannot change the scene's image: every row would equal the reference.
    #[error("--knob {} changes nothing in this scene: {why}", knob.name())]
    Idle {
        /// The knob turned.
        knob: Knob,
        /// What the scene lacks for the knob to matter.
        why: &'static str,
    },
    /// A generated scene that does not compile.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// Drawing the plot failed (the plotting library's error, kept as its message).
    #[error("cannot draw the plot: {0}")]
    Plot(String),
}
