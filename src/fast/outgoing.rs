//! The rays a surface sends on, as tasks to trace later: the core's `Tracer::secondary` traces
//! its reflection and refraction rays at once, one surface after another; a packet of surfaces
//! first finds all their directions (`outgoing`), then builds all their rays (`send`), and
//! traces them as packets of their own (`packet_trace::secondary_packet`). Built from the
//! core's own pieces (`Media`, `Tracer::across`, `fresnel_weights`, `reflect`, `refract`,
//! `Tracer::spawn`, the `Task` constructors), so the rays are the core's to the bit.

use arrayvec::ArrayVec;
use glam::DVec3;

use super::packet_trace::SHADED;
use super::push_in_place;

use crate::geometry::Ray;
use crate::scene::Interaction;
use crate::shading::optics::{fresnel_weights, reflect, refract};
use crate::shading::{Fresnel, Material};
use crate::trace::tree::Indices;
use crate::trace::Termination::Adaptive;
use crate::trace::{Media, Task, Tracer};

/// Where the rays a surface sends on go, before they are built: kr and kt after the Fresnel
/// term, the mirror direction, and each ray's fate. A ray the depth limit or the adaptive
/// threshold cuts off is counted where its fate is decided, and no refracted direction (two
/// square roots and two divisions) is found for it where nothing depends on it: at the last
/// level of a glass every ray is one.
pub(super) struct Outgoing {
    pub kr: f64,
    pub kt: f64,
    /// The mirror direction: of the reflected ray, and of the ray that stays inside past the
    /// limiting angle.
    mirror: DVec3,
    /// The reflected ray.
    reflection: Fate<()>,
    /// The transmitted share.
    transmission: Fate<Transmitted>,
}

/// Where the transmitted share goes.
enum Transmitted {
    /// Along the refracted ray: n1 and n2 across the surface, the media beyond it, and the
    /// refracted direction.
    Refracted(f64, f64, Beyond, DVec3),
    /// Past the limiting angle, along the mirror ray that stays inside.
    Inside,
    /// Past the limiting angle at a surface that reflects too, along its reflection ray
    /// (`Tracer::along_reflection`).
    AlongReflection,
}

/// The media a refracted ray travels inside, before they are built (in the child's task
/// itself: a stack of media built here and moved on with the plan waits, at each move, for
/// the narrow stores that built it).
enum Beyond {
    /// Those of the ray that hit the surface (a sheet has no inside).
    Same,
    /// Those with the surface's object entered through its material.
    Entering,
    /// Those without the surface's object.
    Leaving,
    /// As the geometry has them (`Tracer::across`, where transparent objects may touch).
    Found(Media),
}

/// What becomes of one of the rays a surface may send on.
enum Fate<D> {
    /// The surface sends none (its k is not positive).
    None,
    /// The depth limit or the adaptive threshold stops it: it brings nothing.
    CutOff,
    /// It is traced, with what it needs to be built.
    Traced(D),
}

/// The directions of the rays the surface `si` sends on, for a ray `task` that hit it, as in
/// `Tracer::secondary`. `d` is the task's direction, read from the packet's rays: a primary
/// ray's task has just been built, and a wide load of what was just written field by field
/// waits for the stores.
#[inline(always)]
pub(super) fn outgoing(t: &mut Tracer, task: &Task, d: DVec3, si: &Interaction) -> Outgoing {
    let m = t.scene.material(si.material);
    // `Tracer::coefficients`, written out to be compiled into the packet loop. A surface that
    // transmits nothing and has no Fresnel term needs neither index nor the media beyond:
    // its kr and kt are the material's.
    let (kr, kt, across) = if refracts(si, m) {
        let (n1, n2, beyond) = across(t, task, si, m);
        let (kr, kt) = fresnel_weights(
            m.fresnel,
            -d.dot(si.normal),
            (n1, n2),
            (si.paint.kr, si.paint.kt),
        );
        (kr, kt, Some((n1, n2, beyond)))
    } else {
        (si.paint.kr, si.paint.kt, None)
    };
    // The refracted direction, where it is needed: for a transmitted ray that is traced, and
    // past the limiting angle, for the share a reflection ray may carry.
    let transmitted = child(task, kt);
    let cut = t.limit(&transmitted);
    let direction = match &across {
        Some((n1, n2, _)) if kt > 0.0 && (cut.is_none() || kr > 0.0 && cut == Some(Adaptive)) => {
            Some(refract(d, si.normal, *n1, *n2))
        }
        _ => None,
    };
    // Past the limiting angle the reflection ray carries both shares (`Tracer::secondary`;
    // packets of surfaces have no glossy or frosted lobes, `secondary_packet`).
    let shared = kr > 0.0 && matches!(direction, Some(None));
    let reflection = fate(t, task, if shared { kr + kt } else { kr });
    let transmission = match (across, direction) {
        _ if kt <= 0.0 || kt.is_nan() => Fate::None,
        _ if shared && matches!(reflection, Fate::Traced(())) => {
            Fate::Traced(Transmitted::AlongReflection)
        }
        _ if cut.is_some() => {
            t.stopped(&transmitted);
            Fate::CutOff
        }
        (Some((n1, n2, beyond)), Some(Some(dir))) => {
            Fate::Traced(Transmitted::Refracted(n1, n2, beyond, dir))
        }
        _ => Fate::Traced(Transmitted::Inside),
    };
    Outgoing {
        kr,
        kt,
        mirror: reflect(d, si.normal),
        reflection,
        transmission,
    }
}

impl Outgoing {
    /// Whether the transmitted share follows the reflection ray.
    pub fn along_reflection(&self) -> bool {
        matches!(
            self.transmission,
            Fate::Traced(Transmitted::AlongReflection)
        )
    }
}

/// A child of `task` weighted by k: one level deeper, of weight weight·k.
#[inline(always)]
fn child(task: &Task, k: f64) -> Task {
    Task {
        depth: task.depth + 1,
        weight: task.weight * k,
        ..*task
    }
}

/// Whether the surface sends a child weighted by k, and whether it is traced. Each child of
/// `task` (reflection, refraction, or the mirror ray inside past the limiting angle) is one
/// level deeper and weighs weight·k, so whether it is cut off (`Tracer::stopped`, which counts
/// it) is known before its direction is.
#[inline(always)]
fn fate(t: &mut Tracer, task: &Task, k: f64) -> Fate<()> {
    if k <= 0.0 || k.is_nan() {
        return Fate::None;
    }
    match t.stopped(&child(task, k)) {
        Some(_) => Fate::CutOff,
        None => Fate::Traced(()),
    }
}

/// The rays the surface `si` in packet lane `lane` sends on, as `plan` has them: the mirror
/// ray to `reflected`, the refracted ray (past the limiting angle, the mirror ray that stays
/// inside: rays bouncing inside a glass are many) to `transmitted`, each built in its place
/// there (a task is 168 bytes, and one returned in a value is copied on twice more).
#[inline(always)]
pub(super) fn send(
    t: &mut Tracer,
    task: &Task,
    si: &Interaction,
    lane: usize,
    plan: &Outgoing,
    reflected: &mut Children,
    transmitted: &mut Children,
) {
    let Outgoing { kr, kt, mirror, .. } = *plan;
    match plan.reflection {
        Fate::None => {}
        Fate::CutOff => reflected.cut_off(lane),
        Fate::Traced(()) => {
            let ray = spawn(t, si, mirror);
            let task = if plan.along_reflection() {
                task.reflection_and_transmission(ray, kr, kt)
            } else {
                task.reflection(ray, kr)
            };
            reflected.add(lane, task);
        }
    }
    match &plan.transmission {
        Fate::None => {}
        Fate::CutOff => transmitted.cut_off(lane),
        Fate::Traced(Transmitted::Refracted(n1, n2, beyond, dir)) => {
            let ray = spawn_through(t, si, *dir);
            let media = &task.media;
            let beyond = match beyond {
                Beyond::Same => *media,
                Beyond::Entering => media.entering(si.object, si.material),
                Beyond::Leaving => media.leaving(si.object),
                Beyond::Found(media) => *media,
            };
            let indices = Indices { n1: *n1, n2: *n2 };
            transmitted.add(lane, task.refraction(ray, kt, beyond, indices));
        }
        Fate::Traced(Transmitted::Inside) => {
            let ray = spawn(t, si, mirror);
            transmitted.add(lane, task.mirror_inside(ray, kt));
            t.stats.total_internal_reflections += 1;
        }
        Fate::Traced(Transmitted::AlongReflection) => t.stats.total_internal_reflections += 1,
    }
}

/// `Tracer::spawn`, compiled into the packet loop: called, it hands its ray back through
/// memory, and the task's wide loads of it wait for the call's narrow stores.
#[inline(always)]
fn spawn(t: &Tracer, si: &Interaction, dir: DVec3) -> Ray {
    Ray {
        origin: t.scene.offset(si, dir).0,
        dir,
    }
}

/// `Tracer::spawn_through`, compiled into the packet loop (as `spawn`).
#[inline(always)]
fn spawn_through(t: &Tracer, si: &Interaction, dir: DVec3) -> Ray {
    Ray {
        origin: t.scene.offset_to(si, false).0,
        dir,
    }
}

/// The reflection (or refraction) rays of a packet's surfaces, gathered to be traced as a
/// packet of their own, and the colour each surface receives through them.
pub(super) struct Children {
    pub tasks: ArrayVec<Task, SHADED>,
    /// The surface (its lane in the parent packet) each task leaves from.
    pub lanes: [usize; SHADED],
    /// Per parent lane: the intensity arriving through its child (zero for a child the depth
    /// limit or the adaptive threshold stopped); None for a surface without such a child.
    pub colors: [Option<DVec3>; SHADED],
}

impl Children {
    pub fn new() -> Children {
        Children {
            tasks: ArrayVec::new(),
            lanes: [0; SHADED],
            colors: [None; SHADED],
        }
    }

    /// The child `task` of the surface in lane `lane`, to be traced (built in its place).
    #[inline(always)]
    fn add(&mut self, lane: usize, task: Task) {
        self.lanes[self.tasks.len()] = lane;
        push_in_place(&mut self.tasks, task);
    }

    /// The surface in lane `lane` has a child that is cut off: it brings nothing.
    #[inline(always)]
    fn cut_off(&mut self, lane: usize) {
        self.colors[lane] = Some(DVec3::ZERO);
    }

    /// The intensity arriving at the surface in lane `lane` through its child.
    pub fn settle(&mut self, lane: usize, color: DVec3) {
        self.colors[lane] = Some(color);
    }
}

/// Whether the surface refracts or weighs its rays by Fresnel's term: only then do the
/// indices on its two sides matter.
fn refracts(si: &Interaction, m: &Material) -> bool {
    si.paint.kt != 0.0 || m.fresnel != Fresnel::None
}

/// `Tracer::across` for a surface that refracts: n1, n2 and the media beyond, those built
/// only where the geometry must be asked (more than one transparent object). Written out to be
/// compiled into the packet loop: n1 and n2 returned from a call come back through memory, and
/// the one wide load that reads them there waits for the call's two narrow stores.
#[inline(always)]
fn across(t: &mut Tracer, task: &Task, si: &Interaction, m: &Material) -> (f64, f64, Beyond) {
    let scene = t.scene;
    if scene.features.transparent_objects.len() > 1 {
        let across = t.across(task, si, m);
        return (across.n1, across.n2, Beyond::Found(across.beyond));
    }
    let media = &task.media;
    if !scene.leaves[si.leaf as usize].shape.is_solid() {
        let n1 = media.current(scene);
        return (n1, n1, Beyond::Same);
    }
    let entered = media.entering(si.object, si.material).current(scene);
    if si.inside {
        (
            entered,
            media.leaving(si.object).current(scene),
            Beyond::Leaving,
        )
    } else {
        (media.current(scene), entered, Beyond::Entering)
    }
}
