//! Which media a refracting surface separates: n1 on the side the ray comes from, n2 on the side
//! a refracted ray goes into. A ray carries the stack of transparent solids it is inside, so
//! nested glass (a bubble in a block) keeps n1 and n2 right.

use glam::DVec3;

use super::recorder::Recorder;
use super::task::Task;
use super::tree::Indices;
use super::Tracer;
use crate::geometry::Ray;
use crate::scene::{Interaction, Scene};
use crate::shading::{Fresnel, Material};

/// The refractive media a ray is inside, innermost last: up to eight transparent objects, each
/// with the material it was entered through (its index of refraction holds inside). Indices,
/// not the numbers: the stack is copied with every ray, and 68 bytes copy faster than 104.
#[derive(Clone, Copy, Debug)]
pub struct Media {
    objects: [u32; 8],
    materials: [u32; 8],
    len: u32,
}

impl Default for Media {
    fn default() -> Media {
        Media {
            objects: [u32::MAX; 8],
            materials: [u32::MAX; 8],
            len: 0,
        }
    }
}

impl Media {
    /// The index of refraction around the ray (1 for vacuum/air).
    pub fn current(&self, scene: &Scene) -> f64 {
        match self.len {
            0 => 1.0,
            n => scene.material(self.materials[n as usize - 1]).ior,
        }
    }

    /// The stack with `object`, entered through `material`, innermost.
    pub(crate) fn entering(&self, object: u32, material: u32) -> Media {
        let mut m = *self;
        m.push(object, material);
        m
    }

    /// The stack without `object`: the media beyond a surface where the ray leaves it.
    pub(crate) fn leaving(&self, object: u32) -> Media {
        let mut m = Media::default();
        for (o, material) in self.iter() {
            if o != object {
                m.push(o, material);
            }
        }
        m
    }

    fn push(&mut self, object: u32, material: u32) {
        let n = self.len as usize;
        if n < self.objects.len() {
            (self.objects[n], self.materials[n]) = (object, material);
            self.len += 1;
        }
    }

    fn contains(&self, object: u32) -> bool {
        self.objects[..self.len as usize].contains(&object)
    }

    /// (object, material), outermost first.
    fn iter(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        let n = self.len as usize;
        self.objects[..n]
            .iter()
            .copied()
            .zip(self.materials[..n].iter().copied())
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
    /// transmits nothing and has no Fresnel term needs neither index. `m` is the surface's
    /// material (`si.material`).
    pub(crate) fn across(&mut self, task: &Task, si: &Interaction, m: &Material) -> Across {
        let scene = self.scene;
        let media = &task.media;
        // n1 is the index on the near side; `beyond` the media past the surface.
        let sheet = !scene.leaves[si.leaf as usize].shape.is_solid();
        let (n1, beyond) = if sheet || (si.paint.kt == 0.0 && m.fresnel == Fresnel::None) {
            // A sheet (a lone triangle, an open tube or cone) has no inside: crossing it
            // changes no medium, and the ray stays in those it is in.
            (media.current(scene), *media)
        } else if scene.features.transparent_objects.len() <= 1 {
            let entered = media.entering(si.object, si.material);
            if si.inside {
                (entered.current(scene), media.leaving(si.object))
            } else {
                (media.current(scene), entered)
            }
        } else {
            let step = 2.0 * scene.bias(task.ray.origin, si.point);
            let d = task.ray.dir;
            let near = self.media_at(si.point + step * si.normal, d, media);
            let entered = media.entering(si.object, si.material);
            let beyond = self.media_at(si.point - step * si.normal, d, &entered);
            (near.current(scene), beyond)
        };
        let n2 = if sheet { n1 } else { beyond.current(scene) };
        Across { n1, n2, beyond }
    }

    /// The transparent solids that contain q, innermost last: those already on the ray's
    /// stack keep their order, others follow in scene order.
    fn media_at(&mut self, q: DVec3, d: DVec3, stack: &Media) -> Media {
        let scene = self.scene;
        let probe = Ray { origin: q, dir: d };
        let mut out = Media::default();
        for (o, material) in stack.iter() {
            if scene.contains(o, &probe, &mut self.stats) {
                out.push(o, material);
            }
        }
        for &(o, material) in &scene.features.transparent_objects {
            if !stack.contains(o) && scene.contains(o, &probe, &mut self.stats) {
                out.push(o, material);
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
        // Nine glasses g0..g8 with indices 1.0, 1.1, …, 1.8.
        let mut yaml =
            String::from("camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmaterials:\n");
        for k in 0..9 {
            yaml += &format!("  g{k}: {{ kt: 1, ior: {} }}\n", 1.0 + k as f64 / 10.0);
        }
        yaml += "objects:\n  - { sphere: { center: [0, 0, 0], radius: 1 }, material: g0 }\n";
        let scene = crate::scene::parse(&yaml, "nine.yaml", None, &Default::default()).unwrap();
        let glass = |k: u32| (0..9).find(|&i| scene.material(i).ior == 1.0 + k as f64 / 10.0);
        let mut m = Media::default();
        assert_eq!(m.current(&scene), 1.0);
        for k in 0..9 {
            m = m.entering(k, glass(k).unwrap());
        }
        assert_eq!(m.iter().count(), 8);
        assert_eq!(m.current(&scene), 1.7);
        assert!(m.contains(7) && !m.contains(8));
    }
}
