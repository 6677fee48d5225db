//! The `raytree` command: render, inspect and explore scenes and lessons (all of it lives in
//! the library's `cli` module).

/// mimalloc rather than the C library's allocator: loading a large scene makes and frees hundreds
/// of thousands of small values on every thread, which it serves with less work and fewer fresh
/// pages to fault in (see docs/performance.md).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> std::process::ExitCode {
    raytree::cli::run()
}
