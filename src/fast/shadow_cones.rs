//! Which shadow rays toward a point light can pass through an object's box, told from their
//! directions alone.
//!
//! Seen from a point light at L, an object whose box lies in a ball of centre c and radius r
//! fills a cone of directions around w = c − L, of half-angle asin(r/|w|). A shadow ray runs
//! from its surface to the light: back from L, it goes along −l. Where −l points outside the
//! cone, the ray cannot meet the ball, nor the box inside it, and the box's slab test (six
//! subtractions, six products, and the ray's three divisions for 1/d) is sure to answer
//! "missed": the lanes skip it and count the box missed, as the slab test would. The test is
//! one dot product a ray, with the distance from c to the line back from L along −l:
//!
//! ```text
//!     l·w ≥ 0             the line leaves L away from c: its nearest point to c is L itself
//!     (l·w)² < |w|² − R²  it passes c farther than R   (the square of its distance from c
//!                         is |w|² − (l·w)², with |l| = 1)
//! ```
//!
//! and the ray missed where |w| > R and either holds. R is the ball's radius grown by what
//! separates the computed ray from that line: its origin is the surface point moved off by the
//! bias b and its end, origin + reach·l, lies within 2b of L; and every step rounds (each
//! margin below is 10³ to 10⁶ times the few ulps the coordinates can be off by).

use glam::DVec3;

use super::simd::F64x4;
use crate::accel::Aabb;

/// An object's ball as seen from one light.
#[derive(Clone, Copy, Debug)]
pub struct Cone {
    /// w = c − L.
    w: DVec3,
    /// |w|².
    w2: f64,
    /// The ball's radius with the margin for the test's own rounding (each ray adds its own
    /// slack).
    radius: f64,
}

impl Cone {
    /// The cone of `bounds` seen from a light at `light`, where the light is clearly outside
    /// its ball (a light inside, or a box without finite bounds, leaves every ray to the slab
    /// test).
    pub fn new(light: DVec3, bounds: &Aabb) -> Option<Cone> {
        let (centre, r) = Cone::ball(bounds);
        let w = centre - light;
        let distance = w.length();
        let radius = r
            + 1e-6 * (r + distance)
            + 1e-9 * (centre.abs().element_sum() + light.abs().element_sum());
        (radius.is_finite() && distance.is_finite() && distance > radius * (1.0 + 1e-6)).then(
            || Cone {
                w,
                w2: w.length_squared(),
                radius,
            },
        )
    }

    /// The ball around a box: its centre, and half its diagonal.
    fn ball(bounds: &Aabb) -> (DVec3, f64) {
        (
            (bounds.min + bounds.max) / 2.0,
            (bounds.max - bounds.min).length() / 2.0,
        )
    }

    /// The lanes whose shadow ray, of unit direction l (axis by axis in lanes), strays by up to
    /// `slack` (as the function `slack` finds it) from the line back from the light and cannot
    /// meet the ball. A lane whose l or slack is NaN is never among them.
    #[inline(always)]
    pub fn missed_by<V: F64x4>(&self, [lx, ly, lz]: &[V; 3], slack: V) -> u32 {
        let dot = *lx * V::splat(self.w.x) + *ly * V::splat(self.w.y) + *lz * V::splat(self.w.z);
        let r = V::splat(self.radius) + slack;
        let gap = V::splat(self.w2) - r * r;
        let away = dot.simd_ge(V::ZERO);
        let wide = (dot * dot).simd_lt(gap);
        (gap.simd_gt(V::ZERO) & (away | wide)).to_bitmask()
    }
}

/// How far a computed shadow ray may stray from the line back from the light along −l: twice
/// the bias `b` it was moved off its surface by (the ray's end, origin + reach·l, is the
/// surface point p plus b·(±n − l) past the light's distance), and 10⁻⁹ of p's coordinates
/// and of the light's distance `d` for the rounding of the origin, of l and of reach.
#[inline(always)]
pub fn slack<V: F64x4>(b: V, [px, py, pz]: &[V; 3], d: V) -> V {
    let size = px.abs() + py.abs() + pz.abs() + d;
    (b + b) + V::splat(1e-9) * size
}

/// The cones of a scene's objects tested behind their boxes, seen from one point light, by
/// the objects' probe numbers (none for the other probes).
#[derive(Clone, Debug, Default)]
pub struct ShadowCones {
    pub by_probe: Vec<Option<Cone>>,
}

/// Shadow rays in lanes toward one light: its cones, and the rays' directions and slack.
pub struct TowardLight<'a, V> {
    pub cones: &'a ShadowCones,
    pub l: [V; 3],
    pub slack: V,
}

impl<V: F64x4> TowardLight<'_, V> {
    /// The lanes whose ray surely misses the box of probe `k` (none where it has no cone).
    #[inline(always)]
    pub fn missed(&self, k: usize) -> u32 {
        match self.cones.by_probe.get(k) {
            Some(Some(cone)) => cone.missed_by(&self.l, self.slack),
            _ => 0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::SlabRay;
    use crate::fast::simd::{with_lanes, Wide};
    use crate::scene::{parse, Interaction, Limits, Scene};
    use crate::trace::whitted::shadow_reach;
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64;

    /// The shadow ray from p, whose surface faces along n, toward the light, as the core casts
    /// it (`Scene::offset` from the point itself, `shadow_reach`) with the scene's bias, and l
    /// and d found as `light_lanes::toward` finds them. Returns the ray's origin, l, reach,
    /// and its slack.
    fn shadow_ray(scene: &Scene, p: DVec3, n: DVec3, light: DVec3) -> (DVec3, DVec3, f64, f64) {
        let t = light - p;
        let d = (t.x * t.x + t.y * t.y + t.z * t.z).sqrt();
        let l = t * (1.0 / d);
        let si = Interaction {
            point: p,
            normal: n,
            ..Interaction::default()
        };
        let (origin, b) = scene.offset(&si, l);
        let reach = shadow_reach(d, b);
        let slack = slack(
            Wide::splat(b),
            &p.to_array().map(Wide::splat),
            Wide::splat(d),
        );
        (origin, l, reach, slack.to_array()[0])
    }

    fn unit(rng: &mut Pcg64) -> DVec3 {
        loop {
            let v = DVec3::new(rng.random(), rng.random(), rng.random()) * 2.0 - 1.0;
            if (1e-3..=1.0).contains(&v.length_squared()) {
                return v.normalize();
            }
        }
    }

    /// A point of the box's surface (each coordinate inside, or on a face: an edge or a corner
    /// as often as a face), nudged in or out by 10⁻¹⁶ to 10⁻⁶ of the box's size.
    fn toward_the_surface(rng: &mut Pcg64, bounds: &Aabb, size: f64) -> DVec3 {
        let mut q = bounds.min + (bounds.max - bounds.min) * rng.random::<f64>();
        for axis in 0..3 {
            if rng.random_bool(0.5) {
                q[axis] = if rng.random_bool(0.5) {
                    bounds.min[axis]
                } else {
                    bounds.max[axis]
                };
            }
        }
        q + unit(rng) * 10f64.powi(rng.random_range(-16..=-6)) * size
    }

    /// A point where a line from the light grazes the box's ball (radius: half the diagonal):
    /// on the ball's outline as the light sees it, turned out or in by a relative 10⁻¹⁶ to
    /// 10⁻² of the cone's half-angle.
    fn along_the_cone(rng: &mut Pcg64, bounds: &Aabb, light: DVec3) -> DVec3 {
        let (centre, r) = Cone::ball(bounds);
        let w = centre - light;
        let across = w.cross(unit(rng)).normalize();
        let turn = 1.0 + rng.random_range(-1.0..1.0) * 10f64.powi(rng.random_range(-16..=-2));
        let half_angle = (r / w.length()).asin() * turn;
        let dir = w.normalize() * half_angle.cos() + across * half_angle.sin();
        light + dir * w.length()
    }

    /// The distance from c to the segment from o along l for 0 ≤ t ≤ reach.
    fn segment_distance(c: DVec3, o: DVec3, l: DVec3, reach: f64) -> f64 {
        let t = ((c - o).dot(l) / l.length_squared()).clamp(0.0, reach);
        (c - (o + t * l)).length()
    }

    fn missed<V: F64x4>(cone: &Cone, l: DVec3, slack: f64) -> bool {
        cone.missed_by::<V>(&l.to_array().map(V::splat), V::splat(slack)) & 1 != 0
    }

    /// Wherever a cone says a shadow ray misses the box, the box's slab test (the core's
    /// `Aabb::hit_slabs`, which the lanes repeat bit for bit) says so too. The rays graze on
    /// purpose: each is aimed from the light at a point near the box's surface, or along the
    /// edge of the cone, and starts beyond it; boxes from 10⁻⁶ to 10⁶ across, up to 10⁶ sizes
    /// from the origin, flat ones among them, with the scene's bias or the automatic one.
    #[test]
    fn a_cone_misses_only_where_the_slab_test_misses() {
        let yaml = "camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nobjects: []\n";
        let mut scene = parse(yaml, "cones.yaml", None, &Limits::default()).unwrap();
        let mut rng = Pcg64::seed_from_u64(31);
        let (mut culled, mut hit, mut rays) = (0, 0, 0);
        for _ in 0..4000 {
            let size = 10f64.powi(rng.random_range(-6..=6));
            let centre = unit(&mut rng) * size * 10f64.powi(rng.random_range(-3..=6));
            let mut half = DVec3::new(rng.random(), rng.random(), rng.random()) * size;
            if rng.random_bool(0.2) {
                half[rng.random_range(0..3)] = 0.0;
            }
            let bounds = Aabb::new(centre - half, centre + half);
            let light = centre + unit(&mut rng) * size * rng.random_range(1.5..30.0);
            let Some(cone) = Cone::new(light, &bounds) else {
                continue;
            };
            scene.shadow_bias = match rng.random_range(0..3) {
                0 => None,
                1 => Some(size * 10f64.powi(rng.random_range(-12..=-3))),
                _ => Some(0.0),
            };
            for k in 0..16 {
                let q = if k % 2 == 0 {
                    toward_the_surface(&mut rng, &bounds, size)
                } else {
                    along_the_cone(&mut rng, &bounds, light)
                };
                let p = light + (q - light) * rng.random_range(1.001..4.0);
                let (origin, l, reach, slack) = shadow_ray(&scene, p, unit(&mut rng), light);
                let slabs = SlabRay::new(origin, l.recip());
                let through = bounds.hit_slabs(&slabs, 0.0, reach);
                let wide = missed::<Wide>(&cone, l, slack);
                assert_eq!(with_lanes!(V => missed::<V>(&cone, l, slack)), wide);
                // Stronger: the ray's whole segment stays out of the ball itself.
                if wide {
                    let ball = Cone::ball(&bounds);
                    let gap = segment_distance(ball.0, origin, l, reach) - ball.1;
                    assert!(
                        gap > 0.0,
                        "the ray passes {gap} inside the ball: {origin} {l}"
                    );
                }
                assert!(
                    !(wide && through),
                    "the cone {cone:?} misses a ray the slab test passes: origin {origin}, \
                     l {l}, reach {reach}, slack {slack}, box {bounds:?}"
                );
                rays += 1;
                culled += wide as u32;
                hit += through as u32;
            }
        }
        // Both answers are common: the test is not decided by one side alone.
        assert!(
            culled > rays / 50 && hit > rays / 10,
            "{culled} culled, {hit} hit of {rays}"
        );
    }

    /// The cone's answer for the plain cases the notes would draw: a unit box 10 units from
    /// the light, a ray straight at it, one 45° off, one pointing away; and no cone where the
    /// light is inside the box's ball, or the box has no finite bounds.
    #[test]
    fn a_cone_seen_from_a_light() {
        let bounds = Aabb::new(DVec3::splat(-0.5), DVec3::splat(0.5));
        let light = DVec3::new(0.0, 10.0, 0.0);
        let cone = Cone::new(light, &bounds).expect("a light far outside");
        // l points from the surface to the light: straight down from the light is l = +y.
        assert!(!missed::<Wide>(&cone, DVec3::Y, 0.0));
        assert!(missed::<Wide>(
            &cone,
            DVec3::new(1.0, 1.0, 0.0).normalize(),
            0.0
        ));
        assert!(missed::<Wide>(&cone, -DVec3::Y, 0.0));
        // Just outside the ball of radius √3/2 at distance 10 (sin θ = 0.0866): 5.2° off
        // misses, 4.8° off does not.
        let off = |deg: f64| DVec3::new(deg.to_radians().sin(), deg.to_radians().cos(), 0.0);
        assert!(missed::<Wide>(&cone, off(5.2), 0.0));
        assert!(!missed::<Wide>(&cone, off(4.8), 0.0));
        // A slack of 0.2 grows the ball to 1.066 (6.1°): 5.8° off is then inside it.
        assert!(missed::<Wide>(&cone, off(5.8), 0.0));
        assert!(!missed::<Wide>(&cone, off(5.8), 0.2));
        assert!(!missed::<Wide>(&cone, DVec3::NAN, 0.0));
        assert!(Cone::new(DVec3::new(0.0, 0.8, 0.0), &bounds).is_none());
        assert!(Cone::new(light, &Aabb::new(DVec3::NEG_INFINITY, DVec3::ONE)).is_none());
    }
}
