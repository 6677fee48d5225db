//! The layers of `src/` (see `src/lib.rs` and `docs/architecture.md`): every top-level module
//! imports only from the modules below it, so the graph has no cycle, and only the renderer
//! uses the fast wing (the scene, the tracer, the lessons, the explorer and the CLI know
//! nothing of it). Read off the `crate::…` paths of every source file.

use std::collections::BTreeMap;
use std::path::Path;

/// Each top-level module and the modules it may import.
fn allowed() -> BTreeMap<&'static str, Vec<&'static str>> {
    let base = ["sampling", "stats", "files", "signals"];
    let mut layers: Vec<(&str, Vec<&str>)> = vec![
        ("sampling", vec![]),
        ("stats", vec![]),
        ("files", vec![]),
        ("signals", vec![]),
        ("accel", vec![]),
        ("geometry", vec!["accel"]),
        ("shading", vec!["geometry", "accel"]),
        ("scene", vec!["shading", "geometry", "accel"]),
        ("trace", vec!["scene", "shading", "geometry", "accel"]),
        (
            "fast",
            vec!["trace", "scene", "shading", "geometry", "accel"],
        ),
        (
            "render",
            vec!["fast", "trace", "scene", "shading", "geometry", "accel"],
        ),
        // Ray diagrams: the projection and outlines the explorer and the figures share.
        (
            "diagram",
            vec!["trace", "scene", "shading", "geometry", "accel"],
        ),
    ];
    // The applications, on top: everything but the fast wing, which the renderer alone runs.
    let below_apps = ["render", "trace", "scene", "shading", "geometry", "accel"];
    layers.push(("lessons", below_apps.to_vec()));
    layers.push(("bench", below_apps.to_vec()));
    layers.push(("tui", [&below_apps[..], &["lessons", "diagram"]].concat()));
    layers.push((
        "cli",
        [&below_apps[..], &["lessons", "bench", "tui", "diagram"]].concat(),
    ));
    layers
        .into_iter()
        .map(|(m, mut deps)| {
            if !base.contains(&m) {
                deps.extend(base);
            }
            (m, deps)
        })
        .collect()
}

/// The top-level module a source file belongs to: `src/scene/search.rs` → `scene`.
fn module_of(path: &Path) -> String {
    let rel = path.strip_prefix("src").unwrap();
    let first = rel
        .components()
        .next()
        .unwrap()
        .as_os_str()
        .to_string_lossy();
    first.trim_end_matches(".rs").to_string()
}

/// The top-level modules a file's code names as `crate::module` (comments left out).
fn imports(text: &str) -> Vec<String> {
    let mut out = vec![];
    for line in text.lines() {
        let code = line.split("//").next().unwrap_or("");
        let mut rest = code;
        while let Some(i) = rest.find("crate::") {
            rest = &rest[i + "crate::".len()..];
            let name: String = rest
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if !name.is_empty() && !out.contains(&name) {
                out.push(name);
            }
        }
    }
    out
}

/// The imports of `module` that its layer forbids.
fn violations(module: &str, text: &str) -> Vec<String> {
    let allowed = allowed();
    let ok = allowed
        .get(module)
        .unwrap_or_else(|| panic!("module `{module}` has no place in the layers: add it"));
    imports(text)
        .into_iter()
        .filter(|m| m != module && !ok.contains(&m.as_str()))
        .collect()
}

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn every_file_imports_only_from_the_layers_below_its_own() {
    let mut files = vec![];
    rust_files(Path::new("src"), &mut files);
    assert!(files.len() > 50, "only {} source files found", files.len());
    let mut wrong = vec![];
    for path in files {
        let module = module_of(&path);
        if module == "main" || module == "lib" {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        for m in violations(&module, &text) {
            wrong.push(format!("{}: {module} imports crate::{m}", path.display()));
        }
    }
    assert!(
        wrong.is_empty(),
        "imports against the layers:\n{}",
        wrong.join("\n")
    );
}

/// The table itself is a DAG: following "may import" from any module never comes back to it.
#[test]
fn the_layers_have_no_cycle() {
    let allowed = allowed();
    fn reaches(
        allowed: &BTreeMap<&str, Vec<&str>>,
        from: &str,
        target: &str,
        seen: &mut Vec<String>,
    ) -> bool {
        for &dep in &allowed[from] {
            if dep == target {
                return true;
            }
            if !seen.iter().any(|s| s == dep) {
                seen.push(dep.to_string());
                if reaches(allowed, dep, target, seen) {
                    return true;
                }
            }
        }
        false
    }
    for &m in allowed.keys() {
        assert!(
            !reaches(&allowed, m, m, &mut vec![]),
            "{m} can reach itself"
        );
    }
}

/// The check has teeth: an import against the layers, or of the fast wing from the core, is
/// reported; a comment naming a module is not.
#[test]
fn a_forbidden_import_is_reported() {
    assert_eq!(
        violations("scene", "use crate::render::Camera;"),
        vec!["render"]
    );
    assert_eq!(
        violations("trace", "    let s = crate::fast::FastScene::new(scene);"),
        vec!["fast"]
    );
    assert_eq!(
        violations("tui", "use crate::fast::trace_packet;"),
        vec!["fast"]
    );
    assert!(violations("geometry", "// see crate::render::film").is_empty());
    assert!(violations("render", "use crate::fast::FastScene;").is_empty());
}

/// The textbook core reads as the lecture writes it: compiler hints for speed belong to the fast
/// wing (`src/fast/`), which calls its own copies of the per-ray steps it needs inlined.
#[test]
fn the_textbook_core_carries_no_speed_hints() {
    let mut files = vec![];
    rust_files(Path::new("src/trace"), &mut files);
    assert!(files.iter().any(|p| p.ends_with("whitted.rs")));
    let hinted: Vec<String> = files
        .iter()
        .filter(|p| {
            let text = std::fs::read_to_string(p).unwrap();
            text.contains("#[inline(always)]") || text.contains("target_feature")
        })
        .map(|p| p.display().to_string())
        .collect();
    assert!(hinted.is_empty(), "speed hints in the core: {hinted:?}");
}
