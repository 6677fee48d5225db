//! The `raytree` command: render, inspect and explore scenes and lessons (all of it lives in
//! the library's `cli` module).

fn main() -> std::process::ExitCode {
    raytree::cli::run()
}
