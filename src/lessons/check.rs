//! Checking an answer: raytree computes the expected value from the lesson's scene (never from
//! a number typed into the exercise), compares, and explains.

use glam::DVec3;

use super::answer::{parse_answer, Answer};
use super::exercise::{Ask, Exercise, Lesson};
use crate::geometry::{Ray, Shape};
use crate::render::antialias::{self, Square, Step};
use crate::render::film::Film;
use crate::render::{render_simple, RenderOptions};
use crate::scene::{Antialias, Projection};
use crate::scene::{Integrator, Limits, Scene};
use crate::shading::optics::{reflect, refract};
use crate::shading::Highlight;
use crate::stats::Stats;
use crate::trace::TraceOptions;
use crate::trace::{text, RayKind, RayNode, Termination, Tracer};

/// Everything the exercise is about, computed.
pub struct Worked {
    pub scene: Scene,
    pub ray: Ray,
    pub depth: u32,
    pub tree: RayNode,
    pub expected: Answer,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    pub correct: bool,
    pub given: Answer,
    pub expected: Answer,
    pub tolerance: f64,
    /// A common mistake that explains a wrong answer.
    pub hint: Option<String>,
}

impl Verdict {
    pub fn message(&self) -> String {
        if self.correct {
            format!(
                "right: {} (expected {}, tolerance {})",
                self.given.show(),
                self.expected.show(),
                text::num(self.tolerance)
            )
        } else {
            let mut s = format!(
                "wrong: {} is not within {} of the expected answer",
                self.given.show(),
                text::num(self.tolerance)
            );
            if let Some(h) = &self.hint {
                s.push_str(&format!("\nhint: {h}"));
            }
            s
        }
    }
}

fn load(lesson: &Lesson, ex: &Exercise) -> Result<Scene, String> {
    crate::scene::load(&lesson.scene_path(ex), &Limits::default()).map_err(|e| e.to_string())
}

fn exercise_ray(scene: &Scene, ex: &Exercise) -> Result<Ray, String> {
    match (&ex.pixel, &ex.ray) {
        (Some([x, y]), _) => {
            if *x >= scene.camera.width || *y >= scene.camera.height {
                return Err(format!(
                    "exercise `{}`: pixel {x},{y} is outside the image",
                    ex.id
                ));
            }
            Ok(scene.camera.pixel_ray(*x, *y))
        }
        (None, Some(r)) if r.direction != DVec3::ZERO => Ok(Ray::new(r.origin, r.direction)),
        // A question about the whole image: the tree shown is that of the first pixel.
        (None, None) if ex.ask.about_image() => Ok(scene.camera.pixel_ray(0, 0)),
        _ => Err(format!(
            "exercise `{}` needs a pixel or a ray with a non-zero direction",
            ex.id
        )),
    }
}

fn trace(scene: &Scene, ray: &Ray, options: TraceOptions) -> RayNode {
    Tracer::new(scene).with_options(options).inspect(ray)
}

/// The tree node an exercise asks about.
fn node<'t>(tree: &'t RayNode, ex: &Exercise) -> Result<&'t RayNode, String> {
    tree.find(&ex.node).ok_or_else(|| {
        format!(
            "exercise `{}`: the ray tree has no node `{}`",
            ex.id, ex.node
        )
    })
}

/// How an exercise renders: the scene's own settings (seed 0), with `depth` as max_depth.
fn render_options(scene: &Scene, ex: &Exercise) -> RenderOptions {
    let mut o = RenderOptions::of(scene);
    if let Some(d) = ex.depth {
        o.max_depth = d.clamp(1, 64);
    }
    o
}

/// Renders what an image exercise is about: its pixel alone (its value, and the work it took
/// with its corners traced on the spot), or without a pixel the whole image (the work only).
fn rendered(
    scene: &Scene,
    ex: &Exercise,
    options: RenderOptions,
) -> Result<(DVec3, Stats), String> {
    match ex.pixel {
        Some([x, y]) => {
            if x >= scene.camera.width || y >= scene.camera.height {
                return Err(format!(
                    "exercise `{}`: pixel {x},{y} is outside the image",
                    ex.id
                ));
            }
            let film = Film::new(scene, options);
            let mut t = film.tracer();
            let value = film.lone_pixel(&mut t, x, y);
            Ok((value, t.stats))
        }
        None if ex.ask == Ask::PixelValue => {
            Err(format!("exercise `{}`: pixel_value needs a pixel", ex.id))
        }
        None => Ok((DVec3::ZERO, render_simple(scene, options).1)),
    }
}

/// The value an exercise asks for, read off a traced tree.
fn answer_from(scene: &Scene, ray: &Ray, tree: &RayNode, ex: &Exercise) -> Result<Answer, String> {
    let n = node(tree, ex)?;
    let need_hit = || {
        n.hit
            .as_ref()
            .ok_or_else(|| format!("exercise `{}`: the ray hits nothing", ex.id))
    };
    let light = || {
        let name = ex
            .light
            .as_deref()
            .ok_or_else(|| format!("exercise `{}` needs `light`", ex.id))?;
        n.local
            .as_ref()
            .and_then(|l| l.lights.iter().find(|t| t.light == name))
            .ok_or_else(|| {
                format!(
                    "exercise `{}`: no term for light `{name}` at this node",
                    ex.id
                )
            })
    };
    Ok(match ex.ask {
        Ask::WindowPoint => {
            let [x, y] = ex
                .pixel
                .ok_or_else(|| format!("exercise `{}`: window_point needs a pixel", ex.id))?;
            Answer::Vector(scene.camera.image_point(x as f64 + 0.5, y as f64 + 0.5))
        }
        Ask::RayDirection => Answer::Vector(n.direction),
        Ask::RayOrigin => Answer::Vector(n.origin),
        Ask::Intensity => Answer::color(n.color),
        Ask::Local => Answer::color(n.local.as_ref().map_or(DVec3::ZERO, |l| l.total())),
        Ask::HitT => Answer::Number(need_hit()?.t),
        Ask::HitPoint => Answer::Vector(need_hit()?.point),
        Ask::Normal => Answer::Vector(need_hit()?.normal),
        Ask::ReflectedDirection => Answer::Vector(reflect(n.direction, need_hit()?.normal)),
        Ask::RefractedDirection => {
            let hit = need_hit()?;
            match n.children.iter().find(|c| c.kind == RayKind::Refraction) {
                Some(c) if c.terminated == Some(Termination::TotalInternalReflection) => {
                    Answer::Tir
                }
                Some(c) => Answer::Vector(c.direction),
                None => {
                    // Not traced (opaque, or depth): Snell's law from the material's index.
                    let ior = scene
                        .materials
                        .iter()
                        .find(|m| m.name == hit.material)
                        .map_or(1.0, |m| m.ior);
                    let (n1, n2) = if hit.inside { (ior, 1.0) } else { (1.0, ior) };
                    refract(n.direction, hit.normal, n1, n2).map_or(Answer::Tir, Answer::Vector)
                }
            }
        }
        Ask::ShadowFactor => Answer::Number(light()?.shadow),
        Ask::Diffuse => Answer::color(light()?.diffuse),
        Ask::Specular => Answer::color(light()?.specular),
        Ask::Barycentric => Answer::Vector(
            need_hit()?
                .barycentric
                .ok_or_else(|| format!("exercise `{}`: the hit is not on a triangle", ex.id))?,
        ),
        Ask::PixelValue => Answer::color(rendered(scene, ex, render_options(scene, ex))?.0),
        Ask::PrimaryRays => Answer::Number(
            rendered(scene, ex, render_options(scene, ex))?
                .1
                .primary_rays as f64,
        ),
        Ask::SquaresSplit => {
            Answer::Number(rendered(scene, ex, render_options(scene, ex))?.1.aa_splits as f64)
        }
        Ask::Segments => {
            let name = ex
                .object
                .as_deref()
                .ok_or_else(|| format!("exercise `{}` needs `object`", ex.id))?;
            let o = scene
                .object_index(name)
                .ok_or_else(|| format!("exercise `{}`: no object `{name}`", ex.id))?;
            let (list, _) = scene.object_trace(o, ray, false);
            Answer::Segments(
                list.iter()
                    .filter(|s| s.t_out >= 0.0)
                    .map(|s| (s.t_in, s.t_out))
                    .collect(),
            )
        }
    })
}

/// Traces the exercise and computes its expected answer.
pub fn work(lesson: &Lesson, ex: &Exercise) -> Result<Worked, String> {
    let scene = load(lesson, ex)?;
    let ray = exercise_ray(&scene, ex)?;
    let depth = ex.depth.unwrap_or(scene.max_depth).clamp(1, 64);
    let tree = trace(
        &scene,
        &ray,
        TraceOptions {
            max_depth: depth,
            shadows: true,
        },
    );
    let expected = answer_from(&scene, &ray, &tree, ex)?;
    Ok(Worked {
        scene,
        ray,
        depth,
        tree,
        expected,
    })
}

pub fn check(lesson: &Lesson, ex: &Exercise, input: &str) -> Result<Verdict, String> {
    let given = parse_answer(input, ex.ask == Ask::Segments)?;
    let w = work(lesson, ex)?;
    let correct = given.matches(&w.expected, ex.tolerance);
    let hint = if correct { None } else { hint(&w, ex, &given) };
    Ok(Verdict {
        correct,
        given,
        expected: w.expected,
        tolerance: ex.tolerance,
        hint,
    })
}

/// Recomputes the answer the way a common mistake would; if the student's answer matches one,
/// that mistake is the hint.
fn hint(w: &Worked, ex: &Exercise, given: &Answer) -> Option<String> {
    let tol = ex.tolerance;
    let full = TraceOptions {
        max_depth: w.depth,
        shadows: true,
    };
    let mut tries: Vec<(Answer, &str)> = Vec::new();
    let retrace = |scene: &Scene, options: TraceOptions| {
        answer_from(scene, &w.ray, &trace(scene, &w.ray, options), ex).ok()
    };
    match ex.ask {
        Ask::Intensity | Ask::Local | Ask::Diffuse | Ask::Specular => {
            if let Some(a) = retrace(
                &w.scene,
                TraceOptions {
                    shadows: false,
                    ..full
                },
            ) {
                tries.push((a, "you left out the shadow term: a shadow ray toward a light is blocked here, so s = 0 for it"));
            }
            let mut swapped = w.scene.clone();
            for m in &mut swapped.materials {
                m.highlight = if m.highlight == Highlight::Blinn {
                    Highlight::Phong
                } else {
                    Highlight::Blinn
                };
            }
            if let Some(a) = retrace(&swapped, full) {
                tries.push((a, "you used the other highlight model: check whether the material uses Blinn (h·n)^m or Phong (r·v)^m"));
            }
            let mut dark = w.scene.clone();
            dark.ambient = DVec3::ZERO;
            if let Some(a) = retrace(&dark, full) {
                tries.push((a, "you ignored the ambient term ka·Ia·O"));
            }
            let mut unattenuated = w.scene.clone();
            for l in &mut unattenuated.lights {
                if let crate::shading::LightKind::Point { attenuation, .. } = &mut l.kind {
                    *attenuation = [1.0, 0.0, 0.0];
                }
            }
            if let Some(a) = retrace(&unattenuated, full) {
                tries.push((
                    a,
                    "you left out the distance attenuation fatt = 1/(c0 + c1·d + c2·d²)",
                ));
            }
            if w.depth > 1 {
                if let Some(a) = retrace(
                    &w.scene,
                    TraceOptions {
                        max_depth: 1,
                        ..full
                    },
                ) {
                    tries.push((a, "you stopped at the local term: add kr·I_r and kt·I_t from the secondary rays"));
                }
            }
        }
        Ask::HitT | Ask::HitPoint => {
            let node = w.tree.find(&ex.node);
            if let Some((n, h)) = node.and_then(|n| n.hit.as_ref().map(|h| (n, h))) {
                if let Some(o_idx) = w.scene.object_index(&h.object) {
                    let ray = Ray {
                        origin: n.origin,
                        dir: n.direction,
                    };
                    let list = w.scene.object_trace(o_idx, &ray, false).0;
                    if let Some(s) = list.iter().find(|s| (s.t_in - h.t).abs() < 1e-9) {
                        let far = if ex.ask == Ask::HitT {
                            Answer::Number(s.t_out)
                        } else {
                            Answer::Vector(ray.at(s.t_out))
                        };
                        tries.push((
                            far,
                            "you took the far root: the nearest hit is the smaller positive t",
                        ));
                    }
                }
            }
        }
        Ask::RayDirection => {
            if let Some([x, y]) = ex.pixel {
                let p = w.scene.camera.image_point(x as f64 + 0.5, y as f64 + 0.5);
                tries.push((Answer::Vector(p - w.scene.camera.eye()), "normalise the direction: raytree's directions are unit vectors, so t is a distance"));
            }
        }
        Ask::ReflectedDirection => {
            if let Answer::Vector(v) = &w.expected {
                tries.push((Answer::Vector(-*v), "sign: with v pointing toward the surface, v' = v − 2(v·n)n points away from it"));
            }
        }
        Ask::RefractedDirection => {
            if let Some(n) = w.tree.find(&ex.node) {
                if let Some(h) = &n.hit {
                    let ior = w
                        .scene
                        .materials
                        .iter()
                        .find(|m| m.name == h.material)
                        .map_or(1.0, |m| m.ior);
                    let (n1, n2) = if h.inside { (1.0, ior) } else { (ior, 1.0) };
                    if let Some(t) = refract(n.direction, h.normal, n1, n2) {
                        tries.push((Answer::Vector(t), "n1 and n2 are swapped: η = n1/n2 with n1 the medium the ray comes from"));
                    }
                }
            }
        }
        Ask::PixelValue | Ask::PrimaryRays => {
            let options = render_options(&w.scene, ex);
            let adaptive = matches!(options.antialias, Antialias::Adaptive { .. });
            if ex.ask == Ask::PixelValue
                && w.scene.integrator == Integrator::Whitted
                && (options.spp > 1 || adaptive)
            {
                tries.push((
                    Answer::color(w.tree.color),
                    "that is the ray through the pixel's centre alone: the pixel is the mean of all its rays",
                ));
            }
            if adaptive {
                let grid = RenderOptions {
                    antialias: Antialias::Grid,
                    ..options
                };
                if let Ok((value, stats)) = rendered(&w.scene, ex, grid) {
                    let a = if ex.ask == Ask::PixelValue {
                        Answer::color(value)
                    } else {
                        Answer::Number(stats.primary_rays as f64)
                    };
                    tries.push((a, "that is the full grid of spp rays: adaptive antialiasing splits only the squares whose corners differ by more than the threshold, and a square it does not split takes the mean of its 4 corners"));
                }
                if ex.ask == Ask::PrimaryRays && ex.pixel.is_none() {
                    if let Answer::Number(n) = w.expected {
                        let (nc, nr) = (w.scene.camera.width as f64, w.scene.camera.height as f64);
                        tries.push((
                            Answer::Number(n - (nc + 1.0) * (nr + 1.0) + 4.0 * nc * nr),
                            "neighbouring pixels share their corners: each of the (w + 1)·(h + 1) corners of the image is traced once",
                        ));
                    }
                }
            }
        }
        Ask::Normal => {
            if let Answer::Vector(v) = &w.expected {
                tries.push((Answer::Vector(-*v), "the normal used for shading faces the incoming ray (flip it when the ray is inside)"));
            }
        }
        _ => {}
    }
    tries
        .into_iter()
        .find(|(a, _)| given.matches(a, tol) && !a.matches(&w.expected, tol))
        .map(|(_, h)| h.to_string())
}

/// The worked derivation, step by step, with the numbers filled in.
pub fn explain(lesson: &Lesson, ex: &Exercise) -> Result<Vec<String>, String> {
    let w = work(lesson, ex)?;
    let mut out = vec![format!("{}: {}", ex.id, ex.question.trim())];
    let n = node(&w.tree, ex)?;
    match ex.ask {
        Ask::WindowPoint | Ask::RayDirection if ex.pixel.is_some() && ex.node.is_empty() => {
            let [x, y] = ex.pixel.unwrap();
            let cam = &w.scene.camera;
            match &cam.projection {
                Projection::Window {
                    eye,
                    f,
                    window: [wl, wr, wt, wb],
                    ..
                } => {
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
                    out.push(format!(
                        "Δu = (wr − wl)/(nc − 1) = ({} − {})/({} − 1) = {}",
                        text::num(*wr),
                        signed(*wl),
                        nc,
                        text::num(du)
                    ));
                    out.push(format!(
                        "Δv = (wb − wt)/(nr − 1) = ({} − {})/({} − 1) = {}",
                        text::num(*wb),
                        signed(*wt),
                        nr,
                        text::num(dv)
                    ));
                    let pc = DVec3::new(wl + x as f64 * du, wt + y as f64 * dv, *f);
                    out.push(format!(
                        "p_C = (wl + i·Δu, wt + j·Δv, f) with i = {x}, j = {y}: {}",
                        text::vec3(pc)
                    ));
                    // The camera's own answer, so the derivation cannot drift from what is traced.
                    let pw = cam.image_point(x as f64 + 0.5, y as f64 + 0.5);
                    out.push(format!(
                        "p_W = e + p_C.x·u + p_C.y·v + p_C.z·w = {}",
                        text::vec3(pw)
                    ));
                    out.push(format!("d = p_W − e = {}", text::vec3(pw - *eye)));
                    out.push(format!(
                        "unit direction d/|d| = {}",
                        text::vec3((pw - *eye).normalize())
                    ));
                }
                Projection::LookAt {
                    eye,
                    forward,
                    right,
                    up,
                    tan_half_fov,
                } => {
                    out.push(format!(
                        "forward = {}, right = up × forward = {}, up' = forward × right = {}",
                        text::vec3(*forward),
                        text::vec3(*right),
                        text::vec3(*up)
                    ));
                    out.push(format!(
                        "tan(fov/2) = {}, aspect = {}",
                        text::num(*tan_half_fov),
                        text::num(cam.width as f64 / cam.height as f64)
                    ));
                    let p = cam.image_point(x as f64 + 0.5, y as f64 + 0.5);
                    out.push(format!(
                        "pixel centre on the image plane: {}",
                        text::vec3(p)
                    ));
                    out.push(format!(
                        "unit direction = {}",
                        text::vec3((p - *eye).normalize())
                    ));
                }
            }
        }
        Ask::HitT | Ask::HitPoint | Ask::Normal => {
            out.push(format!(
                "ray o = {}, d = {} (unit)",
                text::vec3(n.origin),
                text::vec3(n.direction)
            ));
            if let Some(h) = &n.hit {
                let leaf = w.scene.leaves.iter().find(|l| l.name == h.leaf);
                if let Some(Shape::Sphere(s)) =
                    leaf.filter(|l| l.transform.is_none()).map(|l| &l.shape)
                {
                    let oc = n.origin - s.center;
                    let b = n.direction.dot(oc);
                    let c = oc.length_squared() - s.radius * s.radius;
                    out.push(format!(
                        "sphere c = {}, r = {}: t² + 2(d·(o − c))t + |o − c|² − r² = 0",
                        text::vec3(s.center),
                        text::num(s.radius)
                    ));
                    out.push(format!(
                        "b = d·(o − c) = {}, c' = |o − c|² − r² = {}",
                        text::num(b),
                        text::num(c)
                    ));
                    let disc = b * b - c;
                    out.push(format!(
                        "discriminant b² − c' = {}{}",
                        text::num(disc),
                        if disc.abs() < 1e-9 {
                            " (zero: the ray is tangent, a double root)"
                        } else {
                            ""
                        }
                    ));
                    out.push(format!(
                        "t = −b ± √(b² − c') → nearest positive root t = {}",
                        text::num(h.t)
                    ));
                } else {
                    out.push(format!("nearest hit on {}: t = {}", h.leaf, text::num(h.t)));
                }
                out.push(format!("point p = o + t·d = {}", text::vec3(h.point)));
                out.push(format!(
                    "unit normal facing the ray n = {}",
                    text::vec3(h.normal)
                ));
            } else {
                out.push("the ray hits nothing".into());
            }
        }
        Ask::ReflectedDirection | Ask::RefractedDirection if n.hit.is_some() => {
            let h = n.hit.as_ref().unwrap();
            let (d, nn) = (n.direction, h.normal);
            out.push(format!(
                "incoming v = {} (unit), normal n = {} (facing v)",
                text::vec3(d),
                text::vec3(nn)
            ));
            let vn = d.dot(nn);
            if ex.ask == Ask::ReflectedDirection {
                out.push(format!("v·n = {}", text::num(vn)));
                out.push(format!(
                    "v' = v − 2(v·n)n = {} − 2·{}·{}",
                    text::vec3(d),
                    signed(vn),
                    text::vec3(nn)
                ));
                out.push(format!("   = {}", text::vec3(reflect(d, nn))));
            } else {
                let (n1, n2) = match n
                    .children
                    .iter()
                    .find(|c| c.kind == RayKind::Refraction)
                    .and_then(|c| c.indices)
                {
                    Some(i) => (i.n1, i.n2),
                    None => {
                        let ior = w
                            .scene
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
                };
                let eta = n1 / n2;
                let c1 = -vn;
                let k = 1.0 - eta * eta * (1.0 - c1 * c1);
                out.push(format!(
                    "{}: n1 = {}, n2 = {}, η = n1/n2 = {}",
                    if h.inside {
                        "leaving the solid"
                    } else {
                        "entering the solid"
                    },
                    text::num(n1),
                    text::num(n2),
                    text::num(eta)
                ));
                out.push(format!(
                    "c1 = cos θ1 = −v·n = {}  (θ1 = {}°)",
                    text::num(c1),
                    text::num(c1.clamp(-1.0, 1.0).acos().to_degrees())
                ));
                out.push(format!("1 − η²(1 − c1²) = {}", text::num(k)));
                if n1 > n2 {
                    out.push(format!(
                        "limiting angle: sin θc = n2/n1 → θc = {}°",
                        text::num((n2 / n1).asin().to_degrees())
                    ));
                }
                if k < 0.0 {
                    out.push("negative: no refracted ray — total internal reflection (the energy goes into the mirror ray)".into());
                } else {
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
                }
            }
        }
        Ask::ShadowFactor | Ask::Diffuse | Ask::Specular
            if n.local.is_some() && ex.light.is_some() =>
        {
            let name = ex.light.as_deref().unwrap();
            let h = n.hit.as_ref().unwrap();
            out.push(format!(
                "hit {} at p = {}, n = {}",
                h.object,
                text::vec3(h.point),
                text::vec3(h.normal)
            ));
            let m = w.scene.materials.iter().find(|m| m.name == h.material);
            let light = w.scene.lights.iter().find(|l| l.name == name);
            if let (Some(t), Some(m), Some(light)) = (
                n.local
                    .as_ref()
                    .unwrap()
                    .lights
                    .iter()
                    .find(|t| t.light == name),
                m,
                light,
            ) {
                out.push(format!(
                    "toward {name}: l = {}, n·l = {}",
                    text::vec3(t.l),
                    text::num(t.n_dot_l)
                ));
                match &light.kind {
                    crate::shading::LightKind::Point {
                        position,
                        attenuation: [c0, c1, c2],
                    } => {
                        let dist = (*position - h.point).length();
                        out.push(format!("point light at {}: distance d = {}; a shadow ray is blocked by a hit with 0 < t < d", text::vec3(*position), text::num(dist)));
                        out.push(format!(
                            "fatt = 1/(c0 + c1·d + c2·d²) = 1/({} + {}·{} + {}·{}²) = {}",
                            text::num(*c0),
                            text::num(*c1),
                            text::num(dist),
                            text::num(*c2),
                            text::num(dist),
                            text::num(t.attenuation)
                        ));
                    }
                    crate::shading::LightKind::Directional { .. } => {
                        out.push("directional light: a shadow ray is blocked by any hit with t > 0; fatt = 1".into());
                    }
                    crate::shading::LightKind::Rect { samples, .. } => {
                        out.push(format!(
                            "area light: l points to its centre; s = the fraction of {} shadow rays (to the centres of a {samples} × {samples} grid on it) that reach it",
                            samples * samples
                        ));
                    }
                    crate::shading::LightKind::Sphere {
                        radius, samples, ..
                    } => {
                        out.push(format!(
                            "sphere light of radius {}: l points to its centre (fatt as for a point light); s = the fraction of {} shadow rays (to a {samples} × {samples} pattern on the disc it shows this point) that reach it",
                            text::num(*radius),
                            samples * samples
                        ));
                    }
                }
                match (
                    &t.skipped,
                    n.children.iter().find(|c| c.light.as_deref() == Some(name)),
                ) {
                    (Some(why), _) => out.push(format!(
                        "no shadow ray: {why}, so the light adds nothing (s = 0)"
                    )),
                    (None, Some(sh)) if light.shadow_rays() > 1 => {
                        let count = light.shadow_rays();
                        let through = (t.shadow * count as f64).round();
                        out.push(match &sh.hit {
                            Some(b) => format!(
                                "{through} of the {count} shadow rays reach the light (the first one blocked meets {} at t = {}) → s = {through}/{count} = {}",
                                b.object,
                                text::num(b.t),
                                text::num(t.shadow)
                            ),
                            None => format!(
                                "all {count} shadow rays reach the light → s = 1"
                            ),
                        })
                    }
                    (None, Some(sh)) => match &sh.hit {
                        Some(b) => out.push(format!(
                            "shadow ray from {} toward l: blocked by {} at t = {} → s = 0",
                            text::vec3(sh.origin),
                            b.object,
                            text::num(b.t)
                        )),
                        None => out.push(format!(
                            "shadow ray from {} toward l: reaches the light → s = 1",
                            text::vec3(sh.origin)
                        )),
                    },
                    _ => {}
                }
                let il = light.intensity;
                let raw_d = t.attenuation * il * m.kd * m.color * t.n_dot_l.max(0.0);
                out.push(format!(
                    "diffuse = s·fatt·Iℓ·kd·O·(n·l) = {}·{}·{}·{}·{}·{} = {}",
                    text::num(t.shadow),
                    text::num(t.attenuation),
                    text::color(il),
                    text::num(m.kd),
                    text::color(m.color),
                    text::num(t.n_dot_l.max(0.0)),
                    text::color(t.shadow * raw_d)
                ));
                let model = if m.highlight == crate::shading::Highlight::Blinn {
                    "h·n, h = (l + v)/|l + v|"
                } else {
                    "r·v, r = 2(n·l)n − l"
                };
                out.push(format!(
                    "specular = s·fatt·Iℓ·ks·({model})^m = {}·{}·{}·{}·{}^{} = {}",
                    text::num(t.shadow),
                    text::num(t.attenuation),
                    text::color(il),
                    text::num(m.ks),
                    text::num(t.highlight_cos),
                    text::num(m.shininess),
                    text::color(t.specular)
                ));
            }
        }
        Ask::Barycentric if n.hit.as_ref().is_some_and(|h| h.barycentric.is_some()) => {
            let h = n.hit.as_ref().unwrap();
            out.push(format!(
                "ray o = {}, d = {} hits {} at t = {}, p = {}",
                text::vec3(n.origin),
                text::vec3(n.direction),
                h.leaf,
                text::num(h.t),
                text::vec3(h.point)
            ));
            if let Some(Shape::Triangle(tri)) = w
                .scene
                .leaves
                .iter()
                .find(|l| l.name == h.leaf && l.transform.is_none())
                .map(|l| &l.shape)
            {
                let area = |a: DVec3, b: DVec3, c: DVec3| 0.5 * (b - a).cross(c - a).length();
                let whole = area(tri.a, tri.b, tri.c);
                out.push(format!(
                    "a = {}, b = {}, c = {}; area(a, b, c) = {}",
                    text::vec3(tri.a),
                    text::vec3(tri.b),
                    text::vec3(tri.c),
                    text::num(whole)
                ));
                out.push(format!(
                    "λ1 = area(p, b, c)/area(a, b, c) = {}/{} = {}",
                    text::num(area(h.point, tri.b, tri.c)),
                    text::num(whole),
                    text::num(area(h.point, tri.b, tri.c) / whole)
                ));
                out.push(format!(
                    "λ2 = area(a, p, c)/area(a, b, c) = {}/{} = {}",
                    text::num(area(tri.a, h.point, tri.c)),
                    text::num(whole),
                    text::num(area(tri.a, h.point, tri.c) / whole)
                ));
                out.push(format!(
                    "λ3 = area(a, b, p)/area(a, b, c) = {}/{} = {}",
                    text::num(area(tri.a, tri.b, h.point)),
                    text::num(whole),
                    text::num(area(tri.a, tri.b, h.point) / whole)
                ));
                out.push("check: λ1 + λ2 + λ3 = 1 and p = λ1·a + λ2·b + λ3·c".into());
            } else {
                let b = h.barycentric.unwrap();
                out.push(format!("on a mesh triangle (a, b, c in the file's order): (λ1, λ2, λ3) = {}, p = λ1·a + λ2·b + λ3·c", text::vec3(b)));
            }
        }
        Ask::PixelValue | Ask::PrimaryRays | Ask::SquaresSplit => {
            explain_render(&w, ex, &mut out)?;
        }
        Ask::Segments => {
            let name = ex.object.as_deref().unwrap_or("");
            if let Some(o) = w.scene.object_index(name) {
                let (_, t) = w.scene.object_trace(o, &w.ray, false);
                out.push(format!(
                    "ray {} → {}",
                    text::vec3(w.ray.origin),
                    text::vec3(w.ray.dir)
                ));
                out.push("segment lists, combined bottom-up:".into());
                out.extend(
                    text::csg_trace(&w.scene, &w.ray, &t)
                        .lines()
                        .map(str::to_string),
                );
            }
        }
        _ => {
            out.push("the ray tree, each node with its terms:".into());
            out.extend(text::tree(n).lines().map(str::to_string));
            out.push("collecting from the leaves up:".into());
            collect_lines(n, &mut out);
        }
    }
    out.push(format!("answer: {}", w.expected.show()));
    Ok(out)
}

/// How a pixel (or the whole image) is rendered: its rays, where they go and what they bring.
/// Each sample is recomputed the way `Film::pixel` takes it (same generator, same order), so
/// the values listed are the ones the render averages.
fn explain_render(w: &Worked, ex: &Exercise, out: &mut Vec<String>) -> Result<(), String> {
    let scene = &w.scene;
    let cam = &scene.camera;
    let options = render_options(scene, ex);
    let film = Film::new(scene, options);
    let path = scene.integrator == Integrator::Path;
    // As `Film::pixel`: the path tracer always jitters.
    let aa = match (options.antialias, path) {
        (Antialias::Grid, true) => Antialias::Jittered,
        (a, _) => a,
    };
    let spp = options.spp.max(1);
    let levels = antialias::adaptive_levels(spp);
    if path {
        out.push(format!(
            "integrator: path, max_depth {}: each primary ray carries one random path (seed {})",
            options.max_depth, options.seed
        ));
    }
    let Some([x, y]) = ex.pixel else {
        let (nc, nr) = (cam.width, cam.height);
        let (_, stats) = rendered(scene, ex, options)?;
        match aa {
            Antialias::Adaptive { threshold } => {
                let corners = (nc + 1) * (nr + 1);
                out.push(format!(
                    "adaptive antialiasing, threshold {}: squares halved at most {levels} times (spp {spp})",
                    text::num(threshold)
                ));
                out.push(format!(
                    "first the corners of all pixels, each traced once and shared: ({nc} + 1)·({nr} + 1) = {corners} primary rays"
                ));
                for py in 0..nr {
                    for px in 0..nc {
                        let mut t = film.tracer();
                        film.lone_pixel(&mut t, px, py);
                        let s = t.stats;
                        if s.aa_splits > 0 {
                            out.push(format!(
                                "pixel ({px}, {py}): {} square{} split",
                                s.aa_splits,
                                if s.aa_splits == 1 { "" } else { "s" }
                            ));
                        }
                    }
                }
                out.push(format!(
                    "squares split in the image: {}; every split traces 5 new rays (the 4 edge midpoints and the centre)",
                    stats.aa_splits
                ));
                out.push(format!(
                    "primary rays = {corners} + 5·{} = {}",
                    stats.aa_splits, stats.primary_rays
                ));
            }
            _ => out.push(format!(
                "{} antialiasing: {spp} primary ray{} in each of the {nc}·{nr} pixels = {}",
                aa.name(),
                if spp == 1 { "" } else { "s" },
                stats.primary_rays
            )),
        }
        return Ok(());
    };
    out.push(format!(
        "pixel ({x}, {y}) covers the image square [{x}, {}] × [{y}, {}]; a ray through (u, v) of the pixel goes through the image point ({x} + u, {y} + v)",
        x + 1,
        y + 1
    ));
    let mut t = film.tracer();
    let value = match aa {
        Antialias::Grid | Antialias::Jittered => {
            let n = (spp as f64).sqrt().round() as u32;
            let pattern = match (aa, n * n == spp) {
                (Antialias::Grid, true) => format!(
                    "a regular {n} × {n} grid: u, v at the centres of the cells, (k + ½)/{n}"
                ),
                (Antialias::Grid, false) => "the R2 sequence (spp is not a square)".to_string(),
                _ => "jittered: one ray at a random point of each cell of the grid".to_string(),
            };
            out.push(format!("{} antialiasing, spp {spp}: {pattern}", aa.name()));
            let samples = film.own_samples(&mut t, x, y);
            for smp in samples.iter().take(16) {
                out.push(format!(
                    "{} through (u, v) = ({}, {}): {}",
                    if path { "path" } else { "ray" },
                    text::num(smp.uv.x),
                    text::num(smp.uv.y),
                    text::color(smp.value)
                ));
            }
            let values: Vec<DVec3> = samples.iter().map(|s| s.value).collect();
            if values.len() > 16 {
                out.push(format!("… and {} more", values.len() - 16));
            }
            let count = values.len() as f64;
            let mean = values.iter().sum::<DVec3>() / count;
            out.push(format!(
                "pixel = the mean of the {} values = {}",
                values.len(),
                text::color(mean)
            ));
            if aa == Antialias::Jittered && values.len() > 1 {
                let var = values
                    .iter()
                    .map(|v| (*v - mean) * (*v - mean))
                    .sum::<DVec3>()
                    / (count - 1.0);
                let sd = DVec3::new(var.x.sqrt(), var.y.sqrt(), var.z.sqrt());
                out.push(format!(
                    "spread of the samples: standard deviation s = {}; the mean's noise, s/√N = {}",
                    text::color(sd),
                    text::color(sd / count.sqrt())
                ));
            }
            if film.splats() {
                let splatted = film.lone_pixel(&mut film.tracer(), x, y);
                out.push(format!(
                    "the Gaussian filter (Mitsuba's: f(d) = e^(−d²/2σ²) − e^(−r²/2σ²), σ = 0.5 px, r = 2 px) then mixes in the samples of the pixels around: pixel = Σ w·L / Σ w over the samples of the 5 × 5 pixels around, w = f(dx)·f(dy) = {}",
                    text::color(splatted)
                ));
                splatted
            } else {
                mean
            }
        }
        Antialias::Adaptive { threshold } => {
            out.push(format!(
                "adaptive antialiasing, threshold {}: a square whose corners differ by more than that (Σ|Δr| + |Δg| + |Δb|) is split in four, at most {levels} times (spp {spp}: up to {side} × {side} squares)",
                text::num(threshold),
                side = 1u32 << levels
            ));
            let corners = [
                film.corner(&mut t, x, y),
                film.corner(&mut t, x + 1, y),
                film.corner(&mut t, x, y + 1),
                film.corner(&mut t, x + 1, y + 1),
            ];
            out.push(format!(
                "corners (shared with the neighbours): top-left {}, top-right {}, bottom-left {}, bottom-right {}",
                text::color(corners[0]),
                text::color(corners[1]),
                text::color(corners[2]),
                text::color(corners[3])
            ));
            film.adaptive(&mut t, x, y, corners, &mut |step| {
                out.push(adaptive_line(step, threshold))
            })
        }
    };
    if ex.ask == Ask::PixelValue && !Answer::color(value).matches(&w.expected, 1e-12) {
        out.push(format!(
            "(the render gives {}: the steps above do not follow it exactly)",
            w.expected.show()
        ));
    }
    if ex.ask != Ask::PixelValue {
        let mut t = film.tracer();
        film.lone_pixel(&mut t, x, y);
        let lone = t.stats;
        let corners = if matches!(aa, Antialias::Adaptive { .. }) {
            "4 corners + "
        } else {
            ""
        };
        out.push(format!(
            "rendered alone, the pixel traces {corners}{} = {} primary rays and splits {} squares",
            if corners.is_empty() {
                format!("{spp}")
            } else {
                format!("5·{}", lone.aa_splits)
            },
            lone.primary_rays,
            lone.aa_splits
        ));
    }
    Ok(())
}

/// One step of adaptive antialiasing, explained: a square kept, split or merged.
fn adaptive_line(step: &Step, threshold: f64) -> String {
    let name = |q: &Square| {
        format!(
            "{}square u ∈ [{}, {}], v ∈ [{}, {}]",
            "  ".repeat(q.level as usize),
            text::num(q.u0),
            text::num(q.u0 + q.side),
            text::num(q.v0),
            text::num(q.v0 + q.side)
        )
    };
    let corners = |q: &Square| {
        let [tl, tr, bl, br] = q.corners;
        format!(
            "corners {}, {}, {}, {}",
            text::color(tl),
            text::color(tr),
            text::color(bl),
            text::color(br)
        )
    };
    let colors = |vs: &[DVec3], sep: &str| {
        vs.iter()
            .map(|v| text::color(*v))
            .collect::<Vec<_>>()
            .join(sep)
    };
    match step {
        Step::Kept {
            square,
            smallest: false,
            value,
        } => format!(
            "{}: {} differ by at most {} ≤ {}: not split, value = mean of the corners = {}",
            name(square),
            corners(square),
            text::num(square.largest),
            text::num(threshold),
            text::color(*value)
        ),
        Step::Kept {
            square,
            smallest: true,
            value,
        } => format!(
            "{}: {} differ by {} > {}, but it is the smallest square allowed: value = mean of the corners = {}",
            name(square),
            corners(square),
            text::num(square.largest),
            text::num(threshold),
            text::color(*value)
        ),
        Step::Split { square, new } => {
            let [top, left, centre, right, bottom] = new.map(text::color);
            format!(
                "{}: {} differ by {} > {}: split; 5 new rays: top {top}, left {left}, centre {centre}, right {right}, bottom {bottom}",
                name(square),
                corners(square),
                text::num(square.largest),
                text::num(threshold),
            )
        }
        Step::Merged {
            square,
            quarters,
            value,
        } => format!(
            "{} = mean of its quarters ({}) / 4 = {}",
            name(square),
            colors(quarters, " + "),
            text::color(*value)
        ),
    }
}

/// A number ready to follow a minus sign: negative values in parentheses.
fn signed(x: f64) -> String {
    if x < 0.0 {
        format!("({})", text::num(x))
    } else {
        text::num(x)
    }
}

/// Post-order: every node's intensity from its local term and its children's.
fn collect_lines(n: &RayNode, out: &mut Vec<String>) {
    for c in n.secondary() {
        collect_lines(c, out);
    }
    let label = format!("I({} depth {})", n.kind.name(), n.depth);
    if let Some((lobe, k)) = n.cone() {
        out.push(format!(
            "I({lobe} depth {}) = (I_1 + … + I_{k})/{k}, the mean of its sampled rays = {}",
            n.depth,
            text::color(n.color)
        ));
        return;
    }
    match (&n.local, n.terminated) {
        (Some(local), _) => {
            let mut terms = vec![text::color(local.total())];
            for c in n.secondary() {
                terms.push(format!(
                    "{}·{}",
                    text::num(c.coefficient),
                    text::color(c.color)
                ));
            }
            out.push(format!(
                "{label} = {} = {}",
                terms.join(" + "),
                text::color(n.color)
            ));
        }
        (None, Some(t)) => out.push(format!("{label} = {} ({})", text::color(n.color), t.name())),
        _ => {}
    }
}
