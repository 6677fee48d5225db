//! The real binary in a real terminal: a tmux server of a test's own, killed when dropped.

use std::process::Command;
use std::time::{Duration, Instant};

/// A tmux server named after its test (and this process), with one session, "explore".
pub struct Tmux {
    socket: String,
}

impl Tmux {
    pub fn new(name: &str) -> Tmux {
        Tmux {
            socket: format!("raytree-{name}-{}", std::process::id()),
        }
    }

    pub fn run(&self, args: &[&str]) -> String {
        let out = Command::new("tmux")
            .arg("-L")
            .arg(&self.socket)
            .args(args)
            .output()
            .expect("tmux runs");
        String::from_utf8_lossy(&out.stdout).into_owned()
    }

    /// Runs `script` with `sh -c` in a detached 100 × 30 session, in the project's folder.
    pub fn start(&self, script: &str) {
        self.run(&[
            "new-session",
            "-d",
            "-s",
            "explore",
            "-x",
            "100",
            "-y",
            "30",
            "-c",
            env!("CARGO_MANIFEST_DIR"),
            "sh",
            "-c",
            script,
        ]);
    }

    pub fn capture(&self) -> String {
        self.run(&["capture-pane", "-p", "-t", "explore"])
    }

    /// A tmux format of the session's pane (`#{alternate_on}`, `#{pane_pid}`, …).
    pub fn flag(&self, f: &str) -> String {
        self.run(&["display", "-p", "-t", "explore", f])
            .trim()
            .to_string()
    }

    /// Waits until every one of `what` is on the screen at once. A frame reaches the terminal
    /// in pieces, top to bottom, so a capture can hold half of one: wait for all the text the
    /// assertions need, not for the first line of the frame.
    pub fn wait_for(&self, what: &[&str]) -> String {
        let start = Instant::now();
        loop {
            let screen = self.capture();
            if what.iter().all(|w| screen.contains(w)) {
                return screen;
            }
            if start.elapsed() > Duration::from_secs(20) {
                panic!("{what:?} never all appeared; the screen:\n{screen}");
            }
            std::thread::sleep(Duration::from_millis(100));
        }
    }

    /// Waits until `done` holds, for `what` to be named if it never does.
    pub fn wait_until(&self, what: &str, done: impl Fn(&Tmux) -> bool) {
        let start = Instant::now();
        while !done(self) {
            if start.elapsed() > Duration::from_secs(30) {
                panic!("{what} never happened; the screen:\n{}", self.capture());
            }
            std::thread::sleep(Duration::from_millis(50));
        }
    }
}

impl Drop for Tmux {
    fn drop(&mut self) {
        self.run(&["kill-server"]);
    }
}

/// Whether tmux is there; the tests that need it say they skip when it is not.
pub fn have_tmux() -> bool {
    let ok = Command::new("tmux").arg("-V").output().is_ok();
    if !ok {
        println!("skipping: tmux is not on PATH");
    }
    ok
}
