//! In-process fuzzing of the scene parser and, for what it accepts, the renderer, on stable
//! Rust in the ordinary test run (the cargo-fuzz targets in tests/fuzz need nightly); proptest
//! generates the inputs.
//!
//! Three generators: random bytes, a soup of YAML and scene tokens, and mutations of the
//! lesson and example scenes (byte flips, deletions, insertions, duplicated / deleted / swapped
//! lines, numbers replaced by extreme values). For every input:
//! * `scene::parse` must not panic;
//! * an error is one line, with line ≥ 1 and column ≥ 1, inside the text;
//! * an accepted scene renders at 8 × 6 without a panic, a hang or a NaN pixel.
//!
//! The seed is fixed, so a run is deterministic. `PROPTEST_CASES=N` sets the number of inputs
//! per generator (default below, sized to stay well under 20 s in the test profile). Every
//! distinct finding is collected, minimised by deleting lines and characters, and reported
//! together. An input still running after `FUZZ_HANG_SECS` (default 5) is a hang; a generator
//! stops after `FUZZ_MAX_HANGS` of them (default 1). With `FUZZ_ISOLATE=1`, or after the first
//! hang, accepted scenes are rendered in a child process that can be killed. A long survey:
//!
//! ```text
//! PROPTEST_CASES=20000 FUZZ_MAX_HANGS=100000 FUZZ_HANG_SECS=3 \
//!     cargo test --test fuzz_parse -- --nocapture
//! ```

use std::collections::BTreeMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use std::sync::{Mutex, Once};
use std::time::{Duration, Instant};

use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use raytree::render::{render_simple, RenderOptions};
use raytree::scene::{parse, Limits};

// `text_of` is for the cargo-fuzz target and the saved inputs (tests/fuzz_regressions.rs).
#[allow(dead_code)]
#[path = "fuzz/checks/split.rs"]
mod split;

const DEFAULT_CASES: u32 = 4000;
const SEED: [u8; 32] = *b"raytree fuzz_parse seed, fixed.!";
/// A single input taking longer than this to parse and render is a finding.
const SLOW: Duration = Duration::from_secs(3);
/// An input still running after this long (`FUZZ_HANG_SECS`, default 5) has hung.
fn hang_limit() -> Duration {
    let secs = std::env::var("FUZZ_HANG_SECS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(5);
    Duration::from_secs(secs)
}

/// The environment variable that makes `fuzz_child` check one input.
const CHILD_INPUT: &str = "RAYTREE_FUZZ_CHILD_INPUT";

fn cases() -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(DEFAULT_CASES)
}

/// Fuzzing a generator stops after this many hangs (`FUZZ_MAX_HANGS`, default 1). A hang
/// in-process leaves a thread spinning until the test binary exits, so after the first one
/// every accepted scene is rendered in a child process that can be killed.
fn max_hangs() -> u64 {
    std::env::var("FUZZ_MAX_HANGS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1)
}

fn runner() -> TestRunner {
    let config = Config {
        cases: cases(),
        failure_persistence: None,
        ..Config::default()
    };
    TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &SEED))
}

// ---------------------------------------------------------------------------------------
// Catching panics quietly, with their location, also from rayon's worker threads.

static LAST_PANIC: Mutex<Option<String>> = Mutex::new(None);
/// Threads whose name starts with this check inputs: only their panics are caught quietly.
const QUIET: &str = "fuzz-";
/// The panic hook is process-wide: the fuzz tests take turns.
static EXCLUSIVE: Mutex<()> = Mutex::new(());

fn quiet_panics() {
    static HOOK: Once = Once::new();
    HOOK.call_once(|| {
        let default = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            let current = std::thread::current();
            if !current.name().is_some_and(|n| n.starts_with(QUIET)) {
                return default(info);
            }
            let message = info
                .payload()
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| info.payload().downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "(non-string payload)".into());
            let at = info
                .location()
                .map_or_else(String::new, |l| format!("{}:{}", l.file(), l.line()));
            let mut last = LAST_PANIC.lock().unwrap_or_else(|e| e.into_inner());
            *last = Some(format!("panic at {at}: {message}"));
        }));
    });
}

fn take_panic() -> String {
    LAST_PANIC
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .take()
        .unwrap_or_else(|| "panic".into())
}

// ---------------------------------------------------------------------------------------
// The property.

/// What went wrong with one input: a signature that groups equal findings, and a detail.
#[derive(Debug)]
struct Finding {
    signature: String,
    detail: String,
}

fn finding(signature: impl Into<String>, detail: impl Into<String>) -> Finding {
    Finding {
        signature: signature.into(),
        detail: detail.into(),
    }
}

/// Digits vary between otherwise equal findings.
fn generalise(s: &str) -> String {
    let mut out = String::new();
    for c in s.chars().take(160) {
        if c.is_ascii_digit() {
            if !out.ends_with('#') {
                out.push('#');
            }
        } else {
            out.push(c);
        }
    }
    out
}

/// The lines of `text` as YAML counts them (`\r\n`, `\n` and a lone `\r` end a line), in bytes.
fn line_lengths(text: &str) -> Vec<usize> {
    let mut lengths = vec![0];
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'\r' if bytes.get(i + 1) == Some(&b'\n') => {
                lengths.push(0);
                i += 1;
            }
            b'\n' | b'\r' => lengths.push(0),
            _ => *lengths.last_mut().unwrap() += 1,
        }
        i += 1;
    }
    lengths
}

#[derive(Default)]
struct Outcome {
    accepted: bool,
    infinite_pixels: bool,
}

/// Parses `text` and, with `render`, renders what is accepted; call it on a `QUIET` thread.
fn check(text: &str, render: bool) -> Result<Outcome, Finding> {
    let start = Instant::now();
    let result = catch_unwind(AssertUnwindSafe(|| {
        parse(text, "fuzz.yaml", None, &Limits::default())
    }));
    let parsed = match result {
        Ok(parsed) => parsed,
        Err(_) => {
            let p = take_panic();
            return Err(finding(format!("parse: {}", generalise(&p)), p));
        }
    };
    let mut outcome = Outcome::default();
    match parsed {
        Err(e) => {
            let shown = e.to_string();
            if shown.contains('\n') || shown.contains('\r') {
                return Err(finding("error message spans several lines", shown));
            }
            if e.line < 1 || e.column < 1 {
                return Err(finding("error position below 1:1", shown));
            }
            if e.message.trim().is_empty() {
                return Err(finding("empty error message", shown));
            }
            let lines = line_lengths(text);
            let line_ok = e.line as usize <= lines.len();
            // One past the end of a line (or of the text) is where a missing token goes.
            let column_ok = !line_ok || e.column as usize <= lines[e.line as usize - 1] + 2;
            if !line_ok || !column_ok {
                return Err(finding(
                    format!(
                        "error position outside the text: {}",
                        generalise(&e.message)
                    ),
                    format!("{shown} (text has {} lines)", lines.len()),
                ));
            }
        }
        Ok(_) if !render => outcome.accepted = true,
        Ok(scene) => {
            outcome.accepted = true;
            // A pool of its own: a render that hangs keeps only its own worker.
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(1)
                .thread_name(|_| format!("{QUIET}render"))
                .build()
                .expect("a thread pool");
            let rendered = catch_unwind(AssertUnwindSafe(|| {
                let mut s = scene;
                s.camera = s.camera.resized(8, 6);
                let mut options = RenderOptions::of(&s);
                options.max_depth = s.max_depth.min(4);
                options.spp = 1;
                pool.install(|| render_simple(&s, options).0)
            }));
            let image = match rendered {
                Ok(image) => image,
                Err(_) => {
                    let p = take_panic();
                    return Err(finding(format!("render: {}", generalise(&p)), p));
                }
            };
            for y in 0..6 {
                for x in 0..8 {
                    let c = image.get(x, y);
                    if c.is_nan() {
                        return Err(finding(
                            "NaN pixel in an accepted scene",
                            format!("pixel {x},{y} = {c}"),
                        ));
                    }
                    outcome.infinite_pixels |= !c.is_finite();
                }
            }
        }
    }
    if start.elapsed() > SLOW {
        return Err(finding("slow input", format!("took {:?}", start.elapsed())));
    }
    Ok(outcome)
}

fn hang(limit: Duration) -> Finding {
    finding(
        "hang: parse + render of an 8 × 6 image did not finish",
        format!("still running after {limit:?}"),
    )
}

/// `check` on its own thread, giving up after `hang_limit()`.
fn check_or_hang(text: &str, render: bool) -> Result<Outcome, Finding> {
    let (send, receive) = std::sync::mpsc::channel();
    let owned = text.to_string();
    std::thread::Builder::new()
        .name(format!("{QUIET}check"))
        .spawn(move || {
            let _ = send.send(check(&owned, render));
        })
        .expect("a thread");
    let limit = hang_limit();
    receive
        .recv_timeout(limit)
        .unwrap_or_else(|_| Err(hang(limit)))
}

/// `check` in a child process (this test binary running `fuzz_child`), killed if it hangs;
/// a crash (abort, stack overflow) is a finding too.
fn check_in_child(text: &str) -> Result<Outcome, Finding> {
    use std::process::{Command, Stdio};
    let input = std::env::temp_dir().join(format!("raytree-fuzz-{}.yaml", std::process::id()));
    std::fs::write(&input, text).expect("a temporary file");
    let mut child = Command::new(std::env::current_exe().expect("the test binary"))
        .args(["fuzz_child", "--exact", "--ignored", "--nocapture"])
        .env(CHILD_INPUT, &input)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("a child process");
    // The child gives up on its own after `hang_limit()`; this is for a child that cannot.
    let deadline = Instant::now() + hang_limit() + Duration::from_secs(5);
    let status = loop {
        match child.try_wait().expect("waits") {
            Some(status) => break status,
            None if Instant::now() > deadline => {
                let _ = child.kill();
                let _ = child.wait();
                return Err(hang(hang_limit()));
            }
            None => std::thread::sleep(Duration::from_millis(2)),
        }
    };
    let mut stdout = String::new();
    if let Some(mut pipe) = child.stdout.take() {
        let _ = std::io::Read::read_to_string(&mut pipe, &mut stdout);
    }
    let Some(line) = stdout.lines().find_map(|l| l.strip_prefix("FUZZ-RESULT\t")) else {
        return Err(finding(
            format!("crash: the process died ({status})"),
            stdout.chars().take(300).collect::<String>(),
        ));
    };
    let fields: Vec<&str> = line.split('\t').collect();
    match fields.as_slice() {
        ["ok", accepted, infinite] => Ok(Outcome {
            accepted: *accepted == "1",
            infinite_pixels: *infinite == "1",
        }),
        ["finding", signature, detail] => Err(finding(*signature, *detail)),
        _ => panic!("unreadable child result {line:?}"),
    }
}

/// Where inputs are checked: in this process, or (accepted scenes) in a child process.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Mode {
    InProcess,
    Isolated,
}

fn run_check(text: &str, mode: Mode) -> Result<Outcome, Finding> {
    match mode {
        Mode::InProcess => check_or_hang(text, true),
        // Parsing has its own budgets; rendering is what may hang.
        Mode::Isolated => match check_or_hang(text, false) {
            Ok(o) if o.accepted => check_in_child(text),
            other => other,
        },
    }
}

/// Deletes lines (then single characters of short texts) while the same finding remains.
fn minimise(text: &str, signature: &str, mode: Mode) -> String {
    let same = |t: &str| matches!(run_check(t, mode), Err(f) if f.signature == signature);
    let mut lines: Vec<&str> = text.split_inclusive('\n').collect();
    let mut i = 0;
    while i < lines.len() && lines.len() > 1 {
        let mut fewer = lines.clone();
        fewer.remove(i);
        if same(&fewer.concat()) {
            lines = fewer;
        } else {
            i += 1;
        }
    }
    let mut text: Vec<char> = lines.concat().chars().collect();
    if text.len() <= 400 {
        let mut i = 0;
        while i < text.len() {
            let mut fewer = text.clone();
            fewer.remove(i);
            if same(&fewer.iter().collect::<String>()) {
                text = fewer;
            } else {
                i += 1;
            }
        }
    }
    text.into_iter().collect()
}

#[derive(Default)]
struct Report {
    executions: u64,
    accepted: u64,
    refused: u64,
    infinite: u64,
    /// signature → (count, first detail, minimised input)
    findings: BTreeMap<String, (u64, String, String)>,
}

/// Runs the generator `cases()` times, collecting every distinct finding.
fn fuzz<S: Strategy>(name: &str, strategy: S, text_of: impl Fn(&S::Value) -> String) {
    let _turn = EXCLUSIVE.lock().unwrap_or_else(|e| e.into_inner());
    quiet_panics();
    let start = Instant::now();
    let mut runner = runner();
    let mut report = Report::default();
    let mut mode = if std::env::var_os("FUZZ_ISOLATE").is_some() {
        Mode::Isolated
    } else {
        Mode::InProcess
    };
    for _ in 0..runner.config().cases {
        let value = strategy
            .new_tree(&mut runner)
            .expect("strategy generates")
            .current();
        let text = text_of(&value);
        report.executions += 1;
        match run_check(&text, mode) {
            Ok(o) => {
                if o.accepted {
                    report.accepted += 1;
                } else {
                    report.refused += 1;
                }
                report.infinite += o.infinite_pixels as u64;
            }
            Err(f) if f.signature.starts_with("hang") => {
                // Not minimised: every attempt could hang again.
                let e = report
                    .findings
                    .entry(f.signature)
                    .or_insert((0, f.detail, text));
                e.0 += 1;
                if e.0 >= max_hangs() {
                    break;
                }
                mode = Mode::Isolated;
            }
            Err(f) => {
                let entry = report.findings.entry(f.signature.clone());
                let e = entry
                    .or_insert_with(|| (0, f.detail.clone(), minimise(&text, &f.signature, mode)));
                e.0 += 1;
            }
        }
    }
    let total: u64 = report.findings.values().map(|f| f.0).sum();
    println!(
        "{name}: {} executions in {:.1?}: {} accepted (rendered, {} with infinite pixels), \
         {} refused, {} findings in {} kinds",
        report.executions,
        start.elapsed(),
        report.accepted,
        report.infinite,
        report.refused,
        total,
        report.findings.len()
    );
    let mut listing = String::new();
    for (signature, (count, detail, input)) in &report.findings {
        listing.push_str(&format!(
            "\n[{count}×] {signature}\n    first: {detail}\n    minimised input: {input:?}\n"
        ));
    }
    assert!(
        report.findings.is_empty(),
        "{name}: {total} of {} inputs broke the contract:{listing}",
        report.executions
    );
}

// ---------------------------------------------------------------------------------------
// Generators.

/// Tokens of scene files, so the soup reaches past the YAML parser into compilation.
const TOKENS: &[&str] = &[
    "camera:",
    "eye:",
    "look_at:",
    "up:",
    "fov:",
    "width:",
    "height:",
    "window:",
    "u:",
    "v:",
    "w:",
    "f:",
    "background:",
    "ambient:",
    "max_depth:",
    "spp:",
    "shadow_bias:",
    "lights:",
    "materials:",
    "objects:",
    "name:",
    "point:",
    "direction:",
    "intensity:",
    "attenuation:",
    "material:",
    "sphere:",
    "plane:",
    "box:",
    "cylinder:",
    "cone:",
    "triangle:",
    "union:",
    "intersection:",
    "difference:",
    "complement:",
    "transform:",
    "center:",
    "radius:",
    "normal:",
    "min:",
    "max:",
    "base:",
    "top:",
    "apex:",
    "translate:",
    "rotate_y:",
    "scale:",
    "kd:",
    "ka:",
    "ks:",
    "kr:",
    "kt:",
    "ior:",
    "shininess:",
    "m",
    "m:",
    "s",
    " ",
    " ",
    " ",
    "\n",
    "\n",
    "\n  ",
    "\n    ",
    "\n  - ",
    "- ",
    "{",
    "}",
    "[",
    "]",
    ",",
    ", ",
    ":",
    "#",
    "\t",
    "&a ",
    "*a",
    "&b ",
    "*b",
    "!!float ",
    "!!str ",
    "'",
    "\"",
    "---",
    "...",
    "|",
    ">",
    "? ",
    "0",
    "1",
    "-1",
    "2",
    "0.5",
    "40",
    "180",
    "1e308",
    "-1e308",
    "1e-308",
    "-0",
    "1e999",
    "65536",
    "9223372036854775808",
    ".nan",
    ".inf",
    "-.INF",
    "\".nan\"",
    "[0, 0, 0]",
    "[0, 1, 0]",
    "[1, 1, 1]",
    "[0, 0, -5]",
    "auto",
    "blinn",
    "schlick",
    "null",
    "~",
    "true",
    "<<: *a",
];

fn token_soup() -> impl Strategy<Value = Vec<&'static str>> {
    prop::collection::vec(prop::sample::select(TOKENS), 0..160)
}

/// Numbers a mutation puts in place of a number of a lesson scene.
const EXTREMES: &[&str] = &[
    "-0",
    "0",
    "1e308",
    "-1e308",
    "1e-308",
    "-1e-308",
    "4.9e-324",
    "1.7976931348623157e308",
    "1e999",
    "-1",
    "1e-12",
    "1e12",
    "64",
    "65",
    "180",
    "65536",
    "1000000",
    "9223372036854775807",
    "9223372036854775808",
    ".nan",
    "-.inf",
    "-.INF",
    "\".nan\"",
];

/// A position in whatever the mutation applies to, whatever its length.
#[derive(Clone, Copy, Debug)]
struct Index(usize);

impl Index {
    fn index(self, len: usize) -> usize {
        self.0 % len
    }
}

impl Arbitrary for Index {
    type Parameters = ();
    type Strategy = prop::strategy::Map<prop::num::usize::Any, fn(usize) -> Index>;
    fn arbitrary_with(_: ()) -> Self::Strategy {
        any::<usize>().prop_map(Index)
    }
}

#[derive(Clone, Debug)]
enum Mutation {
    FlipByte(Index, u8),
    Delete(Index, usize),
    Insert(Index, u8),
    DuplicateLine(Index),
    DeleteLine(Index),
    SwapLines(Index, Index),
    Number(Index, &'static str),
    /// Copies a chunk of the text to another place.
    Splice(Index, Index, usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let interesting = prop::sample::select(b"\t\n\r :{}[],-#&*!'\"|>0.e~".to_vec());
    // Number replacements mostly keep the YAML valid and so reach compilation and rendering.
    prop_oneof![
        1 => (any::<Index>(), any::<u8>()).prop_map(|(i, b)| Mutation::FlipByte(i, b)),
        1 => (any::<Index>(), 1..24usize).prop_map(|(i, n)| Mutation::Delete(i, n)),
        1 => (any::<Index>(), prop_oneof![interesting, any::<u8>()])
            .prop_map(|(i, b)| Mutation::Insert(i, b)),
        2 => any::<Index>().prop_map(Mutation::DuplicateLine),
        2 => any::<Index>().prop_map(Mutation::DeleteLine),
        1 => (any::<Index>(), any::<Index>()).prop_map(|(a, b)| Mutation::SwapLines(a, b)),
        8 => (any::<Index>(), prop::sample::select(EXTREMES)).prop_map(|(i, v)| Mutation::Number(i, v)),
        1 => (any::<Index>(), any::<Index>(), 1..80usize)
            .prop_map(|(a, b, n)| Mutation::Splice(a, b, n)),
    ]
}

/// Byte ranges of the numbers in a text.
fn numbers(text: &[u8]) -> Vec<(usize, usize)> {
    let mut found = vec![];
    let mut i = 0;
    while i < text.len() {
        let starts = text[i].is_ascii_digit()
            || (text[i] == b'-' && text.get(i + 1).is_some_and(u8::is_ascii_digit));
        let inside_word = i > 0 && (text[i - 1].is_ascii_alphanumeric() || text[i - 1] == b'_');
        if starts && !inside_word {
            let mut j = i + 1;
            while j < text.len()
                && (text[j].is_ascii_digit() || matches!(text[j], b'.' | b'e' | b'E' | b'+' | b'-'))
            {
                j += 1;
            }
            found.push((i, j));
            i = j;
        } else {
            i += 1;
        }
    }
    found
}

fn apply(text: &mut Vec<u8>, m: &Mutation) {
    let line_spans = |t: &[u8]| -> Vec<(usize, usize)> {
        let mut spans = vec![];
        let mut start = 0;
        for (i, &b) in t.iter().enumerate() {
            if b == b'\n' {
                spans.push((start, i + 1));
                start = i + 1;
            }
        }
        if start < t.len() {
            spans.push((start, t.len()));
        }
        spans
    };
    match m {
        _ if text.is_empty() => {}
        Mutation::FlipByte(i, b) => {
            let i = i.index(text.len());
            text[i] ^= (*b).max(1);
        }
        Mutation::Delete(i, n) => {
            let i = i.index(text.len());
            let end = (i + n).min(text.len());
            text.drain(i..end);
        }
        Mutation::Insert(i, b) => {
            let i = i.index(text.len() + 1);
            text.insert(i, *b);
        }
        Mutation::DuplicateLine(i) => {
            let spans = line_spans(text);
            let (a, b) = spans[i.index(spans.len())];
            let line = text[a..b].to_vec();
            text.splice(b..b, line);
        }
        Mutation::DeleteLine(i) => {
            let spans = line_spans(text);
            let (a, b) = spans[i.index(spans.len())];
            text.drain(a..b);
        }
        Mutation::SwapLines(i, j) => {
            let spans = line_spans(text);
            let (x, y) = (spans[i.index(spans.len())], spans[j.index(spans.len())]);
            let (first, second) = if x.0 <= y.0 { (x, y) } else { (y, x) };
            if first == second {
                return;
            }
            let mut out = text[..first.0].to_vec();
            out.extend_from_slice(&text[second.0..second.1]);
            out.extend_from_slice(&text[first.1..second.0]);
            out.extend_from_slice(&text[first.0..first.1]);
            out.extend_from_slice(&text[second.1..]);
            *text = out;
        }
        Mutation::Number(i, value) => {
            let found = numbers(text);
            if !found.is_empty() {
                let (a, b) = found[i.index(found.len())];
                text.splice(a..b, value.bytes());
            }
        }
        Mutation::Splice(from, to, n) => {
            let a = from.index(text.len());
            let chunk = text[a..(a + n).min(text.len())].to_vec();
            let at = to.index(text.len() + 1);
            text.splice(at..at, chunk);
        }
    }
}

/// The lesson scenes and the example scenes that parse and render cleanly on their own (with
/// no scene path, scenes that load mesh files are refused): the seeds of the mutations.
fn seeds() -> Vec<String> {
    quiet_panics();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons");
    let mut files = vec![];
    for entry in std::fs::read_dir(&root).expect("lessons/") {
        let dir = entry.unwrap().path();
        let scene = dir.join("scene.yaml");
        if scene.is_file() {
            files.push(scene);
        }
    }
    for entry in std::fs::read_dir(root.join("examples"))
        .into_iter()
        .flatten()
    {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "yaml") {
            files.push(path);
        }
    }
    files.sort();
    let mut seeds = vec![];
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        match check_or_hang(&text, true) {
            Ok(o) if o.accepted => seeds.push(text),
            Ok(_) => println!("seed {} left out: refused", file.display()),
            Err(f) => panic!("seed {}: {}: {}", file.display(), f.signature, f.detail),
        }
    }
    seeds
}

// ---------------------------------------------------------------------------------------
// The tests.

#[test]
fn the_seed_scenes_themselves_pass() {
    let _turn = EXCLUSIVE.lock().unwrap_or_else(|e| e.into_inner());
    quiet_panics();
    let seeds = seeds();
    assert!(seeds.len() >= 10, "only {} seed scenes", seeds.len());
}

#[test]
fn random_bytes_never_break_the_parser() {
    fuzz(
        "random bytes",
        prop::collection::vec(any::<u8>(), 0..400),
        |bytes| String::from_utf8_lossy(bytes).into_owned(),
    );
}

#[test]
fn token_soup_never_breaks_the_parser() {
    // Half the soups follow a valid camera and material, to get past the first checks.
    const HEAD: &str =
        "camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmaterials: { m: { kd: 1 } }\n";
    fuzz(
        "token soup",
        (any::<bool>(), token_soup()),
        |(head, tokens)| {
            let soup = tokens.concat();
            if *head {
                format!("{HEAD}{soup}")
            } else {
                soup
            }
        },
    );
}

#[test]
fn mutated_lesson_scenes_never_break_parser_or_renderer() {
    let seeds = seeds();
    fuzz(
        "mutated lesson scenes",
        (any::<Index>(), prop::collection::vec(mutation(), 1..5)),
        |(which, mutations)| {
            let mut text = seeds[which.index(seeds.len())].clone().into_bytes();
            for m in mutations {
                apply(&mut text, m);
            }
            String::from_utf8_lossy(&text).into_owned()
        },
    );
}

/// Items of a large file's object list, in the styles that have fooled a text scan: brackets
/// in plain scalars, collections across lines, comments, CSG children, odd indentation. `@`
/// stands for the item's number (names must differ).
const ITEMS: &[&str] = &[
    "  - { sphere: { center: [1, 2, 3], radius: 0.5 }, material: m }",
    "  - name: x[@\n    sphere: { center: [0, 0, 0], radius: 1 }\n    material: m",
    "  - name: y] {@\n    box: { min: [0, 0, 0], max: [1, 1, 1] }\n    material: m",
    "  - { cylinder: { base: [0, 0, 0], top: [0, 1, 0],\n radius: 0.25 }, material: m }",
    "  # - { sphere: { center: [0, 0, 0], radius: 1 } }\n  - { cone: { apex: [0, 1, 0], base: [0, 0, 0], radius: 1 }, material: m } # a#b [",
    "  - difference:\n      - box: { min: [0, 0, 0], max: [1, 1, 1] }\n      - sphere:\n          center: [0.5, 0.5, 0.5]\n          radius: 0.6\n    material: m",
    "  -\n    triangle: [[0, 0, 0], [1, 0, 0], [0, 1, 0]]\n    material: m",
    "  - name: q]x[@\n    icosphere: { subdivisions: 0 }\n    material: m",
    "  - name: b{c@\n    plane: { point: [0, 0, 9], normal: [0, 0, -1] }\n    material: m",
    "  - { sphere: { center: [0, 0, 0], radius: 1 }, material: m }\nlights: [ { name: z], point: [0, 5, 0] } ]\nobjects:",
];

/// The parallel loader gives what one thread gives, for large files of mixed items, mutated
/// (`tests/fuzz/checks/split.rs`; the cargo-fuzz target `split` runs the same check).
#[test]
fn large_scenes_load_alike_on_any_number_of_threads() {
    let cases = (cases() / 100).max(8);
    let config = Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    };
    let mut runner =
        TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &SEED));
    // Quoted strings, anchors and tabs keep a file whole; the mutations that add them are
    // tried too, but most files stay plain enough to be cut.
    let strategy = (
        prop::collection::vec(prop::sample::select(ITEMS), 1..12),
        any::<bool>(),
        prop_oneof![
            2 => Just(vec![]),
            1 => prop::collection::vec(mutation(), 1..3),
        ],
    );
    const HEAD: &str = "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], width: 8, height: 6 }\n\
                        materials: { m: { kd: 1 } }\nobjects:\n";
    const TAIL: &str = "lights:\n  - name: y]\n    point: [0, 5, -5]\nspp: 1\n";
    runner
        .run(&strategy, |(items, tail, mutations)| {
            let mut text = String::from(HEAD);
            let mut k = 0;
            while text.len() < split::SPLIT_BYTES {
                text += &items[k % items.len()].replace('@', &k.to_string());
                text += "\n";
                k += 1;
            }
            if tail {
                text += TAIL;
            }
            let mut bytes = text.into_bytes();
            for m in &mutations {
                apply(&mut bytes, m);
            }
            split::check(&String::from_utf8_lossy(&bytes));
            Ok(())
        })
        .unwrap();
}

#[test]
fn mutations_do_what_they_say() {
    let mut t = b"a: 1\nb: [2, -3.5e2]\nc: x1\n".to_vec();
    assert_eq!(numbers(&t), vec![(3, 4), (9, 10), (12, 18)]);
    apply(&mut t, &Mutation::Number(Index(2), "1e308"));
    assert_eq!(t, b"a: 1\nb: [2, 1e308]\nc: x1\n");
    apply(&mut t, &Mutation::SwapLines(Index(0), Index(2)));
    assert_eq!(t, b"c: x1\nb: [2, 1e308]\na: 1\n");
    apply(&mut t, &Mutation::DeleteLine(Index(1)));
    assert_eq!(t, b"c: x1\na: 1\n");
    apply(&mut t, &Mutation::DuplicateLine(Index(0)));
    assert_eq!(t, b"c: x1\nc: x1\na: 1\n");
}

/// Checks the input named by `RAYTREE_FUZZ_CHILD_INPUT`, for `check_in_child`; does nothing
/// otherwise.
#[test]
#[ignore = "run by the fuzz tests in a child process"]
fn fuzz_child() {
    let Some(input) = std::env::var_os(CHILD_INPUT) else {
        return;
    };
    quiet_panics();
    let text = std::fs::read_to_string(input).expect("the input");
    let clean = |s: &str| s.replace(['\t', '\n', '\r'], " ");
    match check_or_hang(&text, true) {
        Ok(o) => println!(
            "FUZZ-RESULT\tok\t{}\t{}",
            o.accepted as u8, o.infinite_pixels as u8
        ),
        Err(f) => println!(
            "FUZZ-RESULT\tfinding\t{}\t{}",
            clean(&f.signature),
            clean(&f.detail)
        ),
    }
    // A hung render thread must not keep the child alive.
    std::process::exit(0);
}
