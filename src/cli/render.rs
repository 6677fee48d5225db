//! `raytree render`: a scene to an image file.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use super::args::{depth, FilmArgs, Format, SceneArgs};
use super::output::eprintln;
use super::Failure;
use crate::render::{render, Encoding, Engine, ImageFormat, RenderOptions};
use crate::sampling::Rng;
use crate::scene::Antialias;
use crate::signals::Signals;
use crate::trace::budget::{affordable_depth, FREE_DEPTH, TREE_BUDGET};

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum Gamma {
    /// The sRGB curve, as screens and image viewers expect.
    Srgb,
    /// The intensities as computed (the lecture's raw values), clamped to [0, 1].
    Linear,
}

#[derive(clap::Args, Debug)]
#[command(after_help = "Examples:
  raytree render lessons/06-refraction/scene.yaml -o refraction.png --stats
  raytree render lessons/07-recursion-depth/scene.yaml --depth-strip 4 -o strip.png
  raytree render lessons/examples/cornell.yaml --spp 64 --width 200 --height 200 -o cornell.exr
  raytree render lessons/05-reflection/scene.yaml -o - | display   (PPM on stdout)")]
pub struct Args {
    #[command(flatten)]
    scene: SceneArgs,
    /// Output image: PNG, PPM or EXR (.png, .ppm, .exr; EXR keeps linear, unclamped values),
    /// written whole or not at all; `-` writes to standard output (see --image-format).
    #[arg(short, long)]
    output: PathBuf,
    /// The image format of `-o -` (standard output): PPM, PNG or EXR. A file's format is
    /// its extension's.
    #[arg(long, value_enum, value_name = "FORMAT")]
    image_format: Option<ImageFormatArg>,
    #[command(flatten)]
    film: FilmArgs,
    /// Rays per path, primary included (overrides the scene's max_depth).
    #[arg(long)]
    depth: Option<u32>,
    /// Worker threads (default: all cores). The image is identical for any count.
    #[arg(long)]
    threads: Option<usize>,
    /// Seed of the random numbers (jittered antialiasing, glossy and frosted rays, paths).
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Render depths 1, 2, …, N side by side into one strip image (the recursion lesson); the
    /// frames set their own depths, so --depth does not go with it.
    #[arg(long, value_name = "N")]
    depth_strip: Option<u32>,
    /// Turn off CSG bounding boxes and pruning (to measure what they save).
    #[arg(long)]
    no_csg_pruning: bool,
    /// Print ray counts and the work skipped (on stderr; with --format json, on stdout).
    #[arg(long)]
    stats: bool,
    /// The statistics of --stats: lines to read, or one JSON document for programs.
    #[arg(long, value_enum, default_value_t = Format::Text, requires = "stats")]
    format: Format,
    /// Encoding of an 8-bit output (PNG, PPM): sRGB, or the lecture's raw linear values
    /// (default: srgb). An EXR holds linear radiance and takes no --gamma.
    #[arg(long, value_enum)]
    gamma: Option<Gamma>,
    /// Which code renders: the fast wing, or the textbook core alone (`src/trace/whitted.rs`,
    /// one ray at a time). The image is the same bit for bit; the core is slower.
    #[arg(long, value_enum, default_value_t = EngineArg::Fast)]
    engine: EngineArg,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
enum ImageFormatArg {
    /// Binary PPM (P6): 8-bit RGB, the simplest to read.
    Ppm,
    /// 8-bit RGB PNG.
    Png,
    /// OpenEXR: linear, unclamped 32-bit floats.
    Exr,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug)]
enum EngineArg {
    /// Packets, SIMD lanes and fast paths (`src/fast/`).
    Fast,
    /// The scalar Whitted recursion of `src/trace/whitted.rs`, one ray at a time.
    Core,
}

/// White pixels between two frames of a strip.
const GAP: u32 = 4;

/// The font size of a strip's labels over frames `w` pixels wide.
fn label_font(w: u32) -> u32 {
    if w >= 60 {
        14
    } else {
        9
    }
}

/// The height of the band of labels above frames `w` pixels wide.
fn label_band(w: u32) -> u32 {
    label_font(w) + 8
}

/// The width and height of a strip of `n` frames of `w` × `h`: the frames, the gaps between
/// them and the band of labels above.
fn strip_size(n: u32, w: u32, h: u32) -> (u32, u32) {
    (n * w + (n - 1) * GAP, h + label_band(w))
}

/// The frames side by side, 4 white pixels apart, each under a label "depth k" (frame k is
/// depth k; just "k" where the frame is too narrow for the word).
fn strip(frames: &[crate::render::Image]) -> Result<crate::render::Image, Failure> {
    let (w, h) = (frames[0].width, frames[0].height);
    let n = frames.len() as u32;
    let font = label_font(w);
    let band = label_band(w);
    let (strip_w, strip_h) = strip_size(n, w, h);
    let mut out = crate::render::Image::new(strip_w, strip_h);
    out.pixels.iter_mut().for_each(|p| *p = glam::DVec3::ONE);
    for (k, f) in frames.iter().enumerate() {
        let left = k as u32 * (w + GAP);
        for y in 0..h {
            for x in 0..w {
                out.pixels[((y + band) * out.width + left + x) as usize] = f.get(x, y);
            }
        }
    }
    // The labels: an SVG of the band drawn by resvg, each label clipped to its own frame.
    let mut svg = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{band}"><rect width="100%" height="100%" fill="white"/>"#,
        out.width
    );
    for k in 0..n {
        let left = k * (w + GAP);
        let word = format!("depth {}", k + 1);
        // About 0.6 em per character in a sans-serif face.
        let label = if word.len() as f64 * 0.6 * font as f64 + 4.0 <= w as f64 {
            word
        } else {
            format!("{}", k + 1)
        };
        svg.push_str(&format!(
            r#"<clipPath id="f{k}"><rect x="{left}" y="0" width="{w}" height="{band}"/></clipPath><text clip-path="url(#f{k})" x="{}" y="{}" font-family="sans-serif" font-size="{font}" font-weight="bold" fill="black">{label}</text>"#,
            left + 2,
            font + 2
        ));
    }
    svg.push_str("</svg>");
    if !crate::diagram::raster::have_fonts() {
        eprintln("warning: no fonts found on this system: the strip has no labels");
    }
    let (bw, _, rgba) = crate::diagram::raster::rasterize(&svg)?;
    // The band's pixels are sRGB; the image holds linear intensities, encoded when saved.
    let linear = |c: u8| {
        let c = c as f64 / 255.0;
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    for (i, px) in rgba.chunks_exact(4).enumerate() {
        let (x, y) = (i as u32 % bw, i as u32 / bw);
        if x < out.width && y < band {
            out.pixels[(y * out.width + x) as usize] =
                glam::DVec3::new(linear(px[0]), linear(px[1]), linear(px[2]));
        }
    }
    Ok(out)
}

/// Checks that images of `pixels` pixels in all fit the budget and that memory for them can be
/// had (`bytes_per_pixel` of it at once): a clear error instead of an abort when it cannot.
/// `what` says what holds them, ending in its verb ("a 10 × 10 image holds").
fn budget_pixels(
    pixels: u64,
    what: &str,
    limits: &crate::scene::Limits,
    bytes_per_pixel: u64,
) -> Result<(), Failure> {
    if pixels > limits.max_pixels {
        return Err(Failure(format!(
            "{what} {pixels} pixels, over the budget of {} pixels ({})",
            limits.max_pixels,
            crate::scene::Limits::RAISE
        )));
    }
    let bytes = pixels.saturating_mul(bytes_per_pixel);
    let mut probe: Vec<u8> = Vec::new();
    usize::try_from(bytes)
        .ok()
        .and_then(|n| probe.try_reserve_exact(n).ok())
        .ok_or_else(|| {
            Failure(format!(
                "{what} {pixels} pixels, which need {} of memory, more than can be had",
                crate::files::bytes(bytes)
            ))
        })
}

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    // From here on an interrupted render winds down (and leaves no temporary file behind)
    // before the process ends as the signal asks.
    let signals = crate::signals::Signals::catch()?;
    let result = render_to_file(&a, &signals);
    signals.finish();
    result
}

/// A warning where some pixel's ray tree at `depth` is far beyond what a render can trace:
/// each level can double a tree, and a scene may ask for 64. A 5 × 5 grid of pixels is tried
/// as `inspect` shows a tree (`affordable_depth`); depths up to `FREE_DEPTH` are not.
fn tree_too_large(scene: &crate::scene::Scene, depth: u32, seed: u64) -> Option<String> {
    if depth <= FREE_DEPTH || scene.integrator != crate::scene::Integrator::Whitted {
        return None;
    }
    let (w, h) = (scene.camera.width, scene.camera.height);
    let mut grid =
        (0..5).flat_map(|j| (0..5).map(move |i| ((2 * i + 1) * w / 10, (2 * j + 1) * h / 10)));
    grid.find_map(|(x, y)| {
        let rng = Rng::for_pixel(seed, x, y);
        let ray = scene.camera.pixel_ray(x, y);
        let fits = affordable_depth(scene, &ray, depth, &|| rng.clone());
        (fits < depth).then(|| {
            format!(
                "warning: pixel {x},{y}'s ray tree holds over {TREE_BUDGET} rays deeper than {fits}: \
                 at depth {depth} this render may take very long (lower max_depth or --depth, \
                 or set adaptive_threshold)"
            )
        })
    })
}

/// What a render stopped by a signal reports.
fn interrupted() -> Failure {
    Failure("interrupted".into())
}

/// Writes the image to its destination (whole or not at all).
fn write_image(
    image: &crate::render::Image,
    output: &std::path::Path,
    destination: Destination,
    encoding: Encoding,
    stop: &AtomicBool,
) -> Result<(), Failure> {
    match destination {
        Destination::File => Ok(image.save_unless(output, encoding, stop)?),
        Destination::Stdout(format) => {
            let bytes = image.encoded(format, encoding)?;
            if stop.load(std::sync::atomic::Ordering::SeqCst) {
                return Err(interrupted());
            }
            super::output::print_raw(&bytes)
        }
    }
}

/// Where the image goes: a file (its format from its extension), or standard output.
#[derive(Clone, Copy)]
enum Destination {
    File,
    Stdout(ImageFormat),
}

/// `-o -` and `--image-format`, checked before anything is rendered.
fn destination(a: &Args) -> Result<Destination, Failure> {
    if a.output.as_os_str() != "-" {
        if a.image_format.is_some() {
            return Err(Failure(
                "--image-format is for -o - (standard output); a file's format is its extension's"
                    .into(),
            ));
        }
        // Before the render, not after it: a wrong name or a missing folder is found at once.
        ImageFormat::of(&a.output)?;
        crate::render::check_output(&a.output)?;
        return Ok(Destination::File);
    }
    if a.stats && a.format == Format::Json {
        return Err(Failure(
            "--stats --format json prints to standard output, which -o - takes for the image: write the image to a file".into(),
        ));
    }
    if std::io::stdout().is_terminal() {
        return Err(Failure(
            "-o - writes the image to standard output, which is a terminal: redirect it (> image.ppm) or pipe it".into(),
        ));
    }
    Ok(Destination::Stdout(match a.image_format {
        None | Some(ImageFormatArg::Ppm) => ImageFormat::Ppm,
        Some(ImageFormatArg::Png) => ImageFormat::Png,
        Some(ImageFormatArg::Exr) => ImageFormat::Exr,
    }))
}

fn render_to_file(a: &Args, signals: &Signals) -> Result<ExitCode, Failure> {
    let stop = signals.stop();
    let destination = destination(a)?;
    if a.depth_strip.is_some() && a.depth.is_some() {
        return Err(Failure(
            "--depth does not go with --depth-strip: the strip's frames are depths 1 to N, each its own".into(),
        ));
    }
    let format = match destination {
        Destination::File => ImageFormat::of(&a.output)?,
        Destination::Stdout(format) => format,
    };
    if a.gamma.is_some() && format == ImageFormat::Exr {
        return Err(Failure(
            "--gamma is for 8-bit images (PNG, PPM): an EXR holds linear radiance, unencoded"
                .into(),
        ));
    }
    let pool = super::args::thread_pool(a.threads)?;
    // Large scene files parse on the pool's threads too (and only on those).
    let mut scene = pool.install(|| a.scene.load())?;
    let same = |p: &std::path::Path| p.canonicalize().ok();
    if matches!(destination, Destination::File)
        && a.output.exists()
        && same(&a.output) == same(&a.scene.scene)
    {
        return Err(Failure(format!(
            "{}: refusing to write the image over the scene file itself",
            a.output.display()
        )));
    }
    scene.csg_pruning = !a.no_csg_pruning;
    let (w, h) = a.film.size(&scene)?;
    let limits = super::args::limits(a.scene.allow_huge);
    // The image (three f64 per pixel), the rows rendered before they are joined, and 8-bit
    // values for encoding; a strip keeps all its frames and the strip besides.
    const BYTES_PER_PIXEL: u64 = 2 * 24 + 3;
    let frames = match a.depth_strip {
        None => 1,
        Some(n) if (1..=64).contains(&n) => n as u64,
        Some(n) => {
            return Err(Failure(format!(
                "--depth-strip must be between 1 and 64, got {n}"
            )))
        }
    };
    let frame = w as u64 * h as u64;
    if frames == 1 {
        budget_pixels(
            frame,
            &format!("an image of {w} × {h} holds"),
            &limits,
            BYTES_PER_PIXEL,
        )?;
    } else {
        let (sw, sh) = strip_size(frames as u32, w, h);
        budget_pixels(
            frames * frame + sw as u64 * sh as u64,
            &format!("{frames} frames of {w} × {h} and their {sw} × {sh} strip hold"),
            &limits,
            BYTES_PER_PIXEL,
        )?;
    }
    a.film.apply(&mut scene, &limits)?;
    let spp = scene.spp;
    let options = RenderOptions {
        max_depth: depth(&scene, a.depth)?,
        seed: a.seed,
        engine: match a.engine {
            EngineArg::Fast => Engine::Fast,
            EngineArg::Core => Engine::Core,
        },
        ..RenderOptions::of(&scene)
    };
    let deepest = a
        .depth_strip
        .map_or(options.max_depth, |n| n.max(options.max_depth));
    if let Some(warning) = pool.install(|| tree_too_large(&scene, deepest, a.seed)) {
        eprintln(&warning);
    }
    let bar = std::io::stderr().is_terminal().then(|| {
        let bar = indicatif::ProgressBar::new(h as u64);
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "{spinner} rendering [{bar:40}] {pos}/{len} rows {elapsed}",
            )
            .expect("valid template")
            .progress_chars("=> "),
        );
        bar
    });
    let start = Instant::now();
    let on_row = |_| {
        if let Some(b) = &bar {
            b.inc(1)
        }
    };
    // Until the image is written nothing is left to undo: a render a signal cannot stop
    // between pixels (one pixel's tree may be astronomically large) is ended at once.
    let rendered = signals.impatient(|| match a.depth_strip {
        None => pool
            .install(|| render(&scene, options, &on_row, stop))
            .ok_or_else(interrupted),
        Some(n) => {
            let mut frames = Vec::new();
            let mut total = crate::stats::Stats::default();
            for depth in 1..=n {
                let o = RenderOptions {
                    max_depth: depth,
                    ..options
                };
                let (img, st) = pool
                    .install(|| render(&scene, o, &|_| {}, stop))
                    .ok_or_else(interrupted)?;
                total.add(&st);
                frames.push(img);
                if let Some(b) = &bar {
                    b.set_position(depth as u64 * h as u64 / n as u64);
                }
            }
            Ok((strip(&frames)?, total))
        }
    });
    let (image, stats) = rendered?;
    let elapsed = start.elapsed();
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    let encoding = if a.gamma == Some(Gamma::Linear) {
        Encoding::Linear
    } else {
        Encoding::Srgb
    };
    // The image is converted and encoded on the render's threads, which are idle by now (and
    // no second pool is started for it), while the other thread looks for pixels that are not
    // finite: the encoder's share of the work is on one thread.
    let (written, non_finite) = pool.install(|| {
        rayon::join(
            || write_image(&image, &a.output, destination, encoding, stop),
            || image.first_non_finite(),
        )
    });
    written?;
    if let Some((x, y)) = non_finite {
        eprintln(&format!(
            "warning: pixel {x},{y} is not finite (NaN or ∞); replay it with: {}",
            replay(a, [x, y])
        ));
    }
    if a.stats && a.format == Format::Json {
        let seconds = elapsed.as_secs_f64();
        super::output::print_json(serde_json::json!({
            "scene": a.scene.scene.display().to_string(),
            "width": w,
            "height": h,
            "spp": spp,
            "antialias": sampling_name(&scene, options.antialias),
            "max_depth": options.max_depth,
            "seconds": seconds,
            "rays": stats.rays(),
            "rays_per_second": stats.rays() as f64 / seconds.max(1e-9),
            "peak_memory_bytes": super::peak_memory::peak_resident_bytes(),
            "cpu_level": crate::render::instruction_level(),
            "stats": stats,
        }))?;
    } else if a.stats {
        eprintln(&format!(
            "{} × {} pixels, {} spp ({}), depth {}, {:.3} s",
            w,
            h,
            spp,
            sampling_name(&scene, options.antialias),
            options.max_depth,
            elapsed.as_secs_f64()
        ));
        let mut rows = vec![(
            "rays per second",
            format!(
                "{:.0}",
                stats.rays() as f64 / elapsed.as_secs_f64().max(1e-9)
            ),
        )];
        if let Some(peak) = super::peak_memory::peak_resident_bytes() {
            rows.push((
                "peak memory (the whole process)",
                format!("{:.1} MB", peak as f64 / 1e6),
            ));
        }
        rows.push((
            "instructions of the fast wing",
            crate::render::instruction_level().to_string(),
        ));
        rows.extend(stats.rows());
        for line in crate::stats::table(&rows).lines() {
            eprintln(line);
        }
    }
    // The process ends next, and the system takes its memory back in one step: freeing the
    // scene's objects one by one first costs more (1.5 ms for 10 000 spheres).
    std::mem::forget(scene);
    std::mem::forget(image);
    Ok(ExitCode::SUCCESS)
}

/// The name of the sampling a render of `scene` uses with `antialias`: the path tracer
/// places a pixel's samples as a Sobol net unless they are adaptive (`Film::antialias`).
fn sampling_name(scene: &crate::scene::Scene, antialias: Antialias) -> &'static str {
    match antialias {
        Antialias::Grid | Antialias::Jittered
            if scene.integrator == crate::scene::Integrator::Path =>
        {
            "sobol"
        }
        a => a.name(),
    }
}

/// The `raytree inspect` command that computes pixel `[x, y]` of this render: the same scene,
/// with the render's settings that change the pixel's value.
fn replay(a: &Args, [x, y]: [u32; 2]) -> String {
    let mut command = format!(
        "raytree inspect {} --pixel {x},{y}",
        a.scene.scene.display()
    );
    command += &a.film.flags();
    if let Some(d) = a.depth {
        command += &format!(" --depth {d}");
    }
    if a.seed != 0 {
        command += &format!(" --seed {}", a.seed);
    }
    command
}
