//! The command line: one module per subcommand; this one parses and dispatches.
//!
//! Output goes through `output` (`print!` and `eprintln!` panic when the write fails, as on a
//! closed pipe or a full device); clippy refuses them here.
#![deny(clippy::print_stdout, clippy::print_stderr)]

mod args;
mod bench;
mod check;
mod completions;
mod cpu;
pub mod csg;
mod diagram;
mod explore;
mod grade;
mod homework;
mod inspect;
mod lessons;
mod man;
mod output;
mod peak_memory;
mod preview;
mod render;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// A step-by-step Whitted ray tracer with a ray-tree debugger.
#[derive(Parser, Debug)]
#[command(name = "raytree", version, about, long_about = None, arg_required_else_help = true)]
pub struct Cli {
    /// A folder of lessons to use instead of the built-in ones (also RAYTREE_LESSONS).
    #[arg(long, global = true, value_name = "DIR")]
    lessons: Option<std::path::PathBuf>,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Render a scene to a PNG, PPM or EXR image (or, with -o -, to standard output).
    Render(render::Args),
    /// Print the ray tree of a pixel or of any ray.
    Inspect(inspect::Args),
    /// Print the segment list at every node of every object a ray meets.
    Csg(csg::Args),
    /// Draw a pixel's rays in a cross-section of the scene, beside its ray tree (SVG or PNG).
    Diagram(diagram::Args),
    /// Print a half-block (colour) or ASCII preview of a scene to stdout.
    Preview(preview::Args),
    /// The terminal explorer: pick a pixel, see its ray tree (no argument: the lesson list).
    Explore(explore::Args),
    /// Measurements: run time against error (sweep), time per ray against scene size (scaling),
    /// speed against threads (threads), the explorer's waits (explorer).
    Bench(bench::Args),
    /// List the lessons and their exercises (or a folder's); `lessons validate DIR` checks them.
    Lessons(lessons::Args),
    /// Check a homework answer against raytree's computation (exit 0 right, 1 wrong).
    Check(check::Args),
    /// Grade a class's answers (CSV student,exercise,answer), each against the student's own variant.
    Grade(grade::Args),
    /// Write one student's own variant of a lesson (its `vary:` values drawn for their ID).
    Homework(homework::Args),
    /// Shell completions (bash, zsh, fish, elvish, powershell) on stdout.
    Completions(completions::Args),
    /// The manual page (roff) on stdout, or a page per command into a folder.
    Man(man::Args),
}

/// An error for the user: printed as one line, exit status 2.
#[derive(Debug)]
pub struct Failure(pub String);

/// Separates a failure's one line from the lines shown under it on a terminal only (a scene
/// error's snippet): scripts and tests read the one line.
const SNIPPET: char = '\u{0}';

impl Failure {
    /// A scene error: its one line, and (on a terminal) the line of the file it points at with
    /// a caret under the column.
    pub fn scene(e: crate::scene::SceneError) -> Failure {
        match e.snippet() {
            Some(snippet) => Failure(format!("{e}{SNIPPET}{snippet}")),
            None => Failure(e.to_string()),
        }
    }
}

impl<E: std::fmt::Display> From<E> for Failure {
    fn from(e: E) -> Failure {
        Failure(e.to_string())
    }
}

/// Runs the `raytree` command line on the process's arguments; the exit code reports success,
/// failure or a usage error.
pub fn run() -> ExitCode {
    if let Err(msg) = cpu::check() {
        output::eprintln(&format!("raytree: {msg}"));
        return ExitCode::from(2);
    }
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // Help and version go to stdout like any output (a closed pipe or a full device is
        // no panic); usage errors are clap's own, exit status 2.
        Err(e) if !e.use_stderr() => {
            return match output::print(&e.render().to_string()) {
                Ok(()) => ExitCode::SUCCESS,
                Err(Failure(msg)) => {
                    output::eprintln(&format!("raytree: {msg}"));
                    ExitCode::from(2)
                }
            };
        }
        Err(e) => e.exit(),
    };
    if let Some(dir) = cli.lessons {
        crate::lessons::use_lessons_root(dir);
    }
    // Renders that run on rayon's global pool (previews, the explorer's, lesson checks, bench
    // sweeps) need the render workers' stack as much as `render`'s own pool does: unoptimised,
    // the fast wing's frames overflow a default thread stack within a few levels.
    let _ = rayon::ThreadPoolBuilder::new()
        .stack_size(args::RENDER_STACK)
        .build_global();
    let result = match cli.command {
        Command::Render(a) => render::run(a),
        Command::Inspect(a) => inspect::run(a),
        Command::Csg(a) => csg::run(a),
        Command::Diagram(a) => diagram::run(a),
        Command::Preview(a) => preview::run(a),
        Command::Explore(a) => explore::run(a),
        Command::Bench(a) => bench::run(a),
        Command::Lessons(a) => lessons::run(a),
        Command::Check(a) => check::run(a),
        Command::Grade(a) => grade::run(a),
        Command::Homework(a) => homework::run(a),
        Command::Completions(a) => completions::run(a),
        Command::Man(a) => man::run(a),
    };
    match result {
        Ok(code) => code,
        Err(Failure(msg)) => {
            let (line, snippet) = match msg.split_once(SNIPPET) {
                Some((line, snippet)) => (line, Some(snippet)),
                None => (msg.as_str(), None),
            };
            output::eprintln(&format!("raytree: {line}"));
            if let Some(snippet) = snippet.filter(|_| output::stderr_is_terminal()) {
                output::eprint_block(snippet);
            }
            ExitCode::from(2)
        }
    }
}
