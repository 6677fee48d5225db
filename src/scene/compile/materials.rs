//! The materials: the coefficients of the local model, reflection and transmission, the index
//! of refraction, glossy and frosted lobes, emission; the colour and kd, ks, kr, kt may be
//! patterns or textures (`patterns.rs`).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use glam::DVec3;
use serde_saphyr::Spanned;

use super::patterns::{Of, Textures};
use super::{invalid, number, pos, printable_name, Invalid};
use crate::scene::format::{Integrator, LobeSpec, MaterialSpec, SceneFile, Varying};
use crate::shading::{Fresnel, Highlight, Lobe, LobeShape, Material, Pattern, Patterns};

/// The indices of refraction a material may have (`ior`).
const IOR_RANGE: (f64, f64) = (0.01, 100.0);

/// The file's materials, and each one's index by name. Texture images are found relative to
/// the folder of the scene file (`source`); each image read is added to `inputs`.
pub fn of(
    file: &SceneFile,
    source: Option<&Path>,
    inputs: &mut Vec<PathBuf>,
) -> Result<(Vec<Material>, BTreeMap<String, u32>), Invalid> {
    let base = source.and_then(Path::parent).unwrap_or(Path::new(""));
    let mut textures = Textures::new(base);
    let mut materials = Vec::new();
    let mut material_index = BTreeMap::new();
    for (name, m) in &file.materials {
        printable_name(name, pos(m), "material")?;
        material_index.insert(name.clone(), materials.len() as u32);
        materials.push(material(name, &m.value, &mut textures)?);
    }
    inputs.extend(textures.into_files());
    Ok((materials, material_index))
}

/// Materials that lose light or make it, as the scene's integrator reads them, each with a
/// warning at the material's entry. The Whitted tracer weighs Schlick's R as Hall's model
/// does: kr·R on the mirror ray, kt·(1 − R) on the refracted one, so a glass whose kr is below
/// its kt loses (kt − kr)·R, and past the limiting angle (R = 1) all of kt. The path tracer
/// sends a path on with the expected weight kd·O + kr + kt (Fresnel's R comes out of kt), so
/// more than 1 makes light.
pub fn warnings(
    file: &SceneFile,
    materials: &[Material],
    integrator: Integrator,
) -> Vec<(super::Pos, String)> {
    file.materials
        .iter()
        .zip(materials)
        .filter_map(|((name, spec), m)| {
            let warning = match integrator {
                Integrator::Whitted if m.fresnel == Fresnel::Schlick && m.kr < m.kt => format!(
                    "material `{name}`: with fresnel: schlick the mirror ray carries kr·R and the \
                     refracted ray kt·(1 − R), so with kr = {} below kt = {} the share \
                     (kt − kr)·R of the light is lost, all of kt past the limiting angle; clear \
                     glass has kr = kt",
                    m.kr, m.kt
                ),
                Integrator::Path if m.kd * m.color.max_element() + m.kr + m.kt > 1.0 => format!(
                    "material `{name}`: kd·O + kr + kt = {} is above 1: under integrator: path \
                     the surface sends on more light than it receives (Fresnel's reflection \
                     comes out of kt; clear glass has kt = 1 and kr = 0)",
                    m.kd * m.color.max_element() + m.kr + m.kt
                ),
                _ => return None,
            };
            Some((pos(spec), warning))
        })
        .collect()
}

/// A value that may vary: its constant (for a pattern, the largest value it takes), and the
/// pattern, if it is one.
fn varying(
    v: &Option<Spanned<Varying>>,
    default: DVec3,
    of: Of,
    textures: &mut Textures,
) -> Result<(DVec3, Option<Pattern>), Invalid> {
    let Some(v) = v else {
        return Ok((default, None));
    };
    Ok(match textures.varying(v, of)? {
        Pattern::Constant(c) => (c, None),
        pattern => (pattern.max(), Some(pattern)),
    })
}

fn material(name: &str, m: &MaterialSpec, textures: &mut Textures) -> Result<Material, Invalid> {
    let coefficient =
        |c: &Option<Spanned<crate::scene::format::Num>>, k: &str| -> Result<f64, Invalid> {
            match c {
                None => Ok(0.0),
                Some(c) if c.value.0 < 0.0 => invalid(
                    pos(c),
                    format!("material `{name}`: {k} must be ≥ 0, got {}", c.value),
                ),
                Some(c) => Ok(c.value.0),
            }
        };
    let ior = match &m.ior {
        None => 1.0,
        // Real media lie between 1 and about 4. Within 0.01 to 100, η = n1/n2 stays within
        // 10⁴, where Snell's law in floating point still gives a unit direction; at ior 10⁻¹⁶
        // the refracted direction rounds to zero.
        Some(i) if !(IOR_RANGE.0..=IOR_RANGE.1).contains(&i.value.0) => {
            return invalid(
                pos(i),
                format!(
                    "material `{name}`: ior must be between {} and {} (real media lie between 1 and about 4), got {}",
                    IOR_RANGE.0, IOR_RANGE.1, i.value
                ),
            )
        }
        Some(i) => i.value.0,
    };
    let shininess = match &m.shininess {
        None => 1.0,
        Some(s) => coefficient(&Some(s.clone()), "shininess")?,
    };
    let emission = match &m.emission {
        None => DVec3::ZERO,
        Some(e) if e.value.0.min_element() < 0.0 => {
            return invalid(
                pos(e),
                format!("material `{name}`: emission must be ≥ 0 in every channel"),
            )
        }
        Some(e) => e.value.0,
    };
    let mut patterns = Patterns::default();
    let mut vary =
        |v: &Option<Spanned<Varying>>, key: &str, default: f64, slot: &mut Option<Pattern>| {
            let scalar = key != "color";
            let of = Of {
                material: name,
                key,
                scalar,
            };
            let (value, pattern) = varying(v, DVec3::splat(default), of, textures)?;
            *slot = pattern;
            Ok::<DVec3, Invalid>(value)
        };
    let color = vary(&m.color, "color", 1.0, &mut patterns.color)?;
    let kd = vary(&m.kd, "kd", 0.0, &mut patterns.kd)?.x;
    let ks = vary(&m.ks, "ks", 0.0, &mut patterns.ks)?.x;
    let kr = vary(&m.kr, "kr", 0.0, &mut patterns.kr)?.x;
    let kt = vary(&m.kt, "kt", 0.0, &mut patterns.kt)?.x;
    Ok(Material {
        name: name.to_string(),
        color,
        ka: coefficient(&m.ka, "ka")?,
        kd,
        ks,
        shininess,
        highlight: m.highlight.unwrap_or(Highlight::Blinn),
        kr,
        kt,
        ior,
        fresnel: m.fresnel.unwrap_or(Fresnel::None),
        transmitted_highlight: m.transmitted_highlight.unwrap_or(false),
        emission,
        glossy: m
            .glossy
            .as_ref()
            .map(|g| lobe(name, "glossy", g))
            .transpose()?,
        frosted: m
            .frosted
            .as_ref()
            .map(|f| lobe(name, "frosted", f))
            .transpose()?,
        patterns: (patterns != Patterns::default()).then(|| Box::new(patterns.noting_uv())),
    })
}

/// A glossy or frosted lobe: exactly one of `spread` (degrees, 0 < σ ≤ 45) or `exponent`
/// (≥ 1), and 1…1024 samples (default 16).
fn lobe(material: &str, key: &str, spec: &Spanned<LobeSpec>) -> Result<Lobe, Invalid> {
    let l = &spec.value;
    let shape = match (&l.spread, &l.exponent) {
        (Some(s), None) => {
            if !(s.value.0 > 0.0 && s.value.0 <= 45.0) {
                return invalid(
                    pos(s),
                    format!(
                        "material `{material}`: {key} spread must be between 0 and 45 degrees, got {}",
                        number(s.value.0)
                    ),
                );
            }
            LobeShape::Normal {
                sigma: s.value.0.to_radians(),
            }
        }
        (None, Some(e)) => {
            if e.value.0 < 1.0 {
                return invalid(
                    pos(e),
                    format!(
                        "material `{material}`: {key} exponent must be ≥ 1, got {}",
                        number(e.value.0)
                    ),
                );
            }
            LobeShape::Phong {
                exponent: e.value.0,
            }
        }
        _ => {
            return invalid(
                pos(spec),
                format!(
                    "material `{material}`: {key} needs exactly one of `spread` (degrees) or `exponent`"
                ),
            )
        }
    };
    let samples = match &l.samples {
        None => 16,
        Some(s) if !(1..=1024).contains(&s.value) => {
            return invalid(
                pos(s),
                format!(
                    "material `{material}`: {key} samples must be between 1 and 1024, got {}",
                    s.value
                ),
            )
        }
        Some(s) => s.value as u32,
    };
    Ok(Lobe { shape, samples })
}
