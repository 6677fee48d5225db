//! Finite cone, given (as in seed 003) by its apex, the centre of its base and the base radius:
//! with a base cap (a solid) or without it (`capped: false`, an open cone: a surface with no
//! inside).

use glam::DVec3;

use super::cylinder::{
    cap_slab, crossings, far_sphere, near_start, quadratic, started_at, AxialQuadratic, Interval,
    BASE_CAP, SIDE,
};
use super::{Ray, Span};

/// A finite cone primitive, in object space: the apex, a circular base disc of `radius` around
/// `base`, and the side between them.
#[derive(Clone, Debug, PartialEq)]
pub struct Cone {
    /// The tip of the cone, where its radius is 0.
    pub apex: DVec3,
    /// Centre of the base disc; the axis runs from `apex` to here.
    pub base: DVec3,
    /// Radius of the base disc.
    pub radius: f64,
}

/// How near the apex, in heights, a point takes the apex's normal.
const APEX_REACH: f64 = 1e-12;

/// The cone has no top cap: the apex end of the slab never contributes a face of its own.
const APEX: u8 = SIDE;

impl Cone {
    /// Unit axis from the apex towards the base.
    pub fn axis(&self) -> DVec3 {
        (self.base - self.apex).normalize()
    }

    pub(crate) fn cos2(&self) -> f64 {
        let h2 = (self.base - self.apex).length_squared();
        h2 / (h2 + self.radius * self.radius)
    }

    /// The double cone's f(t) = ((x − apex)·a)² − cos²θ·|x − apex|² along the ray, with
    /// w = o − apex: qa = (d·a)² − cos²θ·|d|², qb = (d·a)(w·a) − cos²θ·(d·w), qc = (w·a)² −
    /// cos²θ·|w|².
    fn quadratic(&self, ray: &Ray) -> AxialQuadratic {
        let axis = self.base - self.apex;
        let h = axis.length();
        let a = axis / h;
        let k = self.cos2();
        let w = ray.origin - self.apex;
        let (wa, da) = (w.dot(a), ray.dir.dot(a));
        AxialQuadratic {
            h,
            wa,
            da,
            qa: da * da - k * ray.dir.length_squared(),
            qb: da * wa - k * ray.dir.dot(w),
            qc: wa * wa - k * w.length_squared(),
        }
    }

    /// A point x is inside the double cone when ((x − apex)·a)² ≥ cos²θ·|x − apex|²; substituting
    /// the ray gives a quadratic f(t) ≥ 0. The slab 0 ≤ (x − apex)·a ≤ h keeps the one nappe
    /// between apex and base.
    pub fn span(&self, ray: &Ray) -> Option<Span> {
        let (ray, s) = near_start(ray, self.far_sphere());
        started_at(self.span_from(&ray), s)
    }

    /// `far_sphere` of the cone.
    pub(crate) fn far_sphere(&self) -> (DVec3, f64) {
        far_sphere(self.apex, self.base, self.radius)
    }

    fn span_from(&self, ray: &Ray) -> Option<Span> {
        let AxialQuadratic {
            h,
            wa,
            da,
            qa,
            qb,
            qc,
        } = self.quadratic(ray);
        let slab = cap_slab(wa, da, h, APEX, BASE_CAP)?;

        // The set {t : f(t) ≥ 0} is one interval or two half-lines, depending on the sign of the
        // leading coefficient; the slab keeps at most one connected piece of the nappe.
        let pieces: [Option<Interval>; 2] = if qa == 0.0 {
            if qb == 0.0 {
                [(qc >= 0.0).then(|| Interval::everything(SIDE)), None]
            } else {
                let t = -qc / (2.0 * qb);
                let piece = if qb > 0.0 {
                    Interval {
                        t0: t,
                        f0: SIDE,
                        t1: f64::INFINITY,
                        f1: SIDE,
                    }
                } else {
                    Interval {
                        t0: f64::NEG_INFINITY,
                        f0: SIDE,
                        t1: t,
                        f1: SIDE,
                    }
                };
                [Some(piece), None]
            }
        } else if qa < 0.0 {
            match quadratic(qa, qb, qc) {
                Some((t0, t1)) => [
                    Some(Interval {
                        t0,
                        f0: SIDE,
                        t1,
                        f1: SIDE,
                    }),
                    None,
                ],
                None => [None, None],
            }
        } else {
            match quadratic(qa, qb, qc) {
                Some((t0, t1)) => [
                    Some(Interval {
                        t0: f64::NEG_INFINITY,
                        f0: SIDE,
                        t1: t0,
                        f1: SIDE,
                    }),
                    Some(Interval {
                        t0: t1,
                        f0: SIDE,
                        t1: f64::INFINITY,
                        f1: SIDE,
                    }),
                ],
                None => [Some(Interval::everything(SIDE)), None],
            }
        };
        let mut result: Option<Interval> = None;
        for piece in pieces.into_iter().flatten() {
            if let Some(cut) = piece.overlap(slab) {
                // Both pieces survive only within rounding of the apex: take their hull, since a
                // line meets a convex solid in one interval.
                result = Some(match result {
                    None => cut,
                    Some(r) => Interval {
                        t0: r.t0.min(cut.t0),
                        f0: if r.t0 <= cut.t0 { r.f0 } else { cut.f0 },
                        t1: r.t1.max(cut.t1),
                        f1: if r.t1 >= cut.t1 { r.f1 } else { cut.f1 },
                    },
                });
            }
        }
        result.map(Interval::span)
    }

    /// The open cone: where the ray crosses the side of the nappe between the apex and the base
    /// rim, the roots of f(t) = ((x − apex)·a)² − cos²θ·|x − apex|² = 0 whose height along the
    /// axis lies in [0, h): the apex belongs to the surface, the rim circle, an edge, does not
    /// (as The Ray Tracer Challenge's open cones). No inside: the span's ends are the crossings.
    pub fn open_span(&self, ray: &Ray) -> Option<Span> {
        let (ray, s) = near_start(ray, self.far_sphere());
        started_at(self.open_span_from(&ray), s)
    }

    fn open_span_from(&self, ray: &Ray) -> Option<Span> {
        let AxialQuadratic {
            h,
            wa,
            da,
            qa,
            qb,
            qc,
        } = self.quadratic(ray);
        let (t0, t1) = if qa == 0.0 {
            // Parallel to a generator: f is linear, 2·qb·t + qc = 0, one crossing (none when
            // the ray runs along the surface itself, qb = 0).
            if qb == 0.0 {
                return None;
            }
            let t = -qc / (2.0 * qb);
            (t, t)
        } else {
            quadratic(qa, qb, qc)?
        };
        let on_nappe = |t: f64| {
            let height = wa + t * da;
            (0.0..h).contains(&height)
        };
        crossings([t0, t1].map(|t| on_nappe(t).then_some(t)), SIDE)
    }

    /// Outward normal of the side: the gradient of cos²θ·|w|² − (w·a)², i.e. cos²θ·w − (w·a)·a
    /// with w = x − apex. (Seed 003 writes a different expression that is not perpendicular to
    /// the surface; this one is.) At the apex itself the normal is undefined; use −a, also
    /// within rounding of it (`APEX_REACH` of the height): there w is the rounding's own
    /// direction, which depends on how the cone was placed (a turned cone's tip faced sideways).
    pub fn normal(&self, p: DVec3, face: u8) -> DVec3 {
        let a = self.axis();
        if face == BASE_CAP {
            return a;
        }
        let w = p - self.apex;
        if w.length_squared()
            <= (APEX_REACH * APEX_REACH) * (self.base - self.apex).length_squared()
        {
            return -a;
        }
        let n = self.cos2() * w - w.dot(a) * a;
        n.try_normalize().unwrap_or(-a)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_across_the_axis_enters_and_leaves_the_side() {
        // Apex (0,2,0), base (0,0,0), radius 1: at height y the radius is (2 − y)/2.
        let cone = Cone {
            apex: DVec3::new(0.0, 2.0, 0.0),
            base: DVec3::ZERO,
            radius: 1.0,
        };
        let s = cone
            .span(&Ray::new(DVec3::new(-5.0, 1.0, 0.0), DVec3::X))
            .unwrap();
        assert!((s.t_in - 4.5).abs() < 1e-12 && (s.t_out - 5.5).abs() < 1e-12);
        let n = cone.normal(DVec3::new(0.5, 1.0, 0.0), SIDE);
        // The side rises 2 over a run of 1, so the normal is (2, 1, 0)/√5.
        assert!((n - DVec3::new(2.0, 1.0, 0.0) / 5f64.sqrt()).length() < 1e-12);
    }

    #[test]
    fn ray_up_the_axis_enters_the_base_and_leaves_at_the_apex() {
        let cone = Cone {
            apex: DVec3::new(0.0, 2.0, 0.0),
            base: DVec3::ZERO,
            radius: 1.0,
        };
        let s = cone
            .span(&Ray::new(DVec3::new(0.0, -1.0, 0.0), DVec3::Y))
            .unwrap();
        assert!((s.t_in - 1.0).abs() < 1e-12 && (s.t_out - 3.0).abs() < 1e-9);
        assert_eq!(s.face_in, BASE_CAP);
    }

    /// A 45° cone (cos²θ = ½ exactly): the ray up its axis is inside the double cone on both
    /// sides of the apex, f(t) = ½(2 − t)² ≥ 0 with a double root at the apex (t = 2), so both
    /// pieces of the nappe meet the slab [1, 2]: the span is their hull, entered through the
    /// base (t = 1) and left at the apex (t = 2).
    #[test]
    fn up_the_axis_of_a_45_degree_cone_both_pieces_meet_at_the_apex() {
        let cone = Cone {
            apex: DVec3::new(0.0, 1.0, 0.0),
            base: DVec3::ZERO,
            radius: 1.0,
        };
        assert_eq!(cone.cos2(), 0.5);
        let s = cone
            .span(&Ray::raw(DVec3::new(0.0, -1.0, 0.0), DVec3::Y))
            .unwrap();
        assert_eq!((s.t_in, s.face_in), (1.0, BASE_CAP));
        assert_eq!((s.t_out, s.face_out), (2.0, SIDE));
    }

    /// At the apex the gradient of f vanishes: the normal is taken along the axis, out of the
    /// tip (away from the base), so a ray that ends exactly on the tip still shades.
    #[test]
    fn the_normal_at_the_apex_points_out_of_the_tip() {
        let cone = Cone {
            apex: DVec3::new(0.0, 2.0, 0.0),
            base: DVec3::ZERO,
            radius: 1.0,
        };
        assert_eq!(cone.normal(cone.apex, SIDE), DVec3::Y);
    }

    /// A ray parallel to a generator of the open 45° cone (direction (1, −1, 0), the line from
    /// the apex to the rim point (1, 0, 0)) crosses the other side once: from (−1.5, 1, 0) it
    /// meets x = −(1 − y) at t = 0.75, the point (−0.75, 0.25, 0), 0.75 below the apex. There
    /// f is linear: qa = 1 − ½·2 = 0, qb = ½·1.5, qc = −½·1.5², t = −qc/(2·qb).
    #[test]
    fn a_ray_parallel_to_a_generator_crosses_the_open_cone_once() {
        let cone = Cone {
            apex: DVec3::new(0.0, 1.0, 0.0),
            base: DVec3::ZERO,
            radius: 1.0,
        };
        let ray = Ray::raw(DVec3::new(-1.5, 1.0, 0.0), DVec3::new(1.0, -1.0, 0.0));
        assert_eq!(
            cone.open_span(&ray),
            Some(Span::new(0.75, SIDE, 0.75, SIDE))
        );
        // Along the generator itself (through the apex) f is 0 everywhere: no crossing.
        let along = Ray::raw(DVec3::new(-1.0, 2.0, 0.0), DVec3::new(1.0, -1.0, 0.0));
        assert_eq!(cone.open_span(&along), None);
    }
}
