//! Recorders watch the tracer. Rendering uses `NoRecorder`, whose calls compile to nothing;
//! the inspector uses `TreeRecorder`, which builds the ray tree from the same calls. There is
//! one tracer, so the tree shown *is* the computation that coloured the pixel.

use super::tree::{HitInfo, Indices, Local, RayKind, RayNode, Termination};
use glam::DVec3;

/// The start of a ray, as the tracer announces it.
pub struct RayStart {
    pub kind: RayKind,
    pub depth: u32,
    pub origin: DVec3,
    pub direction: DVec3,
    pub weight: f64,
    pub coefficient: f64,
}

pub trait Recorder {
    /// False for recorders that throw everything away: the tracer then skips building records.
    const ACTIVE: bool;
    fn begin(&mut self, ray: RayStart);
    fn hit(&mut self, hit: HitInfo);
    fn local(&mut self, local: Local);
    fn indices(&mut self, indices: Indices);
    /// The open node is the shadow test of `light`: s is the fraction of its `rays` shadow
    /// rays that got through.
    fn shadow(&mut self, light: &str, t_max: f64, s: f64, rays: u32);
    /// The open node is a cone of n sampled rays (glossy or frosted), not a ray.
    fn samples(&mut self, n: u32);
    /// The open node's ray reached the light `light` (the stop rule at lights).
    fn lamp(&mut self, light: &str);
    /// The node closed last was divided by `divisor` before its parent weighted it (the
    /// attenuation of secondary rays by distance).
    fn attenuated(&mut self, divisor: f64);
    fn end(&mut self, color: DVec3, terminated: Option<Termination>);
}

pub struct NoRecorder;

impl Recorder for NoRecorder {
    const ACTIVE: bool = false;
    fn begin(&mut self, _: RayStart) {}
    fn hit(&mut self, _: HitInfo) {}
    fn local(&mut self, _: Local) {}
    fn indices(&mut self, _: Indices) {}
    fn shadow(&mut self, _: &str, _: f64, _: f64, _: u32) {}
    fn samples(&mut self, _: u32) {}
    fn lamp(&mut self, _: &str) {}
    fn attenuated(&mut self, _: f64) {}
    fn end(&mut self, _: DVec3, _: Option<Termination>) {}
}

/// Builds the tree depth-first: `begin` opens a node below the current one, `end` closes it.
#[derive(Default)]
pub struct TreeRecorder {
    open: Vec<RayNode>,
    root: Option<RayNode>,
}

impl TreeRecorder {
    pub fn new() -> TreeRecorder {
        TreeRecorder::default()
    }

    pub fn into_tree(self) -> RayNode {
        self.root.expect("the tracer closes every ray it opens")
    }

    fn current(&mut self) -> &mut RayNode {
        self.open.last_mut().expect("a ray is open")
    }
}

impl Recorder for TreeRecorder {
    const ACTIVE: bool = true;

    fn begin(&mut self, r: RayStart) {
        self.open.push(RayNode {
            kind: r.kind,
            depth: r.depth,
            origin: r.origin,
            direction: r.direction,
            weight: r.weight,
            coefficient: r.coefficient,
            indices: None,
            light: None,
            t_max: None,
            shadow: None,
            shadow_rays: None,
            samples: None,
            attenuation: None,
            hit: None,
            local: None,
            color: DVec3::ZERO,
            terminated: None,
            children: vec![],
        });
    }

    fn hit(&mut self, hit: HitInfo) {
        self.current().hit = Some(hit);
    }

    fn local(&mut self, local: Local) {
        self.current().local = Some(local);
    }

    fn indices(&mut self, indices: Indices) {
        self.current().indices = Some(indices);
    }

    fn shadow(&mut self, light: &str, t_max: f64, s: f64, rays: u32) {
        let node = self.current();
        node.light = Some(light.to_string());
        node.t_max = Some(t_max);
        node.shadow = Some(s);
        node.shadow_rays = (rays > 1).then_some(rays);
    }

    fn samples(&mut self, n: u32) {
        self.current().samples = Some(n);
    }

    fn lamp(&mut self, light: &str) {
        self.current().light = Some(light.to_string());
    }

    fn attenuated(&mut self, divisor: f64) {
        if let Some(child) = self.current().children.last_mut() {
            child.attenuation = Some(divisor);
        }
    }

    fn end(&mut self, color: DVec3, terminated: Option<Termination>) {
        let mut node = self.open.pop().expect("end matches begin");
        node.color = color;
        node.terminated = terminated;
        match self.open.last_mut() {
            Some(parent) => parent.children.push(node),
            None => self.root = Some(node),
        }
    }
}
