//! Settings of a scene that say how its image is sampled: where a pixel's primary rays go,
//! and how their values make the pixel. The renderer (`crate::render::antialias`) carries them
//! out.

/// How a pixel's primary rays are placed.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub enum Antialias {
    /// n × n rays on a regular grid in the pixel.
    #[default]
    Grid,
    /// The grid's strata, each ray at a random point of its cell (stratified sampling).
    Jittered,
    /// Split a square while its corners differ by more than `threshold` (the sum of the
    /// absolute differences of r, g and b, on values clamped to [0, 1]).
    Adaptive {
        /// Largest difference between corners that stops the splitting (POV-Ray's default is
        /// `DEFAULT_THRESHOLD`).
        threshold: f64,
    },
}

/// POV-Ray's default antialiasing threshold.
pub const DEFAULT_THRESHOLD: f64 = 0.3;

impl Antialias {
    /// The name as written in scene files (`grid`, `jittered`, `adaptive`).
    pub fn name(self) -> &'static str {
        match self {
            Antialias::Grid => "grid",
            Antialias::Jittered => "jittered",
            Antialias::Adaptive { .. } => "adaptive",
        }
    }
}

/// The stop rules of the notes beyond the background and the maximum depth, each off unless
/// the scene names it in `stop_rules`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct StopRules {
    /// Seed 000: a ray that hits a light source stops there and brings back its intensity
    /// (area and sphere lights, which a ray can hit, are then seen).
    pub light: bool,
    /// Seed 002: a ray that hits a diffuse surface (kd > 0) sends no reflection or refraction
    /// ray, so a path holds at most one diffuse surface, the last.
    pub diffuse: bool,
    /// Seed 002, path tracing: a path that reaches the maximum depth still adds the direct
    /// light at its last surface ("contributes just its local illumination").
    pub local_at_max_depth: bool,
}

/// The pixel reconstruction filter of supersampling.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Filter {
    /// A pixel is the mean of its own samples.
    #[default]
    Box,
    /// Mitsuba's default: every sample is splatted onto the pixels around it with weight
    /// f(dx)·f(dy), f(x) = e^(−x²/2σ²) − e^(−r²/2σ²), σ = 0.5 px, r = 2 px; a pixel is the
    /// weighted mean of the samples that reach it.
    Gaussian,
}
