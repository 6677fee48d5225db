//! The picked pixel and its ray tree: the depth it is traced to, level stepping, and (in
//! tree_state.rs) which rays are open and selected. An exercise about a ray that is no pixel's
//! aims the tree at that ray instead, until a pixel is picked again.
//!
//! The tree is traced by the tracer itself (`Tracer::inspect`), so what is shown is the
//! computation that coloured the pixel. The methods that change the pixel, the depth or the
//! level leave the tree as it was: `App` calls `retrace` next, once, and then the parts that
//! follow the tree (the CSG panel).

use glam::DVec3;
use ratatui::layout::Rect;

use super::details::{self, DetailRow};
use super::tree_state::TreeState;
use super::{max_scroll, Note, Tone};
use crate::geometry::Ray;
use crate::sampling::Rng;
use crate::scene::Scene;
use crate::stats::Stats;
use crate::trace::{text, RayNode, Tracer};
use crate::tui::layout::inner;
use crate::tui::msg::Msg;
use crate::tui::tree::{self, Row};

/// The deepest recursion the explorer is asked for: the scene format's own limit
/// (`Limits::max_depth`), so a scene is explored at the depth it renders at.
pub const MAX_DEPTH: u32 = 64;

use crate::trace::budget::{affordable_depth, budget_note};
pub use crate::trace::budget::{FREE_DEPTH, TREE_BUDGET};

/// The most rays the picked pixel's tree may hold for the preview to go deeper than
/// `FREE_DEPTH` with it: the preview traces thousands of pixels, each about as deep.
pub const PREVIEW_RAYS: u64 = 1_000;

pub struct RayTree {
    pixel: (u32, u32),
    /// An exercise's ray, traced instead of the picked pixel's.
    ray: Option<Ray>,
    /// The maximum depth asked for (by the scene, the keys or an exercise).
    asked: u32,
    /// The maximum depth the tree is traced with: `asked`, unless a tree that deep would pass
    /// `TREE_BUDGET` rays (`affordable_depth`).
    traced: u32,
    /// The depth was chosen (keys, an exercise), so a reloaded scene does not reset it.
    depth_from_user: bool,
    /// Level stepping: the tree shown is traced with this maximum depth.
    level: Option<u32>,
    /// Root intensity at levels 1..=depth (in level stepping).
    partials: Vec<DVec3>,
    /// The tree at `depth`.
    full: Option<RayNode>,
    /// The tree at `level` while stepping.
    level_tree: Option<RayNode>,
    stats: Stats,
    pixel_value: Option<(DVec3, String)>,
    /// A path-traced pixel's estimate and some of the paths it averages.
    paths: Option<Paths>,
    /// Intensities are not shown (a lesson's hidden solutions, not yet answered).
    hidden: bool,
    /// Open and selected rays, scrolling.
    view: TreeState,
}

/// What a path tracer made of a pixel: its rendered estimate over `spp` paths, and the first
/// paths replayed with the same random numbers, each as its value and the surfaces it met.
#[derive(Clone, Debug, PartialEq)]
pub struct Paths {
    pub estimate: DVec3,
    pub spp: u32,
    pub shown: Vec<(DVec3, String)>,
}

/// Sampled paths shown above a path-traced pixel's tree.
pub const PATHS_SHOWN: u32 = 3;

impl Default for RayTree {
    fn default() -> RayTree {
        RayTree {
            pixel: (0, 0),
            ray: None,
            asked: 1,
            traced: 1,
            depth_from_user: false,
            level: None,
            partials: vec![],
            full: None,
            level_tree: None,
            stats: Stats::default(),
            pixel_value: None,
            paths: None,
            hidden: false,
            view: TreeState::default(),
        }
    }
}

// --- What the panes show

impl RayTree {
    /// The picked pixel.
    pub fn pixel(&self) -> (u32, u32) {
        self.pixel
    }

    /// The exercise's ray the tree follows instead of the picked pixel's, if any.
    pub fn aimed_ray(&self) -> Option<&Ray> {
        self.ray.as_ref()
    }

    /// A path-traced pixel's estimate and sampled paths.
    pub fn paths(&self) -> Option<&Paths> {
        self.paths.as_ref()
    }

    /// Intensities are hidden until the lesson's exercises about them are answered.
    pub fn hidden(&self) -> bool {
        self.hidden
    }

    pub fn set_hidden(&mut self, hidden: bool) {
        self.hidden = hidden;
    }

    /// The lines the tree pane shows above the tree: the rendered value, or the path tracer's
    /// estimate and paths, and the level line.
    pub fn head_lines(&self) -> usize {
        let paths = self.paths.as_ref().map_or(0, |p| p.shown.len() + 2);
        paths + self.level.is_some() as usize + self.pixel_value.is_some() as usize
    }

    /// The maximum depth the tree is traced with.
    pub fn depth(&self) -> u32 {
        self.traced
    }

    /// The maximum depth asked for, where the tree stops short of it (`TREE_BUDGET`).
    pub fn depth_cut_from(&self) -> Option<u32> {
        (self.traced < self.asked).then_some(self.asked)
    }

    /// The maximum depth the preview renders at: the tree's, or `FREE_DEPTH` where the tree
    /// goes deeper and holds more than `PREVIEW_RAYS` rays.
    pub fn preview_depth(&self) -> u32 {
        if self.traced > FREE_DEPTH && self.stats.rays() > PREVIEW_RAYS {
            FREE_DEPTH
        } else {
            self.traced
        }
    }

    /// "depth 5", or "depth 23 of 40" where the tree stops short of the depth asked for, and
    /// the preview's depth where it is not the tree's.
    pub fn depth_label(&self) -> String {
        let mut label = format!("depth {}", self.traced);
        if let Some(asked) = self.depth_cut_from() {
            label += &format!(" of {asked}");
        }
        if self.preview_depth() != self.traced {
            label += &format!(" (preview {})", self.preview_depth());
        }
        label
    }

    pub fn level(&self) -> Option<u32> {
        self.level
    }

    pub fn partials(&self) -> &[DVec3] {
        &self.partials
    }

    /// The picked pixel's tree at the full depth.
    pub fn full_tree(&self) -> Option<&RayNode> {
        self.full.as_ref()
    }

    /// The tree the panel shows: the level being stepped, or the whole tree.
    pub fn shown_tree(&self) -> Option<&RayNode> {
        self.level_tree.as_ref().or(self.full.as_ref())
    }

    /// Ray counts of tracing the full tree.
    pub fn stats(&self) -> &Stats {
        &self.stats
    }

    /// The picked pixel's rendered value and how it was sampled, when that is more than the
    /// one centre ray the tree follows (supersampling, antialiasing, a path tracer).
    pub fn pixel_value(&self) -> Option<&(DVec3, String)> {
        self.pixel_value.as_ref()
    }

    pub fn selected(&self) -> &[usize] {
        self.view.selected()
    }

    pub fn selected_node(&self) -> Option<&RayNode> {
        tree::node_at(self.shown_tree()?, self.view.selected())
    }

    /// The rows of the tree pane, closed rays' descendants left out.
    pub fn rows(&self) -> Vec<Row> {
        self.view.rows(self.shown_tree())
    }

    /// The first row of the tree pane.
    pub fn offset(&self) -> usize {
        self.view.offset()
    }

    pub fn details_scroll(&self) -> u16 {
        self.view.details_scroll()
    }

    /// Lines the tree pane gives to rows (below the `head_lines`).
    pub fn body_height(&self, pane: Rect) -> usize {
        let lines = inner(pane).height as usize;
        lines.saturating_sub(self.head_lines())
    }

    /// The selected ray's details at a width.
    pub fn detail_rows(&self, width: usize) -> Vec<DetailRow> {
        let scale = self.shown_tree().map_or(0.0, text::tree_scale);
        self.selected_node().map_or(vec![], |n| {
            details::rows(n, self.traced, scale, width, self.hidden)
        })
    }

    /// How far the details can scroll in the lower pane (none without the pane).
    pub fn details_max_scroll(&self, pane: Option<Rect>) -> u16 {
        pane.map_or(0, |r| {
            let i = inner(r);
            max_scroll(self.detail_rows(i.width as usize).len(), i.height)
        })
    }
}

// --- Pixel, depth, levels

impl RayTree {
    /// A new scene: its centre pixel, the whole tree, the scene's depth, the root selected.
    pub fn restart(&mut self, (w, h): (u32, u32)) {
        self.level = None;
        self.ray = None;
        self.depth_from_user = false;
        self.view.select_root();
        self.pixel = (w / 2, h / 2);
    }

    /// Follows a scene (new or reloaded): its maximum depth unless the user chose one, the
    /// picked pixel kept inside the image. Needs a retrace.
    pub fn adopt(&mut self, scene: &Scene) {
        if !self.depth_from_user {
            self.asked = scene.max_depth.clamp(1, MAX_DEPTH);
        }
        let (w, h) = (scene.camera.width, scene.camera.height);
        self.pixel = (
            self.pixel.0.min(w.saturating_sub(1)),
            self.pixel.1.min(h.saturating_sub(1)),
        );
    }

    /// Moves the picked pixel, clamped to a `w` × `h` image; true when it moved (and needs a
    /// retrace).
    pub fn move_by(&mut self, dx: i32, dy: i32, (w, h): (u32, u32)) -> bool {
        if w == 0 || h == 0 {
            return false;
        }
        let x = (self.pixel.0 as i64 + dx as i64).clamp(0, w as i64 - 1) as u32;
        let y = (self.pixel.1 as i64 + dy as i64).clamp(0, h as i64 - 1) as u32;
        let moved = (x, y) != self.pixel || self.ray.is_some();
        self.pixel = (x, y);
        self.ray = None;
        moved
    }

    /// Picks a pixel of a `w` × `h` image (then a retrace is due), or says why not.
    pub fn pick(&mut self, x: u32, y: u32, (w, h): (u32, u32)) -> Result<(), Note> {
        if x >= w || y >= h {
            return Err((
                format!("pixel {x},{y} is outside the {w} × {h} image"),
                Tone::Bad,
            ));
        }
        self.pixel = (x, y);
        self.ray = None;
        Ok(())
    }

    /// An exercise's pixel, and the depth it is asked at (`aim_depth`). True when the depth
    /// changed (then the preview renders again).
    pub fn aim(&mut self, pixel: (u32, u32), depth: Option<u32>, scene_depth: u32) -> bool {
        self.pixel = pixel;
        self.ray = None;
        self.aim_depth(depth, scene_depth)
    }

    /// An exercise's ray (not a pixel's), and the depth it is asked at (`aim_depth`).
    pub fn aim_ray(&mut self, ray: Ray, depth: Option<u32>, scene_depth: u32) -> bool {
        self.ray = Some(ray);
        self.aim_depth(depth, scene_depth)
    }

    /// The exercise's depth, or the scene's max_depth where it names none: its question is
    /// asked at that depth, whatever an earlier exercise or the keys chose.
    fn aim_depth(&mut self, depth: Option<u32>, scene_depth: u32) -> bool {
        let before = self.asked;
        self.asked = depth.unwrap_or(scene_depth).clamp(1, MAX_DEPTH);
        self.depth_from_user = depth.is_some();
        self.asked != before
    }

    /// Sets the maximum depth as the user would; true when it changed (retrace and render).
    pub fn set_depth(&mut self, depth: u32) -> bool {
        let depth = depth.clamp(1, MAX_DEPTH);
        if depth == self.asked {
            return false;
        }
        self.asked = depth;
        self.depth_from_user = true;
        true
    }

    /// + and -: one level deeper or shallower. Ok: the depth changed; Err: why it cannot.
    pub fn step_depth(&mut self, deeper: bool) -> Result<Note, Note> {
        if deeper && self.asked >= MAX_DEPTH {
            return Err((
                format!("scenes go at most {MAX_DEPTH} levels deep"),
                Tone::Bad,
            ));
        }
        if deeper && self.traced < self.asked {
            return Err((budget_note(self.traced), Tone::Bad));
        }
        // Shallower goes one level up from the depth the tree has, not from the depth asked.
        if !deeper && self.traced <= 1 {
            return Err((
                "depth 1 traces primary rays only (and their shadow rays)".into(),
                Tone::Bad,
            ));
        }
        self.set_depth(if deeper {
            self.asked + 1
        } else {
            self.traced - 1
        });
        Ok((format!("maximum depth {}", self.asked), Tone::Info))
    }

    /// n: the next level; past the last, the whole tree again (true). Needs a retrace.
    pub fn level_next(&mut self) -> bool {
        match self.level {
            None => self.level = Some(1),
            Some(k) if k >= self.traced => {
                self.level = None;
                return true;
            }
            Some(k) => self.level = Some(k + 1),
        }
        false
    }

    /// p: the previous level (the last but one when not stepping). Needs a retrace.
    pub fn level_prev(&mut self) {
        self.level = Some(match self.level {
            None => self.traced.saturating_sub(1).max(1),
            Some(k) => k.saturating_sub(1).max(1),
        });
    }

    /// What the level being stepped adds to the pixel's intensity.
    pub fn level_note(&self) -> Option<Note> {
        let k = self.level?;
        if self.hidden {
            return Some((format!("level {k} of {}", self.traced), Tone::Info));
        }
        let i = self
            .partials
            .get(k as usize - 1)
            .copied()
            .unwrap_or_default();
        let mut s = format!("level {k} of {}: I = {}", self.traced, text::color(i));
        if k > 1 {
            let before = self.partials[k as usize - 2];
            s.push_str(&format!(
                " (level {} gave {}, this level adds {})",
                k - 1,
                text::color(before),
                text::color(i - before)
            ));
        }
        Some((s, Tone::Info))
    }

    /// Level stepping is over: the intensity of all levels together.
    pub fn collected_note(&self) -> Note {
        if self.hidden {
            return (
                format!("all {} levels collected (n steps again)", self.traced),
                Tone::Info,
            );
        }
        let i = self.full.as_ref().map_or(DVec3::ZERO, |t| t.color);
        (
            format!(
                "all {} levels collected: I = {} (n steps again)",
                self.traced,
                text::color(i)
            ),
            Tone::Info,
        )
    }

    /// Traces the picked pixel (or the aimed ray) again (new pixel, depth, level or scene).
    pub fn retrace(&mut self, scene: &Scene) {
        let (x, y) = self.pixel;
        let ray = self.ray.unwrap_or_else(|| scene.camera.pixel_ray(x, y));
        // Glossy and frosted rays drawn from the pixel's own generator, as the renderer does;
        // an exercise's ray from the generator `raytree check` uses.
        let aimed = self.ray.is_some();
        let rng = || {
            if aimed {
                Rng::for_pixel(0, 0, 0)
            } else {
                Rng::for_pixel(0, x, y)
            }
        };
        self.traced = affordable_depth(scene, &ray, self.asked, &rng);
        let depth = self.traced;
        let mut tracer = Tracer::new(scene).with_depth(depth).with_rng(rng());
        let full = tracer.inspect(&ray);
        self.stats = tracer.stats;
        let path = scene.integrator == crate::scene::Integrator::Path;
        self.paths = (path && !aimed).then(|| sampled_paths(scene, depth, x, y));
        self.pixel_value = if aimed || path {
            None
        } else {
            pixel_value(scene, depth, x, y)
        };
        self.full = Some(full);
        if let Some(k) = self.level {
            let k = k.clamp(1, depth);
            self.level = Some(k);
            self.partials = (1..=depth)
                .map(|d| {
                    Tracer::new(scene)
                        .with_depth(d)
                        .with_rng(rng())
                        .radiance(&ray)
                })
                .collect();
            self.level_tree = Some(
                Tracer::new(scene)
                    .with_depth(k)
                    .with_rng(rng())
                    .inspect(&ray),
            );
        } else {
            self.partials.clear();
            self.level_tree = None;
        }
        let shown = self.level_tree.as_ref().or(self.full.as_ref());
        let shown = shown.expect("a tree was just traced");
        self.view.retraced(shown, self.level.is_some());
    }
}

// --- Selection and scrolling (the tree shown, handed to its state)

impl RayTree {
    /// Tree keys: returns true when the selection moved.
    pub fn update(&mut self, msg: &Msg) -> bool {
        let root = self.level_tree.as_ref().or(self.full.as_ref());
        self.view.update(root, msg)
    }

    /// The ray with these kinds on its path ("reflection.refraction"), if the tree has one;
    /// true when the selection moved.
    pub fn select_kinds(&mut self, kinds: &str) -> bool {
        match self
            .shown_tree()
            .and_then(|t| tree::path_of_kinds(t, kinds))
        {
            Some(p) => self.view.select(p),
            None => false,
        }
    }

    /// A click on the `row`-th row of the tree's body; true when the selection moved.
    pub fn click(&mut self, row: usize) -> bool {
        let root = self.level_tree.as_ref().or(self.full.as_ref());
        self.view.click(root, row)
    }

    /// Scrolls the tree pane by `delta` rows of a `body`-row pane.
    pub fn scroll_rows(&mut self, delta: i32, body: usize) {
        let root = self.level_tree.as_ref().or(self.full.as_ref());
        self.view.scroll_rows(root, delta, body);
    }

    /// Scrolls the tree pane (of `body` rows) so that the selected ray is in sight.
    pub fn keep_selection_visible(&mut self, body: usize) {
        let root = self.level_tree.as_ref().or(self.full.as_ref());
        self.view.keep_selection_visible(root, body);
    }

    /// Scrolls the details in the lower pane.
    pub fn scroll_details(&mut self, delta: i32, pane: Option<Rect>) {
        let max = self.details_max_scroll(pane);
        self.view.scroll_details(delta, max);
    }
}

/// The rendered value of pixel (x, y) and how it was sampled, when the pixel is more than its
/// centre ray: several samples or corners.
fn pixel_value(scene: &Scene, depth: u32, x: u32, y: u32) -> Option<(DVec3, String)> {
    use crate::render::film::Film;
    use crate::render::{Engine, RenderOptions};
    use crate::scene::Antialias;
    // The textbook core gives the pixel the fast engine renders, bit for bit
    // (tests/fast_paths.rs), and one pixel does not repay building the fast wing's search.
    let options = RenderOptions {
        max_depth: depth,
        engine: Engine::Core,
        ..RenderOptions::of(scene)
    };
    if options.spp <= 1 && options.antialias == Antialias::Grid {
        return None;
    }
    let film = Film::new(scene, options);
    let value = film.lone_pixel(&mut film.tracer(), x, y);
    let mut how = format!("{} spp {}", options.spp, film.antialias().name());
    if film.splats() {
        how.push_str(" gaussian");
    }
    how.push_str(" · tree: its centre ray");
    Some((value, how))
}

/// A path-traced pixel as rendered (seed 0), and its first paths replayed with the same random
/// numbers as `raytree inspect` replays them, so the paths shown are ones that went into it.
fn sampled_paths(scene: &Scene, depth: u32, x: u32, y: u32) -> Paths {
    use crate::render::film::Film;
    use crate::render::RenderOptions;
    let options = RenderOptions {
        max_depth: depth,
        ..RenderOptions::of(scene)
    };
    let film = Film::new(scene, options);
    let estimate = film.lone_pixel(&mut film.tracer(), x, y);
    let spp = options.spp.max(1);
    let shown = film
        .replay_paths(x, y, 0..PATHS_SHOWN)
        .into_iter()
        .map(|(value, log)| {
            // Each vertex as the surface met (the light named as such), or what ended the path.
            let steps: Vec<String> = log
                .iter()
                .map(|v| match (&v.object, v.event) {
                    (Some(o), "light") => format!("light {o}"),
                    (Some(o), _) => o.clone(),
                    (None, event) => event.to_string(),
                })
                .collect();
            (value, steps.join(" → "))
        })
        .collect();
    Paths {
        estimate,
        spp,
        shown,
    }
}
