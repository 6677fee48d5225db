//! Random rays against random shapes: segment lists ordered, no NaN, normals unit.
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "../checks/intersect.rs"]
mod intersect;

fuzz_target!(|data: &[u8]| intersect::check(data));
