//! Keys and mouse events to messages. What a key means depends on what is on screen (a prompt
//! takes every character, the help closes on any key, arrows act on the focused pane), so the
//! mapping reads the model; it never changes it.

use crossterm::event::{
    Event, KeyCode, KeyEvent, KeyEventKind, KeyModifiers, MouseButton, MouseEvent, MouseEventKind,
};

use super::app::{App, Focus, Screen, BIG_STEP};
use super::msg::Msg;

/// The message for a terminal event, if it means anything.
pub fn event(app: &App, ev: &Event) -> Option<Msg> {
    match ev {
        Event::Key(k) => key(app, k),
        Event::Mouse(m) => mouse(app, m),
        Event::Resize(w, h) => Some(Msg::Resize(*w, *h)),
        _ => None,
    }
}

/// Ctrl-Z: stop the explorer as a shell's job control does (raw mode delivers it as a key,
/// not as SIGTSTP), the terminal restored until `fg`.
pub fn is_suspend(ev: &Event) -> bool {
    matches!(ev, Event::Key(k) if k.kind == KeyEventKind::Press
        && k.code == KeyCode::Char('z')
        && k.modifiers.contains(KeyModifiers::CONTROL))
}

/// The message for a mouse event (a click picks or selects, a drag picks or pans, the wheel
/// scrolls), or None when it means nothing here.
pub fn mouse(app: &App, m: &MouseEvent) -> Option<Msg> {
    if app.show_help || app.prompt.is_some() {
        return None;
    }
    match m.kind {
        MouseEventKind::Down(MouseButton::Left) => Some(Msg::Click(m.column, m.row)),
        // Dragging over the preview keeps picking; over the diagram it pans.
        MouseEventKind::Drag(MouseButton::Left) if app.focus == Focus::Preview => {
            Some(Msg::Click(m.column, m.row))
        }
        MouseEventKind::Drag(MouseButton::Left) if app.focus == Focus::Diagram => {
            Some(Msg::Drag(m.column, m.row))
        }
        MouseEventKind::Up(MouseButton::Left) => Some(Msg::Release),
        MouseEventKind::ScrollUp => Some(Msg::Wheel(m.column, m.row, -1)),
        MouseEventKind::ScrollDown => Some(Msg::Wheel(m.column, m.row, 1)),
        _ => None,
    }
}

/// The message for a key press, given what is on screen and focused; None for keys that mean
/// nothing there.
pub fn key(app: &App, k: &KeyEvent) -> Option<Msg> {
    if k.kind == KeyEventKind::Release {
        return None;
    }
    let ctrl = k.modifiers.contains(KeyModifiers::CONTROL);
    let shift = k.modifiers.contains(KeyModifiers::SHIFT);
    if ctrl && matches!(k.code, KeyCode::Char('c')) {
        return Some(Msg::Quit);
    }
    if app.prompt.is_some() {
        return match k.code {
            KeyCode::Enter => Some(Msg::Submit),
            KeyCode::Esc => Some(Msg::Cancel),
            KeyCode::Backspace => Some(Msg::Backspace),
            KeyCode::Char(c) if !ctrl => Some(Msg::Input(c)),
            _ => None,
        };
    }
    if app.show_help {
        return match k.code {
            KeyCode::Char('q') => Some(Msg::Quit),
            _ => Some(Msg::ToggleHelp),
        };
    }
    if app.screen == Screen::Lessons {
        return match k.code {
            KeyCode::Char('q') => Some(Msg::Quit),
            KeyCode::Esc => Some(Msg::Cancel)
                .filter(|_| app.file.scene.is_some())
                .or(Some(Msg::Quit)),
            KeyCode::Char('?') => Some(Msg::ToggleHelp),
            KeyCode::Up | KeyCode::Char('k') => Some(Msg::Up),
            KeyCode::Down | KeyCode::Char('j') => Some(Msg::Down),
            KeyCode::PageUp => Some(Msg::Page(-1)),
            KeyCode::PageDown => Some(Msg::Page(1)),
            KeyCode::Enter | KeyCode::Right | KeyCode::Char('l') => Some(Msg::Submit),
            _ => None,
        };
    }
    let big = |dx: i32, dy: i32| Some(Msg::Move(dx * BIG_STEP, dy * BIG_STEP));
    // Keys that mean the same everywhere on the scene screen.
    match k.code {
        KeyCode::Char('q') => return Some(Msg::Quit),
        // Esc goes back a step: out of the exercises, then closes the panels, then quits.
        KeyCode::Esc => {
            return Some(if app.exercises_active() {
                Msg::Cancel
            } else if app.diagram.open {
                Msg::ToggleDiagram
            } else if app.csg.shown() {
                Msg::ToggleCsg
            } else {
                Msg::Quit
            });
        }
        KeyCode::Char('?') => return Some(Msg::ToggleHelp),
        KeyCode::Char('g') => return Some(Msg::Goto),
        KeyCode::Char('+' | '=' | ']') => return Some(Msg::DepthUp),
        KeyCode::Char('-' | '_' | '[') => return Some(Msg::DepthDown),
        KeyCode::Char('n') => return Some(Msg::LevelNext),
        KeyCode::Char('p') => return Some(Msg::LevelPrev),
        KeyCode::Char('c') => return Some(Msg::ToggleCsg),
        KeyCode::Char('d') => return Some(Msg::ToggleDiagram),
        KeyCode::Char('v') => return Some(Msg::CycleView),
        KeyCode::Char('b') => return Some(Msg::ToggleBvh),
        KeyCode::Char('m') => return Some(Msg::ToggleMarks),
        KeyCode::Char('<' | ',') => return Some(Msg::Zoom(-1)),
        KeyCode::Char('>' | '.') => return Some(Msg::Zoom(1)),
        KeyCode::Char('C') => return Some(Msg::CsgAll),
        KeyCode::Char('r') => return Some(Msg::ToggleReadme),
        KeyCode::Char('a') => return Some(Msg::Exercises),
        KeyCode::Char('s') => return Some(Msg::NextScene),
        KeyCode::Char('w') => return Some(Msg::Work),
        KeyCode::Char('o') => return Some(Msg::LessonList),
        KeyCode::Char('e') => return Some(Msg::ExpandAll),
        KeyCode::Tab => return Some(Msg::FocusNext),
        KeyCode::BackTab => return Some(Msg::FocusPrev),
        KeyCode::PageUp => return Some(Msg::Page(-1)),
        KeyCode::PageDown => return Some(Msg::Page(1)),
        KeyCode::Char('H') => return big(-1, 0),
        KeyCode::Char('J') => return big(0, 1),
        KeyCode::Char('K') => return big(0, -1),
        KeyCode::Char('L') => return big(1, 0),
        KeyCode::Left if shift => return big(-1, 0),
        KeyCode::Down if shift => return big(0, 1),
        KeyCode::Up if shift => return big(0, -1),
        KeyCode::Right if shift => return big(1, 0),
        _ => {}
    }
    let (left, down, up, right) = (
        matches!(k.code, KeyCode::Left | KeyCode::Char('h')),
        matches!(k.code, KeyCode::Down | KeyCode::Char('j')),
        matches!(k.code, KeyCode::Up | KeyCode::Char('k')),
        matches!(k.code, KeyCode::Right | KeyCode::Char('l')),
    );
    match app.focus {
        Focus::Preview => {
            if left {
                Some(Msg::Move(-1, 0))
            } else if right {
                Some(Msg::Move(1, 0))
            } else if up {
                Some(Msg::Move(0, -1))
            } else if down {
                Some(Msg::Move(0, 1))
            } else {
                None
            }
        }
        Focus::Tree => {
            if up {
                Some(Msg::Up)
            } else if down {
                Some(Msg::Down)
            } else if right {
                Some(Msg::Expand)
            } else if left {
                Some(Msg::Collapse)
            } else if matches!(k.code, KeyCode::Enter | KeyCode::Char(' ')) {
                Some(Msg::Toggle)
            } else {
                None
            }
        }
        Focus::Diagram => {
            if left {
                Some(Msg::Pan(-1, 0))
            } else if right {
                Some(Msg::Pan(1, 0))
            } else if up {
                Some(Msg::Pan(0, 1))
            } else if down {
                Some(Msg::Pan(0, -1))
            } else {
                None
            }
        }
        Focus::Lower | Focus::Lesson => {
            if app.focus == Focus::Lesson && (left || right) {
                Some(Msg::Sideways(if left { -1 } else { 1 }))
            } else if up {
                Some(Msg::Up)
            } else if down {
                Some(Msg::Down)
            } else if k.code == KeyCode::Enter {
                Some(Msg::Submit)
            } else {
                None
            }
        }
    }
}
