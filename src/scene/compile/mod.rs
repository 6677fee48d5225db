//! Compiling a scene file into a runtime scene, in named steps: the camera, the settings of the
//! recursion and of sampling, the materials, the lights, the objects (shapes, transforms, CSG
//! trees, bounds). Every value is validated with its position in the file, names are resolved,
//! transforms composed and inverted, bounds computed.

mod camera;
mod lights;
mod materials;
mod meshes;
mod objects;
mod patterns;
mod settings;

use std::path::PathBuf;

use glam::DVec3;
use serde_saphyr::Spanned;

use super::error::{invalid, Invalid, Pos};
use super::{Features, Scene, SearchIndex};
use crate::scene::format::SceneFile;

/// Limits that protect against absurd input: every allocation whose size a scene (or a flag)
/// chooses is checked against one of these before it is made. `--allow-huge` raises the
/// budgets of size (`Limits::huge`); the others are limits of the format.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Largest image (width × height) rendered.
    pub max_pixels: u64,
    /// Largest `max_depth` accepted (rays per path).
    pub max_depth: u32,
    /// Largest `spp` accepted (samples per pixel).
    pub max_spp: u32,
    /// Deepest CSG nesting accepted.
    pub max_csg_depth: usize,
    /// Largest scene file read, in bytes.
    pub max_file_bytes: u64,
    /// Largest mesh (OBJ) file read, in bytes.
    pub max_mesh_bytes: u64,
    /// Most objects in a scene.
    pub max_objects: usize,
    /// Most triangles in all of a scene's meshes and icospheres together.
    pub max_triangles: u64,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            max_pixels: 64_000_000,
            max_depth: 64,
            max_spp: 65_536,
            max_csg_depth: 200,
            max_file_bytes: 16 << 20,
            max_mesh_bytes: 256 << 20,
            max_objects: 200_000,
            max_triangles: 4_000_000,
        }
    }
}

impl Limits {
    /// The budgets of size raised as far as the program itself can go (`--allow-huge`):
    /// what is left to stop a scene is the memory of the machine, and the files read stay
    /// bounded so that `/proc` files and the like still end.
    pub fn huge() -> Limits {
        Limits {
            max_pixels: u64::MAX,
            max_file_bytes: 1 << 30,
            max_mesh_bytes: 4 << 30,
            max_objects: u32::MAX as usize,
            max_triangles: u32::MAX as u64,
            ..Limits::default()
        }
    }

    /// The phrase every budget error ends with.
    pub const RAISE: &'static str = "use --allow-huge to go beyond it";
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
    let mut inputs = Vec::new();
    let (materials, by_name) = materials::of(&file, source.as_deref(), &mut inputs)?;
    let lights = lights::of(&file, &by_name)?;
    let mut warnings = materials::warnings(&file, &materials, settings.integrator);
    let (leaves, objects) = objects::of(
        &file,
        &by_name,
        &materials,
        source.as_deref(),
        limits,
        &mut warnings,
        &mut inputs,
    )?;
    let background = file.background.as_ref().map_or(Ok(DVec3::ZERO), |b| {
        not_negative(b.value.0, pos(b), "background")
    })?;
    let ambient = file.ambient.as_ref().map_or(Ok(DVec3::ZERO), |a| {
        not_negative(a.value.0, pos(a), "ambient")
    })?;
    let scene = Scene {
        source,
        inputs,
        camera,
        background,
        ambient,
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
        warnings,
    };
    Ok(scene.prepared())
}

/// An intensity or colour: no component may be negative (light is not taken away).
fn not_negative(v: DVec3, p: Pos, what: &str) -> Result<DVec3, Invalid> {
    if v.min_element() < 0.0 {
        return invalid(
            p,
            format!("{what} must be ≥ 0 in every component, got {}", vec3(v)),
        );
    }
    Ok(v)
}

/// `[r, g, b]` as written (a grey one as one number).
fn vec3(v: DVec3) -> String {
    if v.x == v.y && v.y == v.z {
        number(v.x)
    } else {
        format!("[{}, {}, {}]", number(v.x), number(v.y), number(v.z))
    }
}

/// A number in a message, as a scene's numbers are shown (`Num`).
fn number(x: f64) -> String {
    crate::scene::format::Num(x).to_string()
}

/// A name as given in the file: one line of printable text, so that it can be shown in a
/// terminal as it is (no escape sequences, no line breaks faking output), and not blank, so
/// that trees and segment lists can name what they met.
fn printable_name(name: &str, p: Pos, what: &str) -> Result<(), Invalid> {
    if name.trim().is_empty() {
        return invalid(
            p,
            format!("{what} name is empty: give it a name, or leave `name` out"),
        );
    }
    match name.chars().find(|c| c.is_control()) {
        Some(c) => invalid(
            p,
            format!(
                "{what} name `{}` holds the control character {:?}: names must be printable text",
                name.escape_debug(),
                c
            ),
        ),
        None => Ok(()),
    }
}

fn nonzero(v: DVec3, p: Pos, what: &str) -> Result<DVec3, Invalid> {
    v.try_normalize().map_or_else(
        || {
            let why = if v == DVec3::ZERO {
                "must not be the zero vector"
            } else {
                "is too short to have a direction (its length squared underflows)"
            };
            invalid(p, format!("{what} {why}"))
        },
        Ok,
    )
}
