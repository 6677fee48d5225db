//! Compiling a scene file into a runtime scene: every value validated (with its position in
//! the file), names resolved, transforms composed and inverted, bounds computed.

use std::collections::{BTreeMap, HashSet};
use std::path::PathBuf;

use glam::{DAffine3, DVec3};
use serde_saphyr::Spanned;

use super::error::{invalid, Invalid, Pos};
use super::format::{
    AntialiasMode, Bias, CameraSpec, FilterKind, LightSpec, LobeSpec, MaterialSpec, ObjectSpec,
    SceneFile, TransformStep, Triple,
};
use super::objects::{Geometry, Leaf, Object};
use super::{
    Antialias, Camera, Features, Filter, Projection, Scene, SearchIndex, DEFAULT_THRESHOLD,
};
use crate::accel::{Aabb, Ball};
use crate::geometry::csg::{CsgNode, CsgOp};
use crate::geometry::{Aabox, Cone, Cylinder, Plane, Shape, Sphere, Transform, Triangle};
use crate::shading::{Fresnel, Highlight, Light, LightKind, Lobe, LobeShape, Material};

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

pub fn compile(
    file: SceneFile,
    source: Option<PathBuf>,
    limits: &Limits,
) -> Result<Scene, Invalid> {
    let camera =
        match &file.camera {
            Some(Spanned {
                value: None,
                referenced,
                ..
            }) => {
                return invalid(
                    Pos::of(referenced),
                    "`camera` is empty: give eye and look_at, or the window model",
                )
            }
            Some(
                c @ Spanned {
                    value: Some(spec), ..
                },
            ) => camera(spec, pos(c), limits)?,
            None => return invalid(
                TOP,
                "missing `camera`: a scene needs a camera (eye and look_at, or the window model)",
            ),
        };
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
                    a.value
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
                format!("shadow_bias must be `auto` or ≥ 0, got {v}"),
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

    let mut lights = Vec::new();
    let mut light_names = HashSet::new();
    for (i, l) in file.lights.iter().enumerate() {
        let light = light(&l.value, pos(l), i)?;
        if !light_names.insert(light.name.clone()) {
            return invalid(pos(l), format!("duplicate light name `{}`", light.name));
        }
        lights.push(light);
    }

    let mut materials = Vec::new();
    let mut material_index = BTreeMap::new();
    for (name, m) in &file.materials {
        material_index.insert(name.clone(), materials.len() as u32);
        materials.push(material(name, &m.value, pos(m))?);
    }
    for (l, light) in file.lights.iter().zip(&mut lights) {
        let Some(surface) = &l.value.surface else {
            continue;
        };
        if !matches!(
            light.kind,
            LightKind::Rect { .. } | LightKind::Sphere { .. }
        ) {
            return invalid(
                pos(surface),
                format!(
                    "light `{}`: only area (`rect` and `sphere`) lights have a surface",
                    light.name
                ),
            );
        }
        match material_index.get(&surface.value) {
            Some(&m) => light.surface = Some(m),
            None => {
                return invalid(
                    pos(surface),
                    format!(
                        "light `{}`: unknown material `{}` for its surface",
                        light.name, surface.value
                    ),
                )
            }
        }
    }

    let base = source
        .as_ref()
        .and_then(|p| p.parent())
        .map(|p| p.to_path_buf())
        .unwrap_or_default();
    let mut builder = Builder {
        materials: &material_index,
        leaves: Vec::new(),
        limits,
        base: &base,
    };
    let mut objects = Vec::new();
    let mut names = HashSet::new();
    for (i, o) in file.objects.iter().enumerate() {
        let name = o
            .value
            .name
            .clone()
            .unwrap_or_else(|| format!("object{}", i + 1));
        if !names.insert(name.clone()) {
            return invalid(pos(o), format!("duplicate object name `{name}`"));
        }
        let Some(m) = &o.value.material else {
            return invalid(pos(o), format!("object `{name}` has no `material`"));
        };
        let material = builder.material(m)?;
        let object = objects.len() as u32;
        let mut ctx = Ctx {
            object,
            object_name: &name,
            path: vec![],
            leaf_count: 0,
            depth: 0,
        };
        let node = builder.node(
            o,
            material,
            &Transform::new(DAffine3::IDENTITY),
            &mut ctx,
            true,
        )?;
        let (geometry, bounds) = match node {
            CsgNode::Leaf { leaf, bounds } => {
                builder.leaves[leaf as usize].name = name.clone();
                (Geometry::Leaf(leaf), bounds)
            }
            node => {
                let b = node.bounds();
                (Geometry::Csg(node), b)
            }
        };
        objects.push(Object {
            name,
            geometry,
            bounds,
        });
    }

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
    let scene = Scene {
        source,
        camera,
        background: file.background.map_or(DVec3::ZERO, |t| t.0),
        ambient: file.ambient.map_or(DVec3::ZERO, |t| t.0),
        lights,
        materials,
        leaves: builder.leaves,
        objects,
        max_depth,
        adaptive_threshold,
        shadow_bias,
        secondary_attenuation,
        csg_pruning: true,
        spp,
        integrator,
        antialias,
        filter,
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

fn camera(c: &CameraSpec, p: Pos, limits: &Limits) -> Result<Camera, Invalid> {
    let size = |s: &Option<Spanned<i64>>, default: i64, what: &str| -> Result<u32, Invalid> {
        let (v, at) = s.as_ref().map_or((default, p), |s| (s.value, pos(s)));
        if !(1..=1_000_000).contains(&v) {
            return invalid(
                at,
                format!("camera {what} must be between 1 and 1000000 pixels, got {v}"),
            );
        }
        Ok(v as u32)
    };
    let width = size(&c.width, 320, "width")?;
    let height = size(&c.height, 240, "height")?;
    if width as u64 * height as u64 > limits.max_pixels {
        return invalid(
            c.width.as_ref().map_or(p, pos),
            format!(
                "image of {width} × {height} pixels exceeds the budget of {} pixels (use --allow-huge to render it anyway)",
                limits.max_pixels
            ),
        );
    }
    let Some(eye) = c.eye.map(|v| v.0) else {
        return invalid(p, "camera needs an `eye`");
    };
    if let Some(window) = &c.window {
        let need = |v: Option<DVec3>, k: &str| {
            v.map_or_else(|| invalid(p, format!("window camera needs `{k}`")), Ok)
        };
        let (u, v, w) = (
            need(c.u.as_ref().map(|x| x.value.0), "u")?,
            need(c.v.as_ref().map(|x| x.value.0), "v")?,
            need(c.w.as_ref().map(|x| x.value.0), "w")?,
        );
        let f = c.f.map(|n| n.0).map_or_else(
            || invalid(p, "window camera needs the focal distance `f`"),
            Ok,
        )?;
        for (axis, k) in [(&c.u, "u"), (&c.v, "v"), (&c.w, "w")] {
            let axis = axis.as_ref().expect("checked above");
            nonzero(axis.value.0, pos(axis), &format!("camera axis {k}"))?;
        }
        let [wl, wr, wt, wb] = window.value.map(|n| n.0);
        if wl == wr || wt == wb {
            return invalid(
                pos(window),
                "camera window has zero width or height (wl = wr or wt = wb)",
            );
        }
        if c.look_at.is_some() || c.fov.is_some() {
            return invalid(
                p,
                "camera mixes the window model (window, u, v, w, f) with look_at/fov: use one",
            );
        }
        return Ok(Camera {
            projection: Projection::Window {
                eye,
                u,
                v,
                w,
                f,
                window: window.value.map(|n| n.0),
            },
            width,
            height,
        });
    }
    let Some(target) = c.look_at.map(|v| v.0) else {
        return invalid(
            p,
            "camera needs `look_at` (or the window model: u, v, w, f, window)",
        );
    };
    let forward = nonzero(target - eye, p, "look_at − eye")?;
    let (up, up_pos) = c.up.as_ref().map_or((DVec3::Y, p), |u| (u.value.0, pos(u)));
    let up = nonzero(up, up_pos, "camera up")?;
    if forward.cross(up).length() < 1e-9 {
        return invalid(
            up_pos,
            "camera up is parallel to the view direction (look_at − eye)",
        );
    }
    let fov = match &c.fov {
        None => 40.0,
        Some(f) if !(f.value.0 > 0.0 && f.value.0 < 180.0) => {
            return invalid(
                pos(f),
                format!(
                    "fov must be between 0 and 180 degrees (exclusive), got {}",
                    f.value
                ),
            )
        }
        Some(f) => f.value.0,
    };
    Ok(match c.handedness.unwrap_or_default() {
        super::format::Handedness::Left => Camera::look_at(eye, target, up, fov, width, height),
        super::format::Handedness::Right => {
            Camera::look_at_right_handed(eye, target, up, fov, width, height)
        }
    })
}

fn attenuation(a: &Spanned<[super::format::Num; 3]>) -> Result<[f64; 3], Invalid> {
    let [c0, c1, c2] = a.value.map(|n| n.0);
    if c0 < 0.0 || c1 < 0.0 || c2 < 0.0 || c0 + c1 + c2 <= 0.0 {
        return invalid(
            pos(a),
            "attenuation [c0, c1, c2] must be ≥ 0 and not all zero",
        );
    }
    Ok([c0, c1, c2])
}

fn light(l: &LightSpec, p: Pos, i: usize) -> Result<Light, Invalid> {
    let name = l.name.clone().unwrap_or_else(|| format!("light{}", i + 1));
    let intensity = l.intensity.map_or(DVec3::ONE, |t| t.0);
    if intensity.min_element() < 0.0 {
        return invalid(p, format!("light `{name}` has a negative intensity"));
    }
    let given = [
        l.point.is_some(),
        l.direction.is_some(),
        l.rect.is_some(),
        l.sphere.is_some(),
    ]
    .iter()
    .filter(|&&b| b)
    .count();
    if given != 1 {
        return invalid(
            p,
            format!("light `{name}` needs exactly one of `point`, `direction`, `rect` or `sphere`"),
        );
    }
    if l.samples.is_some() && l.rect.is_none() && l.sphere.is_none() {
        return invalid(
            p,
            format!("light `{name}`: `samples` is for area (`rect` and `sphere`) lights"),
        );
    }
    let samples = match &l.samples {
        None => 3,
        Some(s) if !(1..=64).contains(&s.value) => {
            return invalid(
                pos(s),
                format!(
                    "light `{name}`: samples must be between 1 and 64, got {}",
                    s.value
                ),
            )
        }
        Some(s) => s.value as u32,
    };
    let kind = if let Some(position) = l.point.map(|v| v.0) {
        let attenuation = match &l.attenuation {
            Some(a) => attenuation(a)?,
            None => [1.0, 0.0, 0.0],
        };
        LightKind::Point {
            position,
            attenuation,
        }
    } else if let Some(sphere) = &l.sphere {
        let radius = sphere.value.radius.value.0;
        if radius <= 0.0 {
            return invalid(
                pos(&sphere.value.radius),
                format!("light `{name}`: the sphere's radius must be > 0, got {radius}"),
            );
        }
        LightKind::Sphere {
            center: sphere.value.center.0,
            radius,
            attenuation: match &l.attenuation {
                Some(a) => attenuation(a)?,
                None => [1.0, 0.0, 0.0],
            },
            samples,
        }
    } else if l.attenuation.is_some() {
        return invalid(
            p,
            format!("light `{name}`: only point and sphere lights have distance attenuation"),
        );
    } else if let Some(d) = &l.direction {
        LightKind::Directional {
            direction: nonzero(d.value.0, pos(d), "light direction")?,
        }
    } else {
        let r = l.rect.as_ref().expect("counted above");
        let (corner, u, v) = (r.value.corner.0, r.value.u.0, r.value.v.0);
        if u.cross(v).length() < 1e-12 {
            return invalid(
                pos(r),
                format!(
                    "light `{name}`: the rectangle's edges u and v must not be parallel or zero"
                ),
            );
        }
        LightKind::Rect {
            corner,
            u,
            v,
            samples,
        }
    };
    Ok(Light {
        name,
        kind,
        intensity,
        surface: None,
    })
}

fn material(name: &str, m: &MaterialSpec, p: Pos) -> Result<Material, Invalid> {
    let coefficient = |c: &Option<Spanned<super::format::Num>>, k: &str| -> Result<f64, Invalid> {
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
        Some(i) if i.value.0 <= 0.0 => {
            return invalid(
                pos(i),
                format!("material `{name}`: ior must be > 0, got {}", i.value),
            )
        }
        Some(i) => i.value.0,
    };
    let shininess = match &m.shininess {
        None => 1.0,
        Some(s) => coefficient(&Some(s.clone()), "shininess")?,
    };
    let color = m.color.map_or(DVec3::ONE, |t| t.0);
    if color.min_element() < 0.0 {
        return invalid(p, format!("material `{name}`: color must be ≥ 0"));
    }
    Ok(Material {
        name: name.to_string(),
        color,
        ka: coefficient(&m.ka, "ka")?,
        kd: coefficient(&m.kd, "kd")?,
        ks: coefficient(&m.ks, "ks")?,
        shininess,
        highlight: m.highlight.unwrap_or(Highlight::Blinn),
        kr: coefficient(&m.kr, "kr")?,
        kt: coefficient(&m.kt, "kt")?,
        ior,
        fresnel: m.fresnel.unwrap_or(Fresnel::None),
        emission: m.emission.map_or(DVec3::ZERO, |t| t.0),
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
                        s.value
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
                        e.value
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

struct Builder<'a> {
    materials: &'a BTreeMap<String, u32>,
    leaves: Vec<Leaf>,
    limits: &'a Limits,
    /// Folder of the scene file: mesh files are found relative to it.
    base: &'a std::path::Path,
}

/// Where in an object's CSG tree the builder is.
struct Ctx<'a> {
    object: u32,
    object_name: &'a str,
    path: Vec<String>,
    leaf_count: usize,
    depth: usize,
}

impl Builder<'_> {
    fn material(&self, m: &Spanned<String>) -> Result<u32, Invalid> {
        self.materials.get(&m.value).copied().map_or_else(
            || {
                let known: Vec<&str> = self.materials.keys().map(String::as_str).collect();
                invalid(
                    pos(m),
                    format!(
                        "unknown material `{}` (defined: {})",
                        m.value,
                        known.join(", ")
                    ),
                )
            },
            Ok,
        )
    }

    fn node(
        &mut self,
        o: &Spanned<ObjectSpec>,
        material: u32,
        parent: &Transform,
        ctx: &mut Ctx,
        top: bool,
    ) -> Result<CsgNode, Invalid> {
        let spec = &o.value;
        let p = pos(o);
        if ctx.depth > self.limits.max_csg_depth {
            return invalid(
                p,
                format!(
                    "CSG tree nested deeper than {} levels",
                    self.limits.max_csg_depth
                ),
            );
        }
        let material = match &spec.material {
            Some(m) if !top => self.material(m)?,
            _ => material,
        };
        let transform = parent.after(&transform(&spec.transform)?);
        let shapes = [
            spec.sphere.is_some(),
            spec.plane.is_some(),
            spec.aabox.is_some(),
            spec.cylinder.is_some(),
            spec.cone.is_some(),
            spec.triangle.is_some(),
            spec.mesh.is_some(),
            spec.icosphere.is_some(),
            spec.union.is_some(),
            spec.intersection.is_some(),
            spec.difference.is_some(),
            spec.complement.is_some(),
        ];
        match shapes.iter().filter(|&&b| b).count() {
            1 => {}
            0 => return invalid(p, "no shape: give one of sphere, plane, box, cylinder, cone, triangle, mesh, icosphere, union, intersection, difference, complement"),
            _ => return invalid(p, "more than one shape key in one object: nest them in a union, or write two objects"),
        }
        let csg = [
            (CsgOp::Union, &spec.union),
            (CsgOp::Intersection, &spec.intersection),
            (CsgOp::Difference, &spec.difference),
        ];
        for (op, children) in csg {
            if let Some(children) = children {
                if children.len() < 2 {
                    return invalid(p, format!("{} needs at least two children", op.name()));
                }
                return self.operation(
                    op,
                    spec.name.clone(),
                    children.iter().collect(),
                    material,
                    &transform,
                    ctx,
                );
            }
        }
        if let Some(child) = &spec.complement {
            return self.operation(
                CsgOp::Complement,
                spec.name.clone(),
                vec![&**child],
                material,
                &transform,
                ctx,
            );
        }
        let shape = shape(spec, p, self.base)?;
        if !top && !shape.is_convex_solid() {
            return invalid(
                p,
                format!("a {} cannot take part in CSG: its segment list is not one interval (use spheres, boxes, cylinders, cones)", shape.kind()),
            );
        }
        ctx.leaf_count += 1;
        let name = spec
            .name
            .clone()
            .unwrap_or_else(|| format!("{}.{}{}", ctx.object_name, shape.kind(), ctx.leaf_count));
        // A shape the transform keeps of its kind is stored in world space: no ray needs
        // carrying to object space for it.
        let (shape, transform) = if transform.to_world == DAffine3::IDENTITY {
            (shape, None)
        } else {
            match shape.moved(&transform) {
                Some(moved) => (moved, None),
                None => (shape, Some(transform)),
            }
        };
        let bounds = match &transform {
            Some(tf) => shape.bounds().transformed(&tf.to_world),
            None => shape.bounds(),
        };
        let leaf = self.leaves.len() as u32;
        self.leaves.push(Leaf {
            name,
            object: ctx.object,
            path: ctx.path.clone(),
            shape,
            transform,
            material,
            bounds,
        });
        Ok(CsgNode::Leaf { leaf, bounds })
    }

    fn operation(
        &mut self,
        op: CsgOp,
        name: Option<String>,
        children: Vec<&Spanned<ObjectSpec>>,
        material: u32,
        transform: &Transform,
        ctx: &mut Ctx,
    ) -> Result<CsgNode, Invalid> {
        let name = name.unwrap_or_else(|| op.name().to_string());
        ctx.path.push(name.clone());
        ctx.depth += 1;
        let mut nodes = Vec::with_capacity(children.len());
        for c in children {
            nodes.push(self.node(c, material, transform, ctx, false)?);
        }
        ctx.depth -= 1;
        ctx.path.pop();
        // A result lies inside the first child for ∩ and −, inside some child for ∪.
        let bounds = match op {
            CsgOp::Union => nodes
                .iter()
                .fold(Aabb::empty(), |b, n| b.union(&n.bounds())),
            CsgOp::Intersection => nodes
                .iter()
                .fold(Aabb::everything(), |b, n| b.intersection(&n.bounds())),
            CsgOp::Difference => nodes[0].bounds(),
            CsgOp::Complement => Aabb::everything(),
        };
        // Spheres' common parts are bounded far more tightly by a ball than by their boxes.
        let bounds = match self.ball(op, &nodes) {
            Some(ball) => bounds.intersection(&ball.bounds()),
            None => bounds,
        };
        Ok(CsgNode::Op {
            op,
            name,
            children: nodes,
            bounds,
        })
    }

    /// A ball around an operation's result, when one is known: spheres in world space, and
    /// what intersections and differences keep of them.
    fn ball(&self, op: CsgOp, children: &[CsgNode]) -> Option<Ball> {
        let ball = |node: &CsgNode| match node {
            CsgNode::Leaf { leaf, .. } => self.leaves[*leaf as usize]
                .world_sphere()
                .map(|s| Ball::new(s.center, s.radius)),
            CsgNode::Op { op, children, .. } => self.ball(*op, children),
        };
        match op {
            CsgOp::Intersection => children
                .iter()
                .filter_map(ball)
                .reduce(|a, b| a.around_common(&b)),
            CsgOp::Difference => ball(&children[0]),
            CsgOp::Union | CsgOp::Complement => None,
        }
    }
}

/// The steps compose in the order written: the first step is applied first.
fn transform(steps: &[Spanned<TransformStep>]) -> Result<Transform, Invalid> {
    let mut m = DAffine3::IDENTITY;
    for s in steps {
        let step = match &s.value {
            TransformStep::Translate(v) => DAffine3::from_translation(v.0),
            TransformStep::RotateX(d) => DAffine3::from_rotation_x(d.0.to_radians()),
            TransformStep::RotateY(d) => DAffine3::from_rotation_y(d.0.to_radians()),
            TransformStep::RotateZ(d) => DAffine3::from_rotation_z(d.0.to_radians()),
            TransformStep::Scale(Triple(v)) => {
                if v.abs().min_element() < 1e-12 {
                    return invalid(pos(s), "scale must not be zero in any axis");
                }
                DAffine3::from_scale(*v)
            }
        };
        m = step * m;
    }
    Ok(Transform::new(m))
}

fn shape(spec: &ObjectSpec, p: Pos, base: &std::path::Path) -> Result<Shape, Invalid> {
    let positive = |r: &Spanned<super::format::Num>, what: &str| -> Result<f64, Invalid> {
        if r.value.0 > 0.0 {
            Ok(r.value.0)
        } else {
            invalid(pos(r), format!("{what} must be > 0, got {}", r.value))
        }
    };
    if let Some(s) = &spec.sphere {
        return Ok(Shape::Sphere(Sphere {
            center: s.center.0,
            radius: positive(&s.radius, "sphere radius")?,
        }));
    }
    if let Some(s) = &spec.plane {
        return Ok(Shape::Plane(Plane {
            point: s.point.0,
            normal: nonzero(s.normal.value.0, pos(&s.normal), "plane normal")?,
        }));
    }
    if let Some(s) = &spec.aabox {
        if !(s.min.value.0.cmplt(s.max.0).all()) {
            return invalid(
                pos(&s.min),
                "box min must be smaller than max in every axis",
            );
        }
        return Ok(Shape::Box(Aabox {
            min: s.min.value.0,
            max: s.max.0,
        }));
    }
    if let Some(s) = &spec.cylinder {
        let radius = positive(&s.radius, "cylinder radius")?;
        nonzero(
            s.top.0 - s.base.value.0,
            pos(&s.base),
            "cylinder axis (top − base)",
        )?;
        return Ok(Shape::Cylinder(Cylinder {
            base: s.base.value.0,
            top: s.top.0,
            radius,
        }));
    }
    if let Some(s) = &spec.cone {
        let radius = positive(&s.radius, "cone radius")?;
        nonzero(
            s.base.0 - s.apex.value.0,
            pos(&s.apex),
            "cone axis (base − apex)",
        )?;
        return Ok(Shape::Cone(Cone {
            apex: s.apex.value.0,
            base: s.base.0,
            radius,
        }));
    }
    if let Some(t) = &spec.triangle {
        let [a, b, c] = t.value.map(|v| v.0);
        let tri = Triangle { a, b, c };
        if tri.normal() == DVec3::ZERO {
            return invalid(
                pos(t),
                "degenerate triangle: its three vertices are collinear",
            );
        }
        return Ok(Shape::Triangle(tri));
    }
    if let Some(m) = &spec.mesh {
        let path = base.join(&m.file.value);
        let (mesh, _) = crate::geometry::Mesh::load_obj(&path, m.smooth.unwrap_or(true))
            .or_else(|e| invalid(pos(&m.file), e))?;
        return Ok(Shape::Mesh(std::sync::Arc::new(mesh)));
    }
    if let Some(i) = &spec.icosphere {
        let k = i.subdivisions.value;
        if !(0..=8).contains(&k) {
            return invalid(
                pos(&i.subdivisions),
                format!("icosphere subdivisions must be between 0 and 8, got {k}"),
            );
        }
        let mut mesh = crate::geometry::Mesh::icosphere(k as u32);
        if i.smooth == Some(false) {
            mesh = crate::geometry::Mesh::new(mesh.positions, vec![], mesh.triangles).0;
        }
        return Ok(Shape::Mesh(std::sync::Arc::new(mesh)));
    }
    invalid(p, "no shape")
}
