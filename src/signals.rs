//! The signals that ask a program to stop (SIGINT, SIGTERM, SIGHUP), noted instead of obeyed at
//! once while raytree has something to undo: a temporary file to remove, a terminal to
//! restore. The work polls `stop()` and winds down; `finish` then ends the process as the
//! signal's default action would have, so the caller (a shell, a script) sees it die of that
//! signal.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{mpsc, Arc};
use std::time::{Duration, Instant};

use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
use signal_hook::SigId;

/// How long work with nothing to undo has to wind down after a signal (`Signals::impatient`).
const GRACE: Duration = Duration::from_secs(1);

/// How often the watch over such work looks for a signal.
const POLL: Duration = Duration::from_millis(50);

/// The signals caught while this is alive.
pub struct Signals {
    stop: Arc<AtomicBool>,
    which: Arc<AtomicUsize>,
    ids: Vec<SigId>,
}

impl Signals {
    /// Catches SIGINT, SIGTERM and SIGHUP from now until `finish` (or the drop).
    pub fn catch() -> std::io::Result<Signals> {
        let stop = Arc::new(AtomicBool::new(false));
        let which = Arc::new(AtomicUsize::new(0));
        let mut ids = Vec::new();
        for signal in [SIGINT, SIGTERM, SIGHUP] {
            ids.push(signal_hook::flag::register_usize(
                signal,
                Arc::clone(&which),
                signal as usize,
            )?);
            ids.push(signal_hook::flag::register(signal, Arc::clone(&stop))?);
        }
        Ok(Signals { stop, which, ids })
    }

    /// Set once a signal has arrived: the flag long work polls to give up.
    pub fn stop(&self) -> &AtomicBool {
        &self.stop
    }

    /// The signal that arrived, if one did.
    pub fn caught(&self) -> Option<i32> {
        match self.which.load(Ordering::Relaxed) {
            0 => None,
            s => Some(s as i32),
        }
    }

    /// Runs `work`, during which there is nothing to undo (no file begun, no terminal taken),
    /// watched: where a signal arrives and `work` has not returned `GRACE` later, the process
    /// ends as the signal asks, there and then. Work polls `stop` between its pieces, and one
    /// piece can take hours: a pixel whose ray tree doubles at every one of 64 levels.
    pub fn impatient<R>(&self, work: impl FnOnce() -> R) -> R {
        let (done, watched) = mpsc::channel::<()>();
        std::thread::scope(|scope| {
            scope.spawn(move || {
                let mut since = None;
                // Woken every `POLL` to look at the flag; `work` returning ends the watch.
                while let Err(mpsc::RecvTimeoutError::Timeout) = watched.recv_timeout(POLL) {
                    if !self.stop.load(Ordering::Relaxed) {
                        continue;
                    }
                    let since = *since.get_or_insert_with(Instant::now);
                    if let Some(signal) = self.caught().filter(|_| since.elapsed() >= GRACE) {
                        let _ = signal_hook::low_level::emulate_default_handler(signal);
                        std::process::exit(128 + signal);
                    }
                }
            });
            let result = work();
            drop(done);
            result
        })
    }

    /// Stops catching; if a signal arrived, ends the process as that signal would have.
    pub fn finish(self) {
        let caught = self.caught();
        drop(self);
        if let Some(signal) = caught {
            let _ = signal_hook::low_level::emulate_default_handler(signal);
            // Not reached for these signals; if it were, exit as a shell reports them.
            std::process::exit(128 + signal);
        }
    }
}

/// Stops noting the signals. They are not obeyed by default again (the handler stays, with
/// nothing to do): keep `Signals` for the whole command and end it with `finish`.
impl Drop for Signals {
    fn drop(&mut self) {
        for id in self.ids.drain(..) {
            signal_hook::low_level::unregister(id);
        }
    }
}
