//! Lessons and exercises as files: `lessons/NN-topic/{README.md, scene.yaml, exercises.yaml}`.

use std::path::{Path, PathBuf};

use glam::DVec3;
use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::error::LessonError;
use super::tolerance::Tolerance;
use super::vary::{self, Range};
use super::yaml_spans;
use crate::files::{read_text, ReadError, TEXT_BUDGET};
use crate::shading::Highlight;

/// A validation tries the varied values in every combination up to this many, else in pairs.
const COMBINATIONS: usize = 4096;

/// Combinations of varied values that keep a scene from loading are named up to this many.
const CLASHES_NAMED: usize = 8;

/// What an exercise asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Ask {
    /// p_W, the world point of the pixel's centre on the window (window camera): a vector.
    WindowPoint,
    /// The unit direction of the node's ray.
    RayDirection,
    /// The origin of the node's ray.
    RayOrigin,
    /// The node's total intensity (for the root of a pixel: the pixel intensity): a number
    /// when grey, else r, g, b.
    Intensity,
    /// The node's local term: ambient + Σ over the lights of diffuse + specular.
    Local,
    /// t of the node's nearest hit; directions are unit, so t is a distance.
    HitT,
    /// The node's nearest hit point, o + t·d.
    HitPoint,
    /// The unit normal at the hit, facing the incoming ray.
    Normal,
    /// v' = v − 2(v·n)n at the node's hit.
    ReflectedDirection,
    /// The refracted direction by Snell's law at the node's hit, or `tir` for total internal
    /// reflection.
    RefractedDirection,
    /// The shadow factor s (0 or 1) of `light` at the node's hit.
    ShadowFactor,
    /// `light`'s diffuse term s·fatt·Iℓ·kd·O·(n·l) at the node's hit.
    Diffuse,
    /// `light`'s specular term s·fatt·Iℓ·ks·(h·n)^m (or (r·v)^m with Phong) at the node's hit.
    Specular,
    /// The segment list (t_in, t_out pairs) of `object` along the node's ray.
    Segments,
    /// The barycentric coordinates (λ1, λ2, λ3) of the hit on a triangle.
    Barycentric,
    /// The rendered value of `pixel`: all its primary rays, with the scene's `spp`,
    /// `antialias` and integrator (path tracing with the fixed seed 0, so it is repeatable).
    PixelValue,
    /// Primary rays traced: for `pixel` alone (its corners included), or, without a pixel,
    /// for the whole image.
    PrimaryRays,
    /// Squares split by adaptive antialiasing: in `pixel`, or in the whole image.
    SquaresSplit,
    /// The leaves of `object`'s CSG tree whose segment lists are computed along the ray, the
    /// others skipped by pruning or by bounding boxes.
    LeavesEvaluated,
    /// The texture coordinate u of the hit (a texture's or a uv pattern's).
    U,
    /// The texture coordinate v of the hit.
    V,
    /// The surface's colour O at the hit: its pattern's or texture's value there.
    SurfaceColor,
}

impl Ask {
    /// Asks about rendering the image (or one pixel of it), not about one traced ray.
    pub fn about_image(self) -> bool {
        matches!(self, Ask::PrimaryRays | Ask::SquaresSplit)
    }
}

/// An explicit ray an exercise traces instead of a pixel's primary ray.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RaySpec {
    /// Where the ray starts, in world coordinates.
    pub origin: DVec3,
    /// Its direction, not zero; raytree normalises it before tracing, so t is a distance.
    pub direction: DVec3,
}

/// One exercise of exercises.yaml: a question about one value of a traced ray (or of the
/// rendered image), whose answer raytree works out from the lesson's scene.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Exercise {
    /// Short, unique in the lesson, kebab-case: how `check`, the README's answer lines and the
    /// answers CSV name the exercise.
    pub id: String,
    /// The question as the student reads it (varied values filled in).
    pub question: String,
    /// Which value is asked for, and so which kind of answer.
    pub ask: Ask,
    /// The pixel whose primary ray is traced, [x, y] with (0, 0) at the top left.
    pub pixel: Option<[u32; 2]>,
    /// A ray traced instead of a pixel's.
    pub ray: Option<RaySpec>,
    /// Path from the root of the ray tree: "", "reflection", "refraction/reflection".
    #[serde(default)]
    pub node: String,
    /// The light's name, for `shadow_factor`, `diffuse` and `specular`.
    pub light: Option<String>,
    /// The object's name, for `segments` and `leaves_evaluated`.
    pub object: Option<String>,
    /// Another scene file of the lesson (default scene.yaml).
    pub scene: Option<String>,
    /// Overrides the scene's max_depth (for the ray tree, and for rendering a pixel).
    pub depth: Option<u32>,
    /// The highlight model the exercise is worked in (`phong` or `blinn`), for every material
    /// of its scene; without it, each material's own.
    pub model: Option<Highlight>,
    /// How close an answer must be (see `Tolerance`).
    #[serde(default)]
    pub tolerance: Tolerance,
    /// Shown on request before the answer.
    pub hint: Option<String>,
}

/// Whether the worked solutions are shown.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Solutions {
    /// `check --explain` and the explorer's worked solutions, all numbers in the explorer.
    #[default]
    Shown,
    /// For homework: no worked solutions, and the explorer hides the intensities that would
    /// give an answer away until it is answered.
    Hidden,
}

/// Whose homework a lesson folder is: written by `raytree homework` into its exercises.yaml.
#[derive(Clone, Debug, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct VariantOf {
    /// The lesson it was made from (its folder name).
    pub lesson: String,
    /// The student ID the values were drawn for.
    pub student: String,
    /// The varied values this student got, as written in the scene.
    pub values: BTreeMap<String, String>,
    /// Each scene file of the homework as written (its name → `fingerprint`): a scene changed
    /// afterwards is no longer the variant the values name (`Lesson::edited_scenes`).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub scenes: BTreeMap<String, String>,
}

/// What `Lesson::check_variations` finds of a lesson's varied values.
pub struct Variations {
    /// The values that keep a scene from loading, alone or together, each a line with the
    /// scene's error.
    pub unloadable: Vec<String>,
    /// The lesson with each value on its own whose scenes load, named by the value.
    pub loading: Vec<(String, Lesson)>,
}

/// A short fingerprint of a file's text (64-bit FNV-1a, in hex): enough to see that a file was
/// changed by hand, not a guard against forgery.
pub fn fingerprint(text: &str) -> String {
    let hash = text.bytes().fold(0xcbf2_9ce4_8422_2325_u64, |h, b| {
        (h ^ b as u64).wrapping_mul(0x0000_0100_0000_01b3)
    });
    format!("{hash:016x}")
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ExerciseFile {
    title: String,
    summary: String,
    #[serde(default)]
    solutions: Solutions,
    #[serde(default)]
    vary: BTreeMap<String, Range>,
    variant: Option<VariantOf>,
    exercises: Vec<Exercise>,
}

/// A lesson: its folder's exercises.yaml and README.md, loaded; for a student, with their
/// varied values written in.
#[derive(Clone, Debug, Default)]
pub struct Lesson {
    /// The lesson's folder, where its scene files are.
    pub dir: PathBuf,
    /// The folder name, e.g. "08-pixel-intensity".
    pub id: String,
    /// The title, from exercises.yaml.
    pub title: String,
    /// What the lesson is about in a sentence or two, from exercises.yaml (shown in lesson
    /// lists).
    pub summary: String,
    /// The text of README.md, the lesson itself with its `**Answer (ID):**` lines; empty when
    /// the folder has none.
    pub readme: String,
    /// The exercises in file order, their questions filled in with the varied values.
    pub exercises: Vec<Exercise>,
    /// Whether the worked solutions are shown (`solutions:` of exercises.yaml).
    pub solutions: Solutions,
    /// Scene values that vary from student to student (see `vary.rs`).
    pub vary: BTreeMap<String, Range>,
    /// Set in a student's homework folder, and in a lesson made for a student.
    pub variant: Option<VariantOf>,
    /// Scene texts that replace the files of the same name (a student's variant, in memory).
    pub sources: BTreeMap<String, String>,
    /// The questions as written, with `{path}` where they quote a varied value.
    pub templates: Vec<String>,
}

/// A student's ID as it identifies them: trimmed, and in Unicode's composed form (NFC), so that
/// "José" typed with é and with e and a combining accent (as some systems and spreadsheets
/// write it) is one student, with one variant.
pub fn student_id(id: &str) -> String {
    use unicode_normalization::UnicodeNormalization;
    id.trim().nfc().collect()
}

/// The node at `steps` of a parsed exercises.yaml: a key of a mapping (taken whole: a `vary`
/// key holds dots), or an index into a list.
fn node_at<'n>(root: &'n yaml_spans::Node, steps: &[&str]) -> Option<&'n yaml_spans::Node> {
    steps.iter().try_fold(root, |node, step| match &node.value {
        yaml_spans::Kind::Map(entries) => entries.iter().find(|(k, _)| k == step).map(|(_, v)| v),
        yaml_spans::Kind::Seq(items) => items.get(step.parse::<usize>().ok()?),
        yaml_spans::Kind::Scalar(_) => None,
    })
}

/// Whether a file name stays inside the folder it is read from: relative, and without `..`.
fn inside_the_folder(name: &str) -> bool {
    let path = Path::new(name);
    !name.is_empty()
        && path.components().all(|c| {
            matches!(
                c,
                std::path::Component::Normal(_) | std::path::Component::CurDir
            )
        })
}

impl Lesson {
    /// The lesson a user names: its folder, or its name in the lessons folder (`find_lesson`).
    pub fn named(folder_or_name: &Path) -> Result<Lesson, LessonError> {
        Lesson::load(&lesson_dir(folder_or_name)?)
    }

    /// Loads the lesson of a folder: its exercises.yaml and README.md.
    pub fn load(dir: &Path) -> Result<Lesson, LessonError> {
        let id = dir
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let path = dir.join("exercises.yaml");
        let text =
            read_text(&path, TEXT_BUDGET).map_err(|e| LessonError::io(&path, "read", e.into()))?;
        let file: ExerciseFile = serde_saphyr::from_str(&text).map_err(|e| {
            use serde_saphyr::MessageFormatter;
            let (line, column) = e.location().map_or((1, 1), |l| (l.line(), l.column()));
            // The message alone: the error's own text repeats the line and column.
            let text = serde_saphyr::DefaultMessageFormatter.format_message(&e);
            let first = text.lines().next().unwrap_or("").trim();
            LessonError::Format {
                file: path.clone(),
                line,
                column,
                message: first.strip_prefix("error: ").unwrap_or(first).to_string(),
            }
        })?;
        // A lesson may have no README; one that is there must read.
        let path = dir.join("README.md");
        let readme = match read_text(&path, TEXT_BUDGET) {
            Err(ReadError::Io(e)) if e.kind() == std::io::ErrorKind::NotFound => String::new(),
            read => read.map_err(|e| LessonError::io(&path, "read", e.into()))?,
        };
        let path = dir.join("exercises.yaml");
        // Where in the file a mistake found after parsing lies (the file parsed, it parses
        // again; where a node cannot be found, the file alone is named).
        let spans = yaml_spans::parse(&text).ok();
        let at = |steps: &[&str], message: String| -> LessonError {
            match spans.as_ref().and_then(|root| node_at(root, steps)) {
                Some(node) => LessonError::Format {
                    file: path.clone(),
                    line: node.referenced.line(),
                    column: node.referenced.column(),
                    message,
                },
                None => LessonError::Invalid {
                    file: path.clone(),
                    message,
                },
            }
        };
        let mut seen = std::collections::HashSet::new();
        for (i, ex) in file.exercises.iter().enumerate() {
            let i = i.to_string();
            let field = |key: &'static str| ["exercises", i.as_str(), key];
            if !seen.insert(&ex.id) {
                return Err(at(
                    &field("id"),
                    format!("duplicate exercise id `{}`", ex.id),
                ));
            }
            if let Some(p) = vary::placeholders(&ex.question).find(|p| !file.vary.contains_key(*p))
            {
                let varied: Vec<&str> = file.vary.keys().map(String::as_str).collect();
                return Err(at(
                    &field("question"),
                    format!(
                        "exercise `{}`: the question quotes `{{{p}}}`, which is not a value the lesson varies ({})",
                        ex.id,
                        match varied.is_empty() {
                            true => "it varies none".to_string(),
                            false => format!("it varies {}", varied.join(", ")),
                        }
                    ),
                ));
            }
            if ex.pixel.is_none() && ex.ray.is_none() && !ex.ask.about_image() {
                return Err(at(
                    &["exercises", &i],
                    format!("exercise `{}` needs `pixel` or `ray`", ex.id),
                ));
            }
            if ex.pixel.is_some() && ex.ray.is_some() {
                return Err(at(
                    &field("ray"),
                    format!(
                        "exercise `{}`: give `pixel` or `ray`, not both: the ray would be left unused",
                        ex.id
                    ),
                ));
            }
            let most = crate::scene::Limits::default().max_depth;
            if let Some(depth) = ex.depth.filter(|d| !(1..=most).contains(d)) {
                return Err(at(
                    &field("depth"),
                    format!(
                        "exercise `{}`: depth {depth}: a depth is from 1 (the primary ray alone) to {most}",
                        ex.id
                    ),
                ));
            }
            if let Some(scene) = ex.scene.as_deref().filter(|s| !inside_the_folder(s)) {
                return Err(at(
                    &field("scene"),
                    format!(
                        "exercise `{}`: scene `{scene}`: an exercise's scene is a file of the lesson's folder, named from it without `..`",
                        ex.id
                    ),
                ));
            }
        }
        let templates = file.exercises.iter().map(|e| e.question.clone()).collect();
        let mut lesson = Lesson {
            dir: dir.to_path_buf(),
            id,
            title: file.title,
            summary: file.summary,
            readme,
            exercises: file.exercises,
            solutions: file.solutions,
            vary: file.vary,
            variant: file.variant,
            sources: BTreeMap::new(),
            templates,
        };
        if !lesson.vary.is_empty() {
            for (p, range) in &lesson.vary {
                range
                    .check()
                    .map_err(|e| at(&["vary", p], format!("vary `{p}`: {e}")))?;
            }
            let files = lesson.scene_files()?;
            let base = vary::written(&files, lesson.vary.keys().cloned());
            if let Some(p) = lesson.vary.keys().find(|p| !base.contains_key(*p)) {
                return Err(at(
                    &["vary", p],
                    format!(
                        "vary `{p}`: no scene of the lesson writes that value (write it out to vary it)"
                    ),
                ));
            }
            lesson.fill_questions(&base);
        }
        Ok(lesson)
    }

    /// The texts of the lesson's scene files (scene.yaml and every scene an exercise names),
    /// as a student's variant has them.
    pub fn scene_files(&self) -> Result<BTreeMap<String, String>, LessonError> {
        let mut files = vary::scene_files(
            &self.dir,
            self.exercises.iter().filter_map(|e| e.scene.clone()),
        )?;
        for (name, text) in &self.sources {
            files.insert(name.clone(), text.clone());
        }
        Ok(files)
    }

    fn fill_questions(&mut self, values: &BTreeMap<String, String>) {
        for (ex, template) in self.exercises.iter_mut().zip(&self.templates) {
            ex.question = vary::fill(template, values);
        }
    }

    /// The lesson as a student gets it: the varied values drawn for that student written into
    /// its scenes (in memory) and its questions. A lesson that varies nothing is the same for
    /// everyone.
    pub fn variant(&self, student: &str) -> Result<Lesson, LessonError> {
        let student = &student_id(student);
        if student.is_empty() {
            return Err(LessonError::EmptyStudent);
        }
        // A homework folder is one student's variant already: its values are its owner's.
        if let Some(of) = &self.variant {
            if student_id(&of.student) != *student {
                return Err(LessonError::OtherStudentsHomework {
                    lesson: of.lesson.clone(),
                    owner: of.student.clone(),
                    student: student.to_string(),
                });
            }
        }
        let mut out = self.clone();
        if self.vary.is_empty() {
            return Ok(out);
        }
        let drawn = vary::draw(&self.id, student, &self.vary);
        out.sources = vary::rewrite(&self.scene_files()?, &drawn).map_err(LessonError::Scenes)?;
        let shown: BTreeMap<String, String> = drawn
            .iter()
            .map(|(p, v)| (p.clone(), vary::show(v)))
            .collect();
        if let Err(error) = self.load_sources(&out.sources) {
            return Err(LessonError::VariantDoesNotLoad {
                student: student.to_string(),
                values: shown
                    .iter()
                    .map(|(p, v)| format!("{p} = {v}"))
                    .collect::<Vec<_>>()
                    .join(", "),
                error,
            });
        }
        out.fill_questions(&shown);
        out.variant = Some(VariantOf {
            lesson: self.id.clone(),
            student: student.to_string(),
            values: shown,
            scenes: BTreeMap::new(),
        });
        Ok(out)
    }

    /// Whether scene texts of this lesson (file name → text) load, as a scene file in its
    /// folder would: the first one's error if one does not.
    fn load_sources(&self, sources: &BTreeMap<String, String>) -> Result<(), String> {
        for (name, text) in sources {
            let path = self.dir.join(name);
            let file = path.display().to_string();
            crate::scene::parse(text, &file, Some(&path), &crate::scene::Limits::default())
                .map_err(|e| e.to_string())?;
        }
        Ok(())
    }

    /// The varied values that keep a scene from loading, each as a line naming the values and
    /// the scene's error. Each range is tried at its ends and its first step (a range of whole
    /// numbers written without `step` draws fractions there), and each listed value of a
    /// `one_of`: first each path on its own, the others as the lesson writes them, then those
    /// values together, every combination of them (or, where there would be more than
    /// `COMBINATIONS`, every pair of paths): two values that are fine alone may clash together
    /// (a box's corners varied apart can cross).
    ///
    /// With them, the lesson as it stands with each value tried on its own whose scenes load,
    /// named by the value: what `lessons validate` works every exercise out in.
    pub fn check_variations(&self) -> Result<Variations, LessonError> {
        let files = self.scene_files()?;
        let probes: Vec<(&String, Vec<Vec<String>>)> = self
            .vary
            .iter()
            .map(|(path, r)| (path, r.probes()))
            .collect();
        let mut problems = Vec::new();
        let mut loading = Vec::new();
        let mut fails_alone: Vec<Vec<bool>> = Vec::new();
        for (path, values) in &probes {
            let mut fails = Vec::new();
            for value in values {
                let one = BTreeMap::from([((*path).clone(), value.clone())]);
                let sources = vary::rewrite(&files, &one).map_err(LessonError::Scenes)?;
                let shown = format!("vary `{path}` = {}", vary::show(value));
                let loads = self.load_sources(&sources);
                fails.push(loads.is_err());
                match loads {
                    Err(e) => problems.push(format!("{shown}: {e}")),
                    Ok(()) => {
                        let mut lesson = self.clone();
                        lesson.sources = sources;
                        loading.push((shown, lesson));
                    }
                }
            }
            fails_alone.push(fails);
        }
        let counts: Vec<usize> = probes.iter().map(|(_, v)| v.len()).collect();
        let mut clashes = Vec::new();
        for picks in vary::combinations(&counts, COMBINATIONS) {
            // A value that fails alone fails in every combination: it is named once, above.
            let chosen: Vec<(usize, usize)> = picks
                .iter()
                .enumerate()
                .filter_map(|(p, k)| k.map(|k| (p, k)))
                .collect();
            if chosen.iter().any(|&(p, k)| fails_alone[p][k]) {
                continue;
            }
            let values: BTreeMap<String, Vec<String>> = chosen
                .iter()
                .map(|&(p, k)| (probes[p].0.clone(), probes[p].1[k].clone()))
                .collect();
            if let Some(e) = self.load_error(&files, &values)? {
                let together: Vec<String> = values
                    .iter()
                    .map(|(path, v)| format!("`{path}` = {}", vary::show(v)))
                    .collect();
                clashes.push(format!("vary {} together: {e}", together.join(", ")));
            }
        }
        let more = clashes.len().saturating_sub(CLASHES_NAMED);
        problems.extend(clashes.into_iter().take(CLASHES_NAMED));
        if more > 0 {
            problems.push(format!(
                "… and {more} more combinations of varied values that keep a scene from loading"
            ));
        }
        Ok(Variations {
            unloadable: problems,
            loading,
        })
    }

    /// Why the lesson's scenes, with `values` written in, do not load (None where they do).
    fn load_error(
        &self,
        files: &BTreeMap<String, String>,
        values: &BTreeMap<String, Vec<String>>,
    ) -> Result<Option<String>, LessonError> {
        let sources = vary::rewrite(files, values).map_err(LessonError::Scenes)?;
        Ok(self.load_sources(&sources).err())
    }

    /// The scene files of a homework folder changed since `raytree homework` wrote them (or
    /// missing), by name: grading such a folder would grade the student's own edits.
    pub fn edited_scenes(&self) -> Vec<String> {
        let Some(of) = &self.variant else {
            return Vec::new();
        };
        of.scenes
            .iter()
            .filter(|(name, print)| {
                let text = std::fs::read_to_string(self.dir.join(name.as_str()));
                text.map_or(true, |t| fingerprint(&t) != **print)
            })
            .map(|(name, _)| name.clone())
            .collect()
    }

    /// The text of an exercise's scene when the lesson holds it in memory (a variant).
    pub fn scene_source(&self, ex: &Exercise) -> Option<&str> {
        self.sources
            .get(ex.scene.as_deref().unwrap_or("scene.yaml"))
            .map(String::as_str)
    }

    /// The exercise of that id; fails with `LessonError::UnknownExercise`, which lists the
    /// lesson's exercises.
    pub fn exercise(&self, id: &str) -> Result<&Exercise, LessonError> {
        self.exercises
            .iter()
            .find(|e| e.id == id)
            .ok_or_else(|| LessonError::UnknownExercise {
                lesson: self.id.clone(),
                id: id.into(),
                exercises: self.exercises.iter().map(|e| e.id.clone()).collect(),
            })
    }

    /// The file of an exercise's scene: its `scene`, else scene.yaml, in the lesson's folder
    /// (a variant's text may replace it: `scene_source`).
    pub fn scene_path(&self, ex: &Exercise) -> PathBuf {
        self.dir.join(ex.scene.as_deref().unwrap_or("scene.yaml"))
    }

    /// The `**Answer (ID):** value` lines of the README: the hand-worked results.
    pub fn stated_answers(&self) -> Vec<(String, String)> {
        self.stated_answer_lines()
            .into_iter()
            .map(|(_, id, value)| (id, value))
            .collect()
    }

    /// `stated_answers`, each with its line number in the README (from 1).
    pub fn stated_answer_lines(&self) -> Vec<(usize, String, String)> {
        self.readme
            .lines()
            .enumerate()
            .filter_map(|(i, l)| {
                let rest = l.trim().strip_prefix("**Answer (")?;
                let (id, value) = rest.split_once("):**")?;
                Some((i + 1, id.trim().to_string(), value.trim().to_string()))
            })
            .collect()
    }
}

/// The lessons folder chosen on the command line (`--lessons DIR`), before any other.
static CHOSEN_ROOT: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();

/// Makes `dir` the lessons folder of this run, as `--lessons DIR` does (the first call wins).
pub fn use_lessons_root(dir: PathBuf) {
    let _ = CHOSEN_ROOT.set(dir);
}

/// The lessons folder: `--lessons DIR`, else `RAYTREE_LESSONS`, else `./lessons`, else the
/// built-in lessons (written to the user's cache folder on first use).
pub fn lessons_root() -> Result<PathBuf, LessonError> {
    match named_root() {
        Some(root) => Ok(root),
        None => super::builtin::cached(),
    }
}

/// The lessons folder when one is named (`--lessons DIR`, `RAYTREE_LESSONS`) or at hand
/// (`./lessons`); None where the built-in lessons are used.
fn named_root() -> Option<PathBuf> {
    CHOSEN_ROOT
        .get()
        .cloned()
        .or_else(|| std::env::var_os("RAYTREE_LESSONS").map(PathBuf::from))
        .or_else(|| Some(PathBuf::from("lessons")).filter(|p| p.is_dir()))
}

/// The lesson folder a user names: the path itself when it exists, else the lesson of that
/// name in the lessons folder, so `08-pixel-intensity` and `lessons/08-pixel-intensity` work
/// from any folder.
pub fn find_lesson(path: &Path) -> PathBuf {
    if path.exists() {
        return path.to_path_buf();
    }
    let name = path.strip_prefix("lessons").unwrap_or(path);
    if name.as_os_str().is_empty() {
        return path.to_path_buf();
    }
    let in_root = lessons_root().ok().map(|root| root.join(name));
    if let Some(found) = in_root.filter(|p| p.exists()) {
        return found;
    }
    // A `lessons/` folder that happens to be in the current folder (not one the user chose)
    // comes before the built-in lessons, and does not hide them.
    let chosen = CHOSEN_ROOT.get().is_some() || std::env::var_os("RAYTREE_LESSONS").is_some();
    if !chosen {
        if let Some(found) = super::builtin::cached()
            .ok()
            .map(|root| root.join(name))
            .filter(|p| p.exists())
        {
            return found;
        }
    }
    path.to_path_buf()
}

/// The lesson folder a user names, as `find_lesson` finds it; a name that is neither a path
/// nor a lesson of the lessons folder is an error that says so, rather than a complaint about
/// an exercises.yaml the user never named.
pub fn lesson_dir(path: &Path) -> Result<PathBuf, LessonError> {
    let found = find_lesson(path);
    if found.exists() {
        return Ok(found);
    }
    Err(LessonError::NoLesson {
        name: path.to_path_buf(),
        among: match named_root() {
            Some(root) => format!("not a lesson in {}", root.display()),
            None => "not a built-in lesson".into(),
        },
    })
}

/// Whether a folder is a lesson: it holds an exercises.yaml. Of any kind: one that is not a
/// regular file (a device, a folder) is then refused by name when the lesson loads, rather
/// than the folder passed over in silence.
pub fn is_lesson_folder(dir: &Path) -> bool {
    dir.join("exercises.yaml").exists()
}

/// All lessons, in folder order.
pub fn all_lessons(root: &Path) -> Result<Vec<Lesson>, LessonError> {
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(root)
        .map_err(|e| LessonError::io(root, "list lessons", e))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| is_lesson_folder(p))
        .collect();
    dirs.sort();
    dirs.iter().map(|d| Lesson::load(d)).collect()
}
