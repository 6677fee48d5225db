//! The explorer's model: one `App`, the messages that change it, and `update`.
//!
//! Nothing here touches the terminal. The render worker is not here either: `update` leaves a
//! preview job in `app.preview.job` for the event loop to hand to the worker (or for
//! `App::render_now` to render on the spot, which is what the tests do).

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use std::time::{Duration, SystemTime};

use glam::DVec3;
use ratatui::layout::{Margin, Rect};

use super::layout::{self, Panes};
use super::tree::{self, NodePath};
use super::worker::{self, Done, Job, Pass};
use crate::geometry::Ray;
use crate::lessons::{self, Lesson, Verdict};
use crate::render::preview::ColorMode;
use crate::render::Image;
use crate::sampling::Rng;
use crate::scene::{Limits, Scene};
use crate::stats::Stats;
use crate::trace::{text, RayNode, Termination, Tracer};

/// The deepest recursion the explorer traces (each level can double the tree).
pub const MAX_DEPTH: u32 = 16;
/// Pixels moved by shift + arrow (or H J K L).
pub const BIG_STEP: i32 = 10;
/// The CSG panel lists the segment lists of at most this many rays of a tree.
pub const CSG_MAX_RAYS: usize = 64;
/// How often the scene file is checked for changes.
pub const WATCH_INTERVAL: Duration = Duration::from_millis(300);

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Screen {
    /// The lesson list (`raytree explore` without an argument).
    Lessons,
    Scene,
}

/// The pane that arrow keys act on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Focus {
    Preview,
    Tree,
    /// Node details or the CSG panel.
    Lower,
    Lesson,
}

/// A line being typed on the message line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Prompt {
    /// `g`: image coordinates "x,y".
    Goto(String),
    /// `a` then Enter: an answer to an exercise.
    Answer { exercise: usize, text: String },
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LessonView {
    Readme,
    Exercises,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tone {
    Info,
    Good,
    Bad,
}

/// An answer given in the app and what `lessons::check` said.
#[derive(Clone, Debug)]
pub struct Answered {
    pub given: String,
    pub result: Result<Verdict, String>,
}

pub struct LessonPanel {
    pub lesson: Lesson,
    pub open: bool,
    pub view: LessonView,
    pub scroll: u16,
    /// The exercise selected in the exercises view.
    pub exercise: usize,
    /// The last answer to each exercise.
    pub answers: Vec<Option<Answered>>,
    /// The worked solution of the selected exercise, when asked for (`w`).
    pub work: Option<Result<Vec<String>, String>>,
    /// Scroll of the selected exercise's text in the exercises view.
    pub exercise_scroll: u16,
    signature: [Option<FileSig>; 2],
}

impl LessonPanel {
    fn new(lesson: Lesson) -> LessonPanel {
        let n = lesson.exercises.len();
        LessonPanel {
            signature: lesson_signature(&lesson.dir),
            lesson,
            open: true,
            view: LessonView::Readme,
            scroll: 0,
            exercise: 0,
            answers: vec![None; n],
            work: None,
            exercise_scroll: 0,
        }
    }
}

/// One lesson folder of the list; a lesson that does not load is listed with its error.
pub struct LessonEntry {
    pub dir: PathBuf,
    pub lesson: Result<Lesson, String>,
}

pub struct LessonList {
    pub root: PathBuf,
    pub entries: Vec<LessonEntry>,
    pub selected: usize,
    pub error: Option<String>,
}

impl LessonList {
    /// Every folder under `root` with an exercises.yaml, in name order.
    pub fn load(root: &Path) -> LessonList {
        let mut dirs: Vec<PathBuf> = match std::fs::read_dir(root) {
            Ok(rd) => rd
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.join("exercises.yaml").is_file())
                .collect(),
            Err(e) => {
                return LessonList {
                    root: root.to_path_buf(),
                    entries: vec![],
                    selected: 0,
                    error: Some(format!("{}: cannot list lessons: {e}", root.display())),
                }
            }
        };
        dirs.sort();
        let entries: Vec<LessonEntry> = dirs
            .into_iter()
            .map(|dir| LessonEntry {
                lesson: Lesson::load(&dir),
                dir,
            })
            .collect();
        let error = entries.is_empty().then(|| {
            format!(
                "no lessons in {} (set RAYTREE_LESSONS to the lessons folder)",
                root.display()
            )
        });
        LessonList {
            root: root.to_path_buf(),
            entries,
            selected: 0,
            error,
        }
    }
}

/// The terminal preview: the last image received and the job that will replace it.
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
    /// Statistics of the image shown.
    pub stats: Option<Stats>,
    pub elapsed: Option<Duration>,
}

/// A line of the CSG panel, tagged with the ray (tree node) it belongs to.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CsgLine {
    pub node: NodePath,
    pub header: bool,
    pub text: String,
}

/// Size and modification time: a file changed when either did.
type FileSig = (Option<SystemTime>, u64);

fn signature(path: &Path) -> Option<FileSig> {
    let m = std::fs::metadata(path).ok()?;
    Some((m.modified().ok(), m.len()))
}

fn lesson_signature(dir: &Path) -> [Option<FileSig>; 2] {
    [
        signature(&dir.join("README.md")),
        signature(&dir.join("exercises.yaml")),
    ]
}

/// A path relative to the working directory when it lies below it (shorter, and stable).
fn display_path(path: &Path) -> PathBuf {
    if path.is_absolute() {
        if let Ok(cwd) = std::env::current_dir() {
            if let Ok(rel) = path.strip_prefix(&cwd) {
                return rel.to_path_buf();
            }
        }
    }
    path.to_path_buf()
}

#[derive(Debug)]
pub enum Msg {
    Quit,
    /// The terminal's size in cells.
    Resize(u16, u16),
    /// Moves the picked pixel (clamped to the image).
    Move(i32, i32),
    /// Picks an exact pixel.
    Pick(u32, u32),
    /// A mouse click on a cell.
    Click(u16, u16),
    /// A mouse wheel over a cell: lines (negative: up).
    Wheel(u16, u16, i32),
    FocusNext,
    FocusPrev,
    /// Arrow keys in the focused pane (tree, panel, list).
    Up,
    Down,
    Expand,
    Collapse,
    Toggle,
    /// Opens every node, or back to the default.
    ExpandAll,
    /// Page up (negative) / down in the panel.
    Page(i32),
    DepthUp,
    DepthDown,
    /// Steps the tree open one recursion level / closes one.
    LevelNext,
    LevelPrev,
    ToggleCsg,
    ToggleReadme,
    ToggleHelp,
    /// Opens the exercises (`a`).
    Exercises,
    /// Shows or hides the selected exercise's worked solution (`w`).
    Work,
    /// Starts typing pixel coordinates (`g`).
    Goto,
    /// Back to the lesson list (`o`).
    LessonList,
    Input(char),
    Backspace,
    /// Enter: confirms a prompt, opens a lesson, answers an exercise.
    Submit,
    /// Esc in a prompt or a list.
    Cancel,
    /// Time passes: the scene file is checked for changes.
    Tick,
    /// Render progress: generation, rows done, rows in the pass.
    Progress(u64, u32, u32),
    Rendered(Done),
}

pub struct App {
    pub screen: Screen,
    pub list: Option<LessonList>,
    pub lesson: Option<LessonPanel>,
    /// The scene file.
    pub path: Option<PathBuf>,
    /// The last scene that loaded.
    pub scene: Option<Arc<Scene>>,
    signature: Option<FileSig>,
    /// Why the scene file on disk does not load (the last good scene stays).
    pub error: Option<String>,
    pub message: Option<(String, Tone)>,
    pub cursor: (u32, u32),
    /// The maximum depth the tree and the preview are traced with.
    pub depth: u32,
    depth_from_user: bool,
    /// Level stepping: the tree shown is traced with this maximum depth.
    pub level: Option<u32>,
    /// Root intensity at levels 1..=depth (in level stepping).
    pub partials: Vec<DVec3>,
    /// The picked pixel's tree at `depth`.
    pub full_tree: Option<RayNode>,
    /// The tree at `level` while stepping.
    pub level_tree: Option<RayNode>,
    pub tree_stats: Stats,
    /// The picked pixel's rendered value and how it was sampled, when that is more than the
    /// one centre ray the tree follows (supersampling, antialiasing, a path tracer).
    pub pixel_value: Option<(DVec3, String)>,
    pub open: HashSet<NodePath>,
    pub selected: NodePath,
    pub tree_offset: usize,
    pub show_csg: bool,
    pub csg: Vec<CsgLine>,
    pub csg_scroll: u16,
    pub details_scroll: u16,
    pub show_help: bool,
    pub focus: Focus,
    pub prompt: Option<Prompt>,
    pub preview: Preview,
    pub color: ColorMode,
    /// The terminal size in cells.
    pub size: (u16, u16),
    pub quit: bool,
    /// The list screen was reached from a scene (Esc goes back to it).
    list_from_scene: bool,
}

impl App {
    fn empty(color: ColorMode) -> App {
        App {
            screen: Screen::Scene,
            list: None,
            lesson: None,
            path: None,
            scene: None,
            signature: None,
            error: None,
            message: None,
            cursor: (0, 0),
            depth: 1,
            depth_from_user: false,
            level: None,
            partials: vec![],
            full_tree: None,
            level_tree: None,
            tree_stats: Stats::default(),
            pixel_value: None,
            open: HashSet::new(),
            selected: vec![],
            tree_offset: 0,
            show_csg: false,
            csg: vec![],
            csg_scroll: 0,
            details_scroll: 0,
            show_help: false,
            focus: Focus::Preview,
            prompt: None,
            preview: Preview::default(),
            color,
            size: (80, 24),
            quit: false,
            list_from_scene: false,
        }
    }

    /// Opens a scene file, a lesson folder, or (None) the lesson list of `lessons_root()`.
    pub fn open(target: Option<&Path>, color: ColorMode) -> Result<App, String> {
        let mut app = App::empty(color);
        match target {
            None => {
                app.screen = Screen::Lessons;
                app.list = Some(LessonList::load(&lessons::lessons_root()));
            }
            Some(t) => app.open_target(t)?,
        }
        app.settle();
        Ok(app)
    }

    /// Opens the lesson list of a given lessons folder.
    pub fn open_lessons(root: &Path, color: ColorMode) -> App {
        let mut app = App::empty(color);
        app.screen = Screen::Lessons;
        app.list = Some(LessonList::load(root));
        app.settle();
        app
    }

    fn open_target(&mut self, target: &Path) -> Result<(), String> {
        let target = display_path(target);
        let (scene_path, lesson) = if target.is_dir() {
            let scene = target.join("scene.yaml");
            if target.join("exercises.yaml").is_file() {
                (scene, Some(Lesson::load(&target)?))
            } else if scene.is_file() {
                (scene, None)
            } else {
                return Err(format!(
                    "{}: not a lesson folder (no scene.yaml)",
                    target.display()
                ));
            }
        } else {
            (target.clone(), None)
        };
        let scene =
            crate::scene::load(&scene_path, &Limits::default()).map_err(|e| e.to_string())?;
        self.signature = signature(&scene_path);
        self.path = Some(scene_path);
        self.lesson = lesson.map(LessonPanel::new);
        self.error = None;
        self.screen = Screen::Scene;
        self.level = None;
        self.depth_from_user = false;
        self.selected = vec![];
        self.focus = Focus::Preview;
        self.show_csg = false;
        self.preview.image = None;
        self.preview.stats = None;
        self.cursor = (scene.camera.width / 2, scene.camera.height / 2);
        self.set_scene(scene);
        let hint = if self.lesson.is_some() {
            "←↑↓→ pick · Tab tree · +/- depth · n/p levels · r README · a answer · ? keys"
        } else {
            "←↑↓→ pick a pixel · Tab tree · +/- depth · n/p levels · c CSG · ? keys · q quit"
        };
        self.message = Some((hint.into(), Tone::Info));
        Ok(())
    }

    fn set_scene(&mut self, scene: Scene) {
        if !self.depth_from_user {
            self.depth = scene.max_depth.clamp(1, MAX_DEPTH);
        }
        let (w, h) = (scene.camera.width, scene.camera.height);
        self.cursor = (
            self.cursor.0.min(w.saturating_sub(1)),
            self.cursor.1.min(h.saturating_sub(1)),
        );
        self.scene = Some(Arc::new(scene));
        self.retrace();
        self.request_render();
    }

    /// The image size of the scene (0 × 0 without one).
    pub fn image_size(&self) -> (u32, u32) {
        self.scene
            .as_ref()
            .map_or((0, 0), |s| (s.camera.width, s.camera.height))
    }

    /// The scene file as shown to the user.
    pub fn name(&self) -> String {
        self.path
            .as_ref()
            .map_or(String::new(), |p| p.display().to_string())
    }

    pub fn lesson_open(&self) -> bool {
        self.lesson.as_ref().is_some_and(|l| l.open)
    }

    /// The panes of the scene screen at the current size.
    pub fn panes(&self) -> Panes {
        self.panes_in(Rect::new(0, 0, self.size.0, self.size.1))
    }

    /// The panes of the scene screen in an area.
    pub fn panes_in(&self, area: Rect) -> Panes {
        let (w, h) = self.image_size();
        let aspect = if h == 0 { 1.0 } else { w as f64 / h as f64 };
        layout::scene_panes(area, aspect, self.lesson_open(), self.message_rows())
    }

    /// The message line, as text: a scene error wins over other messages.
    pub fn message_text(&self) -> Option<(String, Tone)> {
        match (&self.error, &self.message) {
            (Some(e), _) => Some((format!("✗ {e} (the last good scene stays)"), Tone::Bad)),
            (None, Some(m)) => Some(m.clone()),
            (None, None) => None,
        }
    }

    /// Message lines at the bottom: two when a scene error does not fit on one.
    pub fn message_rows(&self) -> u16 {
        match (&self.error, &self.prompt) {
            (Some(_), None) => {
                let len = self.message_text().map_or(0, |(t, _)| t.chars().count());
                if len > self.size.0 as usize {
                    2
                } else {
                    1
                }
            }
            _ => 1,
        }
    }

    /// The tree the panel shows: the level being stepped, or the whole tree.
    pub fn shown_tree(&self) -> Option<&RayNode> {
        self.level_tree.as_ref().or(self.full_tree.as_ref())
    }

    pub fn selected_node(&self) -> Option<&RayNode> {
        tree::node_at(self.shown_tree()?, &self.selected)
    }

    pub fn rows(&self) -> Vec<tree::Row> {
        self.shown_tree()
            .map_or(vec![], |t| tree::visible_rows(t, &self.open))
    }

    /// Lines the tree panel gives to rows (the level line takes one in level stepping).
    pub fn tree_body_height(&self) -> usize {
        let inner = self.panes().tree.inner(Margin::new(1, 1)).height as usize;
        inner.saturating_sub(self.level.is_some() as usize + self.pixel_value.is_some() as usize)
    }

    /// Takes the preview job for the worker.
    pub fn take_job(&mut self) -> Option<Job> {
        self.preview.job.take()
    }

    /// Renders the pending preview job here and now (tests, measurements).
    pub fn render_now(&mut self) {
        if let Some(job) = self.take_job() {
            let cancel = AtomicBool::new(false);
            if let Some(done) = worker::render_pass(&job, Pass::Final, &cancel, &|_| {}) {
                update(self, Msg::Rendered(done));
            }
        }
    }

    /// Asks for a new preview at the current size and depth.
    fn request_render(&mut self) {
        let Some(scene) = &self.scene else { return };
        let (w, h) = self.preview.size;
        if w == 0 || h == 0 {
            return;
        }
        self.preview.generation += 1;
        self.preview.job = Some(Job {
            generation: self.preview.generation,
            scene: Arc::clone(scene),
            depth: self.depth,
            width: w,
            height: h,
            spp: scene.spp.clamp(1, 4),
        });
        self.preview.running = true;
        self.preview.rows = (0, h);
    }

    /// Traces the picked pixel again (new pixel, depth, level or scene).
    fn retrace(&mut self) {
        let Some(scene) = self.scene.clone() else {
            return;
        };
        let (x, y) = self.cursor;
        let ray = scene.camera.pixel_ray(x, y);
        // Glossy and frosted rays drawn from the pixel's own generator, as the renderer does.
        let rng = || Rng::for_pixel(0, x, y);
        let mut tracer = Tracer::new(&scene).with_depth(self.depth).with_rng(rng());
        let full = tracer.inspect(&ray);
        self.tree_stats = tracer.stats;
        self.pixel_value = pixel_value(&scene, self.depth, x, y);
        self.full_tree = Some(full);
        if let Some(k) = self.level {
            let k = k.clamp(1, self.depth);
            self.level = Some(k);
            self.partials = (1..=self.depth)
                .map(|d| {
                    Tracer::new(&scene)
                        .with_depth(d)
                        .with_rng(rng())
                        .radiance(&ray)
                })
                .collect();
            self.level_tree = Some(
                Tracer::new(&scene)
                    .with_depth(k)
                    .with_rng(rng())
                    .inspect(&ray),
            );
        } else {
            self.partials.clear();
            self.level_tree = None;
        }
        let shown = self.shown_tree().expect("a tree was just traced");
        let open = if self.level.is_some() {
            tree::all_parents(shown)
        } else {
            tree::default_open(shown)
        };
        let selected = tree::valid_prefix(shown, &self.selected);
        self.open = open;
        self.selected = selected;
        // A selected node inside a closed parent is shown through its parent.
        while !self.selected.is_empty()
            && !self
                .open
                .contains(&self.selected[..self.selected.len() - 1])
        {
            self.selected.pop();
        }
        if self.show_csg {
            self.compute_csg();
        }
    }

    /// The CSG panel: for every ray of the tree, the segment lists of the objects it meets.
    fn compute_csg(&mut self) {
        let (Some(scene), Some(root)) = (self.scene.clone(), self.shown_tree()) else {
            self.csg.clear();
            return;
        };
        let mut lines = Vec::new();
        let paths = tree::ray_paths(root);
        let more = paths.len().saturating_sub(CSG_MAX_RAYS);
        for path in paths.into_iter().take(CSG_MAX_RAYS) {
            let n = tree::node_at(root, &path).expect("path from the tree");
            if matches!(
                n.terminated,
                Some(Termination::MaxDepth) | Some(Termination::Adaptive)
            ) {
                continue;
            }
            let ray = Ray::new(n.origin, n.direction);
            let at = tree::kinds_of_path(root, &path);
            let name = if at.is_empty() {
                "primary ray".to_string()
            } else {
                format!("{at} ray")
            };
            lines.push(CsgLine {
                node: path.clone(),
                header: true,
                text: format!(
                    "{name} {} → {}",
                    text::vec3(ray.origin),
                    text::vec3(ray.dir)
                ),
            });
            let traces = scene.csg_traces(&ray, false);
            if traces.is_empty() {
                lines.push(CsgLine {
                    node: path.clone(),
                    header: false,
                    text: "  meets no object".into(),
                });
            }
            for (object, t) in traces {
                lines.push(CsgLine {
                    node: path.clone(),
                    header: false,
                    text: format!("  object {object}"),
                });
                for l in text::csg_trace(&scene, &ray, &t).lines() {
                    lines.push(CsgLine {
                        node: path.clone(),
                        header: false,
                        text: format!("    {l}"),
                    });
                }
            }
        }
        if more > 0 {
            lines.push(CsgLine {
                node: vec![usize::MAX],
                header: false,
                text: format!("… and {more} more rays (raytree csg --ray shows any of them)"),
            });
        }
        self.csg = lines;
        self.scroll_csg_to_selection();
    }

    /// Scrolls the CSG panel to the selected ray's section.
    fn scroll_csg_to_selection(&mut self) {
        let row = super::ui::csg_section_row(self).unwrap_or(0) as u16;
        self.csg_scroll = row.min(super::ui::max_scroll(self).0);
    }

    fn select(&mut self, path: NodePath) {
        if path != self.selected {
            self.selected = path;
            self.details_scroll = 0;
            if self.show_csg {
                self.scroll_csg_to_selection();
            }
        }
    }

    fn move_cursor(&mut self, dx: i32, dy: i32) {
        let (w, h) = self.image_size();
        if w == 0 || h == 0 {
            return;
        }
        let x = (self.cursor.0 as i64 + dx as i64).clamp(0, w as i64 - 1) as u32;
        let y = (self.cursor.1 as i64 + dy as i64).clamp(0, h as i64 - 1) as u32;
        if (x, y) != self.cursor {
            self.cursor = (x, y);
            self.retrace();
        }
    }

    fn pick(&mut self, x: u32, y: u32) {
        let (w, h) = self.image_size();
        if x >= w || y >= h {
            self.message = Some((
                format!("pixel {x},{y} is outside the {w} × {h} image"),
                Tone::Bad,
            ));
            return;
        }
        self.cursor = (x, y);
        self.retrace();
    }

    fn set_depth(&mut self, depth: u32) {
        let depth = depth.clamp(1, MAX_DEPTH);
        if depth == self.depth {
            return;
        }
        self.depth = depth;
        self.depth_from_user = true;
        self.retrace();
        self.request_render();
    }

    /// Sets the maximum depth as the user would with + and -.
    pub fn with_depth(mut self, depth: u32) -> App {
        self.set_depth(depth);
        self.settle();
        self
    }

    fn focusable(&self) -> Vec<Focus> {
        let p = self.panes();
        let mut f = vec![Focus::Preview, Focus::Tree];
        if p.lower.is_some() {
            f.push(Focus::Lower);
        }
        if p.lesson.is_some() {
            f.push(Focus::Lesson);
        }
        f
    }

    fn cycle_focus(&mut self, forward: bool) {
        let f = self.focusable();
        let i = f.iter().position(|&x| x == self.focus).unwrap_or(0);
        let n = f.len();
        self.focus = f[if forward {
            (i + 1) % n
        } else {
            (i + n - 1) % n
        }];
    }

    fn tree_step(&mut self, delta: i64) {
        let rows = self.rows();
        if rows.is_empty() {
            return;
        }
        let i = rows
            .iter()
            .position(|r| r.path == self.selected)
            .unwrap_or(0) as i64;
        let j = (i + delta).clamp(0, rows.len() as i64 - 1) as usize;
        self.select(rows[j].path.clone());
    }

    fn expand(&mut self) {
        let Some(n) = self.selected_node() else {
            return;
        };
        if n.children.is_empty() {
            return;
        }
        if self.open.contains(&self.selected) {
            let mut child = self.selected.clone();
            child.push(0);
            self.select(child);
        } else {
            self.open.insert(self.selected.clone());
        }
    }

    fn collapse(&mut self) {
        if self.open.contains(&self.selected) {
            self.open.remove(&self.selected);
        } else if !self.selected.is_empty() {
            let mut parent = self.selected.clone();
            parent.pop();
            self.select(parent);
        }
    }

    fn toggle(&mut self) {
        let has_children = self.selected_node().is_some_and(|n| !n.children.is_empty());
        if !has_children {
            return;
        }
        if !self.open.remove(&self.selected) {
            self.open.insert(self.selected.clone());
        }
    }

    fn scroll_lower(&mut self, delta: i32) {
        let max = super::ui::max_scroll(self).0 as i32;
        let s = if self.show_csg {
            &mut self.csg_scroll
        } else {
            &mut self.details_scroll
        };
        *s = (*s as i32 + delta).clamp(0, max) as u16;
    }

    fn scroll_lesson(&mut self, delta: i32) {
        let max = super::ui::max_scroll(self).1 as i32;
        if let Some(l) = &mut self.lesson {
            l.scroll = (l.scroll as i32 + delta).clamp(0, max) as u16;
        }
    }

    fn select_exercise(&mut self, i: usize) {
        let Some(l) = &mut self.lesson else { return };
        if l.lesson.exercises.is_empty() {
            return;
        }
        let i = i.min(l.lesson.exercises.len() - 1);
        if l.exercise != i {
            l.work = None;
            l.exercise_scroll = 0;
        }
        l.exercise = i;
        let ex = l.lesson.exercises[i].clone();
        let same_scene = ex.scene.as_deref().is_none_or(|s| s == "scene.yaml");
        let mut note = format!("exercise {}", ex.id);
        // A ray exercise whose ray is a primary ray of the scene is that pixel's.
        let pixel = match (ex.pixel, &ex.ray, &self.scene) {
            (Some(p), ..) => Some(p),
            (None, Some(r), Some(scene)) if same_scene => {
                pixel_of_ray(scene, &Ray::new(r.origin, r.direction)).map(|(x, y)| [x, y])
            }
            _ => None,
        };
        if let (Some(r), None) = (&ex.ray, ex.pixel) {
            note.push_str(&format!(
                ": ray {} → {}",
                text::vec3(r.origin),
                text::vec3(r.direction)
            ));
            if pixel.is_some() {
                note.push_str(", the primary ray of");
            }
        }
        if let (Some([x, y]), true) = (pixel, same_scene) {
            let (w, h) = self.image_size();
            if x < w && y < h {
                self.cursor = (x, y);
                if let Some(d) = ex.depth {
                    self.depth = d.clamp(1, MAX_DEPTH);
                    self.depth_from_user = true;
                    self.request_render();
                }
                self.retrace();
                if let Some(p) = self
                    .shown_tree()
                    .and_then(|t| tree::path_of_kinds(t, &ex.node))
                {
                    self.select(p);
                }
                let sep = if ex.pixel.is_some() { ":" } else { "" };
                note.push_str(&format!("{sep} pixel {x},{y}"));
                if !ex.node.is_empty() {
                    note.push_str(&format!(", node {}", ex.node));
                }
            }
        }
        if let Some(s) = &ex.scene {
            note.push_str(&format!(" (scene {s})"));
        }
        self.message = Some((
            format!("{note} · Enter: answer · w: worked solution · Esc: back"),
            Tone::Info,
        ));
    }

    /// Shows (or hides) the worked solution of the selected exercise.
    fn toggle_work(&mut self) {
        let Some(l) = &mut self.lesson else {
            self.message = Some((
                "no lesson here: open a lesson folder, or press o for the list".into(),
                Tone::Bad,
            ));
            return;
        };
        if !(l.open && l.view == LessonView::Exercises) {
            self.message = Some((
                "w shows a worked solution in the exercises (press a)".into(),
                Tone::Bad,
            ));
            return;
        }
        if l.work.take().is_some() {
            return;
        }
        if let Some(ex) = l.lesson.exercises.get(l.exercise) {
            // The panel shows the question already.
            let question = format!("{}: ", ex.id);
            l.work = Some(lessons::explain(&l.lesson, ex).map(|lines| {
                lines
                    .into_iter()
                    .enumerate()
                    .filter(|(i, line)| *i > 0 || !line.starts_with(&question))
                    .map(|(_, line)| line)
                    .collect()
            }));
        }
    }

    fn answer(&mut self, exercise: usize, given: String) {
        let Some(l) = &mut self.lesson else { return };
        let Some(ex) = l.lesson.exercises.get(exercise) else {
            return;
        };
        let result = lessons::check(&l.lesson, ex, &given);
        self.message = Some(match &result {
            Ok(v) => (
                format!(
                    "{}: {}",
                    ex.id,
                    v.message().lines().next().unwrap_or_default()
                ),
                if v.correct { Tone::Good } else { Tone::Bad },
            ),
            Err(e) => (format!("{}: {e}", ex.id), Tone::Bad),
        });
        l.answers[exercise] = Some(Answered { given, result });
    }

    fn open_list(&mut self) {
        let root = lessons::lessons_root();
        let mut list = LessonList::load(&root);
        if let Some(l) = &self.lesson {
            if let Some(i) = list.entries.iter().position(|e| e.dir == l.lesson.dir) {
                list.selected = i;
            }
        }
        self.list = Some(list);
        self.list_from_scene = self.scene.is_some();
        self.screen = Screen::Lessons;
        self.show_help = false;
        self.prompt = None;
    }

    fn open_selected_lesson(&mut self) {
        let Some(list) = &self.list else { return };
        let Some(entry) = list.entries.get(list.selected) else {
            return;
        };
        let dir = entry.dir.clone();
        match self.open_target(&dir) {
            Ok(()) => {}
            Err(e) => {
                if let Some(list) = &mut self.list {
                    list.error = Some(e);
                }
            }
        }
    }

    /// Reloads the scene file if it changed on disk.
    fn poll_file(&mut self) {
        self.poll_lesson();
        let Some(path) = self.path.clone() else {
            return;
        };
        let sig = signature(&path);
        if sig == self.signature {
            return;
        }
        self.signature = sig;
        match crate::scene::load(&path, &Limits::default()) {
            Ok(scene) => {
                let had_error = self.error.take().is_some();
                self.set_scene(scene);
                self.message = Some((
                    format!(
                        "reloaded {}{}",
                        path.display(),
                        if had_error { " (fixed)" } else { "" }
                    ),
                    Tone::Good,
                ));
            }
            Err(e) => self.error = Some(e.to_string()),
        }
    }

    /// Reloads the lesson's README and exercises if either changed (answers are kept for the
    /// exercises that are still there).
    fn poll_lesson(&mut self) {
        let Some(l) = &mut self.lesson else { return };
        let sig = lesson_signature(&l.lesson.dir);
        if sig == l.signature {
            return;
        }
        l.signature = sig;
        match Lesson::load(&l.lesson.dir) {
            Ok(lesson) => {
                let answers = lesson
                    .exercises
                    .iter()
                    .map(|ex| {
                        l.lesson
                            .exercises
                            .iter()
                            .position(|old| old.id == ex.id)
                            .and_then(|i| l.answers[i].clone())
                    })
                    .collect();
                l.exercise = l.exercise.min(lesson.exercises.len().saturating_sub(1));
                l.answers = answers;
                l.lesson = lesson;
            }
            Err(e) => self.message = Some((e, Tone::Bad)),
        }
    }

    /// Keeps what depends on the layout in step: the preview resolution, the tree scroll.
    fn settle(&mut self) {
        if self.screen != Screen::Scene || self.scene.is_none() {
            return;
        }
        let panes = self.panes();
        if panes.image_px != self.preview.size {
            self.preview.size = panes.image_px;
            self.request_render();
        }
        if !self.focusable().contains(&self.focus) {
            self.focus = Focus::Preview;
        }
        let rows = self.rows();
        let body = self.tree_body_height().max(1);
        if let Some(i) = rows.iter().position(|r| r.path == self.selected) {
            if i < self.tree_offset {
                self.tree_offset = i;
            } else if i >= self.tree_offset + body {
                self.tree_offset = i + 1 - body;
            }
        }
        self.tree_offset = self.tree_offset.min(rows.len().saturating_sub(body));
    }

    fn click(&mut self, col: u16, row: u16) {
        let at = ratatui::layout::Position::new(col, row);
        if self.screen == Screen::Lessons {
            let (list_area, ..) = layout::list_panes(Rect::new(0, 0, self.size.0, self.size.1));
            let inner = list_area.inner(Margin::new(1, 1));
            if let Some(list) = &mut self.list {
                if inner.contains(at) {
                    let i = list_offset(list.selected, inner.height as usize)
                        + (row - inner.y) as usize;
                    if i < list.entries.len() {
                        if i == list.selected {
                            self.open_selected_lesson();
                        } else {
                            list.selected = i;
                        }
                    }
                }
            }
            return;
        }
        let p = self.panes();
        if let Some((x, y)) = layout::cell_pixel(&p, self.image_size(), col, row) {
            self.focus = Focus::Preview;
            self.pick(x, y);
        } else if p.tree.contains(at) {
            self.focus = Focus::Tree;
            let inner = p.tree.inner(Margin::new(1, 1));
            let top = inner.y + self.level.is_some() as u16;
            if row >= top && row < inner.bottom() {
                let i = self.tree_offset + (row - top) as usize;
                let rows = self.rows();
                if let Some(r) = rows.get(i) {
                    if r.path == self.selected {
                        self.toggle();
                    } else {
                        self.select(r.path.clone());
                    }
                }
            }
        } else if p.lower.is_some_and(|r| r.contains(at)) {
            self.focus = Focus::Lower;
        } else if p.lesson.is_some_and(|r| r.contains(at)) {
            self.focus = Focus::Lesson;
        }
    }

    fn wheel(&mut self, col: u16, row: u16, delta: i32) {
        let at = ratatui::layout::Position::new(col, row);
        if self.screen == Screen::Lessons {
            self.list_step(delta as i64);
            return;
        }
        let p = self.panes();
        if p.tree.contains(at) {
            let rows = self.rows().len();
            let body = self.tree_body_height();
            let max = rows.saturating_sub(body) as i64;
            self.tree_offset = (self.tree_offset as i64 + delta as i64).clamp(0, max) as usize;
        } else if p.lower.is_some_and(|r| r.contains(at)) {
            self.scroll_lower(delta);
        } else if p.lesson.is_some_and(|r| r.contains(at)) {
            self.scroll_lesson(delta);
        }
    }

    fn list_step(&mut self, delta: i64) {
        if let Some(list) = &mut self.list {
            if !list.entries.is_empty() {
                list.selected =
                    (list.selected as i64 + delta).clamp(0, list.entries.len() as i64 - 1) as usize;
            }
        }
    }

    fn exercises_active(&self) -> bool {
        self.focus == Focus::Lesson
            && self
                .lesson
                .as_ref()
                .is_some_and(|l| l.open && l.view == LessonView::Exercises)
    }

    fn level_message(&mut self) {
        let Some(k) = self.level else { return };
        let i = self
            .partials
            .get(k as usize - 1)
            .copied()
            .unwrap_or_default();
        let mut s = format!("level {k} of {}: I = {}", self.depth, text::color(i));
        if k > 1 {
            let before = self.partials[k as usize - 2];
            s.push_str(&format!(
                " (level {} gave {}, this level adds {})",
                k - 1,
                text::color(before),
                text::color(i - before)
            ));
        }
        self.message = Some((s, Tone::Info));
    }
}

/// The pixel whose primary ray (through its centre) is this ray, if there is one.
pub fn pixel_of_ray(scene: &Scene, ray: &Ray) -> Option<(u32, u32)> {
    let cam = &scene.camera;
    if (ray.origin - cam.eye()).length() > 1e-9 || cam.width as u64 * cam.height as u64 > 1 << 20 {
        return None;
    }
    let mut best = (f64::NEG_INFINITY, 0, 0);
    for y in 0..cam.height {
        for x in 0..cam.width {
            let d = cam.pixel_ray(x, y).dir.dot(ray.dir);
            if d > best.0 {
                best = (d, x, y);
            }
        }
    }
    (best.0 > 1.0 - 1e-12).then_some((best.1, best.2))
}

/// The first row shown of a list of which `selected` must be visible in `height` rows.
pub fn list_offset(selected: usize, height: usize) -> usize {
    if height == 0 {
        0
    } else {
        (selected + 1).saturating_sub(height)
    }
}

/// Changes the model. Everything the explorer does goes through here.
pub fn update(app: &mut App, msg: Msg) {
    match msg {
        Msg::Quit => app.quit = true,
        Msg::Resize(w, h) => app.size = (w, h),
        Msg::Tick => app.poll_file(),
        Msg::Progress(generation, rows, total) => {
            if generation == app.preview.generation && app.preview.running {
                app.preview.rows = (rows, total);
            }
        }
        Msg::Rendered(done) => {
            if done.generation == app.preview.generation {
                if done.pass == Pass::Final {
                    app.preview.running = false;
                }
                app.preview.image = Some(done.image);
                app.preview.pass = Some(done.pass);
                app.preview.stats = Some(done.stats);
                app.preview.elapsed = Some(done.elapsed);
                if let Some(why) = done.failure {
                    app.preview.running = false;
                    app.message = Some((format!("the preview renderer crashed: {why}"), Tone::Bad));
                }
            }
        }
        Msg::ToggleHelp => app.show_help = !app.show_help,
        Msg::Input(c) => match &mut app.prompt {
            Some(Prompt::Goto(s)) | Some(Prompt::Answer { text: s, .. })
                if s.chars().count() < 200 =>
            {
                s.push(c)
            }
            _ => {}
        },
        Msg::Backspace => match &mut app.prompt {
            Some(Prompt::Goto(s)) | Some(Prompt::Answer { text: s, .. }) => {
                s.pop();
            }
            None => {}
        },
        Msg::Cancel => {
            if app.prompt.take().is_none() {
                if app.screen == Screen::Lessons && app.list_from_scene {
                    app.screen = Screen::Scene;
                } else if app.focus == Focus::Lesson {
                    app.focus = Focus::Preview;
                }
            }
        }
        Msg::Submit => match app.prompt.take() {
            Some(Prompt::Goto(s)) => match parse_pixel(&s) {
                Some((x, y)) => app.pick(x, y),
                None => {
                    app.message = Some((
                        format!("expected a pixel x,y (two whole numbers), got `{s}`"),
                        Tone::Bad,
                    ))
                }
            },
            Some(Prompt::Answer { exercise, text }) => app.answer(exercise, text),
            None => {
                if app.screen == Screen::Lessons {
                    app.open_selected_lesson();
                } else if app.exercises_active() {
                    let i = app.lesson.as_ref().map_or(0, |l| l.exercise);
                    app.prompt = Some(Prompt::Answer {
                        exercise: i,
                        text: String::new(),
                    });
                } else if app.focus == Focus::Tree {
                    app.toggle();
                }
            }
        },
        Msg::LessonList => app.open_list(),
        _ if app.screen == Screen::Lessons => match msg {
            Msg::Up => app.list_step(-1),
            Msg::Down => app.list_step(1),
            Msg::Page(d) => app.list_step(d as i64 * 10),
            Msg::Click(c, r) => app.click(c, r),
            Msg::Wheel(c, r, d) => app.wheel(c, r, d),
            _ => {}
        },
        Msg::Move(dx, dy) => app.move_cursor(dx, dy),
        Msg::Pick(x, y) => app.pick(x, y),
        Msg::Click(c, r) => app.click(c, r),
        Msg::Wheel(c, r, d) => app.wheel(c, r, d),
        Msg::FocusNext => app.cycle_focus(true),
        Msg::FocusPrev => app.cycle_focus(false),
        Msg::Up | Msg::Down => {
            let d = if matches!(msg, Msg::Up) { -1 } else { 1 };
            match app.focus {
                Focus::Preview => app.move_cursor(0, d),
                Focus::Tree => app.tree_step(d as i64),
                Focus::Lower => app.scroll_lower(d),
                Focus::Lesson => {
                    if app.exercises_active() {
                        let i = app.lesson.as_ref().map_or(0, |l| l.exercise) as i64 + d as i64;
                        app.select_exercise(i.max(0) as usize);
                    } else {
                        app.scroll_lesson(d);
                    }
                }
            }
        }
        Msg::Expand => app.expand(),
        Msg::Collapse => app.collapse(),
        Msg::Toggle => app.toggle(),
        Msg::ExpandAll => {
            if let Some(t) = app.shown_tree() {
                let all = tree::all_parents(t);
                app.open = if app.open == all {
                    tree::parents_above(t, 1)
                } else {
                    all
                };
                let sel = app.selected.clone();
                let mut keep = sel.clone();
                while !keep.is_empty() && !app.open.contains(&keep[..keep.len() - 1]) {
                    keep.pop();
                }
                app.select(keep);
            }
        }
        Msg::Page(d) => {
            let page = 10 * d;
            match app.focus {
                Focus::Tree => app.tree_step(page as i64),
                Focus::Lower => app.scroll_lower(page),
                Focus::Lesson if app.exercises_active() => {
                    let max = super::ui::max_scroll(app).1 as i32;
                    if let Some(l) = &mut app.lesson {
                        l.exercise_scroll = (l.exercise_scroll as i32 + page).clamp(0, max) as u16;
                    }
                }
                Focus::Lesson => app.scroll_lesson(page),
                Focus::Preview => {
                    if app.panes().lesson.is_some() {
                        app.scroll_lesson(page)
                    } else {
                        app.scroll_lower(page)
                    }
                }
            }
        }
        Msg::DepthUp => {
            if app.depth >= MAX_DEPTH {
                app.message = Some((
                    format!("the explorer traces at most {MAX_DEPTH} levels"),
                    Tone::Bad,
                ));
            } else {
                app.set_depth(app.depth + 1);
                app.message = Some((format!("maximum depth {}", app.depth), Tone::Info));
            }
        }
        Msg::DepthDown => {
            if app.depth <= 1 {
                app.message = Some((
                    "depth 1 traces primary rays only (and their shadow rays)".into(),
                    Tone::Bad,
                ));
            } else {
                app.set_depth(app.depth - 1);
                app.message = Some((format!("maximum depth {}", app.depth), Tone::Info));
            }
        }
        Msg::LevelNext => {
            match app.level {
                None => app.level = Some(1),
                Some(k) if k >= app.depth => {
                    app.level = None;
                    app.retrace();
                    let i = app.full_tree.as_ref().map_or(DVec3::ZERO, |t| t.color);
                    app.message = Some((
                        format!(
                            "all {} levels collected: I = {} (n steps again)",
                            app.depth,
                            text::color(i)
                        ),
                        Tone::Info,
                    ));
                    return app.settle();
                }
                Some(k) => app.level = Some(k + 1),
            }
            app.retrace();
            app.level_message();
        }
        Msg::LevelPrev => {
            app.level = Some(match app.level {
                None => app.depth.saturating_sub(1).max(1),
                Some(k) => k.saturating_sub(1).max(1),
            });
            app.retrace();
            app.level_message();
        }
        Msg::ToggleCsg => {
            app.show_csg = !app.show_csg;
            if app.show_csg {
                app.compute_csg();
                if app.size.0 < layout::WIDE {
                    if let Some(l) = &mut app.lesson {
                        l.open = false;
                    }
                }
                if app.csg.iter().all(|l| l.header) || app.csg.is_empty() {
                    app.message = Some(("no object along these rays".into(), Tone::Info));
                }
            }
        }
        Msg::ToggleReadme => match &mut app.lesson {
            None => {
                app.message = Some((
                    "no lesson here: open a lesson folder, or press o for the list".into(),
                    Tone::Bad,
                ))
            }
            Some(l) => {
                if l.open && l.view == LessonView::Readme {
                    l.open = false;
                } else {
                    l.open = true;
                    l.view = LessonView::Readme;
                }
            }
        },
        Msg::Exercises => match &mut app.lesson {
            None => {
                app.message = Some((
                    "no lesson here: open a lesson folder, or press o for the list".into(),
                    Tone::Bad,
                ))
            }
            Some(l) => {
                l.open = true;
                l.view = LessonView::Exercises;
                let i = l.exercise;
                app.focus = Focus::Lesson;
                app.select_exercise(i);
            }
        },
        Msg::Goto => app.prompt = Some(Prompt::Goto(String::new())),
        Msg::Work => app.toggle_work(),
    }
    app.settle();
}

/// "x,y" or "x y".
fn parse_pixel(s: &str) -> Option<(u32, u32)> {
    let parts: Vec<&str> = s
        .split([',', ' '])
        .map(str::trim)
        .filter(|p| !p.is_empty())
        .collect();
    match parts.as_slice() {
        [x, y] => Some((x.parse().ok()?, y.parse().ok()?)),
        _ => None,
    }
}

/// The rendered value of pixel (x, y) and how it was sampled, when the pixel is more than its
/// centre ray: several samples, corners, or a path tracer (whose tree is only the Whitted
/// reading of the scene).
fn pixel_value(scene: &Scene, depth: u32, x: u32, y: u32) -> Option<(DVec3, String)> {
    use crate::render::film::Film;
    use crate::render::RenderOptions;
    use crate::scene::Antialias;
    let options = RenderOptions {
        max_depth: depth,
        ..RenderOptions::of(scene)
    };
    let film = Film::new(scene, options);
    let path = scene.integrator == crate::scene::Integrator::Path;
    if options.spp <= 1 && options.antialias == Antialias::Grid && !path {
        return None;
    }
    let value = film.lone_pixel(&mut film.tracer(), x, y);
    let mut how = format!("{} spp {}", options.spp, film.antialias().name());
    if film.splats() {
        how.push_str(" gaussian");
    }
    if path {
        how = format!("path, {how} · tree: Whitted reading of its centre ray");
    } else {
        how.push_str(" · tree: its centre ray");
    }
    Some((value, how))
}
