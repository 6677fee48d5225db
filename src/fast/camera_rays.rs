//! A film's primary rays four at a time: the core's `Camera::ray` for the look-at camera, lane
//! by lane, with the same operations in the same order (the offset of the point on the image
//! plane from the eye, and `DVec3::normalize`'s square root, reciprocal and products), so each
//! ray is the core's to the bit. The window model takes the core's own steps.
//!
//! A grid sample's offset on the image plane, forward + x·right + y·up, takes a division for x
//! and one for y. Every pixel of a column has the same x at its samples, and every pixel of a
//! row the same y, so the sums' parts are worked out once a film (`ImagePlane::new`):
//! forward + x·right for each column and offset, y·up for each row and offset.

use std::ops::Range;

use arrayvec::ArrayVec;
use glam::{DVec2, DVec3};

use super::bvh_packet::PACKET;
use super::lanes::LANES;
use super::push_in_place;
use super::simd::{with_lanes, F64x4};
use crate::geometry::Ray;
use crate::scene::{plane_x, plane_y, Camera, Projection};

/// A look-at camera's image plane at a film's sample offsets.
pub struct ImagePlane {
    eye: DVec3,
    /// The image's size in pixels, and the number of offsets.
    width: u32,
    height: u32,
    offsets: usize,
    /// Axis by axis, forward + x·right for column c and offset k at c·offsets + k.
    columns: [Vec<f64>; 3],
    /// Axis by axis, y·up for row r and offset k at r·offsets + k.
    rows: [Vec<f64>; 3],
}

/// A look-at camera's frame and its image's size in pixels: what its image plane is made of.
pub(super) struct LookAt {
    pub eye: DVec3,
    pub forward: DVec3,
    pub right: DVec3,
    pub up: DVec3,
    pub tan_half_fov: f64,
    /// Width and height.
    pub size: (f64, f64),
}

impl LookAt {
    /// The frame of `camera`; None for the window model.
    pub(super) fn of(camera: &Camera) -> Option<LookAt> {
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
        Some(LookAt {
            eye,
            forward,
            right,
            up,
            tan_half_fov,
            size: (camera.width as f64, camera.height as f64),
        })
    }
}

impl ImagePlane {
    /// The image plane of `camera` at the samples (c + o.x, r + o.y) of every pixel (c, r), for
    /// each offset o; None for the window model.
    pub fn new(camera: &Camera, offsets: &[DVec2]) -> Option<ImagePlane> {
        let LookAt {
            eye,
            forward,
            right,
            up,
            tan_half_fov,
            size: (w, h),
        } = LookAt::of(camera)?;
        let n = offsets.len();
        let mut columns = [(); 3].map(|_| Vec::with_capacity(camera.width as usize * n + LANES));
        for c in 0..camera.width {
            for o in offsets {
                // `image_offset`'s x, and its sum's first terms.
                let x = plane_x(c as f64 + o.x, (w, h), tan_half_fov);
                let part = forward + x * right;
                for (axis, column) in columns.iter_mut().enumerate() {
                    column.push(part[axis]);
                }
            }
        }
        let mut rows = [(); 3].map(|_| Vec::with_capacity(camera.height as usize * n + LANES));
        for r in 0..camera.height {
            for o in offsets {
                let part = plane_y(r as f64 + o.y, h, tan_half_fov) * up;
                for (axis, row) in rows.iter_mut().enumerate() {
                    row.push(part[axis]);
                }
            }
        }
        // Three more values at the end of each, so that four are read from any place.
        for v in columns.iter_mut().chain(rows.iter_mut()) {
            let last = v.last().copied().unwrap_or(0.0);
            v.extend([last; LANES - 1]);
        }
        Some(ImagePlane {
            eye,
            width: camera.width,
            height: camera.height,
            offsets: n,
            columns,
            rows,
        })
    }

    /// Whether pixel (x, y) lies in the image.
    pub fn holds(&self, x: u32, y: u32) -> bool {
        x < self.width && y < self.height
    }

    /// The rays of pixel (x, y) (which the image holds) through the offsets numbered `which`,
    /// in order: `camera.ray` for each, added to `rays` (written where they stay: rays
    /// returned whole would be copied on).
    pub fn rays(&self, x: u32, y: u32, which: Range<usize>, rays: &mut ArrayVec<Ray, PACKET>) {
        assert!(self.holds(x, y) && which.end <= self.offsets);
        with_lanes!(V => self.rays_in_lanes::<V>(x, y, which, rays))
    }

    #[inline(always)]
    fn rays_in_lanes<V: F64x4>(
        &self,
        x: u32,
        y: u32,
        which: Range<usize>,
        rays: &mut ArrayVec<Ray, PACKET>,
    ) {
        let column = x as usize * self.offsets;
        let row = y as usize * self.offsets;
        for first in which.clone().step_by(LANES) {
            let count = (which.end - first).min(LANES);
            // Unused lanes take the values that follow (the next pixel's, or the padding);
            // their rays are not kept.
            let lanes = |v: &[f64], at: usize| {
                let at = at + first;
                V::new(v[at..at + LANES].try_into().unwrap())
            };
            // d = (forward + x·right) + y·up, one axis at a time.
            let mut d = [V::ZERO; 3];
            for (axis, d) in d.iter_mut().enumerate() {
                *d = lanes(&self.columns[axis], column) + lanes(&self.rows[axis], row);
            }
            // `DVec3::normalize`: d · (1 / √(d·d)).
            let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let recip = V::ONE / length;
            let [dx, dy, dz] = [d[0] * recip, d[1] * recip, d[2] * recip].map(V::to_array);
            for k in 0..count {
                push_in_place(rays, Ray::raw(self.eye, DVec3::new(dx[k], dy[k], dz[k])));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::simd::Wide;
    use crate::sampling::Rng;

    /// Every ray is `Camera::ray`'s to the bit: cameras looking every way, in both handed
    /// frames, with fields of view from narrow to wide, odd image sizes, offsets anywhere in
    /// the pixel, pixels anywhere in the image, and runs of offsets of every length up to 16
    /// (the lanes' own copy and the processor's).
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
            let n = 1 + case % 16;
            let offsets: Vec<DVec2> = (0..n).map(|_| DVec2::new(u(), u())).collect();
            let (x, y) = ((u() * width as f64) as u32, (u() * height as f64) as u32);
            let first = case / 16 % n;
            let expected: Vec<Ray> = offsets[first..]
                .iter()
                .map(|o| camera.ray(x as f64 + o.x, y as f64 + o.y))
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
            let plane = ImagePlane::new(&camera, &offsets).expect("a look-at camera");
            let mut rays = ArrayVec::new();
            plane.rays(x, y, first..n, &mut rays);
            assert_eq!(bits(&rays), bits(&expected), "case {case}");
            let mut rays = ArrayVec::new();
            plane.rays_in_lanes::<Wide>(x, y, first..n, &mut rays);
            assert_eq!(bits(&rays), bits(&expected));
        }
    }
}
