//! A terminal that hangs up while the explorer runs (its window closed, the SSH connection
//! lost, the tmux server killed). The descriptor then stays readable while every read returns
//! nothing, and crossterm's reader retries at once, for ever: the event loop is never given
//! back the control it would need to notice, and the process would spin on a core. A watchdog
//! thread asks poll(2) whether standard input has hung up, without reading it (a key typed
//! stays for the event loop), and ends the process as the hangup's SIGHUP would.

use std::time::Duration;

/// How often the watchdog looks at the terminal.
const EVERY: Duration = Duration::from_millis(250);

/// How long the event loop is given to finish on its own (when the hangup's SIGHUP reached it
/// between two reads) before the watchdog ends the process.
const GRACE: Duration = Duration::from_millis(250);

/// Whether the terminal on standard input has hung up or is gone: poll(2) reports POLLHUP,
/// POLLERR or POLLNVAL for it. Nothing is read.
pub fn hung_up() -> bool {
    let mut fd = libc::pollfd {
        fd: libc::STDIN_FILENO,
        events: 0,
        revents: 0,
    };
    // SAFETY: one valid pollfd, a zero timeout.
    let n = unsafe { libc::poll(&mut fd, 1, 0) };
    n > 0 && fd.revents & (libc::POLLHUP | libc::POLLERR | libc::POLLNVAL) != 0
}

/// Starts the watchdog for the rest of the process. There is no terminal left to restore when
/// it acts, so it only ends the process, dying of SIGHUP as a program without a handler would.
pub fn watch() -> std::io::Result<()> {
    std::thread::Builder::new()
        .name("hangup watchdog".into())
        .spawn(|| {
            while !hung_up() {
                std::thread::sleep(EVERY);
            }
            std::thread::sleep(GRACE);
            let _ = signal_hook::low_level::emulate_default_handler(libc::SIGHUP);
            std::process::exit(128 + libc::SIGHUP);
        })
        .map(drop)
}
