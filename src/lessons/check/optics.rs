//! Optics questions: the directions of the mirror ray (`v' = v − 2(v·n)n`) and of the refracted
//! ray (Snell's law, or total internal reflection).

use glam::DVec3;

use super::tree::tree_explanation;
use super::{signed, Mistake, Question, Traced, Worked};
use crate::lessons::{Answer, Exercise};
use crate::scene::Scene;
use crate::shading::optics::{reflect, refract};
use crate::trace::tree::HitInfo;
use crate::trace::{text, RayKind, RayNode, Termination};

pub(super) struct ReflectedDirection;

impl Question for ReflectedDirection {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        Ok(Answer::Vector(reflect(q.node.direction, q.hit()?.normal)))
    }

    fn mistakes(&self, w: &Worked, _ex: &Exercise) -> Vec<Mistake> {
        let Answer::Vector(v) = &w.expected else {
            return Vec::new();
        };
        vec![Mistake {
            answer: Answer::Vector(-*v),
            hint: "sign: with v pointing toward the surface, v' = v − 2(v·n)n points away from it"
                .into(),
        }]
    }

    fn explain(&self, _w: &Worked, _ex: &Exercise, n: &RayNode) -> Result<Vec<String>, String> {
        let Some(h) = &n.hit else {
            return Ok(tree_explanation(n));
        };
        let (d, nn) = (n.direction, h.normal);
        let vn = d.dot(nn);
        Ok(vec![
            incoming(d, nn),
            format!("v·n = {}", text::num(vn)),
            format!(
                "v' = v − 2(v·n)n = {} − 2·{}·{}",
                text::vec3(d),
                signed(vn),
                text::vec3(nn)
            ),
            format!("   = {}", text::vec3(reflect(d, nn))),
        ])
    }
}

pub(super) struct RefractedDirection;

impl Question for RefractedDirection {
    fn answer(&self, q: &Traced) -> Result<Answer, String> {
        let hit = q.hit()?;
        Ok(match refraction_child(q.node) {
            Some(c) if c.terminated == Some(Termination::TotalInternalReflection) => Answer::Tir,
            Some(c) => Answer::Vector(c.direction),
            // Not traced (opaque, or depth): Snell's law from the material's index.
            None => {
                let (n1, n2) = media(q.scene, hit);
                refract(q.node.direction, hit.normal, n1, n2).map_or(Answer::Tir, Answer::Vector)
            }
        })
    }

    fn mistakes(&self, w: &Worked, ex: &Exercise) -> Vec<Mistake> {
        let Some(n) = w.tree.find(&ex.node) else {
            return Vec::new();
        };
        let Some(h) = &n.hit else {
            return Vec::new();
        };
        let (n1, n2) = media(&w.scene, h);
        refract(n.direction, h.normal, n2, n1)
            .map(|t| Mistake {
                answer: Answer::Vector(t),
                hint: "n1 and n2 are swapped: η = n1/n2 with n1 the medium the ray comes from"
                    .into(),
            })
            .into_iter()
            .collect()
    }

    fn explain(&self, w: &Worked, _ex: &Exercise, n: &RayNode) -> Result<Vec<String>, String> {
        let Some(h) = &n.hit else {
            return Ok(tree_explanation(n));
        };
        let (n1, n2) = match refraction_child(n).and_then(|c| c.indices) {
            Some(i) => (i.n1, i.n2),
            None => media(&w.scene, h),
        };
        let mut out = vec![incoming(n.direction, h.normal)];
        out.extend(snell(n.direction, h, n1, n2));
        Ok(out)
    }
}

fn refraction_child(n: &RayNode) -> Option<&RayNode> {
    n.children.iter().find(|c| c.kind == RayKind::Refraction)
}

/// (n1, n2): the index of refraction of the medium the ray comes from, and of the one it
/// enters, when the tracer did not record them: the hit material's inside, air outside.
fn media(scene: &Scene, h: &HitInfo) -> (f64, f64) {
    let ior = scene
        .materials
        .iter()
        .find(|m| m.name == h.material)
        .map_or(1.0, |m| m.ior);
    if h.inside {
        (ior, 1.0)
    } else {
        (1.0, ior)
    }
}

fn incoming(v: DVec3, n: DVec3) -> String {
    format!(
        "incoming v = {} (unit), normal n = {} (facing v)",
        text::vec3(v),
        text::vec3(n)
    )
}

/// Snell's law in vector form: η and cos θ1, then either total internal reflection or cos θ2
/// and the refracted direction.
fn snell(d: DVec3, h: &HitInfo, n1: f64, n2: f64) -> Vec<String> {
    let nn = h.normal;
    let eta = n1 / n2;
    let c1 = -d.dot(nn);
    let k = 1.0 - eta * eta * (1.0 - c1 * c1);
    let side = if h.inside {
        "leaving the solid"
    } else {
        "entering the solid"
    };
    let mut out = vec![
        format!(
            "{side}: n1 = {}, n2 = {}, η = n1/n2 = {}",
            text::num(n1),
            text::num(n2),
            text::num(eta)
        ),
        format!(
            "c1 = cos θ1 = −v·n = {}  (θ1 = {}°)",
            text::num(c1),
            text::num(c1.clamp(-1.0, 1.0).acos().to_degrees())
        ),
        format!("1 − η²(1 − c1²) = {}", text::num(k)),
    ];
    if n1 > n2 {
        out.push(format!(
            "limiting angle: sin θc = n2/n1 → θc = {}°",
            text::num((n2 / n1).asin().to_degrees())
        ));
    }
    if k < 0.0 {
        out.push("negative: no refracted ray — total internal reflection (the energy goes into the mirror ray)".into());
        return out;
    }
    let c2 = k.sqrt();
    out.push(format!(
        "c2 = cos θ2 = √{} = {}  (θ2 = {}°)",
        text::num(k),
        text::num(c2),
        text::num(c2.acos().to_degrees())
    ));
    out.push(format!(
        "t = η·v + (η·c1 − c2)·n = {}·{} + {}·{}",
        text::num(eta),
        text::vec3(d),
        signed(eta * c1 - c2),
        text::vec3(nn)
    ));
    out.push(format!(
        "  = {}",
        text::vec3(eta * d + (eta * c1 - c2) * nn)
    ));
    out
}
