//! The messages that change the explorer's model: everything it does is one of these, sent to
//! `update` (app.rs) by the key mapping (input.rs), the event loop or a test.

use super::worker::Done;

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
    /// The ray diagram pane (`d`), its view (`v`), the BVH boxes over it (`b`), the hit
    /// points marked on the preview (`m`).
    ToggleDiagram,
    CycleView,
    ToggleBvh,
    ToggleMarks,
    /// Zooms the diagram in (positive) or out, in steps.
    Zoom(i32),
    /// Pans the diagram by arrow steps (right and up positive).
    Pan(i32, i32),
    /// A drag of the mouse to a cell (the diagram pans with it).
    Drag(u16, u16),
    /// The mouse button let go.
    Release,
    /// The CSG panel with every object evaluated whole, or the objects met only (`C`).
    CsgAll,
    ToggleReadme,
    ToggleHelp,
    /// The lesson's next scene (`s`).
    NextScene,
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
