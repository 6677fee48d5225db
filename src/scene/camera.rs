//! Cameras: the look-at camera with a field of view, and the lecture's window model (seed 001).

use glam::DVec3;

use crate::geometry::Ray;

/// How the camera maps image coordinates to points on its image plane.
#[derive(Clone, Debug, PartialEq)]
pub enum Projection {
    /// Look-at camera. right = up × forward, so looking down +z with up +y puts +x on the
    /// right of the image: the same frame as the lecture's window model (u = +x, w = +z) and
    /// as POV-Ray, so scenes translate between them unchanged.
    LookAt {
        /// The eye point e, world space: every primary ray starts here.
        eye: DVec3,
        /// Unit viewing direction, from the eye towards the target; the image plane lies at
        /// distance 1 along it.
        forward: DVec3,
        /// Unit vector to the right in the image.
        right: DVec3,
        /// Unit vector up in the image, perpendicular to `forward` and `right`.
        up: DVec3,
        /// tan(fov/2), the half height of the image plane at distance 1 (fov vertical).
        tan_half_fov: f64,
    },
    /// Seed 001: pixel (i, j) lies at p_C = (wl + i·Δu, wt + j·Δv, f) in camera coordinates,
    /// p_W = e + p_C.x·u + p_C.y·v + p_C.z·w in the world.
    Window {
        /// The eye point e, world space.
        eye: DVec3,
        /// Camera axis u, along which pixel columns i step by Δu (world space).
        u: DVec3,
        /// Camera axis v, along which pixel rows j step by Δv.
        v: DVec3,
        /// Camera axis w (viewing direction).
        w: DVec3,
        /// Distance f of the window along w.
        f: f64,
        /// The window's edges [wl, wr, wt, wb] in camera coordinates: left, right, top, bottom
        /// pixel centres.
        window: [f64; 4],
    },
}

/// The eye and the image: which primary ray goes through each point of the image.
#[derive(Clone, Debug, PartialEq)]
pub struct Camera {
    /// Look-at or window model.
    pub projection: Projection,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
}

impl Camera {
    /// A camera at `eye` looking at `target`, `up` roughly up, with a vertical field of view of
    /// `fov_degrees` (degrees) over a `width` × `height` image; left-handed frame (right = up ×
    /// forward).
    pub fn look_at(
        eye: DVec3,
        target: DVec3,
        up: DVec3,
        fov_degrees: f64,
        width: u32,
        height: u32,
    ) -> Camera {
        Camera::frame(eye, target, up, fov_degrees, width, height, false)
    }

    /// The same, in a right-handed frame (right = forward × up, as Mitsuba and OpenGL): the
    /// image is the mirror image of `look_at`'s.
    pub fn look_at_right_handed(
        eye: DVec3,
        target: DVec3,
        up: DVec3,
        fov_degrees: f64,
        width: u32,
        height: u32,
    ) -> Camera {
        Camera::frame(eye, target, up, fov_degrees, width, height, true)
    }

    fn frame(
        eye: DVec3,
        target: DVec3,
        up: DVec3,
        fov_degrees: f64,
        width: u32,
        height: u32,
        right_handed: bool,
    ) -> Camera {
        let forward = (target - eye).normalize();
        let right = if right_handed {
            forward.cross(up)
        } else {
            up.cross(forward)
        }
        .normalize();
        let up = if right_handed {
            right.cross(forward)
        } else {
            forward.cross(right)
        };
        let tan_half_fov = (fov_degrees.to_radians() / 2.0).tan();
        Camera {
            projection: Projection::LookAt {
                eye,
                forward,
                right,
                up,
                tan_half_fov,
            },
            width,
            height,
        }
    }

    /// The eye point e, where primary rays start (world space).
    pub fn eye(&self) -> DVec3 {
        match &self.projection {
            Projection::LookAt { eye, .. } | Projection::Window { eye, .. } => *eye,
        }
    }

    /// The same view at another image size.
    pub fn resized(&self, width: u32, height: u32) -> Camera {
        Camera {
            projection: self.projection.clone(),
            width,
            height,
        }
    }

    /// The world point on the image plane at continuous image coordinates (sx, sy); the centre
    /// of pixel (x, y) is (x + ½, y + ½) and (0, 0) is the top-left corner.
    pub fn image_point(&self, sx: f64, sy: f64) -> DVec3 {
        self.eye() + self.image_offset(sx, sy)
    }

    /// Where the image plane's point at (sx, sy) lies from the eye: p − e, found from the
    /// camera's axes alone (p − e = forward + x·right + y·up; seed 001's p_C.x·u + p_C.y·v +
    /// p_C.z·w). Subtracting e from p itself would lose the offset next to an eye 10¹⁶ from
    /// the origin, where the spacing of doubles outgrows the image plane.
    pub fn image_offset(&self, sx: f64, sy: f64) -> DVec3 {
        let (w, h) = (self.width as f64, self.height as f64);
        match &self.projection {
            Projection::LookAt {
                forward,
                right,
                up,
                tan_half_fov,
                ..
            } => {
                let x = plane_x(sx, (w, h), *tan_half_fov);
                let y = plane_y(sy, h, *tan_half_fov);
                *forward + x * *right + y * *up
            }
            Projection::Window {
                u,
                v,
                w: axis_w,
                f,
                window: [wl, wr, wt, wb],
                ..
            } => {
                let along = |s: f64, n: f64, lo: f64, hi: f64| {
                    // Δ = (hi − lo)/(n − 1); with a single pixel, the window's centre.
                    if n > 1.0 {
                        lo + (s - 0.5) * (hi - lo) / (n - 1.0)
                    } else {
                        0.5 * (lo + hi) + (s - 0.5) * (hi - lo)
                    }
                };
                let pc = DVec3::new(along(sx, w, *wl, *wr), along(sy, h, *wt, *wb), *f);
                pc.x * *u + pc.y * *v + pc.z * *axis_w
            }
        }
    }

    /// The primary ray from the eye through image coordinates (sx, sy) (pixel (x, y)'s centre is (x
    /// + ½, y + ½)), with a unit direction: d = p − e, normalised.
    pub fn ray(&self, sx: f64, sy: f64) -> Ray {
        Ray::new(self.eye(), self.image_offset(sx, sy))
    }

    /// The primary ray through the centre of pixel (x, y).
    pub fn pixel_ray(&self, x: u32, y: u32) -> Ray {
        self.ray(x as f64 + 0.5, y as f64 + 0.5)
    }
}

/// The look-at camera's coordinate along `right` on its image plane (one unit from the eye)
/// of the image column sx, in an image w × h: x = (2·sx/w − 1)·tan(fov/2)·(w/h).
pub(crate) fn plane_x(sx: f64, (w, h): (f64, f64), tan_half_fov: f64) -> f64 {
    (2.0 * sx / w - 1.0) * tan_half_fov * (w / h)
}

/// The coordinate along `up` of the image row sy, in an image h high: y = (1 − 2·sy/h)·tan(fov/2).
pub(crate) fn plane_y(sy: f64, h: f64, tan_half_fov: f64) -> f64 {
    (1.0 - 2.0 * sy / h) * tan_half_fov
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The window model with the world's axes (u = x, v = y, w = z), the eye at (0, 0, −5) and
    /// the window at f = 2, over `window` = [wl, wr, wt, wb].
    fn seed_001_window(window: [f64; 4], width: u32, height: u32) -> Camera {
        Camera {
            projection: Projection::Window {
                eye: DVec3::new(0.0, 0.0, -5.0),
                u: DVec3::X,
                v: DVec3::Y,
                w: DVec3::Z,
                f: 2.0,
                window,
            },
            width,
            height,
        }
    }

    #[test]
    fn window_model_places_pixels_as_seed_001() {
        // 3 × 3 pixels over the window [−1, 1] × [1, −1] at f = 2: Δu = 1, Δv = −1.
        let cam = seed_001_window([-1.0, 1.0, 1.0, -1.0], 3, 3);
        assert_eq!(cam.image_point(0.5, 0.5), DVec3::new(-1.0, 1.0, -3.0));
        assert_eq!(cam.image_point(2.5, 1.5), DVec3::new(1.0, 0.0, -3.0));
    }

    #[test]
    fn look_at_centre_pixel_looks_forward_and_top_left_is_up_left() {
        let cam = Camera::look_at(DVec3::ZERO, DVec3::NEG_Z, DVec3::Y, 90.0, 2, 2);
        let r = cam.ray(1.0, 1.0);
        assert!((r.dir - DVec3::NEG_Z).length() < 1e-15);
        let tl = cam.pixel_ray(0, 0).dir;
        // Looking down −z with up +y, right = up × forward = −x: the top-left pixel looks up
        // and to +x. (Looking down +z, the top-left pixel looks to −x, as in the window model.)
        assert!(tl.x > 0.0 && tl.y > 0.0);
        let cam = Camera::look_at(DVec3::ZERO, DVec3::Z, DVec3::Y, 90.0, 2, 2);
        let tl = cam.pixel_ray(0, 0).dir;
        assert!(tl.x < 0.0 && tl.y > 0.0);
    }

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-12
    }

    #[test]
    fn the_image_plane_spans_tan_half_fov_up_and_the_aspect_ratio_across() {
        // Eye at (1, 2, 3) looking down +z, fov 60°: the plane at distance 1 reaches
        // tan 30° = 1/√3 up and down, and (w/h)·(1/√3) = 2/√3 left and right of a 4 × 2 image.
        let eye = DVec3::new(1.0, 2.0, 3.0);
        let cam = Camera::look_at(eye, eye + DVec3::new(0.0, 0.0, 5.0), DVec3::Y, 60.0, 4, 2);
        let t = 1.0 / 3f64.sqrt();
        assert!(close(
            cam.image_point(0.0, 0.0),
            eye + DVec3::new(-2.0 * t, t, 1.0)
        ));
        assert!(close(
            cam.image_point(4.0, 2.0),
            eye + DVec3::new(2.0 * t, -t, 1.0)
        ));
        assert!(close(cam.image_point(2.0, 1.0), eye + DVec3::Z));
        // Pixel (3, 0)'s centre is (3.5, 0.5): x = (2·3.5/4 − 1)·t·2 = 1.5t, y = (1 − 2·0.5/2)·t.
        let r = cam.pixel_ray(3, 0);
        assert_eq!(r.origin, eye);
        let d = DVec3::new(1.5 * t, 0.5 * t, 1.0);
        assert!(close(r.dir, d.normalize()));
    }

    #[test]
    fn a_right_handed_camera_sees_the_mirror_image() {
        // right = forward × up = z × y = −x; up = right × forward = (−x) × z = y.
        let cam = Camera::look_at_right_handed(DVec3::ZERO, DVec3::Z, DVec3::Y, 90.0, 2, 2);
        let Projection::LookAt { right, up, .. } = cam.projection else {
            unreachable!()
        };
        assert!(close(right, DVec3::NEG_X) && close(up, DVec3::Y));
        assert!(close(cam.image_point(0.0, 0.0), DVec3::new(1.0, 1.0, 1.0)));
    }

    #[test]
    fn a_tilted_up_vector_is_made_perpendicular_to_the_view() {
        // up = (0, 1, 1) looking down +z: the image's up is y, its right x (left-handed).
        let cam = Camera::look_at(DVec3::ZERO, DVec3::Z, DVec3::new(0.0, 1.0, 1.0), 90.0, 2, 2);
        let Projection::LookAt {
            forward, right, up, ..
        } = cam.projection
        else {
            unreachable!()
        };
        assert!(close(forward, DVec3::Z) && close(right, DVec3::X) && close(up, DVec3::Y));
    }

    #[test]
    fn a_one_pixel_window_covers_the_whole_window() {
        // n = 1: no Δ between pixel centres; the pixel's centre is the window's centre and its
        // corners are the window's corners.
        let cam = seed_001_window([-1.0, 3.0, 2.0, -2.0], 1, 1);
        assert_eq!(cam.image_point(0.5, 0.5), DVec3::new(1.0, 0.0, -3.0));
        assert_eq!(cam.image_point(0.0, 0.0), DVec3::new(-1.0, 2.0, -3.0));
        assert_eq!(cam.image_point(1.0, 1.0), DVec3::new(3.0, -2.0, -3.0));
    }

    #[test]
    fn the_window_model_uses_its_own_axes() {
        // Camera axes u = y, v = z, w = x: p_W = e + p_C.x·u + p_C.y·v + p_C.z·w.
        let cam = Camera {
            projection: Projection::Window {
                eye: DVec3::new(1.0, 1.0, 1.0),
                u: DVec3::Y,
                v: DVec3::Z,
                w: DVec3::X,
                f: 3.0,
                window: [-1.0, 1.0, 1.0, -1.0],
            },
            width: 5,
            height: 3,
        };
        // Pixel (4, 2): p_C = (−1 + 4·0.5, 1 + 2·(−1), 3) = (1, −1, 3).
        assert_eq!(cam.image_point(4.5, 2.5), DVec3::new(4.0, 2.0, 0.0));
        let r = cam.pixel_ray(4, 2);
        assert_eq!(r.origin, DVec3::new(1.0, 1.0, 1.0));
        assert!(close(r.dir, DVec3::new(3.0, 1.0, -1.0).normalize()));
    }

    #[test]
    fn resizing_keeps_the_view() {
        let cam = Camera::look_at(DVec3::ONE, DVec3::ZERO, DVec3::Y, 40.0, 8, 8);
        let big = cam.resized(32, 16);
        assert_eq!((big.width, big.height), (32, 16));
        assert_eq!(big.projection, cam.projection);
        assert_eq!(big.eye(), DVec3::ONE);
    }
}
