//! Terminal previews: half-block cells (two pixels per character: ▀ with the upper pixel as
//! foreground and the lower as background), in true colour, 256 colours, or an ASCII ramp.

use super::image::{encode, Encoding};
use super::Image;
use glam::DVec3;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColorMode {
    TrueColor,
    Ansi256,
    /// No colour at all (NO_COLOR or a dumb terminal): an intensity ramp.
    Ascii,
}

impl ColorMode {
    /// What the environment supports: NO_COLOR and TERM=dumb mean ASCII; COLORTERM announces
    /// true colour.
    pub fn detect() -> ColorMode {
        let var = |k| std::env::var(k).unwrap_or_default();
        if std::env::var_os("NO_COLOR").is_some_and(|v| !v.is_empty()) || var("TERM") == "dumb" {
            ColorMode::Ascii
        } else if matches!(var("COLORTERM").as_str(), "truecolor" | "24bit") {
            ColorMode::TrueColor
        } else {
            ColorMode::Ansi256
        }
    }
}

/// The ramp from dark to bright.
pub const RAMP: &[u8] = b" .:-=+*#%@";

pub fn luminance(c: DVec3) -> f64 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

pub fn ramp_char(c: DVec3) -> char {
    let l = encode(luminance(c), Encoding::Srgb) as usize;
    RAMP[(l * RAMP.len() / 256).min(RAMP.len() - 1)] as char
}

pub fn rgb8(c: DVec3) -> [u8; 3] {
    c.to_array().map(|v| encode(v, Encoding::Srgb))
}

/// The xterm 256-colour cube index nearest to an sRGB colour.
pub fn ansi256(rgb: [u8; 3]) -> u8 {
    let level = |v: u8| {
        if v < 48 {
            0
        } else if v < 115 {
            1
        } else {
            ((v as u16 - 35) / 40) as u8
        }
    };
    16 + 36 * level(rgb[0]) + 6 * level(rgb[1]) + level(rgb[2])
}

/// The image as lines of text. Half-block modes use two image rows per line.
pub fn to_text(image: &Image, mode: ColorMode) -> String {
    let mut out = String::new();
    if mode == ColorMode::Ascii {
        for y in (0..image.height).step_by(2) {
            for x in 0..image.width {
                let lower = if y + 1 < image.height {
                    image.get(x, y + 1)
                } else {
                    image.get(x, y)
                };
                out.push(ramp_char(0.5 * (image.get(x, y) + lower)));
            }
            out.push('\n');
        }
        return out;
    }
    for y in (0..image.height).step_by(2) {
        for x in 0..image.width {
            let top = rgb8(image.get(x, y));
            let bottom = if y + 1 < image.height {
                rgb8(image.get(x, y + 1))
            } else {
                top
            };
            match mode {
                ColorMode::TrueColor => out.push_str(&format!(
                    "\x1b[38;2;{};{};{}m\x1b[48;2;{};{};{}m▀",
                    top[0], top[1], top[2], bottom[0], bottom[1], bottom[2]
                )),
                _ => out.push_str(&format!(
                    "\x1b[38;5;{}m\x1b[48;5;{}m▀",
                    ansi256(top),
                    ansi256(bottom)
                )),
            }
        }
        out.push_str("\x1b[0m\n");
    }
    out
}
