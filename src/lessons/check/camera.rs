//! Camera questions: where a pixel's centre lies on the image plane (the window point), and the
//! primary ray through it (its direction and origin).

use glam::DVec3;

use super::tree::tree_explanation;
use super::{signed, Mistake, Question, Traced, Worked};
use crate::lessons::{Answer, Exercise};
use crate::scene::{Camera, Projection};
use crate::trace::{text, RayNode};

pub(super) struct WindowPoint;

impl Question for WindowPoint {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        let ex = q.ex;
        let pixel = ex
            .pixel
            .ok_or_else(|| format!("exercise `{}`: window_point needs a pixel", ex.id))?;
        Ok(Answer::Vector(pixel_centre(&q.scene.camera, pixel)))
    }

    fn mistakes(&self, w: &Worked, ex: &Exercise) -> Vec<Mistake> {
        ex.pixel
            .map(|pixel| Mistake {
                answer: Answer::Vector(camera_point(&w.scene.camera, pixel)),
                hint: CAMERA_COORDINATES.into(),
            })
            .into_iter()
            .collect()
    }

    fn explain(&self, w: &Worked, ex: &Exercise, n: &RayNode) -> Result<Vec<String>, String> {
        Ok(through_the_pixel(w, ex, n))
    }
}

pub(super) struct RayDirection;

impl Question for RayDirection {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        Ok(Answer::Vector(q.node.direction))
    }

    fn mistakes(&self, w: &Worked, ex: &Exercise) -> Vec<Mistake> {
        let Some(pixel) = ex.pixel else {
            return Vec::new();
        };
        let cam = &w.scene.camera;
        let camera = camera_point(cam, pixel);
        vec![
            Mistake {
                answer: Answer::Vector(pixel_centre(cam, pixel) - cam.eye()),
                hint:
                    "normalise the direction: raytree's directions are unit vectors, so t is a distance".into(),
            },
            Mistake {
                answer: Answer::Vector(camera.normalize()),
                hint: CAMERA_COORDINATES.into(),
            },
            Mistake {
                answer: Answer::Vector(camera),
                hint: CAMERA_COORDINATES.into(),
            },
        ]
    }

    fn explain(&self, w: &Worked, ex: &Exercise, n: &RayNode) -> Result<Vec<String>, String> {
        Ok(through_the_pixel(w, ex, n))
    }
}

pub(super) struct RayOrigin;

impl Question for RayOrigin {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        Ok(Answer::Vector(q.node.origin))
    }

    fn explain(&self, _w: &Worked, _ex: &Exercise, n: &RayNode) -> Result<Vec<String>, String> {
        Ok(tree_explanation(n))
    }
}

const CAMERA_COORDINATES: &str = "that is in camera coordinates (p_C, with the eye at the origin): the answer is in world coordinates, p_W = e + p_C.x·u + p_C.y·v + p_C.z·w";

/// The pixel's point in camera coordinates: the window model's p_C, or for the look-at camera
/// the image point in its frame (right, up, forward).
fn camera_point(cam: &Camera, pixel: [u32; 2]) -> DVec3 {
    match &cam.projection {
        Projection::Window { f, window, .. } => window_pc(cam, pixel, *f, *window),
        Projection::LookAt {
            eye,
            forward,
            right,
            up,
            ..
        } => {
            let p = pixel_centre(cam, pixel) - *eye;
            DVec3::new(p.dot(*right), p.dot(*up), p.dot(*forward))
        }
    }
}

/// Δu and Δv of the window model (0 for a single column or row).
fn window_steps(cam: &Camera, [wl, wr, wt, wb]: [f64; 4]) -> (f64, f64) {
    let (nc, nr) = (cam.width as f64, cam.height as f64);
    let du = if nc > 1.0 {
        (wr - wl) / (nc - 1.0)
    } else {
        0.0
    };
    let dv = if nr > 1.0 {
        (wb - wt) / (nr - 1.0)
    } else {
        0.0
    };
    (du, dv)
}

/// p_C = (wl + i·Δu, wt + j·Δv, f).
fn window_pc(cam: &Camera, [x, y]: [u32; 2], f: f64, window: [f64; 4]) -> DVec3 {
    let (du, dv) = window_steps(cam, window);
    DVec3::new(window[0] + x as f64 * du, window[2] + y as f64 * dv, f)
}

/// The point of the image plane a pixel's primary ray passes through: the pixel's centre.
fn pixel_centre(cam: &Camera, [x, y]: [u32; 2]) -> DVec3 {
    cam.image_point(x as f64 + 0.5, y as f64 + 0.5)
}

/// The primary ray through the exercise's pixel, derived in the camera's own model. A ray
/// further down the tree, or one given by the exercise, has no camera derivation.
fn through_the_pixel(w: &Worked, ex: &Exercise, n: &RayNode) -> Vec<String> {
    let cam = &w.scene.camera;
    match ex.pixel {
        Some(pixel) if ex.node.is_empty() => match &cam.projection {
            Projection::Window { eye, f, window, .. } => {
                window_model(cam, pixel, *eye, *f, *window)
            }
            Projection::LookAt {
                eye,
                forward,
                right,
                up,
                tan_half_fov,
            } => look_at_model(cam, pixel, *eye, [*forward, *right, *up], *tan_half_fov),
        },
        _ => tree_explanation(n),
    }
}

/// The lecture's window model: the pixel's point in camera coordinates, then in the world.
fn window_model(
    cam: &Camera,
    [x, y]: [u32; 2],
    eye: DVec3,
    f: f64,
    [wl, wr, wt, wb]: [f64; 4],
) -> Vec<String> {
    let (nc, nr) = (cam.width as f64, cam.height as f64);
    let (du, dv) = window_steps(cam, [wl, wr, wt, wb]);
    let pc = window_pc(cam, [x, y], f, [wl, wr, wt, wb]);
    // The camera's own answer, so the derivation cannot drift from what is traced.
    let pw = pixel_centre(cam, [x, y]);
    vec![
        format!(
            "Δu = (wr − wl)/(nc − 1) = ({} − {})/({} − 1) = {}",
            text::num(wr),
            signed(wl),
            nc,
            text::num(du)
        ),
        format!(
            "Δv = (wb − wt)/(nr − 1) = ({} − {})/({} − 1) = {}",
            text::num(wb),
            signed(wt),
            nr,
            text::num(dv)
        ),
        format!(
            "p_C = (wl + i·Δu, wt + j·Δv, f) with i = {x}, j = {y}: {}",
            text::vec3(pc)
        ),
        format!("p_W = e + p_C.x·u + p_C.y·v + p_C.z·w = {}", text::vec3(pw)),
        format!("d = p_W − e = {}", text::vec3(pw - eye)),
        format!(
            "unit direction d/|d| = {}",
            text::vec3((pw - eye).normalize())
        ),
    ]
}

/// The look-at camera: its frame, the field of view, and the pixel's centre on the image plane.
fn look_at_model(
    cam: &Camera,
    pixel: [u32; 2],
    eye: DVec3,
    [forward, right, up]: [DVec3; 3],
    tan_half_fov: f64,
) -> Vec<String> {
    let p = pixel_centre(cam, pixel);
    vec![
        format!(
            "forward = {}, right = up × forward = {}, up' = forward × right = {}",
            text::vec3(forward),
            text::vec3(right),
            text::vec3(up)
        ),
        format!(
            "tan(fov/2) = {}, aspect = {}",
            text::num(tan_half_fov),
            text::num(cam.width as f64 / cam.height as f64)
        ),
        format!("pixel centre on the image plane: {}", text::vec3(p)),
        format!("unit direction = {}", text::vec3((p - eye).normalize())),
    ]
}
