//! Terminal previews: half-block cells (two pixels per character: ▀ with the upper pixel as
//! foreground and the lower as background), in true colour, 256 colours, or an ASCII ramp.

use super::image::{encode, Encoding};
use super::Image;
use glam::DVec3;

/// How a terminal preview shows colours.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColorMode {
    /// 24-bit colour escapes.
    TrueColor,
    /// The xterm 256-colour palette.
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

/// Relative luminance of a linear RGB colour (Rec. 709 weights).
fn luminance(c: DVec3) -> f64 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// The ramp character for a colour's brightness (sRGB-encoded luminance).
pub(crate) fn ramp_char(c: DVec3) -> char {
    let l = encode(luminance(c), Encoding::Srgb) as usize;
    RAMP[(l * RAMP.len() / 256).min(RAMP.len() - 1)] as char
}

/// A linear colour as 8-bit sRGB.
pub(crate) fn rgb8(c: DVec3) -> [u8; 3] {
    c.to_array().map(|v| encode(v, Encoding::Srgb))
}

/// The xterm 256-colour index nearest to an sRGB colour: the nearest of the 6×6×6 cube
/// (levels 0, 95, 135, 175, 215, 255), or of the 24-step grey ramp (232 … 255: 8, 18, …, 238)
/// when that is nearer, as greys mostly are: the cube has only six greys, the ramp 24.
pub fn ansi256(rgb: [u8; 3]) -> u8 {
    const CUBE: [i32; 6] = [0, 95, 135, 175, 215, 255];
    let level = |v: u8| -> usize {
        if v < 48 {
            0
        } else if v < 115 {
            1
        } else {
            (v as usize - 35) / 40
        }
    };
    let [r, g, b] = rgb.map(i32::from);
    let q = rgb.map(level);
    let cube = 16 + 36 * q[0] + 6 * q[1] + q[2];
    let dist = |x: i32, y: i32, z: i32| (x - r).pow(2) + (y - g).pow(2) + (z - b).pow(2);
    let cube_dist = dist(CUBE[q[0]], CUBE[q[1]], CUBE[q[2]]);
    // The ramp step nearest the colour's mean: step k is 8 + 10·k.
    let mean = (r + g + b) / 3;
    let step = ((mean - 3) / 10).clamp(0, 23);
    let grey = 8 + 10 * step;
    if dist(grey, grey, grey) < cube_dist {
        (232 + step) as u8
    } else {
        cube as u8
    }
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

#[cfg(test)]
mod tests {
    use super::ansi256;

    #[test]
    fn greys_take_the_grey_ramp() {
        // xterm 244 is #808080 exactly; the cube's nearest grey (102, #878787) is 7 away.
        assert_eq!(ansi256([128, 128, 128]), 244);
        // #1c1c1c is ramp step 2 (8 + 20 = 28): 234.
        assert_eq!(ansi256([30, 30, 30]), 234);
        assert_eq!(ansi256([8, 8, 8]), 232);
        assert_eq!(ansi256([238, 238, 238]), 255);
        // Black, white and the cube's own greys are the cube's.
        assert_eq!(ansi256([0, 0, 0]), 16);
        assert_eq!(ansi256([255, 255, 255]), 231);
        assert_eq!(ansi256([135, 135, 135]), 102);
    }

    #[test]
    fn colours_take_the_cube() {
        assert_eq!(ansi256([255, 0, 0]), 196);
        // 200 → 215 (level 4), 100 → 95 (1), 50 → 95 (1): 16 + 144 + 6 + 1.
        assert_eq!(ansi256([200, 100, 50]), 167);
    }
}
