//! The settings of the recursion (maximum depth, the adaptive threshold, the shadow bias,
//! attenuation of secondary rays) and of sampling (samples per pixel, antialiasing, the
//! filter, the integrator).

use serde_saphyr::Spanned;

use super::lights::attenuation;
use super::{invalid, number, pos, Invalid, Limits};
use crate::scene::format::{AntialiasMode, Bias, FilterKind, SceneFile, StopRule};
use crate::scene::{Antialias, Filter, Integrator, StopRules, DEFAULT_THRESHOLD};

pub struct Settings {
    pub max_depth: u32,
    pub spp: u32,
    pub adaptive_threshold: f64,
    pub shadow_bias: Option<f64>,
    pub secondary_attenuation: Option<[f64; 3]>,
    pub stop_rules: StopRules,
    pub integrator: Integrator,
    pub antialias: Antialias,
    pub filter: Filter,
}

impl Settings {
    pub fn of(file: &SceneFile, limits: &Limits) -> Result<Settings, Invalid> {
        let max_depth = match &file.max_depth {
            None => 5,
            Some(d) if d.value < 1 || d.value > limits.max_depth as i64 => {
                return invalid(
                    pos(d),
                    format!(
                        "max_depth must be between 1 and {}, got {}",
                        limits.max_depth, d.value
                    ),
                )
            }
            Some(d) => d.value as u32,
        };
        let spp = match &file.spp {
            None => 1,
            Some(s) if s.value < 1 || s.value > limits.max_spp as i64 => {
                return invalid(
                    pos(s),
                    format!(
                        "spp must be between 1 and {}, got {}",
                        limits.max_spp, s.value
                    ),
                )
            }
            Some(s) => s.value as u32,
        };
        let adaptive_threshold = match &file.adaptive_threshold {
            None => 0.0,
            Some(a) if !(0.0..=1.0).contains(&a.value.0) => {
                return invalid(
                    pos(a),
                    format!(
                        "adaptive_threshold must be between 0 and 1, got {}",
                        number(a.value.0)
                    ),
                )
            }
            Some(a) => a.value.0,
        };
        let shadow_bias = match &file.shadow_bias {
            None
            | Some(Spanned {
                value: Bias::Auto, ..
            }) => None,
            Some(
                b @ Spanned {
                    value: Bias::Fixed(v),
                    ..
                },
            ) if *v < 0.0 => {
                return invalid(
                    pos(b),
                    format!("shadow_bias must be `auto` or ≥ 0, got {}", number(*v)),
                )
            }
            Some(Spanned {
                value: Bias::Fixed(v),
                ..
            }) => Some(*v),
        };
        let secondary_attenuation = match &file.secondary_attenuation {
            None => None,
            Some(a) => Some(attenuation(a)?),
        };

        let stop_rules = StopRules {
            light: file.stop_rules.contains(&StopRule::Light),
            diffuse: file.stop_rules.contains(&StopRule::Diffuse),
            local_at_max_depth: file.stop_rules.contains(&StopRule::LocalAtMaxDepth),
        };
        let integrator = file.integrator.unwrap_or_default();
        let threshold = match &file.aa_threshold {
            None => DEFAULT_THRESHOLD,
            Some(t) if !(0.0..=3.0).contains(&t.value.0) => {
                return invalid(
                    pos(t),
                    format!("aa_threshold must be between 0 and 3, got {}", t.value),
                )
            }
            Some(t) => t.value.0,
        };
        let antialias = match file.antialias.unwrap_or_default() {
            AntialiasMode::Grid => Antialias::Grid,
            AntialiasMode::Jittered => Antialias::Jittered,
            AntialiasMode::Adaptive => Antialias::Adaptive { threshold },
        };
        let filter = match file.filter.unwrap_or_default() {
            FilterKind::Box => Filter::Box,
            FilterKind::Gaussian => Filter::Gaussian,
        };
        Ok(Settings {
            max_depth,
            spp,
            adaptive_threshold,
            shadow_bias,
            secondary_attenuation,
            stop_rules,
            integrator,
            antialias,
            filter,
        })
    }
}
