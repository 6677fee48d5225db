//! Reading a scene file: YAML text parsed (large files on all threads, see `split`), then
//! compiled; every error names the file, line and column.

use std::path::Path;

use rayon::prelude::*;
use serde_saphyr::{Location, Spanned};

use super::error::{self, SceneError};
use super::{compile, format, simple_items, split, Limits, Scene};
use crate::files::ReadError;

/// Parser options: strict about what the scene format is not (tags, non-finite numbers),
/// with budgets against alias bombs and absurd nesting.
///
/// The node and event budgets are sized from the whole file's length, and given alike to the
/// file and to each of its pieces (see `split`): a piece holds fewer nodes than the file, so
/// the pieces breach these budgets exactly when the file does (which needs more nodes than
/// bytes, i.e. aliases, which the parallel loader never cuts). The file's own size is
/// budgeted before it is read (`Limits::max_file_bytes`).
fn parse_options(file_len: usize) -> serde_saphyr::Options {
    let mut options = serde_saphyr::Options::default();
    options.with_snippet = false;
    options.non_finite_float_policy = serde_saphyr::NonFiniteFloatPolicy::Reject;
    // `!sphere { … }` is not a shape: tags are refused rather than silently dropped.
    options.reject_unsupported_tags = true;
    options.reject_tagged_field_names = true;
    // Scenes with 100 000 objects are legitimate (the BVH scaling sweep), beyond the parser's
    // default of 250 000 nodes.
    let mut budget = serde_saphyr::Budget::default();
    budget.max_nodes = (2 * file_len + 1024).max(20_000_000);
    budget.max_events = (4 * file_len + 1024).max(50_000_000);
    budget.max_total_scalar_bytes = budget.max_total_scalar_bytes.max(file_len + 1024);
    options.budget = Some(budget);
    options
}

/// Why a scene file could not be read (anything but its text's encoding, which has a place).
fn unread(path: &Path, e: ReadError) -> String {
    match e {
        ReadError::Directory => "is a directory, not a scene file".into(),
        ReadError::NotRegular => {
            "not a regular file (a pipe, a socket or a device): give a scene file".into()
        }
        ReadError::TooLarge { budget } => format!(
            "the file is larger than the budget of {} for scene files (use --allow-huge to load it)",
            crate::files::bytes(budget)
        ),
        ReadError::Io(e) if e.kind() == std::io::ErrorKind::NotFound => match path.extension() {
            Some(_) => "no such file".into(),
            None => "no such file, nor a lesson of that name (`raytree lessons` lists them)".into(),
        },
        e => e.to_string(),
    }
}

/// Reads and compiles a scene file.
pub fn load(path: &Path, limits: &Limits) -> Result<Scene, SceneError> {
    let file = path.display().to_string();
    let text = crate::files::read_text(path, limits.max_file_bytes).map_err(|e| {
        let (at, message) = match e {
            ReadError::NotUtf8 { line, column } => {
                (error::Pos { line, column }, "not valid UTF-8 text".into())
            }
            e => (error::Pos::default(), unread(path, e)),
        };
        SceneError::new(&file, at, message)
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
        return Err(SceneError::new(
            file,
            error::Pos::default(),
            "empty scene file",
        ));
    }
    let with_line = |e: SceneError| e.quoting(text);
    if let Some(line) = second_document(text) {
        return Err(with_line(SceneError::new(
            file,
            error::Pos { line, column: 1 },
            MORE_THAN_ONE_DOCUMENT,
        )));
    }
    let parsed = parse_yaml(text, file).map_err(with_line)?;
    compile::compile(parsed, path.map(Path::to_path_buf), limits)
        .map_err(|e| empty_camera(text, e))
        .map_err(|e| SceneError::new(file, e.pos, e.message))
        .map_err(with_line)
}

const MORE_THAN_ONE_DOCUMENT: &str =
    "more than one YAML document (a second `---` line): a scene file holds one";

/// The line of a second document's `---`: a marker after another, or after content. (A `---`
/// at the start of a line is always a document marker: YAML forbids it inside scalars.)
fn second_document(text: &str) -> Option<u64> {
    let mut started = false;
    for (i, line) in text.lines().enumerate() {
        let marker = line
            .strip_prefix("---")
            .is_some_and(|rest| rest.is_empty() || rest.starts_with([' ', '\t', '\r']));
        if marker && started {
            return Some(i as u64 + 1);
        }
        let content = !line.trim().is_empty() && !line.starts_with(['#', '%']);
        started |= marker || content;
    }
    None
}

/// Parses the YAML of a scene file: large files on all threads (see `split`).
fn parse_yaml(text: &str, file: &str) -> Result<format::SceneFile, SceneError> {
    parse_in_pieces(text, file, rayon::current_num_threads())
}

/// Parses a file cut into at most `pieces` pieces (one when it cannot or need not be cut).
/// The answer is always the one-piece parse's: where a piece does not parse, the file is
/// parsed again whole, so its error is the one a single thread reports.
pub(super) fn parse_in_pieces(
    text: &str,
    file: &str,
    pieces: usize,
) -> Result<format::SceneFile, SceneError> {
    if let Some(parsed) = parse_simple(text, file) {
        return parsed;
    }
    match split::split(text, pieces) {
        Some(split) => parse_split(split, text.len(), file).or_else(|_| from_yaml(text, file)),
        None => from_yaml(text, file),
    }
}

/// A large file whose objects after the first are simple items (`simple_items`): the items
/// read directly while the parser reads the rest of the file, the other items blanked. None
/// where some item is not simple; the one-piece parse's error where the rest does not parse.
fn parse_simple(text: &str, file: &str) -> Option<Result<format::SceneFile, SceneError>> {
    if text.len() < split::MIN_SPLIT_BYTES {
        return None;
    }
    let list = split::object_list(text)?;
    let &second = list.items.get(1)?;
    // The file without the items after the first (the lines after the list kept where they
    // are, if there are any).
    let after = &text[list.end..];
    let head = if after.lines().all(|l| split::content(l).trim().is_empty()) {
        text[..second].to_string()
    } else {
        format!(
            "{}{}{after}",
            &text[..second],
            split::blank(&text[second..list.end])?
        )
    };
    // The objects' list is filled where it stays, the first item's slot kept for the head's.
    let mut objects = Vec::with_capacity(list.items.len());
    let (head, simple) = rayon::join(
        || from_yaml_sized::<format::SceneFile>(&head, text.len(), file),
        || {
            let slot = Spanned::new(Default::default(), Location::UNKNOWN, Location::UNKNOWN);
            objects.push(slot);
            simple_items::read(text, &list, 1, &mut objects)
        },
    );
    if !simple {
        return None;
    }
    Some(match head {
        Ok(mut scene) => {
            objects[0] = scene.objects.pop().expect("the head holds the first item");
            scene.objects = objects;
            Ok(scene)
        }
        Err(_) => from_yaml(text, file),
    })
}

/// Parses a file's pieces in parallel and joins their objects in order.
pub(super) fn parse_split(
    split: split::Split,
    file_len: usize,
    file: &str,
) -> Result<format::SceneFile, SceneError> {
    type Objects = Vec<Spanned<format::ObjectSpec>>;
    let (head, pieces): (_, Vec<_>) = rayon::join(
        || from_yaml_sized::<format::SceneFile>(&split.head, file_len, file),
        || {
            split
                .pieces
                .par_iter()
                .map(|p| from_yaml_sized::<Objects>(p, file_len, file))
                .collect()
        },
    );
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
    from_yaml_sized(text, text.len(), file)
}

/// `from_yaml` for a piece of a file of `file_len` bytes.
fn from_yaml_sized<T: serde::de::DeserializeOwned>(
    text: &str,
    file_len: usize,
    file: &str,
) -> Result<T, SceneError> {
    serde_saphyr::from_str_with_options(text, parse_options(file_len)).map_err(|e| {
        let mut pos = e.location().map_or(error::Pos::default(), |l| error::Pos::of(&l));
        let mut message = invalid_scalar(&e, text, pos).unwrap_or_else(|| parser_message(&e));
        let line = text.lines().nth(pos.line.saturating_sub(1) as usize);
        if message.starts_with("expected a mapping") && line.is_some_and(|l| l.contains("complement:")) {
            message += " (`complement` takes one child, not a list)";
        }
        // The parser points at the node after a tag: point at the tag itself.
        if let Some(tag) = tag_of(&e) {
            if let Some(line) = text.lines().nth(pos.line.saturating_sub(1) as usize) {
                let before: String = line.chars().take(pos.column as usize - 1).collect();
                if let Some(at) = before.rfind(tag) {
                    pos.column = before[..at].chars().count() as u64 + 1;
                }
            }
        }
        // A collection left open is found by the parser only where the next line cannot
        // belong to it: point at the bracket that was never closed.
        if is_syntax_error(&e) {
            if let Some(b) = super::flow::unclosed_before(text, pos.line) {
                let (what, close) = match b.open {
                    '[' => ("list", ']'),
                    _ => ("mapping", '}'),
                };
                message = format!(
                    "the {what} opened here (`{}`) is never closed with `{close}`: it runs into line {}",
                    b.open, pos.line
                );
                pos = error::Pos {
                    line: b.line,
                    column: b.column,
                };
            }
        }
        SceneError::new(file, pos, message)
    })
}

/// Why a tag is refused.
fn tag_refused(tag: &str) -> String {
    format!(
        "YAML tags such as `{tag}` are not part of the scene format: remove it (a shape is given by its key, e.g. `sphere: {{ … }}`)"
    )
}

/// A value of the wrong kind (`width: 20.5`, `spp: four`, `max_depth: 99999999999999999999`),
/// said with the key and the value as written: the parser knows only the type it wanted.
fn invalid_scalar(e: &serde_saphyr::Error, text: &str, pos: error::Pos) -> Option<String> {
    use serde_saphyr::Error as E;
    let ty = match e {
        E::WithSnippet { error, .. } => return invalid_scalar(error, text, pos),
        E::InvalidScalar { ty, .. } => *ty,
        _ => return None,
    };
    let line = text.lines().nth(pos.line.checked_sub(1)? as usize)?;
    let at = line
        .char_indices()
        .nth(pos.column.checked_sub(1)? as usize)
        .map_or(line.len(), |(i, _)| i);
    let (before, after) = line.split_at(at);
    // A tag before the value (`radius: !!int 1`, or verbatim, `!<tag:yaml.org,2002:int> 1`,
    // whose commas do not end it), which the parser took as asking for its kind of value.
    let before_value = before.trim_end();
    let tag = match before_value.strip_suffix('>') {
        Some(_) => before_value.rfind("!<").map(|i| &before_value[i..]),
        None => before_value.rsplit([' ', '{', ',', '[']).next(),
    };
    if let Some(tag) = tag.filter(|t| t.starts_with('!')) {
        return Some(tag_refused(tag));
    }
    let value = after
        .split([',', '}', ']', '#'])
        .next()
        .unwrap_or("")
        .trim()
        .trim_matches(['"', '\''])
        .to_string();
    // The key the value belongs to, when it follows the key directly.
    let key = before
        .trim_end()
        .strip_suffix(':')
        .map(|k| {
            k.trim_end()
                .rsplit([' ', '{', ',', '-'])
                .next()
                .unwrap_or("")
        })
        .filter(|k| !k.is_empty());
    let whole = ty.starts_with('i') || ty.starts_with('u');
    let digits = value.trim_start_matches(['-', '+']);
    let wanted = if whole && !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) {
        "a whole number of a usable size"
    } else if whole {
        "a whole number"
    } else if ty == "bool" {
        "true or false"
    } else if value.parse::<f64>().is_ok() {
        "a number within floating point's range"
    } else {
        "a number"
    };
    Some(match key {
        Some(k) => format!("`{k}` must be {wanted}, got `{value}`"),
        None => format!("expected {wanted} here, got `{value}`"),
    })
}

/// The tag an error is about, if it is about one.
fn tag_of(e: &serde_saphyr::Error) -> Option<&str> {
    use serde_saphyr::Error as E;
    match e {
        E::WithSnippet { error, .. } | E::AliasError { error, .. } => tag_of(error),
        E::UnsupportedTag { tag, .. } | E::TaggedStructFieldName { tag, .. } => Some(tag),
        _ => None,
    }
}

/// Whether the parser stopped at the text itself (not at a value that does not fit).
fn is_syntax_error(e: &serde_saphyr::Error) -> bool {
    use serde_saphyr::{Error as E, ExternalMessageSource};
    match e {
        E::WithSnippet { error, .. } | E::AliasError { error, .. } => is_syntax_error(error),
        E::ExternalMessage { source, .. } => matches!(**source, ExternalMessageSource::Parser(_)),
        E::Eof { .. } => true,
        _ => false,
    }
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

/// The parser's error said for a scene's author, on one line and without the position (the
/// caller reports it), from the error's kind where the parser's own words are written for
/// programmers using it.
fn parser_message(e: &serde_saphyr::Error) -> String {
    use serde_saphyr::budget::BudgetBreach;
    use serde_saphyr::{Error as E, MessageFormatter};
    const ALIAS_BOMB: &str = "YAML aliases expand too far (an alias bomb?): refused";
    const MORE_THAN_ONE: &str = MORE_THAN_ONE_DOCUMENT;
    const TOO_DEEP: &str = "nested more than 64 YAML levels deep (a CSG tree or a pattern of about 30 levels, each a mapping and its list, or lists in lists): make it shallower";
    const SELF_ALIAS: &str =
        "an alias (*name) refers to the node it is inside of: a scene cannot contain itself";
    match e {
        E::WithSnippet { error, .. } | E::AliasError { error, .. } => parser_message(error),
        E::DuplicateMappingKey { key: Some(key), .. } => {
            format!("duplicate key `{key}`: each key may appear once in a mapping")
        }
        E::DuplicateMappingKey { key: None, .. } => {
            "duplicate key: each key may appear once in a mapping".into()
        }
        E::MultipleDocuments { .. } => MORE_THAN_ONE.into(),
        E::RecursiveReferencesRequireWeakTypes { .. } => SELF_ALIAS.into(),
        E::Budget { breach, .. } => match breach {
            BudgetBreach::Depth { .. } => TOO_DEEP.into(),
            BudgetBreach::Aliases { .. } | BudgetBreach::Anchors { .. } => ALIAS_BOMB.into(),
            BudgetBreach::Documents { .. } => MORE_THAN_ONE.into(),
            _ => "the file is too large for the parser's limits (nodes, events or bytes)".into(),
        },
        E::AliasReplayCounterOverflow { .. }
        | E::AliasReplayLimitExceeded { .. }
        | E::AliasExpansionLimitExceeded { .. }
        | E::AliasReplayStackDepthExceeded { .. } => ALIAS_BOMB.into(),
        E::UnsupportedTag { tag, .. } | E::TaggedStructFieldName { tag, .. } => tag_refused(tag),
        E::NonFiniteFloat { value, .. } => {
            format!("non-finite number `{value}`: every number in a scene must be finite")
        }
        E::Unexpected {
            expected: "string scalar",
            ..
        } => "expected a single value here (a number or a name), not a list or a mapping".into(),
        E::Unexpected {
            expected: "sequence start",
            ..
        } => "expected a list here: `- item` lines, or `[a, b]` (`[]` for none)".into(),
        E::Unexpected {
            expected: "mapping start",
            ..
        } => "expected a mapping here: `key: value` lines, or `{ key: value }`".into(),
        e => {
            let text = serde_saphyr::DefaultMessageFormatter.format_message(e);
            let first = text.lines().next().unwrap_or("").trim();
            let first = first.strip_prefix("error: ").unwrap_or(first);
            // The same refusal, raised as a plain message where the parser resolves an alias.
            if first.contains("recursive references require weak recursion types") {
                return SELF_ALIAS.into();
            }
            // The parser's own limit on lists in lists, met before the depth budget.
            if first.contains("recursion limit exceeded") {
                return TOO_DEEP.into();
            }
            first.to_string()
        }
    }
}
