//! The `raytree` command: render, inspect and explore scenes and lessons (all of it lives in
//! the library's `cli` module).

#[cfg(target_os = "linux")]
#[global_allocator]
static ALLOCATOR: raytree::fast::huge_pages::HugePages = raytree::fast::huge_pages::HugePages;

fn main() -> std::process::ExitCode {
    raytree::cli::run()
}
