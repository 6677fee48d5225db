//! How `App` routes the prompt, the lesson panel and the lesson list: typing and Enter, the
//! README and the exercises (an exercise points the ray tree at its pixel and ray), and
//! opening a lesson from the list.

use super::{App, Focus, Screen};
use crate::tui::layout;
use crate::tui::msg::Msg;
use crate::tui::state::lesson::{AimAt, NO_LESSON};
use crate::tui::state::list::LessonList;
use crate::tui::state::prompt::{parse_pixel, Prompt};
use crate::tui::state::Tone;

impl App {
    pub(super) fn cancel(&mut self) {
        if self.prompt.take().is_some() {
            return;
        }
        if self.screen == Screen::Lessons && self.list.as_ref().is_some_and(|l| l.from_scene) {
            self.screen = Screen::Scene;
        } else if self.focus == Focus::Lesson {
            self.focus = Focus::Preview;
            // The exercise's "Esc: back" is said and done: a second Esc quits.
            self.message = Some((
                "back to the picture · a: the exercises · Esc or q: quit".into(),
                Tone::Info,
            ));
        }
    }

    /// Enter: confirms a prompt, opens a lesson, starts an answer, opens or closes a ray.
    pub(super) fn submit(&mut self) {
        match self.prompt.take() {
            Some(Prompt::Goto(s)) => match parse_pixel(&s) {
                Some((x, y)) => self.pick(x, y),
                None => {
                    self.message = Some((
                        format!("expected a pixel x,y (two whole numbers), got `{s}`"),
                        Tone::Bad,
                    ))
                }
            },
            Some(Prompt::Answer { exercise, text }) => {
                if let Some(l) = &mut self.lesson {
                    let note = l.answer(exercise, text);
                    self.note(note);
                }
            }
            None if self.screen == Screen::Lessons => self.open_selected_lesson(),
            None if self.exercises_active() => {
                let exercise = self.lesson.as_ref().map_or(0, |l| l.exercise);
                self.prompt = Some(Prompt::Answer {
                    exercise,
                    text: String::new(),
                });
            }
            None if self.focus == Focus::Tree => self.tree_update(&Msg::Toggle),
            None => {}
        }
    }

    pub(super) fn lesson_update(&mut self, msg: &Msg) {
        let Some(l) = &mut self.lesson else {
            self.message = Some((NO_LESSON.into(), Tone::Bad));
            return;
        };
        match msg {
            Msg::ToggleReadme => l.toggle_readme(),
            Msg::Exercises => {
                l.show_exercises();
                let i = l.exercise;
                self.focus = Focus::Lesson;
                self.select_exercise(i);
            }
            Msg::Work => {
                let note = l.toggle_work();
                self.note(note);
            }
            _ => {}
        }
    }

    /// Selects an exercise, switches to the scene it is posed on, and points the ray tree at
    /// what it asks about.
    pub(super) fn select_exercise(&mut self, i: usize) {
        let Some(l) = &self.lesson else { return };
        let n = l.lesson.exercises.len();
        if let Some(wanted) = l.scene_of(i.min(n.saturating_sub(1))) {
            if wanted != self.scene_name() {
                if let Err(e) = self.switch_scene(&wanted) {
                    self.message = Some((e, Tone::Bad));
                    return;
                }
            }
        }
        let size = self.image_size();
        let Some(l) = &mut self.lesson else { return };
        let Some((aim, note)) = l.select_exercise(i, self.file.scene.as_deref(), size) else {
            return;
        };
        if let Some(aim) = aim {
            let scene_depth = self.file.scene.as_ref().map_or(1, |s| s.max_depth);
            let changed = match aim.at {
                AimAt::Pixel(x, y) => self.tree.aim((x, y), aim.depth, scene_depth),
                AimAt::Ray(r) => self.tree.aim_ray(r, aim.depth, scene_depth),
            };
            // The preview renders at the depth the tree is traced to: trace it first.
            self.retrace();
            if changed {
                self.request_render();
            }
            let moved = self.tree.select_kinds(&aim.node);
            self.follow_selection(moved);
        }
        self.message = Some(note);
    }

    /// The file name of the scene shown ("scene.yaml").
    pub(super) fn scene_name(&self) -> String {
        self.file
            .path
            .as_ref()
            .and_then(|p| p.file_name())
            .map_or(String::new(), |n| n.to_string_lossy().into_owned())
    }

    /// Shows another scene of the lesson (its file name), the lesson kept.
    pub(super) fn switch_scene(&mut self, name: &str) -> Result<(), String> {
        let Some(l) = &self.lesson else {
            return Err(NO_LESSON.into());
        };
        let path = l.lesson.dir.join(name);
        let scene = crate::scene::load(&path, &self.file.limits).map_err(|e| e.to_string())?;
        self.file.watch(path, &scene);
        self.tree.restart((scene.camera.width, scene.camera.height));
        self.preview.clear();
        self.set_scene(scene);
        Ok(())
    }

    /// s: the lesson's next scene.
    pub(super) fn next_scene(&mut self) {
        let Some(l) = &self.lesson else {
            self.message = Some((NO_LESSON.into(), Tone::Bad));
            return;
        };
        let scenes = l.scenes();
        let current = self.scene_name();
        if scenes.len() == 1 && scenes[0] == current {
            self.message = Some((
                format!("this lesson has one scene, {current}, and it is shown"),
                Tone::Info,
            ));
            return;
        }
        let k = scenes
            .iter()
            .position(|s| *s == current)
            .map_or(0, |k| (k + 1) % scenes.len());
        let name = scenes[k].clone();
        self.message = Some(match self.switch_scene(&name) {
            Ok(()) => (
                format!(
                    "scene {name} ({} of {}) · s: the lesson's next scene",
                    k + 1,
                    scenes.len()
                ),
                Tone::Info,
            ),
            Err(e) => (e, Tone::Bad),
        });
    }

    pub(super) fn open_list(&mut self) {
        let mut list = LessonList::around(self.lesson.as_ref().map(|l| l.lesson.dir.as_path()));
        list.from_scene = self.file.scene.is_some();
        self.list = Some(list);
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
        if let Err(e) = self.open_target(&dir) {
            if let Some(list) = &mut self.list {
                list.error = Some(e);
            }
        }
    }

    pub(super) fn list_update(&mut self, msg: &Msg) {
        let (pane, ..) = layout::list_panes(self.area());
        if self.list.as_mut().is_some_and(|l| l.update(msg, pane)) {
            self.open_selected_lesson();
        }
    }
}
