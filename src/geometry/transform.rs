//! Object transforms. A solid is intersected in its own space: the ray is carried there by the
//! inverse transform, and normals come back by the inverse transpose.

use glam::{DAffine3, DMat3, DVec3};

use super::Ray;

/// An object's placement: the affine map from object space to world space, with its inverse and the
/// normal matrix precomputed.
#[derive(Clone, Debug, PartialEq)]
pub struct Transform {
    /// Object space → world space.
    pub to_world: DAffine3,
    /// World space → object space (the inverse of `to_world`), for rays.
    pub to_local: DAffine3,
    /// (M⁻¹)ᵀ of the linear part: keeps normals perpendicular under non-uniform scaling.
    pub normal_to_world: DMat3,
}

impl Transform {
    /// The transform of `to_world` (invertible), with its inverse and normal matrix.
    pub fn new(to_world: DAffine3) -> Transform {
        let to_local = to_world.inverse();
        Transform {
            to_world,
            to_local,
            normal_to_world: to_local.matrix3.transpose(),
        }
    }

    /// The ray in object space; its direction is not renormalised so `t` keeps its meaning.
    pub fn ray_to_local(&self, ray: &Ray) -> Ray {
        Ray::raw(
            self.to_local.transform_point3(ray.origin),
            self.to_local.transform_vector3(ray.dir),
        )
    }

    /// An object-space normal in world space: (M⁻¹)ᵀ·n, normalised.
    pub fn normal_to_world(&self, n: DVec3) -> DVec3 {
        (self.normal_to_world * n).normalize()
    }

    /// An object-space point in world space.
    pub fn point_to_world(&self, p: DVec3) -> DVec3 {
        self.to_world.transform_point3(p)
    }

    /// s when the linear part is s times a rotation or reflection (to rounding): such a
    /// transform carries spheres to spheres and cylinders to cylinders.
    pub fn similarity_scale(&self) -> Option<f64> {
        let m = self.to_world.matrix3;
        // The Gram matrix MᵀM is s²·I exactly for a similarity.
        let gram = m.transpose() * m;
        let s2 = (gram.x_axis.x + gram.y_axis.y + gram.z_axis.z) / 3.0;
        let off = (gram - DMat3::from_diagonal(DVec3::splat(s2)))
            .to_cols_array()
            .iter()
            .fold(0.0f64, |worst, v| worst.max(v.abs()));
        (s2.is_normal() && off <= 1e-12 * s2).then(|| s2.sqrt())
    }

    /// `self` applied after `inner`.
    pub fn after(&self, inner: &Transform) -> Transform {
        Transform::new(self.to_world * inner.to_world)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DMat3;

    /// Scale by 2, rotate 90° about z, then move by (1, 0, 0): the object point (1, 2, 3) goes
    /// to (2, 4, 6), then to (−4, 2, 6), then to (−3, 2, 6); and the world ray from (−3, 2, 0)
    /// along z, which meets that point at t = 6, taken to object space meets (1, 2, 3) at t = 6
    /// too (its direction is not renormalised).
    #[test]
    fn points_go_to_the_world_and_rays_come_back() {
        let to_world = DAffine3::from_translation(DVec3::X)
            * DAffine3::from_mat3(DMat3::from_rotation_z(std::f64::consts::FRAC_PI_2))
            * DAffine3::from_scale(DVec3::splat(2.0));
        let t = Transform::new(to_world);
        let p = t.point_to_world(DVec3::new(1.0, 2.0, 3.0));
        assert!((p - DVec3::new(-3.0, 2.0, 6.0)).length() < 1e-12, "{p}");
        let ray = Ray::new(DVec3::new(-3.0, 2.0, 0.0), DVec3::Z);
        let local = t.ray_to_local(&ray);
        let at = local.origin + 6.0 * local.dir;
        assert!((at - DVec3::new(1.0, 2.0, 3.0)).length() < 1e-12, "{at}");
        assert_eq!(
            t.similarity_scale().map(|s| (s * 1e12).round() / 1e12),
            Some(2.0)
        );
    }
}
