//! Where on the film each boxed object can appear: the rectangle of image coordinates that
//! holds its box's shadow on the look-at camera's image plane.
//!
//! A primary ray leaves the eye e along forward + x·right + y·up, through the point (x, y) of
//! the image plane one unit ahead. A box wholly in front of the eye is met only by rays whose
//! (x, y) falls in its projection there, the convex hull of its eight corners' projections
//! (x, y) = (q·right, q·up) / (q·forward) for q = corner − e, and so within their bounding
//! rectangle. Turned into image coordinates (the film's sx, sy, `plane_x` and `plane_y`
//! solved for them) and widened by a pixel on every side, the rectangle tells which pixels' grid
//! samples cannot meet the box: the same verdict the packet's hull (`Hull::of_directions`)
//! proves from the rays themselves, here found once a film, before any ray is made.
//!
//! The pixel of margin dwarfs every rounding: a film is given footprints only where what
//! rounding can move on the plane is below 10⁻⁶ of a pixel (2·tan(fov/2)/height): a corner's
//! (x, y), a computed ray's direction, and the slab test's slack of 4 ulps, which lets a ray
//! that misses a box by as little count as meeting it. So a ray a pixel outside the rectangle
//! is missed by its own slab test too.

use glam::{DVec2, DVec3};

use super::camera_rays::LookAt;
use super::search::FastScene;
use crate::accel::Aabb;
use crate::scene::Camera;

/// The pixels whose grid samples may meet a box: those whose corner (x, y) has
/// `x_min ≤ x ≤ x_max` and `y_min ≤ y ≤ y_max`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Pixels {
    x_min: f64,
    x_max: f64,
    y_min: f64,
    y_max: f64,
}

/// The footprints of a scene's boxed objects on one film: for each object tested behind its
/// box (bit k of a mask for `FastScene::unbounded[k]`, as `boxes_missed_by_all` numbers them),
/// the pixels whose samples may meet it.
#[derive(Clone, Debug)]
pub struct Footprints {
    boxes: Vec<(u32, Pixels)>,
}

impl Footprints {
    /// The footprints of `fast`'s boxed objects seen through `camera`, at the grid samples
    /// (c + o.x, r + o.y) of each pixel (c, r), for each offset o. None where the primary rays
    /// are not searched in lanes with boxes outside a BVH (the hull is not used there either),
    /// for the window model, without finite offsets, or where some box has no footprint (it
    /// reaches behind the eye, or its corners are not found precisely enough): the packets'
    /// hull then decides.
    pub fn new(camera: &Camera, offsets: &[DVec2], fast: &FastScene) -> Option<Footprints> {
        if !(fast.tests_in_lanes() && fast.boxes_outside_bvh) {
            return None;
        }
        let plane = Plane::of(camera)?;
        // The offsets' least and greatest x and y.
        let (mut ox, mut oy) = (
            (f64::INFINITY, f64::NEG_INFINITY),
            (f64::INFINITY, f64::NEG_INFINITY),
        );
        for o in offsets {
            (ox, oy) = (
                (ox.0.min(o.x), ox.1.max(o.x)),
                (oy.0.min(o.y), oy.1.max(o.y)),
            );
        }
        if !(ox.0.is_finite() && ox.1.is_finite() && oy.0.is_finite() && oy.1.is_finite()) {
            return None;
        }
        let mut boxes = vec![];
        for (k, probe) in fast.unbounded.iter().enumerate().take(u64::BITS as usize) {
            let Some(o) = probe.boxed_object().filter(|&o| fast.tested_behind_box(o)) else {
                continue;
            };
            let (sx, sy) = plane.shadow(&fast.scene.objects[o as usize].bounds)?;
            // A pixel's samples lie at c + o.x for its corner c: those of corner c reach the
            // widened rectangle where c + max o.x ≥ its left side and c + min o.x ≤ its right.
            let pixels = Pixels {
                x_min: sx.0 - 1.0 - ox.1,
                x_max: sx.1 + 1.0 - ox.0,
                y_min: sy.0 - 1.0 - oy.1,
                y_max: sy.1 + 1.0 - oy.0,
            };
            boxes.push((k as u32, pixels));
        }
        (!boxes.is_empty()).then_some(Footprints { boxes })
    }

    /// The boxed objects (bit k for `unbounded[k]`) that no grid sample of the pixels
    /// `x_first..=x_last` of row `y` can meet.
    #[inline(always)]
    pub fn missed(&self, x_first: u32, x_last: u32, y: u32) -> u64 {
        let (x_first, x_last, y) = (x_first as f64, x_last as f64, y as f64);
        self.boxes.iter().fold(0, |missed, (k, p)| {
            let apart = x_last < p.x_min || x_first > p.x_max || y < p.y_min || y > p.y_max;
            missed | (apart as u64) << k
        })
    }
}

/// The look-at camera's image plane, to project points onto.
struct Plane {
    frame: LookAt,
}

impl Plane {
    /// The camera's plane, if it is a look-at camera whose frame is orthonormal (the
    /// projection solves for x and y by dot products) and whose pixels are not too small to
    /// project to within a millionth of one.
    fn of(camera: &Camera) -> Option<Plane> {
        let frame = LookAt::of(camera)?;
        let (forward, right, up) = (frame.forward, frame.right, frame.up);
        let unit = |v: DVec3| (v.length() - 1.0).abs() < 1e-12;
        let square = |a: DVec3, b: DVec3| a.dot(b).abs() < 1e-12;
        let orthonormal = unit(forward) && unit(right) && unit(up);
        let orthonormal = orthonormal && square(forward, right) && square(forward, up);
        let orthonormal = orthonormal && square(right, up);
        let per_row = frame.tan_half_fov / frame.size.1;
        let fine = per_row.is_finite() && per_row > 1e-9;
        (orthonormal && fine && frame.eye.is_finite()).then_some(Plane { frame })
    }

    /// The image coordinates (sx, sy) of the bounding rectangle of the box's projection, as
    /// (sx_min, sx_max), (sy_min, sy_max); None where a corner is not well in front of the eye
    /// (within 89.9° of forward), or its projection is not found to within 10⁻⁶ of a pixel.
    fn shadow(&self, bounds: &Aabb) -> Option<((f64, f64), (f64, f64))> {
        let f = &self.frame;
        let (w, h) = f.size;
        // The plane's x and y per unit of image column and row (`plane_x`, `plane_y`).
        let (x_scale, y_scale) = (f.tan_half_fov * (w / h), f.tan_half_fov);
        let (mut sx, mut sy) = (
            (f64::INFINITY, f64::NEG_INFINITY),
            (f64::INFINITY, f64::NEG_INFINITY),
        );
        for corner in 0..8 {
            let pick = |axis: usize| {
                if corner >> axis & 1 == 0 {
                    bounds.min[axis]
                } else {
                    bounds.max[axis]
                }
            };
            let q = DVec3::new(pick(0), pick(1), pick(2)) - f.eye;
            let depth = q.dot(f.forward);
            // False for NaN too.
            let well_ahead = depth > 1e-3 * q.length();
            if !well_ahead {
                return None;
            }
            let (x, y) = (q.dot(f.right) / depth, q.dot(f.up) / depth);
            // What rounding can move, on the plane: a ray's direction (e + forward + x·right
            // + y·up − e), a corner's (x, y) and a point the slab test puts on the box, each by
            // a few ulps of the coordinates that make it, seen from `depth` away.
            let size = 1.0 + f.eye.abs().element_sum();
            let far = (q + f.eye).abs().element_sum() + f.eye.abs().element_sum();
            let error = 1e-14 * (1.0 + x.abs() + y.abs()) * (size + far / depth);
            let precise = error <= 1e-6 * 2.0 * y_scale / h;
            if !precise {
                return None;
            }
            let (cx, cy) = ((x / x_scale + 1.0) * w / 2.0, (1.0 - y / y_scale) * h / 2.0);
            sx = (sx.0.min(cx), sx.1.max(cx));
            sy = (sy.0.min(cy), sy.1.max(cy));
        }
        Some((sx, sy))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::SlabRay;
    use crate::scene::{parse, Limits, Scene};
    use rand::{Rng, SeedableRng};
    use rand_pcg::Pcg64;

    /// The scene of `yaml`, whose objects are made of material `m`.
    fn scene(yaml: &str) -> Scene {
        let yaml = format!("materials: {{ m: {{ color: 0.5 }} }}\n{yaml}");
        parse(&yaml, "footprint.yaml", None, &Limits::default()).unwrap()
    }

    /// An n × n grid of offsets in a pixel, as the film's regular grid places them.
    fn grid_offsets(n: u32) -> Vec<DVec2> {
        let cell = |k: u32| (k as f64 + 0.5) / n as f64;
        (0..n * n)
            .map(|k| DVec2::new(cell(k % n), cell(k / n)))
            .collect()
    }

    fn footprints(scene: &Scene, offsets: &[DVec2]) -> Option<Footprints> {
        Footprints::new(&scene.camera, offsets, &FastScene::new(scene))
    }

    /// The notes' camera at the origin looking down +z, 90° of field (tan = 1), 100 × 100
    /// pixels, and a cube of side 2 from z = 9 to 11 straight ahead. Its near face's corners
    /// (±1, ±1, 9) project to x, y = ±1/9 on the plane, sx = (x + 1)·50: the rectangle spans
    /// columns and rows 44.44 to 55.56. With 2 × 2 samples a pixel (offsets ¼ and ¾) and a
    /// pixel of margin, the pixels whose corner lies in [44.44 − 1 − ¾, 55.56 + 1 − ¼] =
    /// [42.69, 56.31] may meet it: 43 to 56.
    #[test]
    fn a_cube_ahead_casts_the_worked_footprint() {
        let scene = scene(
            "camera: { eye: [0, 0, 0], look_at: [0, 0, 1], fov: 90, width: 100, height: 100 }
objects:
  - { box: { min: [-1, -1, 9], max: [1, 1, 11] }, material: m }
",
        );
        let f = footprints(&scene, &grid_offsets(2)).expect("the cube is ahead");
        let missed = |x0: u32, x1: u32, y: u32| f.missed(x0, x1, y) & 1 != 0;
        assert!(missed(42, 42, 50) && missed(57, 57, 50));
        assert!(!missed(43, 43, 50) && !missed(56, 56, 50));
        assert!(missed(50, 50, 42) && missed(50, 50, 57));
        assert!(!missed(50, 50, 43) && !missed(50, 50, 56));
        // A packet of several pixels is missed only if all of them are.
        assert!(!missed(40, 43, 50) && missed(38, 42, 50));
        assert!(missed(0, 99, 10), "a whole row above it");
    }

    /// No footprints where the packets' hull is not used (no boxes, or a BVH), for the window
    /// model, without samples, or where a box reaches behind the eye.
    #[test]
    fn footprints_only_where_they_hold() {
        let offsets = grid_offsets(4);
        let camera =
            "camera: { eye: [0, 0, 0], look_at: [0, 0, 1], fov: 60, width: 40, height: 30 }";
        let none = |objects: &str| footprints(&scene(&format!("{camera}\n{objects}")), &offsets);
        assert!(
            none("objects: [ { sphere: { center: [0, 0, 5], radius: 1 }, material: m } ]")
                .is_none()
        );
        assert!(
            none("objects: [ { box: { min: [-1, -1, -1], max: [1, 1, 1] }, material: m } ]")
                .is_none()
        );
        assert!(
            none("objects: [ { box: { min: [-1, -1, 1], max: [1, 1, 3] }, material: m } ]")
                .is_some()
        );
        let many: String = (0..40)
            .map(|i| {
                format!("  - {{ box: {{ min: [{i}, 0, 5], max: [{i}.5, 1, 6] }}, material: m }}\n")
            })
            .collect();
        assert!(none(&format!("objects:\n{many}")).is_none(), "a BVH");
        let window = scene(
            "camera:
  { eye: [0, 0, -5], u: [1, 0, 0], v: [0, 1, 0], w: [0, 0, 1], f: 2, window: [-1, 1, 1, -1],
    width: 40, height: 40 }
objects: [ { box: { min: [-1, -1, 1], max: [1, 1, 3] }, material: m } ]
",
        );
        assert!(footprints(&window, &offsets).is_none());
        let ahead = scene(&format!(
            "{camera}\nobjects: [ {{ box: {{ min: [-1, -1, 1], max: [1, 1, 3] }}, material: m }} ]"
        ));
        assert!(footprints(&ahead, &[]).is_none(), "no samples");
    }

    /// Wherever a footprint says a pixel's samples miss a box, each of its primary rays
    /// (`Camera::ray`, which the wing's rays equal to the bit) misses it by the core's slab
    /// test (which the lanes repeat), with t from 0 on; and nine in ten pixels whose rays all
    /// miss are ruled out (the cube's test above pins the rectangle's exact bounds). Random
    /// cameras looking every way, with fields of view from 1° to 150°, boxes of every size
    /// and distance (thin ones among them), and grid or scattered samples.
    #[test]
    fn a_footprint_rules_out_only_pixels_whose_rays_miss() {
        let mut rng = Pcg64::seed_from_u64(7);
        let unit = |rng: &mut Pcg64| loop {
            let v = DVec3::new(rng.random(), rng.random(), rng.random()) * 2.0 - 1.0;
            if (1e-3..=1.0).contains(&v.length_squared()) {
                return v.normalize();
            }
        };
        let (mut ruled_out, mut hit, mut pixels, mut films) = (0, 0, 0, 0);
        for case in 0..300 {
            let scale = 10f64.powi(rng.random_range(-4..=5));
            let eye = unit(&mut rng) * scale * rng.random_range(0.0..100.0);
            let ahead = unit(&mut rng);
            let fov = rng.random_range(1.0..150.0);
            let (w, h) = (rng.random_range(8..40), rng.random_range(8..40));
            let distance = scale * rng.random_range(2.0..50.0);
            // A box around a point in view (near the axis, or toward an edge), or anywhere.
            let centre = eye + (ahead + unit(&mut rng) * rng.random_range(0.0..0.6)) * distance;
            let mut half = DVec3::new(rng.random(), rng.random(), rng.random()) * scale;
            if rng.random_bool(0.2) {
                half[rng.random_range(0..3)] = 1e-9 * scale;
            }
            let bounds = Aabb::new(centre - half, centre + half);
            let v = |p: DVec3| format!("[{:e}, {:e}, {:e}]", p.x, p.y, p.z);
            let yaml = format!(
                "camera: {{ eye: {}, look_at: {}, fov: {fov}, width: {w}, height: {h} }}\n\
                 objects: [ {{ box: {{ min: {}, max: {} }}, material: m }} ]\n",
                v(eye),
                v(eye + ahead),
                v(bounds.min),
                v(bounds.max)
            );
            let scene = scene(&yaml);
            let offsets = match case % 5 {
                4 => (0..5)
                    .map(|_| DVec2::new(rng.random(), rng.random()))
                    .collect(),
                n => grid_offsets(n as u32 + 1),
            };
            let Some(f) = footprints(&scene, &offsets) else {
                continue;
            };
            films += 1;
            let bounds = &scene.objects[0].bounds;
            for (x, y) in (0..h).flat_map(|y| (0..w).map(move |x| (x, y))) {
                let meets = offsets.iter().any(|o| {
                    let ray = scene.camera.ray(x as f64 + o.x, y as f64 + o.y);
                    bounds.hit_slabs(
                        &SlabRay::new(ray.origin, ray.dir.recip()),
                        0.0,
                        f64::INFINITY,
                    )
                });
                let out = f.missed(x, x, y) & 1 != 0;
                assert!(
                    !(out && meets),
                    "pixel ({x}, {y}) ruled out, but a ray meets the box: {yaml}"
                );
                ruled_out += out as u32;
                hit += meets as u32;
                pixels += 1;
            }
        }
        // Both answers are common, over films that have footprints, and the footprints rule out
        // nine in ten of the pixels whose rays all miss.
        assert!(
            films > 150 && hit > 1000 && ruled_out > (pixels - hit) * 9 / 10,
            "{films} films: {ruled_out} pixels ruled out, {hit} met, of {pixels}"
        );
    }
}
