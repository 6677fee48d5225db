//! Where the tree's hit points appear in the picture: the eye's view of each point a reflected
//! or refracted ray landed on, so the explorer can mark them on the preview (`m`).

use glam::{DMat3, DVec2};

use super::rays::{segments, SegKind};
use crate::scene::Camera;
use crate::trace::RayNode;

/// A hit point of the tree, placed in the image.
#[derive(Clone, Debug, PartialEq)]
pub struct HitMark {
    /// The node whose ray hit it.
    pub path: Vec<usize>,
    /// What ended there, which sets the mark's colour.
    pub kind: SegKind,
    /// Continuous image coordinates: (0, 0) is the top-left corner of the image, pixel (x, y)
    /// covers [x, x + 1) × [y, y + 1).
    pub at: DVec2,
}

/// Where the eye sees a world point: the image coordinates of the point where the line from
/// the eye to it crosses the image plane, or None when it lies behind the eye.
pub fn image_position(camera: &Camera, p: glam::DVec3) -> Option<DVec2> {
    let eye = camera.eye();
    // The image plane is affine in the image coordinates: q(sx, sy) = q0 + sx·a + sy·b.
    let q0 = camera.image_point(0.0, 0.0);
    let a = camera.image_point(1.0, 0.0) - q0;
    let b = camera.image_point(0.0, 1.0) - q0;
    // eye + s·(p − eye) = q0 + sx·a + sy·b, solved for (s, sx, sy).
    let m = DMat3::from_cols(p - eye, -a, -b);
    if m.determinant().abs() < 1e-300 {
        return None;
    }
    let sol = m.inverse() * (q0 - eye);
    (sol.x > 0.0 && sol.is_finite()).then(|| DVec2::new(sol.y, sol.z))
}

/// The hit points of the tree's reflection and refraction rays, in the image.
pub fn hit_marks(camera: &Camera, root: &RayNode) -> Vec<HitMark> {
    segments(root)
        .into_iter()
        .filter(|s| matches!(s.kind, SegKind::Reflection | SegKind::Refraction))
        .filter_map(|s| {
            let at = image_position(camera, s.to?)?;
            Some(HitMark {
                path: s.path,
                kind: s.kind,
                at,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn a_pixel_ray_lands_back_on_its_pixel() {
        let cam = Camera::look_at(
            DVec3::new(0.0, 1.0, -6.0),
            DVec3::ZERO,
            DVec3::Y,
            40.0,
            48,
            36,
        );
        for (x, y) in [(0, 0), (20, 15), (47, 35)] {
            let ray = cam.pixel_ray(x, y);
            let at = image_position(&cam, ray.at(7.5)).unwrap();
            assert!(
                (at - DVec2::new(x as f64 + 0.5, y as f64 + 0.5)).length() < 1e-9,
                "{at}"
            );
        }
        assert_eq!(image_position(&cam, DVec3::new(0.0, 1.0, -10.0)), None);
    }
}
