//! How `App` routes keys and the mouse to the panes: focus, Up/Down/Page in the focused pane,
//! scrolling, the CSG panel, clicks and the wheel. Which pane a cell belongs to comes from
//! layout.rs, how far a pane scrolls from the part it shows.

use ratatui::layout::Position;

use super::{App, Focus};
use crate::tui::layout::{self, inner};
use crate::tui::msg::Msg;
use crate::tui::state::Tone;

impl App {
    pub(super) fn focusable(&self) -> Vec<Focus> {
        let p = self.panes();
        let mut f = vec![Focus::Preview, Focus::Tree];
        if p.lower.is_some() {
            f.push(Focus::Lower);
        }
        if p.lesson.is_some() {
            f.push(Focus::Lesson);
        }
        if p.diagram.is_some() {
            f.push(Focus::Diagram);
        }
        f
    }

    pub(super) fn cycle_focus(&mut self, forward: bool) {
        let f = self.focusable();
        let i = f.iter().position(|&x| x == self.focus).unwrap_or(0);
        let n = f.len();
        self.focus = f[if forward {
            (i + 1) % n
        } else {
            (i + n - 1) % n
        }];
        self.hint_focus();
    }

    /// The keys' hint follows the focus, moved by Tab or by a click (a warning or an error
    /// stays until it is read).
    fn hint_focus(&mut self) {
        if self
            .message
            .as_ref()
            .is_none_or(|(_, tone)| *tone == Tone::Info)
        {
            self.message = Some((focus_hint(self.focus).into(), Tone::Info));
        }
    }

    /// Up, Down and Page in the focused pane (Page scrolls a panel when the preview has it).
    pub(super) fn focused(&mut self, msg: &Msg) {
        let (delta, page) = match *msg {
            Msg::Up => (-1, false),
            Msg::Down => (1, false),
            Msg::Page(d) => (10 * d, true),
            _ => return,
        };
        match self.focus {
            Focus::Tree => self.tree_update(msg),
            Focus::Lower => self.scroll_lower(delta),
            Focus::Preview if !page => self.move_pixel(0, delta),
            Focus::Preview if self.panes().lesson.is_some() => self.scroll_lesson(delta),
            Focus::Preview => self.scroll_lower(delta),
            Focus::Lesson if self.exercises_active() && page => {
                let pane = self.panes().lesson;
                if let Some(l) = &mut self.lesson {
                    l.scroll_exercise(delta, pane);
                }
            }
            Focus::Lesson if self.exercises_active() => {
                let i = self.lesson.as_ref().map_or(0, |l| l.exercise) as i64 + delta as i64;
                self.select_exercise(i.max(0) as usize);
            }
            Focus::Lesson => self.scroll_lesson(delta),
            Focus::Diagram => self.diagram.pan_steps(0, -delta.signum()),
        }
    }

    pub(super) fn tree_update(&mut self, msg: &Msg) {
        let moved = self.tree.update(msg);
        self.follow_selection(moved);
    }

    fn scroll_lower(&mut self, delta: i32) {
        let lower = self.panes().lower;
        if self.csg.shown() {
            self.csg.scroll_by(delta, self.tree.selected(), lower);
        } else {
            self.tree.scroll_details(delta, lower);
        }
    }

    fn scroll_lesson(&mut self, delta: i32) {
        let pane = self.panes().lesson;
        if let Some(l) = &mut self.lesson {
            l.scroll_by(delta, pane);
        }
    }

    /// ← → in the README: its figures, a quarter of the pane's width per step.
    pub(super) fn pan_lesson(&mut self, steps: i32) {
        let pane = self.panes().lesson;
        let step = pane.map_or(0, |r| (inner(r).width / 4).max(1) as i32);
        if let Some(l) = &mut self.lesson {
            if !l.in_exercises() {
                l.pan_by(steps * step, pane);
            }
        }
    }

    pub(super) fn toggle_csg(&mut self) {
        if !self.csg.toggle() {
            return;
        }
        self.refresh_csg();
        // Narrow screens have room for one of the two panels.
        if self.size.0 < layout::WIDE {
            if let Some(l) = &mut self.lesson {
                l.open = false;
            }
        }
        if self.csg.is_empty() {
            self.message = Some(("no object along these rays".into(), Tone::Info));
        }
    }

    /// C: every object evaluated whole in the CSG panel, or back to the objects met.
    pub(super) fn csg_all(&mut self) {
        let was_shown = self.csg.shown();
        self.csg.toggle_all();
        if !was_shown && self.size.0 < layout::WIDE {
            if let Some(l) = &mut self.lesson {
                l.open = false;
            }
        }
        self.refresh_csg();
        let note = if self.csg.all() {
            "CSG panel: every object, evaluated whole without bounding boxes (C: the objects met)"
        } else {
            "CSG panel: the objects the rays meet, through their bounding boxes (C: every object)"
        };
        self.message = Some((note.into(), Tone::Info));
    }

    pub(super) fn click(&mut self, col: u16, row: u16) {
        let focus = self.focus;
        self.click_at(col, row);
        if self.focus != focus {
            self.hint_focus();
        }
    }

    fn click_at(&mut self, col: u16, row: u16) {
        let at = Position::new(col, row);
        let p = self.panes();
        if let Some((x, y)) = layout::cell_pixel(&p, self.image_size(), col, row) {
            self.focus = Focus::Preview;
            self.pick(x, y);
        } else if p.tree.contains(at) {
            self.focus = Focus::Tree;
            let body = inner(p.tree);
            let top = body.y + self.tree.head_lines() as u16;
            if row >= top && row < body.bottom() {
                let moved = self.tree.click((row - top) as usize);
                self.follow_selection(moved);
            }
        } else if p.lower.is_some_and(|r| r.contains(at)) {
            self.focus = Focus::Lower;
        } else if p.lesson.is_some_and(|r| r.contains(at)) {
            self.focus = Focus::Lesson;
        } else if p.diagram.is_some_and(|r| r.contains(at)) {
            self.focus = Focus::Diagram;
            self.diagram.drag = Some((col, row));
        }
    }

    pub(super) fn wheel(&mut self, col: u16, row: u16, delta: i32) {
        let at = Position::new(col, row);
        let p = self.panes();
        if p.tree.contains(at) {
            let body = self.tree_body_height();
            self.tree.scroll_rows(delta, body);
        } else if p.lower.is_some_and(|r| r.contains(at)) {
            self.scroll_lower(delta);
        } else if p.lesson.is_some_and(|r| r.contains(at)) {
            self.scroll_lesson(delta);
        } else if p.diagram.is_some_and(|r| r.contains(at)) {
            // The wheel zooms: up (negative) zooms in.
            self.diagram.zoom_by(-delta);
        }
    }

    /// The diagram's keys and the mouse dragging over it.
    pub(super) fn diagram_update(&mut self, msg: &Msg) {
        match *msg {
            Msg::ToggleDiagram => {
                let note = self.diagram.toggle();
                self.message = Some(note);
            }
            Msg::CycleView => {
                let note = self.diagram.cycle_view();
                self.message = Some(note);
            }
            Msg::ToggleBvh => {
                let note = self.diagram.toggle_bvh(self.file.scene.as_deref());
                self.message = Some(note);
            }
            Msg::ToggleMarks => {
                self.preview.marks = !self.preview.marks;
                let note = if !self.preview.marks {
                    "hit marks hidden"
                } else if self.marks_in_view() == 0 {
                    "hit marks on: none to show, this tree's reflection and refraction rays land \
                     outside the picture (or it has none)"
                } else {
                    "hit points marked on the preview: ◆ where the rays landed (reflection, refraction)"
                };
                self.message = Some((note.into(), Tone::Info));
            }
            Msg::Zoom(steps) => self.diagram.zoom_by(steps),
            Msg::Pan(dx, dy) => self.diagram.pan_steps(dx, dy),
            Msg::Drag(col, row) => {
                if let Some(r) = self.panes().diagram {
                    let body = inner(r);
                    self.diagram.drag_to(col, row, (body.width, body.height));
                }
            }
            Msg::Release => self.diagram.drag = None,
            _ => {}
        }
    }
}

impl App {
    /// How many of the tree's reflection and refraction hits land inside the picture.
    fn marks_in_view(&self) -> usize {
        let (Some(scene), Some(root)) = (self.file.scene.as_deref(), self.tree.shown_tree()) else {
            return 0;
        };
        let (w, h) = self.image_size();
        crate::diagram::marks::hit_marks(&scene.camera, root)
            .iter()
            .filter(|m| m.at.x >= 0.0 && m.at.y >= 0.0 && m.at.x < w as f64 && m.at.y < h as f64)
            .count()
    }
}

/// What the arrows and the other keys do where the focus is, for the message line.
pub(super) fn focus_hint(focus: Focus) -> &'static str {
    match focus {
        Focus::Preview => "←↑↓→ pick a pixel · Tab tree · +/- depth · n/p levels · ? keys",
        Focus::Tree => "↑↓ select a ray · → ← open / close · Enter toggle · Tab next pane · ? keys",
        Focus::Lower => "↑↓ PgUp PgDn scroll the panel · Tab next pane · ? keys",
        Focus::Lesson => "↑↓ PgUp PgDn scroll · ← → figures sideways · Tab next pane · ? keys",
        Focus::Diagram => "←↑↓→ pan the diagram · < > zoom · v view · Tab next pane · ? keys",
    }
}
