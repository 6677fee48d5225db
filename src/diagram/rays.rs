//! The rays of a ray tree as segments to draw: each traced ray from its origin to what it hit,
//! a shadow ray to its light or its blocker, a ray that hit nothing on towards the background;
//! with the hit's normal, and the numbers its label carries. Rays the recursion did not trace
//! (cut by the maximum depth, adaptive control or total internal reflection) have no segment.

use glam::DVec3;

use crate::trace::{RayKind, RayNode, Termination};

/// What a segment stands for, which sets its colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SegKind {
    /// A primary ray from the eye.
    Primary,
    /// A reflection ray.
    Reflection,
    /// A refraction ray.
    Refraction,
    /// A shadow ray that reached its light (s > 0).
    ShadowClear,
    /// A shadow ray stopped by an object (s = 0).
    ShadowBlocked,
    /// A ray that hit nothing: it brings back the background.
    Missed,
}

impl SegKind {
    /// Every kind, in the order of the legend.
    pub const ALL: [SegKind; 6] = [
        SegKind::Primary,
        SegKind::Reflection,
        SegKind::Refraction,
        SegKind::ShadowClear,
        SegKind::ShadowBlocked,
        SegKind::Missed,
    ];

    /// How a node of the tree is coloured (a ray not traced counts as missed).
    pub fn of(n: &RayNode) -> SegKind {
        match (n.kind, &n.hit) {
            (RayKind::Shadow, Some(_)) => SegKind::ShadowBlocked,
            (RayKind::Shadow, None) => SegKind::ShadowClear,
            (_, None) => SegKind::Missed,
            (RayKind::Primary, _) => SegKind::Primary,
            (RayKind::Reflection, _) => SegKind::Reflection,
            (RayKind::Refraction, _) => SegKind::Refraction,
        }
    }

    /// The legend's word for it.
    pub fn name(self) -> &'static str {
        match self {
            SegKind::Primary => "primary",
            SegKind::Reflection => "reflection",
            SegKind::Refraction => "refraction",
            SegKind::ShadowClear => "shadow",
            SegKind::ShadowBlocked => "blocked",
            SegKind::Missed => "background",
        }
    }

    /// A short form for narrow legends.
    pub fn short(self) -> &'static str {
        match self {
            SegKind::Primary => "prim",
            SegKind::Reflection => "refl",
            SegKind::Refraction => "refr",
            SegKind::ShadowClear => "shad",
            SegKind::ShadowBlocked => "block",
            SegKind::Missed => "bg",
        }
    }

    /// The colour of rays of this kind in figures (the explorer uses terminal colours of the
    /// same hues), as #rrggbb.
    pub fn rgb(self) -> [u8; 3] {
        match self {
            SegKind::Primary => [0x1f, 0x4e, 0xc8],
            SegKind::Reflection => [0x00, 0x9e, 0x8c],
            SegKind::Refraction => [0xb0, 0x2c, 0xc8],
            SegKind::ShadowClear => [0xe0, 0x9a, 0x00],
            SegKind::ShadowBlocked => [0xd6, 0x27, 0x28],
            SegKind::Missed => [0x7f, 0x7f, 0x7f],
        }
    }
}

/// One ray as drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    /// The node's place in the tree (child indices from the root).
    pub path: Vec<usize>,
    /// What the segment stands for (its colour).
    pub kind: SegKind,
    /// The ray's own kind (a missed ray is still a reflection or a refraction).
    pub ray: RayKind,
    /// Depth of the ray in the tree (0 for the primary ray).
    pub depth: u32,
    /// Where the ray starts, world space.
    pub from: DVec3,
    /// Unit direction.
    pub dir: DVec3,
    /// Where it ends: a hit, a blocker or the light; None when it goes on for ever (a missed
    /// ray, a shadow ray towards a directional light).
    pub to: Option<DVec3>,
    /// The hit point and its normal (facing the incoming ray), for a ray that hit a surface.
    pub normal: Option<(DVec3, DVec3)>,
    /// The object hit (a shadow ray's blocker), or the light a shadow ray looks for.
    pub object: Option<String>,
    /// The ray's intensity (a shadow ray's shadow factor s, as a grey).
    pub intensity: DVec3,
    /// Its weight in its parent: kr, kt (with Fresnel kr·R, kt·(1 − R)), 1 for the primary
    /// ray; s for a shadow ray.
    pub coefficient: f64,
}

impl Segment {
    /// The label drawn beside the ray: its kind and intensity ("reflection I = 0.462", "s = 1").
    pub fn label(&self) -> String {
        match self.kind {
            SegKind::ShadowClear | SegKind::ShadowBlocked => {
                format!("s = {}", short(self.coefficient))
            }
            _ => format!("{} I = {}", self.ray.name(), short_color(self.intensity)),
        }
    }
}

/// The segments of every traced ray of the tree, parents before children.
pub fn segments(root: &RayNode) -> Vec<Segment> {
    let mut out = vec![];
    walk(root, &mut vec![], &mut out);
    out
}

fn walk(n: &RayNode, path: &mut Vec<usize>, out: &mut Vec<Segment>) {
    if let Some(s) = segment(n, path) {
        out.push(s);
    }
    for (i, c) in n.children.iter().enumerate() {
        path.push(i);
        walk(c, path, out);
        path.pop();
    }
}

fn segment(n: &RayNode, path: &[usize]) -> Option<Segment> {
    let shadow = n.kind == RayKind::Shadow;
    let traced =
        shadow || matches!(n.terminated, None | Some(Termination::Background)) || n.hit.is_some();
    if !traced || n.cone().is_some() || !n.direction.is_finite() {
        // A glossy or frosted cone is drawn as its sampled rays, its children.
        return None;
    }
    let (kind, to, object, coefficient) = if shadow {
        let s = n.shadow.unwrap_or(0.0);
        match &n.hit {
            Some(h) => (
                SegKind::ShadowBlocked,
                Some(h.point),
                Some(h.object.clone()),
                s,
            ),
            None => {
                let reach = n.t_max.filter(|t| t.is_finite());
                let to = reach.map(|t| n.origin + t * n.direction);
                (SegKind::ShadowClear, to, n.light.clone(), s)
            }
        }
    } else {
        let kind = match (&n.hit, n.kind) {
            (None, _) => SegKind::Missed,
            (Some(_), RayKind::Primary) => SegKind::Primary,
            (Some(_), RayKind::Reflection) => SegKind::Reflection,
            (Some(_), _) => SegKind::Refraction,
        };
        let h = n.hit.as_ref();
        (
            kind,
            h.map(|h| h.point),
            h.map(|h| h.object.clone()),
            n.coefficient,
        )
    };
    let normal = if shadow {
        None
    } else {
        n.hit.as_ref().map(|h| (h.point, h.normal))
    };
    Some(Segment {
        path: path.to_vec(),
        kind,
        ray: n.kind,
        depth: n.depth,
        from: n.origin,
        dir: n.direction,
        to,
        normal,
        object,
        intensity: if shadow {
            DVec3::splat(coefficient)
        } else {
            n.color
        },
        coefficient,
    })
}

/// A number for labels: at most three decimals, trailing zeros dropped.
pub fn short(x: f64) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    let s = format!("{x:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

/// A colour for labels: one number when grey, else three.
pub fn short_color(c: DVec3) -> String {
    if c.x == c.y && c.y == c.z {
        short(c.x)
    } else {
        format!("({}, {}, {})", short(c.x), short(c.y), short(c.z))
    }
}
