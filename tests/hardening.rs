//! raytree used as a hostile or careless user would: output to a closed pipe or a full device,
//! signals in the middle of a write, files that are not files, budgets, control characters in
//! names, answers that are not answers. Every case: a clear line on stderr and a meaningful exit
//! status, never a panic, a hang, a temporary file left behind or a broken output.
//!
//! `RAYTREE_BIN=path` runs these checks against another build of raytree (how they were seen
//! to fail before the fixes).

mod common;

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

fn bin() -> PathBuf {
    std::env::var_os("RAYTREE_BIN")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_BIN_EXE_raytree")))
}

fn command<S: AsRef<OsStr>>(args: &[S]) -> Command {
    let mut c = Command::new(bin());
    c.args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env("NO_COLOR", "1")
        .stdin(Stdio::null());
    c
}

struct Run {
    status: ExitStatus,
    stdout: String,
    stderr: String,
    elapsed: Duration,
}

impl Run {
    fn code(&self) -> Option<i32> {
        self.status.code()
    }

    /// Problems every run must be free of.
    fn sane(&self) -> Vec<String> {
        let mut p = vec![];
        for (name, text) in [("stdout", &self.stdout), ("stderr", &self.stderr)] {
            if text.contains("panicked") || text.contains("RUST_BACKTRACE") {
                p.push(format!("panic on {name}: {}", excerpt(text)));
            }
        }
        if self.code() == Some(101) {
            p.push("exit status 101 (a panic)".into());
        }
        if self.code().is_none() {
            p.push(format!("killed: {:?}", self.status));
        }
        p
    }
}

fn excerpt(s: &str) -> String {
    s.chars()
        .take(400)
        .collect::<String>()
        .trim_end()
        .to_string()
}

/// Waits for a child, killing it after `limit`.
fn finish(mut child: Child, limit: Duration) -> Run {
    let start = Instant::now();
    let (out, err) = common::drain_output(&mut child);
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!("hung: killed after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    Run {
        status,
        stdout: out.join().unwrap(),
        stderr: err.join().unwrap(),
        elapsed: start.elapsed(),
    }
}

fn run<S: AsRef<OsStr>>(args: &[S]) -> Run {
    let child = command(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("raytree starts");
    finish(child, Duration::from_secs(60))
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("raytree-hardening-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn write(name: &str, text: &str) -> PathBuf {
    let path = scratch(name);
    std::fs::write(&path, text).unwrap();
    path
}

const L08: &str = "lessons/08-pixel-intensity/scene.yaml";
const SMALL: &str = "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], width: 16, height: 12 }\n\
                     ambient: 0.2\nlights: [ { point: [2, 3, -4] } ]\n\
                     materials: { m: { color: [1, 0.5, 0.25], ka: 1, kd: 0.8, ks: 0.3 } }\n\
                     objects: [ { name: ball, sphere: { center: [0, 0, 0], radius: 1.5 }, material: m } ]\n";

/// Every subcommand that writes to stdout, with the exit status it has when all goes well.
fn printing_commands() -> Vec<(Vec<String>, i32)> {
    let small = write("small.yaml", SMALL).to_string_lossy().into_owned();
    let reference = scratch("reference.exr").to_string_lossy().into_owned();
    let r = run(&["render", &small, "-o", &reference]);
    assert_eq!(r.code(), Some(0), "{}", r.stderr);
    let s = |v: &[&str]| v.iter().map(|x| x.to_string()).collect::<Vec<_>>();
    vec![
        (s(&["--help"]), 0),
        (s(&["--version"]), 0),
        (s(&["render", "--help"]), 0),
        (s(&["lessons"]), 0),
        (s(&["inspect", L08, "--pixel", "30,30"]), 0),
        (
            s(&["inspect", L08, "--pixel", "30,30", "--format", "json"]),
            0,
        ),
        (
            s(&[
                "inspect",
                "lessons/15-path-tracing/scene.yaml",
                "--pixel",
                "3,3",
            ]),
            0,
        ),
        (
            s(&["csg", "lessons/10-csg/scene.yaml", "--ray", "0,0,-10:0,0,1"]),
            0,
        ),
        (
            s(&[
                "csg",
                "lessons/10-csg/scene.yaml",
                "--ray",
                "0,0,-10:0,0,1",
                "--format",
                "json",
            ]),
            0,
        ),
        (s(&["preview", L08, "--columns", "24"]), 0),
        (
            s(&[
                "check",
                "lessons/08-pixel-intensity",
                "--exercise",
                "pixel-p",
                "--answer",
                "0.870161",
            ]),
            0,
        ),
        (
            s(&[
                "check",
                "lessons/08-pixel-intensity",
                "--exercise",
                "pixel-p",
                "--explain",
            ]),
            0,
        ),
        (
            s(&[
                "bench",
                "sweep",
                &small,
                "--knob",
                "spp",
                "--values",
                "1,4",
                "--reference",
                &reference,
            ]),
            0,
        ),
        (
            s(&[
                "bench",
                "scaling",
                "--max-spheres",
                "10",
                "--max-brute",
                "10",
                "--max-subdivisions",
                "3",
            ]),
            0,
        ),
    ]
}

/// `raytree … | head -c 1` in a shell, and the same with the reader gone before the first
/// write (deterministic: every write then fails with EPIPE), and `raytree … > /dev/full`.
#[test]
fn a_closed_pipe_ends_quietly_and_a_full_device_is_one_line() {
    let mut failures = vec![];
    for (args, code) in printing_commands() {
        let shown = args.join(" ");
        // The shell's pipe into `head -c 1`, statuses of both sides.
        let out = Command::new("bash")
            .arg("-c")
            .arg(r#"set -o pipefail; "$0" "$@" 2>"$ERR" | head -c 1 >/dev/null; echo $?"#)
            .arg(bin())
            .args(&args)
            .env("ERR", scratch("pipe.err"))
            .env("NO_COLOR", "1")
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .unwrap();
        let status = String::from_utf8_lossy(&out.stdout).trim().to_string();
        let err = std::fs::read_to_string(scratch("pipe.err")).unwrap_or_default();
        if status != code.to_string() || err.contains("panicked") || !err.is_empty() {
            failures.push(format!(
                "{shown} | head -c 1: status {status}, stderr {:?}",
                excerpt(&err)
            ));
        }

        // The reader gone before anything is written.
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let child = command(&args)
            .stdout(writer)
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let r = finish(child, Duration::from_secs(60));
        let mut problems = r.sane();
        if r.code() != Some(code) {
            problems.push(format!("exit status {:?}, want {code}", r.code()));
        }
        if !r.stderr.is_empty() {
            problems.push(format!("stderr not empty: {:?}", excerpt(&r.stderr)));
        }
        if !problems.is_empty() {
            failures.push(format!("{shown} > closed pipe: {}", problems.join("; ")));
        }

        // A full device: one line, exit status 2.
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let child = command(&args)
            .stdout(full)
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let r = finish(child, Duration::from_secs(60));
        let mut problems = r.sane();
        if r.code() != Some(2) {
            problems.push(format!("exit status {:?}, want 2", r.code()));
        }
        let lines = r.stderr.lines().count();
        if lines != 1 || !r.stderr.contains("No space left on device") {
            problems.push(format!("stderr: {:?}", excerpt(&r.stderr)));
        }
        if !problems.is_empty() {
            failures.push(format!("{shown} > /dev/full: {}", problems.join("; ")));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Errors go to stderr; a stderr that cannot be written to must not make raytree panic.
#[test]
fn a_full_stderr_is_no_panic() {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let child = command(&["inspect", "no-such-scene.yaml", "--pixel", "0,0"])
        .stdout(Stdio::piped())
        .stderr(full)
        .spawn()
        .unwrap();
    let r = finish(child, Duration::from_secs(30));
    assert_eq!(r.code(), Some(2));
}

// ---------------------------------------------------------------------------------------
// Files that are not files, and files too large

#[cfg(unix)]
fn fifo(name: &str) -> PathBuf {
    let path = scratch(name);
    let _ = std::fs::remove_file(&path);
    let ok = Command::new("mkfifo")
        .arg(&path)
        .status()
        .unwrap()
        .success();
    assert!(ok, "mkfifo");
    path
}

#[cfg(unix)]
#[test]
fn devices_fifos_and_proc_files_are_refused_at_once() {
    let pipe = fifo("scene-fifo.yaml");
    let image = scratch("fifo.png");
    let cases: Vec<(Vec<&OsStr>, &str)> = vec![
        (
            vec![
                "inspect".as_ref(),
                "/dev/zero".as_ref(),
                "--pixel".as_ref(),
                "0,0".as_ref(),
            ],
            "not a regular file",
        ),
        (
            vec![
                "inspect".as_ref(),
                "/dev/urandom".as_ref(),
                "--pixel".as_ref(),
                "0,0".as_ref(),
            ],
            "not a regular file",
        ),
        (
            vec![
                "inspect".as_ref(),
                "/proc/self/pagemap".as_ref(),
                "--pixel".as_ref(),
                "0,0".as_ref(),
            ],
            "budget",
        ),
        (
            vec![
                "render".as_ref(),
                pipe.as_os_str(),
                "-o".as_ref(),
                image.as_os_str(),
            ],
            "not a regular file",
        ),
        (
            vec!["explore".as_ref(), pipe.as_os_str()],
            "not a regular file",
        ),
    ];
    for (args, says) in cases {
        let r = run(&args);
        let shown = format!("{args:?}");
        assert!(r.sane().is_empty(), "{shown}: {:?}", r.sane());
        assert_eq!(r.code(), Some(2), "{shown}: {}", r.stderr);
        assert_eq!(r.stderr.lines().count(), 1, "{shown}: {}", r.stderr);
        assert!(r.stderr.contains(says), "{shown}: {}", r.stderr);
        assert!(
            r.elapsed < Duration::from_secs(10),
            "{shown}: {:?}",
            r.elapsed
        );
    }
}

#[test]
fn a_scene_file_over_the_budget_is_refused_before_it_is_read() {
    let big = scratch("big.yaml");
    let mut text = String::from(SMALL);
    text += &format!("# {}\n", "x".repeat(17 << 20));
    std::fs::write(&big, text).unwrap();
    let r = run(&[
        OsStr::new("inspect"),
        big.as_os_str(),
        OsStr::new("--pixel"),
        OsStr::new("0,0"),
    ]);
    assert_eq!(r.code(), Some(2), "{}", r.stderr);
    assert!(
        r.stderr.contains("budget of 16 MiB") && r.stderr.contains("--allow-huge"),
        "{}",
        r.stderr
    );
    let r = run(&[
        OsStr::new("inspect"),
        big.as_os_str(),
        OsStr::new("--pixel"),
        OsStr::new("0,0"),
        OsStr::new("--allow-huge"),
    ]);
    assert_eq!(r.code(), Some(0), "{}", r.stderr);
    std::fs::remove_file(&big).unwrap();
}

// ---------------------------------------------------------------------------------------
// Budgets of images

#[test]
fn images_beyond_the_budget_or_memory_are_refused_at_once() {
    let out = scratch("huge.png");
    let out = out.to_str().unwrap();
    for (args, says) in [
        (
            vec![
                "render",
                L08,
                "-o",
                out,
                "--depth-strip",
                "64",
                "--width",
                "2000",
                "--height",
                "2000",
            ],
            "budget",
        ),
        (
            vec![
                "render",
                L08,
                "-o",
                out,
                "--allow-huge",
                "--width",
                "1000000",
                "--height",
                "1000000",
            ],
            "memory",
        ),
    ] {
        let r = run(&args);
        assert!(r.sane().is_empty(), "{args:?}: {:?}", r.sane());
        assert_eq!(r.code(), Some(2), "{args:?}: {}", r.stderr);
        assert_eq!(r.stderr.lines().count(), 1, "{}", r.stderr);
        assert!(r.stderr.contains(says), "{args:?}: {}", r.stderr);
        assert!(
            r.elapsed < Duration::from_secs(10),
            "{args:?} took {:?}",
            r.elapsed
        );
    }
    assert!(!Path::new(out).exists());
}

/// `inspect --width/--height` is held to the image budget as `render` and a scene file's own
/// size are (it used to trace a pixel of a 10 000 × 10 000 image without a word), and
/// `--allow-huge` lifts it there too.
#[test]
fn inspect_holds_its_image_size_to_the_budget() {
    let size = ["--pixel", "1,1", "--width", "10000", "--height", "10000"];
    let r = run(&[&["inspect", L08][..], &size].concat());
    assert_eq!(r.code(), Some(2), "{}", r.stderr);
    assert!(
        r.stderr.contains(
            "an image of 10000 × 10000 holds 100000000 pixels, over the budget of 64000000 pixels"
        ) && r.stderr.contains("--allow-huge"),
        "{}",
        r.stderr
    );
    let r = run(&[&["inspect", L08, "--allow-huge"][..], &size].concat());
    assert_eq!(r.code(), Some(0), "{}", r.stderr);
    assert!(r.stdout.contains("pixel (1, 1)"), "{}", r.stdout);
}

/// A depth strip keeps its frames and the strip they are joined into: the refusal counts both
/// and says so, with the strip's own size (the frames, 4-pixel gaps and a label band).
#[test]
fn a_depth_strip_over_the_budget_says_what_it_counts() {
    let out = scratch("strip.png");
    let out = out.to_str().unwrap();
    let r = run(&[
        "render",
        L08,
        "-o",
        out,
        "--depth-strip",
        "3",
        "--width",
        "4000",
        "--height",
        "4000",
    ]);
    assert!(r.sane().is_empty(), "{:?}", r.sane());
    assert_eq!(r.code(), Some(2), "{}", r.stderr);
    assert_eq!(r.stderr.lines().count(), 1, "{}", r.stderr);
    // 3 · 4000 · 4000 = 48 000 000 in the frames, 12 008 · 4 022 = 48 296 176 in the strip.
    for says in [
        "3 frames of 4000 × 4000",
        "their 12008 × 4022 strip",
        "96296176 pixels",
        "budget of 64000000 pixels",
    ] {
        assert!(r.stderr.contains(says), "{says}: {}", r.stderr);
    }
    assert!(!Path::new(out).exists());
    // The strip's size in the message is the size of the strip written.
    let r = run(&[
        "render",
        L08,
        "-o",
        out,
        "--depth-strip",
        "3",
        "--width",
        "100",
        "--height",
        "50",
    ]);
    assert_eq!(r.code(), Some(0), "{}", r.stderr);
    let strip = image::open(out).unwrap();
    assert_eq!((strip.width(), strip.height()), (3 * 100 + 2 * 4, 50 + 22));
    std::fs::remove_file(out).unwrap();
}

#[test]
fn more_threads_than_can_be_started_is_a_clear_error_at_once() {
    let out = scratch("threads.png");
    for n in ["100000", "0"] {
        let r = run(&["render", L08, "-o", out.to_str().unwrap(), "--threads", n]);
        assert_eq!(r.code(), Some(2), "{n}: {}", r.stderr);
        assert!(
            r.stderr.contains("--threads must be between 1 and"),
            "{}",
            r.stderr
        );
        assert!(r.elapsed < Duration::from_secs(5));
    }
}

// ---------------------------------------------------------------------------------------
// Signals

/// The temporary file of an output being written, if any.
fn temporaries(dir: &Path) -> Vec<PathBuf> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "tmp"))
        .collect()
}

/// SIGINT and SIGTERM while a large image is being written: the previous image stays as it
/// was, no temporary file is left, and raytree dies of the signal.
#[cfg(unix)]
#[test]
fn a_signal_during_the_write_leaves_the_old_image_and_no_temporary_file() {
    let dir = scratch("signals");
    std::fs::create_dir_all(&dir).unwrap();
    // A scene that renders at once: writing the image is the long part.
    let scene = write(
        "signals/flat.yaml",
        "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], width: 8, height: 8 }\nbackground: [0.3, 0.6, 0.9]\n",
    );
    let out = dir.join("big.png");
    for signal in ["INT", "TERM"] {
        std::fs::write(&out, b"the previous image").unwrap();
        let child = command(&[
            OsStr::new("render"),
            scene.as_os_str(),
            OsStr::new("-o"),
            out.as_os_str(),
            OsStr::new("--width"),
            OsStr::new("4000"),
            OsStr::new("--height"),
            OsStr::new("3000"),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
        // Wait for the temporary file to appear, then signal at once (from this process: a
        // `kill` command started now could arrive after the write has finished).
        let start = Instant::now();
        let mut seen = false;
        while !seen && start.elapsed() < Duration::from_secs(60) {
            seen = !temporaries(&dir).is_empty();
            if !seen {
                std::thread::sleep(Duration::from_micros(200));
            }
        }
        let number = if signal == "INT" {
            libc::SIGINT
        } else {
            libc::SIGTERM
        };
        // SAFETY: kill(2) on the child's pid, which has not been waited for, so is still its.
        let killed = unsafe { libc::kill(child.id() as libc::pid_t, number) };
        assert!(seen, "SIG{signal}: no temporary file seen");
        assert_eq!(killed, 0);
        let r = finish(child, Duration::from_secs(60));
        use std::os::unix::process::ExitStatusExt;
        let want = if signal == "INT" { 2 } else { 15 };
        assert_eq!(
            r.status.signal(),
            Some(want),
            "SIG{signal}: {:?} {}",
            r.status,
            r.stderr
        );
        assert!(!r.stderr.contains("panicked"), "{}", r.stderr);
        assert_eq!(
            std::fs::read(&out).unwrap(),
            b"the previous image",
            "SIG{signal}"
        );
        assert!(
            temporaries(&dir).is_empty(),
            "SIG{signal}: {:?}",
            temporaries(&dir)
        );
    }
}

/// One pixel whose tree would take longer than the universe has to trace: two glass spheres,
/// one inside the other, each hit sending a reflection and a refraction on, 64 levels deep.
const ENDLESS: &str =
    "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], width: 1, height: 1, fov: 30 }
max_depth: 64
lights:
  - { name: l, point: [0, 4, -4] }
materials:
  g: { color: 1, kd: 0.1, kr: 0.5, kt: 0.5, ior: 1.5 }
objects:
  - { name: a, sphere: { center: [0, 0, 0], radius: 1 }, material: g }
  - { name: b, sphere: { center: [0, 0, 0], radius: 0.5 }, material: g }
";

/// A render whose one pixel would take longer than the universe has (`ENDLESS`) says so
/// first, and still ends soon after SIGINT or SIGTERM, killed by it, and writes nothing.
#[cfg(unix)]
#[test]
fn a_signal_ends_a_render_stuck_in_one_pixel() {
    let scene = write("endless.yaml", ENDLESS);
    let out = scratch("endless.png");
    for signal in ["INT", "TERM"] {
        let child = command(&[
            OsStr::new("render"),
            scene.as_os_str(),
            OsStr::new("-o"),
            out.as_os_str(),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
        std::thread::sleep(Duration::from_millis(500));
        let killed = Command::new("kill")
            .args([&format!("-{signal}"), &child.id().to_string()])
            .status()
            .unwrap();
        assert!(killed.success());
        let r = finish(child, Duration::from_secs(30));
        use std::os::unix::process::ExitStatusExt;
        let want = if signal == "INT" { 2 } else { 15 };
        assert_eq!(r.status.signal(), Some(want), "SIG{signal}: {:?}", r.status);
        assert!(!out.exists(), "SIG{signal}: an image was written");
        // Said before the render began.
        let said = |s: &str| r.stderr.contains(s);
        assert!(
            said("warning: pixel 0,0's ray tree holds over 100000 rays deeper than ")
                && said("at depth 64 this render may take very long"),
            "{}",
            r.stderr
        );
    }
}

/// `inspect` of a pixel whose value takes that long to render says so first, then renders it
/// (Ctrl-C stops it): the warning is read while the process still runs.
#[cfg(unix)]
#[test]
fn inspect_warns_before_rendering_an_endless_pixel() {
    use std::io::BufRead;
    let scene = write("endless-inspect.yaml", ENDLESS);
    let mut child = command(&[
        OsStr::new("inspect"),
        scene.as_os_str(),
        OsStr::new("--pixel"),
        OsStr::new("0,0"),
    ])
    .stdout(Stdio::null())
    .stderr(Stdio::piped())
    .spawn()
    .unwrap();
    let stderr = child.stderr.take().unwrap();
    let (send, lines) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in std::io::BufReader::new(stderr)
            .lines()
            .map_while(Result::ok)
        {
            let _ = send.send(line);
        }
    });
    // Far longer than finding the depth the tree can be shown to takes; the pixel's value at
    // depth 64 would take for ever.
    let warning = lines.recv_timeout(Duration::from_secs(120));
    let running = child.try_wait().unwrap().is_none();
    let _ = child.kill();
    let _ = child.wait();
    let warning = warning.expect("a warning while the pixel renders");
    assert!(running, "the process ended: {warning}");
    assert!(
        warning.starts_with("warning: a tree deeper than ")
            && warning
                .contains("the pixel's value is rendered at depth 64, which may take very long"),
        "{warning}"
    );
}

// ---------------------------------------------------------------------------------------
// Temporary files and awkward outputs

#[test]
fn long_output_names_symlinks_and_read_only_outputs() {
    let dir = scratch("outputs");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = write("outputs/s.yaml", SMALL);
    let render = |out: &Path| {
        run(&[
            OsStr::new("render"),
            scene.as_os_str(),
            OsStr::new("-o"),
            out.as_os_str(),
        ])
    };
    for len in [245, 250, 255] {
        let out = dir.join(format!("{}.png", "a".repeat(len - 4)));
        let r = render(&out);
        assert_eq!(r.code(), Some(0), "{len}-byte name: {}", r.stderr);
        assert!(out.exists());
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::{symlink, PermissionsExt};
        let target = dir.join("real.png");
        let link = dir.join("link.png");
        std::fs::write(&target, b"old").unwrap();
        let _ = std::fs::remove_file(&link);
        symlink("real.png", &link).unwrap();
        let r = render(&link);
        assert_eq!(r.code(), Some(0), "{}", r.stderr);
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(&std::fs::read(&target).unwrap()[1..4], b"PNG");

        let locked = dir.join("locked.png");
        let _ = std::fs::remove_file(&locked);
        std::fs::write(&locked, b"keep").unwrap();
        std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o444)).unwrap();
        let r = render(&locked);
        assert_eq!(r.code(), Some(2), "{}", r.stderr);
        assert!(r.stderr.contains("read-only"), "{}", r.stderr);
        assert_eq!(std::fs::read(&locked).unwrap(), b"keep");
    }
    // An output in a folder that is not there, or of a format raytree does not write, is
    // refused before the render, not after it: here a render of some 12 G samples, which would
    // outlast `run`'s 60 s and fail it as hung.
    let missing = dir.join("not-there");
    let path = |p: &Path| p.to_str().expect("a UTF-8 temporary path").to_string();
    let (scene, missing_png) = (path(&scene), path(&missing.join("out.png")));
    let jpg = path(&dir.join("out.jpg"));
    let in_a_file = format!("{scene}/out.png");
    let slash = path(&dir.join("out.png/"));
    let big = ["--width", "2000", "--height", "1500", "--spp", "4096"];
    let mut refused = vec![
        (missing_png.clone(), "there is no folder"),
        (jpg, "must end in .png, .ppm or .exr"),
        (in_a_file, "s.yaml is not a folder"),
        (slash, "ends in '/'"),
    ];
    // A folder no file can be made in, even by root.
    if cfg!(target_os = "linux") {
        refused.push(("/proc/raytree-out.png".into(), "cannot write: "));
    }
    for (out, says) in &refused {
        let r = run(&[&["render", &scene, "-o", out][..], &big].concat());
        assert_eq!(r.code(), Some(2), "{}", r.stderr);
        assert!(r.stderr.contains(says), "{}", r.stderr);
        assert!(!r.stderr.contains(".raytree-"), "{}", r.stderr);
    }
    // So is a sweep's table or plot, written after all its renders.
    let sweep = path(&missing.join("sweep.svg"));
    for flag in ["--csv", "--plot"] {
        let r = run(&[
            "bench", "sweep", &scene, "--knob", "spp", "--values", "65536", flag, &sweep,
        ]);
        assert_eq!(r.code(), Some(2), "{flag}: {}", r.stderr);
        assert!(r.stderr.contains("there is no folder"), "{}", r.stderr);
    }
    assert!(!missing.exists());
    assert!(temporaries(&dir).is_empty(), "{:?}", temporaries(&dir));
}

// ---------------------------------------------------------------------------------------
// Control characters

/// No raw control character reaches the terminal, whatever a scene file or a path holds.
#[test]
fn control_characters_in_names_and_paths_are_never_printed_raw() {
    let evil_name = write(
        "evil-name.yaml",
        "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], width: 8, height: 6 }\n\
         materials: { m: { kd: 1 } }\n\
         objects:\n  - { name: \"x\\e]0;pwned\\a\\e[2J\\nraytree: fake.yaml:1:1: all fine\", \
         sphere: { center: [0, 0, 0], radius: 1 }, material: m }\n",
    );
    let evil_key = write("evil-key.yaml", &format!("{SMALL}\"\\e[2Jbad\\nkey\": 1\n"));
    let evil_path = scratch("evil\u{1b}[2J\nraytree: fake.yaml:1:1: ok.yaml");
    let cases: Vec<Vec<&OsStr>> = vec![
        vec![
            "inspect".as_ref(),
            evil_name.as_os_str(),
            "--pixel".as_ref(),
            "8,6".as_ref(),
        ],
        vec![
            "inspect".as_ref(),
            evil_key.as_os_str(),
            "--pixel".as_ref(),
            "8,6".as_ref(),
        ],
        vec![
            "inspect".as_ref(),
            evil_path.as_os_str(),
            "--pixel".as_ref(),
            "8,6".as_ref(),
        ],
    ];
    for args in cases {
        let r = run(&args);
        assert!(r.sane().is_empty(), "{:?}", r.sane());
        for (name, text) in [("stdout", &r.stdout), ("stderr", &r.stderr)] {
            let raw: Vec<char> = text
                .chars()
                .filter(|c| c.is_control() && *c != '\n')
                .collect();
            assert!(raw.is_empty(), "{args:?}: raw {raw:?} on {name}: {text:?}");
        }
        assert_eq!(r.code(), Some(2), "{args:?}: {}", r.stderr);
        assert_eq!(r.stderr.lines().count(), 1, "{args:?}: {:?}", r.stderr);
    }
}

// ---------------------------------------------------------------------------------------
// Rays, answers, inspect against render

fn json(r: &Run) -> serde_json::Value {
    serde_json::from_str(&r.stdout).unwrap_or_else(|e| panic!("{e}: {}", r.stdout))
}

fn direction(v: &serde_json::Value) -> [f64; 3] {
    serde_json::from_value(v["tree"]["direction"].clone()).unwrap()
}

#[test]
fn ray_directions_are_normalised_safely() {
    let third = 1.0 / 3f64.sqrt();
    for (ray, want) in [
        ("0,0,-5:0,0,1e-320", [0.0, 0.0, 1.0]),
        ("0,0,-5:1e308,1e308,1e308", [third, third, third]),
        (
            "0,0,-5:-1e308,0,1e308",
            [-(0.5f64.sqrt()), 0.0, 0.5f64.sqrt()],
        ),
        ("0,0,-5:3e-310,4e-310,0", [0.6, 0.8, 0.0]),
    ] {
        let r = run(&["inspect", L08, "--ray", ray, "--format", "json"]);
        assert_eq!(r.code(), Some(0), "{ray}: {}", r.stderr);
        let d = direction(&json(&r));
        for k in 0..3 {
            assert!(
                (d[k] - want[k]).abs() < 1e-12,
                "{ray}: {d:?}, want {want:?}"
            );
        }
    }
}

#[test]
fn answers_that_are_not_answers_are_usage_errors() {
    let digits = "9".repeat(10_000);
    for (exercise, answer) in [
        ("lessons/10-csg c-empty", ","),
        ("lessons/10-csg c-empty", ";"),
        ("lessons/10-csg c-empty", " ; "),
        ("lessons/10-csg c-empty", ""),
        ("lessons/08-pixel-intensity pixel-p", "1e999"),
        ("lessons/08-pixel-intensity pixel-p", "inf"),
        ("lessons/08-pixel-intensity pixel-p", digits.as_str()),
        ("lessons/08-pixel-intensity pixel-p", ""),
    ] {
        let (lesson, id) = exercise.split_once(' ').unwrap();
        let r = run(&["check", lesson, "--exercise", id, "--answer", answer]);
        let shown: String = answer.chars().take(12).collect();
        assert_eq!(
            r.code(),
            Some(2),
            "`{shown}` for {id}: {} {}",
            r.stdout,
            r.stderr
        );
        assert_eq!(r.stderr.lines().count(), 1, "{}", r.stderr);
        assert!(
            r.stderr.len() < 300,
            "the answer is not echoed whole: {} bytes",
            r.stderr.len()
        );
    }
    let r = run(&[
        "check",
        "lessons/10-csg",
        "--exercise",
        "c-empty",
        "--answer",
        "none",
    ]);
    assert_eq!(r.code(), Some(0), "{}{}", r.stdout, r.stderr);
}

/// The value `inspect --pixel` reports is the pixel `render` writes: all its samples, through
/// the scene's filter, with the same seed.
#[test]
fn inspect_reports_the_rendered_value() {
    let gaussian = write(
        "gaussian.yaml",
        &SMALL.replace(
            "width: 16, height: 12 }",
            "width: 16, height: 12 }\nspp: 4\nantialias: jittered\nfilter: gaussian",
        ),
    );
    let cases: Vec<(PathBuf, u64, Vec<[u32; 2]>)> = vec![
        (
            PathBuf::from("lessons/13-antialiasing/grid-4.yaml"),
            0,
            vec![[1, 0], [0, 0], [2, 1]],
        ),
        (gaussian.clone(), 0, vec![[8, 6], [6, 5], [10, 7], [0, 0]]),
        (gaussian, 7, vec![[8, 6], [6, 5]]),
        (PathBuf::from(L08), 0, vec![[30, 30]]),
        (
            PathBuf::from("lessons/13-antialiasing/scene.yaml"),
            3,
            vec![[1, 0], [2, 1]],
        ),
    ];
    for (scene, seed, pixels) in cases {
        let exr = scratch("rendered.exr");
        let seed_arg = seed.to_string();
        let r = run(&[
            OsStr::new("render"),
            scene.as_os_str(),
            OsStr::new("-o"),
            exr.as_os_str(),
            OsStr::new("--seed"),
            OsStr::new(&seed_arg),
        ]);
        assert_eq!(r.code(), Some(0), "{}", r.stderr);
        let image = image::open(&exr).unwrap().into_rgb32f();
        for [x, y] in pixels {
            let pixel = format!("{x},{y}");
            let r = run(&[
                OsStr::new("inspect"),
                scene.as_os_str(),
                OsStr::new("--pixel"),
                OsStr::new(&pixel),
                OsStr::new("--seed"),
                OsStr::new(&seed_arg),
                OsStr::new("--format"),
                OsStr::new("json"),
            ]);
            assert_eq!(r.code(), Some(0), "{}", r.stderr);
            let color: [f64; 3] = serde_json::from_value(json(&r)["color"].clone()).unwrap();
            let rendered = image.get_pixel(x, y);
            for c in 0..3 {
                assert_eq!(
                    color[c] as f32,
                    rendered[c],
                    "{} pixel {pixel} seed {seed}: inspect {color:?}, render {rendered:?}",
                    scene.display()
                );
            }
        }
    }
    // The text form says which ray the tree is, and `--sample K` follows that sample.
    let grid = |extra: &[&str]| {
        let args = [
            "inspect",
            "lessons/13-antialiasing/grid-4.yaml",
            "--pixel",
            "1,0",
        ];
        run(&[&args[..], extra].concat())
    };
    let r = grid(&[]);
    assert!(
        r.stdout
            .starts_with("pixel (1, 0) = 0.5  as rendered: 4 samples (grid)"),
        "{}",
        r.stdout
    );
    assert!(
        r.stdout
            .contains("the tree of the ray through the pixel's centre"),
        "{}",
        r.stdout
    );
    let r = grid(&["--sample", "1"]);
    assert!(
        r.stdout
            .contains("the tree of sample 1 of 4, through (1.25, 0.25)"),
        "{}",
        r.stdout
    );
    // Adaptive antialiasing traces the corners and as many rays as its splits ask for: no
    // count of samples is claimed, only how far a pixel may be split (16 → 4 × 4) and when.
    let r = run(&["inspect", "lessons/13-antialiasing", "--pixel", "1,0"]);
    assert!(
        r.stdout.contains(
            "as rendered: adaptive: rays at the corners, squares split down to 4 × 4 where \
             corners differ by more than 0.3, box filter, seed 0"
        ),
        "{}",
        r.stdout
    );
    // The Graphviz figure's title says so too: its root's I is the sample's, not the pixel's.
    let r = grid(&["--sample", "1", "--format", "dot"]);
    assert!(
        r.stdout.contains(
            "label=\"pixel (1, 0): I = 0.5; the tree of sample 1 of 4, through (1.25, 0.25)"
        ),
        "{}",
        r.stdout
    );
    let r = grid(&["--sample", "5"]);
    assert_eq!(r.code(), Some(2), "{}", r.stderr);
}

// ---------------------------------------------------------------------------------------
// NaN from a light on a surface

/// A point light exactly on a wall with fatt = 1/d (the issue's case): the centre pixel's ray
/// hits the wall exactly at the light (the window camera's numbers are exact). Through the
/// Gaussian filter a NaN would spread to the pixel's neighbours.
#[test]
fn a_light_on_a_surface_gives_no_nan() {
    let scene = write(
        "light-on-surface.yaml",
        "camera: { eye: [0, 0, -10], u: [1, 0, 0], v: [0, 1, 0], w: [0, 0, 1], f: 10,\n\
         \x20         window: [-1, 1, 1, -1], width: 5, height: 5 }\n\
         filter: gaussian\nambient: 0.1\n\
         lights:\n  - { name: on-wall, point: [0, 0, 0], attenuation: [0, 1, 0] }\n\
         materials: { m: { ka: 1, kd: 0.7, ks: 0.4, shininess: 20 } }\n\
         objects:\n  - { name: wall, plane: { point: [0, 0, 0], normal: [0, 0, -1] }, material: m }\n",
    );
    let exr = scratch("light-on-surface.exr");
    let r = run(&[
        OsStr::new("render"),
        scene.as_os_str(),
        OsStr::new("-o"),
        exr.as_os_str(),
    ]);
    assert_eq!(r.code(), Some(0), "{}", r.stderr);
    assert!(!r.stderr.contains("not finite"), "{}", r.stderr);
    let image = image::open(&exr).unwrap().into_rgb32f();
    assert!(
        image
            .pixels()
            .all(|p| p.0.iter().all(|c| c.is_finite() && *c >= 0.0)),
        "{:?}",
        image.pixels().map(|p| p.0[0]).collect::<Vec<_>>()
    );
    let r = run(&[
        OsStr::new("inspect"),
        scene.as_os_str(),
        OsStr::new("--pixel"),
        OsStr::new("2,2"),
        OsStr::new("--format"),
        OsStr::new("json"),
    ]);
    assert_eq!(r.code(), Some(0), "{}", r.stderr);
    let v = json(&r);
    let hit: [f64; 3] = serde_json::from_value(v["tree"]["hit"]["point"].clone()).unwrap();
    assert_eq!(hit, [0.0, 0.0, 0.0], "the ray meets the wall at the light");
    let color: [f64; 3] = serde_json::from_value(v["tree"]["color"].clone()).unwrap();
    assert_eq!(
        color,
        [0.1, 0.1, 0.1],
        "only the ambient term: the light adds nothing there"
    );
}

// ---------------------------------------------------------------------------------------
// Warnings, bench

#[test]
fn a_mesh_of_degenerate_triangles_only_is_a_warning() {
    let dir = scratch("flat-mesh");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("flat.obj"),
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 3 2 1\n",
    )
    .unwrap();
    let scene = dir.join("s.yaml");
    std::fs::write(
        &scene,
        "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], width: 8, height: 6 }\n\
         materials: { m: { kd: 1 } }\n\
         objects:\n  - { name: flat, mesh: { file: flat.obj }, material: m }\n",
    )
    .unwrap();
    let r = run(&[
        OsStr::new("inspect"),
        scene.as_os_str(),
        OsStr::new("--pixel"),
        OsStr::new("4,3"),
    ]);
    assert_eq!(r.code(), Some(0), "{}", r.stderr);
    let shown = scene.display().to_string();
    assert!(
        r.stderr
            .starts_with(&format!("raytree: {shown}:4:33: warning: "))
            && r.stderr.contains("all 2 triangles"),
        "{}",
        r.stderr
    );
}

/// A sweep without `--reference` keeps the reference it renders in the user's cache folder
/// (`RAYTREE_CACHE`), in a `references/` folder only the user can enter, not under a guessable
/// name in the shared temporary folder; the next sweep of the same scene reads it back.
#[test]
fn bench_sweep_caches_its_reference_in_the_users_cache_folder() {
    let small = write("cached-sweep.yaml", SMALL);
    let cache = scratch("cache");
    let _ = std::fs::remove_dir_all(&cache);
    let sweep = || sweep_with_cache(&small, &cache);
    let first = sweep();
    assert!(
        first.stderr.contains("reference: rendered, cached in"),
        "{}",
        first.stderr
    );
    let references = cache.join("references");
    let kept: Vec<PathBuf> = std::fs::read_dir(&references)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert_eq!(kept.len(), 1, "{kept:?}");
    assert_eq!(kept[0].extension().unwrap(), "exr");
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(&references).unwrap().permissions().mode();
        assert_eq!(mode & 0o777, 0o700, "{mode:o}");
    }
    let written = std::fs::metadata(&kept[0]).unwrap().modified().unwrap();

    let second = sweep();
    assert!(
        second
            .stderr
            .contains(&format!("reference: {} (cached)", kept[0].display())),
        "{}",
        second.stderr
    );
    assert_eq!(
        std::fs::metadata(&kept[0]).unwrap().modified().unwrap(),
        written,
        "the cached reference was written again"
    );
    assert_eq!(first.stdout.lines().count(), second.stdout.lines().count());
}

/// `bench sweep SCENE --knob spp --values 1,4` with `cache` as the user's cache folder.
fn sweep_with_cache(scene: &Path, cache: &Path) -> Run {
    let child = command(&[
        OsStr::new("bench"),
        OsStr::new("sweep"),
        scene.as_os_str(),
        OsStr::new("--knob"),
        OsStr::new("spp"),
        OsStr::new("--values"),
        OsStr::new("1,4"),
    ])
    .env("RAYTREE_CACHE", cache)
    .stdout(Stdio::piped())
    .stderr(Stdio::piped())
    .spawn()
    .expect("raytree starts");
    let r = finish(child, Duration::from_secs(60));
    assert_eq!(r.code(), Some(0), "{}", r.stderr);
    r
}

/// The cached reference stands for the scene's image, so it is named by everything the image
/// depends on: a mesh or a texture changed under an unchanged scene file is a new reference,
/// rendered again, not the old one read back.
#[test]
fn bench_sweep_renders_its_reference_again_when_a_mesh_or_an_image_changes() {
    let dir = scratch("inputs-sweep");
    std::fs::create_dir_all(&dir).unwrap();
    let cache = scratch("inputs-cache");
    let _ = std::fs::remove_dir_all(&cache);
    let obj = |z: f64| format!("v -1 -1 0\nv 1 -1 0\nv 0 1 {z}\nf 1 2 3\n");
    let png = |grey: u8| {
        let image = image::RgbImage::from_pixel(2, 2, image::Rgb([grey, grey, grey]));
        image.save(dir.join("grey.png")).unwrap();
    };
    std::fs::write(dir.join("tri.obj"), obj(0.0)).unwrap();
    png(200);
    let scene = dir.join("s.yaml");
    std::fs::write(
        &scene,
        "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], width: 16, height: 12 }\n\
         lights: [ { point: [2, 3, -4] } ]\n\
         materials: { m: { color: { image: grey.png }, kd: 1 } }\n\
         objects: [ { name: tri, mesh: { file: tri.obj }, material: m } ]\n",
    )
    .unwrap();
    let rendered = |r: &Run| r.stderr.contains("reference: rendered, cached in");
    let cached = |r: &Run| r.stderr.contains("(cached)");
    let first = sweep_with_cache(&scene, &cache);
    assert!(rendered(&first), "{}", first.stderr);
    let again = sweep_with_cache(&scene, &cache);
    assert!(cached(&again), "{}", again.stderr);

    std::fs::write(dir.join("tri.obj"), obj(0.5)).unwrap();
    let moved = sweep_with_cache(&scene, &cache);
    assert!(rendered(&moved), "a changed mesh: {}", moved.stderr);

    png(60);
    let darker = sweep_with_cache(&scene, &cache);
    assert!(rendered(&darker), "a changed image: {}", darker.stderr);
    assert!(cached(&sweep_with_cache(&scene, &cache)));
}

/// `RAYTREE_CACHE=` and `RAYTREE_DATA=`, set but empty, count as not set (as XDG's variables
/// do): the platform's folders under HOME are used, and nothing is written into the current
/// folder, which an empty path would otherwise name.
#[test]
fn empty_cache_and_data_variables_name_the_platforms_folders() {
    let root = scratch("empty-variables");
    let _ = std::fs::remove_dir_all(&root);
    let (home, work) = (root.join("home"), root.join("work"));
    std::fs::create_dir_all(&home).unwrap();
    std::fs::create_dir_all(&work).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_raytree"))
        .args(["check", "05-reflection", "--exercise", "mirror-local"])
        .args(["--answer", "0.23"])
        .current_dir(&work)
        .env("HOME", &home)
        .env("RAYTREE_CACHE", "")
        .env("RAYTREE_DATA", "")
        .env_remove("XDG_CACHE_HOME")
        .env_remove("XDG_DATA_HOME")
        .env_remove("RAYTREE_LESSONS")
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let written: Vec<_> = std::fs::read_dir(&work).unwrap().collect();
    assert!(written.is_empty(), "{written:?}");
    assert!(home.join(".local/share/raytree/progress.json").is_file());
    assert!(home.join(".cache/raytree").is_dir());
}

/// A knob that cannot change the scene's image is refused before any render, naming the knob
/// and why: every row would read "exact" and say nothing of the knob.
#[test]
fn bench_sweep_refuses_a_knob_the_scene_does_not_have() {
    let small = write("idle-knobs.yaml", SMALL);
    let small = small.to_str().unwrap();
    for (scene, knob, values, says) in [
        (L08, "glossy", "1,2", "no glossy or frosted"),
        (small, "glossy", "1,2", "no glossy or frosted"),
        (small, "depth", "1,2", "nothing reflects or refracts"),
        (small, "adaptive", "0,0.1", "nothing reflects or refracts"),
    ] {
        let r = run(&["bench", "sweep", scene, "--knob", knob, "--values", values]);
        assert!(r.sane().is_empty(), "{knob}: {:?}", r.sane());
        assert_eq!(r.code(), Some(2), "{knob}: {}", r.stderr);
        assert_eq!(r.stderr.lines().count(), 1, "{knob}: {}", r.stderr);
        assert!(r.stderr.contains(&format!("--knob {knob}")), "{}", r.stderr);
        assert!(r.stderr.contains(says), "{knob}: {}", r.stderr);
        assert!(r.stdout.is_empty(), "{knob}: {}", r.stdout);
        assert!(r.elapsed < Duration::from_secs(10));
    }
}

#[test]
fn bench_sweep_refuses_what_render_refuses() {
    let small = write("sweep.yaml", SMALL);
    let small = small.to_str().unwrap();
    for (knob, values) in [
        ("spp", "0"),
        ("spp", "1.5"),
        ("spp", "100000"),
        ("depth", "65"),
        ("depth", "0"),
        ("adaptive", "1.5"),
        ("aa-threshold", "-1"),
        ("glossy", "2000"),
        ("spp", "NaN"),
    ] {
        let r = run(&[
            "bench",
            "sweep",
            small,
            "--knob",
            knob,
            "--values",
            &format!("1,{values}"),
        ]);
        assert_eq!(
            r.code(),
            Some(2),
            "--knob {knob} --values {values}: {}",
            r.stderr
        );
        assert!(r.stderr.contains(&format!("--knob {knob}")), "{}", r.stderr);
        assert!(r.elapsed < Duration::from_secs(10));
    }
}

/// `--csv FILE` saves the table: the same columns in the same order, the efficiency
/// 1/(seconds·MSE) included, and on each line the values the table printed (rounded there).
#[test]
fn bench_sweep_csv_has_the_printed_tables_columns() {
    let small = write("csv-sweep.yaml", SMALL);
    let small = small.to_str().unwrap();
    let reference = scratch("csv-reference.exr");
    let reference = reference.to_str().unwrap();
    let r = run(&["render", small, "-o", reference, "--spp", "64"]);
    assert_eq!(r.code(), Some(0), "{}", r.stderr);
    let csv = scratch("sweep.csv");
    let r = run(&[
        "bench",
        "sweep",
        small,
        "--knob",
        "spp",
        "--values",
        "1,4",
        "--reference",
        reference,
        "--csv",
        csv.to_str().unwrap(),
    ]);
    assert_eq!(r.code(), Some(0), "{}", r.stderr);
    let table: Vec<Vec<&str>> = r
        .stdout
        .lines()
        .map(|l| l.split_whitespace().collect())
        .collect();
    let text = std::fs::read_to_string(&csv).unwrap();
    let lines: Vec<Vec<&str>> = text.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(
        lines[0],
        [
            "spp",
            "seconds",
            "rays",
            "rmse",
            "rel_mse",
            "max_abs",
            "psnr",
            "efficiency"
        ]
    );
    assert_eq!(
        table[0],
        [
            "spp",
            "seconds",
            "rays",
            "RMSE",
            "rel",
            "MSE",
            "max",
            "|err|",
            "PSNR",
            "1/(s·MSE)"
        ],
        "{}",
        r.stdout
    );
    assert_eq!(lines.len(), 3, "{text}");
    assert_eq!(table.len(), 3, "{}", r.stdout);
    for (printed, saved) in table[1..].iter().zip(&lines[1..]) {
        assert_eq!(printed.len(), saved.len(), "{printed:?} {saved:?}");
        // The value, rays and efficiency are printed whole; the others to a few decimals.
        for column in [0, 2, 7] {
            assert_eq!(printed[column], saved[column], "{printed:?} {saved:?}");
        }
        // Seconds keep three significant digits: three decimals, more under 0.1 s.
        let seconds: f64 = saved[1].parse().unwrap();
        let second_decimals = (2 - seconds.log10().floor() as i64).max(3) as usize;
        for (column, decimals) in [(1, second_decimals), (3, 5), (4, 5), (5, 4), (6, 2)] {
            let x: f64 = saved[column].parse().unwrap();
            assert_eq!(
                format!("{x:.decimals$}"),
                printed[column],
                "{printed:?} {saved:?}"
            );
        }
    }
}

/// `bench sweep` of the small scene at 1 and 4 spp (with `args`) against an EXR reference
/// rendered at `spp` (files named after `name`): its standard output.
fn sweep_of_spp_1_and_4(name: &str, spp: u32, args: &[&str]) -> String {
    sweep_of_spp_1_and_4_against(name, "exr", spp, args)
}

/// As `sweep_of_spp_1_and_4`, with the reference written as `format` (exr or png).
fn sweep_of_spp_1_and_4_against(name: &str, format: &str, spp: u32, args: &[&str]) -> String {
    let small = write(&format!("{name}-sweep.yaml"), SMALL);
    let small = small.to_str().unwrap();
    let reference = scratch(&format!("{name}-reference.{format}"));
    let reference = reference.to_str().unwrap();
    let r = run(&["render", small, "-o", reference, "--spp", &spp.to_string()]);
    assert_eq!(r.code(), Some(0), "{}", r.stderr);
    let mut all = vec!["bench", "sweep", small, "--knob", "spp", "--values", "1,4"];
    all.extend_from_slice(&["--reference", reference]);
    all.extend_from_slice(args);
    let r = run(&all);
    assert_eq!(r.code(), Some(0), "{args:?}: {}", r.stderr);
    r.stdout
}

/// `--runs 3` times three renders (after an untimed one) and reports their median: the error
/// and the rays counted are those of a single render, since every render is the same image;
/// `--runs 0` is refused with a usage message.
#[test]
fn bench_sweep_takes_the_median_of_its_runs() {
    let sweep = |runs: &str| {
        let doc: serde_json::Value = serde_json::from_str(&sweep_of_spp_1_and_4(
            "runs",
            64,
            &["--runs", runs, "--format", "json"],
        ))
        .unwrap();
        doc["rows"]
            .as_array()
            .unwrap()
            .iter()
            .map(|row| {
                (
                    row["value"].clone(),
                    row["rays"].clone(),
                    row["rmse"].clone(),
                )
            })
            .collect::<Vec<_>>()
    };
    let once = sweep("1");
    assert_eq!(once.len(), 2);
    assert_eq!(sweep("3"), once);
    let small = write("runs-sweep.yaml", SMALL);
    let refused = run(&[
        "bench",
        "sweep",
        small.to_str().unwrap(),
        "--knob",
        "spp",
        "--values",
        "1",
        "--runs",
        "0",
    ]);
    assert_eq!(refused.code(), Some(2), "{}", refused.stderr);
    assert!(refused.stderr.contains("--runs"), "{}", refused.stderr);
}

/// A PNG holds display values: clamped to [0, 1] and rounded to 8-bit sRGB. A render is
/// measured against one as `render` would write it, so the render a PNG was written from is
/// exact, though the small scene's highlight is brighter than 1 (ka·Ia + kd + ks = 1.3 in red)
/// and no `--clamp` is given; a coarser render is not.
#[test]
fn bench_sweep_measures_a_png_reference_as_the_png_holds_it() {
    let doc: serde_json::Value = serde_json::from_str(&sweep_of_spp_1_and_4_against(
        "png",
        "png",
        4,
        &["--format", "json"],
    ))
    .unwrap();
    let rows = doc["rows"].as_array().unwrap();
    assert_eq!(rows[1]["value"], 4.0);
    assert_eq!(rows[1]["exact"], true, "{doc}");
    assert_eq!(rows[1]["rmse"], 0.0, "{doc}");
    assert_eq!(rows[0]["exact"], false, "{doc}");
    // Display values differ by at most 1.
    let worst = rows[0]["max_abs"].as_f64().unwrap();
    assert!(worst > 0.0 && worst <= 1.0, "{doc}");
}

/// A render equal to an EXR reference that raytree wrote of the same image is exact: the EXR
/// keeps f32, and the sweep rounds its render to f32 before measuring it, so the row has no
/// error (RMSE 0, no PSNR, efficiency "exact") rather than the f32 rounding's tiny one. The
/// JSON rows carry the table's efficiency, 1/(seconds·MSE), and whether the row is exact.
#[test]
fn bench_sweep_finds_its_own_exr_reference_exact() {
    let sweep = |format: &str| sweep_of_spp_1_and_4("exact", 4, &["--format", format]);
    let table = sweep("text");
    let efficiencies: Vec<&str> = table
        .lines()
        .skip(1)
        .map(|l| l.split_whitespace().last().unwrap())
        .collect();
    assert_eq!(efficiencies.len(), 2, "{table}");
    assert_eq!(efficiencies[1], "exact", "{table}");
    assert!(efficiencies[0].parse::<f64>().unwrap() > 0.0, "{table}");
    // PSNR, the second column from the right: infinite for the exact row.
    let psnr = |row: usize| {
        table
            .lines()
            .nth(1 + row)
            .unwrap()
            .split_whitespace()
            .rev()
            .nth(1)
    };
    assert_eq!(psnr(1), Some("∞"), "{table}");

    let doc: serde_json::Value = serde_json::from_str(&sweep("json")).unwrap();
    let rows = doc["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 2);
    let (rough, same) = (&rows[0], &rows[1]);
    assert_eq!(same["value"], 4.0);
    assert_eq!(same["rmse"], 0.0, "{same}");
    assert_eq!(same["max_abs"], 0.0, "{same}");
    assert!(same["efficiency"].is_null(), "{same}");
    assert!(same["psnr"].is_null(), "{same}");
    assert_eq!(same["exact"], true, "{same}");
    assert_eq!(rough["exact"], false, "{rough}");
    let (seconds, rmse) = (
        rough["seconds"].as_f64().unwrap(),
        rough["rmse"].as_f64().unwrap(),
    );
    assert!(rmse > 0.0, "{rough}");
    let db = rough["psnr"].as_f64().unwrap();
    assert!((db + 20.0 * rmse.log10()).abs() < 1e-9, "{rough}");
    let shown: f64 = psnr(0).unwrap().parse().unwrap();
    assert!((shown - db).abs() <= 0.005, "{table}");
    let efficiency = rough["efficiency"].as_f64().unwrap();
    let expected = 1.0 / (seconds * rmse * rmse);
    assert!(
        (efficiency - expected).abs() <= 1e-9 * expected,
        "{efficiency} against 1/(seconds·MSE) = {expected}"
    );
}

/// `bench scaling` with a size it has no row for is a usage error that names the flag and its
/// range, before anything is measured: subdivisions 3 to 8 (an icosphere of 9 is past the
/// scene's triangle budget; the mesh rows start at 3), and 10 to 100 000 spheres (the rows are
/// 10, 100, …, 100 000: below 10 no row is named, above 100 000 none is added).
#[test]
fn bench_scaling_refuses_sizes_it_has_no_row_for_at_once() {
    let cases = [
        ("--max-subdivisions", ["9", "2", "0"].as_slice(), "3..=8"),
        (
            "--max-spheres",
            ["5", "0", "9", "100001"].as_slice(),
            "10..=100000",
        ),
    ];
    for (flag, values, range) in cases {
        for v in values {
            let mut args = vec!["bench", "scaling", "--max-brute", "10"];
            args.extend(["--max-spheres", "10", "--max-subdivisions", "3"]);
            let at = args.iter().position(|a| a == &flag).unwrap();
            args[at + 1] = v;
            let r = run(&args);
            assert!(r.sane().is_empty(), "{flag} {v}: {:?}", r.sane());
            assert_eq!(r.code(), Some(2), "{flag} {v}: {}", r.stderr);
            assert!(
                r.stderr.contains(flag) && r.stderr.contains(range),
                "{flag} {v}: {}",
                r.stderr
            );
            assert!(!r.stderr.contains("mesh:"), "{flag} {v}: {}", r.stderr);
            assert!(r.stdout.is_empty(), "{flag} {v}: {}", r.stdout);
        }
    }
}

/// `--max-brute` bounds the sphere rows measured without the BVH, `--max-brute-triangles` the
/// mesh rows, each as given: the 1 280-triangle mesh is measured by brute force up to a bound
/// of 1 280 and not below it.
#[test]
fn bench_scaling_measures_brute_force_up_to_the_bounds_given() {
    let brute = |spheres: &str, triangles: &str| -> Vec<bool> {
        let r = run(&[
            "bench",
            "scaling",
            "--max-spheres",
            "100",
            "--max-brute",
            spheres,
            "--max-brute-triangles",
            triangles,
            "--max-subdivisions",
            "3",
            "--format",
            "json",
        ]);
        assert_eq!(r.code(), Some(0), "{}", r.stderr);
        let doc: serde_json::Value = serde_json::from_str(&r.stdout).unwrap();
        let rows = doc["rows"].as_array().unwrap();
        let kinds: Vec<_> = rows
            .iter()
            .map(|r| (r["kind"].clone(), r["n"].clone()))
            .collect();
        assert_eq!(
            kinds,
            [("spheres", 10), ("spheres", 100), ("mesh", 1280)]
                .map(|(k, n)| (serde_json::json!(k), serde_json::json!(n)))
        );
        rows.iter()
            .map(|r| r["brute_ns_per_ray"].is_f64())
            .collect()
    };
    // 10 spheres have no BVH: their one time is brute force's, whatever the bound.
    assert_eq!(brute("100", "1280"), [true, true, true]);
    assert_eq!(brute("99", "1279"), [true, false, false]);
}

/// On a terminal both streams show: each row of the scaling table must be printed once.
#[test]
fn bench_scaling_prints_each_row_once() {
    let r = run(&[
        "bench",
        "scaling",
        "--max-spheres",
        "100",
        "--max-brute",
        "100",
        "--max-subdivisions",
        "3",
    ]);
    assert_eq!(r.code(), Some(0), "{}", r.stderr);
    let both = format!("{}{}", r.stdout, r.stderr);
    let rows = |kind: &str, n: &str| {
        both.lines()
            .filter(|l| {
                let mut w = l.split_whitespace();
                w.next() == Some(kind) && w.next() == Some(n)
            })
            .count()
    };
    for (kind, n) in [("spheres", "10"), ("spheres", "100"), ("mesh", "1280")] {
        assert_eq!(rows(kind, n), 1, "{kind} {n}:\n{both}");
    }
    assert_eq!(both.matches("BVH ns/ray").count(), 1, "{both}");
}

// ---------------------------------------------------------------------------------------
// The parallel loader

/// An object named `x[` at the end of a list over 64 KiB and a light named `y]` after it:
/// brackets in plain scalars, not a collection. Every thread count loads the same scene.
#[test]
fn a_scene_loads_the_same_for_every_thread_count() {
    let mut text = String::from(
        "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], width: 16, height: 12 }\n\
         ambient: 0.2\nmaterials: { m: { color: [1, 0.5, 0.25], ka: 1, kd: 0.8 } }\nobjects:\n",
    );
    for i in 0..1500 {
        text += &format!(
            "  - {{ sphere: {{ center: [{}, {}, 30], radius: 0.05 }}, material: m }}\n",
            i % 40,
            i / 40
        );
    }
    text += "  - name: x[\n    sphere: { center: [0, 0, 0], radius: 1.5 }\n    material: m\n";
    text += "lights:\n  - name: y]\n    point: [-2, 3, -4]\n";
    assert!(text.len() > 64 * 1024);
    let scene = write("brackets.yaml", &text);
    let mut images = vec![];
    for threads in ["1", "2", "3"] {
        let out = scratch(&format!("brackets-{threads}.png"));
        let r = run(&[
            OsStr::new("render"),
            scene.as_os_str(),
            OsStr::new("-o"),
            out.as_os_str(),
            OsStr::new("--threads"),
            OsStr::new(threads),
        ]);
        assert_eq!(r.code(), Some(0), "--threads {threads}: {}", r.stderr);
        images.push(std::fs::read(&out).unwrap());
    }
    assert!(images.iter().all(|i| *i == images[0]));
}

/// The budget of objects is checked before the objects are compiled, with where and how to
/// raise it.
#[test]
fn the_objects_budget_names_the_first_object_over_it() {
    use raytree::scene::{parse, Limits};
    let mut text = String::from(
        "camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nmaterials: { m: { kd: 1 } }\nobjects:\n",
    );
    for i in 0..12 {
        text += &format!("  - {{ sphere: {{ center: [{i}, 0, 0], radius: 0.5 }}, material: m }}\n");
    }
    let limits = Limits {
        max_objects: 10,
        ..Limits::default()
    };
    let e = parse(&text, "many.yaml", None, &limits).unwrap_err();
    assert_eq!((e.line, e.column), (14, 5), "{e}");
    assert!(
        e.message.contains("more than 10 objects") && e.message.contains("--allow-huge"),
        "{e}"
    );
    assert!(parse(&text, "many.yaml", None, &Limits::default()).is_ok());
}

/// On a terminal a scene error also shows the line it points at, with a caret under the
/// column; piped, it stays one line (scripts and the tests above read that line).
#[cfg(unix)]
#[test]
fn on_a_terminal_a_scene_error_shows_its_line_and_a_caret() {
    if Command::new("script").arg("--version").output().is_err() {
        println!("skipping: `script` is not on PATH");
        return;
    }
    let scene = write(
        "caret.yaml",
        "camera: { eye: [0, 0, -5], look_at: [0, 0, 0] }\nbackground: [0.4, 0.4\nspp: 4\n",
    );
    let inner = format!(
        "'{}' inspect '{}' --pixel 0,0",
        bin().display(),
        scene.display()
    );
    let out = Command::new("script")
        .args(["-qec", &inner, "/dev/null"])
        .env("NO_COLOR", "1")
        .output()
        .unwrap();
    let shown = String::from_utf8_lossy(&out.stdout).replace('\r', "");
    let lines: Vec<&str> = shown.lines().collect();
    assert!(lines.len() >= 3, "{shown}");
    assert!(
        lines[0].ends_with(
            ":2:13: the list opened here (`[`) is never closed with `]`: it runs into line 3"
        ),
        "{shown}"
    );
    assert_eq!(lines[1], "  2 | background: [0.4, 0.4");
    assert_eq!(lines[2], "    |             ^");
}

/// An explicit ray's origin is held to the numbers a scene file may hold (finite, within
/// ±1e100), and a large coordinate is printed with an exponent, not as hundreds of digits.
#[test]
fn an_explicit_ray_takes_the_numbers_a_scene_takes() {
    for ray in ["-1e200,0,0:1,0,0", "0,1e101,-5:0,0,1", "nan,0,0:0,0,1"] {
        let o = run(&["inspect", "lessons/08-pixel-intensity", "--ray", ray]);
        assert_eq!(o.code(), Some(2), "{ray}");
        assert!(o.stderr.contains("within ±1e100"), "{ray}: {}", o.stderr);
    }
    // A direction is only a direction: `ray_directions_are_normalised_safely` takes any size.
    let o = run(&[
        "inspect",
        "lessons/08-pixel-intensity",
        "--ray",
        "0,0,-5:0,0,inf",
    ]);
    assert_eq!(o.code(), Some(2));
    assert!(o.stderr.contains("three finite numbers"), "{}", o.stderr);
    let o = run(&[
        "inspect",
        "lessons/08-pixel-intensity",
        "--ray",
        "-1e100,3,0:1,0,0",
    ]);
    assert_eq!(o.code(), Some(0), "{}", o.stderr);
    assert!(o.stdout.contains("(-1e100, 3, 0)"), "{}", o.stdout);
    assert!(o.stdout.lines().all(|l| l.len() < 200), "{}", o.stdout);
}
