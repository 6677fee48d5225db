//! Triangle, intersected with the watertight test of Woop, Benthin and Wald (2013): a ray
//! through an edge shared by two triangles hits at least one of them, never neither (exactly
//! on the edge, both may report the same t).

use glam::DVec3;

use super::{Ray, Span};

/// A triangle with vertices a, b, c, counter-clockwise seen from the side its normal faces.
#[derive(Clone, Debug, PartialEq)]
pub struct Triangle {
    /// First vertex.
    pub a: DVec3,
    /// Second vertex.
    pub b: DVec3,
    /// Third vertex.
    pub c: DVec3,
}

/// A hit: the distance and the barycentric coordinates (λ1, λ2, λ3) of a, b, c.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit {
    /// Distance along the ray (any sign: the whole line is tested).
    pub t: f64,
    /// Barycentric coordinates (λ1, λ2, λ3) of a, b, c; they sum to 1.
    pub bary: DVec3,
}

impl Triangle {
    /// Where the line of the ray crosses the triangle (watertight test: edges shared by two
    /// triangles are never missed); None when it misses or the triangle is seen edge-on.
    pub fn intersect(&self, ray: &Ray) -> Option<TriangleHit> {
        // Shear and permute so the ray runs along +z from the origin; the test becomes 2-D.
        // (Woop et al. also swap kx and ky when d[kz] < 0, to keep the winding for back-face
        // culling. This test takes both windings, and the swap would only negate u, v, w and
        // their sum exactly, leaving t and the barycentrics as they are.)
        let d = ray.dir;
        let kz = d.abs().max_position();
        let kx = (kz + 1) % 3;
        let ky = (kx + 1) % 3;
        let (sx, sy, sz) = (d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]);
        let (a, b, c) = (
            self.a - ray.origin,
            self.b - ray.origin,
            self.c - ray.origin,
        );
        let (ax, ay) = (a[kx] - sx * a[kz], a[ky] - sy * a[kz]);
        let (bx, by) = (b[kx] - sx * b[kz], b[ky] - sy * b[kz]);
        let (cx, cy) = (c[kx] - sx * c[kz], c[ky] - sy * c[kz]);
        // Scaled barycentrics: signed areas of the edges as seen along the ray.
        let u = cx * by - cy * bx;
        let v = ax * cy - ay * cx;
        let w = bx * ay - by * ax;
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let t = (u * sz * a[kz] + v * sz * b[kz] + w * sz * c[kz]) / det;
        t.is_finite().then(|| TriangleHit {
            t,
            bary: DVec3::new(u, v, w) / det,
        })
    }

    /// The degenerate span `[t, t]` where the line of the ray crosses the triangle, or None.
    pub fn span(&self, ray: &Ray) -> Option<Span> {
        self.intersect(ray).map(|h| Span::new(h.t, 0, h.t, 0))
    }

    /// Geometric normal (b − a) × (c − a), unit; zero for a degenerate triangle.
    pub fn normal(&self) -> DVec3 {
        let (e1, e2) = (self.b - self.a, self.c - self.a);
        let n = e1.cross(e2);
        if n.length_squared().is_normal() {
            return n.normalize();
        }
        // Edges so long or short that the length squared overflows or loses its digits to
        // underflow: the direction is the same for the edges scaled.
        let s = tame(e1.abs().max_element().max(e2.abs().max_element()));
        (s * e1).cross(s * e2).normalize_or_zero()
    }

    /// Barycentric coordinates (λ1, λ2, λ3) of a point in the triangle's plane, from the ratios of
    /// the sub-triangle areas, as seed 002 defines them.
    pub fn barycentric(&self, p: DVec3) -> DVec3 {
        let (l, area) = area_ratios(self.a, self.b, self.c, p);
        if area.is_normal() {
            return l;
        }
        // Coordinates so large or small that a product of four of them overflows or loses
        // its digits: the ratios are the same for the figure scaled.
        let size = [self.a, self.b, self.c, p].map(|v| v.abs().max_element());
        let s = tame(size.into_iter().fold(0.0, f64::max));
        area_ratios(s * self.a, s * self.b, s * self.c, s * p).0
    }
}

/// (λ1, λ2, λ3) of p in the triangle a, b, c: the areas of the triangles p makes with each
/// edge over the whole one's; and |n|², the whole one's doubled area squared.
fn area_ratios(a: DVec3, b: DVec3, c: DVec3, p: DVec3) -> (DVec3, f64) {
    let n = (b - a).cross(c - a);
    let area = n.length_squared();
    let l1 = (b - p).cross(c - p).dot(n) / area;
    let l2 = (c - p).cross(a - p).dot(n) / area;
    (DVec3::new(l1, l2, 1.0 - l1 - l2), area)
}

/// A factor that brings coordinates as large as `size` near 1 where a product of four of
/// them (a cross product's length squared) would overflow or underflow, else 1. A power of
/// two: multiplying by it is exact.
fn tame(size: f64) -> f64 {
    if !size.is_finite() || size == 0.0 || (1e-60..=1e60).contains(&size) {
        return 1.0;
    }
    2f64.powi(-(size.log2().floor() as i32))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A triangle is the same figure at 1e−80 and at 1e80 as at 1: its normal and a point's
    /// barycentric coordinates do not overflow or vanish with the cross product's
    /// length squared (10⁶⁴⁰ and 10⁻⁶⁴⁰ there).
    #[test]
    fn huge_and_tiny_triangles_keep_their_normal_and_barycentrics() {
        for scale in [1e-80, 1e-40, 1.0, 1e40, 1e80, 1e100] {
            let tri = Triangle {
                a: DVec3::new(-1.0, -1.0, 5.0) * scale,
                b: DVec3::new(1.0, -1.0, 5.0) * scale,
                c: DVec3::new(0.0, 1.0, 5.0) * scale,
            };
            assert_eq!(tri.normal(), DVec3::Z, "{scale:e}");
            // (0, −0.5, 5): λ3 = 0.25 (a quarter of the way up), λ1 = λ2 = 0.375.
            let l = tri.barycentric(DVec3::new(0.0, -0.5, 5.0) * scale);
            assert!(
                (l - DVec3::new(0.375, 0.375, 0.25)).abs().max_element() < 1e-15,
                "{scale:e}: {l}"
            );
        }
    }

    #[test]
    fn barycentrics_match_the_hit_point() {
        let tri = Triangle {
            a: DVec3::ZERO,
            b: DVec3::X,
            c: DVec3::Y,
        };
        let ray = Ray::new(DVec3::new(0.2, 0.3, -1.0), DVec3::Z);
        let hit = tri.intersect(&ray).unwrap();
        assert!((hit.t - 1.0).abs() < 1e-15);
        assert!((hit.bary - DVec3::new(0.5, 0.2, 0.3)).length() < 1e-15);
        assert!((tri.barycentric(ray.at(hit.t)) - hit.bary).length() < 1e-15);
    }

    /// (x, y, z) → (z, x, y), k times: the same figure with another axis as its normal.
    fn turned(p: DVec3, k: usize) -> DVec3 {
        (0..k).fold(p, |p, _| DVec3::new(p.z, p.x, p.y))
    }

    #[test]
    fn a_ray_past_any_edge_misses_from_either_side_along_any_axis() {
        // The triangle (0, 0), (2, 0), (0, 2) in the plane z = 2, turned so that x, y and z in
        // turn are its normal, met head-on from the front (z = 0) and from behind (z = 4), its
        // vertices in either order (the signs of the edge functions flip with the winding).
        for (k, wound) in (0..3).flat_map(|k| [(k, false), (k, true)]) {
            let (b, c) = (DVec3::new(2.0, 0.0, 2.0), DVec3::new(0.0, 2.0, 2.0));
            let (b, c) = if wound { (c, b) } else { (b, c) };
            let tri = Triangle {
                a: turned(DVec3::new(0.0, 0.0, 2.0), k),
                b: turned(b, k),
                c: turned(c, k),
            };
            // At (0.5, 0.25): λ = x/2 = 0.25 for (2, 0), y/2 = 0.125 for (0, 2), 0.625 for a.
            let bary = if wound {
                DVec3::new(0.625, 0.125, 0.25)
            } else {
                DVec3::new(0.625, 0.25, 0.125)
            };
            let rays = |x: f64, y: f64| {
                [(0.0, 1.0), (4.0, -1.0)].map(|(z, dz)| {
                    let o = turned(DVec3::new(x, y, z), k);
                    Ray::new(o, turned(DVec3::new(0.0, 0.0, dz), k))
                })
            };
            // Inside, at distance 2 either way.
            for r in rays(0.5, 0.25) {
                let hit = tri.intersect(&r).unwrap();
                assert!((hit.t - 2.0).abs() < 1e-15, "k = {k}");
                assert!((hit.bary - bary).length() < 1e-15);
            }
            // Exactly through each edge and each vertex: a hit (the triangle is closed), one
            // edge function 0 (two at a vertex), whatever the sign of the others.
            for (x, y) in [
                (1.0, 0.0),
                (0.0, 1.0),
                (1.0, 1.0),
                (0.0, 0.0),
                (2.0, 0.0),
                (0.0, 2.0),
            ] {
                for r in rays(x, y) {
                    let hit = tri.intersect(&r);
                    assert_eq!(hit.map(|h| h.t), Some(2.0), "k = {k}, ({x}, {y}), {r:?}");
                }
            }
            // Just past each edge: y < 0, x < 0, x + y > 2.
            for (x, y) in [(1.0, -0.1), (-0.1, 1.0), (1.1, 1.0)] {
                for r in rays(x, y) {
                    assert_eq!(tri.intersect(&r), None, "k = {k}, ({x}, {y}), {r:?}");
                }
            }
        }
    }

    #[test]
    fn a_triangle_too_large_for_its_edge_functions_is_never_hit_at_a_wrong_distance() {
        // Half sides of 7.7e153: each edge function (≈ 0.6e308 and 1.2e308) is finite but
        // their sum overflows, while the plane z = 1e−10 keeps the numerator of t finite.
        let l = 7.7e153;
        let z = 1e-10;
        let tri = Triangle {
            a: DVec3::new(-l, -l, z),
            b: DVec3::new(l, -l, z),
            c: DVec3::new(0.0, l, z),
        };
        let hit = tri.intersect(&Ray::new(DVec3::ZERO, DVec3::Z));
        assert!(hit.is_none_or(|h| (h.t - z).abs() < 1e-25), "{hit:?}");
    }

    #[test]
    fn a_ray_through_a_shared_edge_hits_one_of_the_two_triangles() {
        // Two triangles sharing the diagonal of the unit square.
        let t1 = Triangle {
            a: DVec3::ZERO,
            b: DVec3::X,
            c: DVec3::new(1.0, 1.0, 0.0),
        };
        let t2 = Triangle {
            a: DVec3::ZERO,
            b: DVec3::new(1.0, 1.0, 0.0),
            c: DVec3::Y,
        };
        for i in 1..100 {
            let s = i as f64 / 100.0;
            let ray = Ray::new(DVec3::new(s, s, -1.0), DVec3::new(1e-3, 0.0, 1.0));
            let ray_back = Ray::new(ray.at(2.0), -ray.dir);
            for r in [ray, ray_back] {
                assert!(
                    t1.intersect(&r).is_some() || t2.intersect(&r).is_some(),
                    "leak at {s}"
                );
            }
        }
    }
}
