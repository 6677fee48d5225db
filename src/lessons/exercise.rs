//! Lessons and exercises as files: `lessons/NN-topic/{README.md, scene.yaml, exercises.yaml}`.

use std::path::{Path, PathBuf};

use glam::DVec3;
use serde::Deserialize;

/// What an exercise asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Ask {
    WindowPoint,
    RayDirection,
    RayOrigin,
    Intensity,
    Local,
    HitT,
    HitPoint,
    Normal,
    ReflectedDirection,
    RefractedDirection,
    ShadowFactor,
    Diffuse,
    Specular,
    Segments,
    Barycentric,
    /// The rendered value of `pixel`: all its primary rays, with the scene's `spp`,
    /// `antialias` and integrator (path tracing with the fixed seed 0, so it is repeatable).
    PixelValue,
    /// Primary rays traced: for `pixel` alone (its corners included), or, without a pixel,
    /// for the whole image.
    PrimaryRays,
    /// Squares split by adaptive antialiasing: in `pixel`, or in the whole image.
    SquaresSplit,
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

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RaySpec {
    pub origin: DVec3,
    pub direction: DVec3,
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Exercise {
    pub id: String,
    pub question: String,
    pub ask: Ask,
    pub pixel: Option<[u32; 2]>,
    pub ray: Option<RaySpec>,
    /// Path from the root of the ray tree: "", "reflection", "refraction/reflection".
    #[serde(default)]
    pub node: String,
    pub light: Option<String>,
    pub object: Option<String>,
    /// Another scene file of the lesson (default scene.yaml).
    pub scene: Option<String>,
    /// Overrides the scene's max_depth (for the ray tree, and for rendering a pixel).
    pub depth: Option<u32>,
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
    /// Shown on request before the answer.
    pub hint: Option<String>,
}

fn default_tolerance() -> f64 {
    1e-3
}

#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ExerciseFile {
    title: String,
    summary: String,
    exercises: Vec<Exercise>,
}

#[derive(Clone, Debug)]
pub struct Lesson {
    pub dir: PathBuf,
    /// The folder name, e.g. "08-pixel-intensity".
    pub id: String,
    pub title: String,
    pub summary: String,
    pub readme: String,
    pub exercises: Vec<Exercise>,
}

impl Lesson {
    pub fn load(dir: &Path) -> Result<Lesson, String> {
        let id = dir
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let path = dir.join("exercises.yaml");
        let text = std::fs::read_to_string(&path)
            .map_err(|e| format!("{}: cannot read: {e}", path.display()))?;
        let file: ExerciseFile = serde_saphyr::from_str(&text).map_err(|e| {
            let (line, col) = e.location().map_or((1, 1), |l| (l.line(), l.column()));
            let msg = e.to_string();
            let first = msg.lines().next().unwrap_or("").to_string();
            format!("{}:{line}:{col}: {first}", path.display())
        })?;
        let readme = std::fs::read_to_string(dir.join("README.md")).unwrap_or_default();
        let mut seen = std::collections::HashSet::new();
        for ex in &file.exercises {
            if !seen.insert(&ex.id) {
                return Err(format!(
                    "{}: duplicate exercise id `{}`",
                    path.display(),
                    ex.id
                ));
            }
            if ex.pixel.is_none() && ex.ray.is_none() && !ex.ask.about_image() {
                return Err(format!(
                    "{}: exercise `{}` needs `pixel` or `ray`",
                    path.display(),
                    ex.id
                ));
            }
        }
        Ok(Lesson {
            dir: dir.to_path_buf(),
            id,
            title: file.title,
            summary: file.summary,
            readme,
            exercises: file.exercises,
        })
    }

    pub fn exercise(&self, id: &str) -> Result<&Exercise, String> {
        self.exercises.iter().find(|e| e.id == id).ok_or_else(|| {
            let ids: Vec<&str> = self.exercises.iter().map(|e| e.id.as_str()).collect();
            format!(
                "lesson {} has no exercise `{id}` (exercises: {})",
                self.id,
                ids.join(", ")
            )
        })
    }

    pub fn scene_path(&self, ex: &Exercise) -> PathBuf {
        self.dir.join(ex.scene.as_deref().unwrap_or("scene.yaml"))
    }

    /// The `**Answer (ID):** value` lines of the README: the hand-worked results.
    pub fn stated_answers(&self) -> Vec<(String, String)> {
        self.readme
            .lines()
            .filter_map(|l| {
                let rest = l.trim().strip_prefix("**Answer (")?;
                let (id, value) = rest.split_once("):**")?;
                Some((id.trim().to_string(), value.trim().to_string()))
            })
            .collect()
    }
}

/// The lessons folder: `RAYTREE_LESSONS`, else `./lessons`, else the one beside the sources.
pub fn lessons_root() -> PathBuf {
    if let Some(p) = std::env::var_os("RAYTREE_LESSONS") {
        return PathBuf::from(p);
    }
    let local = PathBuf::from("lessons");
    if local.is_dir() {
        return local;
    }
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("lessons")
}

/// All lessons, in folder order.
pub fn all_lessons(root: &Path) -> Result<Vec<Lesson>, String> {
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(root)
        .map_err(|e| format!("{}: cannot list lessons: {e}", root.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.join("exercises.yaml").is_file())
        .collect();
    dirs.sort();
    dirs.iter().map(|d| Lesson::load(d)).collect()
}
