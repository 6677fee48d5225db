//! The objects: each one's shape (or CSG tree of shapes, or group of objects) with its transform
//! and material, compiled into leaves (the primitives, in world space where a transform allows
//! and no pattern needs the object's own space) and objects (their trees, groups and bounds).

use std::collections::{BTreeMap, HashSet};
use std::path::{Path, PathBuf};

use glam::{DAffine3, DVec3};
use serde_saphyr::Spanned;

use super::{invalid, nonzero, pos, printable_name, Invalid, Limits, Pos};
use crate::accel::{Aabb, Ball};
use crate::geometry::csg::{CsgNode, CsgOp};
use crate::geometry::{Aabox, Cone, Cylinder, Plane, Shape, Sphere, Transform, Triangle};
use crate::scene::format::{ObjectSpec, SceneFile, TransformStep, Triple, MAX_MAGNITUDE};
use crate::scene::{Geometry, Group, Leaf, Object};
use crate::shading::Material;

/// The file's objects and their leaves; names are unique, materials resolved.
pub fn of(
    file: &SceneFile,
    material_index: &BTreeMap<String, u32>,
    materials: &[Material],
    source: Option<&Path>,
    limits: &Limits,
    warnings: &mut Vec<(Pos, String)>,
    inputs: &mut Vec<PathBuf>,
) -> Result<(Vec<Leaf>, Vec<Object>), Invalid> {
    if file.objects.len() > limits.max_objects {
        return invalid(
            pos(&file.objects[limits.max_objects]),
            format!(
                "more than {} objects: over the budget of objects per scene ({})",
                limits.max_objects,
                Limits::RAISE
            ),
        );
    }
    icospheres_within_budget(file, limits)?;
    let base = source
        .and_then(|p| p.parent())
        .map(|p| p.to_path_buf())
        .unwrap_or_default();
    let mut builder = Builder {
        materials: material_index,
        patterned: materials.iter().map(|m| m.patterns.is_some()).collect(),
        // Every object has at least one leaf: one allocation of the usual size, not a series of
        // doublings.
        leaves: Vec::with_capacity(file.objects.len()),
        limits,
        base: &base,
        triangles: 0,
        warnings,
        inputs,
    };
    let mut objects = Vec::with_capacity(file.objects.len());
    let mut names = HashSet::with_capacity(file.objects.len());
    let identity = Transform::new(DAffine3::IDENTITY);
    for (i, o) in file.objects.iter().enumerate() {
        let name = o
            .value
            .name
            .clone()
            .unwrap_or_else(|| format!("object{}", i + 1));
        printable_name(&name, pos(o), "object")?;
        if !names.insert(name.clone()) {
            return invalid(pos(o), format!("duplicate object name `{name}`"));
        }
        let object = objects.len() as u32;
        objects.push(builder.object(o, name, object, None, &identity, 0)?);
    }
    Ok((builder.leaves, objects))
}

/// The icospheres' triangles (20·4^k each) are known from the file: all of them are counted
/// before any is built, and the first that brings the scene over its budget is named.
fn icospheres_within_budget(file: &SceneFile, limits: &Limits) -> Result<(), Invalid> {
    fn visit(o: &Spanned<ObjectSpec>, total: &mut u64, limits: &Limits) -> Result<(), Invalid> {
        let spec = &o.value;
        if let Some(i) = &spec.icosphere {
            let k = i.subdivisions.value;
            if (0..=8).contains(&k) {
                let count = 20u64 << (2 * k);
                *total += count;
                if *total > limits.max_triangles {
                    return invalid(
                        pos(&i.subdivisions),
                        format!(
                            "this icosphere's {count} triangles bring the scene over its budget of {} triangles ({})",
                            limits.max_triangles,
                            Limits::RAISE
                        ),
                    );
                }
            }
        }
        let children = [
            &spec.union,
            &spec.intersection,
            &spec.difference,
            &spec.group,
        ];
        for child in children.into_iter().flatten().flatten() {
            visit(child, total, limits)?;
        }
        if let Some(child) = &spec.complement {
            visit(child, total, limits)?;
        }
        Ok(())
    }
    let mut total = 0;
    for o in &file.objects {
        visit(o, &mut total, limits)?;
    }
    Ok(())
}

struct Builder<'a> {
    materials: &'a BTreeMap<String, u32>,
    /// Per material: whether it has patterns (its leaves then keep their own space).
    patterned: Vec<bool>,
    leaves: Vec<Leaf>,
    limits: &'a Limits,
    /// Folder of the scene file: mesh files are found relative to it.
    base: &'a std::path::Path,
    /// Triangles in the meshes built so far (budgeted by `Limits::max_triangles`).
    triangles: u64,
    warnings: &'a mut Vec<(Pos, String)>,
    /// The mesh files read, each once.
    inputs: &'a mut Vec<PathBuf>,
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

    /// An object of the scene or a member of a group: `object` is the scene object it belongs
    /// to, `inherited` the material of the group around it, `parent` the group's transform.
    fn object(
        &mut self,
        o: &Spanned<ObjectSpec>,
        name: String,
        object: u32,
        inherited: Option<u32>,
        parent: &Transform,
        depth: usize,
    ) -> Result<Object, Invalid> {
        let spec = &o.value;
        let material = match &spec.material {
            Some(m) => Some(self.material(m)?),
            None => inherited,
        };
        if let Some(members) = &spec.group {
            return self.group(o, members, name, object, material, parent, depth);
        }
        let Some(material) = material else {
            let within = if inherited.is_none() && depth > 0 {
                " (nor does its group)"
            } else {
                ""
            };
            return invalid(pos(o), format!("object `{name}` has no `material`{within}"));
        };
        let mut ctx = Ctx {
            object,
            object_name: &name,
            path: vec![],
            leaf_count: 0,
            depth: 0,
        };
        let node = self.node(o, material, parent, &mut ctx, true)?;
        let (geometry, bounds) = match node {
            CsgNode::Leaf { leaf, bounds } => (Geometry::Leaf(leaf), bounds),
            node => {
                let b = node.bounds();
                (Geometry::Csg(node), b)
            }
        };
        Ok(Object {
            name,
            geometry,
            bounds,
        })
    }

    /// A group: its members compiled with its transform after their own and its material for
    /// those without one, and a hierarchy of their boxes.
    #[allow(clippy::too_many_arguments)]
    fn group(
        &mut self,
        o: &Spanned<ObjectSpec>,
        members: &[Spanned<ObjectSpec>],
        name: String,
        object: u32,
        material: Option<u32>,
        parent: &Transform,
        depth: usize,
    ) -> Result<Object, Invalid> {
        let p = pos(o);
        if shape_keys(&o.value) > 1 {
            return invalid(p, "a group is an object of its own: give its shapes as its members, not beside `group`");
        }
        if members.is_empty() {
            return invalid(p, format!("group `{name}` has no members"));
        }
        if depth > self.limits.max_csg_depth {
            return invalid(p, "groups nested too deeply");
        }
        let transform = placed(parent, &o.value.transform)?;
        let mut names = HashSet::new();
        let mut objects = Vec::with_capacity(members.len());
        for (i, m) in members.iter().enumerate() {
            let member = m
                .value
                .name
                .clone()
                .unwrap_or_else(|| format!("{name}.{}{}", key_name(&m.value), i + 1));
            if !names.insert(member.clone()) {
                return invalid(
                    pos(m),
                    format!("duplicate name `{member}` in group `{name}`"),
                );
            }
            objects.push(self.object(m, member, object, material, &transform, depth + 1)?);
        }
        let group = Group::new(objects);
        Ok(Object {
            name,
            bounds: group.bounds(),
            geometry: Geometry::Group(Box::new(group)),
        })
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
        if let Some(name) = &spec.name {
            printable_name(name, p, "object")?;
        }
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
        let transform = placed(parent, &spec.transform)?;
        match shape_keys(spec) {
            1 => {}
            0 => return invalid(p, "no shape: give one of sphere, plane, box, cylinder, cone, triangle, mesh, icosphere, union, intersection, difference, complement, group"),
            _ => return invalid(p, "more than one shape key in one object: nest them in a union or a group, or write two objects"),
        }
        if spec.group.is_some() {
            return invalid(
                p,
                "a group cannot take part in CSG: put the CSG object in the group instead",
            );
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
        let shape = self.shape(spec, p, ctx.object_name)?;
        if !top && matches!(shape, Shape::OpenCylinder(_) | Shape::OpenCone(_)) {
            return invalid(
                p,
                format!(
                    "an open {} (capped: false) has no inside: it cannot take part in CSG",
                    shape.kind()
                ),
            );
        }
        if !top && !shape.is_convex_solid() {
            return invalid(
                p,
                format!("a {} cannot take part in CSG: its segment list is not one interval (use spheres, boxes, cylinders, cones)", shape.kind()),
            );
        }
        ctx.leaf_count += 1;
        // An object that is one shape is its own leaf, named as the object.
        let name = match &spec.name {
            _ if top => ctx.object_name.to_string(),
            Some(name) => name.clone(),
            None => format!("{}.{}{}", ctx.object_name, shape.kind(), ctx.leaf_count),
        };
        // A shape the transform keeps of its kind is stored in world space: no ray needs
        // carrying to object space for it. A patterned one stays in its own space, where its
        // patterns are looked up.
        let (shape, transform) = if transform.to_world == DAffine3::IDENTITY {
            (shape, None)
        } else if self.patterned[material as usize] {
            (shape, Some(Box::new(transform)))
        } else {
            match shape.moved(&transform) {
                Some(moved) => (moved, None),
                None => (shape, Some(Box::new(transform))),
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

impl Builder<'_> {
    /// A leaf's shape; meshes and icospheres are counted against the triangle budget before
    /// they are built (or taken from an earlier compilation, `meshes`).
    fn shape(&mut self, spec: &ObjectSpec, p: Pos, object: &str) -> Result<Shape, Invalid> {
        if let Some(m) = &spec.mesh {
            let path = self.base.join(&m.file.value);
            let left = self.limits.max_triangles.saturating_sub(self.triangles);
            let budget = crate::geometry::ObjBudget {
                max_bytes: self.limits.max_mesh_bytes,
                max_triangles: left,
                total: self.limits.max_triangles,
                raise: Limits::RAISE,
            };
            let (mesh, dropped) = super::meshes::obj(&path, m.smooth.unwrap_or(true), &budget)
                .or_else(|e| invalid(pos(&m.file), e))?;
            if mesh.triangles.is_empty() {
                self.warnings.push((
                    pos(&m.file),
                    format!(
                        "object `{object}`: all {dropped} triangles of {} are degenerate (zero area): the mesh is invisible",
                        path.display()
                    ),
                ));
            }
            self.triangles += mesh.triangles.len() as u64;
            if !self.inputs.contains(&path) {
                self.inputs.push(path);
            }
            return Ok(Shape::Mesh(mesh));
        }
        if let Some(i) = &spec.icosphere {
            let k = i.subdivisions.value;
            if !(0..=8).contains(&k) {
                return invalid(
                    pos(&i.subdivisions),
                    format!("icosphere subdivisions must be between 0 and 8, got {k}"),
                );
            }
            // 20·4^k triangles.
            let count = 20u64 << (2 * k);
            if self.triangles + count > self.limits.max_triangles {
                return invalid(
                    pos(&i.subdivisions),
                    format!(
                        "this icosphere's {count} triangles bring the scene over its budget of {} triangles ({})",
                        self.limits.max_triangles,
                        Limits::RAISE
                    ),
                );
            }
            self.triangles += count;
            let smooth = i.smooth != Some(false);
            return Ok(Shape::Mesh(super::meshes::icosphere(k as u32, smooth)));
        }
        shape(spec, p)
    }
}

/// How many shape keys (a CSG operation and `group` count as one) an object gives.
fn shape_keys(spec: &ObjectSpec) -> usize {
    [
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
        spec.group.is_some(),
    ]
    .iter()
    .filter(|&&b| b)
    .count()
}

/// The shape key an object gives (for the names of unnamed group members).
fn key_name(spec: &ObjectSpec) -> &'static str {
    [
        (spec.sphere.is_some(), "sphere"),
        (spec.plane.is_some(), "plane"),
        (spec.aabox.is_some(), "box"),
        (spec.cylinder.is_some(), "cylinder"),
        (spec.cone.is_some(), "cone"),
        (spec.triangle.is_some(), "triangle"),
        (spec.mesh.is_some(), "mesh"),
        (spec.icosphere.is_some(), "icosphere"),
        (spec.union.is_some(), "union"),
        (spec.intersection.is_some(), "intersection"),
        (spec.difference.is_some(), "difference"),
        (spec.complement.is_some(), "complement"),
        (spec.group.is_some(), "group"),
    ]
    .into_iter()
    .find_map(|(given, key)| given.then_some(key))
    .unwrap_or("object")
}

/// The steps compose in the order written: the first step is applied first.
/// The transform of an object with these steps inside `parent` (its own steps first). Without
/// steps of its own an object is where its parent puts it: no product, no inverse.
fn placed(parent: &Transform, steps: &[Spanned<TransformStep>]) -> Result<Transform, Invalid> {
    let Some(last) = steps.last() else {
        return Ok(parent.clone());
    };
    let own = transform(steps)?;
    if parent.to_world == DAffine3::IDENTITY {
        return Ok(own);
    }
    let whole = parent.after(&own);
    in_range(
        &whole.to_world,
        pos(last),
        ", with the transforms of the groups around it,",
    )?;
    Ok(whole)
}

/// The smallest magnitude of a scale factor: a smaller one flattens the object so far that
/// the inverse, which carries rays into the object's space, is out of range.
const MIN_SCALE: f64 = 1e-12;

/// The largest magnitude among an affine map's matrix and offset (NaN counts as beyond any).
fn largest_entry(m: &DAffine3) -> f64 {
    m.to_cols_array().iter().fold(0.0f64, |worst, v| {
        if v.is_nan() {
            f64::INFINITY
        } else {
            worst.max(v.abs())
        }
    })
}

/// The largest magnitude among the inverse's matrix and offset. The matrix is scaled to
/// entries near 1 before it is inverted: the determinant of a transform shrinking by 1e-108
/// underflows to zero, though its inverse (1e108) is a number like any other.
fn largest_inverse_entry(m: &DAffine3) -> f64 {
    let big = largest_entry(&DAffine3::from_mat3(m.matrix3));
    if !big.is_normal() {
        return f64::INFINITY;
    }
    let unit = m.matrix3 * (1.0 / big);
    if !unit.determinant().is_normal() {
        return f64::INFINITY;
    }
    let inverse = unit.inverse() * (1.0 / big);
    let offset = -(inverse * m.translation);
    largest_entry(&DAffine3::from_mat3_translation(inverse, offset))
}

/// A magnitude for a message: three significant digits, or words for one beyond any number.
fn round(x: f64) -> String {
    if x.is_finite() {
        format!("{:e}", format!("{x:.2e}").parse::<f64>().unwrap_or(x))
    } else {
        "more than any number".into()
    }
}

/// Refuses a composed transform whose matrix or inverse holds numbers beyond ±1e100, the bound
/// every number written in a scene keeps (their squares, met in every intersection test, must
/// not overflow); each step may keep it while their product does not.
fn in_range(m: &DAffine3, at: Pos, context: &str) -> Result<(), Invalid> {
    let forward = largest_entry(m);
    if forward > MAX_MAGNITUDE {
        return invalid(
            at,
            format!(
                "the transform's steps up to here{context} scale or move by {} together: the composed transform must stay within ±1e100 (as every number in a scene)",
                round(forward)
            ),
        );
    }
    let backward = largest_inverse_entry(m);
    if backward > MAX_MAGNITUDE {
        return invalid(
            at,
            format!(
                "the transform's steps up to here{context} shrink the object so far that undoing them takes a factor of {}: the inverse transform must stay within ±1e100 (as every number in a scene)",
                round(backward)
            ),
        );
    }
    Ok(())
}

pub(super) fn transform(steps: &[Spanned<TransformStep>]) -> Result<Transform, Invalid> {
    let mut m = DAffine3::IDENTITY;
    for s in steps {
        let step = match &s.value {
            TransformStep::Translate(v) => DAffine3::from_translation(v.0),
            TransformStep::RotateX(d) => DAffine3::from_rotation_x(d.0.to_radians()),
            TransformStep::RotateY(d) => DAffine3::from_rotation_y(d.0.to_radians()),
            TransformStep::RotateZ(d) => DAffine3::from_rotation_z(d.0.to_radians()),
            TransformStep::Scale(Triple(v)) => {
                let smallest = v.abs().min_element();
                if smallest == 0.0 {
                    return invalid(pos(s), "scale must not be zero in any axis");
                }
                if smallest < MIN_SCALE {
                    return invalid(
                        pos(s),
                        format!(
                            "scale factor {smallest:e} is too small: each factor's magnitude must be at least {MIN_SCALE:e}"
                        ),
                    );
                }
                DAffine3::from_scale(*v)
            }
        };
        m = step * m;
        in_range(&m, pos(s), "")?;
    }
    Ok(Transform::new(m))
}

/// The shape of a leaf: its numbers checked (meshes are built by the builder, which budgets
/// their triangles).
fn shape(spec: &ObjectSpec, p: Pos) -> Result<Shape, Invalid> {
    let positive = |r: &Spanned<crate::scene::format::Num>, what: &str| -> Result<f64, Invalid> {
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
        let cylinder = Cylinder {
            base: s.base.value.0,
            top: s.top.0,
            radius,
        };
        return Ok(if s.capped == Some(false) {
            Shape::OpenCylinder(cylinder)
        } else {
            Shape::Cylinder(cylinder)
        });
    }
    if let Some(s) = &spec.cone {
        let radius = positive(&s.radius, "cone radius")?;
        nonzero(
            s.base.0 - s.apex.value.0,
            pos(&s.apex),
            "cone axis (base − apex)",
        )?;
        let cone = Cone {
            apex: s.apex.value.0,
            base: s.base.0,
            radius,
        };
        return Ok(if s.capped == Some(false) {
            Shape::OpenCone(cone)
        } else {
            Shape::Cone(cone)
        });
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
    invalid(p, "no shape")
}
