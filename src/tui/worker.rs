//! The preview renderer: a thread that renders a draft (a quarter of the resolution) and then
//! the full preview, so keys never wait for it. A newer job cancels the one running.

use std::sync::atomic::{AtomicBool, AtomicU32, AtomicU64, Ordering};
use std::sync::mpsc::{channel, Receiver, Sender};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use crate::render::{render_through, Image, RenderOptions};
use crate::scene::Scene;
use crate::stats::Stats;

/// One preview to render.
#[derive(Clone)]
pub struct Job {
    /// Results of older generations are ignored.
    pub generation: u64,
    /// The scene to render.
    pub scene: Arc<Scene>,
    /// Rays per path (the explorer's current depth).
    pub depth: u32,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Samples per pixel of the final pass.
    pub spp: u32,
}

impl std::fmt::Debug for Job {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Job")
            .field("generation", &self.generation)
            .field("depth", &self.depth)
            .field("width", &self.width)
            .field("height", &self.height)
            .field("spp", &self.spp)
            .finish()
    }
}

/// Which of a job's two passes a result is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pass {
    /// A quarter of the resolution, one sample per pixel: something to look at at once.
    Draft,
    /// The full resolution with the job's samples per pixel.
    Final,
}

/// A finished pass.
#[derive(Clone, Debug)]
pub struct Done {
    /// The job's generation (results of older generations are ignored).
    pub generation: u64,
    /// Draft or final.
    pub pass: Pass,
    /// The rendered image.
    pub image: Image,
    /// Counters of the rays traced.
    pub stats: Stats,
    /// Wall-clock time of the pass.
    pub elapsed: Duration,
    /// The render panicked: why (the preview goes dark, the explorer keeps running).
    pub failure: Option<String>,
}

/// Whether a job is worth a draft pass first.
pub fn wants_draft(job: &Job) -> bool {
    job.width as u64 * job.height as u64 >= 2048
}

/// Renders one pass of a job; None when cancelled.
pub fn render_pass(
    job: &Job,
    pass: Pass,
    cancel: &AtomicBool,
    on_row: &(dyn Fn(u32) + Sync),
) -> Option<Done> {
    let start = Instant::now();
    let (w, h, spp) = match pass {
        Pass::Draft => ((job.width / 4).max(1), (job.height / 4).max(1), 1),
        Pass::Final => (job.width.max(1), job.height.max(1), job.spp.max(1)),
    };
    let camera = job.scene.camera.resized(w, h);
    let options = RenderOptions {
        max_depth: job.depth,
        spp,
        ..RenderOptions::of(&job.scene)
    };
    // A bug in the renderer must not take the terminal down with it: catch the panic here and
    // let the explorer say what happened.
    let rendered = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        if std::env::var("RAYTREE_EXPLORE_TEST_PANIC").as_deref() == Ok("worker") {
            panic!("a deliberate panic in the render thread (RAYTREE_EXPLORE_TEST_PANIC=worker)");
        }
        render_through(&job.scene, camera, options, on_row, cancel)
    }));
    let (image, stats, failure) = match rendered {
        Ok(result) => {
            let (image, stats) = result?;
            (image, stats, None)
        }
        Err(payload) => {
            let why = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            (Image::new(w, h), Stats::default(), Some(why))
        }
    };
    Some(Done {
        generation: job.generation,
        pass,
        image,
        stats,
        elapsed: start.elapsed(),
        failure,
    })
}

/// How far the running job is.
#[derive(Default)]
struct Progress {
    generation: AtomicU64,
    rows: AtomicU32,
    total: AtomicU32,
}

/// The preview renderer on its own thread: jobs go in, finished passes come out, and a new job
/// cancels the one running.
pub struct Worker {
    jobs: Option<Sender<(Job, Arc<AtomicBool>)>>,
    results: Receiver<Done>,
    cancel: Arc<AtomicBool>,
    progress: Arc<Progress>,
    handle: Option<JoinHandle<()>>,
}

impl Worker {
    /// Starts the render thread.
    pub fn spawn() -> Worker {
        let (job_tx, job_rx) = channel::<(Job, Arc<AtomicBool>)>();
        let (done_tx, done_rx) = channel();
        let progress = Arc::new(Progress::default());
        let p = Arc::clone(&progress);
        let handle = std::thread::Builder::new()
            .name("preview".into())
            .spawn(move || work(job_rx, done_tx, p))
            .expect("spawn the preview thread");
        Worker {
            jobs: Some(job_tx),
            results: done_rx,
            cancel: Arc::new(AtomicBool::new(false)),
            progress,
            handle: Some(handle),
        }
    }

    /// Starts a job, cancelling the one running.
    pub fn submit(&mut self, job: Job) {
        self.cancel.store(true, Ordering::Relaxed);
        self.cancel = Arc::new(AtomicBool::new(false));
        if let Some(tx) = &self.jobs {
            let _ = tx.send((job, Arc::clone(&self.cancel)));
        }
    }

    /// The next finished pass, if one is waiting (never blocks).
    pub(crate) fn try_recv(&self) -> Option<Done> {
        self.results.try_recv().ok()
    }

    /// Waits for the next finished pass (tests and measurements).
    pub fn recv_timeout(&self, timeout: Duration) -> Option<Done> {
        self.results.recv_timeout(timeout).ok()
    }

    /// (generation, rows done, rows in the pass running).
    pub fn progress(&self) -> (u64, u32, u32) {
        (
            self.progress.generation.load(Ordering::Relaxed),
            self.progress.rows.load(Ordering::Relaxed),
            self.progress.total.load(Ordering::Relaxed),
        )
    }
}

impl Drop for Worker {
    fn drop(&mut self) {
        self.cancel.store(true, Ordering::Relaxed);
        self.jobs = None;
        if let Some(h) = self.handle.take() {
            let _ = h.join();
        }
    }
}

fn work(jobs: Receiver<(Job, Arc<AtomicBool>)>, done: Sender<Done>, progress: Arc<Progress>) {
    while let Ok(mut next) = jobs.recv() {
        // Only the newest job matters.
        while let Ok(newer) = jobs.try_recv() {
            next = newer;
        }
        let (job, cancel) = next;
        let passes: &[Pass] = if wants_draft(&job) {
            &[Pass::Draft, Pass::Final]
        } else {
            &[Pass::Final]
        };
        for &pass in passes {
            if cancel.load(Ordering::Relaxed) {
                break;
            }
            let rows = match pass {
                Pass::Draft => (job.height / 4).max(1),
                Pass::Final => job.height.max(1),
            };
            progress.rows.store(0, Ordering::Relaxed);
            progress.total.store(rows, Ordering::Relaxed);
            progress.generation.store(job.generation, Ordering::Relaxed);
            let on_row = |_| {
                progress.rows.fetch_add(1, Ordering::Relaxed);
            };
            match render_pass(&job, pass, &cancel, &on_row) {
                Some(d) => {
                    if done.send(d).is_err() {
                        return;
                    }
                }
                None => break,
            }
        }
    }
}
