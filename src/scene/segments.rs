//! Segment lists of whole objects: a plain shape's span, or a CSG tree's list combined from
//! its leaves' (seed 000). The nearest-hit search reads its first crossing; `raytree csg` and
//! the explorer show the list at every node; a point is inside an object when the list of a
//! ray from it says so. A group's list is its members' lists together, in order.

use glam::DVec3;

use super::objects::{Geometry, Object};
use super::Scene;
use crate::geometry::csg::{CsgNode, CsgRay, CsgTrace, CsgWork, LeafSegments};
use crate::geometry::{Ray, SegmentList, Shape};
use crate::stats::Stats;

impl LeafSegments for Scene {
    fn leaf_segments(&self, leaf: u32, ray: &Ray) -> SegmentList {
        self.leaves[leaf as usize].segments(leaf, ray)
    }
    fn leaf_name(&self, leaf: u32) -> String {
        self.leaves[leaf as usize].name.clone()
    }
}

impl Scene {
    /// Is the probe ray's origin inside the object? (Inside a segment of its list; for a mesh,
    /// an odd number of crossings ahead; for a group, inside one of its members.)
    pub fn contains(&self, object: u32, probe: &Ray, stats: &mut Stats) -> bool {
        self.inside(&self.objects[object as usize], probe, stats)
    }

    fn inside(&self, object: &Object, probe: &Ray, stats: &mut Stats) -> bool {
        match &object.geometry {
            Geometry::Group(g) => g.members.iter().any(|m| self.inside(m, probe, stats)),
            Geometry::Leaf(l) if matches!(self.leaves[*l as usize].shape, Shape::Mesh(_)) => {
                let list = self.leaves[*l as usize].segments(*l, probe);
                list.iter().filter(|s| s.t_in > 0.0).count() % 2 == 1
            }
            geometry => self
                .geometry_segments(geometry, probe, f64::NEG_INFINITY, f64::INFINITY, stats)
                .iter()
                .any(|s| s.t_in <= 0.0 && 0.0 <= s.t_out),
        }
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
        let geometry = &self.objects[object as usize].geometry;
        self.geometry_segments(geometry, ray, t_min, t_max, stats)
    }

    fn geometry_segments(
        &self,
        geometry: &Geometry,
        ray: &Ray,
        t_min: f64,
        t_max: f64,
        stats: &mut Stats,
    ) -> SegmentList {
        match geometry {
            Geometry::Leaf(leaf) => self.leaves[*leaf as usize].segments(*leaf, ray),
            Geometry::Csg(root) => {
                let r = self.csg_ray(ray, ray.dir.recip(), t_min, t_max);
                self.csg_segments(root, &r, stats)
            }
            Geometry::Group(g) => merged(
                g.members
                    .iter()
                    .map(|m| self.geometry_segments(&m.geometry, ray, t_min, t_max, stats)),
            ),
        }
    }

    /// A CSG tree's segment list.
    pub fn csg_segments(&self, root: &CsgNode, r: &CsgRay, stats: &mut Stats) -> SegmentList {
        let mut work = CsgWork::default();
        let list = root.segments(self, r, &mut work);
        stats.csg_pruned += work.pruned;
        list
    }

    /// The ray as CSG evaluation sees it, with the scene's boxes and pruning switched on or off.
    #[inline]
    pub fn csg_ray<'a>(&self, ray: &'a Ray, inv_dir: DVec3, t_min: f64, t_max: f64) -> CsgRay<'a> {
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
        self.trace(&self.objects[object as usize], ray, use_bounds)
    }

    fn trace(&self, object: &Object, ray: &Ray, use_bounds: bool) -> (SegmentList, CsgTrace) {
        match &object.geometry {
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
            Geometry::Group(g) => {
                // A group is no operation: its node (neither an operation nor a leaf) lists its
                // members' segments together.
                let (lists, children): (Vec<_>, Vec<_>) = g
                    .members
                    .iter()
                    .map(|m| self.trace(m, ray, use_bounds))
                    .unzip();
                let list = merged(lists.into_iter());
                let trace = CsgTrace {
                    node: object.name.clone(),
                    op: None,
                    leaf: None,
                    segments: list.clone(),
                    pruned: None,
                    children,
                };
                (list, trace)
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
}

/// Segment lists put together in order of t_in (a group's members may overlap: this is a
/// listing, not a union).
fn merged(lists: impl Iterator<Item = SegmentList>) -> SegmentList {
    let mut all: Vec<_> = lists.flat_map(|l| l.into_iter()).collect();
    all.sort_by(|a, b| a.t_in.total_cmp(&b.t_in));
    all.into_iter().collect()
}
