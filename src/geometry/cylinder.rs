//! Finite cylinder: radius r around the segment from `base` to `top`, with caps (a solid) or
//! without them (`capped: false`, an open tube: a surface with no inside).

use glam::DVec3;

use super::{Ray, Span};

/// A finite cylinder primitive, in object space: radius `radius` around the axis from `base` to
/// `top`, closed by two caps.
#[derive(Clone, Debug, PartialEq)]
pub struct Cylinder {
    /// Centre of the base cap.
    pub base: DVec3,
    /// Centre of the top cap.
    pub top: DVec3,
    /// Radius of the side and the caps.
    pub radius: f64,
}

/// Faces: the curved side, the base cap, the top cap.
pub const SIDE: u8 = 0;
/// Face number of the cap at `base`.
pub const BASE_CAP: u8 = 1;
/// Face number of the cap at `top`.
pub const TOP_CAP: u8 = 2;

/// An interval of t with the face at each end.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Interval {
    pub t0: f64,
    pub f0: u8,
    pub t1: f64,
    pub f1: u8,
}

impl Interval {
    pub fn everything(face: u8) -> Interval {
        Interval {
            t0: f64::NEG_INFINITY,
            f0: face,
            t1: f64::INFINITY,
            f1: face,
        }
    }

    pub fn overlap(self, other: Interval) -> Option<Interval> {
        let (t0, f0) = if other.t0 > self.t0 {
            (other.t0, other.f0)
        } else {
            (self.t0, self.f0)
        };
        let (t1, f1) = if other.t1 < self.t1 {
            (other.t1, other.f1)
        } else {
            (self.t1, self.f1)
        };
        (t0 <= t1).then_some(Interval { t0, f0, t1, f1 })
    }

    pub fn span(self) -> Span {
        Span::new(self.t0, self.f0, self.t1, self.f1)
    }
}

/// The slab 0 ≤ (x − base)·a ≤ h between the two caps, with `height0 = (o − base)·a` and
/// `rate = d·a`. Leaving through the base means crossing height 0, the top height h.
pub(crate) fn cap_slab(
    height0: f64,
    rate: f64,
    h: f64,
    base_face: u8,
    top_face: u8,
) -> Option<Interval> {
    if rate == 0.0 {
        return (0.0..=h)
            .contains(&height0)
            .then(|| Interval::everything(base_face));
    }
    let (tb, tt) = (-height0 / rate, (h - height0) / rate);
    Some(if rate > 0.0 {
        Interval {
            t0: tb,
            f0: base_face,
            t1: tt,
            f1: top_face,
        }
    } else {
        Interval {
            t0: tt,
            f0: top_face,
            t1: tb,
            f1: base_face,
        }
    })
}

/// The span of a surface without inside from its crossings (the nearer first), if any.
pub(crate) fn crossings(ts: [Option<f64>; 2], face: u8) -> Option<Span> {
    match ts {
        [Some(t0), Some(t1)] => Some(Span::new(t0, face, t1, face)),
        [Some(t), None] | [None, Some(t)] => Some(Span::new(t, face, t, face)),
        [None, None] => None,
    }
}

/// Roots of a·t² + 2b·t + c = 0 in increasing order, computed stably; None when complex.
/// A surface of revolution along a ray, as a quadratic in t: qa·t² + 2·qb·t + qc, with the
/// ray's height wa + t·da along the unit axis, and the shape's height h along it.
pub(crate) struct AxialQuadratic {
    pub h: f64,
    pub wa: f64,
    pub da: f64,
    pub qa: f64,
    pub qb: f64,
    pub qc: f64,
}

pub(crate) fn quadratic(a: f64, b: f64, c: f64) -> Option<(f64, f64)> {
    let disc = b * b - a * c;
    if disc < 0.0 {
        return None;
    }
    let q = -(b + b.signum() * disc.sqrt());
    if q == 0.0 {
        return Some((0.0, 0.0));
    }
    let (x, y) = (q / a, c / q);
    Some((x.min(y), x.max(y)))
}

/// How many bounding radii from a cylinder's or cone's centre an origin may lie before the ray
/// is started nearer (`near_start`).
const FAR_RADII: f64 = 64.0;

/// Where a cylinder's or cone's quadratic is formed from a ray whose origin lies beyond
/// `FAR_RADII` of the shape's bounding sphere (`centre`, and that distance squared, `far2`):
/// the point of the ray nearest the centre, o' = o + s·d with s = −(o − centre)·d / |d|², and s
/// (roots found from o' lie at t = s + t'). From far off, qc = |w⊥|² − r² and qb² − qa·qc
/// subtract numbers of the distance's size squared, and keep few of their digits; from o' they
/// hold numbers of the shape's own size, as the sphere's r² − ℓ² does. Nearer origins (all
/// secondary rays off the shape) are kept as they are, s = None.
pub(crate) fn near_start(ray: &Ray, (centre, far2): (DVec3, f64)) -> (Ray, Option<f64>) {
    let w = ray.origin - centre;
    let d2 = ray.dir.length_squared();
    if !(w.length_squared() > far2 && d2 > 0.0) {
        return (*ray, None);
    }
    let s = -w.dot(ray.dir) / d2;
    let origin = ray.origin + s * ray.dir;
    (
        Ray {
            origin,
            dir: ray.dir,
        },
        Some(s),
    )
}

/// The bounding sphere of an axis segment from `p` to `q` with radius `r` around it (its
/// centre, the midpoint, and its radius² (|q − p|/2)² + r²), as `near_start` takes it: the
/// centre and `FAR_RADII` of that radius, squared.
pub(crate) fn far_sphere(p: DVec3, q: DVec3, r: f64) -> (DVec3, f64) {
    let centre = (p + q) * 0.5;
    let extent2 = (q - p).length_squared() * 0.25 + r * r;
    (centre, FAR_RADII * FAR_RADII * extent2)
}

/// The span found from a ray started `s` along (`near_start`), in the ray's own t.
pub(crate) fn started_at(span: Option<Span>, s: Option<f64>) -> Option<Span> {
    match (span, s) {
        (Some(span), Some(s)) => Some(Span::new(
            span.t_in + s,
            span.face_in,
            span.t_out + s,
            span.face_out,
        )),
        _ => span,
    }
}

impl Cylinder {
    /// Unit vector along the axis, from `base` towards `top`.
    pub fn axis(&self) -> DVec3 {
        (self.top - self.base).normalize()
    }

    /// The side |w⊥|² = r² along the ray: w⊥ = w − (w·a)a with w = o + t·d − base, so
    /// qa·t² + 2·qb·t + qc = 0 with qa = |d⊥|², qb = d⊥·w⊥, qc = |w⊥|² − r².
    fn quadratic(&self, ray: &Ray) -> AxialQuadratic {
        let axis = self.top - self.base;
        let h = axis.length();
        let a = axis / h;
        let w = ray.origin - self.base;
        let (wa, da) = (w.dot(a), ray.dir.dot(a));
        let (w_perp, d_perp) = (w - wa * a, ray.dir - da * a);
        AxialQuadratic {
            h,
            wa,
            da,
            qa: d_perp.length_squared(),
            qb: d_perp.dot(w_perp),
            qc: w_perp.length_squared() - self.radius * self.radius,
        }
    }

    /// Infinite cylinder |w⊥|² = r² (w⊥ = the part of o + t·d − base across the axis),
    /// clipped by the slab between the caps.
    pub fn span(&self, ray: &Ray) -> Option<Span> {
        let (ray, s) = near_start(ray, self.far_sphere());
        started_at(self.span_from(&ray), s)
    }

    /// `far_sphere` of the cylinder.
    pub(crate) fn far_sphere(&self) -> (DVec3, f64) {
        far_sphere(self.base, self.top, self.radius)
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
        let side = if qa == 0.0 {
            if qc > 0.0 {
                return None;
            }
            Interval::everything(SIDE)
        } else {
            let (t0, t1) = quadratic(qa, qb, qc)?;
            Interval {
                t0,
                f0: SIDE,
                t1,
                f1: SIDE,
            }
        };
        let caps = cap_slab(wa, da, h, BASE_CAP, TOP_CAP)?;
        side.overlap(caps).map(Interval::span)
    }

    /// The open tube: where the ray crosses the curved side between the two rims, the roots of
    /// |w⊥|² = r² whose height along the axis lies strictly between 0 and h (a ray that only
    /// touches a rim circle misses, as in The Ray Tracer Challenge). A tube has no inside, so
    /// the span is not an interval inside it: its ends are the crossings, the nearer first (one
    /// crossing twice if there is one).
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
        if qa == 0.0 {
            // Along the axis the ray never crosses the side (at most it runs in it).
            return None;
        }
        let (t0, t1) = quadratic(qa, qb, qc)?;
        let between_rims = |t: f64| {
            let height = wa + t * da;
            height > 0.0 && height < h
        };
        crossings([t0, t1].map(|t| between_rims(t).then_some(t)), SIDE)
    }

    /// Outward unit normal at point `p` on face `face` (`SIDE`, `BASE_CAP` or `TOP_CAP`).
    pub fn normal(&self, p: DVec3, face: u8) -> DVec3 {
        let a = self.axis();
        match face {
            BASE_CAP => -a,
            TOP_CAP => a,
            _ => {
                // On the axis itself (a degenerate hit of a needle-thin cylinder, found by
                // fuzzing) any direction across the axis will do; never NaN.
                let w = p - self.base;
                (w - w.dot(a) * a)
                    .try_normalize()
                    .unwrap_or_else(|| a.any_orthonormal_vector())
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The outward normals of a capped cylinder standing on the origin (axis +y, height 2,
    /// radius 1): down out of the base, up out of the top, straight out of the side.
    #[test]
    fn each_face_has_its_outward_normal() {
        let c = Cylinder {
            base: DVec3::ZERO,
            top: DVec3::new(0.0, 2.0, 0.0),
            radius: 1.0,
        };
        assert_eq!(c.normal(DVec3::new(0.5, 0.0, 0.0), BASE_CAP), -DVec3::Y);
        assert_eq!(c.normal(DVec3::new(0.5, 2.0, 0.0), TOP_CAP), DVec3::Y);
        assert_eq!(c.normal(DVec3::new(0.0, 1.0, -1.0), SIDE), -DVec3::Z);
    }

    /// Fuzzing finding (tests/fuzz/regressions/intersect-nan-normal.bin): a hit on the axis of
    /// a very thin cylinder gave a NaN normal.
    #[test]
    fn the_normal_on_the_axis_is_a_unit_vector() {
        let c = Cylinder {
            base: DVec3::ZERO,
            top: DVec3::new(0.0, 0.0, 1e6),
            radius: 1e-3,
        };
        let n = c.normal(DVec3::new(0.0, 0.0, 5.0), SIDE);
        assert!(
            (n.length() - 1.0).abs() < 1e-12 && n.dot(c.axis()).abs() < 1e-12,
            "{n}"
        );
    }
}
