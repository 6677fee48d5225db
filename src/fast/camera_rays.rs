//! A pixel's primary rays four at a time: the core's `Camera::ray` for the look-at camera, lane
//! by lane, with the same operations in the same order (the point on the image plane, its
//! offset from the eye, and `DVec3::normalize`'s square root, reciprocal and products), so each
//! ray is the core's to the bit. The window model takes the core's own steps.

use arrayvec::ArrayVec;
use glam::{DVec2, DVec3};

use super::bvh_packet::PACKET;
use super::packet_trace::SHADED;
use super::simd::{with_lanes, F64x4};
use crate::geometry::Ray;
use crate::scene::{Camera, Projection};

/// The rays through (fx + o.x, fy + o.y) for each offset o (at most `SHADED`), in order:
/// `camera.ray` for each, added to `rays` (written where they stay: rays returned whole would
/// be copied on).
pub fn primary_rays(
    camera: &Camera,
    fx: f64,
    fy: f64,
    offsets: &[DVec2],
    rays: &mut ArrayVec<Ray, PACKET>,
) {
    assert!(offsets.len() <= SHADED, "at most {SHADED} rays at once");
    match Frame::of(camera) {
        Some(frame) => with_lanes!(V => frame.rays::<V>(fx, fy, offsets, rays)),
        None => rays.extend(offsets.iter().map(|o| camera.ray(fx + o.x, fy + o.y))),
    }
}

/// The look-at camera's frame, as `Camera::image_point` reads it.
struct Frame {
    eye: DVec3,
    forward: DVec3,
    right: DVec3,
    up: DVec3,
    tan_half_fov: f64,
    size: (f64, f64),
}

impl Frame {
    /// The frame of a look-at camera; None for the window model.
    fn of(camera: &Camera) -> Option<Frame> {
        let Projection::LookAt {
            eye,
            forward,
            right,
            up,
            tan_half_fov,
        } = camera.projection
        else {
            return None;
        };
        Some(Frame {
            eye,
            forward,
            right,
            up,
            tan_half_fov,
            size: (camera.width as f64, camera.height as f64),
        })
    }

    #[inline(always)]
    fn rays<V: F64x4>(
        &self,
        fx: f64,
        fy: f64,
        offsets: &[DVec2],
        rays: &mut ArrayVec<Ray, PACKET>,
    ) {
        for group in offsets.chunks(4) {
            // Unused lanes repeat the group's first offset; their rays are not kept.
            let at = |k: usize| group.get(k).unwrap_or(&group[0]);
            let (o0, o1, o2, o3) = (at(0), at(1), at(2), at(3));
            let sx = V::splat(fx) + V::setr(o0.x, o1.x, o2.x, o3.x);
            let sy = V::splat(fy) + V::setr(o0.y, o1.y, o2.y, o3.y);
            let dir = self.directions(sx, sy);
            let [x, y, z] = [dir[0].to_array(), dir[1].to_array(), dir[2].to_array()];
            for k in 0..group.len() {
                rays.push(Ray::raw(self.eye, DVec3::new(x[k], y[k], z[k])));
            }
        }
    }

    /// The unit directions toward image coordinates (sx, sy), axis by axis.
    #[inline(always)]
    fn directions<V: F64x4>(&self, sx: V, sy: V) -> [V; 3] {
        let (w, h) = (V::splat(self.size.0), V::splat(self.size.1));
        let (one, two, tan) = (V::ONE, V::splat(2.0), V::splat(self.tan_half_fov));
        // `image_point`: x = (2·sx/w − 1)·tan(fov/2)·(w/h), y = (1 − 2·sy/h)·tan(fov/2).
        let x = (two * sx / w - one) * tan * (w / h);
        let y = (one - two * sy / h) * tan;
        // p = e + forward + x·right + y·up, and d = p − e, one axis at a time.
        let mut d = [V::ZERO; 3];
        for (axis, d) in d.iter_mut().enumerate() {
            let e = V::splat(self.eye[axis]);
            let p = e
                + V::splat(self.forward[axis])
                + x * V::splat(self.right[axis])
                + y * V::splat(self.up[axis]);
            *d = p - e;
        }
        // `DVec3::normalize`: d · (1 / √(d·d)).
        let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        let recip = V::ONE / length;
        [d[0] * recip, d[1] * recip, d[2] * recip]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::simd::Wide;
    use crate::sampling::Rng;

    /// Every ray is `Camera::ray`'s to the bit: cameras looking every way, in both handed
    /// frames, with fields of view from narrow to wide, odd image sizes, offsets anywhere in
    /// the pixel, and packets of every length up to 16 (the lanes' own copy and the
    /// processor's).
    #[test]
    fn the_rays_are_the_cameras_own() {
        let mut rng = Rng::for_pixel(31, 0, 0);
        let mut u = move || rng.uniform();
        for case in 0..2000 {
            let eye = DVec3::new(u() - 0.5, u() - 0.5, u() - 0.5) * 20.0;
            let target = eye + DVec3::new(u() - 0.5, u() - 0.5, u() - 0.5);
            let fov = 1.0 + 170.0 * u();
            let (width, height) = (1 + (u() * 1000.0) as u32, 1 + (u() * 700.0) as u32);
            let camera = if case % 2 == 0 {
                Camera::look_at(eye, target, DVec3::Y, fov, width, height)
            } else {
                Camera::look_at_right_handed(eye, target, DVec3::Y, fov, width, height)
            };
            let n = 1 + case % SHADED;
            let offsets: Vec<DVec2> = (0..n).map(|_| DVec2::new(u(), u())).collect();
            let (fx, fy) = ((u() * width as f64).floor(), (u() * height as f64).floor());
            let expected: Vec<Ray> = offsets
                .iter()
                .map(|o| camera.ray(fx + o.x, fy + o.y))
                .collect();
            let bits = |rays: &[Ray]| -> Vec<[u64; 6]> {
                rays.iter()
                    .map(|r| {
                        let [a, b, c] = r.origin.to_array().map(f64::to_bits);
                        let [d, e, f] = r.dir.to_array().map(f64::to_bits);
                        [a, b, c, d, e, f]
                    })
                    .collect()
            };
            let mut rays = ArrayVec::new();
            primary_rays(&camera, fx, fy, &offsets, &mut rays);
            assert_eq!(bits(&rays), bits(&expected), "case {case}");
            let frame = Frame::of(&camera).expect("look_at makes a look-at camera");
            let mut rays = ArrayVec::new();
            frame.rays::<Wide>(fx, fy, &offsets, &mut rays);
            assert_eq!(bits(&rays), bits(&expected));
        }
    }
}
