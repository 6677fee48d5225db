//! Entering and leaving the full-screen terminal. Every way out restores it: the guard's drop
//! (normal exit, errors, unwinding) and a panic hook that restores before the panic message is
//! printed, so the message is readable. Ctrl-Z and SIGTSTP restore it too while the explorer is
//! stopped, and `fg` brings the full screen back (`suspend`).

use std::io::{self, Stdout};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Once};

use crossterm::cursor::Show;
use crossterm::event::{DisableMouseCapture, EnableMouseCapture};
use crossterm::execute;
use crossterm::terminal::{
    disable_raw_mode, enable_raw_mode, EnterAlternateScreen, LeaveAlternateScreen,
};
use ratatui::backend::CrosstermBackend;
use ratatui::Terminal;

pub type Term = Terminal<CrosstermBackend<Stdout>>;

/// Puts the terminal back as it was: cooked mode, main screen, no mouse reports, cursor shown.
/// Safe to call more than once.
pub fn restore() -> io::Result<()> {
    let raw = disable_raw_mode();
    execute!(
        io::stdout(),
        DisableMouseCapture,
        LeaveAlternateScreen,
        Show
    )?;
    raw
}

fn install_panic_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        let ui_thread = std::thread::current().id();
        std::panic::set_hook(Box::new(move |info| {
            // A panic in the render threads is caught and reported inside the explorer; only
            // the UI thread's panic ends it, so only then is the terminal restored and the
            // message printed.
            if std::thread::current().id() != ui_thread {
                return;
            }
            let _ = restore();
            previous(info);
        }));
    });
}

/// Restores the terminal when dropped.
pub struct Guard {
    pub term: Term,
}

impl Drop for Guard {
    fn drop(&mut self) {
        let _ = restore();
    }
}

/// Stops the explorer as Ctrl-Z stops a program in a shell: the terminal restored, the process
/// stopped (the shell takes the terminal back), and on `fg` (SIGCONT) raw mode, the alternate
/// screen and mouse capture again, cleared so that the next frame is drawn whole.
pub fn suspend(term: &mut Term) -> io::Result<()> {
    restore()?;
    // Returns once the process is continued.
    signal_hook::low_level::emulate_default_handler(signal_hook::consts::SIGTSTP)?;
    enable_raw_mode()?;
    execute!(io::stdout(), EnterAlternateScreen, EnableMouseCapture)?;
    term.clear()
}

/// SIGTSTP from outside (`kill -TSTP`; in raw mode Ctrl-Z is a key, not the signal), noted
/// for the event loop to `suspend` with the terminal restored, rather than obeyed at once.
pub struct Suspension {
    asked: Arc<AtomicBool>,
    id: signal_hook::SigId,
}

impl Suspension {
    pub fn catch() -> io::Result<Suspension> {
        let asked = Arc::new(AtomicBool::new(false));
        let id = signal_hook::flag::register(signal_hook::consts::SIGTSTP, Arc::clone(&asked))?;
        Ok(Suspension { asked, id })
    }

    /// Whether a SIGTSTP came since the last call.
    pub fn asked(&self) -> bool {
        self.asked.swap(false, Ordering::Relaxed)
    }
}

impl Drop for Suspension {
    fn drop(&mut self) {
        signal_hook::low_level::unregister(self.id);
    }
}

/// Raw mode, the alternate screen and mouse capture.
pub fn setup() -> io::Result<Guard> {
    install_panic_hook();
    enable_raw_mode()?;
    let entered = execute!(io::stdout(), EnterAlternateScreen, EnableMouseCapture);
    if let Err(e) = entered {
        let _ = restore();
        return Err(e);
    }
    match Terminal::new(CrosstermBackend::new(io::stdout())) {
        Ok(mut term) => {
            let _ = term.clear();
            Ok(Guard { term })
        }
        Err(e) => {
            let _ = restore();
            Err(e)
        }
    }
}
