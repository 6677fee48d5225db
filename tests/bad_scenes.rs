//! The bad-input corpus: every file in `tests/bad_scenes/` is a scene raytree must refuse
//! the way the design promises: exit status 2, one line on stderr naming the file, line and
//! column, a message that says what is wrong, and never a panic or a hang.
//!
//! Each case states what it expects on its first line, `# expect: LINE:COL: fragment`, or, for
//! files that cannot carry a YAML comment (empty, binary, invalid UTF-8), in a sidecar
//! `NN-name.expect` holding `LINE:COL: fragment`. The fragment may list alternatives separated
//! by ` | `; it is matched case-insensitively. A line `# not: TEXT` anywhere in the file names
//! something the message must not say (a misleading claim).

mod common;

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// A case that runs longer than this has hung.
const TIMEOUT: Duration = Duration::from_secs(10);
/// Peak resident memory a refusal may use: the parser's budgets must stop a bomb early.
const MEMORY_LIMIT_KB: u64 = 1 << 20;
const CORPUS: &str = "tests/bad_scenes";

struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
    elapsed: Duration,
    /// Largest VmHWM seen while polling (Linux only; 0 when never seen).
    peak_kb: u64,
}

/// Runs `raytree ARGS` from the crate root, killing it after `TIMEOUT`.
fn raytree<S: AsRef<OsStr>>(args: &[S]) -> Result<Run, String> {
    let start = Instant::now();
    // `RAYTREE_BIN=path` runs the corpus against another build (how new cases were seen to
    // fail before their fixes).
    let bin = std::env::var_os("RAYTREE_BIN")
        .unwrap_or_else(|| std::ffi::OsString::from(env!("CARGO_BIN_EXE_raytree")));
    let mut child = Command::new(bin)
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("NO_COLOR", "1")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot start raytree: {e}"))?;
    let (out, err) = common::drain_output(&mut child);
    let status_file = format!("/proc/{}/status", child.id());
    let mut peak_kb = 0;
    let status = loop {
        if let Some((resident, peak)) = memory_kb(&status_file) {
            peak_kb = peak_kb.max(peak);
            // A blow-up is stopped here rather than left to the machine's OOM killer.
            if resident > MEMORY_LIMIT_KB {
                let _ = child.kill();
                let _ = child.wait();
                return Err(format!("memory blow-up: killed at {resident} KiB resident"));
            }
        }
        match child.try_wait() {
            Ok(Some(status)) => break status,
            Ok(None) if start.elapsed() > TIMEOUT => {
                let _ = child.kill();
                let _ = child.wait();
                return Err(format!("hung: killed after {TIMEOUT:?}"));
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(5)),
            Err(e) => return Err(format!("cannot wait for raytree: {e}")),
        }
    };
    Ok(Run {
        code: status.code(),
        stdout: out.join().unwrap_or_default(),
        stderr: err.join().unwrap_or_default(),
        elapsed: start.elapsed(),
        peak_kb,
    })
}

/// (VmRSS, VmHWM) of a running process, in KiB (Linux only).
fn memory_kb(status_file: &str) -> Option<(u64, u64)> {
    let status = std::fs::read_to_string(status_file).ok()?;
    let field = |name: &str| -> Option<u64> {
        let line = status.lines().find(|l| l.starts_with(name))?;
        line.split_whitespace().nth(1)?.parse().ok()
    };
    Some((field("VmRSS:")?, field("VmHWM:")?))
}

/// What a case expects: where raytree points, and what the message says (and must not say).
#[derive(Debug)]
struct Expect {
    line: u64,
    column: u64,
    /// Any one of these, case-insensitively.
    fragments: Vec<String>,
    /// None of these, case-insensitively.
    nots: Vec<String>,
}

fn parse_expect(spec: &str) -> Result<Expect, String> {
    let bad = || format!("malformed expectation `{spec}`: want `LINE:COL: fragment`");
    let (line, rest) = spec.trim().split_once(':').ok_or_else(bad)?;
    let (column, fragment) = rest.split_once(": ").ok_or_else(bad)?;
    Ok(Expect {
        line: line.parse().map_err(|_| bad())?,
        column: column.parse().map_err(|_| bad())?,
        fragments: fragment
            .split(" | ")
            .map(|f| f.trim().to_string())
            .collect(),
        nots: vec![],
    })
}

fn expectation(file: &Path) -> Result<Expect, String> {
    let bytes = std::fs::read(file).map_err(|e| format!("cannot read the case: {e}"))?;
    let text = String::from_utf8_lossy(&bytes);
    let sidecar = file.with_extension("expect");
    let mut expect = if sidecar.exists() {
        parse_expect(&std::fs::read_to_string(&sidecar).map_err(|e| e.to_string())?)?
    } else {
        let first = text.lines().next().unwrap_or("");
        let spec = first
            .strip_prefix("# expect: ")
            .ok_or("no `# expect: LINE:COL: fragment` on the first line and no .expect sidecar")?;
        parse_expect(spec)?
    };
    expect.nots = text
        .lines()
        .filter_map(|l| l.strip_prefix("# not: "))
        .map(|s| s.trim().to_string())
        .collect();
    Ok(expect)
}

/// Rust `Debug` output such as `Depth { depth: 65 }` is not a message for people.
fn looks_like_debug_output(message: &str) -> bool {
    message.match_indices(" { ").any(|(i, _)| {
        let word = message[..i].rsplit(' ').next().unwrap_or("");
        let field = message[i + 3..].split(": ").next().unwrap_or("");
        word.starts_with(|c: char| c.is_ascii_uppercase())
            && !field.is_empty()
            && field.chars().all(|c| c.is_ascii_lowercase() || c == '_')
    })
}

/// Problems with a message that hold for every case: it must be written for the user of the
/// command line, not for the programmer of a library, and must not be cut short.
fn message_problems(message: &str) -> Vec<String> {
    let mut problems = vec![];
    if message.trim().is_empty() {
        problems.push("empty message".to_string());
    }
    for internal in [
        "DuplicateKeyPolicy",
        "Options",
        "from_str",
        "serde",
        "saphyr",
    ] {
        if message.contains(internal) {
            problems.push(format!(
                "message mentions the parser's API (`{internal}`), which the user cannot change"
            ));
        }
    }
    if looks_like_debug_output(message) {
        problems.push("message contains Rust Debug output".to_string());
    }
    for (open, close) in [('(', ')'), ('[', ']'), ('{', '}')] {
        if message.matches(open).count() != message.matches(close).count() {
            problems.push(format!(
                "unbalanced `{open}{close}`: the message was cut short"
            ));
        }
    }
    problems
}

/// Checks one run against what it should have done; returns what went wrong.
fn judge(shown: &str, run: &Result<Run, String>, expect: &Expect) -> Vec<String> {
    let run = match run {
        Ok(run) => run,
        Err(e) => return vec![e.clone()],
    };
    let mut problems = vec![];
    if run.code != Some(2) {
        problems.push(format!("exit status {:?}, want 2", run.code));
    }
    for (stream, text) in [("stdout", &run.stdout), ("stderr", &run.stderr)] {
        if text.contains("panicked") || text.contains("RUST_BACKTRACE") {
            problems.push(format!("panic on {stream}"));
        }
    }
    if !run.stdout.is_empty() {
        problems.push(format!("stdout not empty: {:?}", excerpt(&run.stdout)));
    }
    if run.stderr.lines().count() != 1 || !run.stderr.ends_with('\n') {
        problems.push(format!(
            "stderr is {} lines, want exactly one",
            run.stderr.lines().count()
        ));
    }
    if run.peak_kb > MEMORY_LIMIT_KB {
        problems.push(format!("peak memory {} KiB", run.peak_kb));
    }
    let line = run.stderr.lines().next().unwrap_or("");
    let prefix = format!("raytree: {shown}:{}:{}: ", expect.line, expect.column);
    let Some(message) = line.strip_prefix(&prefix) else {
        problems.push(format!("does not start with `{prefix}`"));
        return problems;
    };
    let lower = message.to_lowercase();
    if !expect
        .fragments
        .iter()
        .any(|f| lower.contains(&f.to_lowercase()))
    {
        problems.push(format!(
            "message does not say {}",
            expect.fragments.join(" or ")
        ));
    }
    for not in &expect.nots {
        if lower.contains(&not.to_lowercase()) {
            problems.push(format!("message says `{not}`, which is wrong here"));
        }
    }
    problems.extend(message_problems(message));
    problems
}

fn excerpt(s: &str) -> String {
    let s: String = s.chars().take(300).collect();
    s.trim_end().to_string()
}

fn corpus() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(CORPUS);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("tests/bad_scenes exists")
        .map(|e| e.expect("readable directory").path())
        .filter(|p| p.is_file() && p.extension() != Some(OsStr::new("expect")))
        .collect();
    files.sort();
    files
}

#[test]
fn every_bad_scene_is_refused_with_one_line_naming_line_and_column() {
    let files = corpus();
    assert!(files.len() >= 107, "only {} cases", files.len());
    let mut failures = vec![];
    for file in &files {
        let name = file.file_name().unwrap().to_string_lossy().into_owned();
        let shown = format!("{CORPUS}/{name}");
        let expect = match expectation(file) {
            Ok(e) => e,
            Err(e) => {
                failures.push(format!("{name}: {e}"));
                continue;
            }
        };
        let run = raytree(&["inspect", shown.as_str(), "--pixel", "0,0"]);
        let problems = judge(&shown, &run, &expect);
        if !problems.is_empty() {
            let got = run
                .as_ref()
                .map_or_else(|e| e.clone(), |r| excerpt(&r.stderr));
            failures.push(format!(
                "{name}:\n    want {}:{}: {}\n    got  {got}\n    - {}",
                expect.line,
                expect.column,
                expect.fragments.join(" | "),
                problems.join("\n    - ")
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} bad scenes mishandled:\n{}",
        failures.len(),
        files.len(),
        failures.join("\n")
    );
}

#[test]
fn every_sidecar_belongs_to_a_case() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(CORPUS);
    let cases = corpus();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension() == Some(OsStr::new("expect")) {
            let stem = path.file_stem().unwrap();
            assert!(
                cases.iter().any(|c| c.file_stem() == Some(stem)),
                "{} has no case",
                path.display()
            );
            parse_expect(&std::fs::read_to_string(&path).unwrap()).unwrap();
        }
    }
}

/// Bombs, deep nesting and meshes over the budget are stopped before they cost much: quickly and
/// in little memory.
#[test]
fn budgets_stop_bombs_and_deep_nesting_fast() {
    for name in [
        "57-alias-bomb.yaml",
        "59-deep-nesting-10000.yaml",
        "60-csg-nested-2000-deep.yaml",
        "101-icospheres-over-the-triangle-budget.yaml",
        "102-mesh-is-proc-pagemap.yaml",
    ] {
        let shown = format!("{CORPUS}/{name}");
        let run = raytree(&["inspect", shown.as_str(), "--pixel", "0,0"])
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(run.code, Some(2), "{name}: {}", run.stderr);
        assert!(
            run.elapsed < Duration::from_secs(5),
            "{name} took {:?}",
            run.elapsed
        );
        assert!(
            run.peak_kb < MEMORY_LIMIT_KB,
            "{name} used {} KiB",
            run.peak_kb
        );
    }
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("raytree-bad-scenes-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// CSG trees nested thousands deep, written out here rather than committed: every operation,
/// in flow and in block style.
#[test]
fn csg_nested_thousands_deep_is_refused() {
    const HEAD: &str = "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], width: 8, height: 6 }\n\
                        materials: { m: { kd: 1 } }\n\
                        objects:\n  - name: deep\n    material: m\n";
    const LEAF: &str = "{ sphere: { center: [0, 0, 0], radius: 1 } }";
    let mut failures = vec![];
    for op in ["union", "intersection", "difference"] {
        let n = 3000;
        let flow = format!(
            "{HEAD}    {op}: [{}{LEAF}, {LEAF}{}]\n",
            format!("{{ {op}: [{LEAF}, ").repeat(n),
            "] }".repeat(n)
        );
        // Block style, two spaces more per level, deep enough to pass every budget but the
        // nesting one.
        let mut block = format!("{HEAD}    {op}:\n");
        for level in 0..400 {
            let indent = " ".repeat(6 + 2 * level);
            block.push_str(&format!("{indent}- {LEAF}\n{indent}- {op}:\n"));
        }
        block.push_str(&format!("{}- {LEAF}\n", " ".repeat(6 + 2 * 400)));
        block.push_str(&format!("{}- {LEAF}\n", " ".repeat(6 + 2 * 400)));
        for (style, text) in [("flow", flow), ("block", block)] {
            let path = scratch(&format!("{op}-{style}.yaml"));
            std::fs::write(&path, text).unwrap();
            let shown = path.to_string_lossy().into_owned();
            let run = raytree(&["inspect", shown.as_str(), "--pixel", "0,0"]);
            let mut problems = match &run {
                Err(e) => vec![e.clone()],
                Ok(r) => {
                    let mut p = vec![];
                    if r.code != Some(2) {
                        p.push(format!("exit status {:?}", r.code));
                    }
                    if r.stderr.lines().count() != 1 || r.stderr.contains("panicked") {
                        p.push("not exactly one line, or a panic".into());
                    }
                    let prefix = format!("raytree: {shown}:");
                    match r.stderr.strip_prefix(&prefix) {
                        None => p.push(format!("does not start with `{prefix}`")),
                        Some(rest) => {
                            let message = rest.splitn(3, ':').nth(2).unwrap_or("").trim();
                            if !message.to_lowercase().contains("nest") {
                                p.push("message does not say the tree is nested too deep".into());
                            }
                            p.extend(message_problems(message));
                        }
                    }
                    if r.elapsed > Duration::from_secs(5) {
                        p.push(format!("took {:?}", r.elapsed));
                    }
                    p
                }
            };
            if !problems.is_empty() {
                let got = run
                    .as_ref()
                    .map_or_else(|e| e.clone(), |r| excerpt(&r.stderr));
                problems.insert(0, format!("{op} {style}: got {got}"));
                failures.push(problems.join("\n    - "));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn a_directory_as_scene_is_refused_in_one_line() {
    let run = raytree(&["inspect", CORPUS, "--pixel", "0,0"]).unwrap();
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
    assert!(
        run.stderr.starts_with(&format!("raytree: {CORPUS}")),
        "{}",
        run.stderr
    );
    assert!(run.stderr.contains("directory"), "{}", run.stderr);
    assert!(!run.stderr.contains("panicked"));
}

#[test]
fn a_missing_scene_file_is_refused_in_one_line() {
    let missing = "tests/bad_scenes/no-such-scene.yaml";
    let run = raytree(&["inspect", missing, "--pixel", "0,0"]).unwrap();
    assert_eq!(run.code, Some(2), "{}", run.stderr);
    assert_eq!(run.stderr.lines().count(), 1, "{}", run.stderr);
    assert!(
        run.stderr.starts_with(&format!("raytree: {missing}")),
        "{}",
        run.stderr
    );
    assert!(
        run.stderr.to_lowercase().contains("no such file"),
        "{}",
        run.stderr
    );
    assert!(!run.stderr.contains("panicked"));
}

/// The other side of the corpus: scenes that look suspicious to a text scan but are fine.
#[test]
fn valid_scenes_that_look_odd_are_accepted() {
    use raytree::scene::{parse, Limits};
    const SCENE: &str = "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], width: 8, height: 6 }\n\
                         materials: { m: { kd: 1 } }\n";
    let cases = [
        (
            "a name with `.nan` as a word",
            format!("{SCENE}objects:\n  - {{ name: not .nan really, sphere: {{ center: [0, 0, 0], radius: 1 }}, material: m }}\n"),
        ),
        (
            "a name with `.inf` after a colon",
            format!("{SCENE}objects:\n  - {{ name: \"ratio: .inf \", sphere: {{ center: [0, 0, 0], radius: 1 }}, material: m }}\n"),
        ),
        (
            "a byte-order mark and CRLF line ends",
            format!("\u{feff}{}", SCENE.replace('\n', "\r\n")),
        ),
        (
            "tabs as separators inside flow collections",
            "camera: {\teye: [0,\t0, -5],\tlook_at: [0, 0, 0] }\n".to_string(),
        ),
        (
            "tiny numbers and negative zero",
            format!("{SCENE}objects:\n  - {{ name: s, sphere: {{ center: [-0, 1e-308, 0], radius: 1e-300 }}, material: m }}\n"),
        ),
    ];
    let mut failures = vec![];
    for (what, text) in cases {
        if let Err(e) = parse(&text, "odd.yaml", None, &Limits::default()) {
            failures.push(format!("{what}: refused with {e}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Scenes whose numbers are all finite but so large or small that squares and products
/// overflow: raytree may refuse them (exit 2, one line) or render them, but must neither hang
/// nor produce NaN pixels. Found by tests/fuzz_parse.rs.
#[test]
fn extreme_finite_scenes_are_refused_or_render_cleanly() {
    const HEAD: &str = "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], width: 8, height: 6 }\n\
                        materials: { m: { kd: 1, ks: 0.5, kr: 0.5 } }\n";
    let cases = [
        (
            "a huge sphere in a CSG union",
            "lights: [ { point: [0, 5, -5] } ]\nobjects:\n  - name: u\n    material: m\n    union:\n      - { sphere: { center: [0, 0, 0], radius: 1 } }\n      - { sphere: { center: [0, 0, 1e308], radius: 1e308 } }\n",
        ),
        (
            "a point light at 1e200",
            "lights: [ { point: [0, 1e200, -5] } ]\nobjects:\n  - { name: p, plane: { point: [0, 0, 0], normal: [0, 0, -1] }, material: m }\n",
        ),
        (
            "a point light at the largest f64",
            "lights: [ { point: [0, 1.7976931348623157e308, -5] } ]\nobjects:\n  - { name: p, plane: { point: [0, 0, 0], normal: [0, 0, -1] }, material: m }\n",
        ),
        (
            "a sphere of radius 1e308",
            "lights: [ { point: [0, 5, -5] } ]\nobjects:\n  - { name: s, sphere: { center: [0, 0, 0], radius: 1e308 }, material: m }\n",
        ),
        (
            "a sphere of radius 1e-308",
            "lights: [ { point: [0, 5, -5] } ]\nobjects:\n  - { name: s, sphere: { center: [0, 0, 0], radius: 1e-308 }, material: m }\n",
        ),
        (
            "a box from -1e308 to 1e308",
            "lights: [ { direction: [0, -1, 1] } ]\nobjects:\n  - { name: b, box: { min: [-1e308, -1e308, 1], max: [1e308, 1e308, 1e308] }, material: m }\n",
        ),
        (
            "a transform scaling by 1e300 twice",
            "lights: [ { point: [0, 5, -5] } ]\nobjects:\n  - { name: s, sphere: { center: [0, 0, 0], radius: 1 }, material: m, transform: [ { scale: 1e300 }, { scale: 1e300 } ] }\n",
        ),
    ];
    let mut failures = vec![];
    for (i, (what, body)) in cases.iter().enumerate() {
        let scene = scratch(&format!("extreme-{i}.yaml"));
        let image = scratch(&format!("extreme-{i}.png"));
        std::fs::write(&scene, format!("{HEAD}{body}")).unwrap();
        let run = raytree(&[
            OsStr::new("render"),
            scene.as_os_str(),
            OsStr::new("-o"),
            image.as_os_str(),
        ]);
        let problem = match &run {
            Err(e) => Some(e.clone()),
            Ok(r) if r.stderr.contains("panicked") => Some("panic".into()),
            Ok(r) if r.code == Some(2) && r.stderr.lines().count() == 1 => None,
            Ok(r) if r.code == Some(0) && r.stderr.contains("not finite") => {
                Some("rendered with NaN or infinite pixels".into())
            }
            Ok(r) if r.code == Some(0) => None,
            Ok(r) => Some(format!("exit status {:?}", r.code)),
        };
        if let Some(p) = problem {
            let got = run
                .as_ref()
                .map_or_else(|e| e.clone(), |r| excerpt(&r.stderr));
            failures.push(format!("{what}: {p}\n    stderr: {got}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
