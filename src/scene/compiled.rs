//! The compiled, runtime scene: validated, transforms inverted, bounds computed, BVH built and
//! the features the scene uses recorded, so the tracer can skip what is absent.

use std::path::PathBuf;

use glam::DVec3;
use wide::f64x4;

use crate::accel::bvh::{signs, PACKET};
use crate::accel::{Aabb, Bvh, SlabLanes};
use crate::geometry::csg::{CsgNode, CsgOp, CsgRay, CsgTrace, CsgWork, LeafSegments};
use crate::geometry::csg_crossing::{Crossing, FlatCsg, LeafSpans};
use crate::geometry::csg_lanes::CsgLanes;
use crate::geometry::sphere_group::{sphere_against_lanes, LANES};
use crate::geometry::{
    first_crossing, LanesHits, Plane, Ray, Segment, SegmentList, Shape, Span, Sphere, SphereGroup,
    Surface, Transform,
};
use crate::geometry::{lane_mask, RayLanes};
use crate::render::Camera;
use crate::shading::{Light, LightKind, Material};
use crate::trace::Stats;

/// A primitive in the scene: a plain object, or a leaf of a CSG tree.
#[derive(Clone, Debug)]
pub struct Leaf {
    /// The leaf's own name (for a plain object, the object's name).
    pub name: String,
    /// The object it belongs to.
    pub object: u32,
    /// The CSG operations from the object's root down to this leaf ("union/difference").
    pub path: Vec<String>,
    pub shape: Shape,
    pub transform: Option<Transform>,
    pub material: u32,
    /// World-space bounds.
    pub bounds: Aabb,
}

impl Leaf {
    /// The leaf as a sphere in world space, if it is one.
    pub fn world_sphere(&self) -> Option<&Sphere> {
        match (&self.shape, &self.transform) {
            (Shape::Sphere(s), None) => Some(s),
            _ => None,
        }
    }

    pub fn span(&self, ray: &Ray) -> Option<Span> {
        match &self.transform {
            Some(tf) => self.shape.span(&tf.ray_to_local(ray)),
            None => self.shape.span(ray),
        }
    }

    /// The leaf's segment list; its surfaces are named by `id`, its index in the scene.
    pub fn segments(&self, id: u32, ray: &Ray) -> SegmentList {
        let mut list = SegmentList::new();
        if let Shape::Mesh(mesh) = &self.shape {
            // Every crossing of a mesh's surface, as a zero-length segment.
            let local = self
                .transform
                .as_ref()
                .map_or(*ray, |tf| tf.ray_to_local(ray));
            for (t, face) in mesh.crossings(&local) {
                let s = Surface::new(id, face);
                list.push(Segment {
                    t_in: t,
                    t_out: t,
                    enter: s,
                    exit: s,
                });
            }
            return list;
        }
        // A span of NaN (arithmetic overflow on absurd input) is no intersection.
        if let Some(s) = self
            .span(ray)
            .filter(|s| !s.t_in.is_nan() && !s.t_out.is_nan())
        {
            list.push(Segment {
                t_in: s.t_in,
                t_out: s.t_out,
                enter: Surface::new(id, s.face_in as u32),
                exit: Surface::new(id, s.face_out as u32),
            });
        }
        list
    }

    /// The outward unit normal in world space at a world point on `face`. A plain sphere's or
    /// plane's is found here, inline: it is wanted at every shaded hit.
    #[inline(always)]
    pub fn normal(&self, p: DVec3, face: u32) -> DVec3 {
        match (&self.transform, &self.shape) {
            (None, Shape::Sphere(s)) => s.normal(p),
            (None, Shape::Plane(s)) => s.normal,
            (Some(tf), shape) => {
                tf.normal_to_world(shape.normal(tf.to_local.transform_point3(p), face))
            }
            (None, shape) => shape.normal(p, face),
        }
    }
}

#[derive(Clone, Debug)]
pub enum Geometry {
    /// A single primitive (index into `Scene::leaves`).
    Leaf(u32),
    Csg(CsgNode),
}

#[derive(Clone, Debug)]
pub struct Object {
    pub name: String,
    pub geometry: Geometry,
    pub bounds: Aabb,
}

/// The cheap record of an intersection: enough to find everything else later.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub t: f64,
    pub object: u32,
    pub surface: Surface,
}

/// How the hit searches test one object. Plain (untransformed) spheres and planes are tested
/// directly, computing only t: no object → leaf → shape dispatch and no span. Everything else
/// goes through `Scene::object_hit`. Both give the same hits (tests/accel.rs checks).
#[derive(Clone, Debug)]
enum Probe {
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
    Object(u32),
}

/// The probes with each run of plain spheres gathered into groups of up to `LANES`, in order:
/// a group finds what its spheres tested one after another find.
fn grouped(probes: Vec<Probe>) -> Vec<Probe> {
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

/// The shading record, built only for the hit that is shaded.
#[derive(Clone, Copy, Debug)]
pub struct Interaction {
    pub point: DVec3,
    /// Unit normal facing the incoming ray (the one the formulas use).
    pub normal: DVec3,
    /// True when the ray arrives from inside the solid (it is leaving it).
    pub inside: bool,
    pub leaf: u32,
    /// The leaf's face (a mesh's triangle).
    pub face: u32,
    pub object: u32,
    pub material: u32,
}

/// What the scene contains, so the tracer can skip what it does not need.
#[derive(Clone, Copy, Debug, Default)]
pub struct Features {
    pub reflective: bool,
    pub transparent: bool,
    pub csg: bool,
    /// Some material draws random numbers (glossy or frosted lobes).
    pub sampled: bool,
    pub lights: usize,
}

/// How intersections are found.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Accel {
    /// Test every object.
    None,
    #[default]
    Bvh,
}

#[derive(Clone, Debug)]
pub struct Scene {
    pub source: Option<PathBuf>,
    pub camera: Camera,
    pub background: DVec3,
    pub ambient: DVec3,
    pub max_depth: u32,
    pub adaptive_threshold: f64,
    /// Offset of secondary-ray origins; None = automatic, scaled to the hit point.
    pub shadow_bias: Option<f64>,
    pub spp: u32,
    pub integrator: super::format::Integrator,
    /// Where a pixel's primary rays go (`spp` of them).
    pub antialias: crate::render::antialias::Antialias,
    /// The reconstruction filter of jittered (Monte Carlo) sampling.
    pub filter: crate::render::antialias::Filter,
    /// I_r and I_t divided by c0 + c1·d + c2·d² (d = length of the child ray), when set.
    pub secondary_attenuation: Option<[f64; 3]>,
    pub lights: Vec<Light>,
    pub materials: Vec<Material>,
    pub leaves: Vec<Leaf>,
    pub objects: Vec<Object>,
    pub features: Features,
    /// Objects with a transparent material (kt > 0) and their index of refraction: the media a
    /// refracted ray can be in.
    pub transparent_objects: Vec<(u32, f64)>,
    /// CSG bounding boxes and pruning (on; off only to measure what they save).
    pub csg_pruning: bool,
    accel: Accel,
    bvh: Bvh,
    /// Objects the BVH indexes (bounded ones), by BVH item number.
    bounded: Vec<Probe>,
    /// Objects no box can hold (planes, complements): always tested.
    unbounded: Vec<Probe>,
    /// Per object: its CSG tree's flat form, when it has one (nearest hits without segment
    /// lists).
    flat_csg: Vec<Option<FlatCsg>>,
    /// Per object: its flat form of two operands the lanes can test (spheres, boxes, cylinders,
    /// cones), when it has one (`csg_in_lanes`).
    csg_lanes: Vec<Option<CsgLanes>>,
    /// Some object outside the BVH is tested behind its box: packets of rays tested in lanes
    /// then find their 1/d in lanes, for each such box's test of four rays at once.
    boxes_outside_bvh: bool,
    /// Some object, in the BVH or not, is tested behind its box: the searches find each ray's
    /// 1/d once for all the boxes (`inv_dir`).
    boxed_objects: bool,
    /// No BVH: a packet's rays, primary, shadow and secondary, are tested four at a time
    /// (`intersect_in_lanes`, `occluded_in_lanes`).
    in_lanes: bool,
    /// Per object and light (`object · lights + light`): the object is a bounded convex solid
    /// and the light lies outside it, so a shadow ray from a point inside it is blocked by it.
    hides_light_inside: Vec<bool>,
}

impl LeafSegments for Scene {
    fn leaf_segments(&self, leaf: u32, ray: &Ray) -> SegmentList {
        self.leaves[leaf as usize].segments(leaf, ray)
    }
    fn leaf_name(&self, leaf: u32) -> String {
        self.leaves[leaf as usize].name.clone()
    }
}

impl LeafSpans for Scene {
    #[inline]
    fn leaf_span(&self, leaf: u32, ray: &Ray) -> Option<Span> {
        self.leaves[leaf as usize].span(ray)
    }
}

/// Fewer rays than this search the BVH faster one by one than as a packet (callgrind, the
/// 10 000-sphere peer scene at 200×150: one ray per pixel took 79 % more instructions as a
/// packet, four 6 % fewer, sixteen 16 % fewer).
const PACKET_MIN: usize = 4;

/// Below this many bounded objects the BVH buys nothing. Measured with `benches/intersect.rs`
/// (3072 primary rays, spheres; brute force vs BVH): 4 objects 97 µs vs 191 µs, 8 objects
/// 141 µs vs 206 µs, 16 objects 229–322 µs vs 286 µs (a tie), 64 objects 0.81 ms vs 0.40 ms,
/// 1000 objects 15 ms vs 1.2 ms. (Brute force rejects most spheres in a few instructions, in a
/// loop the processor predicts; shadow rays, which stop at the first blocker, favour it more.)
const BVH_MIN_OBJECTS: usize = 16;

impl Scene {
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn assemble(
        source: Option<PathBuf>,
        camera: Camera,
        background: DVec3,
        ambient: DVec3,
        max_depth: u32,
        adaptive_threshold: f64,
        shadow_bias: Option<f64>,
        spp: u32,
        secondary_attenuation: Option<[f64; 3]>,
        lights: Vec<Light>,
        materials: Vec<Material>,
        leaves: Vec<Leaf>,
        objects: Vec<Object>,
    ) -> Scene {
        let used =
            |f: fn(&Material) -> bool| leaves.iter().any(|l| f(&materials[l.material as usize]));
        let features = Features {
            reflective: used(Material::reflective),
            transparent: used(Material::transparent),
            csg: objects
                .iter()
                .any(|o| matches!(o.geometry, Geometry::Csg(_))),
            sampled: used(Material::sampled),
            lights: lights.len(),
        };
        let flat_csg = objects
            .iter()
            .map(|o| match &o.geometry {
                Geometry::Csg(root) => {
                    FlatCsg::new(root, |leaf| leaves[leaf as usize].world_sphere().cloned())
                }
                Geometry::Leaf(_) => None,
            })
            .collect();
        let mut scene = Scene {
            source,
            camera,
            background,
            ambient,
            max_depth,
            adaptive_threshold,
            shadow_bias,
            spp,
            integrator: Default::default(),
            antialias: Default::default(),
            filter: Default::default(),
            secondary_attenuation,
            lights,
            materials,
            leaves,
            objects,
            features,
            transparent_objects: vec![],
            csg_pruning: true,
            accel: Accel::Bvh,
            bvh: Bvh::default(),
            bounded: vec![],
            unbounded: vec![],
            csg_lanes: vec![],
            flat_csg,
            boxes_outside_bvh: false,
            boxed_objects: false,
            in_lanes: false,
            hides_light_inside: vec![],
        };
        scene.transparent_objects = scene
            .leaves
            .iter()
            .filter(|l| l.shape.is_solid() && scene.materials[l.material as usize].transparent())
            .map(|l| (l.object, scene.materials[l.material as usize].ior))
            .fold(Vec::new(), |mut v, e| {
                if !v.iter().any(|x: &(u32, f64)| x.0 == e.0) {
                    v.push(e);
                }
                v
            });
        scene.csg_lanes = scene
            .flat_csg
            .iter()
            .map(|f| scene.lanes_form(f.as_ref()?))
            .collect();
        scene.hides_light_inside = (0..scene.objects.len() as u32)
            .flat_map(|o| (0..scene.lights.len()).map(move |k| (o, k)))
            .map(|(o, k)| scene.is_bounded_convex(o) && scene.light_outside(o, k))
            .collect();
        scene.set_accel(Accel::Bvh);
        scene
    }

    /// The flat CSG object in the form `csg_in_lanes` tests, if it is one: two operands, each a
    /// sphere in world space or a box, cylinder or cone (turned and moved as its transform
    /// says).
    fn lanes_form(&self, flat: &FlatCsg) -> Option<CsgLanes> {
        let [(a, a_box), (b, b_box)] = flat.operands() else {
            return None;
        };
        let operand = |leaf: u32| {
            let l = &self.leaves[leaf as usize];
            match (&l.shape, &l.transform) {
                (Shape::Sphere(s), None) => Some(CsgLanes::sphere(s)),
                (shape, tf) => CsgLanes::solid(shape, tf.as_ref().map(|t| t.to_local)),
            }
        };
        CsgLanes::new(
            flat.op(),
            [operand(*a), operand(*b)],
            [*a, *b],
            [*a_box, *b_box],
        )
    }

    /// Whether a shadow ray toward light k from a point inside object o is surely blocked by
    /// o: a bounded convex solid holds the whole segment between any two of its points, so
    /// the segment from a point inside it to a light outside it must cross its surface.
    #[inline]
    pub fn hides_light_inside(&self, object: u32, light: usize) -> bool {
        self.hides_light_inside[object as usize * self.lights.len() + light]
    }

    /// A bounded convex solid: a sphere, box, cylinder or cone (moved as a transform says),
    /// or a CSG intersection of such solids.
    fn is_bounded_convex(&self, object: u32) -> bool {
        fn convex(scene: &Scene, node: &CsgNode) -> bool {
            match node {
                CsgNode::Leaf { leaf, .. } => scene.leaves[*leaf as usize].shape.is_convex_solid(),
                CsgNode::Op { op, children, .. } => {
                    *op == CsgOp::Intersection && children.iter().all(|c| convex(scene, c))
                }
            }
        }
        let o = &self.objects[object as usize];
        o.bounds.is_finite()
            && match &o.geometry {
                Geometry::Leaf(leaf) => self.leaves[*leaf as usize].shape.is_convex_solid(),
                Geometry::Csg(root) => convex(self, root),
            }
    }

    /// Whether light k lies wholly outside object o: a point light not in it, any
    /// directional light (a bounded object cannot hold infinity), an area light whose box
    /// does not meet the object's.
    fn light_outside(&self, object: u32, light: usize) -> bool {
        let bounds = &self.objects[object as usize].bounds;
        let apart = |b: Aabb| bounds.intersection(&b).is_empty();
        match &self.lights[light].kind {
            LightKind::Directional { .. } => true,
            LightKind::Point { position, .. } => {
                let probe = Ray {
                    origin: *position,
                    dir: DVec3::Y,
                };
                apart(Aabb::point(*position))
                    || !self.contains(object, &probe, &mut Stats::default())
            }
            LightKind::Rect { corner, u, v, .. } => apart(
                Aabb::point(*corner)
                    .grow(*corner + *u)
                    .grow(*corner + *v)
                    .grow(*corner + *u + *v),
            ),
            LightKind::Sphere { center, radius, .. } => {
                apart(Aabb::new(*center - *radius, *center + *radius))
            }
        }
    }

    /// Is the probe ray's origin inside the object? (Inside a segment of its list; for a mesh,
    /// an odd number of crossings ahead.)
    pub fn contains(&self, object: u32, probe: &Ray, stats: &mut Stats) -> bool {
        let list = self.object_segments(object, probe, f64::NEG_INFINITY, f64::INFINITY, stats);
        match &self.objects[object as usize].geometry {
            Geometry::Leaf(l) if matches!(self.leaves[*l as usize].shape, Shape::Mesh(_)) => {
                list.iter().filter(|s| s.t_in > 0.0).count() % 2 == 1
            }
            _ => list.iter().any(|s| s.t_in <= 0.0 && 0.0 <= s.t_out),
        }
    }

    /// Chooses the acceleration structure (rebuilding the BVH if needed).
    pub fn set_accel(&mut self, accel: Accel) {
        self.accel = accel;
        let (bounded, unbounded): (Vec<u32>, Vec<u32>) = (0..self.objects.len() as u32)
            .partition(|&i| self.objects[i as usize].bounds.is_finite());
        let use_bvh = accel == Accel::Bvh && bounded.len() >= BVH_MIN_OBJECTS;
        if use_bvh {
            let boxes: Vec<Aabb> = bounded
                .iter()
                .map(|&i| self.objects[i as usize].bounds)
                .collect();
            self.bvh = Bvh::build(&boxes);
            self.bounded = bounded.into_iter().map(|o| self.probe(o)).collect();
            self.unbounded = grouped(unbounded.into_iter().map(|o| self.probe(o)).collect());
        } else {
            self.bvh = Bvh::default();
            self.bounded = vec![];
            self.unbounded = grouped(
                (0..self.objects.len() as u32)
                    .map(|o| self.probe(o))
                    .collect(),
            );
        }
        let boxed = |probes: &[Probe]| probes.iter().any(|p| matches!(p, Probe::Object(_)));
        self.boxes_outside_bvh = boxed(&self.unbounded);
        self.boxed_objects = self.boxes_outside_bvh || boxed(&self.bounded);
        self.in_lanes = self.bounded.is_empty();
    }

    /// Whether packets of rays go four at a time through the objects (no BVH: `intersect_in_lanes`).
    pub fn tests_in_lanes(&self) -> bool {
        self.in_lanes
    }

    /// 1/d, which the boxes of the objects tested behind one need: found once per ray, not
    /// once per box. Not at all in scenes without such objects (plain spheres and planes),
    /// where a division per ray would buy nothing; there it is NaN, which no box test passes.
    #[inline(always)]
    fn inv_dir(&self, ray: &Ray) -> DVec3 {
        if self.boxed_objects {
            ray.dir.recip()
        } else {
            DVec3::NAN
        }
    }

    /// Object o against up to four rays of a packet, behind its box: the box is tried
    /// against all of them at once, then the object ray by ray where it passed, and each ray's
    /// nearest hit so far and its limit t_max are updated as `intersect` would.
    /// Out of line, so that the lanes' loop over plain spheres and planes stays small.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    fn object_in_lanes(
        &self,
        o: u32,
        rays: &[Ray],
        slabs: &SlabLanes,
        t_max: &mut [f64; LANES],
        hits: &mut [Option<Hit>],
        stats: &mut Stats,
    ) {
        let used = (1 << rays.len()) - 1;
        let limit = f64x4::new(*t_max);
        let mut passed = self.box_passed_by(o, used, slabs, limit, stats);
        if let Some((csg, found)) = self.csg_in_lanes(o, slabs, passed, limit, stats) {
            let t = found.t.to_array();
            for i in (0..rays.len()).filter(|i| found.hit & (1 << i) != 0) {
                t_max[i] = t[i];
                hits[i] = Some(Hit {
                    t: t[i],
                    object: o,
                    surface: csg.surface(&found, i),
                });
            }
            passed = found.undecided;
        }
        for i in (0..rays.len()).filter(|i| passed & (1 << i) != 0) {
            if let Some(h) = self.object_hit(o, &rays[i], slabs.inv_dir(i), 0.0, t_max[i], stats) {
                t_max[i] = h.t;
                hits[i] = Some(h);
            }
        }
    }

    /// Object o against the shadow rays of a packet still `open` (bit i: ray i), behind its
    /// box tried against all of them at once: the bits of the rays it blocks.
    #[allow(clippy::too_many_arguments)]
    #[inline(never)]
    fn object_blocks_lanes(
        &self,
        o: u32,
        rays: &[Ray],
        slabs: &SlabLanes,
        t_max: f64x4,
        open: u32,
        stats: &mut Stats,
    ) -> u32 {
        let mut passed = self.box_passed_by(o, open, slabs, t_max, stats);
        let reach = t_max.to_array();
        let mut blocked = 0;
        if let Some((_, found)) = self.csg_in_lanes(o, slabs, passed, t_max, stats) {
            blocked = found.hit;
            passed = found.undecided;
        }
        for i in (0..rays.len()).filter(|i| passed & (1 << i) != 0) {
            if self
                .object_hit(o, &rays[i], slabs.inv_dir(i), 0.0, reach[i], stats)
                .is_some()
            {
                blocked |= 1 << i;
            }
        }
        blocked
    }

    /// Which of the rays in `lanes` (bit i: lane i) pass through object o's box within
    /// [0, t_max] (all of them where the object is not tested behind its box), with the others
    /// counted as skipped, as `boxed_object_hit` counts them ray by ray.
    #[inline(always)]
    fn box_passed_by(
        &self,
        o: u32,
        lanes: u32,
        slabs: &SlabLanes,
        t_max: f64x4,
        stats: &mut Stats,
    ) -> u32 {
        if !self.tested_behind_box(o) {
            return lanes;
        }
        let passed = lanes & self.objects[o as usize].bounds.hit_lanes(slabs, 0.0, t_max);
        stats.bounds_skipped += (lanes & !passed).count_ones() as u64;
        passed
    }

    /// Object o, if it is a flat CSG object the lanes can test (`lanes_form`), against
    /// the rays whose bits are set in `open`, four at a time, counted as `object_hit` counts
    /// them ray by ray; the rays it leaves undecided are for `object_hit`.
    #[inline(always)]
    fn csg_in_lanes(
        &self,
        o: u32,
        slabs: &SlabLanes,
        open: u32,
        t_max: f64x4,
        stats: &mut Stats,
    ) -> Option<(&CsgLanes, LanesHits)> {
        let csg = self.csg_lanes[o as usize].as_ref()?;
        let found = csg.hits(slabs, open, t_max, self.csg_pruning, self.csg_pruning);
        stats.primitives_tested += (open & !found.undecided).count_ones() as u64;
        stats.csg_pruned += found.pruned;
        Some((csg, found))
    }

    /// How the hit searches test an object: directly for a plain sphere or plane.
    fn probe(&self, object: u32) -> Probe {
        let Geometry::Leaf(leaf) = self.objects[object as usize].geometry else {
            return Probe::Object(object);
        };
        let l = &self.leaves[leaf as usize];
        match (&l.shape, &l.transform) {
            (Shape::Sphere(sphere), None) => Probe::Sphere {
                sphere: sphere.clone(),
                object,
                leaf,
            },
            (Shape::Plane(plane), None) => Probe::Plane {
                plane: plane.clone(),
                object,
                leaf,
            },
            _ => Probe::Object(object),
        }
    }

    pub fn bvh_nodes(&self) -> usize {
        self.bvh.node_count()
    }

    pub fn material(&self, index: u32) -> &Material {
        &self.materials[index as usize]
    }

    pub fn object_index(&self, name: &str) -> Option<u32> {
        self.objects
            .iter()
            .position(|o| o.name == name)
            .map(|i| i as u32)
    }

    /// The segment list of one object along the ray, within [t_min, t_max].
    pub fn object_segments(
        &self,
        object: u32,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        stats: &mut Stats,
    ) -> SegmentList {
        match &self.objects[object as usize].geometry {
            Geometry::Leaf(leaf) => self.leaves[*leaf as usize].segments(*leaf, ray),
            Geometry::Csg(root) => {
                let r = self.csg_ray(ray, ray.dir.recip(), t_min, t_max);
                self.csg_segments(root, &r, stats)
            }
        }
    }

    /// A CSG tree's segment list.
    fn csg_segments(&self, root: &CsgNode, r: &CsgRay, stats: &mut Stats) -> SegmentList {
        let mut work = CsgWork::default();
        let list = root.segments(self, r, &mut work);
        stats.csg_pruned += work.pruned;
        list
    }

    /// The ray as CSG evaluation sees it, with the scene's boxes and pruning switched on or off.
    #[inline]
    fn csg_ray<'a>(&self, ray: &'a Ray, inv_dir: DVec3, t_min: f64, t_max: f64) -> CsgRay<'a> {
        CsgRay {
            ray,
            inv_dir,
            t_min,
            t_max,
            use_bounds: self.csg_pruning,
            prune: self.csg_pruning,
        }
    }

    /// The CSG trace of an object along the whole line of the ray (for `raytree csg`).
    /// With `use_bounds` false, only the notes' pruning rules apply (empty operands).
    pub fn object_trace(
        &self,
        object: u32,
        ray: &Ray,
        use_bounds: bool,
    ) -> (SegmentList, CsgTrace) {
        match &self.objects[object as usize].geometry {
            Geometry::Leaf(leaf) => {
                let list = self.leaves[*leaf as usize].segments(*leaf, ray);
                let trace = CsgTrace {
                    node: self.leaves[*leaf as usize].name.clone(),
                    op: None,
                    leaf: Some(*leaf),
                    segments: list.clone(),
                    pruned: None,
                    children: vec![],
                };
                (list, trace)
            }
            Geometry::Csg(root) => {
                let r = CsgRay {
                    ray,
                    inv_dir: ray.dir.recip(),
                    t_min: f64::NEG_INFINITY,
                    t_max: f64::INFINITY,
                    use_bounds,
                    prune: true,
                };
                root.trace(self, &r, &mut CsgWork::default())
            }
        }
    }

    /// Every object the ray's line meets (segments anywhere along it) with its CSG trace; with
    /// `all`, every object, evaluated without bounding boxes.
    pub fn csg_traces(&self, ray: &Ray, all: bool) -> Vec<(String, CsgTrace)> {
        fn has_segments(t: &CsgTrace) -> bool {
            !t.segments.is_empty() || t.children.iter().any(has_segments)
        }
        (0..self.objects.len() as u32)
            .filter_map(|o| {
                let (list, trace) = self.object_trace(o, ray, !all);
                let met = all || !list.is_empty() || has_segments(&trace);
                met.then(|| (self.objects[o as usize].name.clone(), trace))
            })
            .collect()
    }

    /// `object_hit` behind the object's box: a ray that misses the box, or meets it only beyond
    /// the nearest hit so far, skips the object (and all of a CSG tree's evaluation).
    /// `--no-csg-pruning` switches a CSG tree's boxes off, this one included.
    ///
    /// Inlined: 1/d, passed out of line, went through memory and was read back as the box
    /// test's first step, and that stall (store forwarding fails) cost more than the division.
    #[inline(always)]
    fn boxed_object_hit(
        &self,
        o: u32,
        ray: &Ray,
        inv_dir: DVec3,
        t_min: f64,
        t_max: f64,
        stats: &mut Stats,
    ) -> Option<Hit> {
        if self.tested_behind_box(o)
            && !self.objects[o as usize]
                .bounds
                .hit(ray, inv_dir, t_min, t_max)
        {
            stats.bounds_skipped += 1;
            return None;
        }
        self.object_hit(o, ray, inv_dir, t_min, t_max, stats)
    }

    /// Whether object o is tested behind its box: always, but for CSG objects with their boxes
    /// switched off (`--no-csg-pruning`).
    #[inline(always)]
    fn tested_behind_box(&self, o: u32) -> bool {
        self.csg_pruning || !matches!(self.objects[o as usize].geometry, Geometry::Csg(_))
    }

    /// Nearest crossing of one object's surface with t_min < t < t_max. Kept out of line: its
    /// segment lists would otherwise give the probes' tight loops a large stack frame.
    #[inline(never)]
    fn object_hit(
        &self,
        object: u32,
        ray: &Ray,
        inv_dir: DVec3,
        t_min: f64,
        t_max: f64,
        stats: &mut Stats,
    ) -> Option<Hit> {
        stats.primitives_tested += 1;
        let (t, surface) = match &self.objects[object as usize].geometry {
            Geometry::Leaf(leaf) => {
                let l = &self.leaves[*leaf as usize];
                if let Shape::Mesh(mesh) = &l.shape {
                    let local = l.transform.as_ref().map_or(*ray, |tf| tf.ray_to_local(ray));
                    let (hit, visits) = match self.accel {
                        Accel::Bvh => mesh.hit(&local, t_min, t_max),
                        Accel::None => mesh.hit_brute(&local, t_min, t_max),
                    };
                    stats.bvh_nodes_visited += visits.nodes;
                    stats.primitives_tested += visits.items;
                    let (t, face) = hit?;
                    return Some(Hit {
                        t,
                        object,
                        surface: Surface::new(*leaf, face),
                    });
                }
                let s = l.span(ray)?;
                if s.t_in > t_min {
                    (s.t_in, Surface::new(*leaf, s.face_in as u32))
                } else {
                    (s.t_out, Surface::new(*leaf, s.face_out as u32))
                }
            }
            Geometry::Csg(root) => {
                let r = self.csg_ray(ray, inv_dir, t_min, t_max);
                self.csg_hit(object, root, &r, stats)?
            }
        };
        (t > t_min && t < t_max && t.is_finite()).then_some(Hit { t, object, surface })
    }

    /// The nearest crossing of a CSG object's surface past t_min: read off its primitives'
    /// spans when the tree is flat and the answer is clear, else from its segment list.
    fn csg_hit(
        &self,
        object: u32,
        root: &CsgNode,
        r: &CsgRay,
        stats: &mut Stats,
    ) -> Option<(f64, Surface)> {
        if let Some(flat) = &self.flat_csg[object as usize] {
            let mut work = CsgWork::default();
            let crossing = flat.nearest(self, r, &mut work);
            stats.csg_pruned += work.pruned;
            match crossing {
                Crossing::Hit(t, surface) => return Some((t, surface)),
                Crossing::Miss => return None,
                Crossing::Undecided => {}
            }
        }
        first_crossing(&self.csg_segments(root, r, stats), r.t_min)
    }

    /// The hit of one object through its probe: `object_hit`'s answer, found faster for plain
    /// spheres and planes.
    #[inline(always)]
    fn probe_hit(
        &self,
        probe: &Probe,
        ray: &Ray,
        inv_dir: DVec3,
        t_min: f64,
        t_max: f64,
        stats: &mut Stats,
    ) -> Option<Hit> {
        // Every arm ends in the same three parts, and the hit is put together once from
        // them: an arm that returned its own `Hit` would make the compiler pass all hits
        // through memory, and reading one back right after its field-by-field stores stalls
        // the processor (store forwarding fails: 5 % of the Whitted peer scene's time).
        let (t, object, surface) = match probe {
            Probe::Sphere {
                sphere,
                object,
                leaf,
            } => {
                stats.primitives_tested += 1;
                let t = sphere.hit(ray, t_min, t_max)?;
                (t, *object, Surface::new(*leaf, 0))
            }
            Probe::Plane {
                plane,
                object,
                leaf,
            } => {
                stats.primitives_tested += 1;
                let t = plane.hit(ray, t_min, t_max)?;
                (t, *object, Surface::new(*leaf, 0))
            }
            Probe::Spheres {
                group,
                objects,
                leaves,
            } => {
                stats.primitives_tested += group.len() as u64;
                let (t, k) = group.nearest(ray, t_min, t_max)?;
                (t, objects[k], Surface::new(leaves[k], 0))
            }
            Probe::Object(o) => {
                let h = self.boxed_object_hit(*o, ray, inv_dir, t_min, t_max, stats)?;
                (h.t, h.object, h.surface)
            }
        };
        Some(Hit { t, object, surface })
    }

    /// A blocker of a shadow ray through one probe: `probe_hit`'s answer, except that a group
    /// of spheres answers with its first sphere in the way (not the nearest), as testing them
    /// one after another until a blocker turns up does, and counts the spheres that took.
    #[inline(always)]
    fn probe_blocker(
        &self,
        probe: &Probe,
        ray: &Ray,
        inv_dir: DVec3,
        t_min: f64,
        t_max: f64,
        stats: &mut Stats,
    ) -> Option<Hit> {
        let Probe::Spheres {
            group,
            objects,
            leaves,
        } = probe
        else {
            return self.probe_hit(probe, ray, inv_dir, t_min, t_max, stats);
        };
        match group.first(ray, t_min, t_max) {
            Some((t, k)) => {
                stats.primitives_tested += k as u64 + 1;
                Some(Hit {
                    t,
                    object: objects[k],
                    surface: Surface::new(leaves[k], 0),
                })
            }
            None => {
                stats.primitives_tested += group.len() as u64;
                None
            }
        }
    }

    /// The nearest hit with t_min < t < t_max.
    pub fn intersect(&self, ray: &Ray, t_min: f64, t_max: f64, stats: &mut Stats) -> Option<Hit> {
        let inv_dir = self.inv_dir(ray);
        let (mut best, limit) = self.nearest_unbounded(ray, inv_dir, t_min, t_max, stats);
        if !self.bounded.is_empty() {
            let visits = self.bvh.closest(ray, t_min, limit, |item, limit| {
                let probe = &self.bounded[item as usize];
                let h = self.probe_hit(probe, ray, inv_dir, t_min, limit, stats)?;
                best = Some(h);
                Some(h.t)
            });
            stats.bvh_nodes_visited += visits.nodes;
        }
        best
    }

    /// The nearest hit among the objects outside the BVH, and the limit it sets for the rest.
    #[inline(always)]
    fn nearest_unbounded(
        &self,
        ray: &Ray,
        inv_dir: DVec3,
        t_min: f64,
        t_max: f64,
        stats: &mut Stats,
    ) -> (Option<Hit>, f64) {
        let (mut best, mut limit) = (None, t_max);
        for p in &self.unbounded {
            if let Some(h) = self.probe_hit(p, ray, inv_dir, t_min, limit, stats) {
                limit = h.t;
                best = Some(h);
            }
        }
        (best, limit)
    }

    /// `intersect` (t_min = 0, t_max = ∞) for up to 16 rays at once: `hits[i]` is exactly what
    /// `intersect` answers for ray i, and the stats are those of tracing the rays one by one.
    /// Without a BVH the rays go four at a time (`intersect_in_lanes`). Otherwise the rays
    /// that share the first one's direction signs go through the BVH as a packet (if there are
    /// at least `PACKET_MIN` of them); any others, one by one.
    pub fn intersect_packet(&self, rays: &[Ray], hits: &mut [Option<Hit>], stats: &mut Stats) {
        if self.in_lanes {
            for (rays, hits) in rays.chunks(LANES).zip(hits.chunks_mut(LANES)) {
                self.intersect_in_lanes(rays, hits, stats);
            }
            return;
        }
        let Some(first) = rays.first().map(signs) else {
            return;
        };
        let mut alike = [false; PACKET];
        for (a, ray) in alike.iter_mut().zip(rays) {
            *a = signs(ray) == first;
        }
        let one_by_one = alike.iter().filter(|&&a| a).count() < PACKET_MIN;
        let mut packet = [rays[0]; PACKET];
        let mut packet_inv = [DVec3::NAN; PACKET];
        let mut lanes = [0usize; PACKET];
        let mut n = 0;
        for (i, ray) in rays.iter().enumerate() {
            if !one_by_one && alike[i] {
                (packet[n], packet_inv[n], lanes[n]) = (*ray, self.inv_dir(ray), i);
                n += 1;
            } else {
                hits[i] = self.intersect(ray, 0.0, f64::INFINITY, stats);
            }
        }
        if n == 0 {
            return;
        }
        let mut limits = [f64::INFINITY; PACKET];
        for lane in 0..n {
            let (ray, inv) = (&packet[lane], packet_inv[lane]);
            let (hit, limit) = self.nearest_unbounded(ray, inv, 0.0, f64::INFINITY, stats);
            (hits[lanes[lane]], limits[lane]) = (hit, limit);
        }
        let visits =
            self.bvh
                .closest_packet(&packet[..n], 0.0, &mut limits, |lane, item, limit| {
                    let probe = &self.bounded[item as usize];
                    let h =
                        self.probe_hit(probe, &packet[lane], packet_inv[lane], 0.0, limit, stats)?;
                    hits[lanes[lane]] = Some(h);
                    Some(h.t)
                });
        stats.bvh_nodes_visited += visits.nodes;
    }

    /// Any hit with t_min < t < t_max (for shadow rays: the first blocker found).
    pub fn occluded(&self, ray: &Ray, t_min: f64, t_max: f64, stats: &mut Stats) -> Option<Hit> {
        let inv_dir = self.inv_dir(ray);
        for p in &self.unbounded {
            if let Some(h) = self.probe_blocker(p, ray, inv_dir, t_min, t_max, stats) {
                return Some(h);
            }
        }
        let mut blocker = None;
        if !self.bounded.is_empty() {
            let (_, visits) = self.bvh.any(ray, t_min, t_max, |item| {
                let probe = &self.bounded[item as usize];
                blocker = self.probe_blocker(probe, ray, inv_dir, t_min, t_max, stats);
                blocker.is_some()
            });
            stats.bvh_nodes_visited += visits.nodes;
        }
        blocker
    }

    /// Whether a blocker with 0 < t < t_max is among the objects in the BVH.
    fn occluded_in_bvh(&self, ray: &Ray, inv_dir: DVec3, t_max: f64, stats: &mut Stats) -> bool {
        let (blocked, visits) = self.bvh.any(ray, 0.0, t_max, |item| {
            self.probe_blocker(
                &self.bounded[item as usize],
                ray,
                inv_dir,
                0.0,
                t_max,
                stats,
            )
            .is_some()
        });
        stats.bvh_nodes_visited += visits.nodes;
        blocked
    }

    /// `occluded` for up to 16 shadow rays, ray i looking for blockers with 0 < t < t_max[i]:
    /// bit i of the answer is set when ray i is blocked, and the stats are those of asking
    /// `occluded` ray by ray. Without a BVH the rays go four at a time (`occluded_in_lanes`).
    /// Otherwise rays that get past the objects outside the BVH search it as a packet (any
    /// directions will do: an any-hit search visits the nodes in a fixed order).
    pub fn occluded_packet(&self, rays: &[Ray], t_max: &[f64], stats: &mut Stats) -> u32 {
        if self.in_lanes {
            let mut blocked = 0;
            for (k, (rays, t_max)) in rays.chunks(LANES).zip(t_max.chunks(LANES)).enumerate() {
                blocked |= self.occluded_in_lanes(rays, t_max, stats) << (k * LANES);
            }
            return blocked;
        }
        let mut blocked = 0u32;
        let mut packet = [Ray::UNUSED; PACKET];
        let mut packet_inv = [DVec3::NAN; PACKET];
        let mut reach = [0.0; PACKET];
        let mut lanes = [0usize; PACKET];
        let mut n = 0;
        for (i, ray) in rays.iter().enumerate() {
            let inv_dir = self.inv_dir(ray);
            if self.unbounded.iter().any(|p| {
                self.probe_blocker(p, ray, inv_dir, 0.0, t_max[i], stats)
                    .is_some()
            }) {
                blocked |= 1 << i;
            } else if !self.bounded.is_empty() {
                (packet[n], packet_inv[n], reach[n], lanes[n]) = (*ray, inv_dir, t_max[i], i);
                n += 1;
            }
        }
        if n == 0 {
            return blocked;
        }
        if n < PACKET_MIN {
            for k in 0..n {
                if self.occluded_in_bvh(&packet[k], packet_inv[k], reach[k], stats) {
                    let i = lanes[k];
                    blocked |= 1 << i;
                }
            }
            return blocked;
        }
        let (hit, visits) = self
            .bvh
            .any_packet(&packet[..n], 0.0, &reach, |lane, item| {
                let probe = &self.bounded[item as usize];
                self.probe_blocker(
                    probe,
                    &packet[lane],
                    packet_inv[lane],
                    0.0,
                    reach[lane],
                    stats,
                )
                .is_some()
            });
        stats.bvh_nodes_visited += visits.nodes;
        for (k, &i) in lanes[..n].iter().enumerate() {
            if hit & (1 << k) != 0 {
                blocked |= 1 << i;
            }
        }
        blocked
    }

    /// `intersect` (t_min = 0, t_max = ∞) for up to four rays in a scene without a BVH: each
    /// plain sphere or plane is tested against all the rays at once, in `RayLanes`, and any
    /// other object ray by ray, behind its box (tested against all the rays at once). Each
    /// ray meets the objects in the same order as in `intersect`, with the same arithmetic and
    /// the same shrinking limit, so it finds the same hit and counts the same tests.
    fn intersect_in_lanes(&self, rays: &[Ray], hits: &mut [Option<Hit>], stats: &mut Stats) {
        let lanes = RayLanes::new(rays);
        let slabs = self.boxes_outside_bvh.then(|| SlabLanes::new(&lanes));
        let used = (1u32 << rays.len()) - 1;
        let all = lane_mask(used);
        let mut limit = f64x4::splat(f64::INFINITY);
        hits.fill(None);
        // Lanes whose t lies in 0 < t < limit take it as their nearest hit so far.
        let take = |hits: &mut [Option<Hit>],
                    t: f64x4,
                    bits: u32,
                    object: u32,
                    leaf: u32,
                    limit: &mut f64x4| {
            let bits = bits & used;
            if bits == 0 {
                return;
            }
            *limit = lane_mask(bits).bitselect(t, *limit);
            let t = t.to_array();
            for (i, hit) in hits.iter_mut().enumerate() {
                if bits & (1 << i) != 0 {
                    *hit = Some(Hit {
                        t: t[i],
                        object,
                        surface: Surface::new(leaf, 0),
                    });
                }
            }
        };
        let within =
            |t: f64x4, limit: f64x4| (t.simd_gt(f64x4::ZERO) & t.simd_lt(limit)).to_bitmask();
        let n = rays.len() as u64;
        for p in &self.unbounded {
            match p {
                Probe::Plane {
                    plane,
                    object,
                    leaf,
                } => {
                    stats.primitives_tested += n;
                    let (t, bits) = plane.hits_of_lanes(&lanes, 0.0, limit);
                    take(hits, t, bits, *object, *leaf, &mut limit);
                }
                Probe::Sphere {
                    sphere,
                    object,
                    leaf,
                } => {
                    stats.primitives_tested += n;
                    let r2 = sphere.radius * sphere.radius;
                    if let Some(t) = sphere_against_lanes(sphere.center, r2, &lanes, all, 0.0) {
                        take(hits, t, within(t, limit), *object, *leaf, &mut limit);
                    }
                }
                Probe::Spheres {
                    group,
                    objects,
                    leaves,
                } => {
                    stats.primitives_tested += group.len() as u64 * n;
                    for k in 0..group.len() {
                        if let Some(t) = group.sphere_against(k, &lanes, all, 0.0) {
                            take(hits, t, within(t, limit), objects[k], leaves[k], &mut limit);
                        }
                    }
                }
                Probe::Object(o) => {
                    let slabs = slabs.as_ref().expect("boxed objects get slab lanes");
                    let mut t_max = limit.to_array();
                    self.object_in_lanes(*o, rays, slabs, &mut t_max, hits, stats);
                    limit = f64x4::new(t_max);
                }
            }
        }
    }

    /// `occluded` (t_min = 0) for up to four shadow rays in a scene without a BVH: each plain
    /// sphere or plane is tested against all the rays still open at once, in `RayLanes`, and
    /// any other object ray by ray, as in `intersect_in_lanes`. Each ray meets the objects in
    /// the same order as in `occluded`, with the same arithmetic, so it is blocked by the same
    /// one and counts the same tests.
    fn occluded_in_lanes(&self, rays: &[Ray], t_max: &[f64], stats: &mut Stats) -> u32 {
        let lanes = RayLanes::new(rays);
        let slabs = self.boxes_outside_bvh.then(|| SlabLanes::new(&lanes));
        let mut reach = [0.0; LANES];
        reach[..t_max.len()].copy_from_slice(t_max);
        let reach = f64x4::new(reach);
        let all = (1u32 << rays.len()) - 1;
        let mut open = all;
        // The lanes whose t (NaN for none) lies in 0 < t < t_max.
        let within = |t: f64x4| (t.simd_gt(f64x4::ZERO) & t.simd_lt(reach)).to_bitmask();
        for p in &self.unbounded {
            if open == 0 {
                break;
            }
            match p {
                Probe::Plane { plane, .. } => {
                    stats.primitives_tested += open.count_ones() as u64;
                    open &= !plane.hits_of_lanes(&lanes, 0.0, reach).1;
                }
                Probe::Sphere { sphere, .. } => {
                    stats.primitives_tested += open.count_ones() as u64;
                    let r2 = sphere.radius * sphere.radius;
                    let open_lanes = lane_mask(open);
                    if let Some(t) =
                        sphere_against_lanes(sphere.center, r2, &lanes, open_lanes, 0.0)
                    {
                        open &= !within(t);
                    }
                }
                Probe::Spheres { group, .. } => {
                    // A ray is blocked by the first sphere in the group's order, and counts the
                    // spheres up to it, as `SphereGroup::first` does.
                    for k in 0..group.len() {
                        if open == 0 {
                            break;
                        }
                        stats.primitives_tested += open.count_ones() as u64;
                        if let Some(t) = group.sphere_against(k, &lanes, lane_mask(open), 0.0) {
                            open &= !within(t);
                        }
                    }
                }
                Probe::Object(o) => {
                    let slabs = slabs.as_ref().expect("boxed objects get slab lanes");
                    open &= !self.object_blocks_lanes(*o, rays, slabs, reach, open, stats);
                }
            }
        }
        all & !open
    }

    /// The shading record of a hit. Inlined, with the normal's dispatch, into the tracer: it runs
    /// once per shaded hit.
    #[inline(always)]
    pub fn interaction(&self, ray: &Ray, hit: &Hit) -> Interaction {
        let leaf = &self.leaves[hit.surface.leaf as usize];
        let point = ray.at(hit.t);
        let mut outward = leaf.normal(point, hit.surface.face);
        if hit.surface.flip {
            outward = -outward;
        }
        // A triangle has no inside: it is seen from whichever side the ray comes.
        let inside = leaf.shape.is_solid() && outward.dot(ray.dir) > 0.0;
        let normal = if outward.dot(ray.dir) > 0.0 {
            -outward
        } else {
            outward
        };
        Interaction {
            point,
            normal,
            inside,
            leaf: hit.surface.leaf,
            face: hit.surface.face,
            object: hit.object,
            material: leaf.material,
        }
    }

    /// Offset of secondary-ray origins off a surface hit from `origin`. The automatic bias is
    /// relative: a computed hit point is off by a few ulps of the coordinates involved
    /// (|o| + |p|), so 1e−10 of them clears it by a factor of ~10⁶ while staying far below the
    /// size of any feature a scene at that scale can have (tests/robustness.rs sweeps scales
    /// 1e−4…1e6 and offsets to 1e6).
    #[inline]
    pub fn bias(&self, origin: DVec3, point: DVec3) -> f64 {
        self.shadow_bias.unwrap_or_else(|| {
            (1e-10 * (origin.abs().max_element() + point.abs().max_element())).max(1e-300)
        })
    }

    /// The hit point of a ray from `from`, moved off the surface to the side `dir` leaves by
    /// (so a ray from there cannot hit the surface again), and how far it moved.
    #[inline]
    pub fn offset(&self, si: &Interaction, dir: DVec3, from: DVec3) -> (DVec3, f64) {
        let bias = self.bias(from, si.point);
        let side = if dir.dot(si.normal) >= 0.0 {
            bias
        } else {
            -bias
        };
        (si.point + side * si.normal, bias)
    }
}
