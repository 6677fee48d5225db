//! The terminal preview: the last image received and the job that will replace it. The render
//! worker is not here: a job waits in `job` for the event loop to hand it to the worker (or
//! for `App::render_now` to render it on the spot, which is what the tests do).

use std::sync::Arc;
use std::time::Duration;

use super::{Note, Tone};
use crate::render::Image;
use crate::scene::Scene;
use crate::stats::Stats;
use crate::tui::worker::{Done, Job, Pass};

#[derive(Default)]
pub struct Preview {
    pub image: Option<Image>,
    pub pass: Option<Pass>,
    /// The resolution wanted now (the preview pane's cells × 2 rows).
    pub size: (u32, u32),
    pub generation: u64,
    /// A job not yet handed to the worker.
    pub job: Option<Job>,
    /// True from a job's creation until its final pass arrives.
    pub running: bool,
    /// Rows done and rows in the pass running.
    pub rows: (u32, u32),
    /// The maximum depth of the last preview asked for.
    pub depth: Option<u32>,
    /// Statistics of the image shown.
    pub stats: Option<Stats>,
    pub elapsed: Option<Duration>,
    /// Mark where the tree's rays hit, on the image (`m`).
    pub marks: bool,
}

impl Preview {
    /// Asks for a new preview of `scene` at the current size.
    pub fn request(&mut self, scene: &Arc<Scene>, depth: u32) {
        let (w, h) = self.size;
        if w == 0 || h == 0 {
            return;
        }
        self.generation += 1;
        self.depth = Some(depth);
        self.job = Some(Job {
            generation: self.generation,
            scene: Arc::clone(scene),
            depth,
            width: w,
            height: h,
            spp: scene.spp.clamp(1, 4),
        });
        self.running = true;
        self.rows = (0, h);
    }

    /// Render progress: rows done of the rows in the pass running.
    pub fn progress(&mut self, generation: u64, rows: u32, total: u32) {
        if generation == self.generation && self.running {
            self.rows = (rows, total);
        }
    }

    /// A pass from the worker; one of an older job is dropped.
    pub fn receive(&mut self, done: Done) -> Option<Note> {
        if done.generation != self.generation {
            return None;
        }
        if done.pass == Pass::Final {
            self.running = false;
        }
        self.image = Some(done.image);
        self.pass = Some(done.pass);
        self.stats = Some(done.stats);
        self.elapsed = Some(done.elapsed);
        let why = done.failure?;
        self.running = false;
        Some((format!("the preview renderer crashed: {why}"), Tone::Bad))
    }

    /// Forgets the image shown (a new scene is on its way).
    pub fn clear(&mut self) {
        self.image = None;
        self.stats = None;
    }
}
