//! The camera: a look-at camera with a vertical field of view, or the window model of the
//! lecture notes (eye, u, v, w, f and the window on the image plane).

use glam::DVec3;
use serde_saphyr::Spanned;

use super::{invalid, nonzero, pos, Invalid, Limits, Pos, TOP};
use crate::scene::format::{CameraSpec, Num, SceneFile};
use crate::scene::{Camera, Projection};

/// The file's camera, which every scene needs.
pub fn of(file: &SceneFile, limits: &Limits) -> Result<Camera, Invalid> {
    Ok(match &file.camera {
        Some(Spanned {
            value: None,
            referenced,
            ..
        }) => {
            return invalid(
                Pos::of(referenced),
                "`camera` is empty: give eye and look_at, or the window model",
            )
        }
        Some(
            c @ Spanned {
                value: Some(spec), ..
            },
        ) => camera(spec, pos(c), limits)?,
        None => {
            return invalid(
                TOP,
                "missing `camera`: a scene needs a camera (eye and look_at, or the window model)",
            )
        }
    })
}

fn camera(c: &CameraSpec, p: Pos, limits: &Limits) -> Result<Camera, Invalid> {
    let size = |s: &Option<Spanned<i64>>, default: i64, what: &str| -> Result<u32, Invalid> {
        let (v, at) = s.as_ref().map_or((default, p), |s| (s.value, pos(s)));
        if !(1..=1_000_000).contains(&v) {
            return invalid(
                at,
                format!("camera {what} must be between 1 and 1000000 pixels, got {v}"),
            );
        }
        Ok(v as u32)
    };
    let width = size(&c.width, 320, "width")?;
    let height = size(&c.height, 240, "height")?;
    if width as u64 * height as u64 > limits.max_pixels {
        return invalid(
            c.width.as_ref().map_or(p, pos),
            format!(
                "image of {width} × {height} pixels exceeds the budget of {} pixels (use --allow-huge to render it anyway)",
                limits.max_pixels
            ),
        );
    }
    let Some(eye) = c.eye.map(|v| v.0) else {
        return invalid(p, "camera needs an `eye`");
    };
    if let Some(window) = model(c, p)? {
        let need = |v: Option<DVec3>, k: &str| {
            v.map_or_else(|| invalid(p, format!("window camera needs `{k}`")), Ok)
        };
        let (u, v, w) = (
            need(c.u.as_ref().map(|x| x.value.0), "u")?,
            need(c.v.as_ref().map(|x| x.value.0), "v")?,
            need(c.w.as_ref().map(|x| x.value.0), "w")?,
        );
        let f = c.f.as_ref().map(|n| n.value.0).map_or_else(
            || invalid(p, "window camera needs the focal distance `f`"),
            Ok,
        )?;
        for (axis, k) in [(&c.u, "u"), (&c.v, "v"), (&c.w, "w")] {
            let axis = axis.as_ref().expect("checked above");
            nonzero(axis.value.0, pos(axis), &format!("camera axis {k}"))?;
        }
        // A pixel's ray is x·u + y·v + f·w: with f = 0 the window passes through the eye (the
        // centre ray is the zero vector), and axes in one plane fold the image onto a line.
        if f == 0.0 {
            return invalid(
                p,
                "window camera: the focal distance f must not be 0 (the window would pass through the eye)",
            );
        }
        let volume = u.dot(v.cross(w)).abs();
        if volume <= 1e-9 * u.length() * v.length() * w.length() {
            let at = c.v.as_ref().map_or(p, pos);
            return invalid(
                at,
                "window camera: the axes u, v and w must not lie in one plane (are two of them parallel?)",
            );
        }
        let [wl, wr, wt, wb] = window.value.map(|n| n.0);
        if wl == wr || wt == wb {
            return invalid(
                pos(window),
                "camera window has zero width or height (wl = wr or wt = wb)",
            );
        }
        return Ok(Camera {
            projection: Projection::Window {
                eye,
                u,
                v,
                w,
                f,
                window: window.value.map(|n| n.0),
            },
            width,
            height,
        });
    }
    let Some(target) = c.look_at.as_ref().map(|v| v.value.0) else {
        return invalid(
            p,
            "camera needs `look_at` (or the window model: u, v, w, f, window)",
        );
    };
    let forward = nonzero(target - eye, p, "look_at − eye")?;
    let (up, up_pos) = c.up.as_ref().map_or((DVec3::Y, p), |u| (u.value.0, pos(u)));
    let up = nonzero(up, up_pos, "camera up")?;
    if forward.cross(up).length() < 1e-9 {
        return invalid(
            up_pos,
            "camera up is parallel to the view direction (look_at − eye)",
        );
    }
    let fov = match &c.fov {
        None => 40.0,
        Some(f) if !(f.value.0 > 0.0 && f.value.0 < 180.0) => {
            return invalid(
                pos(f),
                format!(
                    "fov must be between 0 and 180 degrees (exclusive), got {}",
                    f.value
                ),
            )
        }
        Some(f) => f.value.0,
    };
    Ok(
        match c.handedness.as_ref().map(|h| h.value).unwrap_or_default() {
            crate::scene::format::Handedness::Left => {
                Camera::look_at(eye, target, up, fov, width, height)
            }
            crate::scene::format::Handedness::Right => {
                Camera::look_at_right_handed(eye, target, up, fov, width, height)
            }
        },
    )
}

/// Which model the camera's keys describe: the window model (its `window`, once the other
/// window keys are known to be there) or the look-at model (None). A key of one model beside
/// a key of the other is refused at the first key of the model that came second, since the
/// camera built would silently drop the other model's keys.
fn model(c: &CameraSpec, p: Pos) -> Result<Option<&Spanned<[Num; 4]>>, Invalid> {
    // The first of the keys written, in the file's order.
    let first = |keys: &[(Option<Pos>, &'static str)]| {
        keys.iter()
            .filter_map(|&(at, key)| Some((at?, key)))
            .min_by_key(|(at, _)| (at.line, at.column))
    };
    let look_at = first(&[
        (c.look_at.as_ref().map(pos), "look_at"),
        (c.up.as_ref().map(pos), "up"),
        (c.fov.as_ref().map(pos), "fov"),
        (c.handedness.as_ref().map(pos), "handedness"),
    ]);
    let window = first(&[
        (c.u.as_ref().map(pos), "u"),
        (c.v.as_ref().map(pos), "v"),
        (c.w.as_ref().map(pos), "w"),
        (c.f.as_ref().map(pos), "f"),
        (c.window.as_ref().map(pos), "window"),
    ]);
    match (look_at, window) {
        (Some(look), Some(win)) => {
            let ((at, key), (_, before)) =
                if (look.0.line, look.0.column) < (win.0.line, win.0.column) {
                    (win, look)
                } else {
                    (look, win)
                };
            invalid(
                at,
                format!(
                    "camera mixes the look-at model's keys with the window model's: `{key}` here, `{before}` earlier; \
                     use look_at, up, fov and handedness, or u, v, w, f and window, not both"
                ),
            )
        }
        (_, None) => Ok(None),
        (None, Some(_)) => match &c.window {
            Some(window) => Ok(Some(window)),
            None => invalid(p, "window camera needs the `window` [wl, wr, wt, wb]"),
        },
    }
}
