//! The fast search: the core's nearest-hit and any-hit searches (`crate::scene::Search`),
//! faster, with the same hits and the same counted work to the last bit.
//!
//! `FastScene` is built from a compiled scene and its search index; it never changes them. It
//! tests plain spheres and planes directly and runs of spheres four at a time (`probe.rs`),
//! reads the nearest hit of a flat CSG object off its primitives' spans (`csg_crossing.rs`)
//! instead of building segment lists, and answers packets of rays (`packet_search.rs`).

use arrayvec::ArrayVec;
use glam::DVec3;

use super::bvh4::Bvh4;
use super::checker_lanes::checker_colors;
use super::csg_crossing::{Crossing, FlatCsg, LeafSpans};
use super::csg_lanes::CsgLanes;
use super::lanes::LANES;
use super::light_lanes::{lanes_light, LaneHighlight};
use super::plane_lanes::{lights_in_lanes, LanePlane};
use super::probe::{grouped, plane_hit, sphere_hit, Probe};
use super::shadow_cones::{Cone, ShadowCones};
use super::simd::{with_lanes, F64x4};
use crate::accel::Aabb;
use crate::geometry::csg::CsgWork;
use crate::geometry::{first_crossing, Aabox, Ray, Shape, Span, Surface};
use crate::scene::{Geometry, Hit, Interaction, Leaf, Scene, Search};
use crate::shading::{Light, Material};
use crate::stats::Stats;

/// A compiled scene with what the fast search needs beside it.
pub struct FastScene<'s> {
    /// The compiled scene searched.
    pub scene: &'s Scene,
    /// The bounded objects' probes, by BVH item number.
    pub(super) bounded: Vec<Probe>,
    /// The scene's BVH with four children a node, which packets of rays walk.
    pub(super) bvh4: Bvh4,
    /// The probes every ray tests (the scene's `unbounded` objects, runs of spheres grouped).
    pub(super) unbounded: Vec<Probe>,
    /// Per object: its CSG tree's flat form, when it has one. (Boxed, as the next: a few
    /// hundred bytes of `None` for every one of 10 000 spheres is megabytes of fresh pages
    /// for the kernel to clear.)
    flat_csg: Vec<Option<Box<FlatCsg>>>,
    /// Per object: its flat form of two operands the lanes can test (spheres, boxes,
    /// cylinders, cones), when it has one.
    pub(super) csg_lanes: Vec<Option<Box<CsgLanes>>>,
    /// Some object outside the BVH is tested behind its box: packets tested in lanes then find
    /// their 1/d in lanes, for each such box's test of four rays at once.
    pub(super) boxes_outside_bvh: bool,
    /// Some object, in the BVH or not, is tested behind its box: the searches find each ray's
    /// 1/d once for all the boxes (`inv_dir`).
    boxed_objects: bool,
    /// No BVH: a packet's rays, primary, shadow and secondary, are tested four at a time.
    pub(super) in_lanes: bool,
    /// Per material: the colours of its checker, when the lanes paint it (`checker_lanes`).
    checkers: Vec<Option<[DVec3; 2]>>,
    /// Per material: its highlight, as the lanes light it.
    highlights: Vec<LaneHighlight>,
    /// Per light: the cones of the boxes its shadow rays test in lanes (`shadow_cones`).
    pub(super) shadow_cones: Vec<ShadowCones>,
    /// The planes whose surfaces are shaded in lanes from hit to light (`plane_lanes`), where
    /// the objects are tested in lanes, and the lights they are shaded under.
    pub(super) planes: Vec<LanePlane>,
    pub(super) plane_lights: Vec<(DVec3, DVec3)>,
    /// Per leaf: a turned box's six faces' outward normals in world space (its normal at a
    /// hit depends on the face alone), found once rather than carried out of the box's space
    /// at every hit.
    box_normals: Vec<Option<Box<[DVec3; 6]>>>,
}

impl LeafSpans for Scene {
    #[inline]
    fn leaf_span(&self, leaf: u32, ray: &Ray) -> Option<Span> {
        self.leaves[leaf as usize].span(ray)
    }
}

impl<'s> FastScene<'s> {
    /// The fast search of `scene`: its objects' probes gathered (runs of spheres grouped into SIMD
    /// lanes, CSG trees flattened).
    pub fn new(scene: &'s Scene) -> FastScene<'s> {
        let index = &scene.index;
        let flat_csg: Vec<Option<Box<FlatCsg>>> = scene
            .objects
            .iter()
            .map(|o| match &o.geometry {
                Geometry::Csg(root) => FlatCsg::new(root, |leaf| {
                    scene.leaves[leaf as usize].world_sphere().cloned()
                })
                .map(Box::new),
                Geometry::Leaf(_) | Geometry::Group(_) => None,
            })
            .collect();
        let mut fast = FastScene {
            scene,
            bvh4: Bvh4::new(&index.bvh),
            bounded: vec![],
            unbounded: vec![],
            csg_lanes: vec![],
            flat_csg,
            boxes_outside_bvh: false,
            boxed_objects: false,
            in_lanes: false,
            checkers: scene.materials.iter().map(checker_colors).collect(),
            highlights: scene.materials.iter().map(LaneHighlight::of).collect(),
            shadow_cones: vec![],
            planes: vec![],
            plane_lights: vec![],
            box_normals: scene.leaves.iter().map(box_normals).collect(),
        };
        fast.bounded = index.bounded.iter().map(|&o| fast.probe(o)).collect();
        fast.unbounded = grouped(index.unbounded.iter().map(|&o| fast.probe(o)).collect());
        fast.csg_lanes = fast
            .flat_csg
            .iter()
            .map(|f| fast.lanes_form(f.as_ref()?).map(Box::new))
            .collect();
        let boxed = |probes: &[Probe]| probes.iter().any(|p| p.boxed_object().is_some());
        fast.boxes_outside_bvh = boxed(&fast.unbounded);
        fast.boxed_objects = fast.boxes_outside_bvh || boxed(&fast.bounded);
        fast.in_lanes = fast.bounded.is_empty();
        if fast.in_lanes && fast.boxes_outside_bvh {
            fast.shadow_cones = scene.lights.iter().map(|l| fast.cones_from(l)).collect();
        }
        if fast.in_lanes {
            if let Some(lights) = lights_in_lanes(scene) {
                fast.planes = LanePlane::of_scene(scene, &fast.checkers, &fast.highlights);
                fast.plane_lights = lights;
            }
        }
        fast
    }

    /// The shading record of a ray's hit without its patterns (`Scene::record_surface`), a
    /// turned box's normal read from the table.
    #[inline(always)]
    pub(super) fn record_surface(&self, ray: &Ray, hit: &Hit, si: &mut Interaction) -> &Material {
        let scene = self.scene;
        match &self.box_normals[hit.surface.leaf as usize] {
            Some(normals) => {
                let outward = normals[hit.surface.face as usize];
                scene.record_with_normal(ray, hit, ray.at(hit.t), outward, si)
            }
            None => scene.record_surface(ray, hit, si),
        }
    }

    /// The cones of the boxes tested behind them, seen from `light` where the lanes light it
    /// (`lanes_light`).
    fn cones_from(&self, light: &Light) -> ShadowCones {
        let Some((position, _)) = lanes_light(light) else {
            return ShadowCones::default();
        };
        let cone = |p: &Probe| {
            let o = p.boxed_object().filter(|&o| self.tested_behind_box(o))?;
            Cone::new(position, &self.scene.objects[o as usize].bounds)
        };
        ShadowCones {
            by_probe: self.unbounded.iter().map(cone).collect(),
        }
    }

    /// The flat CSG object in the form `csg_in_lanes` tests, if it is one: two operands, each a
    /// sphere in world space or a box, cylinder or cone (turned and moved as its transform
    /// says).
    fn lanes_form(&self, flat: &FlatCsg) -> Option<CsgLanes> {
        let [(a, a_box), (b, b_box)] = flat.operands() else {
            return None;
        };
        let operand = |leaf: u32| {
            let l = &self.scene.leaves[leaf as usize];
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

    /// The colours of a material's checker, when the lanes paint it.
    #[inline(always)]
    pub(super) fn checker(&self, material: u32) -> Option<&[DVec3; 2]> {
        self.checkers[material as usize].as_ref()
    }

    /// The highlight of material `material`, as the lanes light it.
    #[inline(always)]
    pub(super) fn highlight(&self, material: u32) -> LaneHighlight {
        self.highlights[material as usize]
    }

    /// How many planes are shaded in lanes from hit to light (`plane_lanes`).
    pub fn planes_in_lanes(&self) -> usize {
        self.planes.len()
    }

    /// Whether packets of rays go four at a time through the objects (no BVH: `intersect_in_lanes`).
    pub fn tests_in_lanes(&self) -> bool {
        self.in_lanes
    }

    /// The plain spheres tested outside a BVH, as centre and r², in the order the searches
    /// meet them (a group's in its order): sphere s is bit s of `Missed::spheres`.
    pub(super) fn plain_spheres(&self) -> impl Iterator<Item = (DVec3, f64)> + '_ {
        self.unbounded.iter().flat_map(|probe| {
            let mut spheres = ArrayVec::<(DVec3, f64), LANES>::new();
            match probe {
                Probe::Sphere { sphere, .. } => {
                    spheres.push((sphere.center, sphere.radius * sphere.radius))
                }
                Probe::Spheres { group, .. } => {
                    spheres.extend((0..group.len()).map(|k| group.sphere(k)))
                }
                Probe::Plane { .. } | Probe::Box { .. } | Probe::Object(_) => {}
            }
            spheres
        })
    }

    /// How the hit searches test an object: directly for a plain sphere or plane.
    fn probe(&self, object: u32) -> Probe {
        let Geometry::Leaf(leaf) = self.scene.objects[object as usize].geometry else {
            return Probe::Object(object);
        };
        let l = &self.scene.leaves[leaf as usize];
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
            (Shape::Box(_), _) => Probe::Box {
                bounds: self.scene.objects[object as usize].bounds,
                object,
                leaf,
            },
            _ => Probe::Object(object),
        }
    }

    /// 1/d, which the boxes of the objects tested behind one need: found once per ray, not
    /// once per box. Not at all in scenes without such objects (plain spheres and planes),
    /// where a division per ray would buy nothing; there it is NaN, which no box test passes.
    #[inline(always)]
    pub(super) fn inv_dir(&self, ray: &Ray) -> DVec3 {
        if self.boxed_objects {
            ray.dir.recip()
        } else {
            DVec3::NAN
        }
    }

    /// `object_hit` behind the object's box: a ray that misses the box, or meets it only beyond
    /// the nearest hit so far, skips the object (and all of a CSG tree's evaluation).
    /// `--no-csg-pruning` switches a CSG tree's boxes off, this one included.
    ///
    /// Inlined, so that 1/d stays in registers for the box test rather than going through
    /// memory and being read back at once (a store-forwarding stall).
    #[inline(always)]
    fn boxed_object_hit<V: F64x4>(
        &self,
        o: u32,
        ray: &Ray,
        inv_dir: DVec3,
        t_min: f64,
        t_max: f64,
        stats: &mut Stats,
    ) -> Option<Hit> {
        let bounds = &self.scene.objects[o as usize].bounds;
        if self.tested_behind_box(o) && misses(bounds, ray, inv_dir, t_min, t_max, stats) {
            return None;
        }
        self.object_hit::<V>(o, ray, inv_dir, t_min, t_max, stats)
    }

    /// Whether object o is tested behind its box: always, but for CSG objects with their boxes
    /// switched off (`--no-csg-pruning`).
    #[inline(always)]
    pub(super) fn tested_behind_box(&self, o: u32) -> bool {
        self.scene.csg_pruning
            || !matches!(self.scene.objects[o as usize].geometry, Geometry::Csg(_))
    }

    /// Nearest crossing of one object's surface with t_min < t < t_max: the core's
    /// `Scene::object_crossing`, but for a box, tested right here (`box_crossing`), and for a
    /// flat CSG object, whose nearest crossing is read off its primitives' spans where the
    /// answer is clear. All but the box kept out of line: CSG's segment lists would otherwise
    /// give the probes' tight loops a large stack frame.
    #[inline(always)]
    pub(super) fn object_hit<V: F64x4>(
        &self,
        o: u32,
        ray: &Ray,
        inv_dir: DVec3,
        t_min: f64,
        t_max: f64,
        stats: &mut Stats,
    ) -> Option<Hit> {
        let scene = self.scene;
        let geometry = &scene.objects[o as usize].geometry;
        if let Geometry::Leaf(leaf) = geometry {
            if let Some(hit) = box_crossing(scene, o, *leaf, ray, t_min, t_max, stats) {
                return hit;
            }
        }
        V::outlined(
            #[inline(always)]
            || {
                let (Geometry::Csg(root), Some(flat)) = (geometry, &self.flat_csg[o as usize])
                else {
                    return scene.object_crossing(o, ray, inv_dir, t_min, t_max, stats);
                };
                stats.primitives_tested += 1;
                let r = scene.csg_ray(ray, inv_dir, t_min, t_max);
                let mut work = CsgWork::default();
                let crossing = flat.nearest::<V>(scene, &r, &mut work);
                stats.csg_pruned += work.pruned;
                let (t, surface) = match crossing {
                    Crossing::Hit(t, surface) => (t, surface),
                    Crossing::Miss => return None,
                    Crossing::Undecided => {
                        first_crossing(&scene.csg_segments(root, &r, stats), t_min)?
                    }
                };
                (t > t_min && t < t_max && t.is_finite()).then_some(Hit {
                    t,
                    object: o,
                    surface,
                })
            },
        )
    }

    /// The hit of one object through its probe: `object_hit`'s answer, found faster for plain
    /// spheres and planes.
    #[inline(always)]
    pub(super) fn probe_hit<V: F64x4>(
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
        // the processor (store forwarding fails).
        let (t, object, surface) = match probe {
            Probe::Sphere {
                sphere,
                object,
                leaf,
            } => {
                stats.primitives_tested += 1;
                let t = sphere_hit(sphere, ray, t_min, t_max)?;
                (t, *object, Surface::new(*leaf, 0))
            }
            Probe::Plane {
                plane,
                object,
                leaf,
            } => {
                stats.primitives_tested += 1;
                let t = plane_hit(plane, ray, t_min, t_max)?;
                (t, *object, Surface::new(*leaf, 0))
            }
            Probe::Spheres {
                group,
                objects,
                leaves,
            } => {
                stats.primitives_tested += group.len() as u64;
                let (t, k) = group.nearest::<V>(ray, t_min, t_max)?;
                (t, objects[k], Surface::new(leaves[k], 0))
            }
            Probe::Box {
                bounds,
                object,
                leaf,
            } => {
                // `boxed_object_hit`'s test and count, then `object_hit`'s box crossing.
                if misses(bounds, ray, inv_dir, t_min, t_max, stats) {
                    return None;
                }
                let crossing = box_crossing(self.scene, *object, *leaf, ray, t_min, t_max, stats);
                let h = crossing.expect("a box probe holds a box leaf")?;
                (h.t, h.object, h.surface)
            }
            Probe::Object(o) => {
                let h = self.boxed_object_hit::<V>(*o, ray, inv_dir, t_min, t_max, stats)?;
                (h.t, h.object, h.surface)
            }
        };
        Some(Hit { t, object, surface })
    }

    /// A blocker of a shadow ray through one probe: `probe_hit`'s answer, except that a group
    /// of spheres answers with its first sphere in the way (not the nearest), as testing them
    /// one after another until a blocker turns up does, and counts the spheres that took.
    #[inline(always)]
    pub(super) fn probe_blocker<V: F64x4>(
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
            return self.probe_hit::<V>(probe, ray, inv_dir, t_min, t_max, stats);
        };
        match group.first::<V>(ray, t_min, t_max) {
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

    /// The nearest hit among the objects outside the BVH, and the limit it sets for the rest.
    #[inline(always)]
    pub(super) fn nearest_unbounded<V: F64x4>(
        &self,
        ray: &Ray,
        inv_dir: DVec3,
        t_min: f64,
        t_max: f64,
        stats: &mut Stats,
    ) -> (Option<Hit>, f64) {
        let (mut best, mut limit) = (None, t_max);
        for p in &self.unbounded {
            if let Some(h) = self.probe_hit::<V>(p, ray, inv_dir, t_min, limit, stats) {
                limit = h.t;
                best = Some(h);
            }
        }
        (best, limit)
    }
}

impl Search for FastScene<'_> {
    fn nearest(&self, ray: &Ray, t_min: f64, t_max: f64, stats: &mut Stats) -> Option<Hit> {
        with_lanes!(V => self.nearest_in::<V>(ray, t_min, t_max, stats))
    }

    fn blocker(&self, ray: &Ray, t_min: f64, t_max: f64, stats: &mut Stats) -> Option<Hit> {
        with_lanes!(V => self.blocker_in::<V>(ray, t_min, t_max, stats))
    }
}

impl FastScene<'_> {
    /// `Search::nearest`, in lanes of type V.
    #[inline(always)]
    fn nearest_in<V: F64x4>(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        stats: &mut Stats,
    ) -> Option<Hit> {
        let inv_dir = self.inv_dir(ray);
        let (mut best, limit) = self.nearest_unbounded::<V>(ray, inv_dir, t_min, t_max, stats);
        if !self.bounded.is_empty() {
            let bvh = &self.scene.index.bvh;
            let visits = bvh.closest(ray.origin, ray.dir, t_min, limit, |item, limit| {
                let probe = &self.bounded[item as usize];
                let h = self.probe_hit::<V>(probe, ray, inv_dir, t_min, limit, stats)?;
                best = Some(h);
                Some(h.t)
            });
            stats.bvh_nodes_visited += visits.nodes;
        }
        best
    }

    /// `Search::blocker`, in lanes of type V.
    #[inline(always)]
    fn blocker_in<V: F64x4>(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        stats: &mut Stats,
    ) -> Option<Hit> {
        let inv_dir = self.inv_dir(ray);
        for p in &self.unbounded {
            if let Some(h) = self.probe_blocker::<V>(p, ray, inv_dir, t_min, t_max, stats) {
                return Some(h);
            }
        }
        let mut blocker = None;
        if !self.bounded.is_empty() {
            let bvh = &self.scene.index.bvh;
            let (_, visits) = bvh.any(ray.origin, ray.dir, t_min, t_max, |item| {
                let probe = &self.bounded[item as usize];
                blocker = self.probe_blocker::<V>(probe, ray, inv_dir, t_min, t_max, stats);
                blocker.is_some()
            });
            stats.bvh_nodes_visited += visits.nodes;
        }
        blocker
    }
}

/// The core's crossing of a box leaf (`Scene::object_crossing`: the leaf's span, then its
/// first end past t_min), compiled into the wing's copy with the box's slab test, instead of
/// through the dispatch over every kind of shape. `None` when the leaf is not a box; else
/// the answer, a hit or none.
#[inline(always)]
fn box_crossing(
    scene: &Scene,
    o: u32,
    leaf: u32,
    ray: &Ray,
    t_min: f64,
    t_max: f64,
    stats: &mut Stats,
) -> Option<Option<Hit>> {
    let l = &scene.leaves[leaf as usize];
    let Shape::Box(aabox) = &l.shape else {
        return None;
    };
    stats.primitives_tested += 1;
    let local = l.transform.as_ref().map_or(*ray, |tf| tf.ray_to_local(ray));
    let (t, face, crosses) = first_crossing_past(aabox, &local, t_min);
    let hit = crosses & (t > t_min) & (t < t_max) & t.is_finite();
    Some(hit.then_some(Hit {
        t,
        object: o,
        surface: Surface::new(leaf, face as u32),
    }))
}

/// Whether the ray misses `bounds` for t in [t_min, t_max] (`Aabb::hit`), counting the object
/// skipped when it does.
#[inline(always)]
fn misses(
    bounds: &Aabb,
    ray: &Ray,
    inv_dir: DVec3,
    t_min: f64,
    t_max: f64,
    stats: &mut Stats,
) -> bool {
    let missed = !bounds.hit(ray.origin, inv_dir, t_min, t_max);
    if missed {
        stats.bounds_skipped += 1;
    }
    missed
}

/// `Aabox::span`, then the span's first end past t_min (`Span::first_end_past`): its t and
/// face, and whether the ray meets the box at all (whether the core's span exists). The same
/// arithmetic, but selects where the core branches: whether a ray meets a box, and through
/// which faces, is as random as the ray, and a mispredicted jump costs more than the slabs.
/// A ray parallel to a slab divides by zero here, but the quotient is never taken.
#[inline(always)]
fn first_crossing_past(aabox: &Aabox, ray: &Ray, t_min: f64) -> (f64, u8, bool) {
    let (mut t_in, mut t_out) = (f64::NEG_INFINITY, f64::INFINITY);
    let (mut face_in, mut face_out) = (0u8, 0u8);
    let mut outside = false;
    for axis in 0..3 {
        let (o, d) = (ray.origin[axis], ray.dir[axis]);
        let (lo, hi) = (aabox.min[axis], aabox.max[axis]);
        let parallel = d == 0.0;
        outside |= parallel & ((o < lo) | (o > hi));
        let (t0, t1) = ((lo - o) / d, (hi - o) / d);
        let (f0, f1) = (2 * axis as u8, 2 * axis as u8 + 1);
        let negative = d < 0.0;
        let (near, far) = select(negative, (t1, t0), (t0, t1));
        let (face_near, face_far) = select(negative, (f1, f0), (f0, f1));
        let enters = !parallel & (near > t_in);
        (t_in, face_in) = select(enters, (near, face_near), (t_in, face_in));
        let leaves = !parallel & (far < t_out);
        (t_out, face_out) = select(leaves, (far, face_far), (t_out, face_out));
    }
    let (t, face) = select(t_in > t_min, (t_in, face_in), (t_out, face_out));
    (t, face, !outside & (t_in <= t_out))
}

/// `a` where `c`, else `b`.
#[inline(always)]
fn select<T>(c: bool, a: T, b: T) -> T {
    if c {
        a
    } else {
        b
    }
}

/// A turned box's faces' outward normals in world space, as `Leaf::normal` finds them.
fn box_normals(leaf: &Leaf) -> Option<Box<[DVec3; 6]>> {
    match (&leaf.shape, &leaf.transform) {
        (Shape::Box(b), Some(tf)) => Some(Box::new(std::array::from_fn(|face| {
            tf.normal_to_world(b.normal(face as u8))
        }))),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The core's answer: the box's span, then its first end past t_min.
    fn core_crossing(aabox: &Aabox, ray: &Ray, t_min: f64) -> Option<(u64, u8)> {
        let (t, face) = aabox.span(ray)?.first_end_past(t_min);
        Some((t.to_bits(), face))
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 5000, ..ProptestConfig::default() })]

        /// On a coarse grid, so that rays start on faces, edges and corners, run along faces
        /// (d = ±0) and meet boxes flat as a sheet: the same crossing, to the bit, and the
        /// same misses, as the core's branches find.
        #[test]
        fn the_branch_free_box_crossing_is_the_cores(
            corner in prop::array::uniform3(-2i32..=2),
            size in prop::array::uniform3(0i32..=2),
            origin in prop::array::uniform3(-6i32..=6),
            dir in prop::array::uniform3(-2i32..=2),
            negative_zero in prop::array::uniform3(prop::bool::ANY),
            t_min in prop::sample::select(vec![0.0, -1.0, 1e-9, 0.5]),
        ) {
            let min = DVec3::from_array(corner.map(f64::from));
            let aabox = Aabox { min, max: min + DVec3::from_array(size.map(f64::from)) };
            let mut d = dir.map(f64::from);
            for (c, negative) in d.iter_mut().zip(negative_zero) {
                if *c == 0.0 && negative {
                    *c = -0.0;
                }
            }
            let ray = Ray::raw(DVec3::from_array(origin.map(|k| k as f64 * 0.5)), DVec3::from_array(d));
            let (t, face, crosses) = first_crossing_past(&aabox, &ray, t_min);
            let wing = crosses.then_some((t.to_bits(), face));
            prop_assert_eq!(wing, core_crossing(&aabox, &ray, t_min), "{:?} {:?}", aabox, ray);
        }
    }
}
