//! The parts of the explorer's model, each with its own data and the changes that concern only
//! it: the scene file, the preview, the picked pixel's ray tree, the CSG panel, the diagram
//! pane, the lesson panel, the lesson list and the prompt. `App` (app.rs) composes them and routes each
//! message.
//!
//! A part never reaches into another: what it needs from outside (the scene, a pane's
//! rectangle) comes in as arguments, and what others must follow (a retrace, a message for
//! the user) goes back as a return value.

pub mod csg;
pub mod details;
pub mod diagram;
pub mod exercises;
pub mod lesson;
pub mod list;
pub mod preview;
pub mod prompt;
pub mod ray_tree;
pub mod scene;
pub mod tree_state;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Tone {
    Info,
    Good,
    Bad,
}

/// A line for the message line.
pub type Note = (String, Tone);

/// The furthest `rows` rows can scroll in a pane of `height` rows.
pub(crate) fn max_scroll(rows: usize, height: u16) -> u16 {
    rows.saturating_sub(height as usize).min(u16::MAX as usize) as u16
}

/// A scroll position moved by `delta` rows, kept within 0..=`max`.
pub(crate) fn scrolled(at: u16, delta: i32, max: u16) -> u16 {
    (at as i32 + delta).clamp(0, max as i32) as u16
}
