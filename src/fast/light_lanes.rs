//! A point light's share at four surfaces of a packet at once: the steps of `light_share` (the
//! light's direction and distance, the diffuse and specular terms of I_local, whether a shadow
//! ray is needed) and of `Tracer::shadow_ray`, all in lanes, for the usual light (a point light
//! that does not fade) and the usual surface (Blinn or Phong highlights with a whole exponent up
//! to 1024). In scenes whose objects are tested four rays at a time (no BVH) the shadow rays are
//! searched in those lanes too; through a BVH, as one packet with the others toward the light.
//! Each lane does the IEEE operations the core does for its surface, in the same order, so
//! every term, ray, colour and counter of rays is the core's to the bit. Other surfaces and
//! lights, and points where the light's distance is 0 or not finite, take `light_share` itself.

use glam::DVec3;

use super::lanes::{lane_mask, RayLanes, LANES};
use super::packet_trace::ShadowPacket;
use super::search::FastScene;
use super::shadow_cones::{self, TowardLight};
use super::simd::F64x4;
use crate::geometry::Ray;
use crate::scene::Interaction;
use crate::shading::local::whole_exponent;
use crate::shading::{Highlight, Light, LightKind, Material};
use crate::trace::Tracer;

/// The light's position and intensity where the lanes can take it: a point light without
/// fading (c0, c1, c2 = 1, 0, 0) that is not dark.
pub(super) fn lanes_light(light: &Light) -> Option<(DVec3, DVec3)> {
    match &light.kind {
        LightKind::Point {
            position,
            attenuation,
        } if *attenuation == [1.0, 0.0, 0.0] && !light.is_dark() => {
            Some((*position, light.intensity))
        }
        _ => None,
    }
}

/// What the lanes need to know of a material's highlight.
#[derive(Clone, Copy, Debug)]
pub(super) struct LaneHighlight {
    /// Hall's transmitted highlight: the surface takes `light_share`.
    pub transmitted: bool,
    /// The exponent m where it is whole, up to 1024 (`whole_exponent`); None takes
    /// `light_share` where ks > 0.
    pub whole: Option<u32>,
    /// Blinn's highlight (h·n), else Phong's (r·v).
    pub blinn: bool,
}

impl LaneHighlight {
    pub fn of(m: &Material) -> LaneHighlight {
        LaneHighlight {
            transmitted: m.transmitted_highlight,
            whole: whole_exponent(m.shininess),
            blinn: m.highlight == Highlight::Blinn,
        }
    }
}

/// Which surfaces of a packet of up to N rays the lanes light, and what they need to know of
/// their materials.
pub(super) struct SurfaceLanes<'a, const N: usize> {
    /// The packet's surfaces, and by packet lane v = −d, toward the viewer (lane i < N:
    /// indexing them `% N` only spares the bounds checks).
    shaded: &'a [Option<Interaction>; N],
    view: &'a [DVec3; N],
    /// The packet lanes of those surfaces, in order, and their number.
    chosen: [usize; N],
    count: usize,
    /// By packet lane: the highlight's exponent m (0 where ks ≤ 0: nothing to raise).
    exponent: [u32; N],
    /// By packet lane: Blinn's highlight (bit set) or Phong's.
    blinn: u32,
    /// By packet lane: the point is inside its object (which may hide the light from it).
    inside: u32,
    /// The shaded surfaces that take `light_share` (Hall's transmitted highlight, a
    /// fractional exponent).
    pub alone: u32,
}

impl<'a, const N: usize> SurfaceLanes<'a, N> {
    /// The surfaces of a packet, found by rays whose v = −d is `view`, none chosen yet
    /// (`choose` chooses them where they stay: returned whole, they would be copied on, and
    /// the copy's wide loads would wait for the narrower stores just made).
    #[inline(always)]
    pub fn new(shaded: &'a [Option<Interaction>; N], view: &'a [DVec3; N]) -> SurfaceLanes<'a, N> {
        SurfaceLanes {
            shaded,
            view,
            chosen: [0; N],
            count: 0,
            exponent: [0; N],
            blinn: 0,
            inside: 0,
            alone: 0,
        }
    }

    /// Chooses among the first `n` surfaces those lit in lanes.
    #[inline(always)]
    pub fn choose(&mut self, fast: &FastScene, n: usize) {
        for (i, si) in self.shaded[..n].iter().enumerate() {
            let Some(si) = si else { continue };
            let highlight = fast.highlight(si.material);
            let exponent = if highlight.transmitted {
                None
            } else if si.paint.ks > 0.0 {
                highlight.whole
            } else {
                // No highlight (ks ≤ 0 or NaN): nothing to raise.
                Some(0)
            };
            match exponent {
                Some(e) => {
                    (self.chosen[self.count], self.exponent[i]) = (i, e);
                    self.count += 1;
                    if highlight.blinn {
                        self.blinn |= 1 << i;
                    }
                    if si.inside {
                        self.inside |= 1 << i;
                    }
                }
                None => self.alone |= 1 << i,
            }
        }
    }

    /// Light k (a light `lanes_light` accepts: at `position`, of `intensity`) at the chosen
    /// surfaces, four at a time, shadow rays searched in lanes too (a scene without a BVH):
    /// `out[i] += s·(diffuse + specular)` with s from the surface's shadow ray, or s = 0 where
    /// it casts none. Returns the packet lanes whose point is at the light or at no finite
    /// distance from it: those take `light_share`.
    #[inline(always)]
    pub fn light<V: F64x4>(
        &self,
        t: &mut Tracer,
        fast: &FastScene,
        k: usize,
        light: (DVec3, DVec3),
        out: &mut [DVec3],
    ) -> u32 {
        let mut far = 0;
        for group in self.chosen[..self.count].chunks(LANES) {
            let lit = self.group::<V>(t, k, light, group);
            lit.add_shadowed(t, fast, k, group, out);
            far |= lit.far_lanes(group);
        }
        far
    }

    /// `light` up to the shadow rays, for a scene whose shadow rays are searched as one packet
    /// (through the BVH): each surface's term and shadow ray go to `shadows`, which the caller
    /// searches and adds as it does `light_share`'s; a surface that casts none gets s = 0 here.
    #[inline(always)]
    pub fn light_before_shadows<V: F64x4>(
        &self,
        t: &mut Tracer,
        k: usize,
        light: (DVec3, DVec3),
        shadows: &mut ShadowPacket<N>,
        out: &mut [DVec3],
    ) -> u32 {
        let mut far = 0;
        for group in self.chosen[..self.count].chunks(LANES) {
            let lit = self.group::<V>(t, k, light, group);
            let [tx, ty, tz] = lit.terms.map(V::to_array);
            let [ox, oy, oz] = lit.origin.map(V::to_array);
            let [dx, dy, dz] = lit.l.map(V::to_array);
            let reach = lit.reach.to_array();
            for (j, &i) in group.iter().enumerate() {
                if lit.far & 1 << j != 0 {
                    continue;
                }
                let term = DVec3::new(tx[j], ty[j], tz[j]);
                if lit.cast & 1 << j == 0 {
                    // As `color += s · terms` with s = 0, to the bit.
                    out[i] += 0.0 * term;
                } else {
                    let ray = Ray {
                        origin: DVec3::new(ox[j], oy[j], oz[j]),
                        dir: DVec3::new(dx[j], dy[j], dz[j]),
                    };
                    shadows.cast(i, term, ray, reach[j]);
                }
            }
            far |= lit.far_lanes(group);
        }
        far
    }

    /// The light's terms at the surfaces in the packet lanes `group` (one to four; spare lanes
    /// repeat the first, and their results are dropped), which of them cast a shadow ray (the
    /// counters counted), and those rays.
    #[inline(always)]
    fn group<V: F64x4>(
        &self,
        t: &mut Tracer,
        k: usize,
        (position, intensity): (DVec3, DVec3),
        group: &[usize],
    ) -> GroupLit<V> {
        let len = group.len();
        // A whole group (the usual) is copied as one array, not through `copy_from_slice`
        // (a call into the library for a length known only at run time).
        let at: [usize; LANES] = group
            .try_into()
            .unwrap_or_else(|_| std::array::from_fn(|j| group[if j < len { j } else { 0 }]));
        let used = (1u32 << len) - 1;
        let si = at.map(|i| self.shaded[i % N].as_ref().expect("a shaded surface"));
        let v = at.map(|i| self.view[i % N]);
        let surfaces: Surfaces<V> = Surfaces {
            point: axes(si.map(|s| s.point)),
            origin_size: lanes(si.map(|s| s.origin_size)),
            normal: axes(si.map(|s| s.normal)),
            view: axes(v),
            color: axes(si.map(|s| s.paint.color)),
            kd: lanes(si.map(|s| s.paint.kd)),
            ks: lanes(si.map(|s| s.paint.ks)),
            blinn: lane_mask(lane_bits(at, |i| self.blinn >> i & 1 != 0)),
            exponent: at.map(|i| self.exponent[i % N]),
        };
        let inside = if self.inside != 0 {
            (0..len).fold(0, |bits, j| bits | (si[j].inside as u32) << j)
        } else {
            0
        };
        let objects = si.map(|s| s.object);
        GroupLit::new(
            t,
            k,
            (position, intensity),
            &surfaces,
            used,
            inside,
            objects,
        )
    }
}

impl<V: F64x4> GroupLit<V> {
    /// A light (at `position`, of `intensity`) at four `surfaces`, of which the lanes `used`
    /// (bits 0–3) are shaded: the points in the lanes `inside` are inside their `objects`.
    #[inline(always)]
    pub(super) fn new(
        t: &mut Tracer,
        k: usize,
        (position, intensity): (DVec3, DVec3),
        surfaces: &Surfaces<V>,
        used: u32,
        inside: u32,
        objects: [u32; LANES],
    ) -> GroupLit<V> {
        let (l, d, far) = toward(position, surfaces.point);
        let far = far & used;
        let (terms, n_dot_l) = surfaces.terms(l, intensity);

        // `Tracer::no_shadow_ray`: behind the surface, or inside a convex solid the light is
        // outside of.
        let features = &t.scene.features;
        let behind = n_dot_l.simd_le(V::ZERO).to_bitmask() & used & !far;
        let inside = if inside & used != 0 {
            (0..LANES).fold(0, |bits, j| {
                let hidden = inside >> j & 1 != 0 && features.hides_light_inside(objects[j], k);
                bits | (hidden as u32) << j
            }) & used
                & !behind
                & !far
        } else {
            0
        };
        let cast = used & !far & !behind & !inside;
        t.stats.shadow_skipped_backfacing += behind.count_ones() as u64;
        t.stats.shadow_skipped_inside += inside.count_ones() as u64;
        t.stats.shadow_rays += cast.count_ones() as u64;

        // `Tracer::shadow_ray`: from the point moved off the surface by the bias, toward l, as
        // far as the light less the bias.
        let (origin, reach, bias) = if cast != 0 {
            shadow_rays(t.scene.shadow_bias, surfaces, n_dot_l, d)
        } else {
            ([V::ZERO; 3], V::ZERO, V::ZERO)
        };
        GroupLit {
            terms,
            l,
            far,
            cast,
            origin,
            reach,
            slack: shadow_cones::slack(bias, &surfaces.point, d),
        }
    }

    /// Searches the shadow rays in lanes (a scene without a BVH) and adds each term with its
    /// shadow factor, `out[group[j]] += s·term` with s = 1 where the shadow ray reaches the
    /// light, else 0 (also where lane j casts none), except in the lanes left to `light_share`.
    #[inline(always)]
    pub(super) fn add_shadowed(
        &self,
        t: &mut Tracer,
        fast: &FastScene,
        k: usize,
        group: &[usize],
        out: &mut [DVec3],
    ) {
        let mut blocked = 0;
        if self.cast != 0 {
            let rays = RayLanes::from_lanes(self.origin, self.l);
            // Written out, not `Option::map`: a closure holding lanes may be compiled
            // outside the wing's copy.
            let toward = match fast.shadow_cones.get(k) {
                Some(cones) => Some(TowardLight {
                    cones,
                    l: self.l,
                    slack: self.slack,
                }),
                None => None,
            };
            blocked =
                fast.occluded_lanes(&rays, self.reach, self.cast, toward.as_ref(), &mut t.stats);
        }
        // color += s·terms: s = 1 where the shadow ray reaches the light, else 0.
        let s = lane_mask::<V>(self.cast & !blocked).bitselect(V::ONE, V::ZERO);
        let [tx, ty, tz] = self.terms;
        let [sx, sy, sz] = [
            (s * tx).to_array(),
            (s * ty).to_array(),
            (s * tz).to_array(),
        ];
        for (j, &i) in group.iter().enumerate() {
            if self.far & 1 << j == 0 {
                out[i] += DVec3::new(sx[j], sy[j], sz[j]);
            }
        }
    }
}

/// A light at four surfaces, before their shadow rays are searched.
pub(super) struct GroupLit<V> {
    /// The diffuse plus specular term, before the shadow factor.
    terms: [V; 3],
    /// Toward the light.
    l: [V; 3],
    /// The lanes (bits 0–3) left to `light_share`, and those that cast a shadow ray.
    far: u32,
    cast: u32,
    /// The shadow rays' origins and reach, where any lane casts one.
    origin: [V; 3],
    reach: V,
    /// How far each shadow ray may stray from the line back from the light along −l
    /// (`shadow_cones::slack`).
    slack: V,
}

impl<V> GroupLit<V> {
    /// The packet lanes of `group` left to `light_share`.
    #[inline(always)]
    fn far_lanes(&self, group: &[usize]) -> u32 {
        if self.far == 0 {
            return 0;
        }
        (0..group.len()).fold(0, |bits, j| bits | (self.far >> j & 1) << group[j])
    }
}

/// Four surfaces in lanes: what a light's terms and shadow rays need of them.
pub(super) struct Surfaces<V> {
    pub point: [V; 3],
    /// The largest |coordinate| of the origin of the ray that found each point
    /// (`Interaction::origin_size`).
    pub origin_size: V,
    pub normal: [V; 3],
    /// v = −d, toward the viewer.
    pub view: [V; 3],
    pub color: [V; 3],
    pub kd: V,
    pub ks: V,
    /// All ones where the highlight is Blinn's (h·n), zero where it is Phong's (r·v).
    pub blinn: V,
    /// The highlight's exponent m (0 where ks ≤ 0).
    pub exponent: [u32; LANES],
}

impl<V: F64x4> Surfaces<V> {
    /// `light_terms` for a light of `intensity` (fatt = 1) along l: diffuse plus specular,
    /// fatt·I·kd·O·max(n·l, 0) + fatt·I·ks·cos^m, with cos^m only where a highlight is lit
    /// (ks > 0, n·l > 0), and n·l.
    #[inline(always)]
    fn terms(&self, [lx, ly, lz]: [V; 3], intensity: DVec3) -> ([V; 3], V) {
        let [nx, ny, nz] = self.normal;
        let [vx, vy, vz] = self.view;
        let n_dot_l = nx * lx + ny * ly + nz * lz;
        let highlight = self.ks.simd_gt(V::ZERO) & n_dot_l.simd_gt(V::ZERO);
        let power = if highlight.any() {
            // h·n with h = (l + v)/|l + v|, where positive; r·v with r = 2(n·l)n − l. Each only
            // where some lit highlight is of its kind (a group's surfaces are mostly of one
            // material): the other lanes' cos^m is not used.
            let blinn_lit = (self.blinn & highlight).any();
            let phong_lit = (!self.blinn & highlight).any();
            let blinn = if blinn_lit {
                let (hx, hy, hz) = (lx + vx, ly + vy, lz + vz);
                let hn = hx * nx + hy * ny + hz * nz;
                hn.simd_gt(V::ZERO)
                    .bitselect(hn / (hx * hx + hy * hy + hz * hz).sqrt(), V::ZERO)
            } else {
                V::ZERO
            };
            let phong = if phong_lit {
                let twice = V::splat(2.0) * n_dot_l;
                let (rx, ry, rz) = (twice * nx - lx, twice * ny - ly, twice * nz - lz);
                let rv = rx * vx + ry * vy + rz * vz;
                rv.simd_gt(V::ZERO).bitselect(rv, V::ZERO)
            } else {
                V::ZERO
            };
            power(self.blinn.bitselect(blinn, phong), self.exponent)
        } else {
            V::ZERO
        };
        // max(n·l, 0) lane by lane, as the core takes it (the sign of a zero included).
        let [a, b, c, e] = n_dot_l.to_array();
        let lit = V::setr(a.max(0.0), b.max(0.0), c.max(0.0), e.max(0.0));
        let [r, g, b] = self.color;
        let lit = (lit, highlight, power);
        (
            [
                self.channel(intensity.x, r, lit),
                self.channel(intensity.y, g, lit),
                self.channel(intensity.z, b, lit),
            ],
            n_dot_l,
        )
    }

    /// One colour channel of the diffuse plus specular term of a light of intensity `i`:
    /// i·kd·O·max(n·l, 0) + i·ks·cos^m where a highlight is lit, + 0 elsewhere.
    #[inline(always)]
    fn channel(&self, i: f64, color: V, (lit, highlight, power): (V, V, V)) -> V {
        let diffuse = V::splat(i) * self.kd * color * lit;
        diffuse + highlight.bitselect(V::splat(i) * self.ks * power, V::ZERO)
    }
}

/// `Light::sample` for a point light at `position` that does not fade, seen from the points
/// p: l = (position − p)·(1/d) with d = |position − p| (as the core finds it), d,
/// and the lanes where d is 0 or not finite (bits 0–3), which the core answers otherwise.
#[inline(always)]
fn toward<V: F64x4>(position: DVec3, [px, py, pz]: [V; 3]) -> ([V; 3], V, u32) {
    let (tx, ty, tz) = (
        V::splat(position.x) - px,
        V::splat(position.y) - py,
        V::splat(position.z) - pz,
    );
    let d = (tx * tx + ty * ty + tz * tz).sqrt();
    let far = (d.simd_eq(V::ZERO) | !d.is_finite()).to_bitmask();
    let recip = V::ONE / d;
    ([tx * recip, ty * recip, tz * recip], d, far)
}

/// `Tracer::shadow_ray` toward a light at distance d: each origin is the point moved off its
/// surface by the bias (the scene's, or 10⁻¹⁰ of the sizes of the point and of the origin of
/// the ray that found it, as `Scene::offset` finds it) to the side of the normal the light is
/// on, and the ray reaches as far as the light less the bias; and that bias.
#[inline(always)]
fn shadow_rays<V: F64x4>(
    bias: Option<f64>,
    surfaces: &Surfaces<V>,
    n_dot_l: V,
    d: V,
) -> ([V; 3], V, V) {
    let [px, py, pz] = surfaces.point;
    let [nx, ny, nz] = surfaces.normal;
    let bias = match bias {
        Some(bias) => V::splat(bias),
        None => {
            // `max_element` is `if a > b { a } else { b }`, twice.
            let (ax, ay, az) = (px.abs(), py.abs(), pz.abs());
            let xy = ax.simd_gt(ay).bitselect(ax, ay);
            let largest = xy.simd_gt(az).bitselect(xy, az);
            let b = V::splat(1e-10) * (surfaces.origin_size + largest);
            let tiny = V::splat(1e-300);
            b.simd_gt(tiny).bitselect(b, tiny)
        }
    };
    let side = n_dot_l.simd_ge(V::ZERO).bitselect(bias, -bias);
    let reach = d - bias;
    (
        [px + side * nx, py + side * ny, pz + side * nz],
        reach.simd_gt(V::ZERO).bitselect(reach, V::ZERO),
        bias,
    )
}

/// Four numbers in lanes.
#[inline(always)]
pub(super) fn lanes<V: F64x4>(x: [f64; LANES]) -> V {
    V::setr(x[0], x[1], x[2], x[3])
}

/// Four vectors in lanes, axis by axis.
#[inline(always)]
pub(super) fn axes<V: F64x4>(v: [DVec3; LANES]) -> [V; 3] {
    [
        lanes(v.map(|v| v.x)),
        lanes(v.map(|v| v.y)),
        lanes(v.map(|v| v.z)),
    ]
}

/// Bit j set where `f` holds for packet lane `at[j]`.
#[inline(always)]
fn lane_bits(at: [usize; LANES], f: impl Fn(usize) -> bool) -> u32 {
    (0..LANES).fold(0, |bits, j| bits | (f(at[j]) as u32) << j)
}

/// `highlight_power` in lanes: cos^m by repeated squaring, each lane with its own exponent m
/// (the multiplications of `powi_by_squaring`, in its order). Its shortcut to 0 where cos = 0
/// < m is not needed: the cosines here are +0 or positive, and +0 raised to m > 0 is +0.
#[inline(always)]
fn power<V: F64x4>(cos: V, exponent: [u32; LANES]) -> V {
    let mut product = V::ONE;
    let mut a = cos;
    if exponent == [exponent[0]; LANES] {
        // One material in all four lanes (the usual case): one exponent's bits.
        let mut e = exponent[0];
        loop {
            if e & 1 != 0 {
                product = product * a;
            }
            e >>= 1;
            if e == 0 {
                break;
            }
            a = a * a;
        }
    } else {
        let mut e = exponent;
        loop {
            let odd = (0..LANES).fold(0, |bits, j| bits | (e[j] & 1) << j);
            product = lane_mask::<V>(odd).bitselect(product * a, product);
            e = e.map(|e| e >> 1);
            if e == [0; LANES] {
                break;
            }
            a = a * a;
        }
    }
    product
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::simd::{with_lanes, Wide};
    use crate::sampling::Rng;
    use crate::scene::{parse, Limits};
    use crate::shading::local::light_terms;
    use crate::shading::{Material, Paint};
    use crate::trace::whitted::shadow_reach;

    fn bits(v: DVec3) -> [u64; 3] {
        v.to_array().map(f64::to_bits)
    }

    fn lane(v: [[f64; LANES]; 3], j: usize) -> DVec3 {
        DVec3::new(v[0][j], v[1][j], v[2][j])
    }

    fn unit(rng: &mut Rng) -> DVec3 {
        loop {
            let v = DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0 - 1.0;
            if v.length() > 0.1 {
                return v.normalize();
            }
        }
    }

    /// One lane's surface: a material (its highlight and exponent), the paint at the point, the
    /// normal, the direction toward the viewer, and the light's direction.
    struct Case {
        material: Material,
        paint: Paint,
        n: DVec3,
        v: DVec3,
        l: DVec3,
    }

    fn case(rng: &mut Rng, k: usize) -> Case {
        let mut material = Material::matte("m", DVec3::ONE);
        material.shininess = [0.0, 1.0, 2.0, 7.0, 40.0, 200.0, 1024.0][k % 7];
        material.highlight = if k.is_multiple_of(3) {
            Highlight::Phong
        } else {
            Highlight::Blinn
        };
        let (n, v) = (unit(rng), unit(rng));
        // Some lights straight along n, behind it, at its horizon, or along −v (h = 0).
        let l = match k % 11 {
            0 => n,
            1 => -n,
            2 => n.any_orthonormal_vector(),
            3 => -v,
            _ => unit(rng),
        };
        let paint = Paint {
            color: DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()),
            kd: rng.uniform(),
            ks: if k.is_multiple_of(5) {
                0.0
            } else {
                rng.uniform()
            },
            kr: 0.0,
            kt: 0.0,
        };
        Case {
            material,
            paint,
            n,
            v,
            l,
        }
    }

    fn terms_of<V: F64x4>(cases: &[Case], intensity: DVec3) -> ([[f64; LANES]; 3], [f64; LANES]) {
        let c: [&Case; LANES] = std::array::from_fn(|j| &cases[j]);
        let blinn = (0..LANES).fold(0, |bits, j| {
            bits | ((c[j].material.highlight == Highlight::Blinn) as u32) << j
        });
        let surfaces = Surfaces::<V> {
            point: [V::ZERO; 3],
            origin_size: V::ZERO,
            normal: axes(c.map(|c| c.n)),
            view: axes(c.map(|c| c.v)),
            color: axes(c.map(|c| c.paint.color)),
            kd: lanes(c.map(|c| c.paint.kd)),
            ks: lanes(c.map(|c| c.paint.ks)),
            blinn: lane_mask(blinn),
            exponent: c.map(|c| {
                if c.paint.ks > 0.0 {
                    c.material.shininess as u32
                } else {
                    0
                }
            }),
        };
        let (terms, n_dot_l) = surfaces.terms(axes(c.map(|c| c.l)), intensity);
        (terms.map(V::to_array), n_dot_l.to_array())
    }

    /// Four surfaces at a time, with their exponents, highlights and lights mixed in the lanes,
    /// get `light_terms`' diffuse plus specular term and n·l to the bit (the processor's copy
    /// and the portable lanes'). Every other round the four share one kind of highlight,
    /// Phong's or Blinn's, as one material's surfaces do.
    #[test]
    fn the_terms_in_lanes_are_light_terms() {
        let mut rng = Rng::for_pixel(7, 1, 2);
        let intensity = DVec3::new(0.8, 0.5, 0.3);
        for round in 0..3000 {
            let mut cases: Vec<Case> = (0..LANES).map(|j| case(&mut rng, round * 5 + j)).collect();
            let shared = [Some(Highlight::Phong), None, Some(Highlight::Blinn), None][round % 4];
            if let Some(highlight) = shared {
                cases
                    .iter_mut()
                    .for_each(|c| c.material.highlight = highlight);
            }
            let own = with_lanes!(V => terms_of::<V>(&cases, intensity));
            let wide = terms_of::<Wide>(&cases, intensity);
            for (j, c) in cases.iter().enumerate() {
                let core = light_terms(&c.material, &c.paint, c.n, c.v, c.l, intensity, false);
                let expected = bits(core.diffuse + core.specular);
                for (name, (terms, n_dot_l)) in [("own", own), ("wide", wide)] {
                    assert_eq!(
                        bits(lane(terms, j)),
                        expected,
                        "{name}, round {round} lane {j}"
                    );
                    assert_eq!(n_dot_l[j].to_bits(), core.n_dot_l.to_bits(), "{name}");
                }
            }
        }
    }

    /// l and d are `Light::sample`'s to the bit, and the lanes it answers `AT_THE_POINT` (the
    /// point on the light, or at no finite distance) are the ones set aside.
    #[test]
    fn the_lights_direction_in_lanes_is_the_samples() {
        let mut rng = Rng::for_pixel(7, 3, 4);
        let position = DVec3::new(-6.0, 10.0, -6.0);
        let light = Light {
            name: "key".into(),
            kind: LightKind::Point {
                position,
                attenuation: [1.0, 0.0, 0.0],
            },
            intensity: DVec3::ONE,
            surface: None,
        };
        let mut points = vec![position, DVec3::splat(1e300), DVec3::splat(f64::NAN)];
        for _ in 0..4000 {
            let scale = 10f64.powf(rng.uniform() * 40.0 - 20.0);
            points.push(position + scale * unit(&mut rng));
        }
        for quad in points.chunks_exact(LANES) {
            let p: [DVec3; LANES] = std::array::from_fn(|j| quad[j]);
            let own = with_lanes!(V => {
                let (l, d, far) = toward::<V>(position, axes(p));
                (l.map(V::to_array), d.to_array(), far)
            });
            let (l, d, far) = toward::<Wide>(position, axes(p));
            let wide = (l.map(Wide::to_array), d.to_array(), far);
            for (l, d, far) in [own, wide] {
                for (j, &p) in p.iter().enumerate() {
                    let core = light.sample(p);
                    let at_the_point = core.attenuation == 0.0;
                    assert_eq!(far >> j & 1 == 1, at_the_point, "{p}");
                    if !at_the_point {
                        assert_eq!(bits(lane(l, j)), bits(core.l), "{p}");
                        assert_eq!(d[j].to_bits(), core.distance.to_bits(), "{p}");
                    }
                }
            }
        }
    }

    /// The shadow rays' origins, reach and bias are `Tracer::shadow_ray`'s (`Scene::offset`
    /// and `shadow_reach`) to the bit, with the automatic bias at every scale of the point and
    /// of the origin of the ray that found it, and with a scene's fixed one.
    #[test]
    fn the_shadow_rays_in_lanes_are_the_cores() {
        let yaml = "camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nobjects: []\n";
        let mut scene = parse(yaml, "bias.yaml", None, &Limits::default()).unwrap();
        let mut rng = Rng::for_pixel(7, 5, 6);
        for bias in [None, Some(0.25), Some(1e-6)] {
            scene.shadow_bias = bias;
            for _ in 0..2000 {
                let p: [DVec3; LANES] = std::array::from_fn(|_| {
                    let scale = 10f64.powf(rng.uniform() * 12.0 - 6.0);
                    scale * unit(&mut rng)
                });
                let from: [f64; LANES] =
                    std::array::from_fn(|_| 10f64.powf(rng.uniform() * 16.0 - 6.0));
                let mut n: [DVec3; LANES] = std::array::from_fn(|_| unit(&mut rng));
                let mut l: [DVec3; LANES] = std::array::from_fn(|_| unit(&mut rng));
                // A light at the horizon (n·l = 0) is on the normal's side.
                (n[0], l[0]) = (DVec3::Y, DVec3::X);
                let d: [f64; LANES] = std::array::from_fn(|_| rng.uniform() * 20.0);
                let n_dot_l: [f64; LANES] = std::array::from_fn(|j| n[j].dot(l[j]));
                let own = with_lanes!(V => {
                    let s = surfaces_at::<V>(p, from, n);
                    let (o, r, b) = shadow_rays(bias, &s, lanes(n_dot_l), lanes(d));
                    (o.map(V::to_array), r.to_array(), b.to_array())
                });
                let s = surfaces_at::<Wide>(p, from, n);
                let (o, r, b) = shadow_rays(bias, &s, lanes(n_dot_l), lanes(d));
                let wide = (o.map(Wide::to_array), r.to_array(), b.to_array());
                for (origin, reach, moved_by) in [own, wide] {
                    for j in 0..LANES {
                        let si = Interaction {
                            point: p[j],
                            normal: n[j],
                            inside: false,
                            leaf: 0,
                            face: 0,
                            object: 0,
                            material: 0,
                            paint: Material::matte("m", DVec3::ONE).paint(),
                            origin_size: from[j],
                        };
                        let (start, moved) = scene.offset(&si, l[j]);
                        assert_eq!(bits(lane(origin, j)), bits(start), "{bias:?} {}", p[j]);
                        assert_eq!(moved_by[j].to_bits(), moved.to_bits(), "{bias:?}");
                        let expected = shadow_reach(d[j], moved);
                        assert_eq!(reach[j].to_bits(), expected.to_bits(), "{bias:?}");
                    }
                }
            }
        }
    }

    fn surfaces_at<V: F64x4>(
        p: [DVec3; LANES],
        from: [f64; LANES],
        n: [DVec3; LANES],
    ) -> Surfaces<V> {
        Surfaces {
            point: axes(p),
            origin_size: lanes(from),
            normal: axes(n),
            view: [V::ZERO; 3],
            color: [V::ZERO; 3],
            kd: V::ZERO,
            ks: V::ZERO,
            blinn: V::ZERO,
            exponent: [0; LANES],
        }
    }
}
