//! A student's progress: which exercises of which lesson they have answered right, kept
//! between runs in the user's data folder (`progress.json` in `~/.local/share/raytree` on
//! Linux, the platform's own elsewhere; `RAYTREE_DATA` names another folder). `raytree check`
//! and the explorer record a right answer; `raytree lessons` and the explorer's lists show ✓.
//!
//! A lesson is known by its folder's full path, so a teacher's copy of a lesson and a student's
//! homework keep their own marks. Progress is a convenience: a file that cannot be read or
//! written never stops a check.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::error::LessonError;
use super::exercise::Lesson;

/// The exercises a student has answered right, lesson by lesson, as `progress.json` keeps them.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct Progress {
    /// Lesson folder → the exercises answered right.
    #[serde(default)]
    pub lessons: BTreeMap<String, BTreeSet<String>>,
}

/// The folder progress is kept in: `RAYTREE_DATA`, else the platform's data folder.
pub fn data_dir() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("RAYTREE_DATA") {
        return Some(PathBuf::from(p));
    }
    directories::ProjectDirs::from("", "", "raytree").map(|d| d.data_dir().to_path_buf())
}

fn file() -> Option<PathBuf> {
    data_dir().map(|d| d.join("progress.json"))
}

/// How a lesson is known in the file: its folder, as a full path.
pub fn key(lesson: &Lesson) -> String {
    std::fs::canonicalize(&lesson.dir)
        .unwrap_or_else(|_| lesson.dir.clone())
        .display()
        .to_string()
}

impl Progress {
    /// The progress saved so far (none when there is no file, or it does not read).
    pub fn load() -> Progress {
        file()
            .and_then(|f| std::fs::read_to_string(f).ok())
            .and_then(|t| serde_json::from_str(&t).ok())
            .unwrap_or_default()
    }

    /// The exercises of a lesson answered right.
    pub fn solved(&self, lesson: &Lesson) -> BTreeSet<String> {
        self.lessons.get(&key(lesson)).cloned().unwrap_or_default()
    }

    /// Records a right answer and saves; the error says why it could not be saved.
    pub fn record(lesson: &Lesson, exercise: &str) -> Result<(), LessonError> {
        let mut p = Progress::load();
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
