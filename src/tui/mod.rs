//! The terminal explorer (`raytree explore`): pick a pixel of the preview, see its ray tree,
//! every term of every intensity, the CSG segment lists, depth by depth, beside a lesson.
//!
//! Headless core: one `App` model composed of the parts in state/, a `Msg` enum (msg.rs) and
//! `update` (app.rs); keys to messages (input.rs); pane geometry (layout.rs) and word wrap
//! (wrap.rs, markdown.rs) shared by the model and the drawing; drawing as pure functions of
//! `&App`, one per pane (ui/); the preview renderer on its own thread (worker.rs); terminal
//! setup and restore (terminal.rs), and a watchdog that ends the explorer when its terminal
//! hangs up (hangup.rs). Everything but the last three runs without a terminal, which is how
//! tests/explorer.rs drives it.

pub mod app;
pub(crate) mod hangup;
pub mod input;
pub mod latency;
pub mod layout;
pub(crate) mod markdown;
pub(crate) mod msg;
pub(crate) mod state;
pub(crate) mod terminal;
pub(crate) mod tree;
pub mod ui;
pub mod worker;
pub(crate) mod wrap;

use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::{Duration, Instant};

pub use app::{update, App};
pub use msg::Msg;
pub use state::ray_tree::{FREE_DEPTH, TREE_BUDGET};

use crate::render::preview::ColorMode;
use crate::scene::Limits;
use state::ray_tree::MAX_DEPTH;

/// How the explorer starts.
#[derive(Clone, Debug, Default)]
pub struct Options {
    /// A scene file or a lesson folder; None opens the lesson list.
    pub target: Option<PathBuf>,
    /// Force the ASCII preview.
    pub ascii: bool,
    /// Pick this pixel (x, y) at the start.
    pub pixel: Option<[u32; 2]>,
    /// Start with this maximum depth (rays per path) instead of the scene's.
    pub depth: Option<u32>,
    /// The budgets scenes are loaded within (raised by `--allow-huge`).
    pub limits: Limits,
}

/// Runs the explorer until the user quits.
pub fn run(options: Options) -> Result<(), String> {
    let color = if options.ascii {
        ColorMode::Ascii
    } else {
        ColorMode::detect()
    };
    let mut app = App::open_within(options.target.as_deref(), color, options.limits)?;
    if let Some(d) = options.depth {
        if !(1..=MAX_DEPTH).contains(&d) {
            return Err(format!(
                "--depth must be between 1 and {MAX_DEPTH}, got {d}"
            ));
        }
        app = app.with_depth(d);
    }
    if let Some([x, y]) = options.pixel {
        let (w, h) = app.image_size();
        if x >= w || y >= h {
            return Err(format!("pixel {x},{y} is outside the {w} × {h} image"));
        }
        update(&mut app, Msg::Pick(x, y));
    }
    // After loading, so a bad scene is reported the same way everywhere.
    if !std::io::stdout().is_terminal() || !std::io::stdin().is_terminal() {
        return Err(
            "explore needs a terminal (use `raytree inspect` or `raytree preview` in scripts)"
                .into(),
        );
    }
    // A reload waits only briefly: a large scene arrives on a later tick, the keys meanwhile.
    app.file.reload_wait = RELOAD_WAIT;
    // SIGTERM, SIGHUP and SIGINT end the explorer as `q` does, the terminal restored, and then
    // the process as the signal asks.
    let signals =
        crate::signals::Signals::catch().map_err(|e| format!("cannot catch signals: {e}"))?;
    let suspension =
        terminal::Suspension::catch().map_err(|e| format!("cannot catch signals: {e}"))?;
    let mut guard = terminal::setup().map_err(|e| format!("cannot set up the terminal: {e}"))?;
    hangup::watch().map_err(|e| format!("cannot watch the terminal: {e}"))?;
    let result = event_loop(&mut guard.term, &mut app, signals.stop(), &suspension);
    drop(guard);
    signals.finish();
    result.map_err(|e| format!("terminal error: {e}"))
}

/// How long a tick waits for a scene being reloaded before drawing again.
const RELOAD_WAIT: Duration = Duration::from_millis(15);

fn event_loop(
    term: &mut terminal::Term,
    app: &mut App,
    stop: &std::sync::atomic::AtomicBool,
    suspension: &terminal::Suspension,
) -> std::io::Result<()> {
    use crossterm::event;
    let mut worker = worker::Worker::spawn();
    let size = term.size()?;
    update(app, Msg::Resize(size.width, size.height));
    let mut last_tick = Instant::now();
    let mut last_progress = (0, 0, 0);
    let mut dirty = true;
    while !app.quit && !stop.load(std::sync::atomic::Ordering::Relaxed) {
        if suspension.asked() {
            terminal::suspend(term)?;
            dirty = true;
        }
        if let Some(job) = app.take_job() {
            worker.submit(job);
        }
        if dirty {
            let size = term.size()?;
            if (size.width, size.height) != app.size {
                update(app, Msg::Resize(size.width, size.height));
                if let Some(job) = app.take_job() {
                    worker.submit(job);
                }
            }
            term.draw(|f| ui::draw(f, app))?;
            dirty = false;
            if std::env::var_os("RAYTREE_EXPLORE_TEST_PANIC").is_some_and(|v| v != "worker") {
                // tests/explorer.rs checks that a panic leaves a usable terminal behind.
                panic!("RAYTREE_EXPLORE_TEST_PANIC is set: a deliberate panic");
            }
        }
        let timeout = app::WATCH_INTERVAL
            .saturating_sub(last_tick.elapsed())
            .min(Duration::from_millis(40));
        if event::poll(timeout)? {
            // Handle everything queued before drawing again (key repeat, mouse drags).
            loop {
                let ev = event::read()?;
                if input::is_suspend(&ev) {
                    terminal::suspend(term)?;
                } else if let Some(msg) = input::event(app, &ev) {
                    update(app, msg);
                }
                dirty = true;
                if app.quit || !event::poll(Duration::ZERO)? {
                    break;
                }
            }
        }
        while let Some(done) = worker.try_recv() {
            update(app, Msg::Rendered(done));
            dirty = true;
        }
        let progress = worker.progress();
        if progress != last_progress {
            last_progress = progress;
            update(app, Msg::Progress(progress.0, progress.1, progress.2));
            dirty = true;
        }
        if last_tick.elapsed() >= app::WATCH_INTERVAL {
            last_tick = Instant::now();
            let before = (app.file.error.clone(), app.preview.generation);
            update(app, Msg::Tick);
            if before != (app.file.error.clone(), app.preview.generation) {
                dirty = true;
            }
        }
    }
    Ok(())
}
