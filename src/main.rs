fn main() -> std::process::ExitCode {
    raytree::cli::run()
}
