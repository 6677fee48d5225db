//! The lesson list (`raytree explore` without an argument, or `o`): every lesson folder under
//! the lessons root (or under the folder the open lesson came from), the selected one, and
//! whether Esc goes back to a scene.

use std::path::{Path, PathBuf};

use ratatui::layout::{Position, Rect};

use std::collections::BTreeSet;

use crate::lessons::progress::Progress;
use crate::lessons::Lesson;
use crate::tui::layout::{inner, list_offset};
use crate::tui::msg::Msg;

/// One lesson folder of the list; a lesson that does not load is listed with its error.
pub struct LessonEntry {
    pub dir: PathBuf,
    pub lesson: Result<Lesson, String>,
    /// Its exercises answered right (the user's progress).
    pub solved: BTreeSet<String>,
}

pub struct LessonList {
    pub root: PathBuf,
    pub entries: Vec<LessonEntry>,
    pub selected: usize,
    pub error: Option<String>,
    /// The list was opened from a scene, which Esc goes back to.
    pub from_scene: bool,
}

impl LessonList {
    /// The lessons of `lessons::lessons_root()`, or the list saying why there are none.
    pub fn load_default() -> LessonList {
        match crate::lessons::lessons_root() {
            Ok(root) => LessonList::load(&root),
            Err(e) => LessonList {
                root: PathBuf::new(),
                entries: vec![],
                selected: 0,
                error: Some(e.to_string()),
                from_scene: false,
            },
        }
    }

    /// The list `o` shows beside the lesson in `open`: the folder that lesson came from where
    /// it holds other lessons too (a user's own folder, which need not be the lessons root),
    /// else the lessons root's; the open lesson selected.
    pub fn around(open: Option<&Path>) -> LessonList {
        let mut list = match open.and_then(folder_of_lessons) {
            Some(root) => LessonList::load(&root),
            None => LessonList::load_default(),
        };
        if let Some(dir) = open {
            if let Some(i) = list.entries.iter().position(|e| same_dir(&e.dir, dir)) {
                list.selected = i;
            }
        }
        list
    }

    /// Every folder under `root` with an exercises.yaml, in name order.
    pub fn load(root: &Path) -> LessonList {
        let mut list = LessonList {
            root: root.to_path_buf(),
            entries: vec![],
            selected: 0,
            error: None,
            from_scene: false,
        };
        let mut dirs: Vec<PathBuf> = match std::fs::read_dir(root) {
            Ok(rd) => rd
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| crate::lessons::is_lesson_folder(p))
                .collect(),
            Err(e) => {
                list.error = Some(format!("{}: cannot list lessons: {e}", root.display()));
                return list;
            }
        };
        dirs.sort();
        let progress = Progress::load();
        list.entries = dirs
            .into_iter()
            .map(|dir| {
                let lesson = Lesson::load(&dir).map_err(String::from);
                LessonEntry {
                    solved: lesson
                        .as_ref()
                        .map(|l| progress.solved(l))
                        .unwrap_or_default(),
                    lesson,
                    dir,
                }
            })
            .collect();
        list.error = list.entries.is_empty().then(|| {
            format!(
                "no lessons in {} (set RAYTREE_LESSONS to the lessons folder)",
                root.display()
            )
        });
        list
    }

    /// Keys and the mouse on the list screen, whose list pane is `pane`; true when the
    /// selected lesson is to be opened.
    pub fn update(&mut self, msg: &Msg, pane: Rect) -> bool {
        match *msg {
            Msg::Up => self.step(-1),
            Msg::Down => self.step(1),
            Msg::Page(d) => self.step(d as i64 * 10),
            Msg::Wheel(_, _, d) => self.step(d as i64),
            Msg::Click(col, row) => return self.click(col, row, pane),
            _ => {}
        }
        false
    }

    fn step(&mut self, delta: i64) {
        if !self.entries.is_empty() {
            self.selected =
                (self.selected as i64 + delta).clamp(0, self.entries.len() as i64 - 1) as usize;
        }
    }

    /// A click selects a lesson; a click on the selected one opens it (true).
    fn click(&mut self, col: u16, row: u16, pane: Rect) -> bool {
        let inner = inner(pane);
        if !inner.contains(Position::new(col, row)) {
            return false;
        }
        let i = list_offset(self.selected, inner.height as usize) + (row - inner.y) as usize;
        if i >= self.entries.len() {
            return false;
        }
        if i == self.selected {
            return true;
        }
        self.selected = i;
        false
    }
}

/// The folder that holds the lesson `dir` and at least one other lesson.
fn folder_of_lessons(dir: &Path) -> Option<PathBuf> {
    let name = dir.file_name()?;
    let parent = match dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let others = std::fs::read_dir(parent)
        .ok()?
        .filter_map(|e| e.ok())
        .any(|e| e.file_name() != name && crate::lessons::is_lesson_folder(&e.path()));
    others.then(|| parent.to_path_buf())
}

/// Whether two paths name the same folder, however each is written (`./a`, `a`).
fn same_dir(a: &Path, b: &Path) -> bool {
    a == b
        || matches!(
            (a.canonicalize(), b.canonicalize()),
            (Ok(a), Ok(b)) if a == b
        )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn list(n: usize) -> LessonList {
        LessonList {
            root: PathBuf::from("lessons"),
            entries: (0..n)
                .map(|i| LessonEntry {
                    dir: PathBuf::from(format!("lessons/{i:02}")),
                    lesson: Err("does not load".into()),
                    solved: Default::default(),
                })
                .collect(),
            selected: 0,
            error: None,
            from_scene: false,
        }
    }

    #[test]
    fn keys_move_within_the_list() {
        let pane = Rect::new(0, 0, 40, 10);
        let mut l = list(5);
        assert!(!l.update(&Msg::Page(1), pane));
        assert_eq!(l.selected, 4);
        l.update(&Msg::Up, pane);
        l.update(&Msg::Wheel(0, 0, -9), pane);
        assert_eq!(l.selected, 0);
        let mut empty = list(0);
        empty.update(&Msg::Down, pane);
        assert_eq!(empty.selected, 0);
    }

    #[test]
    fn a_click_selects_and_a_second_click_opens() {
        let pane = Rect::new(0, 0, 40, 10);
        let mut l = list(5);
        assert!(
            !l.update(&Msg::Click(3, 3), pane),
            "row 3 is the third lesson"
        );
        assert_eq!(l.selected, 2);
        assert!(l.update(&Msg::Click(3, 3), pane));
        assert!(!l.update(&Msg::Click(3, 8), pane), "below the last lesson");
        assert!(!l.update(&Msg::Click(0, 3), pane), "on the border");
        assert_eq!(l.selected, 2);
    }
}
