//! The lessons are compiled into the library (`src/lessons/builtin.rs`): a change to any file
//! under `lessons/` rebuilds it.

fn main() {
    println!("cargo:rerun-if-changed=lessons");
}
