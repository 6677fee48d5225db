//! The docs point students at the code: `docs/architecture.md` maps each concept of the notes
//! to a file and its functions, and every lesson's README has an "In the code" section. Every
//! function or type named there beside a `src/…` file must exist in that file, so the pointers
//! stay true when the code moves.

use std::path::Path;

/// A name to find in a source file: `Type::function`, `function` or `Type`.
#[derive(Debug)]
struct Link {
    doc: String,
    line: usize,
    file: String,
    name: String,
}

fn is_name(span: &str) -> bool {
    let ident = |s: &str| {
        !s.is_empty()
            && s.chars()
                .next()
                .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
            && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
    };
    match span.split_once("::") {
        Some((ty, f)) => ident(ty) && ident(f),
        None => ident(span),
    }
}

/// The links of one Markdown text: on each line, every code span naming a `src/….rs` file
/// sets the file for the names in the code spans after it.
fn links(doc: &str, text: &str) -> Vec<Link> {
    let mut out = vec![];
    for (i, line) in text.lines().enumerate() {
        let mut file: Option<String> = None;
        for (k, span) in line.split('`').enumerate() {
            if k % 2 == 0 {
                continue;
            }
            if span.starts_with("src/") && span.ends_with(".rs") {
                file = Some(span.to_string());
            } else if let (Some(f), true) = (&file, is_name(span)) {
                out.push(Link {
                    doc: doc.to_string(),
                    line: i + 1,
                    file: f.clone(),
                    name: span.to_string(),
                });
            }
        }
    }
    out
}

/// Whether `source` defines `item` as a function, a type, a trait or a constant.
fn defines(source: &str, item: &str) -> bool {
    let words: Vec<&str> = source
        .split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .filter(|w| !w.is_empty())
        .collect();
    words.windows(2).any(|w| {
        matches!(w[0], "fn" | "struct" | "enum" | "trait" | "type" | "const") && w[1] == item
    })
}

/// Whether the link's name is in its file: the function, and for `Type::function` the type
/// too (defined there or implemented there).
fn found(link: &Link) -> Result<(), String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(&link.file);
    let source = std::fs::read_to_string(&path).map_err(|_| "no such file".to_string())?;
    let (ty, item) = match link.name.split_once("::") {
        Some((ty, f)) => (Some(ty), f),
        None => (None, link.name.as_str()),
    };
    if !defines(&source, item) {
        return Err(format!("no `{item}` defined there"));
    }
    if let Some(ty) = ty {
        let implemented = source.lines().any(|l| {
            let l = l.trim_start();
            l.starts_with("impl") && l.split(|c: char| !c.is_alphanumeric()).any(|w| w == ty)
        });
        if !implemented && !defines(&source, ty) {
            return Err(format!("no `impl {ty}` there"));
        }
    }
    Ok(())
}

fn lesson_readmes() -> Vec<std::path::PathBuf> {
    let mut out: Vec<_> = std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.is_dir()
                && p.file_name().is_some_and(|n| {
                    n.to_string_lossy()
                        .starts_with(|c: char| c.is_ascii_digit())
                })
        })
        .map(|p| p.join("README.md"))
        .collect();
    out.sort();
    out
}

#[test]
fn every_function_the_docs_name_exists_where_they_say() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut all = vec![];
    let architecture = std::fs::read_to_string(root.join("docs/architecture.md")).unwrap();
    let map = links("docs/architecture.md", &architecture);
    assert!(
        map.len() >= 50,
        "the concept map names only {} functions",
        map.len()
    );
    all.extend(map);
    for readme in lesson_readmes() {
        let text = std::fs::read_to_string(&readme).unwrap();
        let doc = readme.strip_prefix(root).unwrap().display().to_string();
        let section = text
            .split("\n## In the code")
            .nth(1)
            .unwrap_or_else(|| panic!("{doc} has no \"## In the code\" section"));
        let section = section.split("\n## ").next().unwrap();
        let found = links(&doc, section);
        assert!(
            !found.is_empty(),
            "{doc}: \"In the code\" names no function"
        );
        all.extend(found);
    }
    let wrong: Vec<String> = all
        .iter()
        .filter_map(|l| {
            found(l)
                .err()
                .map(|why| format!("{}:{}: `{}` in `{}`: {why}", l.doc, l.line, l.name, l.file))
        })
        .collect();
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// The check has teeth: a renamed function or a wrong file is reported.
#[test]
fn a_name_that_is_not_there_is_reported() {
    let l = links(
        "test",
        "| x | `src/trace/whitted.rs` | `Tracer::shade`, `Tracer::no_such_step` |",
    );
    assert_eq!(l.len(), 2);
    assert!(found(&l[0]).is_ok());
    assert!(found(&l[1]).is_err());
    let moved = links("test", "`src/geometry/sphere.rs`: `Plane::span`");
    assert!(found(&moved[0]).is_err(), "Plane is not in sphere.rs");
}
