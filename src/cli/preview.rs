//! `raytree preview`: the scene as half-block characters (or ASCII) on stdout.

use std::io::IsTerminal;
use std::process::ExitCode;

use super::args::{depth, SceneArgs};
use super::Failure;
use crate::render::preview::{to_text, ColorMode};
use crate::render::{render_simple, RenderOptions};

#[derive(clap::Args, Debug)]
#[command(after_help = "Examples:
  raytree preview lessons/05-reflection/scene.yaml
  raytree preview lessons/06-refraction/scene.yaml --columns 60 --ascii
  raytree preview lessons/05-reflection/scene.yaml --color always | less -R")]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    /// Width in characters, 4 to 1000 (default: the terminal's, or 80).
    #[arg(long, value_parser = clap::value_parser!(u32).range(4..=1000))]
    columns: Option<u32>,
    /// Plain ASCII intensity ramp instead of colour.
    #[arg(long)]
    ascii: bool,
    /// Colour escapes: auto writes them only to a terminal (not with NO_COLOR or TERM=dumb;
    /// CLICOLOR_FORCE writes them to a pipe too); without colour the preview is ASCII.
    #[arg(long, value_enum, default_value_t = ColorChoice::Auto, value_name = "WHEN")]
    color: ColorChoice,
    /// Rays per path, primary included (overrides the scene's max_depth).
    #[arg(long)]
    depth: Option<u32>,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum ColorChoice {
    /// Colour on a terminal, as the environment allows.
    Auto,
    /// Colour wherever the output goes.
    Always,
    /// No colour: the ASCII ramp.
    Never,
}

/// Whether the preview is in colour, and which: `--color`, then (for auto) NO_COLOR (set and
/// not empty: no colour), CLICOLOR_FORCE (set and not 0: colour even into a pipe), TERM=dumb,
/// and whether stdout is a terminal; COLORTERM=truecolor|24bit chooses 24-bit colour over the
/// 256 colours.
fn color_mode(
    choice: ColorChoice,
    terminal: bool,
    var: impl Fn(&str) -> Option<String>,
) -> ColorMode {
    let set = |k: &str| var(k).is_some_and(|v| !v.is_empty());
    let colour = match choice {
        ColorChoice::Always => true,
        ColorChoice::Never => false,
        ColorChoice::Auto => {
            if set("NO_COLOR") {
                false
            } else if set("CLICOLOR_FORCE") && var("CLICOLOR_FORCE").as_deref() != Some("0") {
                true
            } else {
                terminal && var("TERM").as_deref() != Some("dumb")
            }
        }
    };
    if !colour {
        ColorMode::Ascii
    } else if matches!(var("COLORTERM").as_deref(), Some("truecolor" | "24bit")) {
        ColorMode::TrueColor
    } else {
        ColorMode::Ansi256
    }
}

/// The most pixel rows a preview has: 1000 lines of half blocks.
const MAX_ROWS: u32 = 2000;

/// The terminal's width as it reports it, else `COLUMNS`, else 80. A terminal that reports 0
/// columns (as the terminals of some containers and CI runners do) has not said.
fn terminal_columns() -> u32 {
    let reported = crossterm::terminal::size().ok().map(|(c, _)| c as u32);
    let from_env = || std::env::var("COLUMNS").ok()?.trim().parse::<u32>().ok();
    let said = |c: &u32| *c > 0;
    reported
        .filter(said)
        .or_else(|| from_env().filter(said))
        .unwrap_or(80)
}

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    let scene = a.scene.load()?;
    let columns = a
        .columns
        .unwrap_or_else(terminal_columns)
        // A terminal's own width, which no flag checked.
        .clamp(4, 1000);
    let (w, h) = (scene.camera.width as f64, scene.camera.height as f64);
    // Two pixels per character cell vertically; cells are about twice as tall as wide. A tall
    // image is previewed at most 1000 lines (2000 pixels) high, its columns fewer to keep its
    // shape. The rows are even: each line shows two, and an odd last one would draw a picture
    // symmetric top to bottom lopsided.
    let rows = (((columns as f64 * h / w / 2.0).round() as u32) * 2).max(2);
    let (columns, rows) = if rows > MAX_ROWS {
        let narrower = (columns as f64 * MAX_ROWS as f64 / rows as f64).round();
        (narrower.max(1.0) as u32, MAX_ROWS)
    } else {
        (columns, rows)
    };
    let mut small = scene.clone();
    small.camera = scene.camera.resized(columns, rows);
    let options = RenderOptions {
        max_depth: depth(&scene, a.depth)?,
        spp: scene.spp.min(4),
        ..RenderOptions::of(&scene)
    };
    let (image, _) = render_simple(&small, options);
    let mode = if a.ascii {
        ColorMode::Ascii
    } else {
        color_mode(a.color, std::io::stdout().is_terminal(), |k| {
            std::env::var(k).ok()
        })
    };
    super::output::print_raw(to_text(&image, mode).as_bytes())?;
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use super::{color_mode, ColorChoice};
    use crate::render::preview::ColorMode;

    fn mode(choice: ColorChoice, terminal: bool, env: &[(&str, &str)]) -> ColorMode {
        color_mode(choice, terminal, |k| {
            env.iter()
                .find(|(n, _)| *n == k)
                .map(|(_, v)| v.to_string())
        })
    }

    #[test]
    fn colour_only_on_a_terminal_unless_asked() {
        use ColorChoice::*;
        assert_eq!(mode(Auto, true, &[]), ColorMode::Ansi256);
        assert_eq!(mode(Auto, false, &[]), ColorMode::Ascii);
        assert_eq!(mode(Always, false, &[]), ColorMode::Ansi256);
        assert_eq!(mode(Never, true, &[]), ColorMode::Ascii);
        assert_eq!(
            mode(Auto, true, &[("COLORTERM", "truecolor")]),
            ColorMode::TrueColor
        );
    }

    #[test]
    fn no_color_clicolor_force_and_dumb_terminals() {
        use ColorChoice::*;
        assert_eq!(mode(Auto, true, &[("NO_COLOR", "1")]), ColorMode::Ascii);
        // An empty NO_COLOR does not count.
        assert_eq!(mode(Auto, true, &[("NO_COLOR", "")]), ColorMode::Ansi256);
        assert_eq!(
            mode(Auto, false, &[("CLICOLOR_FORCE", "1")]),
            ColorMode::Ansi256
        );
        assert_eq!(
            mode(Auto, false, &[("CLICOLOR_FORCE", "0")]),
            ColorMode::Ascii
        );
        assert_eq!(
            mode(Auto, false, &[("CLICOLOR_FORCE", "1"), ("NO_COLOR", "1")]),
            ColorMode::Ascii
        );
        assert_eq!(mode(Auto, true, &[("TERM", "dumb")]), ColorMode::Ascii);
        // --color always is the user's word: it wins over the environment.
        assert_eq!(
            mode(Always, false, &[("NO_COLOR", "1")]),
            ColorMode::Ansi256
        );
    }
}
