//! The scene file: where it is, the last scene that loaded from it, and why the file on disk
//! does not load when it does not (the last good scene stays on screen meanwhile). A changed
//! file is loaded again on a thread of its own, so a large scene (or a file that is not a file
//! at all) never holds up the keys.

use std::path::{Path, PathBuf};
use std::sync::mpsc::{channel, Receiver, RecvTimeoutError};
use std::sync::Arc;
use std::time::{Duration, SystemTime};

use super::{Note, Tone};
use crate::lessons::Lesson;
use crate::scene::{Limits, Scene};

/// Size and modification time: a file changed when either did.
pub(crate) type FileSig = (Option<SystemTime>, u64);

pub(crate) fn signature(path: &Path) -> Option<FileSig> {
    let m = std::fs::metadata(path).ok()?;
    Some((m.modified().ok(), m.len()))
}

/// The signatures of a scene file and of the files it reads (meshes, textures): the scene
/// changed when any of them did.
fn signatures(path: &Path, scene: Option<&Scene>) -> Vec<Option<FileSig>> {
    let inputs = scene.map_or(&[][..], |s| &s.inputs[..]);
    std::iter::once(path)
        .chain(inputs.iter().map(PathBuf::as_path))
        .map(signature)
        .collect()
}

pub struct SceneFile {
    pub path: Option<PathBuf>,
    /// The last scene that loaded.
    pub scene: Option<Arc<Scene>>,
    /// Why the scene file on disk does not load.
    pub error: Option<String>,
    /// The scene file's and its inputs' (`signatures`) when last loaded.
    signature: Vec<Option<FileSig>>,
    /// A reload running on its own thread: where its scene (or error) arrives.
    loading: Option<Receiver<Result<Scene, String>>>,
    /// How long `poll` waits for a reload before leaving it to a later poll. The explorer's
    /// event loop waits a few milliseconds (a small scene still appears at once); without a
    /// loop (tests, scripts) a poll waits for the reload to finish.
    pub reload_wait: Duration,
    /// The budgets every scene is loaded within, reloads too: `--allow-huge` raises them for
    /// the whole session, so an edit that grows the scene is still shown.
    pub limits: Limits,
}

impl Default for SceneFile {
    fn default() -> SceneFile {
        SceneFile {
            path: None,
            scene: None,
            error: None,
            signature: Vec::new(),
            loading: None,
            reload_wait: Duration::from_secs(60),
            limits: Limits::default(),
        }
    }
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
    /// Loads a scene file or a lesson folder (its scene.yaml and its lesson) within `limits`.
    pub fn open(target: &Path, limits: &Limits) -> Result<Opened, String> {
        let target = display_path(target);
        let (path, lesson) = if target.is_dir() {
            let scene = target.join("scene.yaml");
            if crate::lessons::is_lesson_folder(&target) {
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
                .filter(|d| crate::lessons::is_lesson_folder(d));
            (target.clone(), dir.and_then(|d| Lesson::load(d).ok()))
        };
        let scene = crate::scene::load(&path, limits).map_err(|e| e.to_string())?;
        Ok(Opened {
            path,
            scene,
            lesson,
            folder: target.is_dir(),
        })
    }

    /// Watches `path`, just loaded as `scene`, for changes from now on: it and the files the
    /// scene reads.
    pub fn watch(&mut self, path: PathBuf, scene: &Scene) {
        self.signature = signatures(&path, Some(scene));
        self.path = Some(path);
        self.error = None;
    }

    /// Takes the file as changed on disk: the next poll loads it again (the explorer's latency
    /// bench times a reload this way without touching the user's file).
    pub(crate) fn mark_changed(&mut self) {
        self.signature.clear();
    }

    /// The scene file again if it changed on disk and loads; a file that does not load is kept
    /// in `error` instead. The load runs on its own thread: a poll starts it, and this poll or
    /// a later one takes its result.
    pub fn poll(&mut self) -> Option<(Scene, Note)> {
        let path = self.path.clone()?;
        if self.loading.is_none() {
            let sig = signatures(&path, self.scene.as_deref());
            if sig == self.signature {
                return None;
            }
            self.signature = sig;
            let (tx, rx) = channel();
            let file = path.clone();
            let limits = self.limits;
            let started = std::thread::Builder::new()
                .name("reload".into())
                .spawn(move || {
                    let loaded = crate::scene::load(&file, &limits);
                    let _ = tx.send(loaded.map_err(|e| e.to_string()));
                });
            if let Err(e) = started {
                self.error = Some(format!("{}: cannot reload: {e}", path.display()));
                return None;
            }
            self.loading = Some(rx);
        }
        let result = match self.loading.as_ref()?.recv_timeout(self.reload_wait) {
            Err(RecvTimeoutError::Timeout) => return None,
            Ok(result) => result,
            Err(RecvTimeoutError::Disconnected) => {
                Err(format!("{}: the reload failed", path.display()))
            }
        };
        self.loading = None;
        match result {
            Ok(scene) => {
                // The files this scene reads are the ones to watch now.
                self.signature = signatures(&path, Some(&scene));
                let had_error = self.error.take().is_some();
                let note = format!(
                    "reloaded {}{}",
                    path.display(),
                    if had_error { " (fixed)" } else { "" }
                );
                Some((scene, (note, Tone::Good)))
            }
            Err(e) => {
                self.error = Some(e);
                None
            }
        }
    }

    /// A reload is running.
    pub fn loading(&self) -> bool {
        self.loading.is_some()
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
