//! The lesson panel: the lesson beside its scene, shown as its README or as its exercises,
//! with the answers given in the app and what `lessons::check` said of them.

use std::path::Path;

use ratatui::layout::Rect;

use super::exercises;
use super::scene::{signature, FileSig};
use super::{max_scroll, scrolled, Note, Tone};
use crate::geometry::Ray;
use std::collections::BTreeSet;

use crate::lessons::progress::Progress;
use crate::lessons::{self, Ask, CheckError, Lesson, Solutions, Verdict};
use crate::scene::Scene;
use crate::trace::text;
use crate::tui::layout::inner;
use crate::tui::markdown::{markdown, overhang};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LessonView {
    Readme,
    Exercises,
}

/// An answer given in the app and what `lessons::check` said.
#[derive(Clone, Debug)]
pub struct Answered {
    pub given: String,
    pub result: Result<Verdict, CheckError>,
}

pub struct LessonPanel {
    pub lesson: Lesson,
    pub open: bool,
    pub view: LessonView,
    /// Scroll of the README.
    pub scroll: u16,
    /// How many cells into its figures the README is shown (they are never wrapped).
    pub pan: u16,
    /// The exercise selected in the exercises view.
    pub exercise: usize,
    /// The last answer to each exercise.
    pub answers: Vec<Option<Answered>>,
    /// The worked solution of the selected exercise, when asked for (`w`).
    pub work: Option<Result<Vec<String>, CheckError>>,
    /// Scroll of the selected exercise's text in the exercises view.
    pub exercise_scroll: u16,
    /// The exercises answered right, now or in an earlier session (the user's progress).
    pub solved: BTreeSet<String>,
    signature: [Option<FileSig>; 2],
}

/// Where an exercise points the ray tree: a pixel of the scene or a ray, a depth, a ray of the
/// tree.
pub struct Aim {
    pub at: AimAt,
    pub depth: Option<u32>,
    /// The kinds on the path to the ray asked about ("reflection.refraction").
    pub node: String,
}

/// What the tree follows for an exercise.
pub enum AimAt {
    Pixel(u32, u32),
    /// A ray that is no pixel's primary ray.
    Ray(Ray),
}

/// What the explorer says when there is no lesson to act on.
pub const NO_LESSON: &str = "no lesson here: open a lesson folder, or press o for the list";

fn lesson_signature(dir: &Path) -> [Option<FileSig>; 2] {
    [
        signature(&dir.join("README.md")),
        signature(&dir.join("exercises.yaml")),
    ]
}

impl LessonPanel {
    pub fn new(lesson: Lesson) -> LessonPanel {
        let n = lesson.exercises.len();
        LessonPanel {
            signature: lesson_signature(&lesson.dir),
            solved: Progress::load().solved(&lesson),
            lesson,
            open: true,
            view: LessonView::Readme,
            scroll: 0,
            pan: 0,
            exercise: 0,
            answers: vec![None; n],
            work: None,
            exercise_scroll: 0,
        }
    }

    /// The exercises are on screen.
    pub fn in_exercises(&self) -> bool {
        self.open && self.view == LessonView::Exercises
    }

    /// r: the README, or closes it when it is shown.
    pub fn toggle_readme(&mut self) {
        if self.open && self.view == LessonView::Readme {
            self.open = false;
        } else {
            self.open = true;
            self.view = LessonView::Readme;
        }
    }

    /// a: the exercises.
    pub fn show_exercises(&mut self) {
        self.open = true;
        self.view = LessonView::Exercises;
    }

    /// The scene file an exercise is posed on.
    pub fn scene_of(&self, i: usize) -> Option<String> {
        let ex = self.lesson.exercises.get(i)?;
        Some(ex.scene.clone().unwrap_or_else(|| "scene.yaml".into()))
    }

    /// The lesson's scenes: scene.yaml, then the other scene files of its folder in name order.
    pub fn scenes(&self) -> Vec<String> {
        let mut others: Vec<String> = std::fs::read_dir(&self.lesson.dir)
            .map(|rd| {
                rd.filter_map(|e| e.ok())
                    .map(|e| e.file_name().to_string_lossy().into_owned())
                    .filter(|n| n.ends_with(".yaml") && n != "exercises.yaml" && n != "scene.yaml")
                    .collect()
            })
            .unwrap_or_default();
        others.sort();
        let mut all = vec!["scene.yaml".to_string()];
        all.extend(others);
        all
    }

    /// Selects exercise `i` (clamped); None without exercises. `scene` is the exercise's own
    /// scene (the caller switches to it first): the `Aim` says where the ray tree should go, a
    /// pixel of its `w` × `h` image (also for a ray that is a pixel's primary ray) or the
    /// exercise's ray; the note says what the exercise is about.
    pub fn select_exercise(
        &mut self,
        i: usize,
        scene: Option<&Scene>,
        (w, h): (u32, u32),
    ) -> Option<(Option<Aim>, Note)> {
        if self.lesson.exercises.is_empty() {
            return None;
        }
        let i = i.min(self.lesson.exercises.len() - 1);
        if self.exercise != i {
            self.work = None;
            self.exercise_scroll = 0;
        }
        self.exercise = i;
        let ex = &self.lesson.exercises[i];
        let mut note = format!("exercise {}", ex.id);
        let ray = ex.ray.as_ref().map(|r| Ray::new(r.origin, r.direction));
        // A ray exercise whose ray is a primary ray of the scene is that pixel's.
        let pixel = match (ex.pixel, &ray, scene) {
            (Some(p), ..) => Some(p),
            (None, Some(r), Some(scene)) => pixel_of_ray(scene, r).map(|(x, y)| [x, y]),
            _ => None,
        };
        if let (Some(r), None) = (&ex.ray, ex.pixel) {
            note.push_str(&format!(
                ": ray {} → {}",
                text::vec3(r.origin),
                text::vec3(r.direction)
            ));
            if pixel.is_some() {
                note.push_str(", the primary ray of");
            }
        }
        let at = match (pixel, ray) {
            (Some([x, y]), _) if x < w && y < h => {
                let sep = if ex.pixel.is_some() { ":" } else { "" };
                note.push_str(&format!("{sep} pixel {x},{y}"));
                Some(AimAt::Pixel(x, y))
            }
            (_, Some(r)) if r.dir.is_finite() && r.dir != glam::DVec3::ZERO => Some(AimAt::Ray(r)),
            _ => None,
        };
        if at.is_some() && !ex.node.is_empty() {
            note.push_str(&format!(", node {}", ex.node));
        }
        let aim = at.map(|at| Aim {
            at,
            depth: ex.depth,
            node: ex.node.clone(),
        });
        if let Some(s) = &ex.scene {
            note.push_str(&format!(" (scene {s})"));
        }
        // The tree is the scene's: an exercise worked in the other highlight model says so.
        if let (Some(model), Some(scene)) = (ex.model, scene) {
            let shiny = |m: &&crate::shading::Material| m.ks != 0.0 || m.patterns.is_some();
            let other = scene
                .materials
                .iter()
                .filter(shiny)
                .find(|m| m.highlight != model);
            if let Some(m) = other {
                note.push_str(&format!(
                    ", worked in {} where the tree shows {}",
                    model.name(),
                    m.highlight.name()
                ));
            }
        }
        let note = format!("{note} · Enter: answer · w: worked solution · Esc: back");
        Some((aim, (note, Tone::Info)))
    }

    /// In a lesson whose solutions are hidden, the intensities of scene `scene` stay hidden
    /// while an exercise about an intensity on it is not answered right.
    pub fn hides_intensities(&self, scene: &str) -> bool {
        self.lesson.solutions == Solutions::Hidden
            && self.lesson.exercises.iter().any(|ex| {
                let on = ex.scene.as_deref().unwrap_or("scene.yaml") == scene;
                on && about_intensity(ex.ask) && !self.solved.contains(&ex.id)
            })
    }

    /// w: shows (or hides) the worked solution of the selected exercise.
    pub fn toggle_work(&mut self) -> Option<Note> {
        if self.lesson.solutions == Solutions::Hidden {
            return Some((
                "the worked solutions of this lesson are hidden (solutions: hidden)".into(),
                Tone::Bad,
            ));
        }
        if !self.in_exercises() {
            return Some((
                "w shows a worked solution in the exercises (press a)".into(),
                Tone::Bad,
            ));
        }
        if self.work.take().is_some() {
            return None;
        }
        if let Some(ex) = self.lesson.exercises.get(self.exercise) {
            // The panel shows the question already.
            let question = format!("{}: ", ex.id);
            self.work = Some(lessons::explain(&self.lesson, ex).map(|lines| {
                lines
                    .into_iter()
                    .enumerate()
                    .filter(|(i, line)| *i > 0 || !line.starts_with(&question))
                    .map(|(_, line)| line)
                    .collect()
            }));
        }
        None
    }

    /// Checks an answer to an exercise and keeps it with the verdict.
    pub fn answer(&mut self, exercise: usize, given: String) -> Option<Note> {
        let ex = self.lesson.exercises.get(exercise)?;
        let result = lessons::check(&self.lesson, ex, &given);
        let mut note = match &result {
            Ok(v) => (
                format!(
                    "{}: {}",
                    ex.id,
                    v.message().lines().next().unwrap_or_default()
                ),
                if v.correct { Tone::Good } else { Tone::Bad },
            ),
            Err(e) => (format!("{}: {e}", ex.id), Tone::Bad),
        };
        // A built-in lesson edited in its cached copy is checked as it now is, but its marks
        // are the lesson's as built.
        let edited = crate::lessons::builtin::edited(&self.lesson.dir);
        if let Some(file) = edited.first().and_then(|f| f.file_name()) {
            note.0.push_str(&format!(
                " (checked against the changed {}, not recorded: raytree puts the built-in \
                 lesson back when it next starts)",
                file.to_string_lossy()
            ));
        } else if result.as_ref().is_ok_and(|v| v.correct) {
            self.solved.insert(ex.id.clone());
            if let Err(e) = Progress::record(&self.lesson, &ex.id) {
                note.0.push_str(&format!(" (progress not saved: {e})"));
            }
        }
        self.answers[exercise] = Some(Answered { given, result });
        Some(note)
    }

    /// Reloads the README and exercises if either changed on disk (answers are kept for the
    /// exercises that are still there).
    pub fn poll(&mut self) -> Option<Note> {
        let sig = lesson_signature(&self.lesson.dir);
        if sig == self.signature {
            return None;
        }
        self.signature = sig;
        match Lesson::load(&self.lesson.dir) {
            Ok(lesson) => {
                let answers = lesson
                    .exercises
                    .iter()
                    .map(|ex| {
                        self.lesson
                            .exercises
                            .iter()
                            .position(|old| old.id == ex.id)
                            .and_then(|i| self.answers[i].clone())
                    })
                    .collect();
                self.exercise = self.exercise.min(lesson.exercises.len().saturating_sub(1));
                self.answers = answers;
                self.lesson = lesson;
                None
            }
            Err(e) => Some((e.to_string(), Tone::Bad)),
        }
    }

    /// How far the view shown can scroll in the lesson pane (none without the pane).
    pub fn max_scroll(&self, pane: Option<Rect>) -> u16 {
        let Some(r) = pane else { return 0 };
        let i = inner(r);
        match self.view {
            LessonView::Exercises => {
                let v = exercises::view(self, i);
                v.text.len().saturating_sub(v.room).min(u16::MAX as usize) as u16
            }
            LessonView::Readme => {
                let rows = markdown(&self.lesson.readme, (i.width as usize).max(10));
                max_scroll(rows.len(), i.height)
            }
        }
    }

    /// Scrolls the README by `delta` rows, within the limit of the view shown.
    pub fn scroll_by(&mut self, delta: i32, pane: Option<Rect>) {
        self.scroll = scrolled(self.scroll, delta, self.max_scroll(pane));
    }

    /// Moves the window over the README's figures sideways by `delta` cells, as far as the
    /// widest figure goes in the pane.
    pub fn pan_by(&mut self, delta: i32, pane: Option<Rect>) {
        let Some(r) = pane else { return };
        let width = (inner(r).width as usize).max(10);
        let most = overhang(&markdown(&self.lesson.readme, width), width);
        let most = most.min(u16::MAX as usize) as u16;
        self.pan = scrolled(self.pan, delta, most);
    }

    /// Scrolls the selected exercise's text by `delta` rows.
    pub fn scroll_exercise(&mut self, delta: i32, pane: Option<Rect>) {
        self.exercise_scroll = scrolled(self.exercise_scroll, delta, self.max_scroll(pane));
    }
}

/// The kinds of question whose answer is an intensity (or a term of one).
fn about_intensity(ask: Ask) -> bool {
    matches!(
        ask,
        Ask::Intensity | Ask::Local | Ask::Diffuse | Ask::Specular | Ask::PixelValue
    )
}

/// The pixel whose primary ray (through its centre) is this ray, if there is one.
pub fn pixel_of_ray(scene: &Scene, ray: &Ray) -> Option<(u32, u32)> {
    let cam = &scene.camera;
    if (ray.origin - cam.eye()).length() > 1e-9 || cam.width as u64 * cam.height as u64 > 1 << 20 {
        return None;
    }
    let mut best = (f64::NEG_INFINITY, 0, 0);
    for y in 0..cam.height {
        for x in 0..cam.width {
            let d = cam.pixel_ray(x, y).dir.dot(ray.dir);
            if d > best.0 {
                best = (d, x, y);
            }
        }
    }
    (best.0 > 1.0 - 1e-12).then_some((best.1, best.2))
}
