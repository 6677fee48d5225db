//! The hit search: which object a ray meets first (the nearest hit), and whether anything lies
//! between a point and a light (any hit: a shadow ray needs only one blocker).
//!
//! Objects with a bounding box sit in a bounding volume hierarchy; a ray descends only into
//! the boxes it passes through (seed 002: "fewer ray-object intersections"). Objects no box
//! can hold (planes, complements) are tested by every ray. Each object is tested by the one
//! intersection routine of its shape, or through its CSG segment list.

use glam::DVec3;

use super::objects::{Geometry, Group, Object};
use super::{Hit, Scene};
use crate::accel::{Aabb, Bvh};
use crate::geometry::{first_crossing, Ray, Shape, Surface};
use crate::stats::Stats;

/// Where rays find what they hit. The scene answers these itself, one object at a time
/// (below); the renderer's fast wing (`crate::fast`) answers them with the same results to the
/// last bit, faster. The tracer asks through this trait, so the same recursion runs on either.
pub trait Search: Sync {
    /// The nearest hit with t_min < t < t_max.
    fn nearest(&self, ray: &Ray, t_min: f64, t_max: f64, stats: &mut Stats) -> Option<Hit>;
    /// A hit with t_min < t < t_max, the first one found: a shadow ray is blocked by any.
    fn blocker(&self, ray: &Ray, t_min: f64, t_max: f64, stats: &mut Stats) -> Option<Hit>;
}

/// How intersections are found.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Accel {
    /// Test every object (the brute force a lesson compares the BVH with).
    None,
    /// Search a bounding volume hierarchy over the objects with a box.
    #[default]
    Bvh,
}

/// The objects arranged for the search.
#[derive(Clone, Debug, Default)]
pub struct SearchIndex {
    /// Whether the search uses the BVH or tests every object.
    pub accel: Accel,
    /// The hierarchy over the bounded objects; its item i is object `bounded[i]`.
    pub bvh: Bvh,
    /// The objects with a finite box, in the BVH's item order.
    pub bounded: Vec<u32>,
    /// The objects every ray tests, in scene order: those without a box, or all of them when
    /// the scene has no BVH.
    pub unbounded: Vec<u32>,
}

/// Below this many bounded objects a BVH buys nothing: a brute-force loop rejects most
/// objects in a few instructions (`benches/intersect.rs`: the two cross between 16 and 64
/// spheres).
const BVH_MIN_OBJECTS: usize = 16;

impl SearchIndex {
    /// A BVH over the bounded objects if `accel` asks for one and there are enough of them.
    pub fn build(scene: &Scene, accel: Accel) -> SearchIndex {
        let (bounded, unbounded): (Vec<u32>, Vec<u32>) = (0..scene.objects.len() as u32)
            .partition(|&i| scene.objects[i as usize].bounds.is_finite());
        if accel == Accel::Bvh && bounded.len() >= BVH_MIN_OBJECTS {
            let boxes: Vec<_> = bounded
                .iter()
                .map(|&i| scene.objects[i as usize].bounds)
                .collect();
            SearchIndex {
                accel,
                bvh: Bvh::build(&boxes),
                bounded,
                unbounded,
            }
        } else {
            SearchIndex {
                accel,
                bvh: Bvh::default(),
                bounded: vec![],
                unbounded: (0..scene.objects.len() as u32).collect(),
            }
        }
    }
}

impl Search for Scene {
    fn nearest(&self, ray: &Ray, t_min: f64, t_max: f64, stats: &mut Stats) -> Option<Hit> {
        self.nearest_watched(ray, t_min, t_max, stats, |_, _| {})
    }

    fn blocker(&self, ray: &Ray, t_min: f64, t_max: f64, stats: &mut Stats) -> Option<Hit> {
        self.blocker_watched(ray, t_min, t_max, stats, |_, _| {})
    }
}

/// The BVH boxes one ray's search tested: what the explorer overlays on its diagram (`b`).
#[derive(Clone, Debug, Default)]
pub struct Visited {
    /// Each box tested, in the order tested, and whether the ray entered it.
    pub boxes: Vec<(Aabb, bool)>,
    /// Boxes in the whole hierarchy.
    pub total: usize,
    /// Objects whose own test ran (the leaves' objects the ray reached, and the unbounded).
    pub objects_tested: u64,
    /// What the search found.
    pub hit: Option<Hit>,
}

impl Scene {
    /// `Search::nearest`, telling `watch(node, entered)` of every BVH node whose box it tests.
    pub fn nearest_watched(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        stats: &mut Stats,
        watch: impl FnMut(u32, bool),
    ) -> Option<Hit> {
        let inv_dir = ray.dir.recip();
        let (mut best, mut limit) = (None, t_max);
        for &o in &self.index.unbounded {
            if let Some(h) = self.object_hit(o, ray, inv_dir, t_min, limit, stats) {
                limit = h.t;
                best = Some(h);
            }
        }
        let index = &self.index;
        let visits = index.bvh.closest_watched(
            ray.origin,
            ray.dir,
            t_min,
            limit,
            |item, limit| {
                let o = index.bounded[item as usize];
                let h = self.object_hit(o, ray, inv_dir, t_min, limit, stats)?;
                best = Some(h);
                Some(h.t)
            },
            watch,
        );
        stats.bvh_nodes_visited += visits.nodes;
        best
    }

    /// `Search::blocker`, telling `watch(node, entered)` of every BVH node whose box it tests.
    pub fn blocker_watched(
        &self,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        stats: &mut Stats,
        watch: impl FnMut(u32, bool),
    ) -> Option<Hit> {
        let inv_dir = ray.dir.recip();
        for &o in &self.index.unbounded {
            if let Some(h) = self.object_hit(o, ray, inv_dir, t_min, t_max, stats) {
                return Some(h);
            }
        }
        let index = &self.index;
        let mut blocker = None;
        let (_, visits) = index.bvh.any_watched(
            ray.origin,
            ray.dir,
            t_min,
            t_max,
            |item| {
                let o = index.bounded[item as usize];
                blocker = self.object_hit(o, ray, inv_dir, t_min, t_max, stats);
                blocker.is_some()
            },
            watch,
        );
        stats.bvh_nodes_visited += visits.nodes;
        blocker
    }

    /// The boxes the search of a ray tests: the nearest-hit search up to `t_max`, or the
    /// shadow ray's any-hit search (`shadow`), exactly as the tracer runs them.
    pub fn visited_boxes(&self, ray: &Ray, t_max: f64, shadow: bool) -> Visited {
        let nodes = self.index.bvh.nodes();
        let mut boxes = vec![];
        let watch = |node: u32, entered: bool| boxes.push((nodes[node as usize].bounds(), entered));
        let mut stats = Stats::default();
        let hit = if shadow {
            self.blocker_watched(ray, 0.0, t_max, &mut stats, watch)
        } else {
            self.nearest_watched(ray, 0.0, t_max, &mut stats, watch)
        };
        Visited {
            boxes,
            total: nodes.len(),
            objects_tested: stats.primitives_tested,
            hit,
        }
    }

    /// Chooses the acceleration structure (rebuilding the BVH if needed).
    pub fn set_accel(&mut self, accel: Accel) {
        self.index = SearchIndex::build(self, accel);
    }

    /// Nodes in the scene's BVH (0 without one).
    pub fn bvh_nodes(&self) -> usize {
        self.index.bvh.node_count()
    }

    /// The nearest crossing of object o's surface with t_min < t < t_max. `inv_dir` is 1/d,
    /// for the object's box.
    pub fn object_hit(
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
                .hit(ray.origin, inv_dir, t_min, t_max)
        {
            stats.bounds_skipped += 1;
            return None;
        }
        self.object_crossing(o, ray, inv_dir, t_min, t_max, stats)
    }

    /// `object_hit` without the box: the object's own test.
    pub fn object_crossing(
        &self,
        o: u32,
        ray: &Ray,
        inv_dir: DVec3,
        t_min: f64,
        t_max: f64,
        stats: &mut Stats,
    ) -> Option<Hit> {
        let geometry = &self.objects[o as usize].geometry;
        let reach = Reach {
            ray,
            inv_dir,
            t_min,
            t_max,
        };
        self.geometry_crossing(o, geometry, reach, stats)
    }

    /// The nearest crossing of a geometry's surface with t_min < t < t_max, reported as a hit
    /// on object o (a group's members report the group).
    fn geometry_crossing(
        &self,
        o: u32,
        geometry: &Geometry,
        reach: Reach,
        stats: &mut Stats,
    ) -> Option<Hit> {
        let Reach {
            ray,
            inv_dir,
            t_min,
            t_max,
        } = reach;
        stats.primitives_tested += 1;
        let (t, surface) = match geometry {
            Geometry::Leaf(leaf) => {
                let l = &self.leaves[*leaf as usize];
                if let Shape::Mesh(mesh) = &l.shape {
                    // A mesh searches its own hierarchy of triangles.
                    let local = l.transform.as_ref().map_or(*ray, |tf| tf.ray_to_local(ray));
                    let (hit, visits) = match self.index.accel {
                        Accel::Bvh => mesh.hit(&local, t_min, t_max),
                        Accel::None => mesh.hit_brute(&local, t_min, t_max),
                    };
                    stats.bvh_nodes_visited += visits.nodes;
                    stats.primitives_tested += visits.items;
                    let (t, face) = hit?;
                    let surface = Surface::new(*leaf, face);
                    return Some(Hit {
                        t,
                        object: o,
                        surface,
                    });
                }
                let (t, face) = l.span(ray)?.first_end_past(t_min);
                (t, Surface::new(*leaf, face as u32))
            }
            Geometry::Csg(root) => {
                let r = self.csg_ray(ray, inv_dir, t_min, t_max);
                first_crossing(&self.csg_segments(root, &r, stats), t_min)?
            }
            Geometry::Group(group) => return self.group_crossing(o, group, reach, stats),
        };
        (t > t_min && t < t_max && t.is_finite()).then_some(Hit {
            t,
            object: o,
            surface,
        })
    }

    /// The nearest hit among a group's members: those without a box first, then the group's
    /// own hierarchy, each member behind its box (as objects are in the scene's).
    fn group_crossing(
        &self,
        o: u32,
        group: &Group,
        reach: Reach,
        stats: &mut Stats,
    ) -> Option<Hit> {
        let Reach {
            ray,
            inv_dir,
            t_min,
            t_max,
        } = reach;
        let (mut best, mut limit) = (None, t_max);
        let member_hit = |m: u32, limit: f64, stats: &mut Stats| {
            let member = &group.members[m as usize];
            if self.member_behind_box(member)
                && !member.bounds.hit(ray.origin, inv_dir, t_min, limit)
            {
                stats.bounds_skipped += 1;
                return None;
            }
            let reach = Reach {
                t_max: limit,
                ..reach
            };
            self.geometry_crossing(o, &member.geometry, reach, stats)
        };
        if self.index.accel == Accel::None {
            // Brute force, as for the scene's objects: every member.
            for m in 0..group.members.len() as u32 {
                if let Some(h) = member_hit(m, limit, stats) {
                    limit = h.t;
                    best = Some(h);
                }
            }
            return best;
        }
        for &m in &group.unbounded {
            if let Some(h) = member_hit(m, limit, stats) {
                limit = h.t;
                best = Some(h);
            }
        }
        let visits = group
            .bvh
            .closest(ray.origin, ray.dir, t_min, limit, |item, limit| {
                let h = member_hit(group.bounded[item as usize], limit, stats)?;
                best = Some(h);
                Some(h.t)
            });
        stats.bvh_nodes_visited += visits.nodes;
        best
    }

    /// Whether a group's member is tested behind its box: as objects are (`tested_behind_box`).
    fn member_behind_box(&self, member: &Object) -> bool {
        match &member.geometry {
            Geometry::Leaf(leaf) => {
                let l = &self.leaves[*leaf as usize];
                !(l.transform.is_none() && matches!(l.shape, Shape::Sphere(_) | Shape::Plane(_)))
            }
            Geometry::Csg(_) => self.csg_pruning,
            Geometry::Group(_) => true,
        }
    }

    /// Whether object o is tested behind its bounding box. A plain sphere or plane is not: its
    /// own test costs what a box's does. A CSG object is not when its boxes are switched off
    /// (`--no-csg-pruning`).
    pub fn tested_behind_box(&self, o: u32) -> bool {
        self.member_behind_box(&self.objects[o as usize])
    }
}

/// The stretch of a ray a search looks along: t_min < t < t_max, with 1/d for the boxes.
#[derive(Clone, Copy)]
struct Reach<'r> {
    ray: &'r Ray,
    inv_dir: DVec3,
    t_min: f64,
    t_max: f64,
}
