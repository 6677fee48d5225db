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

/// One channel to 8 bits; NaN becomes 0.
pub fn encode(c: f64, encoding: Encoding) -> u8 {
    let c = if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) };
    let v = match encoding {
        Encoding::Linear => c,
        Encoding::Srgb if c <= 0.0031308 => 12.92 * c,
        Encoding::Srgb => 1.055 * c.powf(1.0 / 2.4) - 0.055,
    };
    (v * 255.0 + 0.5) as u8
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
