//! Compiling a scene file into a runtime scene, in named steps: the camera, the settings of the
//! recursion and of sampling, the materials, the lights, the objects (shapes, transforms, CSG
//! trees, bounds). Every value is validated with its position in the file, names are resolved,
//! transforms composed and inverted, bounds computed.

mod camera;
mod lights;
mod materials;
mod objects;
mod settings;

use std::path::PathBuf;

use glam::DVec3;
use serde_saphyr::Spanned;

use super::error::{invalid, Invalid, Pos};
use super::{Features, Scene, SearchIndex};
use crate::scene::format::SceneFile;

/// Limits that protect against absurd input.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Largest image (width × height) rendered without `--allow-huge`.
    pub max_pixels: u64,
    pub max_depth: u32,
    pub max_spp: u32,
    /// Deepest CSG nesting accepted.
    pub max_csg_depth: usize,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            max_pixels: 64_000_000,
            max_depth: 64,
            max_spp: 65_536,
            max_csg_depth: 200,
        }
    }
}

const TOP: Pos = Pos { line: 1, column: 1 };

fn pos<T>(s: &Spanned<T>) -> Pos {
    Pos::of(&s.referenced)
}

/// The scene a file describes.
pub fn compile(
    file: SceneFile,
    source: Option<PathBuf>,
    limits: &Limits,
) -> Result<Scene, Invalid> {
    let camera = camera::of(&file, limits)?;
    let settings = settings::Settings::of(&file, limits)?;
    let (materials, by_name) = materials::of(&file)?;
    let lights = lights::of(&file, &by_name)?;
    let (leaves, objects) = objects::of(&file, &by_name, source.as_deref(), limits)?;
    let scene = Scene {
        source,
        camera,
        background: file.background.map_or(DVec3::ZERO, |t| t.0),
        ambient: file.ambient.map_or(DVec3::ZERO, |t| t.0),
        lights,
        materials,
        leaves,
        objects,
        max_depth: settings.max_depth,
        adaptive_threshold: settings.adaptive_threshold,
        shadow_bias: settings.shadow_bias,
        secondary_attenuation: settings.secondary_attenuation,
        stop_rules: settings.stop_rules,
        csg_pruning: true,
        spp: settings.spp,
        integrator: settings.integrator,
        antialias: settings.antialias,
        filter: settings.filter,
        features: Features::default(),
        index: SearchIndex::default(),
    };
    Ok(scene.prepared())
}

fn nonzero(v: DVec3, p: Pos, what: &str) -> Result<DVec3, Invalid> {
    v.try_normalize().map_or_else(
        || invalid(p, format!("{what} must not be the zero vector")),
        Ok,
    )
}
