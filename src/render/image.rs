//! The rendered image: linear intensities, and writing it out (whole or not at all).

use std::fs::File;
use std::io::{self, BufWriter, Seek, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

use glam::DVec3;
use rayon::prelude::*;

use super::error::{ImageError, WriteError};

/// A rendered image: one linear intensity (r, g, b) per pixel, before any encoding.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
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
    /// A black image (every intensity 0) of that size. Its memory comes zeroed from the
    /// system, untouched: the kernel clears each page when the render first writes to it, on
    /// whichever thread that is, rather than all of them here, on one thread, before the
    /// render starts.
    pub fn new(width: u32, height: u32) -> Image {
        Image {
            width,
            height,
            pixels: bytemuck::zeroed_vec((width as usize) * (height as usize)),
        }
    }

    /// The intensity of pixel (x, y), (0, 0) at the top left; x < width and y < height.
    pub fn get(&self, x: u32, y: u32) -> DVec3 {
        self.pixels[(y * self.width + x) as usize]
    }

    /// The first pixel that is NaN or infinite, if any.
    pub fn first_non_finite(&self) -> Option<(u32, u32)> {
        let i = self.pixels.iter().position(|p| !p.is_finite())?;
        Some((i as u32 % self.width, i as u32 / self.width))
    }

    /// The pixels as 8-bit r, g, b bytes, row by row from the top, in `encoding`.
    pub fn to_rgb8(&self, encoding: Encoding) -> Vec<u8> {
        let mut bytes = vec![0; 3 * self.pixels.len()];
        // On every thread: the render's threads are idle while the image is written.
        bytes
            .par_chunks_mut(3 * 4096)
            .zip(self.pixels.par_chunks(4096))
            .for_each(|(bytes, pixels)| {
                for (rgb, p) in bytes.chunks_exact_mut(3).zip(pixels) {
                    for (b, c) in rgb.iter_mut().zip(p.to_array()) {
                        *b = encode(c, encoding);
                    }
                }
            });
        bytes
    }

    /// Writes PNG, PPM or EXR (by extension), whole or not at all (see `write_atomically`).
    pub fn save(&self, path: &Path, encoding: Encoding) -> Result<(), ImageError> {
        self.save_unless(path, encoding, &AtomicBool::new(false))
    }

    /// `save`, given up (and nothing left behind) as soon as `cancel` is set: a signal arriving
    /// while a large image is written.
    pub fn save_unless(
        &self,
        path: &Path,
        encoding: Encoding,
        cancel: &AtomicBool,
    ) -> Result<(), ImageError> {
        let format = Format::of(path)?;
        Ok(write_atomically_with(path, cancel, |out| {
            self.encode_to(format, encoding, out)
        })?)
    }

    /// The whole file in memory: for a stream that cannot seek, as standard output.
    pub fn encoded(&self, format: Format, encoding: Encoding) -> Result<Vec<u8>, ImageError> {
        let mut out = io::Cursor::new(Vec::new());
        self.encode_to(format, encoding, &mut out)
            .map_err(ImageError::Encode)?;
        Ok(out.into_inner())
    }

    /// The image encoded into `out`, streamed (no second copy of a large image in memory).
    fn encode_to(
        &self,
        format: Format,
        encoding: Encoding,
        out: &mut (impl Write + Seek),
    ) -> io::Result<()> {
        let encoder_error = |e: image::ImageError| match e {
            image::ImageError::IoError(e) => e,
            e => io::Error::other(e.to_string()),
        };
        match format {
            Format::Png => image::ImageEncoder::write_image(
                image::codecs::png::PngEncoder::new(out),
                &self.to_rgb8(encoding),
                self.width,
                self.height,
                image::ExtendedColorType::Rgb8,
            )
            .map_err(encoder_error),
            Format::Ppm => {
                write!(out, "P6\n{} {}\n255\n", self.width, self.height)?;
                for row in self.pixels.chunks(self.width.max(1) as usize) {
                    let bytes: Vec<u8> = row
                        .iter()
                        .flat_map(|p| p.to_array().map(|c| encode(c, encoding)))
                        .collect();
                    out.write_all(&bytes)?;
                }
                Ok(())
            }
            Format::Exr => {
                // Linear radiance as computed, unclamped (for comparisons with references).
                // The encoder takes f32 samples as bytes in native order.
                let data: Vec<u8> = self
                    .pixels
                    .iter()
                    .flat_map(|p| [p.x as f32, p.y as f32, p.z as f32])
                    .flat_map(f32::to_ne_bytes)
                    .collect();
                image::ImageEncoder::write_image(
                    image::codecs::openexr::OpenExrEncoder::new(out),
                    &data,
                    self.width,
                    self.height,
                    image::ExtendedColorType::Rgb32F,
                )
                .map_err(encoder_error)
            }
        }
    }
}

/// An image file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// PNG, 8 bits per channel, encoded.
    Png,
    /// Binary PPM (P6), 8 bits per channel, encoded.
    Ppm,
    /// OpenEXR, 32-bit float linear intensities, not encoded.
    Exr,
}

impl Format {
    /// The format an output's extension names.
    pub fn of(path: &Path) -> Result<Format, ImageError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("png") => Ok(Format::Png),
            Some("ppm") => Ok(Format::Ppm),
            Some("exr") => Ok(Format::Exr),
            _ => Err(ImageError::UnknownFormat {
                path: path.to_path_buf(),
            }),
        }
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
/// than one 8-bit step per bucket, so one comparison settles the value.
const SRGB_BUCKETS: usize = 4096;

/// sRGB encoding as thresholds. The formula is monotone, so its value at c is the number of
/// thresholds (the least c giving each value 1..=255) at or below c; the bucket of c gives the
/// value at the bucket's low end, and the one threshold a bucket can hold above it the rest.
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
        let mut thresholds = [f64::INFINITY; 257];
        for (k, t) in thresholds.iter_mut().enumerate().take(256).skip(1) {
            *t = least_encoded_as(k as u8);
        }
        // The value at c is the number of thresholds at or below c.
        let mut start = [0u8; SRGB_BUCKETS];
        let mut value = 0;
        for (i, s) in start.iter_mut().enumerate() {
            let c = i as f64 / SRGB_BUCKETS as f64;
            while thresholds[value + 1] <= c {
                value += 1;
            }
            *s = value as u8;
            // `encode` steps past one threshold at most: the next lies beyond the bucket.
            let next = thresholds[(*s as usize + 2).min(256)];
            assert!(next >= (i + 1) as f64 / SRGB_BUCKETS as f64);
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
        // c · 2¹² is exact, so the bucket's bounds are exactly i/4096 ≤ c < (i+1)/4096. At most
        // one threshold lies in a bucket above its first value (`build` checks it): one
        // comparison, which the compiler makes without a branch to mispredict.
        let v = self.start[(c * SRGB_BUCKETS as f64) as usize];
        v + (c >= self.thresholds[v as usize + 1]) as u8
    }
}

/// The least c in [0, 1] the sRGB formula encodes as k or more: the inverse of the curve at
/// the value's lower rounding edge, (k − ½)/255, then stepped one double at a time to the exact
/// edge (the inverse's rounding leaves it a few doubles off; the formula is monotone).
fn least_encoded_as(k: u8) -> f64 {
    let f = |c: f64| encode_formula(c, Encoding::Srgb);
    let v = (k as f64 - 0.5) / 255.0;
    let guess = if v <= 12.92 * 0.0031308 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    };
    let mut c = guess.clamp(0.0, 1.0);
    while c < 1.0 && f(c) < k {
        c = c.next_up();
    }
    while c > 0.0 && f(c.next_down()) >= k {
        c = c.next_down();
    }
    c
}

/// Writes `bytes` to `path` whole or not at all (see `write_atomically_with`).
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    write_atomically_with(path, &AtomicBool::new(false), |out| out.write_all(bytes))
}

/// Writes a file whole or not at all: into a temporary file beside it (a short name of its
/// own, whatever the length of the output's), then renamed over it. A failed write, or one
/// given up because `cancel` was set, removes the temporary file and leaves the old output as
/// it was. An output that is a symbolic link is written through: the file it points to is
/// replaced and the link stays. A read-only output, or one that is not a regular file (a
/// device such as /dev/full), is refused rather than replaced.
pub fn write_atomically_with(
    path: &Path,
    cancel: &AtomicBool,
    write: impl FnOnce(&mut Cancellable<BufWriter<File>>) -> io::Result<()>,
) -> Result<(), WriteError> {
    let path_buf = || path.to_path_buf();
    let Place {
        target,
        existing,
        dir,
    } = place(path)?;
    let failed = |source| WriteError::Io {
        path: path_buf(),
        source,
    };
    let tmp = temporary_file_in(&dir).map_err(failed)?;
    let result = (|| {
        if let Some(meta) = &existing {
            tmp.as_file().set_permissions(meta.permissions())?;
        }
        // 64 KiB: a larger buffer is more fresh pages to fault in, for no fewer writes that count.
        let mut out = Cancellable {
            inner: BufWriter::with_capacity(64 << 10, tmp.reopen()?),
            cancel,
        };
        write(&mut out)?;
        let file = out.inner.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        if cancel.load(Ordering::Relaxed) {
            return Err(given_up());
        }
        Ok(())
    })();
    // Dropping `tmp` on an error removes the temporary file. Once `cancel` is set, whatever
    // failed failed because of it.
    result.map_err(|e| {
        if cancel.load(Ordering::Relaxed) {
            WriteError::Cancelled { path: path_buf() }
        } else {
            failed(e)
        }
    })?;
    tmp.persist(&target)
        .map(|_| ())
        .map_err(|e| failed(e.error))
}

/// Where a write to `path` goes, checked as far as it can be before writing.
struct Place {
    /// The file written (through the output's symbolic links).
    target: PathBuf,
    /// What is there now.
    existing: Option<std::fs::Metadata>,
    /// The folder of the target, which holds the temporary file.
    dir: PathBuf,
}

/// The refusals of `write_atomically_with` found before anything is written: an output that
/// is a folder, a device or read-only, whose links cannot be followed, whose folder is not
/// there, or in a folder where no file can be made (a temporary file is made there and removed).
/// A command checks them before a long render, so as not to find out after it.
pub fn check_output(path: &Path) -> Result<(), WriteError> {
    let place = place(path)?;
    temporary_file_in(&place.dir)
        .map(drop)
        .map_err(|source| WriteError::Io {
            path: path.to_path_buf(),
            source,
        })
}

/// A new temporary file in `dir`, removed when dropped; its error is the system's reason alone
/// (tempfile adds the temporary file's name, which the user never asked for).
fn temporary_file_in(dir: &Path) -> io::Result<tempfile::NamedTempFile> {
    let mut builder = tempfile::Builder::new();
    builder.prefix(".raytree-").suffix(".tmp");
    // A new file gets the permissions any new file would (0666 less the umask), not the
    // temporary file's private 0600.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    builder.tempfile_in(dir).map_err(|e| {
        let errno = e.raw_os_error().or_else(|| {
            let inner = std::error::Error::source(e.get_ref()?)?;
            inner.downcast_ref::<io::Error>()?.raw_os_error()
        });
        errno.map_or_else(|| io::Error::from(e.kind()), io::Error::from_raw_os_error)
    })
}

fn place(path: &Path) -> Result<Place, WriteError> {
    let path_buf = || path.to_path_buf();
    // "out.png/" names a folder, though none is there yet.
    if path.as_os_str().as_encoded_bytes().last() == Some(&b'/') {
        return Err(WriteError::FolderName { path: path_buf() });
    }
    let target = through_links(path).map_err(|source| WriteError::Links {
        path: path_buf(),
        source,
    })?;
    let existing = std::fs::metadata(&target).ok();
    if let Some(meta) = &existing {
        if meta.is_dir() {
            return Err(WriteError::Directory { path: path_buf() });
        }
        if !meta.is_file() {
            return Err(WriteError::NotRegular { path: path_buf() });
        }
        if meta.permissions().readonly() {
            return Err(WriteError::ReadOnly { path: path_buf() });
        }
    }
    let dir = target
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
        .to_path_buf();
    if !dir.is_dir() {
        return Err(if dir.exists() {
            WriteError::NotAFolder {
                path: path_buf(),
                folder: dir,
            }
        } else {
            WriteError::NoFolder {
                path: path_buf(),
                folder: dir,
            }
        });
    }
    Ok(Place {
        target,
        existing,
        dir,
    })
}

/// The file a path names, following symbolic links (also one that points to a file not yet
/// there), so that an output link is written through rather than replaced.
fn through_links(path: &Path) -> io::Result<std::path::PathBuf> {
    let mut at = path.to_path_buf();
    for _ in 0..40 {
        match std::fs::symlink_metadata(&at) {
            Ok(meta) if meta.file_type().is_symlink() => {
                let to = std::fs::read_link(&at)?;
                at = match at.parent() {
                    Some(parent) if to.is_relative() => parent.join(to),
                    _ => to,
                };
            }
            _ => return Ok(at),
        }
    }
    Err(io::Error::other("too many levels of symbolic links"))
}

/// The error of a write given up. Not `ErrorKind::Interrupted`, which `write_all` retries.
fn given_up() -> io::Error {
    io::Error::other("interrupted")
}

/// A writer that fails as soon as `cancel` is set, so that a long write stops at once.
pub struct Cancellable<'a, W> {
    inner: W,
    cancel: &'a AtomicBool,
}

impl<W: Write> Write for Cancellable<'_, W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        if self.cancel.load(Ordering::Relaxed) {
            return Err(given_up());
        }
        self.inner.write(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.inner.flush()
    }
}

impl<W: Seek> Seek for Cancellable<'_, W> {
    fn seek(&mut self, pos: io::SeekFrom) -> io::Result<u64> {
        self.inner.seek(pos)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A file in a folder of its own per test (tests run in parallel; each looks for
    /// temporary files left in its folder).
    fn scratch(test: &str, name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("raytree-image-{}-{test}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir.join(name)
    }

    fn leftovers(dir: &Path) -> Vec<String> {
        std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".tmp"))
            .collect()
    }

    #[test]
    fn names_up_to_the_filesystem_limit_are_written() {
        for len in [245, 251, 255] {
            let name = format!("{}.ppm", "n".repeat(len - 4));
            let path = scratch("names", &name);
            Image::new(2, 1).save(&path, Encoding::Srgb).unwrap();
            assert_eq!(std::fs::read(&path).unwrap().len(), 11 + 6, "{len} bytes");
        }
        assert!(leftovers(scratch("names", "").as_path()).is_empty());
    }

    #[cfg(unix)]
    #[test]
    fn a_symlinked_output_is_written_through_and_a_read_only_one_is_kept() {
        use std::os::unix::fs::{symlink, FileTypeExt, PermissionsExt};
        let target = scratch("links", "target.ppm");
        let link = scratch("links", "link.ppm");
        std::fs::write(&target, b"old").unwrap();
        let _ = std::fs::remove_file(&link);
        symlink("target.ppm", &link).unwrap();
        Image::new(1, 1).save(&link, Encoding::Srgb).unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert!(std::fs::read(&target).unwrap().starts_with(b"P6"));

        let locked = scratch("links", "locked.ppm");
        let _ = std::fs::remove_file(&locked);
        std::fs::write(&locked, b"keep me").unwrap();
        std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o444)).unwrap();
        let e = Image::new(1, 1).save(&locked, Encoding::Srgb).unwrap_err();
        assert!(
            matches!(&e, ImageError::Write(WriteError::ReadOnly { path }) if *path == locked),
            "{e:?}"
        );
        assert!(e.to_string().contains("read-only"), "{e}");
        assert_eq!(std::fs::read(&locked).unwrap(), b"keep me");

        // Renaming over a device would replace the device node by a file.
        let device = scratch("links", "device.ppm");
        let _ = std::fs::remove_file(&device);
        symlink("/dev/null", &device).unwrap();
        let e = Image::new(1, 1).save(&device, Encoding::Srgb).unwrap_err();
        assert!(
            matches!(&e, ImageError::Write(WriteError::NotRegular { .. })),
            "{e:?}"
        );
        assert!(e.to_string().contains("not a regular file"), "{e}");
        assert!(std::fs::metadata("/dev/null")
            .unwrap()
            .file_type()
            .is_char_device());
    }

    /// A program using the library learns which output failed and why, not only a message;
    /// a person reads the folder that is missing, and nothing of the temporary file the write
    /// would have gone through (neither its name nor a file left behind).
    #[test]
    fn a_failed_save_names_the_output_and_its_cause() {
        let folder = scratch("missing", "").join("no-such-folder");
        let missing = folder.join("out.png");
        let e = Image::new(1, 1).save(&missing, Encoding::Srgb).unwrap_err();
        let ImageError::Write(WriteError::NoFolder { path, folder: f }) = &e else {
            panic!("{e:?}")
        };
        assert_eq!((path, f), (&missing, &folder));
        let message = format!(
            "{}: cannot write: there is no folder {}",
            missing.display(),
            folder.display()
        );
        assert_eq!(e.to_string(), message);
        assert!(!folder.exists());
        let odd = scratch("missing", "out.jpg");
        match Image::new(1, 1).save(&odd, Encoding::Srgb) {
            Err(e @ ImageError::UnknownFormat { .. }) => {
                assert_eq!(
                    e.to_string(),
                    format!("{}: output must end in .png, .ppm or .exr", odd.display())
                );
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn a_cancelled_write_leaves_the_old_file_and_no_temporary_one() {
        let path = scratch("cancel", "cancelled.ppm");
        std::fs::write(&path, b"previous").unwrap();
        let e = Image::new(64, 64)
            .save_unless(&path, Encoding::Srgb, &AtomicBool::new(true))
            .unwrap_err();
        assert!(
            matches!(&e, ImageError::Write(WriteError::Cancelled { path: p }) if *p == path),
            "{e:?}"
        );
        assert!(e.to_string().contains("interrupted"), "{e}");
        assert_eq!(std::fs::read(&path).unwrap(), b"previous");
        assert!(leftovers(path.parent().unwrap()).is_empty());
    }

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
