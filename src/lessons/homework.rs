//! A student's homework folder: the lesson's scenes with that student's values written in, its
//! exercises (the questions quoting those values, no `vary:` left, and a `variant:` record of
//! whose homework it is), and a README with the questions and without the answers.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde_json::Value;

use super::error::LessonError;
use super::exercise::Lesson;
use super::exercise::Solutions;

/// Writes the homework of `student` for `lesson` into `out`, a folder that must not exist yet
/// (or be empty). The folder is written whole, under a temporary name renamed at the end.
/// Returns the homework, and the links in the lesson's folder that were left out (each named,
/// with why).
pub fn write(
    lesson: &Lesson,
    student: &str,
    out: &Path,
) -> Result<(Lesson, Vec<String>), LessonError> {
    let mut hw = lesson.variant(student)?;
    files_inside(lesson, &hw)?;
    // Each scene as the homework writes it, fingerprinted, so that grading can tell a folder
    // the student changed afterwards.
    let scenes = hw.scene_files()?;
    if let Some(v) = &mut hw.variant {
        v.scenes = scenes
            .iter()
            .map(|(name, text)| (name.clone(), super::exercise::fingerprint(text)))
            .collect();
    }
    if out.exists() && std::fs::read_dir(out).map_or(true, |mut d| d.next().is_some()) {
        return Err(LessonError::Exists(out.to_path_buf()));
    }
    let name = out
        .file_name()
        .ok_or_else(|| LessonError::NotAFolderName(out.to_path_buf()))?;
    let parent = out
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(parent).map_err(|e| LessonError::io(parent, "create the folder", e))?;
    let tmp = parent.join(format!(
        ".{}.{}.tmp",
        name.to_string_lossy(),
        std::process::id()
    ));
    let mut left_out = Vec::new();
    let written = fill(lesson, &hw, &tmp, out, &mut left_out).and_then(|()| {
        if out.exists() {
            std::fs::remove_dir(out).map_err(|e| LessonError::io(out, "replace the folder", e))?;
        }
        std::fs::rename(&tmp, out)
            .map_err(|e| LessonError::io(out, "move the homework into place", e))
    });
    if let Err(e) = written {
        let _ = std::fs::remove_dir_all(&tmp);
        return Err(e);
    }
    Ok((Lesson::load(out)?, left_out))
}

/// Everything of the homework folder, written into `dir` (to become `out`); the links left
/// out go to `left_out`.
fn fill(
    lesson: &Lesson,
    hw: &Lesson,
    dir: &Path,
    out: &Path,
    left_out: &mut Vec<String>,
) -> Result<(), LessonError> {
    std::fs::create_dir_all(dir).map_err(|e| LessonError::io(dir, "create the folder", e))?;
    // The lesson's other files (meshes, textures, extra scenes), in its subfolders too, as
    // they are. Its figures (SVG, drawn by `raytree diagram` from the lesson's own scene) are
    // left out: they show the lesson's values and answers, not the student's, and the homework
    // README cites none. So is the homework itself where it is written inside the lesson.
    let lesson_dir = std::fs::canonicalize(&lesson.dir)
        .map_err(|e| LessonError::io(&lesson.dir, "find the lesson's folder", e))?;
    let copy = Copy {
        lesson: &lesson_dir,
        skip: [dir, out].map(|p| std::fs::canonicalize(p).ok()),
        sources: &hw.sources,
    };
    copy.folder(&lesson.dir, dir, true, left_out)?;
    for (name, text) in &hw.sources {
        let to = dir.join(name);
        std::fs::write(&to, text).map_err(|e| LessonError::io(&to, "write", e))?;
    }
    let exercises = dir.join("exercises.yaml");
    let write_exercises = |e: std::io::Error| LessonError::io(&exercises, "write", e);
    let text = exercises_yaml(hw).map_err(|e| write_exercises(e.into()))?;
    std::fs::write(&exercises, text).map_err(write_exercises)?;
    let readme = dir.join("README.md");
    std::fs::write(&readme, readme_md(hw)).map_err(|e| LessonError::io(&readme, "write", e))?;
    Ok(())
}

/// How the lesson's files are copied: only what lies in its folder, `lesson` (canonical),
/// leaving out the folders the homework is being written to; a link to one of the student's
/// scenes (`sources`, by their names in the lesson) gets the student's text.
struct Copy<'a> {
    lesson: &'a Path,
    skip: [Option<PathBuf>; 2],
    sources: &'a BTreeMap<String, String>,
}

impl Copy<'_> {
    /// The files of folder `from` copied into `to`, its subfolders' too; at the top (`top`),
    /// all but the lesson's README, exercises and figures, which the homework writes anew or
    /// leaves out. Links are not followed: one to a file of the lesson is copied as that file
    /// (as the student's variant of it, for a scene); one to a folder (which may hold the link
    /// itself) or out of the lesson is left out, and named in `left_out`.
    fn folder(
        &self,
        from: &Path,
        to: &Path,
        top: bool,
        left_out: &mut Vec<String>,
    ) -> Result<(), LessonError> {
        let entries = std::fs::read_dir(from)
            .map_err(|e| LessonError::io(from, "list the lesson's files", e))?;
        for entry in entries.flatten() {
            let path: PathBuf = entry.path();
            let file = entry.file_name();
            let figure = path
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
            if top && (file == "README.md" || file == "exercises.yaml" || figure) {
                continue;
            }
            let Ok(kind) = entry.file_type() else {
                continue;
            };
            let into = to.join(&file);
            if kind.is_symlink() {
                match std::fs::canonicalize(&path) {
                    Ok(target) if target.starts_with(self.lesson) && target.is_file() => {
                        let varied = target
                            .strip_prefix(self.lesson)
                            .ok()
                            .and_then(|name| self.sources.get(name.to_str()?));
                        match varied {
                            Some(text) => std::fs::write(&into, text)
                                .map_err(|e| LessonError::io(&into, "write", e))?,
                            None => {
                                std::fs::copy(&target, &into)
                                    .map_err(|e| LessonError::io(&path, "copy", e))?;
                            }
                        }
                    }
                    Ok(target) if target.starts_with(self.lesson) => {
                        left_out.push(format!("{}: a link to a folder", path.display()))
                    }
                    _ => left_out.push(format!(
                        "{}: a link out of the lesson's folder",
                        path.display()
                    )),
                }
            } else if kind.is_dir() {
                let Ok(here) = std::fs::canonicalize(&path) else {
                    continue;
                };
                let skipped = self.skip.iter().flatten();
                if skipped.clone().any(|s| *s == here) {
                    continue;
                }
                std::fs::create_dir_all(&into)
                    .map_err(|e| LessonError::io(&into, "create the folder", e))?;
                self.folder(&path, &into, false, left_out)?;
                // A folder that only holds the homework being written (`-o hw/s1` inside
                // the lesson) is not part of it.
                if skipped.clone().any(|s| s.starts_with(&here)) {
                    let _ = std::fs::remove_dir(&into);
                }
            } else if kind.is_file() {
                std::fs::copy(&path, &into).map_err(|e| LessonError::io(&path, "copy", e))?;
            }
        }
        Ok(())
    }
}

/// Every file the homework's scenes read (meshes, images) lies in the lesson's folder, which
/// the homework copies: a scene reading `../textures/x.png` would not load from the homework
/// folder.
fn files_inside(lesson: &Lesson, hw: &Lesson) -> Result<(), LessonError> {
    let folder = std::fs::canonicalize(&lesson.dir)
        .map_err(|e| LessonError::io(&lesson.dir, "find the lesson's folder", e))?;
    for (name, text) in &hw.scene_files()? {
        let path = lesson.dir.join(name);
        let limits = crate::scene::Limits::default();
        // A scene that does not load is reported where it is used; here only what loads.
        let Ok(scene) =
            crate::scene::parse(text, &path.display().to_string(), Some(&path), &limits)
        else {
            continue;
        };
        for input in &scene.inputs {
            let inside = std::fs::canonicalize(input).is_ok_and(|p| p.starts_with(&folder));
            if !inside {
                let named = input.strip_prefix(&lesson.dir).unwrap_or(input);
                return Err(LessonError::Outside {
                    scene: path,
                    input: named.to_path_buf(),
                });
            }
        }
    }
    Ok(())
}

/// A value in YAML: JSON is YAML's flow style, and strings come out double-quoted.
fn yaml(v: &Value) -> String {
    v.to_string()
}

/// The homework's exercises.yaml: the lesson's, with the student's questions and the record of
/// whose variant it is.
fn exercises_yaml(hw: &Lesson) -> Result<String, serde_json::Error> {
    let mut out =
        String::from("# Written by `raytree homework`: one student's variant of a lesson.\n");
    out.push_str(&format!("title: {}\n", yaml(&hw.title.clone().into())));
    out.push_str(&format!("summary: {}\n", yaml(&hw.summary.clone().into())));
    if hw.solutions == Solutions::Hidden {
        out.push_str("solutions: hidden\n");
    }
    if let Some(v) = &hw.variant {
        let record = serde_json::to_value(v)?;
        out.push_str(&format!("variant: {}\n", yaml(&record)));
    }
    out.push_str("exercises:\n");
    for ex in &hw.exercises {
        let mut ex = ex.clone();
        ex.question = ex.question.trim().to_string();
        let Value::Object(fields) = serde_json::to_value(&ex)? else {
            continue;
        };
        out.push_str(&format!("  - id: {}\n", yaml(&fields["id"])));
        for (k, v) in &fields {
            let empty = v.is_null() || *v == Value::String(String::new());
            if k != "id" && !empty {
                out.push_str(&format!("    {k}: {}\n", yaml(v)));
            }
        }
    }
    Ok(out)
}

/// The homework's README: the questions, the student's own values, and how to answer.
fn readme_md(hw: &Lesson) -> String {
    let mut out = format!("# {} — homework\n\n", hw.title);
    if let Some(v) = &hw.variant {
        out.push_str(&format!(
            "Homework of **{}**, made from lesson `{}` with values of your own: your answers are \
             not your neighbour's. {}\n\n",
            v.student,
            v.lesson,
            hw.summary.trim()
        ));
        if !v.values.is_empty() {
            out.push_str("Your values (already written into the scene files here):\n\n");
            for (path, value) in &v.values {
                out.push_str(&format!("- `{path}` = {value}\n"));
            }
            out.push('\n');
        }
    } else {
        out.push_str(&format!("{}\n\n", hw.summary.trim()));
    }
    out.push_str("## Exercises\n\n");
    for (k, ex) in hw.exercises.iter().enumerate() {
        let question = ex.question.split_whitespace().collect::<Vec<_>>().join(" ");
        out.push_str(&format!("{}. **{}** — {question}\n", k + 1, ex.id));
    }
    out.push_str(
        "\n## Answering\n\nLook at the scene, work the answers out by hand, and check them:\n\n",
    );
    out.push_str(
        "    raytree explore .                                  # the scene and its ray trees\n",
    );
    out.push_str(
        "    raytree check . --exercise ID --answer VALUE       # right or wrong, with a hint\n\n",
    );
    out.push_str(
        "An answer is a number, a vector `x, y, z`, a segment list `t_in, t_out; t_in, t_out`, \
         `none` for an empty segment list, or `tir`.\n",
    );
    out
}
