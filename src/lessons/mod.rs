//! Lessons: loading them, and checking students' answers against raytree's own computation.

mod answer;
pub mod builtin;
mod check;
mod error;
mod exercise;
pub mod grade;
pub mod homework;
pub mod progress;
pub mod raster;
mod tolerance;
pub mod validate;
mod vary;
mod yaml_spans;

pub use answer::{parse_answer, Answer};
pub use check::{check, explain, work, Verdict, Worked};
pub use error::{AnswerError, CheckError, LessonError, RangeError};
pub use exercise::{
    all_lessons, find_lesson, is_lesson_folder, lesson_dir, lessons_root, use_lessons_root, Ask,
    Exercise, Lesson, Solutions, VariantOf,
};
pub use tolerance::Tolerance;
pub use vary::Range;
