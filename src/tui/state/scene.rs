//! The scene file: where it is, the last scene that loaded from it, and why the file on disk
//! does not load when it does not (the last good scene stays on screen meanwhile).

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::SystemTime;

use super::{Note, Tone};
use crate::lessons::Lesson;
use crate::scene::{Limits, Scene};

/// Size and modification time: a file changed when either did.
pub(crate) type FileSig = (Option<SystemTime>, u64);

pub(crate) fn signature(path: &Path) -> Option<FileSig> {
    let m = std::fs::metadata(path).ok()?;
    Some((m.modified().ok(), m.len()))
}

#[derive(Default)]
pub struct SceneFile {
    pub path: Option<PathBuf>,
    /// The last scene that loaded.
    pub scene: Option<Arc<Scene>>,
    /// Why the scene file on disk does not load.
    pub error: Option<String>,
    signature: Option<FileSig>,
}

/// What `raytree explore TARGET` opens: a scene, and its lesson when TARGET is a lesson folder
/// or one of a lesson's scene files.
pub struct Opened {
    pub path: PathBuf,
    pub scene: Scene,
    pub lesson: Option<Lesson>,
    /// TARGET was the lesson folder (its README opens beside the scene).
    pub folder: bool,
}

impl SceneFile {
    /// Loads a scene file or a lesson folder (its scene.yaml and its lesson).
    pub fn open(target: &Path) -> Result<Opened, String> {
        let target = display_path(target);
        let (path, lesson) = if target.is_dir() {
            let scene = target.join("scene.yaml");
            if target.join("exercises.yaml").is_file() {
                (scene, Some(Lesson::load(&target)?))
            } else if scene.is_file() {
                (scene, None)
            } else {
                return Err(format!(
                    "{}: not a lesson folder (no scene.yaml)",
                    target.display()
                ));
            }
        } else {
            // A scene file beside an exercises.yaml is one of that lesson's scenes.
            let dir = target
                .parent()
                .filter(|d| d.join("exercises.yaml").is_file());
            (target.clone(), dir.and_then(|d| Lesson::load(d).ok()))
        };
        let scene = crate::scene::load(&path, &Limits::default()).map_err(|e| e.to_string())?;
        Ok(Opened {
            path,
            scene,
            lesson,
            folder: target.is_dir(),
        })
    }

    /// Watches `path` for changes from now on.
    pub fn watch(&mut self, path: PathBuf) {
        self.signature = signature(&path);
        self.path = Some(path);
        self.error = None;
    }

    /// The scene file again if it changed on disk and loads; a file that does not load is kept
    /// in `error` instead.
    pub fn poll(&mut self) -> Option<(Scene, Note)> {
        let path = self.path.clone()?;
        let sig = signature(&path);
        if sig == self.signature {
            return None;
        }
        self.signature = sig;
        match crate::scene::load(&path, &Limits::default()) {
            Ok(scene) => {
                let had_error = self.error.take().is_some();
                let note = format!(
                    "reloaded {}{}",
                    path.display(),
                    if had_error { " (fixed)" } else { "" }
                );
                Some((scene, (note, Tone::Good)))
            }
            Err(e) => {
                self.error = Some(e.to_string());
                None
            }
        }
    }

    /// The image size of the scene (0 × 0 without one).
    pub fn image_size(&self) -> (u32, u32) {
        self.scene
            .as_ref()
            .map_or((0, 0), |s| (s.camera.width, s.camera.height))
    }

    /// The scene file as shown to the user.
    pub fn name(&self) -> String {
        self.path
            .as_ref()
            .map_or(String::new(), |p| p.display().to_string())
    }
}

/// A path relative to the working directory when it lies below it (shorter, and stable).
fn display_path(path: &Path) -> PathBuf {
    if path.is_absolute() {
        if let Ok(cwd) = std::env::current_dir() {
            if let Ok(rel) = path.strip_prefix(&cwd) {
                return rel.to_path_buf();
            }
        }
    }
    path.to_path_buf()
}
