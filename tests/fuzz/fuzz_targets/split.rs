//! The parallel scene loader against the one-thread parse, on arbitrary bytes made large
//! enough to be cut (see `checks/split.rs`).
#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "../checks/split.rs"]
mod split;

fuzz_target!(|data: &[u8]| {
    if let Some(text) = split::text_of(data) {
        split::check(&text);
    }
});
