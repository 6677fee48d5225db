//! How long the explorer makes its user wait, measured headlessly: the app model is driven by
//! the same messages keys send, and the preview passes the worker thread would run are timed
//! here, on this thread (`raytree bench explorer`).

use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use super::worker::{render_pass, wants_draft, Pass};
use super::{update, App, Msg};
use crate::render::preview::ColorMode;

/// The waits of one scene in the explorer, medians over the runs.
#[derive(Clone, Debug)]
pub struct Latency {
    /// The preview's size in pixels (a half-block cell is one pixel wide and two high).
    pub preview: (u32, u32),
    /// A depth key (`-`/`+`) to the draft preview on screen: the tree traced again, then a
    /// quarter of the resolution with one sample per pixel. `None` when the preview is too
    /// small to be worth a draft.
    pub draft: Option<Duration>,
    /// A depth key to the full preview on screen (after the draft, as the worker renders
    /// them), with the scene's samples per pixel (at most 4).
    pub full: Duration,
    /// A picked pixel to its ray tree on screen (traced, recorded and laid out).
    pub pick: Duration,
    /// The scene file changed on disk to the full preview on screen: read, parsed and compiled
    /// again on the reload thread, the tree traced again, then the draft and the full preview.
    pub reload: Duration,
}

/// Opens `target` (a scene file or a lesson folder) in a `size` terminal and measures `runs`
/// depth changes, pixel picks and reloads of the scene file.
pub fn measure(target: &Path, size: (u16, u16), runs: usize) -> Result<Latency, String> {
    let mut app = App::open(Some(target), ColorMode::TrueColor)?;
    update(&mut app, Msg::Resize(size.0, size.1));
    app.render_now();
    let (w, h) = app.preview.size;
    if w == 0 || h == 0 {
        return Err(format!("{}: no preview to measure", target.display()));
    }
    let (mut drafts, mut fulls, mut picks, mut reloads) = (vec![], vec![], vec![], vec![]);
    let cancel = AtomicBool::new(false);
    for run in 0..runs.max(1) {
        // Down and up in turn, so the depth stays near the scene's own; at a limit, the
        // other way.
        let keys = if run % 2 == 0 {
            [Msg::DepthDown, Msg::DepthUp]
        } else {
            [Msg::DepthUp, Msg::DepthDown]
        };
        let start = Instant::now();
        let mut job = None;
        for key in keys {
            update(&mut app, key);
            job = app.take_job();
            if job.is_some() {
                break;
            }
        }
        let Some(job) = job else {
            return Err(format!(
                "{}: depth keys asked for no new preview",
                target.display()
            ));
        };
        let (draft, full) = preview(&mut app, &job, start, &cancel);
        drafts.extend(draft);
        fulls.push(full);
        // Pixels spread over the image, a different one each run.
        let (iw, ih) = app.image_size();
        let k = run as u32 + 1;
        let pixel = ((iw * k / (runs as u32 + 1)).min(iw - 1), ih / 2);
        let start = Instant::now();
        update(&mut app, Msg::Pick(pixel.0, pixel.1));
        picks.push(start.elapsed());

        let before = app.file.scene.clone();
        app.file.mark_changed();
        let start = Instant::now();
        update(&mut app, Msg::Tick);
        let replaced = match (&before, &app.file.scene) {
            (Some(a), Some(b)) => !std::sync::Arc::ptr_eq(a, b),
            _ => false,
        };
        if !replaced {
            return Err(match &app.file.error {
                Some(e) => e.clone(),
                None => format!("{}: the scene did not reload", target.display()),
            });
        }
        let Some(job) = app.take_job() else {
            return Err(format!(
                "{}: a reload asked for no new preview",
                target.display()
            ));
        };
        reloads.push(preview(&mut app, &job, start, &cancel).1);
    }
    Ok(Latency {
        preview: (w, h),
        draft: (!drafts.is_empty()).then(|| median(&mut drafts)),
        full: median(&mut fulls),
        pick: median(&mut picks),
        reload: median(&mut reloads),
    })
}

/// Renders `job` as the worker does, the draft (when it wants one) and then the full preview,
/// and hands the result to the app: the times from `start` to each on screen.
fn preview(
    app: &mut App,
    job: &super::worker::Job,
    start: Instant,
    cancel: &AtomicBool,
) -> (Option<Duration>, Duration) {
    let draft = wants_draft(job).then(|| {
        render_pass(job, Pass::Draft, cancel, &|_| {});
        start.elapsed()
    });
    let done = render_pass(job, Pass::Final, cancel, &|_| {});
    let full = start.elapsed();
    if let Some(done) = done {
        update(app, Msg::Rendered(done));
    }
    (draft, full)
}

fn median(times: &mut [Duration]) -> Duration {
    times.sort();
    times[times.len() / 2]
}
