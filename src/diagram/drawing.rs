//! Everything a ray diagram draws, in the plane of one view: the rays of the tree shown, the
//! objects' outlines, the lights, the eye and the image plane, and the frame around the rays.
//! The explorer's pane and the `raytree diagram` figure both draw a `Drawing`, each in its
//! own medium.

use glam::{DVec2, DVec3};

use super::frame::Frame;
use super::outline::{outlines, LeafOutline};
use super::rays::{segments, SegKind, Segment};
use super::view::{View, ViewChoice};
use crate::scene::Scene;
use crate::shading::LightKind;
use crate::trace::RayNode;

/// A light as drawn: a point (point, rectangle and sphere lights at their centre) or a
/// direction its light travels along, from far away.
#[derive(Clone, Debug, PartialEq)]
pub struct LightMark {
    /// The light's name in the scene.
    pub name: String,
    /// Where it is drawn (world space): the position or centre; None for a directional light.
    pub at: Option<DVec3>,
    /// The unit direction its light travels, for a directional light; None otherwise.
    pub direction: Option<DVec3>,
    /// The first shadow ray of the whole tree that reaches it, from its start to its end: a
    /// light off the figure is drawn where that ray leaves it, so the ray is seen to arrive.
    pub reached_by: Option<(DVec3, DVec3)>,
}

/// The eye of a pixel's primary ray, the image plane and the pixel's point on it.
#[derive(Clone, Debug, PartialEq)]
pub struct Eye {
    /// The eye point, world space.
    pub at: DVec3,
    /// The image plane's corners, in order round it.
    pub image_plane: [DVec3; 4],
    /// Where the pixel's primary ray crosses the image plane, world space.
    pub pixel: DVec3,
}

/// A ray tree laid out in one orthographic view: its rays, the primitives' outlines, the lights and
/// the eye, in the view's plane.
#[derive(Clone, Debug)]
pub struct Drawing {
    /// Which world axes the drawing keeps.
    pub view: View,
    /// Around the rays of the whole tree (and the eye), before it is fitted to a pane.
    pub frame: Frame,
    /// Where planes are cut: the mean of the rays' coordinates along the axis the view drops.
    pub section: f64,
    /// The rays of the tree shown, parents before children.
    pub segments: Vec<Segment>,
    /// The outlines of the scene's primitives cut by or projected onto the view's plane.
    pub outlines: Vec<LeafOutline>,
    /// The scene's lights.
    pub lights: Vec<LightMark>,
    /// For a pixel's tree (not for a ray given by hand).
    pub eye: Option<Eye>,
}

impl Drawing {
    /// The drawing of `shown`, framed around `whole` (the tree at full depth while the levels
    /// are stepped, so the frame stays put as the rays appear), in the view chosen; `pixel`
    /// adds the eye and the image plane.
    pub fn new(
        scene: &Scene,
        shown: &RayNode,
        whole: &RayNode,
        choice: ViewChoice,
        pixel: Option<(u32, u32)>,
    ) -> Drawing {
        let all = segments(whole);
        let eye = pixel.map(|(x, y)| {
            let c = &scene.camera;
            let (w, h) = (c.width as f64, c.height as f64);
            Eye {
                at: c.eye(),
                image_plane: [
                    c.image_point(0.0, 0.0),
                    c.image_point(w, 0.0),
                    c.image_point(w, h),
                    c.image_point(0.0, h),
                ],
                pixel: c.image_point(x as f64 + 0.5, y as f64 + 0.5),
            }
        });
        let mut points: Vec<DVec3> = vec![];
        for s in &all {
            points.push(s.from);
            points.push(s.to.unwrap_or(s.from + s.dir));
        }
        let view = choice.resolve(&points);
        let axis = view.dropped_axis();
        let section = if points.is_empty() {
            0.0
        } else {
            points.iter().map(|p| p[axis]).sum::<f64>() / points.len() as f64
        };
        let frame = frame_around(scene, &all, eye.as_ref(), view);
        Drawing {
            view,
            frame,
            section,
            segments: segments(shown),
            outlines: outlines(scene, view, section),
            lights: scene.lights.iter().map(|l| light_mark(l, &all)).collect(),
            eye,
        }
    }

    /// A point's place in the drawing.
    pub fn at(&self, p: DVec3) -> DVec2 {
        self.view.project(p)
    }

    /// A segment's ends in the drawing; a ray without end runs to the edge of `frame`.
    pub fn ends(&self, s: &Segment, frame: &Frame) -> (DVec2, DVec2) {
        let a = self.at(s.from);
        let b = match s.to {
            Some(p) => self.at(p),
            None => frame.exit(a, self.view.project(s.dir)),
        };
        (a, b)
    }

    /// The segment of the node at `path`, if it was drawn.
    pub fn segment(&self, path: &[usize]) -> Option<&Segment> {
        self.segments.iter().find(|s| s.path == path)
    }
}

fn light_mark(l: &crate::shading::Light, all: &[Segment]) -> LightMark {
    let (at, direction) = match &l.kind {
        LightKind::Point { position, .. } => (Some(*position), None),
        LightKind::Directional { direction } => (None, Some(*direction)),
        LightKind::Rect { corner, u, v, .. } => (Some(*corner + 0.5 * (*u + *v)), None),
        LightKind::Sphere { center, .. } => (Some(*center), None),
    };
    let reached_by = all
        .iter()
        .filter(|s| s.kind == SegKind::ShadowClear && s.object.as_ref() == Some(&l.name))
        .find_map(|s| Some((s.from, s.to?)));
    LightMark {
        name: l.name.clone(),
        at,
        direction,
        reached_by,
    }
}

/// The frame around the rays: their origins and hits, the eye and the image plane; the objects
/// hit and a shadow ray's light only when they are not far off (a distant light would shrink
/// the rays to a dot: its ray runs off the edge instead); all objects when no ray hit any.
fn frame_around(scene: &Scene, all: &[Segment], eye: Option<&Eye>, view: View) -> Frame {
    let mut near: Vec<DVec2> = vec![];
    let mut lights: Vec<DVec2> = vec![];
    for s in all {
        near.push(view.project(s.from));
        match (s.kind, s.to) {
            (SegKind::ShadowClear, Some(p)) => lights.push(view.project(p)),
            (_, Some(p)) => near.push(view.project(p)),
            _ => {}
        }
    }
    if let Some(e) = eye {
        near.push(view.project(e.at));
        near.extend(e.image_plane.iter().map(|p| view.project(*p)));
    }
    if !all.iter().any(|s| s.normal.is_some()) {
        for o in scene.objects.iter().filter(|o| o.bounds.is_finite()) {
            near.push(view.project(o.bounds.min));
            near.push(view.project(o.bounds.max));
        }
    }
    // Rays seen end on (along the view's axis) project to a point or nearly: the frame is at
    // least a fifth of the rays' own length across, so the drawing keeps its scale. Not of a
    // shadow ray that reaches its light, which may be far off.
    let longest = all
        .iter()
        .filter(|s| s.kind != SegKind::ShadowClear)
        .filter_map(|s| s.to.map(|p| (p - s.from).length()))
        .filter(|l| l.is_finite())
        .fold(0.0, f64::max);
    let core = Frame::around(near.iter().copied(), 0.0).at_least(0.2 * longest);
    let big = core.size().max_element();
    let reach = Frame {
        min: core.min - big,
        max: core.max + big,
    };
    // The objects the rays hit, whole, unless one is much larger than the rays' reach.
    for s in all.iter().filter(|s| s.normal.is_some()) {
        let Some(o) = s
            .object
            .as_ref()
            .and_then(|n| scene.objects.iter().find(|o| &o.name == n))
        else {
            continue;
        };
        let (lo, hi) = (view.project(o.bounds.min), view.project(o.bounds.max));
        if o.bounds.is_finite() && reach.contains(lo) && reach.contains(hi) {
            near.push(lo);
            near.push(hi);
        }
    }
    near.extend(lights.into_iter().filter(|p| reach.contains(*p)));
    // Some way along each ray that leaves for the background, so that it is seen going.
    for s in all.iter().filter(|s| s.kind == SegKind::Missed) {
        near.push(view.project(s.from + s.dir * 0.5 * big.max(1.0)));
    }
    Frame::around(near, 0.08).at_least(0.2 * longest)
}
