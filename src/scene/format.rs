//! The scene file as a student writes it: serde structs that mirror the YAML keys. Nothing
//! here is validated beyond types; `compile` turns it into a runtime `Scene`.

use std::collections::BTreeMap;
use std::fmt;

use glam::DVec3;
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::Deserialize;
use serde_saphyr::Spanned;

use crate::shading::{Fresnel, Highlight};

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Handedness {
    #[default]
    Left,
    Right,
}

/// How pixels are computed: the lecture's Whitted recursion or a path tracer.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Integrator {
    #[default]
    Whitted,
    Path,
}

/// A colour or vector that may be written as one number (grey / uniform) or as `[x, y, z]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triple(pub DVec3);

impl<'de> Deserialize<'de> for Triple {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Triple, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Triple;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a number or a list [x, y, z]")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Triple, E> {
                Ok(Triple(DVec3::splat(v)))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Triple, E> {
                Ok(Triple(DVec3::splat(v as f64)))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Triple, E> {
                Ok(Triple(DVec3::splat(v as f64)))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Triple, A::Error> {
                let mut v = [0.0; 3];
                for (i, slot) in v.iter_mut().enumerate() {
                    *slot = seq
                        .next_element()?
                        .ok_or_else(|| de::Error::invalid_length(i, &"3 numbers"))?;
                }
                if seq.next_element::<f64>()?.is_some() {
                    return Err(de::Error::invalid_length(4, &"3 numbers"));
                }
                Ok(Triple(DVec3::from_array(v)))
            }
        }
        d.deserialize_any(V)
    }
}

/// `shadow_bias: auto` or a length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bias {
    Auto,
    Fixed(f64),
}

impl<'de> Deserialize<'de> for Bias {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Bias, D::Error> {
        struct V;
        impl Visitor<'_> for V {
            type Value = Bias;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("`auto` or a length")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Bias, E> {
                Ok(Bias::Fixed(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Bias, E> {
                Ok(Bias::Fixed(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Bias, E> {
                Ok(Bias::Fixed(v as f64))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Bias, E> {
                match v {
                    "auto" => Ok(Bias::Auto),
                    _ => Err(E::invalid_value(de::Unexpected::Str(v), &self)),
                }
            }
        }
        d.deserialize_any(V)
    }
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    pub camera: Option<Spanned<CameraSpec>>,
    pub background: Option<Triple>,
    pub ambient: Option<Triple>,
    pub max_depth: Option<Spanned<i64>>,
    pub adaptive_threshold: Option<Spanned<f64>>,
    pub shadow_bias: Option<Spanned<Bias>>,
    pub spp: Option<Spanned<i64>>,
    pub integrator: Option<Integrator>,
    pub secondary_attenuation: Option<Spanned<[f64; 3]>>,
    #[serde(default)]
    pub lights: Vec<Spanned<LightSpec>>,
    #[serde(default)]
    pub materials: BTreeMap<String, Spanned<MaterialSpec>>,
    #[serde(default)]
    pub objects: Vec<Spanned<ObjectSpec>>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraSpec {
    pub eye: Option<DVec3>,
    pub look_at: Option<DVec3>,
    pub up: Option<Spanned<DVec3>>,
    pub fov: Option<Spanned<f64>>,
    /// `left` (default: +x on the right looking down +z, as the lecture's window model and
    /// POV-Ray) or `right` (+x on the right looking down −z, as Mitsuba).
    pub handedness: Option<Handedness>,
    pub u: Option<DVec3>,
    pub v: Option<DVec3>,
    pub w: Option<DVec3>,
    pub f: Option<f64>,
    pub window: Option<Spanned<[f64; 4]>>,
    pub width: Option<Spanned<i64>>,
    pub height: Option<Spanned<i64>>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightSpec {
    pub name: Option<String>,
    pub point: Option<DVec3>,
    pub direction: Option<Spanned<DVec3>>,
    pub rect: Option<Spanned<RectSpec>>,
    /// Area lights: n × n shadow rays per shaded point (default 3).
    pub samples: Option<Spanned<i64>>,
    pub intensity: Option<Triple>,
    pub attenuation: Option<Spanned<[f64; 3]>>,
}

/// A rectangular area light: `corner + a·u + b·v`, emitting on the side of u × v.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RectSpec {
    pub corner: DVec3,
    pub u: DVec3,
    pub v: DVec3,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    pub color: Option<Triple>,
    pub ka: Option<Spanned<f64>>,
    pub kd: Option<Spanned<f64>>,
    pub ks: Option<Spanned<f64>>,
    pub shininess: Option<Spanned<f64>>,
    pub highlight: Option<Highlight>,
    pub kr: Option<Spanned<f64>>,
    pub kt: Option<Spanned<f64>>,
    pub ior: Option<Spanned<f64>>,
    pub fresnel: Option<Fresnel>,
    pub emission: Option<Triple>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SphereSpec {
    pub center: DVec3,
    pub radius: Spanned<f64>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneSpec {
    pub point: DVec3,
    pub normal: Spanned<DVec3>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxSpec {
    pub min: Spanned<DVec3>,
    pub max: DVec3,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CylinderSpec {
    pub base: Spanned<DVec3>,
    pub top: DVec3,
    pub radius: Spanned<f64>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConeSpec {
    pub apex: Spanned<DVec3>,
    pub base: DVec3,
    pub radius: Spanned<f64>,
}

/// A triangle mesh from a Wavefront OBJ file (relative to the scene file).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshSpec {
    pub file: Spanned<String>,
    /// Interpolate the file's vertex normals (default true).
    pub smooth: Option<bool>,
}

/// A generated unit sphere mesh: an icosahedron subdivided `subdivisions` times.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IcosphereSpec {
    pub subdivisions: Spanned<i64>,
    /// Interpolated vertex normals (default true) or flat facets.
    pub smooth: Option<bool>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum TransformStep {
    Translate(DVec3),
    RotateX(f64),
    RotateY(f64),
    RotateZ(f64),
    Scale(Triple),
}

/// An object, or a CSG child (where `name` and `material` are optional). Exactly one shape
/// key must be present; `compile` checks that.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectSpec {
    pub name: Option<String>,
    pub material: Option<Spanned<String>>,
    #[serde(default)]
    pub transform: Vec<Spanned<TransformStep>>,
    pub sphere: Option<SphereSpec>,
    pub plane: Option<PlaneSpec>,
    #[serde(rename = "box")]
    pub aabox: Option<BoxSpec>,
    pub cylinder: Option<CylinderSpec>,
    pub cone: Option<ConeSpec>,
    pub triangle: Option<Spanned<[DVec3; 3]>>,
    pub mesh: Option<MeshSpec>,
    pub icosphere: Option<IcosphereSpec>,
    pub union: Option<Vec<Spanned<ObjectSpec>>>,
    pub intersection: Option<Vec<Spanned<ObjectSpec>>>,
    pub difference: Option<Vec<Spanned<ObjectSpec>>>,
    pub complement: Option<Box<Spanned<ObjectSpec>>>,
}
