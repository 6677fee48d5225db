//! Axis-aligned box, intersected as the overlap of three slabs.

use glam::DVec3;

use super::{Ray, Span};

/// An axis-aligned box primitive (scene `box`), in object space: a solid bounded by six faces,
/// numbered −x, +x, −y, +y, −z, +z.
#[derive(Clone, Debug, PartialEq)]
pub struct Aabox {
    /// Corner with the smallest coordinates.
    pub min: DVec3,
    /// Corner with the largest coordinates.
    pub max: DVec3,
}

/// Faces are numbered −x, +x, −y, +y, −z, +z.
const NORMALS: [DVec3; 6] = [
    DVec3::NEG_X,
    DVec3::X,
    DVec3::NEG_Y,
    DVec3::Y,
    DVec3::NEG_Z,
    DVec3::Z,
];

impl Aabox {
    /// The interval of t (over the whole line) inside the box, by the slab method, with the faces
    /// the ray enters and leaves through; None when the ray misses it.
    pub fn span(&self, ray: &Ray) -> Option<Span> {
        let (mut t_in, mut t_out) = (f64::NEG_INFINITY, f64::INFINITY);
        let (mut face_in, mut face_out) = (0u8, 0u8);
        for axis in 0..3 {
            let (o, d) = (ray.origin[axis], ray.dir[axis]);
            let (lo, hi) = (self.min[axis], self.max[axis]);
            if d == 0.0 {
                // Parallel to this slab: inside it everywhere or nowhere.
                if o < lo || o > hi {
                    return None;
                }
                continue;
            }
            let (mut t0, mut t1) = ((lo - o) / d, (hi - o) / d);
            let (mut f0, mut f1) = (2 * axis as u8, 2 * axis as u8 + 1);
            if d < 0.0 {
                std::mem::swap(&mut t0, &mut t1);
                std::mem::swap(&mut f0, &mut f1);
            }
            if t0 > t_in {
                t_in = t0;
                face_in = f0;
            }
            if t1 < t_out {
                t_out = t1;
                face_out = f1;
            }
        }
        (t_in <= t_out).then(|| Span::new(t_in, face_in, t_out, face_out))
    }

    /// The outward unit normal of face `face` (0–5: −x, +x, −y, +y, −z, +z).
    pub fn normal(&self, face: u8) -> DVec3 {
        NORMALS[face as usize]
    }
}
