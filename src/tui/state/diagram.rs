//! The diagram pane's state: whether it is open, the view, zoom and pan, and whether the BVH
//! boxes the selected ray's search visited are drawn over it. What it draws is computed from
//! the tree and the scene when it is drawn (`diagram` module), so it always follows them.

use glam::{DVec2, DVec3};

use super::{Note, Tone};
use crate::diagram::{Drawing, Frame, ViewChoice};
use crate::geometry::Ray;
use crate::scene::{Scene, Visited};
use crate::trace::{RayKind, RayNode};

/// Zoom steps of `<` and `>` (and the mouse wheel).
const ZOOM_STEP: f64 = 1.25;
const ZOOM_MAX: f64 = 64.0;
/// Arrow keys pan by this share of the pane.
const PAN_STEP: f64 = 0.1;

pub struct DiagramPane {
    pub open: bool,
    pub view: ViewChoice,
    /// 1 frames the rays; 2 shows half as much, twice as large.
    pub zoom: f64,
    /// The centre's offset, in shares of the framed width and height.
    pub pan: DVec2,
    /// Draw the BVH boxes the selected ray's search visited.
    pub bvh: bool,
    /// Where a drag over the pane last was (a cell).
    pub drag: Option<(u16, u16)>,
}

impl Default for DiagramPane {
    fn default() -> DiagramPane {
        DiagramPane {
            open: false,
            view: ViewChoice::Auto,
            zoom: 1.0,
            pan: DVec2::ZERO,
            bvh: false,
            drag: None,
        }
    }
}

impl DiagramPane {
    /// d: opens or closes the pane.
    pub fn toggle(&mut self) -> Note {
        self.open = !self.open;
        if self.open {
            (
                "ray diagram: v view · < > zoom · drag or arrows pan · b BVH boxes · m marks on the preview".into(),
                Tone::Info,
            )
        } else {
            ("ray diagram closed (d opens it)".into(), Tone::Info)
        }
    }

    /// v: the next view, framed afresh.
    pub fn cycle_view(&mut self) -> Note {
        self.view = self.view.next();
        self.reset();
        let open = if self.open {
            ""
        } else {
            " (d opens the diagram)"
        };
        (format!("diagram view: {}{open}", self.view), Tone::Info)
    }

    /// Back to the rays framed whole.
    pub fn reset(&mut self) {
        self.zoom = 1.0;
        self.pan = DVec2::ZERO;
    }

    /// Zooms in (`steps` > 0) or out.
    pub fn zoom_by(&mut self, steps: i32) {
        self.zoom = (self.zoom * ZOOM_STEP.powi(steps)).clamp(1.0 / 4.0, ZOOM_MAX);
    }

    /// Pans by arrow-key steps (right and up positive), in shares of what is shown.
    pub fn pan_steps(&mut self, dx: i32, dy: i32) {
        self.pan += DVec2::new(dx as f64, dy as f64) * PAN_STEP / self.zoom;
    }

    /// Pans as a drag from one cell to another over a pane of `cols` × `rows` cells: what was
    /// under the pointer stays under it.
    pub fn drag_to(&mut self, col: u16, row: u16, (cols, rows): (u16, u16)) {
        if let Some((c0, r0)) = self.drag {
            let d = DVec2::new(
                (col as f64 - c0 as f64) / cols.max(1) as f64,
                -(row as f64 - r0 as f64) / rows.max(1) as f64,
            );
            self.pan -= d / self.zoom;
        }
        self.drag = Some((col, row));
    }

    /// b: shows or hides the BVH boxes.
    pub fn toggle_bvh(&mut self, scene: Option<&Scene>) -> Note {
        let nodes = scene.map_or(0, |s| s.bvh_nodes());
        if nodes == 0 {
            // Nothing to show or hide: the switch stays as it is.
            let n = scene.map_or(0, |s| s.objects.len());
            let objects = if n == 1 { "1 object is" } else { "objects are" };
            let count = if n == 1 {
                String::new()
            } else {
                format!("{n} ")
            };
            return (
                format!("this scene has no BVH: {count}{objects} few enough to test every one"),
                Tone::Info,
            );
        }
        self.bvh = !self.bvh;
        if !self.bvh {
            return ("BVH boxes hidden".into(), Tone::Info);
        }
        let open = if self.open {
            ""
        } else {
            " (d opens the diagram)"
        };
        (
            format!("BVH boxes the selected ray's search visited{open}"),
            Tone::Info,
        )
    }

    /// The part of the view's plane shown in a canvas of `cols` × `rows` cells (braille: two
    /// dots across and four down a cell, which is about twice as high as wide, so the dots are
    /// square).
    pub fn frame(&self, d: &Drawing, cols: u16, rows: u16) -> Frame {
        let aspect = cols as f64 / (2.0 * rows.max(1) as f64);
        d.frame.with_aspect(aspect).zoomed(self.zoom, self.pan)
    }
}

/// The search a tree node's ray ran, replayed with its boxes recorded: the nearest-hit search
/// of a ray, the any-hit search of a shadow ray (up to its light).
pub fn visited(scene: &Scene, n: &RayNode) -> Visited {
    let ray = Ray::new(n.origin, n.direction);
    let shadow = n.kind == RayKind::Shadow;
    let reach = if shadow {
        n.t_max.unwrap_or(f64::INFINITY)
    } else {
        f64::INFINITY
    };
    if n.direction == DVec3::ZERO {
        return Visited::default();
    }
    scene.visited_boxes(&ray, reach, shadow)
}
