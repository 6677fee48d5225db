//! Scenes built in Rust code instead of read from YAML: the builder fills in the same
//! description a scene file parses into, and `build` compiles it with the same checks, so a
//! scene built in code and one read from a file with the same values are the same scene.
//!
//! ```
//! use glam::DVec3;
//! use raytree::scene::{MaterialDesc, SceneBuilder};
//!
//! let scene = SceneBuilder::new()
//!     .camera(DVec3::new(0.0, 0.0, -5.0), DVec3::ZERO, DVec3::Y, 40.0)
//!     .image_size(64, 48)
//!     .point_light(DVec3::new(-5.0, 5.0, -5.0), DVec3::ONE)
//!     .material("red", MaterialDesc::new(DVec3::new(1.0, 0.0, 0.0)).kd(0.8))
//!     .sphere(DVec3::ZERO, 1.0, "red")
//!     .build()
//!     .expect("a valid scene");
//! assert_eq!(scene.objects.len(), 1);
//! ```

use glam::DVec3;
use serde_saphyr::{Location, Spanned};

use super::compile::{compile, Limits};
use super::error::SceneError;
use super::format::{
    BoxSpec, CameraSpec, CylinderSpec, LightSpec, MaterialSpec, Num, ObjectSpec, PlaneSpec,
    SceneFile, SphereSpec, Triple, Varying, V3,
};
use super::Scene;

/// How a scene built in code is named in its errors (in place of a file name).
pub const BUILDER: &str = "SceneBuilder";

/// A value the builder was given, at no place in any file.
fn at<T>(value: T) -> Spanned<T> {
    Spanned::new(value, Location::UNKNOWN, Location::UNKNOWN)
}

/// A material: a colour and the coefficients of the lecture's local model and of the
/// recursion. Every coefficient left unset takes the scene format's default.
#[derive(Clone, Debug, Default)]
pub struct MaterialDesc {
    color: DVec3,
    ka: Option<f64>,
    kd: Option<f64>,
    ks: Option<f64>,
    shininess: Option<f64>,
    kr: Option<f64>,
    kt: Option<f64>,
    ior: Option<f64>,
    emission: Option<DVec3>,
}

impl MaterialDesc {
    /// A material of colour O (r, g, b).
    pub fn new(color: DVec3) -> MaterialDesc {
        MaterialDesc {
            color,
            ..MaterialDesc::default()
        }
    }
    /// The ambient coefficient ka.
    pub fn ka(mut self, ka: f64) -> Self {
        self.ka = Some(ka);
        self
    }
    /// The diffuse coefficient kd.
    pub fn kd(mut self, kd: f64) -> Self {
        self.kd = Some(kd);
        self
    }
    /// The specular coefficient ks.
    pub fn ks(mut self, ks: f64) -> Self {
        self.ks = Some(ks);
        self
    }
    /// The exponent n of the specular highlight.
    pub fn shininess(mut self, n: f64) -> Self {
        self.shininess = Some(n);
        self
    }
    /// The reflection coefficient kr.
    pub fn kr(mut self, kr: f64) -> Self {
        self.kr = Some(kr);
        self
    }
    /// The transmission coefficient kt.
    pub fn kt(mut self, kt: f64) -> Self {
        self.kt = Some(kt);
        self
    }
    /// The index of refraction inside the surface.
    pub fn ior(mut self, ior: f64) -> Self {
        self.ior = Some(ior);
        self
    }
    /// Light the surface emits (the path tracer's light sources).
    pub fn emission(mut self, e: DVec3) -> Self {
        self.emission = Some(e);
        self
    }
}

/// Builds a `Scene` method by method: camera, lights, materials, objects and settings.
#[derive(Clone, Debug)]
pub struct SceneBuilder {
    file: SceneFile,
    limits: Limits,
    /// The first number given that a scene file could not hold (NaN, ±∞, beyond ±1e100).
    bad_number: Option<String>,
}

impl Default for SceneBuilder {
    fn default() -> Self {
        SceneBuilder::new()
    }
}

impl SceneBuilder {
    /// An empty scene: no camera yet, black background, no lights, materials or objects.
    pub fn new() -> SceneBuilder {
        SceneBuilder {
            file: SceneFile {
                camera: None,
                background: None,
                ambient: None,
                max_depth: None,
                adaptive_threshold: None,
                shadow_bias: None,
                spp: None,
                integrator: None,
                antialias: None,
                aa_threshold: None,
                filter: None,
                secondary_attenuation: None,
                stop_rules: vec![],
                lights: vec![],
                materials: Default::default(),
                objects: vec![],
            },
            limits: Limits::default(),
            bad_number: None,
        }
    }

    /// A number as the scene format accepts it: finite, of magnitude at most 1e100.
    fn num(&mut self, x: f64, what: &str) -> Num {
        if !(x.is_finite() && x.abs() <= 1e100) && self.bad_number.is_none() {
            self.bad_number = Some(format!("{what}: {x} is not a finite number within ±1e100"));
        }
        Num(x)
    }

    fn v3(&mut self, v: DVec3, what: &str) -> V3 {
        for c in v.to_array() {
            self.num(c, what);
        }
        V3(v)
    }

    fn triple(&mut self, v: DVec3, what: &str) -> Triple {
        Triple(self.v3(v, what).0)
    }

    fn camera_spec(&mut self) -> &mut CameraSpec {
        let camera = self.file.camera.get_or_insert_with(|| at(None));
        camera.value.get_or_insert(CameraSpec {
            eye: None,
            look_at: None,
            up: None,
            fov: None,
            handedness: None,
            u: None,
            v: None,
            w: None,
            f: None,
            window: None,
            width: None,
            height: None,
        })
    }

    /// A pinhole camera at `eye` looking at `look_at`, `up` upwards, with a vertical field of
    /// view of `fov_degrees`.
    pub fn camera(mut self, eye: DVec3, look_at: DVec3, up: DVec3, fov_degrees: f64) -> Self {
        let (eye, look_at, up) = (
            self.v3(eye, "camera eye"),
            self.v3(look_at, "camera look_at"),
            self.v3(up, "camera up"),
        );
        let fov = self.num(fov_degrees, "camera fov");
        let c = self.camera_spec();
        c.eye = Some(eye);
        c.look_at = Some(at(look_at));
        c.up = Some(at(up));
        c.fov = Some(at(fov));
        self
    }

    /// The image's size in pixels.
    pub fn image_size(mut self, width: u32, height: u32) -> Self {
        let c = self.camera_spec();
        c.width = Some(at(width as i64));
        c.height = Some(at(height as i64));
        self
    }

    /// The colour of rays that hit nothing.
    pub fn background(mut self, color: DVec3) -> Self {
        let c = self.triple(color, "background");
        self.file.background = Some(at(c));
        self
    }

    /// The ambient light I_a.
    pub fn ambient(mut self, color: DVec3) -> Self {
        let c = self.triple(color, "ambient");
        self.file.ambient = Some(at(c));
        self
    }

    /// Rays per path, the primary ray included.
    pub fn max_depth(mut self, depth: u32) -> Self {
        self.file.max_depth = Some(at(depth as i64));
        self
    }

    /// Primary rays per pixel.
    pub fn spp(mut self, spp: u32) -> Self {
        self.file.spp = Some(at(spp as i64));
        self
    }

    /// The limits the scene is checked against (default: those of a scene file).
    pub fn limits(mut self, limits: Limits) -> Self {
        self.limits = limits;
        self
    }

    fn light(mut self, point: Option<V3>, direction: Option<V3>, intensity: DVec3) -> Self {
        let intensity = self.triple(intensity, "light intensity");
        self.file.lights.push(at(LightSpec {
            name: None,
            point,
            direction: direction.map(at),
            rect: None,
            sphere: None,
            samples: None,
            intensity: Some(intensity),
            attenuation: None,
            surface: None,
        }));
        self
    }

    /// A point light at `position`, of intensity I_p (r, g, b).
    pub fn point_light(mut self, position: DVec3, intensity: DVec3) -> Self {
        let p = self.v3(position, "light position");
        self.light(Some(p), None, intensity)
    }

    /// A directional light shining along `direction`, of intensity I_p (r, g, b).
    pub fn directional_light(mut self, direction: DVec3, intensity: DVec3) -> Self {
        let d = self.v3(direction, "light direction");
        self.light(None, Some(d), intensity)
    }

    /// A material objects can name; a second material of the same name replaces the first.
    pub fn material(mut self, name: &str, m: MaterialDesc) -> Self {
        let mut coefficient = |x: Option<f64>, what: &str| {
            x.map(|x| at(Varying::Value(Triple(DVec3::splat(self.num(x, what).0)))))
        };
        let spec = MaterialSpec {
            kd: coefficient(m.kd, "kd"),
            ks: coefficient(m.ks, "ks"),
            kr: coefficient(m.kr, "kr"),
            kt: coefficient(m.kt, "kt"),
            ka: m.ka.map(|x| at(self.num(x, "ka"))),
            shininess: m.shininess.map(|x| at(self.num(x, "shininess"))),
            ior: m.ior.map(|x| at(self.num(x, "ior"))),
            color: Some(at(Varying::Value(self.triple(m.color, "color")))),
            emission: m.emission.map(|e| at(self.triple(e, "emission"))),
            highlight: None,
            fresnel: None,
            transmitted_highlight: None,
            glossy: None,
            frosted: None,
        };
        self.file.materials.insert(name.to_string(), at(spec));
        self
    }

    fn object(mut self, material: &str, shape: impl FnOnce(&mut ObjectSpec)) -> Self {
        let mut o = ObjectSpec {
            name: None,
            material: Some(at(material.to_string())),
            transform: vec![],
            sphere: None,
            plane: None,
            aabox: None,
            cylinder: None,
            cone: None,
            triangle: None,
            mesh: None,
            icosphere: None,
            union: None,
            intersection: None,
            difference: None,
            complement: None,
            group: None,
        };
        shape(&mut o);
        self.file.objects.push(at(o));
        self
    }

    /// A sphere of `radius` about `center`, of the named material.
    pub fn sphere(mut self, center: DVec3, radius: f64, material: &str) -> Self {
        let (center, radius) = (self.v3(center, "sphere center"), self.num(radius, "radius"));
        self.object(material, |o| {
            o.sphere = Some(Box::new(SphereSpec {
                center,
                radius: at(radius),
            }))
        })
    }

    /// The plane through `point` with the given `normal`, of the named material.
    pub fn plane(mut self, point: DVec3, normal: DVec3, material: &str) -> Self {
        let (point, normal) = (self.v3(point, "plane point"), self.v3(normal, "normal"));
        self.object(material, |o| {
            o.plane = Some(Box::new(PlaneSpec {
                point,
                normal: at(normal),
            }))
        })
    }

    /// The axis-aligned box from corner `min` to corner `max`, of the named material.
    pub fn aabox(mut self, min: DVec3, max: DVec3, material: &str) -> Self {
        let (min, max) = (self.v3(min, "box min"), self.v3(max, "box max"));
        self.object(material, |o| {
            o.aabox = Some(Box::new(BoxSpec { min: at(min), max }))
        })
    }

    /// The capped cylinder of `radius` from the centre of its `base` to that of its `top`.
    pub fn cylinder(mut self, base: DVec3, top: DVec3, radius: f64, material: &str) -> Self {
        let (base, top) = (self.v3(base, "cylinder base"), self.v3(top, "cylinder top"));
        let radius = self.num(radius, "radius");
        self.object(material, |o| {
            o.cylinder = Some(Box::new(CylinderSpec {
                base: at(base),
                top,
                radius: at(radius),
                capped: None,
            }))
        })
    }

    /// The triangle with corners `a`, `b`, `c` (its normal by the right-hand rule).
    pub fn triangle(mut self, [a, b, c]: [DVec3; 3], material: &str) -> Self {
        let corners = [
            self.v3(a, "triangle"),
            self.v3(b, "triangle"),
            self.v3(c, "triangle"),
        ];
        self.object(material, |o| o.triangle = Some(Box::new(at(corners))))
    }

    /// Names the object added last (as the scene file's `name:`), for trees and errors.
    pub fn named(mut self, name: &str) -> Self {
        if let Some(o) = self.file.objects.last_mut() {
            o.value.name = Some(name.to_string());
        }
        self
    }

    /// The scene, checked as a scene file is: a missing camera, an unknown material, a
    /// negative radius and the like are errors named after the builder.
    pub fn build(self) -> Result<Scene, SceneError> {
        if let Some(message) = self.bad_number {
            return Err(SceneError::built(message));
        }
        compile(self.file, None, &self.limits).map_err(|e| SceneError::built(e.message))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::parse;

    /// The builder's scene and the same scene written as YAML are one scene.
    #[test]
    fn a_built_scene_equals_the_same_scene_read_from_yaml() {
        let yaml = "camera: { eye: [0, 1, -4], look_at: [0, 0, 0], up: [0, 1, 0], fov: 50, width: 8, height: 6 }
background: [0.1, 0.2, 0.3]
ambient: 0.2
max_depth: 3
lights:
  - { point: [-3, 4, -2], intensity: [1, 0.9, 0.8] }
  - { direction: [0, -1, 0], intensity: 0.5 }
materials:
  red: { color: [1, 0, 0], kd: 0.7, ks: 0.2, shininess: 20, kr: 0.1 }
  glass: { color: 1, kd: 0, kt: 0.9, ior: 1.5, ka: 0 }
objects:
  - { name: ball, sphere: { center: [0, 0, 0], radius: 1 }, material: red }
  - { plane: { point: [0, -1, 0], normal: [0, 1, 0] }, material: red }
  - { box: { min: [1, -1, 1], max: [2, 0, 2] }, material: glass }
  - { cylinder: { base: [-2, -1, 1], top: [-2, 1, 1], radius: 0.5 }, material: glass }
  - { triangle: [[0, 0, 3], [1, 0, 3], [0, 1, 3]], material: red }
";
        let from_yaml = parse(yaml, "s.yaml", None, &Limits::default()).unwrap();
        let built = SceneBuilder::new()
            .camera(DVec3::new(0.0, 1.0, -4.0), DVec3::ZERO, DVec3::Y, 50.0)
            .image_size(8, 6)
            .background(DVec3::new(0.1, 0.2, 0.3))
            .ambient(DVec3::splat(0.2))
            .max_depth(3)
            .point_light(DVec3::new(-3.0, 4.0, -2.0), DVec3::new(1.0, 0.9, 0.8))
            .directional_light(DVec3::NEG_Y, DVec3::splat(0.5))
            .material(
                "red",
                MaterialDesc::new(DVec3::X)
                    .kd(0.7)
                    .ks(0.2)
                    .shininess(20.0)
                    .kr(0.1),
            )
            .material(
                "glass",
                MaterialDesc::new(DVec3::ONE)
                    .kd(0.0)
                    .kt(0.9)
                    .ior(1.5)
                    .ka(0.0),
            )
            .sphere(DVec3::ZERO, 1.0, "red")
            .named("ball")
            .plane(DVec3::NEG_Y, DVec3::Y, "red")
            .aabox(
                DVec3::new(1.0, -1.0, 1.0),
                DVec3::new(2.0, 0.0, 2.0),
                "glass",
            )
            .cylinder(
                DVec3::new(-2.0, -1.0, 1.0),
                DVec3::new(-2.0, 1.0, 1.0),
                0.5,
                "glass",
            )
            .triangle(
                [
                    DVec3::new(0.0, 0.0, 3.0),
                    DVec3::X + DVec3::new(0.0, 0.0, 3.0),
                    DVec3::new(0.0, 1.0, 3.0),
                ],
                "red",
            )
            .build()
            .unwrap();
        // Everything but where the scene came from is the same.
        assert_eq!(format!("{:?}", built), format!("{:?}", from_yaml));
    }

    #[test]
    fn a_built_scene_is_checked_as_a_file_is() {
        let e = SceneBuilder::new()
            .sphere(DVec3::ZERO, 1.0, "m")
            .build()
            .unwrap_err();
        assert!(
            e.to_string().starts_with("SceneBuilder: missing `camera`"),
            "{e}"
        );
        let camera = || SceneBuilder::new().camera(DVec3::NEG_Z, DVec3::ZERO, DVec3::Y, 40.0);
        let e = camera()
            .sphere(DVec3::ZERO, 1.0, "nowhere")
            .build()
            .unwrap_err();
        assert!(e.to_string().contains("nowhere"), "{e}");
        let e = camera()
            .background(DVec3::splat(f64::NAN))
            .build()
            .unwrap_err();
        assert!(e.to_string().contains("background"), "{e}");
    }
}
