//! Checking an answer: raytree computes the expected value from the lesson's scene (never from
//! a number typed into the exercise), compares, and explains.
//!
//! This module loads the exercise's scene, traces its ray and hands the rest to the kind of
//! question asked. Each kind is a [`Question`]: how its answer is computed, which common
//! mistakes a wrong answer may come from, and its worked derivation, side by side. The kinds
//! are grouped by topic, one module each:
//!
//! - `camera`: the window point, the primary ray's direction and origin;
//! - `intersection`: hit t, hit point, normal, barycentric coordinates;
//! - `lighting`: intensity, local term, diffuse, specular, shadow factor;
//! - `optics`: reflected and refracted directions;
//! - `csg`: segment lists;
//! - `image`: rendered pixel values, primary rays, squares split by adaptive antialiasing
//!   (whose steps `adaptive` explains);
//! - `texture`: texture coordinates and the colour of a patterned surface.

mod adaptive;
mod camera;
mod csg;
mod image;
mod intersection;
mod lighting;
mod optics;
mod texture;
mod tree;

use glam::DVec3;

use super::answer::{parse_answer, Answer};
use super::exercise::{Ask, Exercise, Lesson};
use crate::geometry::Ray;
use crate::scene::{Limits, Scene};
use crate::trace::tree::HitInfo;
use crate::trace::TraceOptions;
use crate::trace::{text, RayNode, Tracer};

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

// --- Kinds of question ---

/// One kind of question an exercise can ask.
trait Question {
    /// The expected answer, read off the traced tree (or computed from the scene).
    fn answer(&self, q: &Traced) -> Result<Answer, String>;

    /// The answers common mistakes give, in the order they are tried. None by default: a kind
    /// of question without a known mistake gives no hint.
    fn mistakes(&self, _w: &Worked, _ex: &Exercise) -> Vec<Mistake> {
        Vec::new()
    }

    /// The worked derivation, step by step with the numbers filled in: the lines between the
    /// question and the answer.
    fn explain(&self, w: &Worked, ex: &Exercise, n: &RayNode) -> Result<Vec<String>, String>;
}

/// The answer a common mistake gives, and the hint that names the mistake.
struct Mistake {
    answer: Answer,
    hint: &'static str,
}

/// The kind of question an `Ask` names.
fn question(ask: Ask) -> &'static dyn Question {
    match ask {
        Ask::WindowPoint => &camera::WindowPoint,
        Ask::RayDirection => &camera::RayDirection,
        Ask::RayOrigin => &camera::RayOrigin,
        Ask::HitT => &intersection::HitT,
        Ask::HitPoint => &intersection::HitPoint,
        Ask::Normal => &intersection::Normal,
        Ask::Barycentric => &intersection::Barycentric,
        Ask::Intensity => &lighting::Intensity,
        Ask::Local => &lighting::Local,
        Ask::ShadowFactor => &lighting::ShadowFactor,
        Ask::Diffuse => &lighting::Diffuse,
        Ask::Specular => &lighting::Specular,
        Ask::ReflectedDirection => &optics::ReflectedDirection,
        Ask::RefractedDirection => &optics::RefractedDirection,
        Ask::Segments => &csg::Segments,
        Ask::PixelValue => &image::PixelValue,
        Ask::PrimaryRays => &image::PrimaryRays,
        Ask::SquaresSplit => &image::SquaresSplit,
        Ask::U => &texture::TextureCoordinate { v: false },
        Ask::V => &texture::TextureCoordinate { v: true },
        Ask::SurfaceColor => &texture::SurfaceColor,
    }
}

/// What an answer is read from: the exercise, its scene and ray, and the node of the traced
/// tree the exercise asks about.
struct Traced<'a> {
    ex: &'a Exercise,
    scene: &'a Scene,
    ray: &'a Ray,
    node: &'a RayNode,
}

impl<'a> Traced<'a> {
    /// The surface the node's ray hits, for the questions about one.
    fn hit(&self) -> Result<&'a HitInfo, String> {
        self.node
            .hit
            .as_ref()
            .ok_or_else(|| format!("exercise `{}`: the ray hits nothing", self.ex.id))
    }
}

// --- Working an exercise out ---

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

/// The value an exercise asks for, read off a traced tree.
fn answer(scene: &Scene, ray: &Ray, tree: &RayNode, ex: &Exercise) -> Result<Answer, String> {
    let node = node(tree, ex)?;
    question(ex.ask).answer(&Traced {
        ex,
        scene,
        ray,
        node,
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
    let expected = answer(&scene, &ray, &tree, ex)?;
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

/// The first common mistake that gives the student's answer. A mistake that happens to give
/// the right answer here explains nothing, so it is passed over.
fn hint(w: &Worked, ex: &Exercise, given: &Answer) -> Option<String> {
    let tol = ex.tolerance;
    question(ex.ask)
        .mistakes(w, ex)
        .into_iter()
        .find(|m| given.matches(&m.answer, tol) && !m.answer.matches(&w.expected, tol))
        .map(|m| m.hint.to_string())
}

/// The worked derivation, step by step, with the numbers filled in.
pub fn explain(lesson: &Lesson, ex: &Exercise) -> Result<Vec<String>, String> {
    let w = work(lesson, ex)?;
    let n = node(&w.tree, ex)?;
    let mut out = vec![format!("{}: {}", ex.id, ex.question.trim())];
    out.extend(question(ex.ask).explain(&w, ex, n)?);
    out.push(format!("answer: {}", w.expected.show()));
    Ok(out)
}

/// A number ready to follow a minus sign: negative values in parentheses.
fn signed(x: f64) -> String {
    if x < 0.0 {
        format!("({})", text::num(x))
    } else {
        text::num(x)
    }
}
