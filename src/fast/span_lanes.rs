//! Spans of convex primitives along four rays at once, one ray per lane of an `F64x4`: the same
//! arithmetic as each primitive's `span`, in the same order, so every lane's ends are the
//! ray's own to the last bit. Where a primitive's scalar code would meet a NaN (degenerate
//! input) a lane is marked `odd`, for the caller to ask the scalar code instead.

use glam::{DAffine3, DVec3};

use super::lanes::RayLanes;
use super::simd::F64x4;
use super::sphere_group::LaneQuadratic;
use crate::geometry::cylinder::{BASE_CAP, SIDE, TOP_CAP};
use crate::geometry::{Aabox, Cone, Cylinder};

/// Four rays' spans through one primitive.
#[derive(Clone, Copy)]
pub struct SpanLanes<V> {
    /// Entry and exit t (NaN where a ray has no span).
    pub t_in: V,
    pub t_out: V,
    /// The faces entered and left through.
    pub face_in: V,
    pub face_out: V,
    /// All ones where the lanes cannot vouch for the scalar answer.
    pub odd: V,
}

impl<V: F64x4> SpanLanes<V> {
    /// No span for any ray.
    #[inline(always)]
    pub fn none() -> SpanLanes<V> {
        let none = V::splat(f64::NAN);
        SpanLanes {
            t_in: none,
            t_out: none,
            face_in: V::ZERO,
            face_out: V::ZERO,
            odd: V::ZERO,
        }
    }

    /// The spans in `lanes` (all ones), none elsewhere.
    #[inline(always)]
    pub fn only(self, lanes: V) -> SpanLanes<V> {
        let none = V::splat(f64::NAN);
        SpanLanes {
            t_in: lanes.bitselect(self.t_in, none),
            t_out: lanes.bitselect(self.t_out, none),
            ..self
        }
    }

    /// All ones where there is a span (neither end NaN: a NaN span is no span).
    #[inline(always)]
    pub fn exists(&self) -> V {
        self.t_in.simd_eq(self.t_in) & self.t_out.simd_eq(self.t_out)
    }
}

/// An interval of t with a face at each end, four rays at a time (`cylinder::Interval`).
#[derive(Clone, Copy)]
struct Interval<V> {
    t0: V,
    f0: V,
    t1: V,
    f1: V,
}

impl<V: F64x4> Interval<V> {
    #[inline(always)]
    fn everything(face: u8) -> Interval<V> {
        Interval {
            t0: V::splat(f64::NEG_INFINITY),
            f0: face_lanes(face),
            t1: V::splat(f64::INFINITY),
            f1: face_lanes(face),
        }
    }

    /// `where_` (all ones) ? a : b, lane by lane.
    #[inline(always)]
    fn select(where_: V, a: Interval<V>, b: Interval<V>) -> Interval<V> {
        Interval {
            t0: where_.bitselect(a.t0, b.t0),
            f0: where_.bitselect(a.f0, b.f0),
            t1: where_.bitselect(a.t1, b.t1),
            f1: where_.bitselect(a.f1, b.f1),
        }
    }

    /// `Interval::overlap`: the later start and the earlier end, `other`'s on a tie going to
    /// `self`; and all ones where the overlap is not empty.
    #[inline(always)]
    fn overlap(self, other: Interval<V>) -> (Interval<V>, V) {
        let later = other.t0.simd_gt(self.t0);
        let earlier = other.t1.simd_lt(self.t1);
        let cut = Interval {
            t0: later.bitselect(other.t0, self.t0),
            f0: later.bitselect(other.f0, self.f0),
            t1: earlier.bitselect(other.t1, self.t1),
            f1: earlier.bitselect(other.f1, self.f1),
        };
        (cut, cut.t0.simd_le(cut.t1))
    }

    #[inline(always)]
    fn span(self, exists: V, odd: V) -> SpanLanes<V> {
        SpanLanes {
            t_in: self.t0,
            t_out: self.t1,
            face_in: self.f0,
            face_out: self.f1,
            odd,
        }
        .only(exists)
    }
}

#[inline(always)]
fn face_lanes<V: F64x4>(face: u8) -> V {
    V::splat(face as f64)
}

/// All ones where x and y are both zero (of either sign): `f64::min` and the lanes' min may
/// pick different signs there.
#[inline(always)]
fn zero_tie<V: F64x4>(x: V, y: V) -> V {
    x.simd_eq(y) & x.simd_eq(V::ZERO)
}

#[inline(always)]
fn is_nan<V: F64x4>(v: V) -> V {
    v.simd_ne(v)
}

#[inline(always)]
fn splat3<V: F64x4>(v: DVec3) -> [V; 3] {
    v.to_array().map(V::splat)
}

/// [f(0), f(1), f(2)]: `std::array::from_fn`, which the compiler does not always inline into
/// the lanes' copy for the processor (`simd::with_lanes`).
#[inline(always)]
fn axes<V: F64x4>(f: impl Fn(usize) -> V) -> [V; 3] {
    [f(0), f(1), f(2)]
}

/// glam's `dot`: (x·x' + y·y') + z·z'.
#[inline(always)]
fn dot<V: F64x4>(u: [V; 3], v: [V; 3]) -> V {
    u[0] * v[0] + u[1] * v[1] + u[2] * v[2]
}

/// The quadratic of the sphere (centre, r²) along the four rays.
#[inline(always)]
pub(crate) fn sphere_quadratic<V: F64x4>(
    rays: &RayLanes<V>,
    centre: DVec3,
    r2: f64,
) -> LaneQuadratic<V> {
    LaneQuadratic::new(rays, splat3(centre), V::splat(r2))
}

/// `Sphere::span` of the sphere (centre, r²).
#[inline(always)]
pub fn sphere<V: F64x4>(rays: &RayLanes<V>, centre: DVec3, r2: f64) -> SpanLanes<V> {
    let q = sphere_quadratic(rays, centre, r2);
    let (disc, no_root) = q.disc();
    let (t_in, t_out) = q.roots(disc);
    SpanLanes {
        t_in,
        t_out,
        face_in: V::ZERO,
        face_out: V::ZERO,
        odd: V::ZERO,
    }
    .only(!(q.passes | no_root))
}

/// `Aabox::span`: the overlap of three slabs, each entered through its near face (the sign of
/// d says which); a ray parallel to a slab is inside it everywhere or nowhere.
#[inline(always)]
pub fn aabox<V: F64x4>(shape: &Aabox, rays: &RayLanes<V>) -> SpanLanes<V> {
    let zero = V::ZERO;
    let mut span = Interval::everything(0);
    let mut outside = zero;
    for axis in 0..3 {
        let (o, d) = (rays.origin[axis], rays.dir[axis]);
        let (lo, hi) = (V::splat(shape.min[axis]), V::splat(shape.max[axis]));
        let parallel = d.simd_eq(zero);
        outside |= parallel & (o.simd_lt(lo) | o.simd_gt(hi));
        let (t0, t1) = ((lo - o) / d, (hi - o) / d);
        let (f0, f1) = (face_lanes(2 * axis as u8), face_lanes(2 * axis as u8 + 1));
        let negative = d.simd_lt(zero);
        let (t0, t1, f0, f1) = (
            negative.bitselect(t1, t0),
            negative.bitselect(t0, t1),
            negative.bitselect(f1, f0),
            negative.bitselect(f0, f1),
        );
        let enters = !parallel & t0.simd_gt(span.t0);
        (span.t0, span.f0) = (enters.bitselect(t0, span.t0), enters.bitselect(f0, span.f0));
        let leaves = !parallel & t1.simd_lt(span.t1);
        (span.t1, span.f1) = (leaves.bitselect(t1, span.t1), leaves.bitselect(f1, span.f1));
    }
    span.span(!outside & span.t0.simd_le(span.t1), zero)
}

/// `cylinder::quadratic`: the roots of a·t² + 2b·t + c = 0 in increasing order, all ones
/// where they are real, and the odd lanes.
#[inline(always)]
fn quadratic<V: F64x4>(a: V, b: V, c: V) -> (V, V, V, V) {
    let zero = V::ZERO;
    let disc = b * b - a * c;
    let real = !disc.simd_lt(zero);
    let sign = (b & V::splat(-0.0)) | V::ONE;
    let q = -(b + sign * disc.sqrt());
    let (x, y) = (q / a, c / q);
    let q0 = q.simd_eq(zero);
    let t0 = q0.bitselect(zero, x.min(y));
    let t1 = q0.bitselect(zero, x.max(y));
    // NaN roots (overflow), and roots that tie at zero (±0: `f64::min` and the lanes' min may
    // pick different signs) are odd.
    let odd = real & !q0 & (is_nan(x) | is_nan(y) | zero_tie(x, y));
    (t0, t1, real, odd)
}

/// `cylinder::cap_slab`: the slab 0 ≤ height ≤ h, with height0 at t = 0 and changing at `rate`
/// per unit t; and all ones where it is not empty.
#[inline(always)]
fn cap_slab<V: F64x4>(
    height0: V,
    rate: V,
    h: f64,
    base_face: u8,
    top_face: u8,
) -> (Interval<V>, V) {
    let (zero, h) = (V::ZERO, V::splat(h));
    let flat = rate.simd_eq(zero);
    let (tb, tt) = (-height0 / rate, (h - height0) / rate);
    let (base, top) = (face_lanes(base_face), face_lanes(top_face));
    let rising = rate.simd_gt(zero);
    let slab = Interval {
        t0: rising.bitselect(tb, tt),
        f0: rising.bitselect(base, top),
        t1: rising.bitselect(tt, tb),
        f1: rising.bitselect(top, base),
    };
    let within = height0.simd_ge(zero) & height0.simd_le(h);
    (
        Interval::select(flat, Interval::everything(base_face), slab),
        !flat | within,
    )
}

/// `cylinder::near_start` for four rays: the origins each quadratic is formed from, the s
/// each lies at along its ray, and all ones where an origin was moved there.
#[inline(always)]
fn near_start<V: F64x4>(rays: &RayLanes<V>, (centre, far2): (DVec3, f64)) -> ([V; 3], V, V) {
    let c = splat3(centre);
    let w: [V; 3] = axes(|k| rays.origin[k] - c[k]);
    let far = dot(w, w).simd_gt(V::splat(far2));
    // The usual: every origin near (secondary rays, an eye a few sizes away).
    if !far.any() {
        return (rays.origin, V::ZERO, far);
    }
    let d2 = dot(rays.dir, rays.dir);
    let far = far & d2.simd_gt(V::ZERO);
    let s = -dot(w, rays.dir) / d2;
    let origin = axes(|k| far.bitselect(rays.origin[k] + s * rays.dir[k], rays.origin[k]));
    (origin, s, far)
}

/// `cylinder::started_at`: the interval found from origins moved by s (where `far`), in the
/// rays' own t.
#[inline(always)]
fn started_at<V: F64x4>(cut: Interval<V>, s: V, far: V) -> Interval<V> {
    if !far.any() {
        return cut;
    }
    Interval {
        t0: far.bitselect(cut.t0 + s, cut.t0),
        t1: far.bitselect(cut.t1 + s, cut.t1),
        ..cut
    }
}

/// `Cylinder::span`: the infinite cylinder |w⊥|² = r² clipped by the slab between the caps.
#[inline(always)]
pub fn cylinder<V: F64x4>(shape: &Cylinder, rays: &RayLanes<V>) -> SpanLanes<V> {
    let (origin, s, far) = near_start(rays, shape.far_sphere());
    let axis = shape.top - shape.base;
    let h = axis.length();
    let a = splat3(axis / h);
    let base = splat3(shape.base);
    let w: [V; 3] = axes(|k| origin[k] - base[k]);
    let (wa, da) = (dot(w, a), dot(rays.dir, a));
    let w_perp: [V; 3] = axes(|k| w[k] - wa * a[k]);
    let d_perp: [V; 3] = axes(|k| rays.dir[k] - da * a[k]);
    let qa = dot(d_perp, d_perp);
    let qc = dot(w_perp, w_perp) - V::splat(shape.radius * shape.radius);
    let parallel = qa.simd_eq(V::ZERO);
    let (t0, t1, real, roots_odd) = quadratic(qa, dot(d_perp, w_perp), qc);
    let roots = Interval {
        t0,
        f0: face_lanes(SIDE),
        t1,
        f1: face_lanes(SIDE),
    };
    let side = Interval::select(parallel, Interval::everything(SIDE), roots);
    let side_exists = parallel.bitselect(!qc.simd_gt(V::ZERO), real);
    let (caps, caps_exist) = cap_slab(wa, da, h, BASE_CAP, TOP_CAP);
    let (cut, overlaps) = side.overlap(caps);
    let odd = is_nan(qa) | is_nan(qc) | is_nan(wa) | is_nan(da) | (!parallel & roots_odd);
    started_at(cut, s, far).span(side_exists & caps_exist & overlaps, odd)
}

/// `Cone::span`: where f(t) = ((x − apex)·a)² − cos²θ·|x − apex|² ≥ 0 (one interval or two
/// half-lines), within the slab between apex and base; the hull of the pieces that survive.
#[inline(always)]
pub fn cone<V: F64x4>(shape: &Cone, rays: &RayLanes<V>) -> SpanLanes<V> {
    let zero = V::ZERO;
    let (origin, s, far) = near_start(rays, shape.far_sphere());
    let axis = shape.base - shape.apex;
    let h = axis.length();
    let a = splat3(axis / h);
    let k = V::splat(shape.cos2());
    let apex = splat3(shape.apex);
    let w: [V; 3] = axes(|i| origin[i] - apex[i]);
    let (wa, da) = (dot(w, a), dot(rays.dir, a));
    let qa = da * da - k * dot(rays.dir, rays.dir);
    let qb = da * wa - k * dot(rays.dir, w);
    let qc = wa * wa - k * dot(w, w);
    let (slab, slab_exists) = cap_slab(wa, da, h, SIDE, BASE_CAP);

    let side = |t0: V, t1: V| Interval {
        t0,
        f0: face_lanes(SIDE),
        t1,
        f1: face_lanes(SIDE),
    };
    let (infinity, minus_infinity) = (V::splat(f64::INFINITY), V::splat(f64::NEG_INFINITY));
    // qa = 0: f is linear (or constant).
    let constant = qb.simd_eq(zero);
    let t = -qc / (V::splat(2.0) * qb);
    let rising = qb.simd_gt(zero);
    let linear = side(
        rising.bitselect(t, minus_infinity),
        rising.bitselect(infinity, t),
    );
    let linear_piece = Interval::select(constant, Interval::everything(SIDE), linear);
    let linear_exists = !constant | qc.simd_ge(zero);
    // qa ≠ 0: a quadratic; below zero one interval, otherwise two half-lines (or all of it).
    let (r0, r1, real, roots_odd) = quadratic(qa, qb, qc);
    let opens_down = qa.simd_lt(zero);
    let first = Interval::select(
        opens_down,
        side(r0, r1),
        Interval::select(real, side(minus_infinity, r0), Interval::everything(SIDE)),
    );
    let first_exists = !opens_down | real;
    let second = side(r1, infinity);
    let second_exists = !opens_down & real;
    let linear_lanes = qa.simd_eq(zero);
    let piece0 = Interval::select(linear_lanes, linear_piece, first);
    let piece0_exists = linear_lanes.bitselect(linear_exists, first_exists);
    let piece1_exists = !linear_lanes & second_exists;

    let (cut0, in0) = piece0.overlap(slab);
    let (cut1, in1) = second.overlap(slab);
    let (in0, in1) = (piece0_exists & in0, piece1_exists & in1);
    // Both pieces survive only within rounding of the apex: their hull.
    let hull = Interval {
        t0: cut0.t0.min(cut1.t0),
        f0: cut0.t0.simd_le(cut1.t0).bitselect(cut0.f0, cut1.f0),
        t1: cut0.t1.max(cut1.t1),
        f1: cut0.t1.simd_ge(cut1.t1).bitselect(cut0.f1, cut1.f1),
    };
    let result = Interval::select(in0 & in1, hull, Interval::select(in0, cut0, cut1));
    let odd = is_nan(qa)
        | is_nan(qb)
        | is_nan(qc)
        | is_nan(wa)
        | is_nan(da)
        | (linear_lanes & !constant & is_nan(t))
        | (!linear_lanes & roots_odd)
        | (in0 & in1 & (is_nan(cut0.t0) | is_nan(cut1.t0) | is_nan(cut0.t1) | is_nan(cut1.t1)))
        // Ends that tie at zero in the hull (±0 again).
        | (in0 & in1 & zero_tie(cut0.t0, cut1.t0))
        | (in0 & in1 & zero_tie(cut0.t1, cut1.t1));
    started_at(result, s, far).span(slab_exists & (in0 | in1), odd)
}

/// `Transform::ray_to_local` for four rays: the same products and sums as glam's
/// `transform_point3` and `transform_vector3`, in the same order.
#[inline(always)]
pub fn to_local<V: F64x4>(rays: &RayLanes<V>, m: &DAffine3) -> RayLanes<V> {
    let (x, y, z) = (
        splat3::<V>(m.matrix3.x_axis),
        splat3::<V>(m.matrix3.y_axis),
        splat3::<V>(m.matrix3.z_axis),
    );
    let t = splat3::<V>(m.translation);
    let [ox, oy, oz] = rays.origin;
    let [dx, dy, dz] = rays.dir;
    let origin: [V; 3] = axes(|c| x[c] * ox + y[c] * oy + z[c] * oz + t[c]);
    let dir: [V; 3] = axes(|c| x[c] * dx + y[c] * dy + z[c] * dz);
    RayLanes::from_lanes(origin, dir)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::simd::Wide;
    use crate::geometry::{Ray, Shape, Span};
    use proptest::prelude::*;

    /// A span as (t_in bits, face_in, t_out bits, face_out); None: no span.
    type Bits = Option<(u64, u8, u64, u8)>;

    /// Each lane's span where the lanes vouch for it, and nothing for an odd lane.
    fn lane_spans(s: &SpanLanes<Wide>) -> [Option<Bits>; 4] {
        let (t_in, t_out) = (s.t_in.to_array(), s.t_out.to_array());
        let (f_in, f_out) = (s.face_in.to_array(), s.face_out.to_array());
        let (exists, odd) = (s.exists().to_bitmask(), s.odd.to_bitmask());
        std::array::from_fn(|i| {
            (odd & (1 << i) == 0).then(|| {
                (exists & (1 << i) != 0).then(|| {
                    (
                        t_in[i].to_bits(),
                        f_in[i] as u8,
                        t_out[i].to_bits(),
                        f_out[i] as u8,
                    )
                })
            })
        })
    }

    fn scalar(span: Option<Span>) -> Bits {
        // A NaN span is no span, as the CSG evaluation reads it.
        span.filter(|s| !s.t_in.is_nan() && !s.t_out.is_nan())
            .map(|s| (s.t_in.to_bits(), s.face_in, s.t_out.to_bits(), s.face_out))
    }

    /// Cones of 45° (cos²θ = ½ exactly) and steeper, cylinders and boxes on a grid, and
    /// rays from grid points and from the apex along small integer directions, unnormalised:
    /// rays along the cone's generators (a linear f), through its apex (both nappes meet), along
    /// the axis, parallel to caps and faces.
    fn shape() -> impl Strategy<Value = Shape> {
        let grid = || (-2i32..=2).prop_map(|k| k as f64 * 0.5);
        let p = move || (grid(), grid(), grid()).prop_map(|(x, y, z)| DVec3::new(x, y, z));
        let axis = prop::sample::select(vec![DVec3::Y, DVec3::X, DVec3::new(0.0, 1.0, 1.0)]);
        prop_oneof![
            (
                p(),
                axis.clone(),
                prop::sample::select(vec![1.0, 2.0]),
                0.5..1.5f64
            )
                .prop_map(|(apex, axis, h, r)| Shape::Cone(Cone {
                    apex,
                    base: apex - h * axis,
                    radius: if h == 1.0 { 1.0 } else { r },
                })),
            (p(), axis, prop::sample::select(vec![0.5, 1.0])).prop_map(|(base, axis, r)| {
                Shape::Cylinder(Cylinder {
                    base,
                    top: base + 2.0 * axis,
                    radius: r,
                })
            }),
            (p(), prop::array::uniform3(1i32..=3)).prop_map(|(c, e)| {
                let e = DVec3::from_array(e.map(|k| k as f64 * 0.5));
                Shape::Box(Aabox {
                    min: c - e,
                    max: c + e,
                })
            }),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 3000, ..ProptestConfig::default() })]

        #[test]
        fn lanes_give_each_rays_own_span_to_the_bit(
            shape in shape(),
            rays in prop::collection::vec(
                (prop::array::uniform3(-4i32..=4), prop::bool::ANY, prop::array::uniform3(-2i32..=2)),
                4,
            ),
        ) {
            let apex = match &shape {
                Shape::Cone(c) => c.apex,
                Shape::Cylinder(c) => c.base,
                _ => DVec3::ZERO,
            };
            let rays: Vec<Ray> = rays
                .iter()
                .map(|(o, at_apex, d)| {
                    let origin = if *at_apex {
                        apex
                    } else {
                        DVec3::from_array(o.map(|k| k as f64 * 0.5))
                    };
                    let d = DVec3::from_array(d.map(f64::from));
                    Ray::raw(origin, if d == DVec3::ZERO { DVec3::Z } else { d })
                })
                .collect();
            let lanes = RayLanes::<Wide>::new(&rays);
            let spans = match &shape {
                Shape::Cone(c) => cone(c, &lanes),
                Shape::Cylinder(c) => cylinder(c, &lanes),
                Shape::Box(b) => aabox(b, &lanes),
                _ => unreachable!(),
            };
            for (ray, lane) in rays.iter().zip(lane_spans(&spans)) {
                if let Some(lane) = lane {
                    prop_assert_eq!(lane, scalar(shape.span(ray)), "{:?}", ray);
                }
            }
        }
    }

    /// The degenerate cone cases the grid reaches exactly: a ray along a generator (f linear)
    /// and one from the apex along a generator (f constant), in the lanes as in `Cone::span`;
    /// and two rays through the apex, where both nappes survive: the one along the axis meets
    /// them at t = ±0, which the lanes leave to the scalar code; the other, at t = 1, gets
    /// their hull.
    #[test]
    fn rays_along_a_cones_generators_are_the_scalar_spans() {
        let cone_45 = Cone {
            apex: DVec3::new(0.0, 1.0, 0.0),
            base: DVec3::ZERO,
            radius: 1.0,
        };
        let rays = [
            Ray::raw(DVec3::new(-2.0, 0.5, 0.0), DVec3::new(1.0, 1.0, 0.0)),
            Ray::raw(DVec3::new(0.0, 1.0, 0.0), DVec3::new(1.0, -1.0, 0.0)),
            Ray::raw(DVec3::new(0.0, 1.0, 0.0), DVec3::new(0.0, -1.0, 0.0)),
            Ray::raw(DVec3::new(-1.0, 3.0, 0.0), DVec3::new(1.0, -2.0, 0.0)),
        ];
        let spans = cone(&cone_45, &RayLanes::<Wide>::new(&rays));
        let lanes = lane_spans(&spans);
        assert_eq!(spans.odd.to_bitmask(), 0b0100);
        for (ray, lane) in rays.iter().zip(lanes) {
            if let Some(lane) = lane {
                assert_eq!(lane, scalar(cone_45.span(ray)), "{ray:?}");
            }
        }
    }
}
