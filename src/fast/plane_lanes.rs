//! A plane's surfaces shaded four at a time from hit to light, without a shading record: the
//! usual floor (a plane without a transform, of a plain or checkered material that sends no
//! rays on) in a scene whose objects are tested four rays at a time and whose lights the lanes
//! take (`light_lanes`). Each lane does what the core does for its surface, in the same order:
//!
//! ```text
//! p = o + t·d                                   (`Ray::at`)
//! leaving = n·d > 10⁻⁹,  N = −n if leaving, else n   (`Scene::record_surface`)
//! O = the checker's A or B at p, or the colour      (`checker_lanes`)
//! I = ka·Ia·O + Σ_ℓ s·(diffuse + specular)           (`light_lanes`, shadow rays in lanes)
//! ```
//!
//! so every colour and counter is the core's to the bit. Where a light is at the point or at
//! no finite distance from it, the surfaces are left to the packet's usual shading.

use glam::DVec3;

use super::checker_lanes::even_cells_of;
use super::lanes::{lane_mask, LANES};
use super::light_lanes::{axes, lanes, lanes_light, GroupLit, LaneHighlight, Surfaces};
use super::search::FastScene;
use super::simd::F64x4;
use crate::geometry::{Ray, Shape};
use crate::scene::{Geometry, Hit, Scene, TANGENT_COSINE};
use crate::trace::Tracer;

/// The most planes of a scene the lanes shade (the first ones).
pub(super) const MOST_PLANES: usize = 4;

/// A plane leaf the lanes shade, and what its material gives every point of it.
#[derive(Clone, Debug)]
pub(super) struct LanePlane {
    leaf: u32,
    object: u32,
    /// The plane's outward unit normal n.
    normal: DVec3,
    /// Whether the plane is a solid half-space (a ray from behind it is inside).
    solid: bool,
    /// The checker's colours A and B, or the material's colour twice.
    colors: [DVec3; 2],
    checkered: bool,
    /// ka·Ia, the ambient term's factor of O.
    ka_ia: DVec3,
    kd: f64,
    ks: f64,
    /// The highlight's exponent m (0 where ks ≤ 0), and whether it is Blinn's.
    exponent: u32,
    blinn: bool,
}

impl LanePlane {
    /// The planes of `scene` the lanes shade: leaves that are a whole object's plane, without
    /// a transform, whose material sends no rays on and has at most a checker of two colours
    /// (`checkers`, by material) and a whole highlight exponent (`highlights`, by material).
    /// Only for a scene whose every light the lanes take (`lights_in_lanes`).
    pub fn of_scene(
        scene: &Scene,
        checkers: &[Option<[DVec3; 2]>],
        highlights: &[LaneHighlight],
    ) -> Vec<LanePlane> {
        let mut planes = vec![];
        for (object, o) in scene.objects.iter().enumerate() {
            let Geometry::Leaf(leaf) = o.geometry else {
                continue;
            };
            let l = &scene.leaves[leaf as usize];
            let (Shape::Plane(plane), None) = (&l.shape, &l.transform) else {
                continue;
            };
            let m = &scene.materials[l.material as usize];
            let checker = checkers[l.material as usize];
            let highlight = highlights[l.material as usize];
            let plain = m.patterns.is_none();
            let sends_rays = m.kr > 0.0 || m.kt > 0.0;
            let exponent = if m.ks > 0.0 { highlight.whole } else { Some(0) };
            let (Some(exponent), false, false) = (exponent, sends_rays, highlight.transmitted)
            else {
                continue;
            };
            if !plain && checker.is_none() {
                continue;
            }
            if planes.len() == MOST_PLANES {
                break;
            }
            planes.push(LanePlane {
                leaf,
                object: object as u32,
                normal: plane.normal,
                solid: l.shape.is_solid(),
                colors: checker.unwrap_or([m.color; 2]),
                checkered: checker.is_some(),
                ka_ia: m.ka * scene.ambient,
                kd: m.kd,
                ks: m.ks,
                exponent,
                blinn: highlight.blinn,
            });
        }
        planes
    }

    /// Whether the hit is on this plane (as a whole object: not flipped).
    #[inline(always)]
    pub fn holds(&self, hit: &Hit) -> bool {
        hit.surface.leaf == self.leaf && !hit.surface.flip
    }

    /// Shades the packet lanes `taken` (rays `ray(i)`, hits on this plane), four at a time:
    /// `out[i]` is what `Tracer::shade` gives them. Returns the lanes it leaves to the
    /// packet's usual shading (a light at the point, or at no finite distance from it).
    #[inline(always)]
    pub fn shade<'r, V: F64x4>(
        &self,
        t: &mut Tracer,
        fast: &FastScene,
        ray: impl Fn(usize) -> &'r Ray,
        hits: &[Option<Hit>],
        mut taken: u32,
        out: &mut [DVec3],
    ) -> u32 {
        let lights = &fast.plane_lights;
        let mut left = 0;
        while taken != 0 {
            // Up to four lanes; a short group repeats its first.
            let mut at = [taken.trailing_zeros() as usize; LANES];
            let mut len = 0;
            while taken != 0 && len < LANES {
                at[len] = taken.trailing_zeros() as usize;
                taken &= taken - 1;
                len += 1;
            }
            let group = &at[..len];
            let used = (1u32 << len) - 1;
            let rays = at.map(&ray);
            let (o, d) = (axes::<V>(rays.map(|r| r.origin)), axes(rays.map(|r| r.dir)));
            let hit_t = lanes::<V>(at.map(|i| hits[i].map_or(0.0, |h| h.t)));
            // p = o + t·d. (Written out here and below: a closure holding lanes may be
            // compiled outside the wing's copy.)
            let point = [
                o[0] + hit_t * d[0],
                o[1] + hit_t * d[1],
                o[2] + hit_t * d[2],
            ];
            if beside_a_light(lights, point) & used != 0 {
                left |= group.iter().fold(0, |bits, &i| bits | 1 << i);
                continue;
            }
            let leaving = self.leaving(d);
            let surfaces = self.surfaces(point, o, d, leaving);
            // The ray leaves the half-space where it meets n at a clearly positive cosine.
            let inside = if self.solid {
                leaving.to_bitmask() & used
            } else {
                0
            };
            // I = ka·Ia·O, then each light's s·(diffuse + specular).
            let [cr, cg, cb] = surfaces.color;
            let r = (V::splat(self.ka_ia.x) * cr).to_array();
            let g = (V::splat(self.ka_ia.y) * cg).to_array();
            let b = (V::splat(self.ka_ia.z) * cb).to_array();
            for (j, &i) in group.iter().enumerate() {
                out[i] = DVec3::new(r[j], g[j], b[j]);
            }
            for (k, &light) in lights.iter().enumerate() {
                let objects = [self.object; LANES];
                let lit = GroupLit::new(t, k, light, &surfaces, used, inside, objects);
                lit.add_shadowed(t, fast, k, group, out);
            }
        }
        left
    }

    /// n·d > 10⁻⁹ in each lane: the ray leaves the solid half-space.
    #[inline(always)]
    fn leaving<V: F64x4>(&self, [dx, dy, dz]: [V; 3]) -> V {
        let (nx, ny, nz) = (
            V::splat(self.normal.x),
            V::splat(self.normal.y),
            V::splat(self.normal.z),
        );
        (nx * dx + ny * dy + nz * dz).simd_gt(V::splat(TANGENT_COSINE))
    }

    /// The surfaces at the points p of rays from o along d, `leaving` the half-space where
    /// set: the normal turned toward each ray, the checker's colour at p, and the material's
    /// coefficients.
    #[inline(always)]
    fn surfaces<V: F64x4>(&self, point: [V; 3], o: [V; 3], d: [V; 3], leaving: V) -> Surfaces<V> {
        let [nx, ny, nz] = [self.normal.x, self.normal.y, self.normal.z];
        let [a, b] = self.colors;
        let color = if self.checkered {
            let even = lane_mask::<V>(even_cells_of(point));
            [
                even.bitselect(V::splat(a.x), V::splat(b.x)),
                even.bitselect(V::splat(a.y), V::splat(b.y)),
                even.bitselect(V::splat(a.z), V::splat(b.z)),
            ]
        } else {
            [V::splat(a.x), V::splat(a.y), V::splat(a.z)]
        };
        // `max_element` of |o|: `if a > b { a } else { b }`, twice.
        let (ax, ay, az) = (o[0].abs(), o[1].abs(), o[2].abs());
        let xy = ax.simd_gt(ay).bitselect(ax, ay);
        Surfaces {
            point,
            origin_size: xy.simd_gt(az).bitselect(xy, az),
            normal: [
                leaving.bitselect(V::splat(-nx), V::splat(nx)),
                leaving.bitselect(V::splat(-ny), V::splat(ny)),
                leaving.bitselect(V::splat(-nz), V::splat(nz)),
            ],
            view: [-d[0], -d[1], -d[2]],
            color,
            kd: V::splat(self.kd),
            ks: V::splat(self.ks),
            blinn: if self.blinn {
                lane_mask(0b1111)
            } else {
                V::ZERO
            },
            exponent: [self.exponent; LANES],
        }
    }
}

/// Every light's position and intensity, where the lanes take every light of the scene (a
/// point light that does not fade, `lanes_light`, with one shadow ray).
pub(super) fn lights_in_lanes(scene: &Scene) -> Option<Vec<(DVec3, DVec3)>> {
    scene
        .lights
        .iter()
        .map(|light| lanes_light(light).filter(|_| light.shadow_rays() == 1))
        .collect()
}

/// The lanes whose point is at one of the `lights`, or at no finite distance from it: where
/// `light_lanes::toward`'s d = √(d²) is 0 or not finite, d² is too.
#[inline(always)]
fn beside_a_light<V: F64x4>(lights: &[(DVec3, DVec3)], [px, py, pz]: [V; 3]) -> u32 {
    let mut beside = 0;
    for (position, _) in lights {
        let (tx, ty, tz) = (
            V::splat(position.x) - px,
            V::splat(position.y) - py,
            V::splat(position.z) - pz,
        );
        let d2 = tx * tx + ty * ty + tz * tz;
        beside |= (d2.simd_eq(V::ZERO) | !d2.is_finite()).to_bitmask();
    }
    beside
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::simd::{with_lanes, Wide};
    use crate::sampling::Rng;
    use crate::scene::{parse, Limits};

    /// The points set aside as beside a light are those `Light::sample` answers as at the
    /// point or at no finite distance (attenuation 0), found from d² without its root: at the
    /// light itself, at every scale from 10⁻²⁰ to 10²⁰⁰ away, and at NaN.
    #[test]
    fn the_points_beside_a_light_are_those_the_light_cannot_be_sampled_from() {
        let yaml = "camera: { eye: [0, 2, -6], look_at: [0, 0, 0] }
lights: [ { name: key, point: [-6, 10, -6], intensity: 1 } ]
materials: { floor: { color: 0.5 } }
objects: [ { name: floor, plane: { point: [0, 0, 0], normal: [0, 1, 0] }, material: floor } ]
";
        let scene = parse(yaml, "floor.yaml", None, &Limits::default()).unwrap();
        let lights = lights_in_lanes(&scene).expect("a point light");
        let light = &scene.lights[0];
        let position = DVec3::new(-6.0, 10.0, -6.0);
        let mut rng = Rng::for_pixel(3, 1, 4);
        let mut points = vec![position, DVec3::splat(1e300), DVec3::splat(f64::NAN)];
        for _ in 0..4000 {
            let scale = 10f64.powf(rng.uniform() * 220.0 - 20.0);
            let dir = DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()) - 0.5;
            points.push(position + scale * dir);
        }
        points.truncate(points.len() / LANES * LANES);
        let (mut beside, mut away) = (0, 0);
        for four in points.chunks_exact(LANES) {
            let p: [DVec3; LANES] = std::array::from_fn(|j| four[j]);
            let own = with_lanes!(V => beside_a_light::<V>(&lights, axes(p)));
            let wide = beside_a_light::<Wide>(&lights, axes(p));
            for (j, p) in p.iter().enumerate() {
                let at_the_point = light.sample(*p).attenuation == 0.0;
                assert_eq!(own >> j & 1 == 1, at_the_point, "{p}");
                assert_eq!(wide >> j & 1 == 1, at_the_point, "{p}");
                if at_the_point {
                    beside += 1;
                } else {
                    away += 1;
                }
            }
        }
        assert!(beside > 3 && away > 1000, "{beside} beside, {away} away");
    }
}
