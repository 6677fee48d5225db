//! Probes: how the fast search tests one object. A plain (untransformed) sphere or plane is
//! tested directly, computing only t: no object → leaf → shape dispatch and no span. A run of
//! plain spheres next to each other in the scene's order is tested four at a time
//! (`SphereGroup`). Everything else goes through the object's own test. Each probe finds
//! exactly the hit the core's `Scene::object_hit` finds, and counts the same work.

use super::lanes::LANES;
use super::sphere_group::SphereGroup;
use crate::accel::Aabb;
use crate::geometry::sphere::Quadratic;
use crate::geometry::{Plane, Ray, Sphere};

/// How the hit searches test one object. Plain (untransformed) spheres and planes are tested
/// directly, computing only t: no object → leaf → shape dispatch and no span. Everything else
/// goes through `FastScene::boxed_object_hit`. Both give the same hits (tests/accel.rs checks).
#[derive(Clone, Debug)]
pub enum Probe {
    Sphere {
        sphere: Sphere,
        object: u32,
        leaf: u32,
    },
    Plane {
        plane: Plane,
        object: u32,
        leaf: u32,
    },
    /// A run of plain spheres next to each other in the list, tested side by side.
    Spheres {
        group: SphereGroup,
        objects: [u32; LANES],
        leaves: [u32; LANES],
    },
    /// A box (turned and moved or not), tested behind its bounding box, which the probe
    /// holds: most rays miss the bounding box, and are done without looking up the object.
    Box {
        bounds: Aabb,
        object: u32,
        leaf: u32,
    },
    Object(u32),
}

impl Probe {
    /// The object this probe tests behind its bounding box, if it is one (not a plain sphere
    /// or plane, nor a group of spheres).
    pub fn boxed_object(&self) -> Option<u32> {
        match self {
            Probe::Object(o) | Probe::Box { object: o, .. } => Some(*o),
            _ => None,
        }
    }
}

/// The probes with each run of plain spheres gathered into groups of up to `LANES`, in order:
/// a group finds what its spheres tested one after another find.
pub fn grouped(probes: Vec<Probe>) -> Vec<Probe> {
    let mut out = Vec::with_capacity(probes.len());
    let mut run: Vec<(Sphere, u32, u32)> = vec![];
    let flush = |run: &mut Vec<(Sphere, u32, u32)>, out: &mut Vec<Probe>| {
        for chunk in run.chunks(LANES) {
            if let [(sphere, object, leaf)] = chunk {
                out.push(Probe::Sphere {
                    sphere: sphere.clone(),
                    object: *object,
                    leaf: *leaf,
                });
                continue;
            }
            let spheres: Vec<Sphere> = chunk.iter().map(|c| c.0.clone()).collect();
            let (mut objects, mut leaves) = ([u32::MAX; LANES], [u32::MAX; LANES]);
            for (k, c) in chunk.iter().enumerate() {
                (objects[k], leaves[k]) = (c.1, c.2);
            }
            out.push(Probe::Spheres {
                group: SphereGroup::new(&spheres),
                objects,
                leaves,
            });
        }
        run.clear();
    };
    for p in probes {
        match p {
            Probe::Sphere {
                sphere,
                object,
                leaf,
            } => run.push((sphere, object, leaf)),
            other => {
                flush(&mut run, &mut out);
                out.push(other);
            }
        }
    }
    flush(&mut run, &mut out);
    out
}

/// The sphere's nearest crossing with t_min < t < t_max: the arithmetic of `Sphere::span` (so
/// the same t to the last bit), but most misses are rejected before any division or square
/// root: a ray that starts outside and moves away, and a line that clearly passes it by.
#[inline(always)]
pub fn sphere_hit(sphere: &Sphere, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
    let q = Quadratic::new(sphere, ray);
    if q.c > 0.0 && q.b > 0.0 && t_min >= 0.0 {
        // Outside and moving away: both roots are behind the origin.
        return None;
    }
    if q.clearly_misses() {
        return None;
    }
    let (t_in, t_out) = q.roots()?;
    let t = if t_in > t_min { t_in } else { t_out };
    (t > t_min && t < t_max).then_some(t)
}

/// The plane's crossing with t_min < t < t_max (and finite): what the search takes from
/// `Plane::span` (its finite end past t_min), without building the span.
#[inline]
pub fn plane_hit(plane: &Plane, ray: &Ray, t_min: f64, t_max: f64) -> Option<f64> {
    let rate = ray.dir.dot(plane.normal);
    if rate == 0.0 {
        // Parallel: the span is all or nothing, with no finite end.
        return None;
    }
    let height = (ray.origin - plane.point).dot(plane.normal);
    if t_min >= 0.0 && height.is_sign_negative() == rate.is_sign_negative() {
        // t = −height/rate ≤ 0 (or NaN): behind the ray; no division needed to know.
        return None;
    }
    let t = -height / rate;
    (t > t_min && t < t_max && t.is_finite()).then_some(t)
}
