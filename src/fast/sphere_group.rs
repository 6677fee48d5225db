//! Up to four plain spheres tested against one ray side by side.
//!
//! `probe::sphere_hit` leaves most misses early, through branches that the processor guesses
//! wrong whenever a ray's fate differs from the last one's. Here the same arithmetic runs for
//! four spheres at once in four-lane vectors (`F64x4`) (the compiler does not vectorise the
//! scalar version by itself), and each test's early exits become masks, with one branch left:
//! none of the four can be hit. Every lane's t is the one `sphere_hit` gives to the last bit,
//! so a group answers exactly what testing its spheres one after another does.

use glam::DVec3;

use super::lanes::{RayLanes, LANES};
use super::simd::F64x4;
use crate::geometry::sphere::{MISS_MARGIN, MISS_TEST_FLOOR, TANGENT_TOLERANCE};
use crate::geometry::{Ray, Span, Sphere};

/// The spheres' centres and squared radii in structure-of-arrays form, one lane per sphere
/// (loaded into vectors where they are tested, as the processor's lanes are known there).
#[derive(Clone, Debug)]
pub struct SphereGroup {
    cx: [f64; LANES],
    cy: [f64; LANES],
    cz: [f64; LANES],
    r2: [f64; LANES],
    /// All ones in the lanes that hold a sphere.
    used: [f64; LANES],
    len: usize,
}

impl SphereGroup {
    /// A group of one to four spheres, tested in the order given.
    pub fn new(spheres: &[Sphere]) -> SphereGroup {
        assert!(!spheres.is_empty() && spheres.len() <= LANES);
        let lane = |f: &dyn Fn(&Sphere) -> f64, unused: f64| {
            let mut v = [unused; LANES];
            for (k, s) in spheres.iter().enumerate() {
                v[k] = f(s);
            }
            v
        };
        SphereGroup {
            cx: lane(&|s| s.center.x, 0.0),
            cy: lane(&|s| s.center.y, 0.0),
            cz: lane(&|s| s.center.z, 0.0),
            r2: lane(&|s| s.radius * s.radius, 0.0),
            used: lane(&|_| f64::from_bits(u64::MAX), 0.0),
            len: spheres.len(),
        }
    }

    /// How many spheres the group holds.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the group holds no sphere.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Sphere k's centre and r², as the group tests it.
    pub fn sphere(&self, k: usize) -> (DVec3, f64) {
        (DVec3::new(self.cx[k], self.cy[k], self.cz[k]), self.r2[k])
    }

    /// The nearest crossing with t_min < t < t_max and the sphere it belongs to: the first of
    /// the nearest, as testing the spheres in order with a shrinking limit finds it.
    #[inline(always)]
    pub fn nearest<V: F64x4>(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<(f64, usize)> {
        let t = self.candidates::<V>(ray, t_min)?;
        let mut best = None;
        let mut limit = t_max;
        for (k, &t) in t.iter().enumerate().take(self.len) {
            if t > t_min && t < limit {
                limit = t;
                best = Some((t, k));
            }
        }
        best
    }

    /// The first sphere, in order, with a crossing at t_min < t < t_max (a shadow ray's first
    /// blocker), and its t.
    #[inline(always)]
    pub fn first<V: F64x4>(&self, ray: &Ray, t_min: f64, t_max: f64) -> Option<(f64, usize)> {
        let t = self.candidates::<V>(ray, t_min)?;
        (0..self.len)
            .find(|&k| t[k] > t_min && t[k] < t_max)
            .map(|k| (t[k], k))
    }

    /// Each lane's candidate t, NaN where `Sphere::hit` returns early; None when every lane
    /// does so before the divisions and the square root (most rays, for most groups).
    #[inline(always)]
    fn candidates<V: F64x4>(&self, ray: &Ray, t_min: f64) -> Option<[f64; LANES]> {
        let (spheres, r2, used) = self.lanes::<V>();
        Some(crossings(&RayLanes::splat(ray), spheres, r2, used, t_min)?.to_array())
    }

    /// Each sphere's span along the whole line of the ray: bit for bit what `Sphere::span`
    /// gives, one sphere after another.
    #[inline(always)]
    pub fn spans<V: F64x4>(&self, ray: &Ray) -> [Option<Span>; LANES] {
        let (spheres, r2, used) = self.lanes::<V>();
        let Ok((t_in, t_out, crossed)) =
            lane_spans(&RayLanes::splat(ray), spheres, r2, used, false, false)
        else {
            return [None; LANES];
        };
        let (t_in, t_out, crossed) = (t_in.to_array(), t_out.to_array(), crossed.to_bitmask());
        std::array::from_fn(|k| {
            (crossed & (1 << k) != 0).then(|| Span::new(t_in[k], 0, t_out[k], 0))
        })
    }

    /// `spans`, for the spheres' common part searched from t = 0 on: Err when it is surely
    /// missed there (a sphere passed by, without a root, or met only behind the origin),
    /// found before the square roots, with bit k set where sphere k has no span.
    #[inline(always)]
    pub fn common_spans<V: F64x4>(&self, ray: &Ray) -> Result<[Option<Span>; LANES], u32> {
        let (spheres, r2, used) = self.lanes::<V>();
        let (t_in, t_out, crossed) =
            lane_spans(&RayLanes::splat(ray), spheres, r2, used, true, true)?;
        let (t_in, t_out, crossed) = (t_in.to_array(), t_out.to_array(), crossed.to_bitmask());
        Ok(std::array::from_fn(|k| {
            (crossed & (1 << k) != 0).then(|| Span::new(t_in[k], 0, t_out[k], 0))
        }))
    }

    /// Sphere k of the group against every ray of `rays` (the lanes in `open`): each lane's
    /// candidate t, bit for bit what `candidates` gives that ray for sphere k.
    #[inline(always)]
    pub fn sphere_against<V: F64x4>(
        &self,
        k: usize,
        rays: &RayLanes<V>,
        open: V,
        t_min: f64,
    ) -> Option<V> {
        let centre = DVec3::new(self.cx[k], self.cy[k], self.cz[k]);
        sphere_against_lanes(centre, self.r2[k], rays, open, t_min)
    }

    /// The centres, r² and the used lanes, in vectors.
    #[inline(always)]
    fn lanes<V: F64x4>(&self) -> ([V; 3], V, V) {
        let centre = [V::new(self.cx), V::new(self.cy), V::new(self.cz)];
        (centre, V::new(self.r2), V::new(self.used))
    }
}

/// One sphere (centre, r²) against every ray of `rays` (the lanes in `open`): each lane's
/// candidate t, bit for bit what `Sphere::hit` computes for that ray (NaN where it returns
/// early); None when every open lane returns early.
#[inline(always)]
pub fn sphere_against_lanes<V: F64x4>(
    centre: DVec3,
    r2: f64,
    rays: &RayLanes<V>,
    open: V,
    t_min: f64,
) -> Option<V> {
    let centre = centre.to_array().map(V::splat);
    crossings(rays, centre, V::splat(r2), open, t_min)
}

/// The steps of `Sphere::hit` (`Quadratic::new`, the two early exits, `Quadratic::roots` and
/// the choice of root), with the same operations in the same order, for four (ray, sphere)
/// pairs side by side: lane i pairs ray lane i with sphere lane i. A lane's t is NaN where
/// `Sphere::hit` returns early; None when every lane of `open` does so before the divisions
/// and the square root.
#[inline(always)]
fn crossings<V: F64x4>(
    rays: &RayLanes<V>,
    centre: [V; 3],
    r2: V,
    open: V,
    t_min: f64,
) -> Option<V> {
    let (t_in, t_out, crossed) = lane_spans(rays, centre, r2, open, t_min >= 0.0, false).ok()?;
    let t = t_in.simd_gt(V::splat(t_min)).bitselect(t_in, t_out);
    Some(crossed.bitselect(t, V::splat(f64::NAN)))
}

/// The quadratic a·t² + 2b·t + c = 0 of four (ray, sphere) pairs (lane i pairs ray lane i
/// with sphere lane i), and the tests `Sphere::span` and `Sphere::hit` make before any
/// division: the steps of `Quadratic::new` and `clearly_misses`, in the same order.
#[derive(Clone, Copy)]
pub(crate) struct LaneQuadratic<V> {
    a: V,
    b: V,
    c: V,
    /// o − centre.
    oc: [V; 3],
    dir: [V; 3],
    r2: V,
    /// All ones where the line clearly passes the sphere by.
    pub passes: V,
    /// All ones where the ray starts outside and moves away.
    pub away: V,
    /// All ones where a, b and c are finite (then a span's ends are finite and in order).
    pub finite: V,
}

impl<V: F64x4> LaneQuadratic<V> {
    #[inline(always)]
    pub(crate) fn new(rays: &RayLanes<V>, centre: [V; 3], r2: V) -> LaneQuadratic<V> {
        let [dx, dy, dz] = rays.dir;
        let a = rays.a;
        let zero = V::ZERO;
        let ox = rays.origin[0] - centre[0];
        let oy = rays.origin[1] - centre[1];
        let oz = rays.origin[2] - centre[2];
        let oc2 = ox * ox + oy * oy + oz * oz;
        let b = dx * ox + dy * oy + dz * oz;
        let c = oc2 - r2;
        let scale = b * b + a * (oc2 + r2);
        let d = b * b - a * c;
        let infinity = V::splat(f64::INFINITY);
        LaneQuadratic {
            a,
            b,
            c,
            oc: [ox, oy, oz],
            dir: rays.dir,
            r2,
            passes: scale.simd_gt(V::splat(MISS_TEST_FLOOR))
                & d.simd_lt(V::splat(-MISS_MARGIN) * scale),
            away: c.simd_gt(zero) & b.simd_gt(zero),
            finite: a.abs().simd_lt(infinity)
                & b.abs().simd_lt(infinity)
                & c.abs().simd_lt(infinity),
        }
    }

    /// disc = r² − ℓ² (ℓ the distance from the centre to the line), and all ones where it
    /// says the line has no root: the first division.
    #[inline(always)]
    pub(crate) fn disc(&self) -> (V, V) {
        let [ox, oy, oz] = self.oc;
        let [dx, dy, dz] = self.dir;
        let s = self.b / self.a;
        let (lx, ly, lz) = (ox - s * dx, oy - s * dy, oz - s * dz);
        let disc = self.r2 - (lx * lx + ly * ly + lz * lz);
        let no_root = disc.simd_lt(V::splat(-TANGENT_TOLERANCE) * self.r2);
        (disc, no_root)
    }

    /// The entry and exit t from `disc`: the square root and the last divisions.
    #[inline(always)]
    pub(crate) fn roots(&self, disc: V) -> (V, V) {
        let (a, b, c, zero) = (self.a, self.b, self.c, V::ZERO);
        let disc = disc.simd_lt(zero).bitselect(zero, disc);
        // q = −(b + sign(b)·√disc), t = q/a and c/q. (sign(b) for a NaN b does not matter:
        // q is NaN either way.)
        let root = (a * disc).sqrt();
        let sign = (b & V::splat(-0.0)) | V::ONE;
        let q = -(b + sign * root);
        let (x, y) = (q / a, c / q);
        let (q0, tangent) = (q.simd_eq(zero), disc.simd_eq(zero));
        let t_in = q0.bitselect(zero, tangent.bitselect(x, x.min(y)));
        let t_out = q0.bitselect(zero, tangent.bitselect(x, x.max(y)));
        (t_in, t_out)
    }
}

/// The steps of `Sphere::span` (and of `Sphere::hit` up to its choice of root, which also
/// leaves out lines starting outside and moving `away` when asked) for four (ray, sphere)
/// pairs: each lane's entry and exit, and all ones in the lanes of `open` whose line crosses
/// its sphere. Err when no lane of `open` does, found before the divisions and the square
/// root.
///
/// With `common` (and `away`), the spheres' common part is what counts: Err as soon as one
/// lane's line passes its sphere by, has no root, or meets it only behind the origin, before
/// the square root and the last divisions, with bit k set where lane k has no span.
#[inline(always)]
fn lane_spans<V: F64x4>(
    rays: &RayLanes<V>,
    centre: [V; 3],
    r2: V,
    open: V,
    away: bool,
    common: bool,
) -> Result<(V, V, V), u32> {
    let q = LaneQuadratic::new(rays, centre, r2);
    let away = if away { q.away } else { V::ZERO };
    // (The common part stops at the first lane behind the origin, below; a span behind the
    // origin is still a span.)
    let crossing = open & !(if common { q.passes } else { away | q.passes });
    if !common && crossing.to_bitmask() == 0 {
        return Err((open & q.passes).to_bitmask());
    }
    let (disc, no_root) = q.disc();
    if common {
        // Whether a lane has a span is known now, and `Sphere::span`'s ends are finite and in
        // order where a, b and c are finite: a lane behind the origin then lies before t = 0.
        let empty = open & (q.passes | no_root);
        let all_finite = (open & !q.finite).to_bitmask() == 0;
        if all_finite && (empty | (open & away)).to_bitmask() != 0 {
            return Err(empty.to_bitmask());
        }
    }
    let (t_in, t_out) = q.roots(disc);
    Ok((t_in, t_out, crossing & !no_root))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::lanes::lane_mask;
    use crate::fast::probe::sphere_hit;
    use crate::fast::simd::Wide;
    use proptest::prelude::*;

    fn one_by_one(spheres: &[Sphere], ray: &Ray, t_min: f64, t_max: f64) -> Option<(f64, usize)> {
        let mut best = None;
        let mut limit = t_max;
        for (k, s) in spheres.iter().enumerate() {
            if let Some(t) = sphere_hit(s, ray, t_min, limit) {
                (limit, best) = (t, Some((t, k)));
            }
        }
        best
    }

    fn first_one_by_one(
        spheres: &[Sphere],
        ray: &Ray,
        t_min: f64,
        t_max: f64,
    ) -> Option<(f64, usize)> {
        spheres
            .iter()
            .enumerate()
            .find_map(|(k, s)| sphere_hit(s, ray, t_min, t_max).map(|t| (t, k)))
    }

    /// Coordinates on a coarse grid, so that tangents, shared centres, equal distances and
    /// rays through centres come up often.
    fn coord() -> impl Strategy<Value = f64> {
        (-8i32..=8).prop_map(|k| k as f64 * 0.5)
    }

    fn sphere() -> impl Strategy<Value = Sphere> {
        (coord(), coord(), coord(), 0u32..6).prop_map(|(x, y, z, r)| Sphere {
            center: DVec3::new(x, y, z),
            radius: [0.5, 1.0, 1.5, 2.0, 1e-9, 1e7][r as usize],
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4000))]

        /// The group's nearest hit and first blocker are those of the spheres one by one, to
        /// the last bit of t.
        #[test]
        fn a_group_answers_as_its_spheres_one_by_one(
            spheres in prop::collection::vec(sphere(), 1..=LANES),
            origin in (coord(), coord(), coord()),
            aim in (coord(), coord(), coord()),
            scale_exp in -3i32..=3,
            t_min in prop::sample::select(vec![0.0, 1e-9, 0.5, f64::NEG_INFINITY]),
            t_max in prop::sample::select(vec![f64::INFINITY, 3.0, 0.25]),
        ) {
            let k = 10f64.powi(scale_exp);
            let spheres: Vec<Sphere> = spheres
                .into_iter()
                .map(|s| Sphere { center: s.center * k, radius: s.radius * k })
                .collect();
            let origin = DVec3::new(origin.0, origin.1, origin.2) * k;
            let dir = DVec3::new(aim.0 + 0.25, aim.1, aim.2 - 0.125).normalize();
            let ray = Ray { origin, dir };
            let group = SphereGroup::new(&spheres);
            let bits = |h: Option<(f64, usize)>| h.map(|(t, k)| (t.to_bits(), k));
            prop_assert_eq!(
                bits(group.nearest::<Wide>(&ray, t_min, t_max)),
                bits(one_by_one(&spheres, &ray, t_min, t_max))
            );
            prop_assert_eq!(
                bits(group.first::<Wide>(&ray, t_min, t_max)),
                bits(first_one_by_one(&spheres, &ray, t_min, t_max))
            );
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        /// One sphere of a group against four rays in lanes gives each ray, to the last bit,
        /// the t that the group gives it for that sphere (NaN for none).
        #[test]
        fn a_sphere_against_rays_in_lanes_answers_as_for_each_ray(
            spheres in prop::collection::vec(sphere(), 1..=LANES),
            rays in prop::collection::vec(((coord(), coord(), coord()), (coord(), coord(), coord())), 1..=LANES),
            t_min in prop::sample::select(vec![0.0, 1e-9, 0.5, f64::NEG_INFINITY]),
        ) {
            let group = SphereGroup::new(&spheres);
            let rays: Vec<Ray> = rays
                .into_iter()
                .map(|(o, d)| Ray {
                    origin: DVec3::new(o.0, o.1, o.2),
                    dir: DVec3::new(d.0 + 0.25, d.1, d.2 - 0.125).normalize(),
                })
                .collect();
            let lanes = RayLanes::<Wide>::new(&rays);
            let open = lane_mask::<Wide>((1 << rays.len()) - 1);
            for k in 0..spheres.len() {
                let t = group.sphere_against(k, &lanes, open, t_min).map(|t| t.to_array());
                for (i, ray) in rays.iter().enumerate() {
                    let alone = group.candidates::<Wide>(ray, t_min).map_or(f64::NAN, |t| t[k]);
                    let in_lanes = t.map_or(f64::NAN, |t| t[i]);
                    prop_assert_eq!(in_lanes.to_bits(), alone.to_bits(), "sphere {} ray {}", k, i);
                }
            }
        }
    }

    /// The lecture's tangent ray (seed 004) and a ray from inside, beside spheres it misses.
    #[test]
    fn tangent_and_inside_rays() {
        let unit = Sphere {
            center: DVec3::ZERO,
            radius: 1.0,
        };
        let far = Sphere {
            center: DVec3::new(0.0, 50.0, 0.0),
            radius: 1.0,
        };
        let group = SphereGroup::new(&[far.clone(), unit.clone()]);
        let tangent = Ray::new(DVec3::new(-3.0, 1.0, 0.0), DVec3::new(0.8, -0.6, 0.0));
        let (t, k) = group.nearest::<Wide>(&tangent, 0.0, f64::INFINITY).unwrap();
        assert_eq!(k, 1);
        assert!((t - 3.0).abs() < 1e-12);
        let inside = Ray::new(DVec3::ZERO, DVec3::X);
        assert_eq!(
            group.nearest::<Wide>(&inside, 0.0, f64::INFINITY),
            Some((1.0, 1))
        );
        assert_eq!(group.first::<Wide>(&inside, 0.0, 0.5), None);
    }
}
