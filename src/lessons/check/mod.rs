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
//! - `csg`: segment lists, and the leaves evaluated (pruning, bounding boxes);
//! - `image`: rendered pixel values, primary rays, squares split by adaptive antialiasing
//!   (whose steps `adaptive` explains);
//! - `montecarlo`: the standard error of a sampled mean, for answers graded in standard errors;
//! - `texture`: texture coordinates and the colour of a patterned surface.

mod adaptive;
mod camera;
mod csg;
mod derive;
mod image;
mod intersection;
mod lighting;
mod mistakes;
mod montecarlo;
mod optics;
mod texture;
mod tree;

use glam::DVec3;

use super::answer::{parse_answer, Answer};
use super::error::CheckError;
use super::exercise::{Ask, Exercise, Lesson};
use super::tolerance::Tolerance;
use crate::geometry::Ray;
use crate::scene::{Limits, Scene, SceneError};
use crate::trace::tree::HitInfo;
use crate::trace::TraceOptions;
use crate::trace::{text, RayNode, Tracer};

/// Everything the exercise is about, computed.
pub struct Worked {
    /// The exercise's scene, every material in the highlight model the exercise states.
    pub scene: Scene,
    /// The traced ray: the pixel's primary ray, the exercise's own ray, or for a question
    /// about the whole image the first pixel's.
    pub ray: Ray,
    /// The max_depth traced with: the exercise's `depth`, else the scene's, within 1..=64.
    pub depth: u32,
    /// The ray tree traced from `ray`; the exercise asks about its node `node`.
    pub tree: RayNode,
    /// raytree's answer, computed from the scene.
    pub expected: Answer,
    /// The rule an answer is held to: the exercise's, with a Monte Carlo mean's standard
    /// error filled in.
    pub tolerance: Tolerance,
}

/// What `check` found of a student's answer.
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    /// Whether the answer is within the tolerance of the expected one.
    pub correct: bool,
    /// The student's answer, as read.
    pub given: Answer,
    /// raytree's answer.
    pub expected: Answer,
    /// The rule the answer was held to.
    pub tolerance: Tolerance,
    /// Whether the answer is of the kind asked (one number for a grey colour is).
    pub of_the_kind: bool,
    /// A common mistake that explains a wrong answer.
    pub hint: Option<String>,
    /// The highlight model an intensity was computed in, and why (stated by the exercise,
    /// or set by the materials); None where no specular term enters the answer.
    pub model: Option<String>,
}

impl Verdict {
    /// The verdict as `raytree check` prints it: right or wrong with the expected answer and
    /// the tolerance, then the hint and the highlight model, each on a line of its own.
    pub fn message(&self) -> String {
        let mut out = if self.correct {
            format!(
                "right: {} (expected {}, tolerance {})",
                self.given.show(),
                self.expected.show(),
                self.tolerance.describe()
            )
        } else {
            let mut s = if self.of_the_kind {
                format!(
                    "wrong: {} is not within {} of the expected answer",
                    self.given.show(),
                    self.tolerance.describe()
                )
            } else {
                format!(
                    "wrong: {} is not the kind of answer asked",
                    self.given.show()
                )
            };
            if let Some(h) = &self.hint {
                s.push_str(&format!("\nhint: {h}"));
            }
            s
        };
        if let Some(m) = &self.model {
            out.push_str(&format!("\n{m}"));
        }
        out
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
    hint: String,
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
        Ask::LeavesEvaluated => &csg::LeavesEvaluated,
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

/// The exercise's scene, in the highlight model the exercise states.
fn load(lesson: &Lesson, ex: &Exercise) -> Result<Scene, SceneError> {
    let path = lesson.scene_path(ex);
    let mut scene = match lesson.scene_source(ex) {
        Some(text) => crate::scene::parse(
            text,
            &path.display().to_string(),
            Some(&path),
            &Limits::default(),
        ),
        None => crate::scene::load(&path, &Limits::default()),
    }?;
    if let Some(model) = ex.model {
        for m in &mut scene.materials {
            m.highlight = model;
        }
    }
    Ok(scene)
}

/// An exercise's pixel must lie in its scene's image.
fn pixel_inside(scene: &Scene, ex: &Exercise, x: u32, y: u32) -> Result<(), String> {
    let (w, h) = (scene.camera.width, scene.camera.height);
    if x < w && y < h {
        return Ok(());
    }
    Err(format!(
        "exercise `{}`: pixel {x},{y} is outside its scene's {w} × {h} image (x from 0 to {}, y from 0 to {})",
        ex.id,
        w.saturating_sub(1),
        h.saturating_sub(1)
    ))
}

fn exercise_ray(scene: &Scene, ex: &Exercise) -> Result<Ray, String> {
    match (&ex.pixel, &ex.ray) {
        (Some([x, y]), _) => {
            pixel_inside(scene, ex, *x, *y)?;
            Ok(scene.camera.pixel_ray(*x, *y))
        }
        (None, Some(r))
            if r.origin.is_finite() && r.direction.is_finite() && r.direction != DVec3::ZERO =>
        {
            // A direction too short or too long to square (1e-200, 1e200) is first brought
            // near unit length by its largest component: the same direction.
            let d = r.direction;
            let d = if d.length_squared().is_normal() {
                d
            } else {
                d / d.abs().max_element()
            };
            Ok(Ray::new(r.origin, d))
        }
        // A question about the whole image: the tree shown is that of the first pixel.
        (None, None) if ex.ask.about_image() => Ok(scene.camera.pixel_ray(0, 0)),
        _ => Err(format!(
            "exercise `{}` needs a pixel or a ray with a finite origin and a finite, non-zero direction",
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
pub fn work(lesson: &Lesson, ex: &Exercise) -> Result<Worked, CheckError> {
    let scene = load(lesson, ex)?;
    let ray = exercise_ray(&scene, ex).map_err(CheckError::Unworkable)?;
    let depth = ex.depth.unwrap_or(scene.max_depth).clamp(1, 64);
    let tree = trace(
        &scene,
        &ray,
        TraceOptions {
            max_depth: depth,
            ..TraceOptions::of(&scene)
        },
    );
    let expected = answer(&scene, &ray, &tree, ex).map_err(CheckError::Unworkable)?;
    let tolerance = node(&tree, ex)
        .and_then(|n| montecarlo::tolerance(ex, n))
        .map_err(CheckError::Unworkable)?;
    Ok(Worked {
        scene,
        ray,
        depth,
        tree,
        expected,
        tolerance,
    })
}

/// Checks a student's answer (`input`, as typed) to an exercise against the answer raytree
/// works out, with a hint when it is wrong. Fails when the answer does not read or the exercise
/// cannot be worked out.
pub fn check(lesson: &Lesson, ex: &Exercise, input: &str) -> Result<Verdict, CheckError> {
    let given = parse_answer(input, ex.ask == Ask::Segments)?;
    let w = work(lesson, ex)?;
    // One number and a vector of three equal ones are the same grey where a colour is asked;
    // elsewhere a number is not a point or a direction, nor a vector a t or a count.
    let grey = asks_colour(ex.ask)
        && matches!(
            (&given, &w.expected),
            (Answer::Vector(_), Answer::Number(_)) | (Answer::Number(_), Answer::Vector(_))
        );
    let of_the_kind = grey || std::mem::discriminant(&given) == std::mem::discriminant(&w.expected);
    let correct = of_the_kind && given.matches(&w.expected, &w.tolerance);
    // A lesson whose solutions are hidden only says right or wrong: a hint names the kind of
    // the answer (total internal reflection or not) or the mistake that gives it.
    let hint = if correct || lesson.solutions == super::exercise::Solutions::Hidden {
        None
    } else {
        kind_hint(ex.ask, &given, &w.expected).or_else(|| hint(&w, ex, &given))
    };
    let model = highlight_model(&w, ex);
    Ok(Verdict {
        correct,
        given,
        expected: w.expected,
        tolerance: w.tolerance,
        of_the_kind,
        hint,
        model,
    })
}

/// The kinds of question whose answer is an intensity, in which the highlight model matters.
fn asks_intensity(ask: Ask) -> bool {
    matches!(
        ask,
        Ask::Intensity | Ask::Local | Ask::Specular | Ask::PixelValue
    )
}

/// Which highlight model an intensity exercise is worked in, in words: the one it states, or
/// the one of the shiny surfaces (ks > 0) in its tree. None for other questions, and where no
/// surface with a specular term is hit.
pub fn highlight_model(w: &Worked, ex: &Exercise) -> Option<String> {
    use crate::shading::Highlight;
    if !asks_intensity(ex.ask) || w.scene.integrator == crate::scene::Integrator::Path {
        return None;
    }
    let mut shiny: Vec<(String, Highlight)> = Vec::new();
    fn walk(n: &RayNode, scene: &Scene, out: &mut Vec<(String, Highlight)>) {
        if let Some(h) = &n.hit {
            if let Some(m) = scene.materials.iter().find(|m| m.name == h.material) {
                if m.ks > 0.0 && n.local.is_some() && !out.iter().any(|(name, _)| *name == m.name) {
                    out.push((m.name.clone(), m.highlight));
                }
            }
        }
        for c in n.secondary() {
            walk(c, scene, out);
        }
    }
    walk(node(&w.tree, ex).ok()?, &w.scene, &mut shiny);
    // No lit surface with a highlight: no model to name.
    let (_, first) = shiny.first()?;
    if let Some(m) = ex.model {
        // The exercise's `model:` (its exercises.yaml; the question may not say it).
        return Some(format!("highlight model: {}, the exercise's", m.name()));
    }
    if shiny.iter().all(|(_, h)| h == first) {
        Some(format!(
            "highlight model: {}, as the material{} set{}",
            first.name(),
            if shiny.len() == 1 { "" } else { "s" },
            if shiny.len() == 1 { "s" } else { "" }
        ))
    } else {
        let each: Vec<String> = shiny
            .iter()
            .map(|(name, h)| format!("{} for {name}", h.name()))
            .collect();
        Some(format!(
            "highlight model: each material's own ({})",
            each.join(", ")
        ))
    }
}

/// A hint for an answer of the wrong kind: one number where a vector is asked, a vector where
/// one number is, `tir` where Snell's law gives a ray, a ray where it gives none.
fn kind_hint(ask: Ask, given: &Answer, expected: &Answer) -> Option<String> {
    let what = match ask {
        Ask::WindowPoint | Ask::HitPoint => "a point",
        Ask::RayDirection | Ask::ReflectedDirection | Ask::RefractedDirection => "a direction",
        Ask::RayOrigin => "the ray's origin, a point,",
        Ask::Normal => "a normal",
        Ask::Barycentric => "the barycentric coordinates (λ1, λ2, λ3)",
        Ask::HitT => "t",
        Ask::ShadowFactor => "the shadow factor s",
        Ask::PrimaryRays | Ask::SquaresSplit | Ask::LeavesEvaluated => "a count",
        Ask::Intensity | Ask::Local | Ask::Diffuse | Ask::Specular | Ask::PixelValue => {
            "this intensity"
        }
        Ask::Segments => "a segment list",
        Ask::U | Ask::V => "a texture coordinate",
        Ask::SurfaceColor => "the surface colour",
    };
    Some(match (given, expected) {
        (Answer::Number(_), Answer::Vector(_)) if asks_colour(ask) => {
            "this intensity is a colour, not grey: give it as r, g, b".into()
        }
        (Answer::Number(_), Answer::Vector(_)) => {
            format!("{what} is a vector: give it as x, y, z")
        }
        (Answer::Vector(_), Answer::Number(_)) if !asks_colour(ask) => {
            format!("{what} is one number, not a vector")
        }
        (Answer::Tir, Answer::Vector(_)) if ask == Ask::RefractedDirection => {
            "Snell's law gives a refracted ray here: 1 − η²(1 − c1²) is positive, so there is no total internal reflection".into()
        }
        (Answer::Vector(_), Answer::Tir) => {
            "1 − η²(1 − c1²) is negative here: there is no refracted ray (total internal reflection, answer tir)".into()
        }
        (Answer::Tir, _) => format!("tir is an answer for a refracted direction only; {what} is asked"),
        (Answer::Segments(s), Answer::Tir) if s.is_empty() => {
            "no ray is refracted, right: that is total internal reflection, which is answered tir".into()
        }
        (Answer::Segments(s), _) if s.is_empty() && !matches!(expected, Answer::Segments(_)) => {
            format!("none is an answer for a segment list only (an empty one); {what} is asked")
        }
        (Answer::Numbers(_), Answer::Segments(_)) => {
            "a segment list is pairs t_in, t_out (e.g. `13, 16; 22, 23`): an even count of numbers".into()
        }
        (Answer::Numbers(v), _) if v.len() == 2 => format!(
            "{what} is {}, not two (a decimal comma? decimals are written with a point)",
            numbers_of(ask, expected)
        ),
        (Answer::Numbers(v), _) => {
            format!("{what} is {}, not {}", numbers_of(ask, expected), v.len())
        }
        _ => return None,
    })
}

/// How many numbers an answer to `ask` is: a colour may be given grey, as one.
fn numbers_of(ask: Ask, expected: &Answer) -> &'static str {
    match expected {
        _ if asks_colour(ask) => "one number or three",
        Answer::Number(_) => "one number",
        Answer::Vector(_) => "three numbers",
        _ => "one number or three",
    }
}

fn asks_colour(ask: Ask) -> bool {
    matches!(
        ask,
        Ask::Intensity
            | Ask::Local
            | Ask::Diffuse
            | Ask::Specular
            | Ask::PixelValue
            | Ask::SurfaceColor
    )
}

/// The first common mistake that gives the student's answer. A mistake that happens to give
/// the right answer here explains nothing, so it is passed over.
fn hint(w: &Worked, ex: &Exercise, given: &Answer) -> Option<String> {
    let tol = &w.tolerance;
    question(ex.ask)
        .mistakes(w, ex)
        .into_iter()
        .find(|m| given.matches(&m.answer, tol) && !m.answer.matches(&w.expected, tol))
        .map(|m| m.hint)
}

/// The worked derivation, step by step, with the numbers filled in (refused for a lesson whose
/// solutions are hidden).
pub fn explain(lesson: &Lesson, ex: &Exercise) -> Result<Vec<String>, CheckError> {
    if lesson.solutions == super::exercise::Solutions::Hidden {
        return Err(CheckError::Hidden {
            lesson: lesson.id.clone(),
        });
    }
    let w = work(lesson, ex)?;
    let n = node(&w.tree, ex).map_err(CheckError::Unworkable)?;
    let mut out = vec![format!("{}: {}", ex.id, ex.question.trim())];
    out.extend(
        question(ex.ask)
            .explain(&w, ex, n)
            .map_err(CheckError::Unworkable)?,
    );
    out.extend(montecarlo::explain(&w, n));
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
