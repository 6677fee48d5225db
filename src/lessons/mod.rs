//! Lessons: loading them, and checking students' answers against raytree's own computation.

mod answer;
mod check;
mod exercise;
mod tolerance;

pub use answer::{parse_answer, Answer};
pub use check::{check, explain, work, Verdict, Worked};
pub use exercise::{all_lessons, lessons_root, Ask, Exercise, Lesson};
pub use tolerance::Tolerance;
