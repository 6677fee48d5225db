//! Lessons: loading them, and checking students' answers against raytree's own computation.

mod answer;
mod check;
mod exercise;

pub use answer::{parse_answer, Answer};
pub use check::{check, explain, work, Verdict, Worked};
pub use exercise::{all_lessons, lessons_root, Ask, Exercise, Lesson};
