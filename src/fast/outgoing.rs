//! The rays a surface sends on, as tasks to trace later: the core's `Tracer::secondary` traces
//! its reflection and refraction rays at once, one surface after another; a packet of surfaces
//! first gathers all their rays (`packet_trace::secondary_packet`) and traces them as packets
//! of their own. Built from the core's own pieces (`Media`, `Tracer::across`,
//! `fresnel_weights`, `reflect`, `refract`, `Tracer::spawn`, the `Task` constructors), so the
//! rays are the core's to the bit.

use glam::DVec3;

use crate::scene::Interaction;
use crate::shading::optics::{fresnel_weights, reflect, refract};
use crate::shading::{Fresnel, Material};
use crate::trace::{Across, Task, Tracer};

/// A surface's secondary rays, before the depth limit and the adaptive threshold have their
/// say.
pub(super) struct Outgoing {
    /// kr and kt after the Fresnel term.
    pub kr: f64,
    pub kt: f64,
    /// The mirror ray, when kr > 0.
    pub reflection: Option<Task>,
    /// The refracted ray when kt > 0; past the limiting angle, the mirror ray that stays
    /// inside and carries kt.
    pub transmission: Option<Transmission>,
}

pub(super) enum Transmission {
    Refracted(Task),
    TotalInternalReflection(Task),
}

/// The rays the surface `si` sends on, for a ray `task` that hit it: as in `Tracer::secondary`.
/// `d` is the task's direction, read from the packet's rays: a primary ray's task has just
/// been built, and a wide load of what was just written field by field waits for the stores.
#[inline(always)]
pub(super) fn outgoing(t: &mut Tracer, task: &Task, d: DVec3, si: &Interaction) -> Outgoing {
    let m = t.scene.material(si.material);
    // `Tracer::coefficients`, written out to be compiled into the packet loop. A surface that
    // transmits nothing and has no Fresnel term needs neither index nor the media beyond:
    // its kr and kt are the material's.
    let (kr, kt, across) = if refracts(si, m) {
        let across = across(t, task, si, m);
        let (kr, kt) = fresnel_weights(
            m.fresnel,
            -d.dot(si.normal),
            (across.n1, across.n2),
            (si.paint.kr, si.paint.kt),
        );
        (kr, kt, Some(across))
    } else {
        (si.paint.kr, si.paint.kt, None)
    };
    let mirror = reflect(d, si.normal);
    // Plain branches, not closures: the compiler inlines them into the packet loop.
    let reflection = if kr > 0.0 {
        Some(task.reflection(t.spawn(si, mirror, task), kr))
    } else {
        None
    };
    let transmission = match across {
        Some(across) if kt > 0.0 => {
            let indices = across.indices();
            Some(match refract(d, si.normal, indices.n1, indices.n2) {
                Some(dir) => {
                    let ray = t.spawn(si, dir, task);
                    Transmission::Refracted(task.refraction(ray, kt, across.beyond, indices))
                }
                None => Transmission::TotalInternalReflection(
                    task.mirror_inside(t.spawn(si, mirror, task), kt),
                ),
            })
        }
        _ => None,
    };
    Outgoing {
        kr,
        kt,
        reflection,
        transmission,
    }
}

/// Whether the surface refracts or weighs its rays by Fresnel's term: only then do the
/// indices on its two sides matter.
fn refracts(si: &Interaction, m: &Material) -> bool {
    si.paint.kt != 0.0 || m.fresnel != Fresnel::None
}

/// `Tracer::across` for a surface that refracts, written out to be compiled into the packet
/// loop where the geometry need not be asked (a scene with at most one transparent object):
/// n1 and n2 returned from a call come back through memory, and the one wide load that reads
/// them there waits for the call's two narrow stores.
#[inline(always)]
fn across(t: &mut Tracer, task: &Task, si: &Interaction, m: &Material) -> Across {
    let scene = t.scene;
    if scene.features.transparent_objects.len() > 1 {
        return t.across(task, si, m);
    }
    let media = &task.media;
    let (n1, beyond) = if si.inside {
        let within = media.entering(si.object, si.material);
        (within.current(scene), media.leaving(si.object))
    } else {
        (media.current(scene), media.entering(si.object, si.material))
    };
    let n2 = if scene.leaves[si.leaf as usize].shape.is_solid() {
        beyond.current(scene)
    } else {
        n1
    };
    Across { n1, n2, beyond }
}
