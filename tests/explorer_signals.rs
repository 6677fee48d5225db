//! The explorer stopped by a signal and its scene file turned into something else: the
//! terminal is restored as after `q`, and a reload never holds up the keys.
//!
//! `RAYTREE_BIN=path` runs the tmux checks against another build of raytree.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

mod common;

use common::tmux::{have_tmux, Tmux};
use raytree::render::preview::ColorMode;
use raytree::tui::{update, App, Msg};

fn bin() -> PathBuf {
    std::env::var_os("RAYTREE_BIN")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_BIN_EXE_raytree")))
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir()
        .join(format!("raytree-explorer-signals-{}", std::process::id()))
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The children of a process (Linux).
fn children(pid: &str) -> Vec<String> {
    std::fs::read_to_string(format!("/proc/{pid}/task/{pid}/children"))
        .unwrap_or_default()
        .split_whitespace()
        .map(str::to_string)
        .collect()
}

/// SIGTERM, SIGHUP and SIGINT sent to the explorer: it leaves the alternate screen, shows the
/// cursor, turns mouse reporting off and puts the terminal back in cooked mode, then dies of
/// the signal (the shell sees 128 + its number).
#[test]
fn a_signal_restores_the_terminal_as_q_does() {
    if !have_tmux() {
        return;
    }
    for (signal, number) in [("TERM", 15), ("HUP", 1), ("INT", 2)] {
        let dir = scratch(&format!("sig{signal}"));
        let (status, stty) = (dir.join("status"), dir.join("stty"));
        let tmux = Tmux::new(&format!("sig{signal}"));
        tmux.start(&format!(
            "'{}' explore lessons/08-pixel-intensity; echo \"exit $?\" > '{}'; stty -a > '{}'; echo DONE; sleep 60",
            bin().display(),
            status.display(),
            stty.display()
        ));
        tmux.wait_until("the explorer's screen", |t| {
            t.flag("#{alternate_on}") == "1" && t.flag("#{mouse_any_flag}") == "1"
        });
        std::thread::sleep(Duration::from_millis(300));
        let shell = tmux.flag("#{pane_pid}");
        let explorer = children(&shell);
        assert_eq!(explorer.len(), 1, "the shell's children: {explorer:?}");
        let sent = Command::new("kill")
            .args([&format!("-{signal}"), &explorer[0]])
            .status()
            .unwrap();
        assert!(sent.success());
        tmux.wait_until("the shell's DONE", |t| t.capture().contains("DONE"));
        let code = std::fs::read_to_string(&status).unwrap();
        assert_eq!(code.trim(), format!("exit {}", 128 + number), "SIG{signal}");
        let modes = std::fs::read_to_string(&stty).unwrap();
        let words: Vec<&str> = modes.split_whitespace().collect();
        assert!(
            words.contains(&"icanon") && words.contains(&"echo"),
            "SIG{signal}: {modes}"
        );
        assert_eq!(
            tmux.flag("#{alternate_on}"),
            "0",
            "SIG{signal}: alternate screen"
        );
        assert_eq!(tmux.flag("#{mouse_any_flag}"), "0", "SIG{signal}: mouse");
        assert_eq!(tmux.flag("#{mouse_button_flag}"), "0", "SIG{signal}: mouse");
        assert_eq!(
            tmux.flag("#{mouse_standard_flag}"),
            "0",
            "SIG{signal}: mouse"
        );
        assert_eq!(
            tmux.flag("#{cursor_flag}"),
            "1",
            "SIG{signal}: cursor shown"
        );
    }
}

// ---------------------------------------------------------------------------------------
// Reloading off the UI thread (driven without a terminal)

const SCENE: &str = "camera: { eye: [0, 0, -5], look_at: [0, 0, 0], width: 16, height: 12 }\n\
                     materials: { m: { kd: 1 } }\n\
                     lights: [ { point: [2, 3, -4] } ]\n\
                     objects:\n  - { name: ball, sphere: { center: [0, 0, 0], radius: 1 }, material: m }\n";

fn open(path: &Path) -> App {
    let mut app = App::open(Some(path), ColorMode::Ascii).expect("opens");
    update(&mut app, Msg::Resize(80, 24));
    app
}

/// Ticks until `done` or 20 s; each tick must return at once.
fn tick_until(app: &mut App, done: impl Fn(&App) -> bool) {
    let start = Instant::now();
    while !done(app) {
        let tick = Instant::now();
        update(app, Msg::Tick);
        assert!(
            tick.elapsed() < Duration::from_millis(500),
            "a tick took {:?}",
            tick.elapsed()
        );
        assert!(start.elapsed() < Duration::from_secs(20), "never done");
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// The watched file swapped for a FIFO (no writer: opening it for reading would wait forever)
/// or for a link to /dev/zero (reading it would never end): the explorer says so at once and
/// keeps the last good scene; `q` still quits.
#[cfg(unix)]
/// Whether a process is still running: not gone, and not a zombie waiting for its parent.
fn running(pid: &str) -> bool {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).unwrap_or_default();
    // "pid (name) S ...": the state follows the name's closing parenthesis.
    let state = stat.rsplit_once(')').map(|(_, rest)| rest.trim_start());
    state.is_some_and(|s| !s.starts_with('Z') && !s.starts_with('X'))
}

/// The terminal hangs up under the explorer (the tmux server killed, as a closed window or a
/// lost SSH connection would): the explorer ends, rather than living on with its reader
/// spinning on the dead terminal.
#[test]
fn a_terminal_that_hangs_up_ends_the_explorer() {
    if !have_tmux() {
        return;
    }
    let tmux = Tmux::new("hangup");
    tmux.start(&format!(
        "'{}' explore lessons/08-pixel-intensity; sleep 60",
        bin().display()
    ));
    tmux.wait_until("the explorer's screen", |t| {
        t.flag("#{alternate_on}") == "1"
    });
    let shell = tmux.flag("#{pane_pid}");
    let explorer = children(&shell);
    assert_eq!(explorer.len(), 1, "the shell's children: {explorer:?}");
    tmux.run(&["kill-server"]);
    let start = Instant::now();
    while running(&explorer[0]) {
        if start.elapsed() > Duration::from_secs(10) {
            let _ = Command::new("kill").args(["-KILL", &explorer[0]]).status();
            panic!("the explorer outlived its terminal by 10 s");
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

#[test]
fn a_watched_file_swapped_for_a_fifo_or_a_device_never_freezes_the_explorer() {
    let dir = scratch("swapped");
    let path = dir.join("scene.yaml");
    std::fs::write(&path, SCENE).unwrap();
    let mut app = open(&path);
    app.file.reload_wait = Duration::from_millis(20);
    for swap in ["fifo", "zero"] {
        std::fs::remove_file(&path).unwrap();
        match swap {
            "fifo" => assert!(Command::new("mkfifo")
                .arg(&path)
                .status()
                .unwrap()
                .success()),
            _ => std::os::unix::fs::symlink("/dev/zero", &path).unwrap(),
        }
        tick_until(&mut app, |a| a.file.error.is_some());
        let error = app.file.error.clone().unwrap();
        assert!(error.contains("not a regular file"), "{swap}: {error}");
        assert!(app.file.scene.is_some(), "the last good scene stays");
        // Back to a good file: it loads again and the error goes.
        std::fs::remove_file(&path).unwrap();
        std::fs::write(&path, SCENE.replace("radius: 1", "radius: 1.5")).unwrap();
        tick_until(&mut app, |a| a.file.error.is_none() && !a.file.loading());
    }
    update(&mut app, Msg::Quit);
    assert!(app.quit);
}

/// A large scene saved while the explorer runs: ticks return at once while it loads on its
/// own thread, and it is adopted when it has loaded.
#[test]
fn reloading_a_large_scene_never_holds_up_a_tick() {
    let dir = scratch("large");
    let path = dir.join("scene.yaml");
    std::fs::write(&path, SCENE).unwrap();
    let mut app = open(&path);
    app.file.reload_wait = Duration::ZERO;
    let mut large = SCENE.to_string();
    for i in 0..20_000 {
        large += &format!(
            "  - {{ sphere: {{ center: [{}, {}, 4], radius: 0.01 }}, material: m }}\n",
            i % 200,
            i / 200
        );
    }
    std::fs::write(&path, &large).unwrap();
    let tick = Instant::now();
    update(&mut app, Msg::Tick);
    assert!(
        tick.elapsed() < Duration::from_millis(200),
        "{:?}",
        tick.elapsed()
    );
    tick_until(&mut app, |a| {
        a.file
            .scene
            .as_ref()
            .is_some_and(|s| s.objects.len() == 20_001)
    });
    assert!(app.file.error.is_none());
}
