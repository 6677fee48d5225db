//! The lessons raytree ships with, compiled into the library so that an installed `raytree`
//! finds them from any folder. Lessons name their scenes, meshes and textures by paths relative
//! to their own folder, so they are used from a real folder: written once to the user's cache
//! folder, under a name that changes whenever their content does.

use std::path::{Path, PathBuf};

use include_dir::{include_dir, Dir, DirEntry};

use super::error::LessonError;

/// The `lessons/` folder of the sources, as it was when raytree was built.
static LESSONS: Dir<'static> = include_dir!("$CARGO_MANIFEST_DIR/lessons");

/// Every built-in file: its path inside the lessons folder, and its bytes.
pub fn files() -> Vec<(&'static Path, &'static [u8])> {
    fn walk(dir: &'static Dir<'static>, out: &mut Vec<(&'static Path, &'static [u8])>) {
        for entry in dir.entries() {
            match entry {
                DirEntry::Dir(d) => walk(d, out),
                DirEntry::File(f) => out.push((f.path(), f.contents())),
            }
        }
    }
    let mut out = vec![];
    walk(&LESSONS, &mut out);
    out.sort_by_key(|(p, _)| *p);
    out
}

/// A fingerprint of the built-in files (FNV-1a over their paths and bytes): two builds share
/// a cached copy only when their lessons are the same.
pub fn fingerprint() -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |bytes: &[u8]| {
        for &b in bytes {
            h = (h ^ b as u64).wrapping_mul(0x0000_0100_0000_01b3);
        }
        // A separator, so that moving bytes between a name and a content changes the hash.
        h = (h ^ 0xff).wrapping_mul(0x0000_0100_0000_01b3);
    };
    for (path, bytes) in files() {
        eat(path.to_string_lossy().as_bytes());
        eat(bytes);
    }
    h
}

/// Writes every built-in lesson under `dest`, which must not exist or be empty. The folder
/// appears whole or not at all: the files are written beside it, then moved into place.
pub fn export(dest: &Path) -> Result<(), LessonError> {
    if let Ok(mut entries) = std::fs::read_dir(dest) {
        if entries.next().is_some() {
            return Err(LessonError::NotEmpty(dest.to_path_buf()));
        }
    }
    let parent = match dest.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    std::fs::create_dir_all(&parent)
        .map_err(|e| LessonError::io(&parent, "create the folder", e))?;
    let staging = write_staging(&parent)?;
    if dest.is_dir() {
        // Empty (checked above): make way for the finished copy.
        std::fs::remove_dir(dest).map_err(|e| LessonError::io(dest, "replace the folder", e))?;
    }
    std::fs::rename(staging.path(), dest)
        .map_err(|e| LessonError::io(dest, "move the lessons into place", e))?;
    // The staging folder is now `dest`: nothing is left to clean up.
    let _ = staging.keep();
    Ok(())
}

/// The built-in lessons in a temporary folder inside `parent`, removed unless kept.
fn write_staging(parent: &Path) -> Result<tempfile::TempDir, LessonError> {
    let staging = tempfile::Builder::new()
        .prefix(".raytree-lessons-")
        .tempdir_in(parent)
        .map_err(|e| LessonError::io(parent, "create a temporary folder", e))?;
    for (path, bytes) in files() {
        let target = staging.path().join(path);
        if let Some(dir) = target.parent() {
            std::fs::create_dir_all(dir)
                .map_err(|e| LessonError::io(dir, "create the folder", e))?;
        }
        std::fs::write(&target, bytes).map_err(|e| LessonError::io(&target, "write", e))?;
    }
    Ok(staging)
}

/// Where the built-in lessons' copy lies in the user's cache folder.
fn cached_path() -> Option<PathBuf> {
    let cache = crate::files::cache_dir()?;
    Some(cache.join(format!(
        "lessons-{}-{:016x}",
        env!("CARGO_PKG_VERSION"),
        fingerprint()
    )))
}

/// The built-in files whose copy under `root` is not theirs byte for byte (edited, or gone),
/// among those whose path starts with `within`.
fn changed_in(root: &Path, within: &Path) -> Vec<(&'static Path, &'static [u8])> {
    files()
        .into_iter()
        .filter(|(path, _)| path.starts_with(within))
        .filter(|(path, bytes)| std::fs::read(root.join(path)).ok().as_deref() != Some(*bytes))
        .collect()
}

/// The files of the lesson in `dir` that differ from the built-in ones, where `dir` is a
/// lesson of the built-in copy in the cache (a student who edits that copy, which the explorer
/// reloads, changes what its answers are checked against); none for any other folder.
pub fn edited(dir: &Path) -> Vec<PathBuf> {
    let canonical = |p: &Path| std::fs::canonicalize(p).ok();
    let (Some(root), Some(dir)) = (cached_path().and_then(|r| canonical(&r)), canonical(dir))
    else {
        return vec![];
    };
    match dir.strip_prefix(&root) {
        Ok(lesson) if !lesson.as_os_str().is_empty() => changed_in(&root, lesson)
            .into_iter()
            .map(|(path, _)| root.join(path))
            .collect(),
        _ => vec![],
    }
}

/// The built-in lessons as a folder: the copy in the user's cache folder (`RAYTREE_CACHE`, else
/// the platform's), written on first use. A file of the copy that was edited (or removed) is
/// put back as it was built: a cache is not the place for a student's changes, and the
/// built-in lessons are what answers are checked against.
pub fn cached() -> Result<PathBuf, LessonError> {
    let cache = crate::files::cache_dir().ok_or(LessonError::NoCacheDir)?;
    let dir = cached_path().ok_or(LessonError::NoCacheDir)?;
    if dir.is_dir() {
        for (path, bytes) in changed_in(&dir, Path::new("")) {
            let target = dir.join(path);
            if let Some(parent) = target.parent() {
                std::fs::create_dir_all(parent)
                    .map_err(|e| LessonError::io(parent, "create the folder", e))?;
            }
            crate::render::write_atomically(&target, bytes)
                .map_err(|e| LessonError::io(&target, "restore", std::io::Error::other(e)))?;
        }
        return Ok(dir);
    }
    std::fs::create_dir_all(&cache).map_err(|e| LessonError::io(&cache, "create the folder", e))?;
    let staging = write_staging(&cache)?;
    match std::fs::rename(staging.path(), &dir) {
        Ok(()) => {
            let _ = staging.keep();
            Ok(dir)
        }
        // Another raytree wrote the same copy meanwhile: it will do (this one is removed).
        Err(_) if dir.is_dir() => Ok(dir),
        Err(e) => Err(LessonError::io(&dir, "move the lessons into place", e)),
    }
}
