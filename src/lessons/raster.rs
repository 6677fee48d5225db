//! The work a rasteriser would do for a scene, to set beside the ray tracer's (seed 004, "ray
//! tracing vs. triangle scan conversion"). Scan conversion loops over triangles: it projects
//! each one's vertices onto the image and shades one **fragment** for every pixel centre the
//! projected triangle covers, whether or not a nearer triangle later hides it (a z-buffer keeps
//! the nearest; a rasteriser that shades before the depth test does all of them). Ray tracing
//! loops over pixels: one primary ray each.
//!
//! Counted here, for the triangles and meshes of a scene (other shapes would have to be
//! meshed first, and are left out): the triangles, those facing away from the eye (which
//! back-face culling drops), the fragments of all of them and of the front-facing ones, and
//! the pixels covered at least once. A pixel centre on an edge shared by two triangles belongs
//! to one of them (the top-left rule), so a closed mesh covers each pixel once per layer.
//! Triangles with a vertex at or behind the eye's plane would need clipping; they are counted
//! apart and not rasterised.

use glam::{DMat3, DVec2, DVec3};

use crate::geometry::Shape;
use crate::scene::{Camera, Scene};

/// What scan conversion of a scene's triangles costs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RasterWork {
    /// Triangles in the scene (meshes' included).
    pub triangles: u64,
    /// Facing away from the eye: dropped by back-face culling.
    pub back_facing: u64,
    /// With a vertex at or behind the eye: would need clipping (not rasterised here).
    pub clipped: u64,
    /// Pixel centres covered, summed over every triangle (back faces too).
    pub fragments: u64,
    /// The same over the front-facing triangles only (with back-face culling).
    pub front_fragments: u64,
    /// Pixels covered by at least one triangle.
    pub covered_pixels: u64,
}

/// Scan-converts every triangle of the scene (meshes and lone triangles, in world space).
pub fn raster_work(scene: &Scene) -> RasterWork {
    let cam = &scene.camera;
    let (w, h) = (cam.width as usize, cam.height as usize);
    let mut covered = vec![false; w * h];
    let mut work = RasterWork::default();
    for leaf in &scene.leaves {
        let world = |p: DVec3| leaf.transform.as_ref().map_or(p, |t| t.point_to_world(p));
        let triangles: Vec<[DVec3; 3]> = match &leaf.shape {
            Shape::Triangle(t) => vec![[world(t.a), world(t.b), world(t.c)]],
            Shape::Mesh(m) => m
                .triangles
                .iter()
                .map(|t| t.map(|i| world(m.positions[i as usize])))
                .collect(),
            _ => continue,
        };
        for tri in triangles {
            work.triangles += 1;
            let eye = cam.eye();
            let front = (tri[1] - tri[0]).cross(tri[2] - tri[0]).dot(eye - tri[0]) > 0.0;
            if !front {
                work.back_facing += 1;
            }
            let Some(p) = project_all(cam, &tri) else {
                work.clipped += 1;
                continue;
            };
            let n = rasterise(&p, w, h, &mut covered);
            work.fragments += n;
            if front {
                work.front_fragments += n;
            }
        }
    }
    work.covered_pixels = covered.iter().filter(|c| **c).count() as u64;
    work
}

fn project_all(cam: &Camera, tri: &[DVec3; 3]) -> Option<[DVec2; 3]> {
    Some([
        project(cam, tri[0])?,
        project(cam, tri[1])?,
        project(cam, tri[2])?,
    ])
}

/// Image coordinates (pixels, (0, 0) the top-left corner) where the line from the eye to q
/// crosses the image plane, or None for a point at or behind the eye. The camera's image point
/// is affine in the image coordinates, so this solves eye + s·(q − eye) = P0 + x·Px + y·Py.
pub fn project(cam: &Camera, q: DVec3) -> Option<DVec2> {
    let eye = cam.eye();
    let p0 = cam.image_point(0.0, 0.0);
    let px = cam.image_point(1.0, 0.0) - p0;
    let py = cam.image_point(0.0, 1.0) - p0;
    let m = DMat3::from_cols(px, py, -(q - eye));
    if m.determinant().abs() < 1e-300 {
        return None;
    }
    let [x, y, inv_s] = (m.inverse() * (eye - p0)).to_array();
    (inv_s > 0.0).then_some(DVec2::new(x, y))
}

/// Marks and counts the pixel centres (x + ½, y + ½) inside the projected triangle: inside
/// all three edges, or on an edge that is a top or a left edge.
fn rasterise(p: &[DVec2; 3], w: usize, h: usize, covered: &mut [bool]) -> u64 {
    // Orient the triangle one way round, so "inside" is the same side of every edge.
    let area = (p[1] - p[0]).perp_dot(p[2] - p[0]);
    if area == 0.0 || !area.is_finite() {
        return 0;
    }
    let v = if area > 0.0 {
        [p[0], p[1], p[2]]
    } else {
        [p[0], p[2], p[1]]
    };
    let lo = v[0].min(v[1]).min(v[2]);
    let hi = v[0].max(v[1]).max(v[2]);
    let x0 = (lo.x - 0.5).ceil().max(0.0) as usize;
    let y0 = (lo.y - 0.5).ceil().max(0.0) as usize;
    let x1 = ((hi.x - 0.5).floor().min(w as f64 - 1.0)).max(-1.0);
    let y1 = ((hi.y - 0.5).floor().min(h as f64 - 1.0)).max(-1.0);
    if x1 < 0.0 || y1 < 0.0 {
        return 0;
    }
    let mut count = 0;
    for y in y0..=y1 as usize {
        for x in x0..=x1 as usize {
            let c = DVec2::new(x as f64 + 0.5, y as f64 + 0.5);
            let inside = (0..3).all(|k| {
                let (a, b) = (v[k], v[(k + 1) % 3]);
                let e = (b - a).perp_dot(c - a);
                e > 0.0 || (e == 0.0 && top_left(a, b))
            });
            if inside {
                count += 1;
                covered[y * w + x] = true;
            }
        }
    }
    count
}

/// With y down and the vertices in this winding, an edge is a top edge when it runs level
/// and toward −x, a left edge when it runs toward +y.
fn top_left(a: DVec2, b: DVec2) -> bool {
    let d = b - a;
    (d.y == 0.0 && d.x < 0.0) || d.y > 0.0
}
