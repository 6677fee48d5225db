//! The Whitted tracer: the lecture's recursion, written once and watched by a recorder.
//!
//! I = ka·Ia·O + Σ_ℓ s·fatt·Iℓ·(kd·O·(n·l) + ks·(h·n)^m) + kr·I_r + kt·I_t
//!
//! A ray of depth k spawns shadow rays toward every light, and, if the path may still grow,
//! a reflection ray (kr > 0) and a refraction ray (kt > 0) of depth k + 1. Intensities are
//! collected from the leaves up as the recursion returns.

use std::borrow::Cow;

use arrayvec::ArrayVec;
use glam::DVec3;
use wide::f64x4;

use super::recorder::{NoRecorder, RayStart, Recorder, TreeRecorder};
use super::sampling::Rng;
use super::tree::{HitInfo, Indices, Inspection, LightTerm, Local, RayKind, RayNode, Termination};
use super::Stats;
use crate::accel::bvh::PACKET;
use crate::geometry::{Ray, Shape};
use crate::scene::{Hit, Interaction, Scene};
use crate::shading::local::{ambient, light_terms, LightTerms};
use crate::shading::optics::{reflect, refract, schlick};
use crate::shading::{lobe, Fresnel, Light, LightSample, Lobe, Material};

/// The refractive media a ray is inside, innermost last (nested glass keeps n1/n2 right).
#[derive(Clone, Copy, Debug)]
pub struct Media {
    entries: [(u32, f64); 8],
    len: usize,
}

impl Default for Media {
    fn default() -> Media {
        Media {
            entries: [(u32::MAX, 1.0); 8],
            len: 0,
        }
    }
}

impl Media {
    /// The index of refraction around the ray (1 for vacuum/air).
    pub fn current(&self) -> f64 {
        if self.len == 0 {
            1.0
        } else {
            self.entries[self.len - 1].1
        }
    }

    fn entering(&self, object: u32, ior: f64) -> Media {
        let mut m = *self;
        if m.len < m.entries.len() {
            m.entries[m.len] = (object, ior);
            m.len += 1;
        }
        m
    }

    fn contains(&self, object: u32) -> bool {
        self.entries[..self.len].iter().any(|e| e.0 == object)
    }
}

/// How far a shadow ray that starts `moved` off the surface looks for blockers: up to the light
/// (the normal is a unit vector, so the offset moved the origin by exactly `moved`).
pub fn shadow_reach(distance: f64, moved: f64) -> f64 {
    if distance.is_finite() {
        (distance - moved).max(0.0)
    } else {
        distance
    }
}

/// Options that change how one trace runs, beyond the scene's own settings.
#[derive(Clone, Copy, Debug)]
pub struct TraceOptions {
    /// Rays per path, primary included: 1 traces primary rays only.
    pub max_depth: u32,
    /// Cast shadow rays (off only to show what the shadow term changes).
    pub shadows: bool,
}

pub struct Tracer<'s> {
    pub scene: &'s Scene,
    pub options: TraceOptions,
}

/// What tracing one ray gives: its intensity and the distance to what it hit (∞ for none).
///
/// The intensity crosses the recursion's calls as one 32-byte vector, not as a `DVec3`: the
/// compiler writes a returned `DVec3` as 16 + 8 bytes and the caller read it back as 8 + 16, a
/// load that spans two stores and so waits for both to reach the cache (store forwarding
/// fails). That wait was 4 % of the Whitted peer scene's time.
#[derive(Clone, Copy)]
struct Traced {
    color: f64x4,
    t: f64,
}

impl Traced {
    fn new(color: DVec3, t: f64) -> Traced {
        Traced {
            color: f64x4::new([color.x, color.y, color.z, 0.0]),
            t,
        }
    }

    fn color(&self) -> DVec3 {
        let [x, y, z, _] = self.color.to_array();
        DVec3::new(x, y, z)
    }
}

/// The secondary rays one surface sends on, before the depth limit and the adaptive
/// threshold have their say.
struct Children {
    /// kr and kt after the Fresnel term.
    kr: f64,
    kt: f64,
    /// The mirror ray, when kr > 0.
    reflection: Option<Task>,
    refraction: Transmission,
}

/// The rays of a packet, each with its place in the tree: a pixel's primary rays, or the
/// tasks of a packet of secondary rays.
trait Lanes {
    fn ray(&self, i: usize) -> &Ray;
    fn depth(&self, i: usize) -> u32;
    fn count(&self, i: usize, stats: &mut Stats);
    /// The whole task (built on demand for a primary ray: it is needed only where secondary
    /// rays leave, and building all sixteen up front cost 5–9 % of a render).
    fn task(&self, i: usize) -> Cow<'_, Task>;
}

impl Lanes for [Ray] {
    fn ray(&self, i: usize) -> &Ray {
        &self[i]
    }

    fn depth(&self, _: usize) -> u32 {
        0
    }

    fn count(&self, _: usize, stats: &mut Stats) {
        stats.primary_rays += 1;
    }

    fn task(&self, i: usize) -> Cow<'_, Task> {
        Cow::Owned(Task::primary(&self[i]))
    }
}

impl Lanes for [Task] {
    fn ray(&self, i: usize) -> &Ray {
        &self[i].ray
    }

    fn depth(&self, i: usize) -> u32 {
        self[i].depth
    }

    fn count(&self, i: usize, stats: &mut Stats) {
        self[i].count(stats);
    }

    fn task(&self, i: usize) -> Cow<'_, Task> {
        Cow::Borrowed(&self[i])
    }
}

/// The reflection (or refraction) rays of a packet's surfaces, gathered to be traced as a
/// packet of their own, and the colour each surface receives through them.
struct Packet {
    tasks: ArrayVec<Task, PACKET>,
    /// The surface (its lane in the parent packet) each task leaves from.
    lanes: [usize; PACKET],
    /// Per parent lane: the intensity arriving through its child (zero for a child the depth
    /// limit or the adaptive threshold stopped); None for a surface without such a child.
    colors: [Option<DVec3>; PACKET],
}

impl Packet {
    fn new() -> Packet {
        Packet {
            tasks: ArrayVec::new(),
            lanes: [0; PACKET],
            colors: [None; PACKET],
        }
    }

    /// The child of the surface in lane `lane`: to be traced, or stopped (it brings nothing).
    fn add(&mut self, lane: usize, task: &Task, traced: bool) {
        if traced {
            self.lanes[self.tasks.len()] = lane;
            self.tasks.push(*task);
        }
        self.colors[lane] = Some(DVec3::ZERO);
    }

    fn settle(&mut self, lane: usize, color: DVec3) {
        self.colors[lane] = Some(color);
    }
}

/// Where a surface's transmitted light comes from.
enum Transmission {
    /// kt = 0: nothing.
    None,
    /// The refracted ray (Snell's law).
    Ray(Task),
    /// Beyond the limiting angle: the mirror ray, staying inside, between media n1 → n2.
    TotalInternalReflection { mirror: DVec3, indices: (f64, f64) },
}

/// One ray to trace and its place in the tree.
#[derive(Clone, Copy)]
struct Task {
    ray: Ray,
    kind: RayKind,
    depth: u32,
    weight: f64,
    coefficient: f64,
    media: Media,
    /// n1 → n2 for a refraction ray.
    indices: Option<Indices>,
    /// A glossy or frosted surface above this ray already split the path into many rays:
    /// deeper ones send a single sampled ray, so the work grows linearly, not as nᵈ.
    split: bool,
}

impl Task {
    fn primary(ray: &Ray) -> Task {
        Task {
            ray: *ray,
            kind: RayKind::Primary,
            depth: 0,
            weight: 1.0,
            coefficient: 1.0,
            media: Media::default(),
            indices: None,
            split: false,
        }
    }

    /// Counts this ray among the rays of its kind.
    #[inline(always)]
    fn count(&self, stats: &mut Stats) {
        match self.kind {
            RayKind::Primary => stats.primary_rays += 1,
            RayKind::Reflection => stats.reflection_rays += 1,
            RayKind::Refraction => stats.refraction_rays += 1,
            RayKind::Shadow => stats.shadow_rays += 1,
        }
    }

    /// Announces this ray to the recorder.
    fn begin<R: Recorder>(&self, rec: &mut R) {
        rec.begin(RayStart {
            kind: self.kind,
            depth: self.depth,
            origin: self.ray.origin,
            direction: self.ray.dir,
            weight: self.weight,
            coefficient: self.coefficient,
        });
        if let Some(i) = self.indices {
            rec.indices(i);
        }
    }
}

impl<'s> Tracer<'s> {
    pub fn new(scene: &'s Scene) -> Tracer<'s> {
        Tracer {
            scene,
            options: TraceOptions {
                max_depth: scene.max_depth,
                shadows: true,
            },
        }
    }

    pub fn with_depth(scene: &'s Scene, max_depth: u32) -> Tracer<'s> {
        Tracer {
            scene,
            options: TraceOptions {
                max_depth,
                shadows: true,
            },
        }
    }

    /// The intensity seen along a primary ray. Glossy and frosted surfaces draw their rays
    /// from a fixed generator; the renderer uses `radiance_with` and the pixel's own.
    pub fn radiance(&self, ray: &Ray, stats: &mut Stats) -> DVec3 {
        self.primary(ray, &mut NoRecorder, &mut Rng::for_pixel(0, 0, 0), stats)
    }

    /// The renderer's entry point: random numbers from the pixel's generator.
    pub fn radiance_with(&self, ray: &Ray, rng: &mut Rng, stats: &mut Stats) -> DVec3 {
        self.primary(ray, &mut NoRecorder, rng, stats)
    }

    /// The same computation as `radiance`, recording its ray tree.
    pub fn inspect(&self, ray: &Ray, stats: &mut Stats) -> RayNode {
        self.inspect_with(ray, &mut Rng::for_pixel(0, 0, 0), stats)
    }

    pub fn inspect_with(&self, ray: &Ray, rng: &mut Rng, stats: &mut Stats) -> RayNode {
        let mut rec = TreeRecorder::new();
        self.primary(ray, &mut rec, rng, stats);
        rec.into_tree()
    }

    /// The tree of the ray through the centre of pixel (x, y), with the random numbers the
    /// renderer gives that pixel (seed 0): for one sample per pixel its colour is the pixel's.
    pub fn inspect_pixel(&self, x: u32, y: u32) -> Inspection {
        let mut stats = Stats::default();
        let ray = self.scene.camera.pixel_ray(x, y);
        let tree = self.inspect_with(&ray, &mut Rng::for_pixel(0, x, y), &mut stats);
        Inspection {
            pixel: Some([x, y]),
            color: tree.color,
            tree,
        }
    }

    pub fn primary<R: Recorder>(
        &self,
        ray: &Ray,
        rec: &mut R,
        rng: &mut Rng,
        stats: &mut Stats,
    ) -> DVec3 {
        self.trace(&Task::primary(ray), rec, rng, stats).color()
    }

    /// Traces one ray; returns its intensity and the distance to what it hit (∞ for none).
    #[inline(always)]
    fn trace<R: Recorder>(
        &self,
        task: &Task,
        rec: &mut R,
        rng: &mut Rng,
        stats: &mut Stats,
    ) -> Traced {
        let hit = self.scene.intersect(&task.ray, 0.0, f64::INFINITY, stats);
        self.trace_from(task, hit, rec, rng, stats)
    }

    /// `trace` from the ray's nearest hit.
    fn trace_from<R: Recorder>(
        &self,
        task: &Task,
        hit: Option<Hit>,
        rec: &mut R,
        rng: &mut Rng,
        stats: &mut Stats,
    ) -> Traced {
        let scene = self.scene;
        task.count(stats);
        task.begin(rec);
        let Some(hit) = hit else {
            rec.end(scene.background, Some(Termination::Background));
            return Traced::new(scene.background, f64::INFINITY);
        };
        let si = scene.interaction(&task.ray, &hit);
        let m = scene.material(si.material);
        if R::ACTIVE {
            rec.hit(self.hit_info(&task.ray, hit.t, &si));
        }

        // Local illumination: the ambient term and every light's diffuse and specular terms.
        let v = -task.ray.dir;
        let mut color = ambient(m, scene.ambient);
        let mut terms = Vec::new();
        for (k, light) in scene.lights.iter().enumerate() {
            let (sample, lit, skipped) = self.light_share(m, &si, v, k, R::ACTIVE, stats);
            let s = match skipped {
                Some(_) => 0.0,
                None => self.shadow_factor(
                    &si,
                    task.depth,
                    sample.l,
                    sample.distance,
                    light,
                    rec,
                    stats,
                ),
            };
            color += s * (lit.diffuse + lit.specular);
            if R::ACTIVE {
                terms.push(LightTerm {
                    light: light.name.clone(),
                    shadow: s,
                    l: sample.l,
                    n_dot_l: lit.n_dot_l,
                    attenuation: sample.attenuation,
                    highlight_cos: lit.highlight_cos,
                    diffuse: s * lit.diffuse,
                    specular: s * lit.specular,
                    skipped: skipped.map(str::to_string),
                });
            }
        }
        if R::ACTIVE {
            rec.local(Local {
                ambient: ambient(m, scene.ambient),
                lights: terms,
            });
        }
        self.finish(task, &si, color, hit.t, rec, rng, stats)
    }

    /// The primary rays of one pixel (a regular grid's samples, up to 16) from their nearest
    /// hits: `out[i]` is exactly what `radiance_with` gives ray i, and the stats and the
    /// random numbers drawn are those of tracing the rays one after another.
    pub fn radiance_packet(
        &self,
        rays: &[Ray],
        hits: &[Option<Hit>],
        rng: &mut Rng,
        stats: &mut Stats,
        out: &mut [DVec3],
    ) {
        assert!(rays.len() <= PACKET && hits.len() == rays.len() && out.len() == rays.len());
        self.shade_packet(rays, hits, rng, stats, out);
    }

    /// A packet of rays from their nearest hits: `out[i]` is exactly what `trace_from` gives
    /// task i, and the stats are those of tracing the tasks one after another.
    ///
    /// The same steps as `trace_from`, taken in another order: every ray's local terms of a
    /// light first, then all their shadow rays toward it together (`Scene::occluded_packet`:
    /// the BVH searched as a packet, or without one each plain sphere and plane tested against
    /// four rays at once), and then the secondary rays: in waves (`secondary_packet`) where the objects
    /// are tested in lanes and nothing draws random numbers, else one ray after another.
    fn shade_packet<L: Lanes + ?Sized>(
        &self,
        tasks: &L,
        hits: &[Option<Hit>],
        rng: &mut Rng,
        stats: &mut Stats,
        out: &mut [DVec3],
    ) {
        let scene = self.scene;
        let n = hits.len();
        let mut shaded: [Option<Interaction>; PACKET] = [None; PACKET];
        for i in 0..n {
            tasks.count(i, stats);
            match &hits[i] {
                None => out[i] = scene.background,
                Some(hit) => {
                    let si = scene.interaction(tasks.ray(i), hit);
                    out[i] = ambient(scene.material(si.material), scene.ambient);
                    shaded[i] = Some(si);
                }
            }
        }
        for (k, light) in scene.lights.iter().enumerate() {
            let single = light.shadow_rays() == 1 && self.options.shadows;
            let mut terms = [DVec3::ZERO; PACKET];
            let mut shadow_rays = [Ray::UNUSED; PACKET];
            let mut reach = [0.0; PACKET];
            let mut lanes = [0usize; PACKET];
            let mut cast = 0;
            for i in 0..n {
                let Some(si) = &shaded[i] else { continue };
                let m = scene.material(si.material);
                let (sample, lit, skipped) =
                    self.light_share(m, si, -tasks.ray(i).dir, k, false, stats);
                terms[i] = lit.diffuse + lit.specular;
                if skipped.is_some() {
                    out[i] += 0.0 * terms[i];
                } else if single {
                    stats.shadow_rays += 1;
                    (shadow_rays[cast], reach[cast]) =
                        self.shadow_ray(si, sample.l, sample.distance);
                    lanes[cast] = i;
                    cast += 1;
                } else {
                    let s = self.shadow_factor(
                        si,
                        tasks.depth(i),
                        sample.l,
                        sample.distance,
                        light,
                        &mut NoRecorder,
                        stats,
                    );
                    out[i] += s * terms[i];
                }
            }
            let blocked = scene.occluded_packet(&shadow_rays[..cast], &reach[..cast], stats);
            for (k, &i) in lanes[..cast].iter().enumerate() {
                let s = if blocked & (1 << k) == 0 { 1.0 } else { 0.0 };
                out[i] += s * terms[i];
            }
        }
        if scene.features.sampled || !scene.tests_in_lanes() {
            // Glossy and frosted surfaces draw random numbers: the rays go on one by one, in
            // order, so each draws the numbers it draws when traced alone. And gathering the
            // secondary rays into packets pays where packets are tested four rays at a time
            // (no BVH: Whitted peer scene 1.17 → 1.05 s; CSG peer scene, whose CSG objects
            // are still tested ray by ray, 2.02 vs 2.01 s).
            for i in 0..n {
                if let (Some(si), Some(hit)) = (&shaded[i], &hits[i]) {
                    out[i] = self
                        .finish(
                            &tasks.task(i),
                            si,
                            out[i],
                            hit.t,
                            &mut NoRecorder,
                            rng,
                            stats,
                        )
                        .color();
                }
            }
        } else {
            self.secondary_packet(tasks, &shaded[..n], rng, stats, out);
        }
    }

    /// `secondary` for every surface of a packet (where no material draws random numbers, so
    /// the order rays are traced in changes nothing): all their reflection rays are traced
    /// together as one packet, then all their refraction rays (or, past the limiting angle,
    /// the mirror rays that stay inside) as another, and each surface sums kr·I_r + kt·I_t as
    /// `secondary` does.
    fn secondary_packet<L: Lanes + ?Sized>(
        &self,
        tasks: &L,
        shaded: &[Option<Interaction>],
        rng: &mut Rng,
        stats: &mut Stats,
        out: &mut [DVec3],
    ) {
        let scene = self.scene;
        let mut splits: [Option<(f64, f64)>; PACKET] = [None; PACKET];
        let mut reflected = Packet::new();
        let mut transmitted = Packet::new();
        for (i, si) in shaded.iter().enumerate() {
            let Some(si) = si else { continue };
            let m = scene.material(si.material);
            if !(m.kr > 0.0 || m.kt > 0.0) {
                continue;
            }
            let task = tasks.task(i);
            let c = self.children(&task, si, stats);
            splits[i] = Some((c.kr, c.kt));
            if let Some(child) = &c.reflection {
                reflected.add(i, child, self.stopped(child, stats).is_none());
            }
            match &c.refraction {
                Transmission::None => {}
                Transmission::Ray(child) => {
                    transmitted.add(i, child, self.stopped(child, stats).is_none())
                }
                // The mirror ray joins the refraction rays' packet: traced one by one, the
                // rays bouncing inside a glass were a large share of the CSG scene's rays.
                Transmission::TotalInternalReflection { mirror, .. } => {
                    let child = self.mirror_inside(&task, si, *mirror, c.kt);
                    let traced = self.stopped(&child, stats).is_none();
                    if traced {
                        stats.total_internal_reflections += 1;
                    }
                    transmitted.add(i, &child, traced);
                }
            }
        }
        self.trace_children(&mut reflected, rng, stats);
        self.trace_children(&mut transmitted, rng, stats);
        for (i, split) in splits.iter().enumerate() {
            let Some((kr, kt)) = *split else { continue };
            let mut sum = DVec3::ZERO;
            if let Some(color) = reflected.colors[i] {
                sum += kr * color;
            }
            if let Some(color) = transmitted.colors[i] {
                sum += kt * color;
            }
            out[i] += sum;
        }
    }

    /// Traces the rays of a packet of children that are not stopped, as one packet, and
    /// settles their parents' colours.
    fn trace_children(&self, children: &mut Packet, rng: &mut Rng, stats: &mut Stats) {
        let n = children.tasks.len();
        if n == 0 {
            return;
        }
        let rays: ArrayVec<Ray, PACKET> = children.tasks.iter().map(|t| t.ray).collect();
        let mut hits = [None; PACKET];
        self.scene.intersect_packet(&rays, &mut hits[..n], stats);
        let mut colors = [DVec3::ZERO; PACKET];
        self.shade_packet(
            &children.tasks[..],
            &hits[..n],
            rng,
            stats,
            &mut colors[..n],
        );
        for k in 0..n {
            let distance = hits[k].map_or(f64::INFINITY, |h| h.t);
            children.settle(children.lanes[k], self.attenuated(colors[k], distance));
        }
    }

    /// Light k's diffuse and specular terms at a shaded point, before the shadow factor,
    /// and why no shadow ray is needed, if none is (then the shadow factor is 0).
    /// `shows`: the terms go into a recorded tree.
    #[inline(always)]
    fn light_share(
        &self,
        m: &Material,
        si: &Interaction,
        v: DVec3,
        k: usize,
        shows: bool,
        stats: &mut Stats,
    ) -> (LightSample, LightTerms, Option<&'static str>) {
        let light = &self.scene.lights[k];
        let sample = light.sample(si.point);
        let lit = light_terms(
            m,
            si.normal,
            v,
            sample.l,
            sample.attenuation * light.intensity,
            shows,
        );
        let skipped = if lit.n_dot_l <= 0.0 {
            stats.shadow_skipped_backfacing += 1;
            Some("light behind the surface (n·l ≤ 0)")
        } else if light.is_dark() {
            stats.shadow_skipped_dark += 1;
            Some("light has zero intensity")
        } else if si.inside && self.options.shadows && self.scene.hides_light_inside(si.object, k) {
            // The ray travels inside a convex solid (a glass lens, say): the way to a light
            // outside leaves the solid, whose surface is in the way.
            stats.shadow_skipped_inside += 1;
            Some("inside a convex solid the light is outside of: the solid blocks it")
        } else {
            None
        };
        (sample, lit, skipped)
    }

    /// The local intensity `color` plus the secondary rays' kr·I_r + kt·I_t: the node's total.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn finish<R: Recorder>(
        &self,
        task: &Task,
        si: &Interaction,
        mut color: DVec3,
        t: f64,
        rec: &mut R,
        rng: &mut Rng,
        stats: &mut Stats,
    ) -> Traced {
        let m = self.scene.material(si.material);
        // Secondary rays: the mirror direction and Snell's law, weighted by kr and kt.
        if m.kr > 0.0 || m.kt > 0.0 {
            color += self.secondary(task, si, rec, rng, stats);
        }
        rec.end(color, None);
        Traced::new(color, t)
    }

    /// kr·I_r + kt·I_t at a surface.
    fn secondary<R: Recorder>(
        &self,
        task: &Task,
        si: &Interaction,
        rec: &mut R,
        rng: &mut Rng,
        stats: &mut Stats,
    ) -> DVec3 {
        let m = self.scene.material(si.material);
        let c = self.children(task, si, stats);
        let mut sum = DVec3::ZERO;
        if let Some(child) = &c.reflection {
            sum += c.kr
                * match m.glossy {
                    None => self.child(child, rec, rng, stats),
                    Some(lobe) => self.bundle(child, task, si, lobe, rec, rng, stats),
                };
        }
        match &c.refraction {
            Transmission::None => {}
            Transmission::Ray(child) => {
                sum += c.kt
                    * match m.frosted {
                        None => self.child(child, rec, rng, stats),
                        Some(lobe) => self.bundle(child, task, si, lobe, rec, rng, stats),
                    };
            }
            Transmission::TotalInternalReflection { mirror, indices } => {
                sum += c.kt
                    * self.total_internal_reflection(
                        task, si, *mirror, c.kt, *indices, rec, rng, stats,
                    )
            }
        }
        sum
    }

    /// The secondary rays a surface sends on: the mirror direction and Snell's law, with kr
    /// and kt after the Fresnel term.
    #[inline(always)]
    fn children(&self, task: &Task, si: &Interaction, stats: &mut Stats) -> Children {
        let m = self.scene.material(si.material);
        let d = task.ray.dir;
        let n = si.normal;
        // Which media the surface separates: the transparent solids containing a point just
        // before and just beyond it. Asking the geometry (rather than only pushing and popping
        // a stack) keeps n1/n2 right where two glasses touch in a shared face. With a single
        // transparent object nothing can touch or nest, and entering/leaving says it all.
        // A surface that transmits nothing and has no Fresnel term needs neither index.
        let (near, media_beyond) = if m.kt == 0.0 && m.fresnel == Fresnel::None {
            (task.media, task.media)
        } else if self.scene.transparent_objects.len() <= 1 {
            if si.inside {
                let mut outside = Media::default();
                for &(o, ior) in &task.media.entries[..task.media.len] {
                    if o != si.object {
                        outside = outside.entering(o, ior);
                    }
                }
                (task.media.entering(si.object, m.ior), outside)
            } else {
                (task.media, task.media.entering(si.object, m.ior))
            }
        } else {
            let step = 2.0 * self.scene.bias(task.ray.origin, si.point);
            let near = self.media_at(si.point + step * n, d, &task.media, stats);
            let beyond = self.media_at(
                si.point - step * n,
                d,
                &task.media.entering(si.object, m.ior),
                stats,
            );
            (near, beyond)
        };
        let (n1, n2) = if self.scene.leaves[si.leaf as usize].shape.is_solid() {
            (near.current(), media_beyond.current())
        } else {
            // A lone triangle is a sheet with no inside: nothing changes across it.
            (near.current(), near.current())
        };
        let transmitted = if m.kt > 0.0 {
            refract(d, n, n1, n2)
        } else {
            None
        };
        let fresnel = match m.fresnel {
            Fresnel::None => 1.0,
            Fresnel::Schlick => schlick(-d.dot(n), n1, n2),
        };
        let (kr, kt) = match m.fresnel {
            Fresnel::None => (m.kr, m.kt),
            Fresnel::Schlick => (m.kr * fresnel, m.kt * (1.0 - fresnel)),
        };
        let mirror = reflect(d, n);
        let reflection = (kr > 0.0).then(|| Task {
            ray: self.spawn(si, mirror, task),
            kind: RayKind::Reflection,
            depth: task.depth + 1,
            weight: task.weight * kr,
            coefficient: kr,
            media: task.media,
            indices: None,
            split: task.split,
        });
        let refraction = match (kt > 0.0, transmitted) {
            (false, _) => Transmission::None,
            (true, Some(dir)) => Transmission::Ray(Task {
                ray: self.spawn(si, dir, task),
                kind: RayKind::Refraction,
                depth: task.depth + 1,
                weight: task.weight * kt,
                coefficient: kt,
                media: media_beyond,
                indices: Some(Indices { n1, n2 }),
                split: task.split,
            }),
            (true, None) => Transmission::TotalInternalReflection {
                mirror,
                indices: (n1, n2),
            },
        };
        Children {
            kr,
            kt,
            reflection,
            refraction,
        }
    }

    /// Beyond the limiting angle no light is transmitted: the refraction ray becomes a
    /// reflection ray that stays inside. The tree shows a refraction node that ends in
    /// "total_internal_reflection" with that mirror ray as its child.
    #[allow(clippy::too_many_arguments)]
    fn total_internal_reflection<R: Recorder>(
        &self,
        task: &Task,
        si: &Interaction,
        mirror: glam::DVec3,
        kt: f64,
        (n1, n2): (f64, f64),
        rec: &mut R,
        rng: &mut Rng,
        stats: &mut Stats,
    ) -> DVec3 {
        let depth = task.depth + 1;
        if depth >= self.options.max_depth || task.weight * kt < self.scene.adaptive_threshold {
            // The refraction ray would not be traced anyway: record it as cut off.
            let cut = Task {
                ray: Ray {
                    origin: si.point,
                    dir: task.ray.dir,
                },
                kind: RayKind::Refraction,
                depth,
                weight: task.weight * kt,
                coefficient: kt,
                media: task.media,
                indices: Some(Indices { n1, n2 }),
                split: task.split,
            };
            return self.child(&cut, rec, rng, stats);
        }
        stats.total_internal_reflections += 1;
        rec.begin(RayStart {
            kind: RayKind::Refraction,
            depth: task.depth + 1,
            origin: si.point,
            direction: task.ray.dir,
            weight: task.weight * kt,
            coefficient: kt,
        });
        rec.indices(Indices { n1, n2 });
        let child = self.mirror_inside(task, si, mirror, kt);
        let color = self.child(&child, rec, rng, stats);
        rec.end(color, Some(Termination::TotalInternalReflection));
        color
    }

    /// The mirror ray of a total internal reflection, which carries the transmitted share kt
    /// and stays inside. (The cut-off refraction ray `total_internal_reflection` records has
    /// its depth and weight: the depth limit and the adaptive threshold stop both alike.)
    fn mirror_inside(&self, task: &Task, si: &Interaction, mirror: DVec3, kt: f64) -> Task {
        Task {
            ray: self.spawn(si, mirror, task),
            kind: RayKind::Reflection,
            depth: task.depth + 1,
            weight: task.weight * kt,
            coefficient: 1.0,
            media: task.media,
            indices: None,
            split: task.split,
        }
    }

    /// Traces a secondary ray unless the depth limit or the adaptive threshold stops it.
    fn child<R: Recorder>(
        &self,
        task: &Task,
        rec: &mut R,
        rng: &mut Rng,
        stats: &mut Stats,
    ) -> DVec3 {
        if let Some(why) = self.stopped(task, stats) {
            if R::ACTIVE {
                task.begin(rec);
                rec.end(DVec3::ZERO, Some(why));
            }
            return DVec3::ZERO;
        }
        let traced = self.trace(task, rec, rng, stats);
        self.attenuated(traced.color(), traced.t)
    }

    /// Why a secondary ray is not traced, if it is not: the depth limit or the adaptive
    /// threshold (its weight, the product of kr/kt along its path, is too small to matter).
    #[inline(always)]
    fn stopped(&self, task: &Task, stats: &mut Stats) -> Option<Termination> {
        if task.depth >= self.options.max_depth {
            stats.max_depth_cutoffs += 1;
            Some(Termination::MaxDepth)
        } else if task.weight < self.scene.adaptive_threshold {
            stats.adaptive_cutoffs += 1;
            Some(Termination::Adaptive)
        } else {
            None
        }
    }

    /// A secondary ray's intensity as its parent receives it.
    #[inline(always)]
    fn attenuated(&self, color: DVec3, distance: f64) -> DVec3 {
        match self.scene.secondary_attenuation {
            // Seed 004: a secondary intensity is attenuated by the distance it travelled.
            Some([c0, c1, c2]) if distance.is_finite() => {
                color / (c0 + c1 * distance + c2 * distance * distance)
            }
            _ => color,
        }
    }

    /// Seed 000's Monte Carlo reflection and refraction: the light arriving in a cone about
    /// the principal direction is the average of n rays drawn from the lobe, each traced
    /// recursively. The tree shows the cone as a node whose children are the sampled rays.
    #[allow(clippy::too_many_arguments)]
    fn bundle<R: Recorder>(
        &self,
        principal: &Task,
        parent: &Task,
        si: &Interaction,
        lobe: Lobe,
        rec: &mut R,
        rng: &mut Rng,
        stats: &mut Stats,
    ) -> DVec3 {
        let n = if principal.split { 1 } else { lobe.samples };
        if R::ACTIVE {
            principal.begin(rec);
            rec.samples(n);
        }
        let mut sum = DVec3::ZERO;
        for _ in 0..n {
            let (u1, u2) = (rng.uniform(), rng.uniform());
            let dir = lobe::spread(lobe.shape, principal.ray.dir, si.normal, u1, u2);
            stats.glossy_rays += 1;
            let sample = Task {
                ray: self.spawn(si, dir, parent),
                coefficient: 1.0 / n as f64,
                split: true,
                ..*principal
            };
            sum += self.child(&sample, rec, rng, stats);
        }
        let mean = sum / n as f64;
        if R::ACTIVE {
            rec.end(mean, None);
        }
        mean
    }

    /// s for one light: cast a shadow ray from the surface toward it. A point light is
    /// blocked by a hit with 0 < t < distance, a directional one by any hit with t > 0. An area
    /// light gets one shadow ray per point of its grid; s is the fraction that get through.
    #[allow(clippy::too_many_arguments)]
    fn shadow_factor<R: Recorder>(
        &self,
        si: &Interaction,
        depth: u32,
        l: DVec3,
        distance: f64,
        light: &Light,
        rec: &mut R,
        stats: &mut Stats,
    ) -> f64 {
        // One shadow ray toward a point or directional light; one per grid point of an area
        // light (computed on the fly: the render path allocates nothing per ray).
        let count = light.shadow_rays();
        let mut visible = 0u32;
        let mut first_blocker = None;
        for k in 0..count {
            let (dir, dist) = match light.shadow_point(k, si.point) {
                Some(q) => {
                    let to = q - si.point;
                    (to.normalize(), to.length())
                }
                None => (l, distance),
            };
            stats.shadow_rays += 1;
            let (ray, t_max) = self.shadow_ray(si, dir, dist);
            let blocker = if self.options.shadows {
                self.scene.occluded(&ray, 0.0, t_max, stats)
            } else {
                None
            };
            match blocker {
                None => visible += 1,
                // Only the tree shows the blocker: rendering keeps no note of it.
                Some(h) if R::ACTIVE && first_blocker.is_none() => first_blocker = Some((ray, h)),
                Some(_) => {}
            }
        }
        let s = visible as f64 / count as f64;
        if R::ACTIVE {
            let (origin, moved) = self.scene.offset(si, l, si.point);
            rec.begin(RayStart {
                kind: RayKind::Shadow,
                depth: depth + 1,
                origin,
                direction: l,
                weight: 1.0,
                coefficient: 1.0,
            });
            rec.shadow(&light.name, shadow_reach(distance, moved), s);
            if let Some((ray, h)) = first_blocker {
                let bsi = self.scene.interaction(&ray, &h);
                rec.hit(self.hit_info(&ray, h.t, &bsi));
            }
            rec.end(DVec3::splat(s), None);
        }
        s
    }

    /// A shadow ray from the surface along `dir` and how far it looks for blockers: up to a
    /// light `distance` away.
    #[inline(always)]
    fn shadow_ray(&self, si: &Interaction, dir: DVec3, distance: f64) -> (Ray, f64) {
        let (from, moved) = self.scene.offset(si, dir, si.point);
        (Ray { origin: from, dir }, shadow_reach(distance, moved))
    }

    /// The transparent solids that contain q, innermost last: those already on the ray's
    /// stack keep their order, others follow in scene order.
    fn media_at(&self, q: DVec3, d: DVec3, stack: &Media, stats: &mut Stats) -> Media {
        let scene = self.scene;
        let probe = Ray { origin: q, dir: d };
        let mut out = Media::default();
        for &(o, ior) in &stack.entries[..stack.len] {
            if scene.contains(o, &probe, stats) {
                out = out.entering(o, ior);
            }
        }
        for &(o, ior) in &scene.transparent_objects {
            if !stack.contains(o) && scene.contains(o, &probe, stats) {
                out = out.entering(o, ior);
            }
        }
        out
    }

    /// The one place secondary rays leave a surface: the origin moves off the surface, along
    /// the normal, to the side the new ray travels into, so it cannot hit its own surface.
    fn spawn(&self, si: &Interaction, dir: DVec3, parent: &Task) -> Ray {
        Ray {
            origin: self.scene.offset(si, dir, parent.ray.origin).0,
            dir,
        }
    }

    fn hit_info(&self, ray: &Ray, t: f64, si: &Interaction) -> HitInfo {
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
}
