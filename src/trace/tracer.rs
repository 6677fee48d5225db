//! The tracer: one scene, the options of a trace, and the context its rays share (the
//! recorder that watches them, the random numbers of glossy and frosted rays, the counters of
//! work). How it computes an intensity is the Whitted recursion in `whitted.rs`; here are the
//! ways in (`radiance`, `inspect`) and the bookkeeping that records what it did.

use glam::DVec3;

use super::recorder::{NoRecorder, RayStart, Recorder, TreeRecorder};
use super::task::Task;
use super::tree::{Coefficients, HitInfo, Inspection, Local, PatternLookup, RayKind, RayNode};
use super::whitted::shadow_reach;
use crate::geometry::uv::Edges;
use crate::geometry::{Ray, Shape};
use crate::sampling::Rng;
use crate::scene::{Hit, Interaction, Scene, Search};
use crate::shading::{Light, LightSample};
use crate::stats::Stats;

/// Options that change how one trace runs: where the recursion stops, and whether shadow rays
/// are cast. A tracer starts with the scene's own (`TraceOptions::of`).
#[derive(Clone, Copy, Debug)]
pub struct TraceOptions {
    /// Rays per path, primary included: 1 traces primary rays only.
    pub max_depth: u32,
    /// Cast shadow rays (off only to show what the shadow term changes).
    pub shadows: bool,
    /// Seed 000's stop rule: a ray that hits a light source stops there and brings back the
    /// light's intensity. Area and sphere lights are then seen; off, rays pass through them.
    pub stop_at_lights: bool,
    /// Seed 002's stop rule: a ray that hits a diffuse surface (kd > 0) sends no reflection
    /// or refraction ray: it contributes its local illumination only.
    pub stop_at_diffuse: bool,
}

impl TraceOptions {
    /// The scene's own: its maximum depth and the stop rules it names, shadows cast.
    pub fn of(scene: &Scene) -> TraceOptions {
        TraceOptions {
            max_depth: scene.max_depth,
            shadows: true,
            stop_at_lights: scene.stop_rules.light,
            stop_at_diffuse: scene.stop_rules.diffuse,
        }
    }
}

/// The tracer of one scene, with the context its rays share: the recorder that watches them,
/// the random numbers of glossy and frosted rays, and the counters of rays and skipped work.
pub struct Tracer<'s, R: Recorder = NoRecorder> {
    /// The scene traced.
    pub scene: &'s Scene,
    /// Where rays find their hits: the scene's own search, or the fast wing's.
    pub search: &'s dyn Search,
    /// Depth limit, shadows and stop rules for this tracer's rays.
    pub options: TraceOptions,
    /// The recorder told about every ray (`NoRecorder` when rendering, `TreeRecorder` for the ray
    /// tree).
    pub rec: R,
    /// Random numbers for glossy and frosted rays and area light samples.
    pub rng: Rng,
    /// Counters of rays traced and work done or skipped.
    pub stats: Stats,
    /// Per light, the BVH item that last blocked a shadow ray toward it, where a search noted
    /// one. Whether a shadow ray is blocked does not depend on which blocker is found, and
    /// neighbouring rays are mostly blocked by the same object, so a search may try that one
    /// first. The core's search keeps no notes; the fast wing's packets do.
    pub last_blockers: Vec<Option<u32>>,
}

impl<'s> Tracer<'s> {
    /// A tracer of the scene with its own search and settings, recording nothing.
    pub fn new(scene: &'s Scene) -> Tracer<'s> {
        Tracer {
            scene,
            search: scene,
            options: TraceOptions::of(scene),
            rec: NoRecorder,
            rng: Rng::for_pixel(0, 0, 0),
            stats: Stats::default(),
            last_blockers: vec![None; scene.lights.len()],
        }
    }
}

impl<'s, R: Recorder> Tracer<'s, R> {
    /// The same tracer with paths of at most `max_depth` rays (1: primary rays only).
    pub fn with_depth(mut self, max_depth: u32) -> Self {
        self.options.max_depth = max_depth;
        self
    }

    /// The same tracer with other options.
    pub fn with_options(mut self, options: TraceOptions) -> Self {
        self.options = options;
        self
    }

    /// Glossy and frosted rays draw from `rng` (the renderer gives each pixel its own).
    pub fn with_rng(mut self, rng: Rng) -> Self {
        self.rng = rng;
        self
    }

    /// The same tracer, finding its hits through `search`.
    pub fn with_search(mut self, search: &'s dyn Search) -> Self {
        self.search = search;
        self
    }

    /// The intensity seen along a primary ray.
    pub fn radiance(&mut self, ray: &Ray) -> DVec3 {
        self.trace(&Task::primary(ray)).0
    }

    /// The same computation as `radiance`, recording its ray tree.
    pub fn inspect(&mut self, ray: &Ray) -> RayNode {
        let mut recording = Tracer {
            scene: self.scene,
            search: self.search,
            options: self.options,
            rec: TreeRecorder::new(),
            rng: self.rng.clone(),
            stats: Stats::default(),
            last_blockers: self.last_blockers.clone(),
        };
        recording.radiance(ray);
        self.rng = recording.rng;
        self.stats.add(&recording.stats);
        recording.rec.into_tree()
    }

    /// The tree of the ray through the centre of pixel (x, y), with the random numbers the
    /// renderer gives that pixel (seed 0): for one sample per pixel its colour is the pixel's.
    pub fn inspect_pixel(&mut self, x: u32, y: u32) -> Inspection {
        self.rng = Rng::for_pixel(0, x, y);
        let tree = self.inspect(&self.scene.camera.pixel_ray(x, y));
        Inspection {
            pixel: Some([x, y]),
            color: tree.color,
            tree,
        }
    }

    // --- Bookkeeping ---

    /// Counts a ray among the rays of its kind.
    pub(crate) fn count(&mut self, kind: RayKind) {
        match kind {
            RayKind::Primary => self.stats.primary_rays += 1,
            RayKind::Reflection => self.stats.reflection_rays += 1,
            RayKind::Refraction => self.stats.refraction_rays += 1,
            RayKind::Shadow => self.stats.shadow_rays += 1,
        }
    }

    /// Records a shadow node: the ray toward the light, s, and the first blocker.
    pub(super) fn record_shadow(
        &mut self,
        si: &Interaction,
        depth: u32,
        toward: &LightSample,
        light: &Light,
        s: f64,
        first_blocker: Option<(Ray, Hit)>,
    ) {
        let (l, distance) = (toward.l, toward.distance);
        let (origin, moved) = self.scene.offset(si, l);
        self.rec.begin(RayStart {
            kind: RayKind::Shadow,
            depth: depth + 1,
            origin,
            direction: l,
            weight: 1.0,
            coefficient: 1.0,
        });
        self.rec.shadow(
            &light.name,
            shadow_reach(distance, moved),
            s,
            light.shadow_rays(),
        );
        if let Some((ray, h)) = first_blocker {
            let bsi = self.scene.interaction(&ray, &h);
            self.rec.hit(self.hit_info(&ray, h.t, &bsi));
        }
        self.rec.end(DVec3::splat(s), None);
    }

    pub(super) fn hit_info(&self, ray: &Ray, t: f64, si: &Interaction) -> HitInfo {
        let scene = self.scene;
        let leaf = &scene.leaves[si.leaf as usize];
        let local = || {
            leaf.transform
                .as_ref()
                .map_or(si.point, |tf| tf.to_local.transform_point3(si.point))
        };
        let barycentric = match &leaf.shape {
            Shape::Triangle(tri) => Some(tri.barycentric(local())),
            Shape::Mesh(mesh) => Some(mesh.triangle(si.face).barycentric(local())),
            _ => None,
        };
        HitInfo {
            uv: self.lookups(si).iter().find_map(|l| l.uv),
            object: scene.objects[si.object as usize].name.clone(),
            leaf: leaf.name.clone(),
            csg_path: leaf.path.clone(),
            material: scene.material(si.material).name.clone(),
            t,
            point: ray.at(t),
            normal: si.normal,
            inside: si.inside,
            barycentric,
        }
    }

    /// The patterns of the hit's material, each looked up at the hit: what the tree shows of
    /// them.
    pub(super) fn lookups(&self, si: &Interaction) -> Vec<PatternLookup> {
        let scene = self.scene;
        let Some(patterns) = &scene.material(si.material).patterns else {
            return vec![];
        };
        let leaf = &scene.leaves[si.leaf as usize];
        let at = scene.pattern_point(leaf, si.point, si.face, true);
        patterns
            .named()
            .map(|(varies, p)| {
                let (point, mapped) = p.lookup(&at);
                PatternLookup {
                    varies: varies.into(),
                    pattern: p.describe(),
                    point,
                    uv: mapped.map(|(uv, _)| uv),
                    edges: mapped.map_or(Edges::NONE, |(_, edges)| edges),
                    value: p.value(&at),
                }
            })
            .collect()
    }

    /// The surface's colour and coefficients at a hit, for its node's local terms, when its
    /// material has patterns.
    pub(super) fn surface(&self, si: &Interaction) -> Local {
        let lookups = self.lookups(si);
        if lookups.is_empty() {
            return Local::default();
        }
        let p = si.paint;
        let coefficients = lookups
            .iter()
            .any(|l| l.varies != "O")
            .then_some(Coefficients {
                kd: p.kd,
                ks: p.ks,
                kr: p.kr,
                kt: p.kt,
            });
        Local {
            color: Some(p.color),
            coefficients,
            patterns: lookups,
            ..Local::default()
        }
    }
}
