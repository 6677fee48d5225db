//! Recorders watch the tracer. Rendering uses `NoRecorder`, whose calls compile to nothing;
//! the inspector uses `TreeRecorder`, which builds the ray tree from the same calls. There is
//! one tracer, so the tree shown *is* the computation that coloured the pixel.

use super::tree::{HitInfo, Indices, LobeKind, Local, RayKind, RayNode, Termination};
use glam::DVec3;

/// The start of a ray, as the tracer announces it.
pub struct RayStart {
    /// Primary, shadow, reflection or refraction.
    pub kind: RayKind,
    /// 0 for the primary ray, one more per bounce.
    pub depth: u32,
    /// Where the ray starts (world space).
    pub origin: DVec3,
    /// Unit direction of the ray.
    pub direction: DVec3,
    /// Product of the kr/kt coefficients from the primary ray down to this ray.
    pub weight: f64,
    /// The coefficient the parent multiplies this ray's intensity by (1 for primary and shadow
    /// rays).
    pub coefficient: f64,
}

/// An observer of the tracer: it is told when each ray of the ray tree starts, what it met and how
/// it ended, in depth-first order.
pub trait Recorder {
    /// False for recorders that throw everything away: the tracer then skips building records.
    const ACTIVE: bool;
    /// A new ray starts: it becomes the open node, a child of the node open before it.
    fn begin(&mut self, ray: RayStart);
    /// The open node's ray hit a surface.
    fn hit(&mut self, hit: HitInfo);
    /// The local illumination at the open node's hit, term by term.
    fn local(&mut self, local: Local);
    /// The open node is a refraction ray, from medium n1 into n2.
    fn indices(&mut self, indices: Indices);
    /// The open node is the shadow test of `light`: s is the fraction of its `rays` shadow
    /// rays that got through.
    fn shadow(&mut self, light: &str, t_max: f64, s: f64, rays: u32);
    /// The open node is a cone of n sampled rays drawn from the `lobe`, not a ray.
    fn samples(&mut self, n: u32, lobe: LobeKind);
    /// The open node's ray reached the light `light` (the stop rule at lights).
    fn lamp(&mut self, light: &str);
    /// The node closed last was divided by `divisor` before its parent weighted it (the
    /// attenuation of secondary rays by distance).
    fn attenuated(&mut self, divisor: f64);
    /// The open node's ray is done: its intensity, and why it stopped early if it did; its parent
    /// becomes the open node again.
    fn end(&mut self, color: DVec3, terminated: Option<Termination>);
}

/// The recorder that records nothing (rendering): its calls compile away.
pub struct NoRecorder;

impl Recorder for NoRecorder {
    const ACTIVE: bool = false;
    fn begin(&mut self, _: RayStart) {}
    fn hit(&mut self, _: HitInfo) {}
    fn local(&mut self, _: Local) {}
    fn indices(&mut self, _: Indices) {}
    fn shadow(&mut self, _: &str, _: f64, _: f64, _: u32) {}
    fn samples(&mut self, _: u32, _: LobeKind) {}
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
    /// A recorder with no tree yet.
    pub fn new() -> TreeRecorder {
        TreeRecorder::default()
    }

    /// The ray tree of the pixel traced (panics when no ray was traced).
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
            lobe: None,
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

    fn samples(&mut self, n: u32, lobe: LobeKind) {
        let node = self.current();
        (node.samples, node.lobe) = (Some(n), Some(lobe));
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
