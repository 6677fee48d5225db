//! The scene file as a student writes it: serde structs that mirror the YAML keys. Nothing
//! here is validated beyond types; `compile` turns it into a runtime `Scene`.

use std::collections::BTreeMap;
use std::fmt;

use glam::DVec3;
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::Deserialize;
use serde_saphyr::Spanned;

pub use crate::geometry::MAX_MAGNITUDE;
use crate::shading::texture::Mapping;
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
    /// Whitted's recursion: local shading plus one reflection and one refraction ray per hit (the
    /// lecture's ray tree).
    #[default]
    Whitted,
    /// A Monte Carlo path tracer: one randomly chosen continuation per hit, averaged over many
    /// samples.
    Path,
}

/// A rule that ends a ray's recursion besides the background and the maximum depth (see
/// `StopRules`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StopRule {
    Light,
    Diffuse,
    LocalAtMaxDepth,
}

/// Where a pixel's primary rays go (see `render::antialias`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AntialiasMode {
    #[default]
    Grid,
    Jittered,
    Adaptive,
}

/// The reconstruction filter of jittered sampling.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FilterKind {
    #[default]
    Box,
    Gaussian,
}

fn check<E: de::Error>(v: f64) -> Result<f64, E> {
    if !v.is_finite() {
        Err(E::custom(format!(
            "non-finite number `{v}`: every number in a scene must be finite"
        )))
    } else if v.abs() > MAX_MAGNITUDE {
        Err(E::custom(format!(
            "number {v:e} is too large: numbers must lie within ±1e100"
        )))
    } else {
        Ok(v)
    }
}

/// A finite number of sensible magnitude (NaN, ±∞ and |x| > 1e100 are refused where they
/// are written, however they are spelled: `.nan`, `".inf"`, `1e308`).
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct Num(pub f64);

impl<'de> Deserialize<'de> for Num {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Num, D::Error> {
        // Read as a float (so errors point at the value itself), then refuse NaN, ±∞ and
        // magnitudes whose squares would overflow, however they were spelled.
        check(f64::deserialize(d)?).map(Num)
    }
}

impl std::ops::Deref for Num {
    type Target = f64;
    fn deref(&self) -> &f64 {
        &self.0
    }
}

/// As written where it is of a usual size (0.25, 180, 0), in scientific notation where its
/// digits would run on in a message (1e50, not fifty zeros; 1e-300).
impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        let x = self.0;
        if x == 0.0 || !x.is_finite() || (1e-4..1e7).contains(&x.abs()) {
            write!(f, "{x}")
        } else {
            write!(f, "{x:e}")
        }
    }
}

/// A vector `[x, y, z]` of such numbers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct V3(pub DVec3);

impl<'de> Deserialize<'de> for V3 {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<V3, D::Error> {
        let [x, y, z] = <[Num; 3]>::deserialize(d)?;
        Ok(V3(DVec3::new(x.0, y.0, z.0)))
    }
}

impl std::ops::Deref for V3 {
    type Target = DVec3;
    fn deref(&self) -> &DVec3 {
        &self.0
    }
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
                Ok(Triple(DVec3::splat(check(v)?)))
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
                    let n: Num = seq
                        .next_element()?
                        .ok_or_else(|| de::Error::invalid_length(i, &"3 numbers"))?;
                    *slot = n.0;
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
                Ok(Bias::Fixed(check(v)?))
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
    /// `camera:` with nothing after it is `Some(None)`, so its position can be reported.
    pub camera: Option<Spanned<Option<CameraSpec>>>,
    pub background: Option<Spanned<Triple>>,
    pub ambient: Option<Spanned<Triple>>,
    pub max_depth: Option<Spanned<i64>>,
    pub adaptive_threshold: Option<Spanned<Num>>,
    pub shadow_bias: Option<Spanned<Bias>>,
    pub spp: Option<Spanned<i64>>,
    pub integrator: Option<Integrator>,
    /// `grid` (default), `jittered` or `adaptive`, with `spp` samples per pixel.
    pub antialias: Option<AntialiasMode>,
    /// Adaptive antialiasing splits a square whose corners differ by more than this.
    pub aa_threshold: Option<Spanned<Num>>,
    /// `box` (default) or `gaussian` (Mitsuba's): how jittered samples are spread.
    pub filter: Option<FilterKind>,
    pub secondary_attenuation: Option<Spanned<[Num; 3]>>,
    /// `[light, diffuse, local_at_max_depth]`: the notes' other stop rules (default none).
    #[serde(default)]
    pub stop_rules: Vec<StopRule>,
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
    pub eye: Option<V3>,
    pub look_at: Option<Spanned<V3>>,
    pub up: Option<Spanned<V3>>,
    pub fov: Option<Spanned<Num>>,
    /// `left` (default: +x on the right looking down +z, as the lecture's window model and
    /// POV-Ray) or `right` (+x on the right looking down −z, as Mitsuba).
    pub handedness: Option<Spanned<Handedness>>,
    pub u: Option<Spanned<V3>>,
    pub v: Option<Spanned<V3>>,
    pub w: Option<Spanned<V3>>,
    pub f: Option<Spanned<Num>>,
    pub window: Option<Spanned<[Num; 4]>>,
    pub width: Option<Spanned<i64>>,
    pub height: Option<Spanned<i64>>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightSpec {
    pub name: Option<String>,
    pub point: Option<V3>,
    pub direction: Option<Spanned<V3>>,
    pub rect: Option<Spanned<RectSpec>>,
    pub sphere: Option<Spanned<SphereSpec>>,
    /// Area lights: n × n shadow rays per shaded point (default 3).
    pub samples: Option<Spanned<i64>>,
    pub intensity: Option<Triple>,
    pub attenuation: Option<Spanned<[Num; 3]>>,
    /// Area lights in the path tracer: the material of the emitting surface, which then also
    /// reflects light like any surface (Mitsuba's Cornell-box light is white).
    pub surface: Option<Spanned<String>>,
}

/// A rectangular area light: `corner + a·u + b·v`, emitting on the side of u × v.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RectSpec {
    pub corner: V3,
    pub u: V3,
    pub v: V3,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// A colour, or a pattern or texture of colours.
    pub color: Option<Spanned<Varying>>,
    pub ka: Option<Spanned<Num>>,
    /// kd, ks, kr and kt: a number, or a pattern of numbers.
    pub kd: Option<Spanned<Varying>>,
    pub ks: Option<Spanned<Varying>>,
    pub shininess: Option<Spanned<Num>>,
    pub highlight: Option<Highlight>,
    pub kr: Option<Spanned<Varying>>,
    pub kt: Option<Spanned<Varying>>,
    pub ior: Option<Spanned<Num>>,
    pub fresnel: Option<Fresnel>,
    /// Hall's transmitted highlight H′ for lights behind a transparent surface (default false).
    pub transmitted_highlight: Option<bool>,
    /// Light the surface gives off itself (r, g, b ≥ 0; path tracing).
    pub emission: Option<Spanned<Triple>>,
    /// Glossy reflection: the reflection ray becomes `samples` rays about the mirror direction.
    pub glossy: Option<Spanned<LobeSpec>>,
    /// Frosted refraction: the refraction ray becomes `samples` rays about Snell's direction.
    pub frosted: Option<Spanned<LobeSpec>>,
}

/// A value that may vary over a surface: a number or colour, or a mapping that describes a
/// pattern (`{ pattern: checker, colors: [A, B], transform: [...] }`) or an image texture
/// (`{ image: FILE, mapping: spherical, transform: [...] }`).
#[derive(Clone, Debug)]
pub enum Varying {
    Value(Triple),
    Pattern(Box<PatternSpec>),
}

impl<'de> Deserialize<'de> for Varying {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Varying, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Varying;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str(
                    "a number, a list [r, g, b], or a pattern { pattern: ..., colors: [A, B] } or texture { image: FILE }",
                )
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Varying, E> {
                Ok(Varying::Value(Triple(DVec3::splat(check(v)?))))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Varying, E> {
                Ok(Varying::Value(Triple(DVec3::splat(v as f64))))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Varying, E> {
                Ok(Varying::Value(Triple(DVec3::splat(v as f64))))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Varying, A::Error> {
                Triple::deserialize(de::value::SeqAccessDeserializer::new(seq)).map(Varying::Value)
            }
            fn visit_map<A: de::MapAccess<'de>>(self, map: A) -> Result<Varying, A::Error> {
                PatternSpec::deserialize(de::value::MapAccessDeserializer::new(map))
                    .map(|p| Varying::Pattern(Box::new(p)))
            }
        }
        d.deserialize_any(V)
    }
}

/// The kinds of pattern (see `crate::shading::pattern`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PatternName {
    Stripes,
    Gradient,
    Rings,
    Checker,
    UvChecker,
    Blend,
}

/// A pattern (`pattern:`) or an image texture (`image:`).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PatternSpec {
    pub pattern: Option<Spanned<PatternName>>,
    /// An image file (PNG, or EXR for linear values), relative to the scene file.
    pub image: Option<Spanned<String>>,
    /// The two values A and B (numbers, colours or patterns); `values` is the same key.
    #[serde(alias = "values")]
    pub colors: Option<Spanned<Vec<Spanned<Varying>>>>,
    /// How an image or a uv checker finds (u, v): `uv` (the surface's own, default),
    /// `spherical`, `planar`, `cylindrical` or `cube`.
    pub mapping: Option<Spanned<Mapping>>,
    /// A uv checker's squares across and up the unit square.
    pub width: Option<Spanned<Num>>,
    pub height: Option<Spanned<Num>>,
    /// A blend's share of B: (1 − w)·A + w·B (default ½).
    pub weight: Option<Spanned<Num>>,
    /// Places the pattern, as object transforms place objects (in the order written).
    #[serde(default)]
    pub transform: Vec<Spanned<TransformStep>>,
}

/// A lobe: `spread` (degrees, the standard deviation of a normal distribution, as seed 000
/// says) or `exponent` (a Phong lobe cosⁿ), and the number of rays.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LobeSpec {
    pub spread: Option<Spanned<Num>>,
    pub exponent: Option<Spanned<Num>>,
    pub samples: Option<Spanned<i64>>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SphereSpec {
    pub center: V3,
    pub radius: Spanned<Num>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlaneSpec {
    pub point: V3,
    pub normal: Spanned<V3>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxSpec {
    pub min: Spanned<V3>,
    pub max: V3,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CylinderSpec {
    pub base: Spanned<V3>,
    pub top: V3,
    pub radius: Spanned<Num>,
    /// False for an open tube, a surface without caps or inside (default true).
    pub capped: Option<bool>,
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConeSpec {
    pub apex: Spanned<V3>,
    pub base: V3,
    pub radius: Spanned<Num>,
    /// False for an open cone, a surface without base or inside (default true).
    pub capped: Option<bool>,
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
    Translate(V3),
    RotateX(Num),
    RotateY(Num),
    RotateZ(Num),
    Scale(Triple),
}

/// An object, a CSG child or a group member (where `name` and `material` are optional).
/// Exactly one shape key must be present; `compile` checks that.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectSpec {
    pub name: Option<String>,
    pub material: Option<Spanned<String>>,
    #[serde(default)]
    pub transform: Vec<Spanned<TransformStep>>,
    // The shapes are boxed so that an object does not carry room for all of them: a list of
    // many thousand objects stays small while it is parsed.
    pub sphere: Option<Box<SphereSpec>>,
    pub plane: Option<Box<PlaneSpec>>,
    #[serde(rename = "box")]
    pub aabox: Option<Box<BoxSpec>>,
    pub cylinder: Option<Box<CylinderSpec>>,
    pub cone: Option<Box<ConeSpec>>,
    pub triangle: Option<Box<Spanned<[V3; 3]>>>,
    pub mesh: Option<Box<MeshSpec>>,
    pub icosphere: Option<Box<IcosphereSpec>>,
    pub union: Option<Vec<Spanned<ObjectSpec>>>,
    pub intersection: Option<Vec<Spanned<ObjectSpec>>>,
    pub difference: Option<Vec<Spanned<ObjectSpec>>>,
    pub complement: Option<Box<Spanned<ObjectSpec>>>,
    /// Objects moved together by the group's `transform`, those without a material taking
    /// the group's; the search treats the group as one object with its own hierarchy.
    pub group: Option<Vec<Spanned<ObjectSpec>>>,
}
