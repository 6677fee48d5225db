//! Entering and leaving the full-screen terminal. Every way out restores it: the guard's drop
//! (normal exit, errors, unwinding) and a panic hook that restores before the panic message is
//! printed, so the message is readable.

use std::io::{self, Stdout};
use std::sync::Once;

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
