//! The Whitted recursion for a packet of rays: a pixel's grid samples, then the secondary rays
//! of their surfaces, wave after wave. The core's steps (`light_share` for
//! `Tracer::light_share`, `Tracer::shadow_factor`, `Tracer::finish`, …, and `outgoing` with
//! `send` for `Tracer::secondary`) in another order: every ray's local terms of a light first,
//! then all their shadow rays toward it together (trying first the object that blocked the last
//! shadow ray toward that light, `Tracer::last_blockers`; the usual point lights take four
//! surfaces at once, `light_lanes`, and without a BVH their shadow rays too), then the
//! secondary rays as packets of their own. Each ray's intensity, the counters of rays and of
//! skipped shading and the random numbers drawn are those of tracing the rays one after
//! another with `Tracer::radiance`. The tracer must find its hits through the same
//! `FastScene` the packets are searched with.

use std::borrow::Cow;

use arrayvec::ArrayVec;
use glam::DVec3;

use super::bvh_packet::PACKET;
use super::checker_lanes;
use super::footprint::Missed;
use super::light_lanes::{lanes_light, SurfaceLanes};
use super::light_share::light_share;
use super::outgoing::{outgoing, send, Children, Outgoing};
use super::plane_lanes::MOST_PLANES;
use super::push_in_place;
use super::search::FastScene;
use super::simd::{with_lanes, F64x4};
use crate::geometry::Ray;
use crate::scene::{Hit, Interaction};
use crate::shading::local::ambient;
use crate::shading::Light;
use crate::trace::{RayKind, Task, Tracer};

/// The most rays shaded together where the objects are tested four rays at a time: a pixel's
/// grid samples, or the secondary rays of their surfaces. Through a BVH a whole packet of
/// several pixels' rays (up to `PACKET`) is shaded together, so that its shadow rays toward a
/// light walk the tree as one packet. Both are 32: two pixels of 16 samples.
pub const SHADED: usize = 32;
const _: () = assert!(SHADED <= PACKET, "a packet of primary rays shades whole");

/// The rays of a packet, each with its place in the tree: a pixel's primary rays, or the tasks
/// of a packet of secondary rays.
trait Lanes {
    fn kind(&self, i: usize) -> RayKind;
    fn ray(&self, i: usize) -> &Ray;
    fn depth(&self, i: usize) -> u32;
    /// The whole task (built on demand for a primary ray: it is needed only where secondary
    /// rays leave).
    fn task(&self, i: usize) -> Cow<'_, Task>;
}

impl Lanes for [Ray] {
    fn kind(&self, _: usize) -> RayKind {
        RayKind::Primary
    }

    fn ray(&self, i: usize) -> &Ray {
        &self[i]
    }

    fn depth(&self, _: usize) -> u32 {
        0
    }

    fn task(&self, i: usize) -> Cow<'_, Task> {
        Cow::Owned(Task::primary(&self[i]))
    }
}

impl Lanes for [Task] {
    fn kind(&self, i: usize) -> RayKind {
        self[i].kind
    }

    fn ray(&self, i: usize) -> &Ray {
        &self[i].ray
    }

    fn depth(&self, i: usize) -> u32 {
        self[i].depth
    }

    fn task(&self, i: usize) -> Cow<'_, Task> {
        Cow::Borrowed(&self[i])
    }
}

/// A light's terms at a packet's surfaces that cast a shadow ray toward it, and those rays, to
/// be searched together.
pub(super) struct ShadowPacket<const N: usize> {
    /// The packet lane of each shadow ray, and its surface's diffuse plus specular term.
    terms: ArrayVec<(usize, DVec3), N>,
    rays: ArrayVec<Ray, N>,
    reach: ArrayVec<f64, N>,
}

impl<const N: usize> ShadowPacket<N> {
    fn new() -> ShadowPacket<N> {
        ShadowPacket {
            terms: ArrayVec::new(),
            rays: ArrayVec::new(),
            reach: ArrayVec::new(),
        }
    }

    /// The shadow ray of the surface in packet lane `lane`, whose term waits on it.
    #[inline(always)]
    pub fn cast(&mut self, lane: usize, term: DVec3, ray: Ray, reach: f64) {
        self.terms.push((lane, term));
        self.rays.push(ray);
        self.reach.push(reach);
    }

    /// Searches the shadow rays toward light k (trying first the object that blocked the last
    /// one) and adds each term with its shadow factor s: `out[i] += s·term`, s = 1 where the
    /// ray reaches the light, else 0.
    #[inline(always)]
    fn search(&self, t: &mut Tracer, fast: &FastScene, k: usize, out: &mut [DVec3]) {
        if self.rays.is_empty() {
            return;
        }
        let blocked = fast.occluded_packet(
            &self.rays,
            &self.reach,
            &mut t.last_blockers[k],
            &mut t.stats,
        );
        for (j, &(i, term)) in self.terms.iter().enumerate() {
            let s = if blocked & (1 << j) == 0 { 1.0 } else { 0.0 };
            out[i] += s * term;
        }
    }
}

/// Primary rays, up to `PACKET` (the grid samples of a pixel, or of neighbouring pixels in a
/// BVH scene): `out[i]` is exactly what `Tracer::radiance` gives ray i, and the counters of
/// rays and the random numbers drawn are those of tracing the rays one after another. They are
/// searched as one packet, then shaded together through a BVH, else `SHADED` at a time, in
/// order. `missed`: the boxes and spheres every ray is known to miss, as the film knows them
/// (`FastScene::intersect_packet_knowing`).
pub fn trace_packet(
    t: &mut Tracer,
    fast: &FastScene,
    rays: &[Ray],
    missed: Missed,
    out: &mut [DVec3],
) {
    with_lanes!(V => trace_packet_inline::<V>(t, fast, rays, missed, out))
}

#[inline(always)]
fn trace_packet_inline<V: F64x4>(
    t: &mut Tracer,
    fast: &FastScene,
    rays: &[Ray],
    missed: Missed,
    out: &mut [DVec3],
) {
    let n = rays.len();
    assert!(n <= PACKET && out.len() == n);
    if t.options.stop_at_lights {
        // Rays that stop at lights look for lights as well as objects: one by one, the core's
        // way (no scene of the course needs that fast).
        for (ray, o) in rays.iter().zip(out.iter_mut()) {
            *o = t.radiance(ray);
        }
        return;
    }
    let mut hits = [None; PACKET];
    fast.intersect_packet_knowing(rays, missed, &mut hits[..n], &mut t.stats);
    if !fast.tests_in_lanes() {
        shade_packet::<V, _, PACKET>(t, fast, rays, &hits[..n], out);
        return;
    }
    for ((rays, hits), out) in rays
        .chunks(SHADED)
        .zip(hits[..n].chunks(SHADED))
        .zip(out.chunks_mut(SHADED))
    {
        shade_packet::<V, _, SHADED>(t, fast, rays, hits, out);
    }
}

/// A packet of up to N rays from their nearest hits: `out[i]` is exactly what `Tracer::shade`
/// gives task i. The shadow rays toward each light are searched together
/// (`FastScene::occluded_packet`); the secondary rays go in waves (`secondary_packet`) where
/// the objects are tested in lanes and nothing draws random numbers, else one after another.
#[inline(always)]
fn shade_packet<V: F64x4, L: Lanes + ?Sized, const N: usize>(
    t: &mut Tracer,
    fast: &FastScene,
    tasks: &L,
    hits: &[Option<Hit>],
    out: &mut [DVec3],
) {
    let scene = t.scene;
    let n = hits.len();
    let mut shaded: [Option<Interaction>; N] = [None; N];
    // The records are written in their places (`Scene::record_interaction`), the usual
    // checkers painted four at a time. The usual floor's hits are set aside, and shaded in
    // lanes without records (`plane_lanes`).
    let planes = if t.options.shadows {
        &fast.planes[..]
    } else {
        &[]
    };
    let mut on_planes = [0u32; MOST_PLANES];
    let mut checkers = 0u32;
    for i in 0..n {
        t.count(tasks.kind(i));
        match &hits[i] {
            None => out[i] = scene.background,
            Some(hit) => match planes.iter().position(|plane| plane.holds(hit)) {
                Some(p) => on_planes[p] |= 1 << i,
                None => {
                    let checker = record(fast, tasks.ray(i), hit, &mut shaded[i], &mut out[i]);
                    checkers |= (checker as u32) << i;
                }
            },
        }
    }
    for (plane, &taken) in planes.iter().zip(&on_planes) {
        if taken != 0 {
            // The lanes beside a light are shaded as usual.
            let mut left = plane.shade::<V>(t, fast, |i| tasks.ray(i), hits, taken, out);
            while left != 0 {
                let i = left.trailing_zeros() as usize;
                left &= left - 1;
                let hit = hits[i].as_ref().expect("a hit on the plane");
                let checker = record(fast, tasks.ray(i), hit, &mut shaded[i], &mut out[i]);
                checkers |= (checker as u32) << i;
            }
        }
    }
    let surfaces_hit = (0..n).fold(0u32, |bits, i| bits | (shaded[i].is_some() as u32) << i);
    if surfaces_hit == 0 {
        return;
    }
    if checkers != 0 {
        checker_lanes::paint_checkers::<V, N>(fast, &mut shaded, checkers);
        for (i, si) in shaded[..n].iter().enumerate() {
            if let Some(si) = si.as_ref().filter(|_| checkers & 1 << i != 0) {
                out[i] = ambient(scene.material(si.material), &si.paint, scene.ambient);
            }
        }
    }
    // The usual lights (a point light that does not fade, one shadow ray) light the usual
    // surfaces four at a time (`light_lanes`); where the objects are tested four rays at a
    // time, shadow rays and all.
    let in_lanes = fast.tests_in_lanes();
    let shadows_on = t.options.shadows;
    let single = |light: &Light| light.shadow_rays() == 1 && shadows_on;
    let some_in_lanes = scene
        .lights
        .iter()
        .any(|light| single(light) && lanes_light(light).is_some());
    let mut view = [DVec3::ZERO; N];
    if some_in_lanes {
        for (i, v) in view[..n].iter_mut().enumerate() {
            *v = -tasks.ray(i).dir;
        }
    }
    let mut surfaces = some_in_lanes.then(|| SurfaceLanes::new(&shaded, &view));
    if let Some(surfaces) = &mut surfaces {
        surfaces.choose(fast, n);
    }
    for (k, light) in scene.lights.iter().enumerate() {
        let single = single(light);
        let mut shadows = ShadowPacket::new();
        let mut alone = u32::MAX;
        if let (true, Some(surfaces), Some(light)) = (single, &surfaces, lanes_light(light)) {
            let far = if in_lanes {
                surfaces.light::<V>(t, fast, k, light, out)
            } else {
                surfaces.light_before_shadows::<V>(t, k, light, &mut shadows, out)
            };
            alone = surfaces.alone | far;
        }
        // The surfaces left to `light_share`, one by one (usually none where the lanes lit).
        if alone & surfaces_hit != 0 {
            for i in 0..n {
                let Some(si) = &shaded[i] else { continue };
                if alone & 1 << i == 0 {
                    continue;
                }
                let m = scene.material(si.material);
                let (sample, term, skipped) =
                    light_share(t, m, si, tasks.ray(i), || tasks.task(i), k);
                if skipped {
                    // As `color += s · terms` with s = 0, to the bit.
                    out[i] += 0.0 * term;
                } else if single {
                    t.stats.shadow_rays += 1;
                    let (ray, reach) = t.shadow_ray(si, sample.l, sample.distance);
                    shadows.cast(i, term, ray, reach);
                } else {
                    let s = t.shadow_factor(si, tasks.depth(i), &sample, light);
                    out[i] += s * term;
                }
            }
        }
        shadows.search(t, fast, k, out);
    }
    if scene.features.sampled || !fast.tests_in_lanes() || N > SHADED {
        // Glossy and frosted surfaces draw random numbers: the rays go on one by one, in
        // order, so each draws the numbers it draws when traced alone. And gathering the
        // secondary rays into packets pays only where packets are tested four rays at a time
        // (those packets, and only those, are at most `SHADED` rays).
        // A surface that sends no rays on is finished as it is (the tracer records nothing
        // here), without building its task.
        for i in 0..n {
            if let Some(si) = shaded[i].as_ref().filter(|si| si.paint.sends_rays()) {
                out[i] = t.finish(&tasks.task(i), si, out[i]);
            }
        }
    } else {
        secondary_packet(t, fast, tasks, &shaded[..n], out);
    }
}

/// The shading record of a ray's hit, written in its place `si`, and its ambient term `out`;
/// or, where the lanes paint its checker (`checker_lanes`), true, the record left unpainted.
#[inline(always)]
fn record(
    fast: &FastScene,
    ray: &Ray,
    hit: &Hit,
    si: &mut Option<Interaction>,
    out: &mut DVec3,
) -> bool {
    let scene = fast.scene;
    let si = si.insert(Interaction::default());
    let m = fast.record_surface(ray, hit, si);
    if checker_lanes::in_lanes(fast, m, si) {
        return true;
    }
    scene.paint_patterns(m, si);
    *out = ambient(m, &si.paint, scene.ambient);
    false
}

/// `Tracer::secondary` for every surface of a packet (where no material draws random numbers,
/// so the order rays are traced in changes nothing): all their reflection rays are traced
/// together as one packet, then all their refraction rays (or, past the limiting angle, the
/// mirror rays that stay inside) as another, and each surface sums kr·I_r + kt·I_t.
#[inline(always)]
fn secondary_packet<L: Lanes + ?Sized>(
    t: &mut Tracer,
    fast: &FastScene,
    tasks: &L,
    shaded: &[Option<Interaction>],
    out: &mut [DVec3],
) {
    // A packet of matte surfaces (the usual floor) sends nothing on.
    if !shaded.iter().flatten().any(|si| si.paint.sends_rays()) {
        return;
    }
    // First the directions of all the surfaces' rays, then the rays: one surface's square
    // roots and divisions then overlap the next one's, instead of holding up its rays. (A
    // primary ray's task is built in each pass: kept between them, 16 of them on the stack,
    // the wave is slower.)
    let mut plans: [Option<Outgoing>; SHADED] = [const { None }; SHADED];
    for (i, si) in shaded.iter().enumerate() {
        let Some(si) = si else { continue };
        if si.paint.sends_rays() && !t.stops_at(&si.paint) {
            plans[i] = Some(outgoing(t, &tasks.task(i), tasks.ray(i).dir, si));
        }
    }
    let mut reflected = Children::new();
    let mut transmitted = Children::new();
    for (i, (si, plan)) in shaded.iter().zip(&plans).enumerate() {
        if let (Some(si), Some(plan)) = (si, plan) {
            let task = tasks.task(i);
            send(t, &task, si, i, plan, &mut reflected, &mut transmitted);
        }
    }
    trace_children(t, fast, &mut reflected);
    trace_children(t, fast, &mut transmitted);
    for (i, plan) in plans.iter().enumerate() {
        let Some(plan) = plan else {
            continue;
        };
        let mut sum = DVec3::ZERO;
        if let Some(color) = reflected.colors[i] {
            sum += plan.kr * color;
        }
        // Past the limiting angle, the transmitted share may follow the reflection ray.
        let through = if plan.along_reflection() {
            reflected.colors[i]
        } else {
            transmitted.colors[i]
        };
        if let Some(color) = through {
            sum += plan.kt * color;
        }
        out[i] += sum;
    }
}

/// Traces the children as one packet, and settles their parents' colours.
/// Each level of waves keeps its rays' records, tasks and hits on the stack (tens of kilobytes):
/// where a tree goes deeper than the thread's stack holds (the render's workers have room for
/// 64 levels, `cli::args::RENDER_STACK`; other threads may have less), the next level goes on
/// a fresh stack of its own.
fn trace_children(t: &mut Tracer, fast: &FastScene, children: &mut Children) {
    stacker::maybe_grow(
        WAVE_STACK,
        8 * WAVE_STACK,
        || with_lanes!(V => trace_children_inline::<V>(t, fast, children)),
    )
}

/// More than one level of waves takes of the stack, in any build.
const WAVE_STACK: usize = 256 * 1024;

#[inline(always)]
fn trace_children_inline<V: F64x4>(t: &mut Tracer, fast: &FastScene, children: &mut Children) {
    let n = children.tasks.len();
    if n == 0 {
        return;
    }
    // Pushed one by one where they stay: a collected ArrayVec is built elsewhere and moved
    // here whole, its wide loads waiting on the narrow stores just made.
    let mut rays: ArrayVec<Ray, SHADED> = ArrayVec::new();
    for task in &children.tasks {
        push_in_place(&mut rays, task.ray);
    }
    let mut hits = [None; SHADED];
    fast.intersect_packet(&rays, &mut hits[..n], &mut t.stats);
    let mut colors = [DVec3::ZERO; SHADED];
    shade_packet::<V, _, SHADED>(t, fast, &children.tasks[..], &hits[..n], &mut colors[..n]);
    for k in 0..n {
        let distance = hits[k].map_or(f64::INFINITY, |h| h.t);
        let color = t.attenuated(colors[k], distance);
        children.settle(children.lanes[k], color);
    }
}
