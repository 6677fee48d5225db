//! The explorer's model: one `App` composed of the parts in state/, and `update`, which routes
//! each message to the parts it concerns and keeps them in step (a new pixel retraces the tree,
//! a new tree recomputes the CSG panel, a new depth renders the preview again).
//!
//! Nothing here touches the terminal or calls the drawing code (ui/). Where the model needs
//! geometry, which pane a click hit or how far a pane scrolls, it asks the pure functions the
//! drawing code asks too: layout.rs for where the panes are, and the parts' own rows of text
//! (wrapped by wrap.rs) for how many rows a pane's content takes. So the model needs no draw
//! to have happened, and what it clamps to is what is drawn.
//!
//! The routing of keys and the mouse to the panes is in app/panes.rs, of the prompt, the
//! lesson and the lesson list in app/lesson.rs.

mod lesson;
mod panes;

use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use std::time::Duration;

use ratatui::layout::Rect;

use super::layout::{self, Panes};
use super::msg::Msg;
use super::state::csg::CsgPanel;
use super::state::diagram::DiagramPane;
use super::state::lesson::LessonPanel;
use super::state::list::LessonList;
use super::state::preview::Preview;
use super::state::prompt::Prompt;
use super::state::ray_tree::RayTree;
use super::state::scene::{Opened, SceneFile};
use super::state::{Note, Tone};
use super::worker::{self, Job, Pass};
use crate::render::preview::ColorMode;
use crate::scene::{Limits, Scene};

/// Pixels moved by shift + arrow (or H J K L).
pub const BIG_STEP: i32 = 10;
/// How often the scene file is checked for changes.
pub const WATCH_INTERVAL: Duration = Duration::from_millis(300);

/// Which screen the explorer shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Screen {
    /// The lesson list (`raytree explore` without an argument).
    Lessons,
    /// A scene: preview, ray tree, details, and the lesson beside them.
    Scene,
}

/// The most lines a scene error takes at the bottom of the screen.
const ERROR_ROWS: usize = 4;

/// The pane that arrow keys act on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Focus {
    /// The preview image, where arrows move the picked pixel.
    Preview,
    /// The ray tree, where arrows select and open nodes.
    Tree,
    /// Node details or the CSG panel.
    Lower,
    /// The lesson's README or exercises.
    Lesson,
    /// The ray diagram: arrows pan it.
    Diagram,
}

/// The explorer's whole state (the model of model–update–view): what is open, picked and shown.
pub struct App {
    /// The lesson list or the scene screen.
    pub screen: Screen,
    /// The scene file shown, its compiled scene, and what went wrong loading it.
    pub file: SceneFile,
    /// The preview image and the render under way.
    pub preview: Preview,
    /// The picked pixel and its ray tree.
    pub tree: RayTree,
    /// The CSG panel (`c`): the segment lists along the picked pixel's ray.
    pub csg: CsgPanel,
    /// The ray diagram pane (`d`).
    pub diagram: DiagramPane,
    /// The lesson beside the scene, when one is open.
    pub lesson: Option<LessonPanel>,
    /// The lesson list, when it is shown.
    pub list: Option<LessonList>,
    /// The pane that arrow keys act on.
    pub focus: Focus,
    /// The line being typed (pixel coordinates, an answer), if any.
    pub prompt: Option<Prompt>,
    /// The last message for the user (`message_text` says what the message line shows).
    message: Option<Note>,
    /// The key help is shown over everything (`?`).
    pub show_help: bool,
    /// How the preview shows colours (true colour, 256 colours or ASCII).
    pub color: ColorMode,
    /// The terminal size in cells.
    pub size: (u16, u16),
    /// The user asked to leave; the main loop ends.
    pub quit: bool,
}

/// Changes the model. Everything the explorer does goes through here.
pub fn update(app: &mut App, msg: Msg) {
    match msg {
        Msg::Quit => app.quit = true,
        Msg::Resize(w, h) => app.size = (w, h),
        Msg::Tick => app.poll_files(),
        Msg::Progress(generation, rows, total) => app.preview.progress(generation, rows, total),
        Msg::Rendered(done) => {
            let note = app.preview.receive(done);
            app.note(note);
        }
        Msg::ToggleHelp => app.show_help = !app.show_help,
        Msg::Input(_) | Msg::Backspace => {
            if let Some(p) = &mut app.prompt {
                p.edit(&msg);
            }
        }
        Msg::Cancel => app.cancel(),
        Msg::Submit => app.submit(),
        Msg::LessonList => app.open_list(),
        _ if app.screen == Screen::Lessons => app.list_update(&msg),
        Msg::Move(dx, dy) => app.move_pixel(dx, dy),
        Msg::Pick(x, y) => app.pick(x, y),
        Msg::Click(col, row) => app.click(col, row),
        Msg::Wheel(col, row, delta) => app.wheel(col, row, delta),
        Msg::FocusNext => app.cycle_focus(true),
        Msg::FocusPrev => app.cycle_focus(false),
        Msg::Up | Msg::Down | Msg::Page(_) => app.focused(&msg),
        Msg::Sideways(steps) => app.pan_lesson(steps),
        Msg::Expand | Msg::Collapse | Msg::Toggle | Msg::ExpandAll => app.tree_update(&msg),
        Msg::DepthUp => app.step_depth(true),
        Msg::DepthDown => app.step_depth(false),
        Msg::LevelNext => app.step_level(true),
        Msg::LevelPrev => app.step_level(false),
        Msg::ToggleCsg => app.toggle_csg(),
        Msg::ToggleDiagram
        | Msg::CycleView
        | Msg::ToggleBvh
        | Msg::ToggleMarks
        | Msg::Zoom(_)
        | Msg::Pan(..)
        | Msg::Drag(..)
        | Msg::Release => app.diagram_update(&msg),
        Msg::CsgAll => app.csg_all(),
        Msg::ToggleReadme | Msg::Exercises | Msg::Work => app.lesson_update(&msg),
        Msg::NextScene => app.next_scene(),
        Msg::Goto => app.prompt = Some(Prompt::Goto(String::new())),
    }
    app.settle();
}

// --- Opening

impl App {
    fn empty(color: ColorMode) -> App {
        App {
            screen: Screen::Scene,
            file: SceneFile::default(),
            preview: Preview::default(),
            tree: RayTree::default(),
            csg: CsgPanel::default(),
            diagram: DiagramPane::default(),
            lesson: None,
            list: None,
            focus: Focus::Preview,
            prompt: None,
            message: None,
            show_help: false,
            color,
            size: (80, 24),
            quit: false,
        }
    }

    /// Opens a scene file, a lesson folder, or (None) the lesson list of `lessons_root()`.
    pub fn open(target: Option<&Path>, color: ColorMode) -> Result<App, String> {
        App::open_within(target, color, Limits::default())
    }

    /// As `open`, every scene of the session (the first, reloads, lessons opened from the
    /// list) loaded within `limits`.
    pub fn open_within(
        target: Option<&Path>,
        color: ColorMode,
        limits: Limits,
    ) -> Result<App, String> {
        let mut app = App::empty(color);
        app.file.limits = limits;
        match target {
            None => {
                app.screen = Screen::Lessons;
                app.list = Some(LessonList::load_default());
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

    /// Sets the maximum depth as the user would with + and -.
    pub fn with_depth(mut self, depth: u32) -> App {
        self.set_depth(depth);
        self.settle();
        self
    }

    fn open_target(&mut self, target: &Path) -> Result<(), String> {
        let Opened {
            path,
            scene,
            lesson,
            folder,
        } = SceneFile::open(target, &self.file.limits)?;
        self.file.watch(path, &scene);
        self.lesson = lesson.map(|l| {
            let mut panel = LessonPanel::new(l);
            panel.open = folder;
            panel
        });
        self.screen = Screen::Scene;
        self.tree.restart((scene.camera.width, scene.camera.height));
        self.focus = Focus::Preview;
        self.csg.hide();
        self.preview.clear();
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
        self.tree.adopt(&scene);
        self.file.scene = Some(Arc::new(scene));
        self.retrace();
        self.request_render();
    }

    /// Reloads the lesson and the scene file if they changed on disk.
    fn poll_files(&mut self) {
        if let Some(l) = &mut self.lesson {
            let note = l.poll();
            self.note(note);
        }
        if let Some((scene, (mut note, tone))) = self.file.poll() {
            let pixel = self.tree.pixel();
            self.set_scene(scene);
            // A smaller image keeps the picked pixel inside it: said, not done silently.
            let (x, y) = self.tree.pixel();
            if (x, y) != pixel && self.tree.aimed_ray().is_none() {
                let (w, h) = self.image_size();
                note.push_str(&format!(
                    " · the image is now {w} × {h}: pixel {},{} moved to {x},{y}",
                    pixel.0, pixel.1
                ));
            }
            self.message = Some((note, tone));
        }
    }
}

// --- What the drawing code and the event loop read

impl App {
    /// The image size of the scene (0 × 0 without one).
    pub fn image_size(&self) -> (u32, u32) {
        self.file.image_size()
    }

    /// Whether a lesson is open beside the scene.
    pub fn lesson_open(&self) -> bool {
        self.lesson.as_ref().is_some_and(|l| l.open)
    }

    /// The exercises are on screen and keys go to them.
    pub fn exercises_active(&self) -> bool {
        self.focus == Focus::Lesson && self.lesson.as_ref().is_some_and(|l| l.in_exercises())
    }

    fn area(&self) -> Rect {
        Rect::new(0, 0, self.size.0, self.size.1)
    }

    /// The panes of the scene screen at the current size.
    pub fn panes(&self) -> Panes {
        self.panes_in(self.area())
    }

    /// The panes of the scene screen in an area.
    pub fn panes_in(&self, area: Rect) -> Panes {
        let (w, h) = self.image_size();
        let aspect = if h == 0 { 1.0 } else { w as f64 / h as f64 };
        let open = layout::Open {
            lesson: self.lesson_open(),
            diagram: self.diagram.open,
        };
        layout::scene_panes(area, aspect, open, self.message_rows())
    }

    /// Lines the tree pane gives to rows at the current size.
    pub fn tree_body_height(&self) -> usize {
        self.tree.body_height(self.panes().tree)
    }

    /// How far the lower pane (details or CSG) and the lesson pane can scroll, in rows.
    pub fn scroll_limits(&self) -> (u16, u16) {
        let p = self.panes();
        let lower = if self.csg.shown() {
            self.csg.max_scroll(self.tree.selected(), p.lower)
        } else {
            self.tree.details_max_scroll(p.lower)
        };
        let lesson = self.lesson.as_ref().map_or(0, |l| l.max_scroll(p.lesson));
        (lower, lesson)
    }

    /// The message line, as text: a scene error wins over other messages.
    pub fn message_text(&self) -> Option<Note> {
        match (&self.file.error, &self.message) {
            (Some(e), _) => Some((format!("✗ {e} (the last good scene stays)"), Tone::Bad)),
            (None, Some(m)) => Some(m.clone()),
            // Nothing to say: what the keys do where the focus is.
            (None, None) if self.screen == Screen::Scene => {
                Some((panes::focus_hint(self.focus).into(), Tone::Info))
            }
            (None, None) => None,
        }
    }

    /// Message lines at the bottom: as many as a scene error takes, wrapped as it is drawn, up
    /// to `ERROR_ROWS` (the error's place in the file, then why: a long path must not leave
    /// the why below the screen).
    pub fn message_rows(&self) -> u16 {
        match (&self.file.error, &self.prompt) {
            (Some(_), None) => {
                let text = self.message_text().map_or(String::new(), |(t, _)| t);
                let rows = crate::tui::wrap::wrap_hang(&text, self.size.0 as usize, "  ").len();
                rows.clamp(1, ERROR_ROWS) as u16
            }
            _ => 1,
        }
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
}

// --- Keeping the parts in step

impl App {
    fn note(&mut self, note: Option<Note>) {
        if let Some(n) = note {
            self.message = Some(n);
        }
    }

    /// Traces the picked pixel again, and the CSG panel follows the new tree.
    fn retrace(&mut self) {
        let Some(scene) = &self.file.scene else {
            return;
        };
        self.tree.retrace(scene);
        if self.csg.shown() {
            self.refresh_csg();
        }
    }

    fn refresh_csg(&mut self) {
        let lower = self.panes().lower;
        let scene = self.file.scene.as_deref();
        self.csg
            .compute(scene, self.tree.shown_tree(), self.tree.selected(), lower);
    }

    /// The CSG panel scrolls to the newly selected ray's section.
    fn follow_selection(&mut self, moved: bool) {
        if moved && self.csg.shown() {
            let lower = self.panes().lower;
            self.csg.follow(self.tree.selected(), lower);
        }
    }

    /// Asks for a new preview at the current size and depth.
    fn request_render(&mut self) {
        if let Some(scene) = &self.file.scene {
            self.preview.request(scene, self.tree.preview_depth());
        }
    }

    /// Keeps what depends on the layout in step: the preview resolution, the focus, the tree
    /// scroll.
    fn settle(&mut self) {
        if self.screen != Screen::Scene || self.file.scene.is_none() {
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
        let scene = self.scene_name();
        let hidden = self
            .lesson
            .as_ref()
            .is_some_and(|l| l.hides_intensities(&scene));
        self.tree.set_hidden(hidden);
        let body = self.tree_body_height();
        self.tree.keep_selection_visible(body);
    }
}

// --- Pixel, depth, levels

/// A level-stepping note on the message line: the level reached, or all levels collected.
#[derive(Clone, Copy)]
enum LevelNote {
    Reached,
    Collected,
}

impl App {
    fn move_pixel(&mut self, dx: i32, dy: i32) {
        let levels = self.levels_said();
        if self.tree.move_by(dx, dy, self.image_size()) {
            self.retrace();
            self.say_levels_again(levels);
        }
    }

    /// Which of the level-stepping notes the message line shows, if one.
    fn levels_said(&self) -> Option<LevelNote> {
        let said = self.message.as_ref()?;
        if Some(said) == self.tree.level_note().as_ref() {
            Some(LevelNote::Reached)
        } else if self.tree.level().is_some() && *said == self.tree.collected_note() {
            Some(LevelNote::Collected)
        } else {
            None
        }
    }

    /// After another pixel's tree is traced: a level-stepping note on the message line is
    /// said again of the new tree (it kept the old pixel's intensities).
    fn say_levels_again(&mut self, said: Option<LevelNote>) {
        match said {
            Some(LevelNote::Collected) => self.message = Some(self.tree.collected_note()),
            Some(LevelNote::Reached) => self.message = self.tree.level_note(),
            None => {}
        }
    }

    fn pick(&mut self, x: u32, y: u32) {
        let levels = self.levels_said();
        match self.tree.pick(x, y, self.image_size()) {
            Ok(()) => {
                // The refusal of an earlier pick (a mistyped or outside pixel) is stale now;
                // the keys' hint is not.
                if matches!(self.message, Some((_, Tone::Bad))) {
                    self.message = None;
                }
                self.retrace();
                self.say_levels_again(levels);
            }
            Err(note) => self.message = Some(note),
        }
    }

    fn set_depth(&mut self, depth: u32) {
        if self.tree.set_depth(depth) {
            self.retrace();
            self.request_render();
        }
    }

    fn step_depth(&mut self, deeper: bool) {
        match self.tree.step_depth(deeper) {
            Ok(note) => {
                self.retrace();
                self.request_render();
                self.message = Some(note);
            }
            Err(note) => self.message = Some(note),
        }
    }

    fn step_level(&mut self, next: bool) {
        let collected = if next {
            self.tree.level_next()
        } else {
            self.tree.level_prev();
            false
        };
        self.retrace();
        let note = if collected {
            Some(self.tree.collected_note())
        } else {
            self.tree.level_note()
        };
        self.note(note);
    }
}
