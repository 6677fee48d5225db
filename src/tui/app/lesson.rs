//! How `App` routes the prompt, the lesson panel and the lesson list: typing and Enter, the
//! README and the exercises (an exercise points the ray tree at its pixel and ray), and
//! opening a lesson from the list.

use super::{App, Focus, Screen};
use crate::lessons;
use crate::tui::layout;
use crate::tui::msg::Msg;
use crate::tui::state::lesson::NO_LESSON;
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

    /// Selects an exercise, and points the ray tree at what it asks about.
    pub(super) fn select_exercise(&mut self, i: usize) {
        let size = self.image_size();
        let Some(l) = &mut self.lesson else { return };
        let Some((aim, note)) = l.select_exercise(i, self.file.scene.as_deref(), size) else {
            return;
        };
        if let Some(aim) = aim {
            self.tree.aim(aim.pixel, aim.depth);
            if aim.depth.is_some() {
                self.request_render();
            }
            self.retrace();
            let moved = self.tree.select_kinds(&aim.node);
            self.follow_selection(moved);
        }
        self.message = Some(note);
    }

    pub(super) fn open_list(&mut self) {
        let mut list = LessonList::load(&lessons::lessons_root());
        if let Some(l) = &self.lesson {
            if let Some(i) = list.entries.iter().position(|e| e.dir == l.lesson.dir) {
                list.selected = i;
            }
        }
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
