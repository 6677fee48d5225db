//! The messages that change the explorer's model: everything it does is one of these, sent to
//! `update` (app.rs) by the key mapping (input.rs), the event loop or a test.

use super::worker::Done;

/// Everything that can happen to the explorer: keys, mouse, time and finished renders, each a
/// change `update` makes to the `App`.
#[derive(Debug)]
pub enum Msg {
    /// Leave the explorer (`q`, Esc, Ctrl-C).
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
    /// Focus the next pane (Tab).
    FocusNext,
    /// Focus the previous pane (Shift-Tab).
    FocusPrev,
    /// Arrow keys in the focused pane (tree, panel, list).
    Up,
    /// Arrow down in the focused pane.
    Down,
    /// Opens the selected tree node (→).
    Expand,
    /// Closes the selected tree node (←).
    Collapse,
    /// Opens or closes the selected tree node (Enter, space).
    Toggle,
    /// Opens every node, or back to the default.
    ExpandAll,
    /// ← → in the lesson pane: its README's figures moved sideways by steps (negative: left).
    Sideways(i32),
    /// Page up (negative) / down in the panel.
    Page(i32),
    /// One more ray per path (`+`): the maximum depth up by one.
    DepthUp,
    /// One ray fewer per path (`-`): the maximum depth down by one.
    DepthDown,
    /// Steps the tree open one recursion level / closes one.
    LevelNext,
    /// Closes the deepest open recursion level of the tree (`p`).
    LevelPrev,
    /// Shows or hides the CSG panel (`c`).
    ToggleCsg,
    /// The ray diagram pane (`d`), its view (`v`), the BVH boxes over it (`b`), the hit
    /// points marked on the preview (`m`).
    ToggleDiagram,
    /// The diagram's next view: top, side, front (`v`).
    CycleView,
    /// Shows or hides the BVH boxes over the diagram (`b`).
    ToggleBvh,
    /// Shows or hides the hit points on the preview (`m`).
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
    /// Shows or hides the lesson's README (`r`).
    ToggleReadme,
    /// Shows or hides the key help (`?`).
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
    /// A character typed into the prompt.
    Input(char),
    /// Deletes the prompt's last character.
    Backspace,
    /// Enter: confirms a prompt, opens a lesson, answers an exercise.
    Submit,
    /// Esc in a prompt or a list.
    Cancel,
    /// Time passes: the scene file is checked for changes.
    Tick,
    /// Render progress: generation, rows done, rows in the pass.
    Progress(u64, u32, u32),
    /// A render pass finished on the worker thread.
    Rendered(Done),
}
