//! Reading a scene file: YAML text parsed (large files on all threads, see `split`), then
//! compiled; every error names the file, line and column.

use std::path::Path;

use rayon::prelude::*;
use serde_saphyr::Spanned;

use super::error::{self, SceneError};
use super::{compile, format, split, Limits, Scene};

/// Parser limits against alias bombs and absurd nesting.
fn parse_options() -> serde_saphyr::Options {
    let mut options = serde_saphyr::Options::default();
    options.with_snippet = false;
    options.non_finite_float_policy = serde_saphyr::NonFiniteFloatPolicy::Reject;
    // Scenes with 100 000 objects are legitimate (the BVH scaling sweep); the default budget
    // stops at 250 000 YAML nodes. Alias bombs and nesting stay bounded by the other limits
    // (50 000 aliases, depth 64, 256 MiB of input).
    let mut budget = serde_saphyr::Budget::default();
    budget.max_nodes = 20_000_000;
    budget.max_events = 50_000_000;
    options.budget = Some(budget);
    options
}

/// Reads and compiles a scene file.
pub fn load(path: &Path, limits: &Limits) -> Result<Scene, SceneError> {
    let file = path.display().to_string();
    let fail = |message: String| SceneError {
        file: file.clone(),
        line: 1,
        column: 1,
        message,
    };
    if path.is_dir() {
        return Err(fail("is a directory, not a scene file".into()));
    }
    let bytes = std::fs::read(path).map_err(|e| fail(format!("cannot read: {e}")))?;
    let text = String::from_utf8(bytes).map_err(|e| {
        let before = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        let line = before.iter().filter(|&&b| b == b'\n').count() as u64 + 1;
        let column = before.iter().rev().take_while(|&&b| b != b'\n').count() as u64 + 1;
        SceneError {
            file: file.clone(),
            line,
            column,
            message: "not valid UTF-8 text".into(),
        }
    })?;
    parse(&text, &file, Some(path), limits)
}

/// Parses and compiles scene text; `file` names it in errors.
pub fn parse(
    text: &str,
    file: &str,
    path: Option<&Path>,
    limits: &Limits,
) -> Result<Scene, SceneError> {
    if text.trim().is_empty() {
        return Err(SceneError {
            file: file.into(),
            line: 1,
            column: 1,
            message: "empty scene file".into(),
        });
    }
    let parsed = parse_yaml(text, file)?;
    compile::compile(parsed, path.map(Path::to_path_buf), limits)
        .map_err(|e| empty_camera(text, e))
        .map_err(|e| SceneError {
            file: file.into(),
            line: e.pos.line,
            column: e.pos.column,
            message: e.message,
        })
}

/// Parses the YAML of a scene file: large files on all threads (see `split`).
fn parse_yaml(text: &str, file: &str) -> Result<format::SceneFile, SceneError> {
    match split::split(text, rayon::current_num_threads()) {
        Some(split) => parse_split(split, file),
        None => from_yaml(text, file),
    }
}

/// Parses a file's pieces in parallel and joins their objects in order.
pub(super) fn parse_split(
    split: split::Split,
    file: &str,
) -> Result<format::SceneFile, SceneError> {
    type Objects = Vec<Spanned<format::ObjectSpec>>;
    let (head, pieces): (_, Vec<_>) = rayon::join(
        || from_yaml::<format::SceneFile>(&split.head, file),
        || {
            split
                .pieces
                .par_iter()
                .map(|p| from_yaml::<Objects>(p, file))
                .collect()
        },
    );
    // Reading the file in one go would stop at its first error.
    let errors = head.as_ref().err().into_iter();
    let errors = errors.chain(pieces.iter().filter_map(|p| p.as_ref().err()));
    if let Some(first) = errors.min_by_key(|e| (e.line, e.column)) {
        return Err(first.clone());
    }
    let mut scene = head?;
    for piece in pieces {
        scene.objects.extend(piece?);
    }
    Ok(scene)
}

/// Deserialises YAML text, with the parser's errors said for a scene's author.
pub(super) fn from_yaml<T: serde::de::DeserializeOwned>(
    text: &str,
    file: &str,
) -> Result<T, SceneError> {
    serde_saphyr::from_str_with_options(text, parse_options()).map_err(|e| {
        let (line, column) = e
            .location()
            .map_or((1, 1), |l| (l.line().max(1), l.column().max(1)));
        SceneError {
            file: file.into(),
            line,
            column,
            message: parser_message(&e.to_string()),
        }
    })
}

/// `camera:` with nothing after it parses as no camera at all; point at the empty key.
fn empty_camera(text: &str, e: error::Invalid) -> error::Invalid {
    if !e.message.starts_with("missing `camera`") {
        return e;
    }
    for (i, line) in text.lines().enumerate() {
        if let Some(rest) = line.strip_prefix("camera:") {
            let column = line.len() - rest.trim_start().len() + 1;
            return error::Invalid {
                pos: error::Pos {
                    line: i as u64 + 1,
                    column: column as u64,
                },
                message: "`camera` is empty: give eye and look_at, or the window model".into(),
            };
        }
    }
    e
}

/// The parser's message on one line, without the position it repeats.
fn parser_message(raw: &str) -> String {
    let first = raw.lines().next().unwrap_or(raw).trim();
    let stripped = first.strip_prefix("error: ").unwrap_or(first);
    // "line 3 column 7: unknown field" → "unknown field"
    let stripped = match stripped.strip_prefix("line ") {
        Some(rest) => rest.split_once(": ").map_or(stripped, |(_, msg)| msg),
        None => stripped,
    };
    // A trailing "at line 2, column 1": the position is reported separately.
    let stripped = match stripped.rfind(" at line ") {
        Some(i) if stripped[i..].contains(", column ") && !stripped[i..].contains('(') => {
            &stripped[..i]
        }
        _ => stripped,
    };
    // Messages written for programmers using the parser, said for the scene's author.
    if let Some(key) = stripped.strip_prefix("duplicate mapping key: ") {
        let key = key.split(',').next().unwrap_or(key).trim();
        return format!("duplicate key `{key}`: each key may appear once in a mapping");
    }
    if stripped.starts_with("multiple YAML documents") {
        return "multiple YAML documents (a `---` line): a scene file holds one".into();
    }
    if stripped.starts_with("budget breached") {
        return if stripped.contains("Depth") {
            "nested more than 64 levels deep (CSG trees and lists must be shallower)".into()
        } else if stripped.contains("Anchor") || stripped.contains("Alias") {
            "YAML aliases expand too far (an alias bomb?): refused".into()
        } else {
            "the file is too large for the parser's limits (nodes, events or bytes)".into()
        };
    }
    if stripped == "expected string scalar" {
        return "expected a single value here (a number or a name), not a list or a mapping".into();
    }

    stripped.to_string()
}
