//! A student's progress: which exercises of which lesson they have answered right, kept
//! between runs in the user's data folder (`progress.json` in `~/.local/share/raytree` on
//! Linux, the platform's own elsewhere; `RAYTREE_DATA` names another folder). `raytree check`
//! and the explorer record a right answer; `raytree lessons` and the explorer's lists show ✓.
//!
//! A built-in lesson is known by its name, so its marks outlive the cache folder its copy is
//! written to (a new version of raytree writes a new copy). Any other lesson is known by its
//! folder's full path, so a teacher's copy of a lesson and a student's homework keep their own
//! marks. Progress is a convenience: a file that cannot be read or written never stops a check,
//! and one that does not read as progress is left as it is, not written over.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::error::LessonError;
use super::exercise::Lesson;
use crate::files::{read_text, ReadError, TEXT_BUDGET};

/// The exercises a student has answered right, lesson by lesson, as `progress.json` keeps them.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct Progress {
    /// Lesson folder → the exercises answered right.
    #[serde(default)]
    pub lessons: BTreeMap<String, BTreeSet<String>>,
}

use crate::files::data_dir;

fn file() -> Option<PathBuf> {
    data_dir().map(|d| d.join("progress.json"))
}

/// How a lesson is known in the file: `built-in/NAME` for a built-in lesson, else its folder
/// as a full path.
pub fn key(lesson: &Lesson) -> String {
    folder_key(&lesson.dir)
}

/// The key of the lesson in `dir`. A built-in lesson's copy is `CACHE/lessons-VERSION-HASH/NAME`.
fn folder_key(dir: &Path) -> String {
    let dir = std::fs::canonicalize(dir).unwrap_or_else(|_| dir.to_path_buf());
    let cache = crate::files::cache_dir().map(|c| std::fs::canonicalize(&c).unwrap_or(c));
    let copy = dir.parent();
    let built_in = copy
        .and_then(Path::parent)
        .is_some_and(|c| Some(c) == cache.as_deref())
        && copy
            .and_then(Path::file_name)
            .is_some_and(|n| n.to_string_lossy().starts_with("lessons-"));
    match dir.file_name() {
        Some(name) if built_in => format!("built-in/{}", name.to_string_lossy()),
        _ => dir.display().to_string(),
    }
}

impl Progress {
    /// The progress saved so far (none when there is no file, or it does not read).
    pub fn load() -> Progress {
        Progress::read().unwrap_or_default()
    }

    /// The progress saved so far: none when there is no file; an error when there is one that
    /// cannot be read or does not read as progress. Marks kept under a built-in lesson's
    /// folder (as earlier versions kept them) count as that lesson's.
    fn read() -> Result<Progress, LessonError> {
        let Some(path) = file() else {
            return Ok(Progress::default());
        };
        let text = match read_text(&path, TEXT_BUDGET) {
            Ok(text) => text,
            Err(ReadError::Io(e)) if e.kind() == std::io::ErrorKind::NotFound => {
                return Ok(Progress::default())
            }
            Err(e) => return Err(LessonError::io(&path, "read", e.into())),
        };
        let saved: Progress =
            serde_json::from_str(&text).map_err(|e| LessonError::ProgressUnreadable {
                path: path.clone(),
                reason: e.to_string(),
            })?;
        let mut progress = Progress::default();
        for (folder, solved) in saved.lessons {
            let key = if folder.starts_with("built-in/") {
                folder
            } else {
                folder_key(Path::new(&folder))
            };
            progress.lessons.entry(key).or_default().extend(solved);
        }
        Ok(progress)
    }

    /// The exercises of a lesson answered right.
    pub fn solved(&self, lesson: &Lesson) -> BTreeSet<String> {
        self.lessons.get(&key(lesson)).cloned().unwrap_or_default()
    }

    /// Records a right answer and saves; the error says why it could not be saved.
    pub fn record(lesson: &Lesson, exercise: &str) -> Result<(), LessonError> {
        let mut p = Progress::read()?;
        let new = p
            .lessons
            .entry(key(lesson))
            .or_default()
            .insert(exercise.to_string());
        if new {
            p.save()?;
        }
        Ok(())
    }

    /// Writes the file whole (a temporary file renamed over it).
    fn save(&self) -> Result<(), LessonError> {
        let path = file().ok_or(LessonError::NoDataDir)?;
        let dir = path.parent().unwrap_or(Path::new("."));
        std::fs::create_dir_all(dir).map_err(|e| LessonError::io(dir, "create the folder", e))?;
        let unwritable = |e: serde_json::Error| LessonError::io(&path, "write", e.into());
        let mut doc = serde_json::to_value(self).map_err(unwritable)?;
        doc["raytree_version"] = env!("CARGO_PKG_VERSION").into();
        let text = serde_json::to_string_pretty(&doc).map_err(unwritable)?;
        let tmp = dir.join(format!(".progress.json.{}", std::process::id()));
        std::fs::write(&tmp, text).map_err(|e| LessonError::io(&tmp, "write", e))?;
        std::fs::rename(&tmp, &path).map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            LessonError::io(&path, "write", e)
        })
    }
}
