//! The rendered image: linear intensities, and writing it out (whole or not at all).

use std::io::Write;
use std::path::Path;

use glam::DVec3;

#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    /// Linear intensities, row by row from the top.
    pub pixels: Vec<DVec3>,
}

/// How linear intensities become 8-bit values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Encoding {
    /// The sRGB transfer curve (what displays expect).
    #[default]
    Srgb,
    /// Clamp and scale: the lecture's raw values.
    Linear,
}

impl Image {
    pub fn new(width: u32, height: u32) -> Image {
        Image {
            width,
            height,
            pixels: vec![DVec3::ZERO; (width as usize) * (height as usize)],
        }
    }

    pub fn get(&self, x: u32, y: u32) -> DVec3 {
        self.pixels[(y * self.width + x) as usize]
    }

    /// The first pixel that is NaN or infinite, if any.
    pub fn first_non_finite(&self) -> Option<(u32, u32)> {
        let i = self.pixels.iter().position(|p| !p.is_finite())?;
        Some((i as u32 % self.width, i as u32 / self.width))
    }

    pub fn to_rgb8(&self, encoding: Encoding) -> Vec<u8> {
        self.pixels
            .iter()
            .flat_map(|p| p.to_array().map(|c| encode(c, encoding)))
            .collect()
    }

    /// Writes PNG, PPM or EXR (by extension) to a temporary file beside `path` and renames it into
    /// place, so a failed or interrupted write never leaves a truncated image.
    pub fn save(&self, path: &Path, encoding: Encoding) -> Result<(), String> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let bytes = match ext.as_deref() {
            Some("png") => {
                let mut out = Vec::new();
                let encoder = image::codecs::png::PngEncoder::new(&mut out);
                image::ImageEncoder::write_image(
                    encoder,
                    &self.to_rgb8(encoding),
                    self.width,
                    self.height,
                    image::ExtendedColorType::Rgb8,
                )
                .map_err(|e| format!("{}: {e}", path.display()))?;
                out
            }
            Some("ppm") => {
                let mut out = format!("P6\n{} {}\n255\n", self.width, self.height).into_bytes();
                out.extend(self.to_rgb8(encoding));
                out
            }
            Some("exr") => {
                // Linear radiance as computed, unclamped (for comparisons with references).
                let mut out = std::io::Cursor::new(Vec::new());
                // The encoder takes f32 samples as bytes in native order.
                let data: Vec<u8> = self
                    .pixels
                    .iter()
                    .flat_map(|p| [p.x as f32, p.y as f32, p.z as f32])
                    .flat_map(f32::to_ne_bytes)
                    .collect();
                image::ImageEncoder::write_image(
                    image::codecs::openexr::OpenExrEncoder::new(&mut out),
                    &data,
                    self.width,
                    self.height,
                    image::ExtendedColorType::Rgb32F,
                )
                .map_err(|e| format!("{}: {e}", path.display()))?;
                out.into_inner()
            }
            _ => {
                return Err(format!(
                    "{}: output must end in .png, .ppm or .exr",
                    path.display()
                ))
            }
        };
        write_atomically(path, &bytes)
    }
}

/// One channel to 8 bits; NaN becomes 0. The sRGB curve is read from a table that gives
/// exactly `encode_formula`'s answer without calling `powf` per channel.
pub fn encode(c: f64, encoding: Encoding) -> u8 {
    match encoding {
        Encoding::Srgb => srgb_table().encode(c),
        Encoding::Linear => encode_formula(c, encoding),
    }
}

/// The transfer formulas themselves: what `encode` answers, and what its table is built from.
pub fn encode_formula(c: f64, encoding: Encoding) -> u8 {
    let c = if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) };
    let v = match encoding {
        Encoding::Linear => c,
        Encoding::Srgb if c <= 0.0031308 => 12.92 * c,
        Encoding::Srgb => 1.055 * c.powf(1.0 / 2.4) - 0.055,
    };
    (v * 255.0 + 0.5) as u8
}

/// Buckets of the table's first guess: the curve is steepest near 0, where it still rises less
/// than one 8-bit step per bucket, so one comparison usually settles the value.
const SRGB_BUCKETS: usize = 4096;

/// sRGB encoding as thresholds. The formula is monotone, so its value at c is the number of
/// thresholds (the least c giving each value 1..=255) at or below c; the bucket of c gives the
/// value at the bucket's low end, and stepping past the thresholds up to c gives the rest.
struct SrgbTable {
    /// thresholds[k]: the least c encoded as k or more (k = 1..=255); thresholds[256] = ∞.
    thresholds: [f64; 257],
    /// start[i]: the encoding of i / SRGB_BUCKETS, the lowest in bucket i.
    start: [u8; SRGB_BUCKETS],
}

fn srgb_table() -> &'static SrgbTable {
    static TABLE: std::sync::OnceLock<SrgbTable> = std::sync::OnceLock::new();
    TABLE.get_or_init(SrgbTable::build)
}

impl SrgbTable {
    fn build() -> SrgbTable {
        let formula = |c: f64| encode_formula(c, Encoding::Srgb);
        let mut thresholds = [f64::INFINITY; 257];
        for (k, t) in thresholds.iter_mut().enumerate().take(256).skip(1) {
            *t = least_reaching(formula, k as u8);
        }
        let mut start = [0u8; SRGB_BUCKETS];
        for (i, s) in start.iter_mut().enumerate() {
            *s = formula(i as f64 / SRGB_BUCKETS as f64);
        }
        SrgbTable { thresholds, start }
    }

    #[inline]
    fn encode(&self, c: f64) -> u8 {
        // NaN, negatives and 0 encode as 0; 1 and above as 255 (the formula clamps).
        if c.is_nan() || c <= 0.0 {
            return 0;
        }
        if c >= 1.0 {
            return 255;
        }
        // c · 2¹² is exact, so the bucket's bounds are exactly i/4096 ≤ c < (i+1)/4096.
        let mut v = self.start[(c * SRGB_BUCKETS as f64) as usize];
        while c >= self.thresholds[v as usize + 1] {
            v += 1;
        }
        v
    }
}

/// The least c in [0, 1] with f(c) ≥ k, for a monotone f with f(0) < k ≤ f(1): bisection on
/// the bit patterns of non-negative doubles, which are ordered like their values.
fn least_reaching(f: impl Fn(f64) -> u8, k: u8) -> f64 {
    let (mut below, mut reaching) = (0f64.to_bits(), 1f64.to_bits());
    while reaching - below > 1 {
        let mid = below + (reaching - below) / 2;
        if f(f64::from_bits(mid)) >= k {
            reaching = mid;
        } else {
            below = mid;
        }
    }
    f64::from_bits(reaching)
}

pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .ok_or_else(|| format!("{}: not a file name", path.display()))?;
    let tmp = dir.join(format!(
        ".{}.{}.tmp",
        name.to_string_lossy(),
        std::process::id()
    ));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    result.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        format!("{}: cannot write: {e}", path.display())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn agrees(c: f64) {
        assert_eq!(
            encode(c, Encoding::Srgb),
            encode_formula(c, Encoding::Srgb),
            "c = {c:e} ({:#x})",
            c.to_bits()
        );
    }

    #[test]
    fn srgb_table_is_the_formula_at_every_step_and_bucket_edge() {
        let table = srgb_table();
        for &t in &table.thresholds[1..256] {
            for bits in t.to_bits() - 2..=t.to_bits() + 2 {
                agrees(f64::from_bits(bits));
            }
        }
        for i in 0..=SRGB_BUCKETS {
            let c = i as f64 / SRGB_BUCKETS as f64;
            for bits in c.to_bits().saturating_sub(2)..=c.to_bits() + 2 {
                agrees(f64::from_bits(bits));
            }
        }
    }

    #[test]
    fn srgb_table_is_the_formula_everywhere_sampled() {
        for c in [
            f64::NAN,
            -f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            -1.0,
            -0.0,
            0.0,
            f64::MIN_POSITIVE,
            5e-324,
            0.0031308,
            0.5,
            1.0,
            1.0 + f64::EPSILON,
            2.0,
        ] {
            agrees(c);
        }
        // Uniform in [0, 1.1) and log-uniform down to 1e−12 (xorshift: no dependencies).
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..1_000_000 {
            agrees(1.1 * next());
            agrees(10f64.powf(-12.0 * next()));
        }
    }
}
