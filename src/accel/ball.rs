//! Bounding balls: where a box is loose. The common part of two spheres (a lens) lies in a
//! ball much smaller than the common part of their boxes, and that ball's box is what tightens
//! the bounds of CSG intersections of spheres (seed 000's bounding volumes: the tighter the
//! volume, the fewer rays evaluate the tree only to miss it).

use glam::DVec3;

use super::Aabb;

/// A bounding ball (sphere) in world space: the points within `radius` of `center`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ball {
    /// Centre of the ball, world space.
    pub center: DVec3,
    /// Radius of the ball, in scene units.
    pub radius: f64,
}

/// Rounding in the rim circle's radius must not cut off the lens's edge.
const PAD: f64 = 1e-9;

impl Ball {
    /// The ball of the given centre and radius.
    pub fn new(center: DVec3, radius: f64) -> Ball {
        Ball { center, radius }
    }

    /// The axis-aligned box around the ball.
    pub fn bounds(&self) -> Aabb {
        Aabb::new(self.center - self.radius, self.center + self.radius)
    }

    /// A ball that holds every point of both `self` and `other`'s common part.
    ///
    /// Two spheres meet in a circle, the rim. With the centres d apart, the rim's plane is
    /// x = (d² + r₁² − r₂²) / 2d from the first centre and the rim's radius h = √(r₁² − x²).
    /// When the plane lies between the centres, each sphere's part on the other's side is a
    /// cap no bigger than a hemisphere, and a cap lies within h of its rim's centre: a point
    /// s beyond the rim's plane and ρ from the axis has ρ² + (x + s)² ≤ r², so its squared
    /// distance to the rim's centre, ρ² + s², is at most h² − 2xs ≤ h². Otherwise the smaller
    /// sphere bounds the common part.
    pub fn around_common(&self, other: &Ball) -> Ball {
        let smaller = if self.radius <= other.radius {
            *self
        } else {
            *other
        };
        let axis = other.center - self.center;
        let d = axis.length();
        // One inside the other (concentric ones included), or apart: no rim.
        if d + smaller.radius >= self.radius.max(other.radius) && d < self.radius + other.radius {
            let x = (d * d + self.radius * self.radius - other.radius * other.radius) / (2.0 * d);
            if (0.0..=d).contains(&x) {
                let h = (self.radius * self.radius - x * x).max(0.0).sqrt();
                let rim = Ball::new(
                    self.center + axis * (x / d),
                    h + PAD * self.radius.max(other.radius),
                );
                if rim.radius < smaller.radius {
                    return rim;
                }
            }
        }
        smaller
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn distance_to_farthest_common_point(a: &Ball, b: &Ball, c: DVec3) -> f64 {
        // Sample both spheres' surfaces and keep the points inside the other: the common
        // part's boundary, whose farthest point from c is the farthest of the whole part.
        let mut farthest = 0.0f64;
        for (s, o) in [(a, b), (b, a)] {
            for i in 0..200 {
                for j in 0..400 {
                    let theta = std::f64::consts::PI * (i as f64 + 0.5) / 200.0;
                    let phi = std::f64::consts::TAU * j as f64 / 400.0;
                    let p = s.center
                        + s.radius
                            * DVec3::new(
                                theta.sin() * phi.cos(),
                                theta.sin() * phi.sin(),
                                theta.cos(),
                            );
                    if (p - o.center).length() <= o.radius {
                        farthest = farthest.max((p - c).length());
                    }
                }
            }
        }
        farthest
    }

    #[test]
    fn the_peer_scenes_lens_lies_in_its_rim_ball() {
        // Spheres of radius 1.6 whose centres are 2.4 apart: the rim is halfway, with radius
        // √(1.6² − 1.2²) = √1.12 (Pythagoras), far below the 1.6 of either sphere.
        let a = Ball::new(DVec3::new(0.0, 0.0, -1.2), 1.6);
        let b = Ball::new(DVec3::new(0.0, 0.0, 1.2), 1.6);
        let lens = a.around_common(&b);
        assert!((lens.radius - 1.12f64.sqrt()).abs() < 1e-8);
        assert!(lens.center.length() < 1e-15);
        let reach = distance_to_farthest_common_point(&a, &b, lens.center);
        // The farthest points are on the rim, which the sampling comes within 1 % of.
        assert!(
            reach <= lens.radius && reach > 0.99 * lens.radius,
            "{reach} {lens:?}"
        );
    }

    #[test]
    fn unequal_spheres_and_deep_overlaps_are_bounded() {
        let cases = [
            // Rim plane between the centres, unequal radii.
            (
                Ball::new(DVec3::ZERO, 2.0),
                Ball::new(DVec3::new(2.5, 0.3, 0.0), 1.0),
            ),
            // Rim plane behind the small sphere's centre: the small sphere is the bound.
            (
                Ball::new(DVec3::ZERO, 2.0),
                Ball::new(DVec3::new(1.5, 0.0, 0.0), 1.0),
            ),
            // One inside the other, and concentric.
            (
                Ball::new(DVec3::ZERO, 2.0),
                Ball::new(DVec3::new(0.5, 0.0, 0.0), 1.0),
            ),
            (Ball::new(DVec3::ONE, 1.0), Ball::new(DVec3::ONE, 1.0)),
        ];
        for (a, b) in cases {
            for (p, q) in [(a, b), (b, a)] {
                let bound = p.around_common(&q);
                let reach = distance_to_farthest_common_point(&p, &q, bound.center);
                // (The samples on a sphere lie on it to rounding.)
                assert!(
                    reach <= bound.radius * (1.0 + 1e-12),
                    "{p:?} ∩ {q:?}: {bound:?} misses {reach}"
                );
                assert!(bound.radius <= p.radius.min(q.radius));
            }
        }
        // The second case's rim is x = (2.25 + 4 − 1) / 3 = 1.75 from the big centre: past
        // the small centre at 1.5, so the small sphere bounds it.
        let (a, b) = cases[1];
        assert_eq!(a.around_common(&b), b);
    }
}
