//! Which media a refracting surface separates: n1 on the side the ray comes from, n2 on the side
//! a refracted ray goes into. A ray carries the stack of transparent solids it is inside, so
//! nested glass (a bubble in a block) keeps n1 and n2 right.

use glam::DVec3;

use super::recorder::Recorder;
use super::task::Task;
use super::tree::Indices;
use super::Tracer;
use crate::geometry::Ray;
use crate::scene::Interaction;
use crate::shading::{Fresnel, Material};

/// The refractive media a ray is inside, innermost last: up to eight transparent objects and
/// their indices of refraction. (Two arrays rather than one of pairs: a pair of u32 and f64
/// takes 16 bytes, and the stack is copied with every refraction ray.)
#[derive(Clone, Copy, Debug)]
pub struct Media {
    objects: [u32; 8],
    iors: [f64; 8],
    len: usize,
}

impl Default for Media {
    fn default() -> Media {
        Media {
            objects: [u32::MAX; 8],
            iors: [1.0; 8],
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
            self.iors[self.len - 1]
        }
    }

    fn entering(&self, object: u32, ior: f64) -> Media {
        let mut m = *self;
        if m.len < m.objects.len() {
            (m.objects[m.len], m.iors[m.len]) = (object, ior);
            m.len += 1;
        }
        m
    }

    fn contains(&self, object: u32) -> bool {
        self.objects[..self.len].contains(&object)
    }

    /// (object, index of refraction), outermost first.
    fn iter(&self) -> impl Iterator<Item = (u32, f64)> + '_ {
        self.objects[..self.len]
            .iter()
            .copied()
            .zip(self.iors[..self.len].iter().copied())
    }
}

/// The two sides of a surface a ray hits.
pub struct Across {
    /// The index of refraction on the side the ray comes from.
    pub n1: f64,
    /// The index on the far side.
    pub n2: f64,
    /// The media a refracted ray is inside.
    pub beyond: Media,
}

impl Across {
    /// n1 → n2, as the ray tree shows them on a refraction ray.
    pub fn indices(&self) -> Indices {
        Indices {
            n1: self.n1,
            n2: self.n2,
        }
    }
}

impl<R: Recorder> Tracer<'_, R> {
    /// The media on both sides of the surface `si` that `task` hits.
    ///
    /// The media are asked of the geometry (the transparent solids containing a point just
    /// before and just beyond the surface), rather than only pushed and popped, so that n1 and
    /// n2 stay right where two glasses touch in a shared face. With one transparent object
    /// nothing can touch or nest, and entering or leaving says it all; a surface that
    /// transmits nothing and has no Fresnel term needs neither index.
    pub(crate) fn across(&mut self, task: &Task, si: &Interaction, m: &Material) -> Across {
        let (near, beyond) = if si.paint.kt == 0.0 && m.fresnel == Fresnel::None {
            (task.media, task.media)
        } else if self.scene.features.transparent_objects.len() <= 1 {
            if si.inside {
                let mut outside = Media::default();
                for (o, ior) in task.media.iter() {
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
            let d = task.ray.dir;
            let near = self.media_at(si.point + step * si.normal, d, &task.media);
            let entered = task.media.entering(si.object, m.ior);
            let beyond = self.media_at(si.point - step * si.normal, d, &entered);
            (near, beyond)
        };
        let n2 = if self.scene.leaves[si.leaf as usize].shape.is_solid() {
            beyond.current()
        } else {
            // A lone triangle is a sheet with no inside: nothing changes across it.
            near.current()
        };
        Across {
            n1: near.current(),
            n2,
            beyond,
        }
    }

    /// The transparent solids that contain q, innermost last: those already on the ray's
    /// stack keep their order, others follow in scene order.
    fn media_at(&mut self, q: DVec3, d: DVec3, stack: &Media) -> Media {
        let scene = self.scene;
        let probe = Ray { origin: q, dir: d };
        let mut out = Media::default();
        for (o, ior) in stack.iter() {
            if scene.contains(o, &probe, &mut self.stats) {
                out = out.entering(o, ior);
            }
        }
        for &(o, ior) in &scene.features.transparent_objects {
            if !stack.contains(o) && scene.contains(o, &probe, &mut self.stats) {
                out = out.entering(o, ior);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The stack holds eight media; a ninth nested solid is not recorded (the ray keeps the
    /// eighth's index) rather than written past the end.
    #[test]
    fn a_ninth_nested_medium_is_left_out() {
        let mut m = Media::default();
        for k in 0..9 {
            m = m.entering(k, 1.0 + k as f64 / 10.0);
        }
        assert_eq!(m.iter().count(), 8);
        assert_eq!(m.current(), 1.7);
        assert!(m.contains(7) && !m.contains(8));
    }
}
