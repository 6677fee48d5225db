//! `raytree bench`: measured sweeps (run time against error; time per ray against scene size;
//! speed-up with threads against the machine's own).

use std::process::ExitCode;

use super::args::Format;
use super::output::{eprintln, print, print_json};
use super::Failure;
use crate::bench::{
    measure, mesh, spheres, table_header, table_row, thread_rounds, threads_table, Precision,
    Reference, Row,
};
use crate::diagram::raster;

#[derive(clap::Args, Debug)]
#[command(after_help = "Examples:
  raytree bench sweep lessons/examples/glossy.yaml --knob spp --values 1,4,16,64 --plot sweep.svg
  raytree bench scaling --max-spheres 10000 --max-subdivisions 6 --format json
  raytree bench threads benches/peers/whitted.yaml --runs 3
  raytree bench explorer 08-pixel-intensity 10-csg")]
pub struct Args {
    #[command(subcommand)]
    measure: Measure,
}

#[derive(clap::Subcommand, Debug)]
enum Measure {
    /// Run time against error: renders SCENE at each value of one knob, compares every image
    /// with a reference (an EXR/PNG file, or the scene at a much higher setting) and prints
    /// seconds, rays, RMSE, relative MSE, max error, PSNR and efficiency 1/(seconds·MSE).
    #[command(after_help = "Examples:
  raytree bench sweep lessons/examples/glossy.yaml --knob spp --values 1,4,16,64 --plot sweep.svg
  raytree bench sweep benches/peers/whitted.yaml --knob adaptive --values 0,0.001,0.01,0.1 --plot adaptive.png
  raytree bench sweep scene.yaml --knob depth --values 1,2,4,8 --reference truth.exr --csv depth.csv")]
    Sweep {
        /// The scene file (YAML), or a lesson's folder or name for its scene.yaml.
        #[arg(value_parser = super::args::scene_path)]
        scene: std::path::PathBuf,
        /// The setting turned from one render to the next. A knob that cannot change the
        /// scene's image is refused: depth and adaptive where nothing reflects or refracts
        /// (adaptive and glossy also under the path tracer), glossy without a glossy or
        /// frosted material.
        #[arg(long, value_enum)]
        knob: crate::bench::Knob,
        /// Comma-separated values, e.g. 1,4,16,64.
        #[arg(long, value_delimiter = ',', required = true)]
        values: Vec<f64>,
        /// Reference image: a linear EXR, or a PNG decoded from sRGB, against which renders
        /// are measured as display values rounded to its 8 bits (default: the scene rendered
        /// at a much higher setting, cached in the user's cache folder or RAYTREE_CACHE).
        #[arg(long, value_name = "FILE")]
        reference: Option<std::path::PathBuf>,
        /// Seed of the random numbers, as for `render`.
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Worker threads (default: all cores).
        #[arg(long)]
        threads: Option<usize>,
        /// Also write the table as CSV to FILE.
        #[arg(long, value_name = "FILE")]
        csv: Option<std::path::PathBuf>,
        /// Plot error against time (log-log): FILE.svg, or FILE.png (the same plot drawn by
        /// resvg).
        #[arg(long, value_name = "FILE")]
        plot: Option<std::path::PathBuf>,
        /// Compare display values (clamped to [0, 1]) instead of raw radiance, so the few
        /// pixels of a bright emitter do not dominate the error.
        #[arg(long)]
        clamp: bool,
        /// Time this many renders at each value, after one untimed render when more than
        /// one, and report the median time (the image is the same each time).
        #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=99))]
        runs: u32,
        /// Output: the table to read, or JSON for programs.
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
    },
    /// Time per ray against the number of spheres (10 … 100 000) and mesh triangles
    /// (≈10³ … 10⁶), with and without the BVH, on one thread.
    #[command(after_help = "Examples:
  raytree bench scaling
  raytree bench scaling --max-spheres 10000 --max-subdivisions 6 --format json")]
    Scaling {
        /// Sphere rows are N = 10, 100, … 100 000 spheres, up to this N; a smaller value would
        /// leave no row to measure, and a larger one no row to add.
        #[arg(long, value_name = "N", default_value_t = MAX_SPHERES,
              value_parser = clap::value_parser!(u64).range(MIN_SPHERES..=MAX_SPHERES))]
        max_spheres: u64,
        /// Most spheres tested without the BVH too (brute force is O(N) per ray).
        #[arg(long, value_name = "N", default_value_t = 100_000)]
        max_brute: usize,
        /// Most mesh triangles tested without the BVH too (20 480 is the largest icosphere
        /// within the default).
        #[arg(long, value_name = "N", default_value_t = 25_000)]
        max_brute_triangles: usize,
        /// Mesh rows are icospheres of 20·4^k triangles at levels k = 3 (1 280 triangles) up
        /// to K; 8 (1.3 million) is the most an icosphere has.
        #[arg(long, value_name = "K", default_value_t = 8,
              value_parser = clap::value_parser!(u32).range(MIN_SUBDIVISIONS as i64..=8))]
        max_subdivisions: u32,
        /// Output: the table to read (a row as each is measured), or JSON at the end.
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
    },
    /// Speed-up with threads: SCENE rendered on 1 thread and on N, alternately, beside a
    /// control job of pure arithmetic split the same way, whose speed-up is the most this
    /// machine gives N threads. Prints medians over the runs.
    #[command(after_help = "Examples:
  raytree bench threads benches/peers/whitted.yaml
  raytree bench threads lessons/examples/cornell.yaml --threads 2 --runs 3 --format json")]
    Threads {
        /// The scene file (YAML), or a lesson's folder or name for its scene.yaml.
        #[arg(value_parser = super::args::scene_path)]
        scene: std::path::PathBuf,
        /// N (default: every core, at least 2).
        #[arg(long, value_parser = clap::value_parser!(u64).range(2..=super::args::MAX_THREADS as u64))]
        threads: Option<u64>,
        /// Rounds of 1 and N threads; the table shows their medians.
        #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u64).range(1..))]
        runs: u64,
        /// Output: the table to read, or JSON for programs.
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
    },
    /// How long the explorer makes its user wait: for each lesson (or scene), a depth key to
    /// the draft and to the full preview, a picked pixel to its ray tree, and a changed scene
    /// file to its full preview, in a terminal of the given size, driven headlessly. Prints
    /// medians in milliseconds.
    #[command(after_help = "Examples:
  raytree bench explorer
  raytree bench explorer 08-pixel-intensity lessons/examples/cornell.yaml --size 160x48
  raytree bench explorer --runs 9 --format json")]
    Explorer {
        /// Lesson folders or scene files (default: every built-in lesson).
        targets: Vec<std::path::PathBuf>,
        /// The terminal, COLUMNSxROWS.
        #[arg(long, default_value = "160x48", value_parser = parse_size)]
        size: (u16, u16),
        /// Depth changes and picks per scene; the table shows their medians.
        #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u64).range(1..=1000))]
        runs: u64,
        /// Output: the table to read, or JSON for programs.
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
    },
}

/// The first mesh row's icosphere level: 1 280 triangles, the ≈10³ the mesh rows start from.
const MIN_SUBDIVISIONS: u32 = 3;
/// The scaling table's fewest and most spheres: its first and last sphere rows.
const MIN_SPHERES: u64 = 10;
const MAX_SPHERES: u64 = 100_000;

/// A terminal size, `COLUMNSxROWS`.
fn parse_size(s: &str) -> Result<(u16, u16), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("`{s}`: give the size as COLUMNSxROWS, e.g. 160x48"))?;
    let number = |n: &str| match n.trim().parse::<u16>() {
        Ok(v) if (20..=1000).contains(&v) => Ok(v),
        _ => Err(format!(
            "`{s}`: COLUMNSxROWS, each a whole number from 20 to 1000"
        )),
    };
    Ok((number(w)?, number(h)?))
}

/// A number for JSON, which has no infinity: PSNR is infinite for an exact image.
fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// The plot's format, from its file name; checked before anything is rendered.
#[derive(Clone, Copy)]
enum PlotKind {
    Svg,
    Png,
}

impl PlotKind {
    fn of(path: &std::path::Path) -> Result<PlotKind, Failure> {
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("svg") => Ok(PlotKind::Svg),
            Some(e) if e.eq_ignore_ascii_case("png") => Ok(PlotKind::Png),
            _ => Err(Failure(format!(
                "{}: the plot is written as .svg or .png",
                path.display()
            ))),
        }
    }
}

/// A reference image as linear intensities: EXR as stored (f32, the precision renders are
/// rounded to before they are measured against it); an 8-bit PNG decoded from sRGB (renders are
/// encoded to 8-bit sRGB and decoded again before they are measured against it, as `render`
/// writes them); a 16-bit PNG decoded from sRGB.
fn load_reference(path: &std::path::Path, w: u32, h: u32) -> Result<Reference, Failure> {
    let img = image::open(path).map_err(|e| {
        let why = match e {
            image::ImageError::IoError(e) => e.to_string(),
            e => crate::shading::texture::decode_reason(&e),
        };
        Failure(format!("{}: {why}", path.display()))
    })?;
    if img.width() != w || img.height() != h {
        return Err(Failure(format!(
            "{}: reference is {}×{}, the scene renders {w}×{h}",
            path.display(),
            img.width(),
            img.height()
        )));
    }
    let exr = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("exr"));
    let (pixels, precision) = if exr {
        let pixels = img
            .into_rgb32f()
            .pixels()
            .map(|p| p.0.map(f64::from).into())
            .collect();
        (pixels, Precision::F32)
    } else if matches!(
        img.color(),
        image::ColorType::L8
            | image::ColorType::La8
            | image::ColorType::Rgb8
            | image::ColorType::Rgba8
    ) {
        let byte = Precision::srgb8_to_linear;
        let pixels = img
            .into_rgb8()
            .pixels()
            .map(|p| p.0.map(byte).into())
            .collect();
        (pixels, Precision::Srgb8)
    } else {
        let decode = |c: f32| crate::shading::texture::srgb_to_linear(c as f64);
        let pixels = img
            .into_rgb32f()
            .pixels()
            .map(|p| p.0.map(decode).into())
            .collect();
        (pixels, Precision::Full)
    };
    Ok(Reference {
        image: crate::render::Image {
            width: w,
            height: h,
            pixels,
        },
        precision,
    })
}

/// Where the reference of a sweep is cached: `references/` in the user's cache folder, a name
/// hashed from the contents of the scene file and of every file it read (meshes, images), the
/// knob, its values, the seed and this build's version. None when there is no cache folder, or
/// it cannot be made (the reference is then rendered every time).
fn reference_cache(
    scene_path: &std::path::Path,
    scene: &crate::scene::Scene,
    knob: crate::bench::Knob,
    values: &[f64],
    seed: u64,
) -> Result<Option<std::path::PathBuf>, Failure> {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    for path in std::iter::once(scene_path).chain(scene.inputs.iter().map(|p| p.as_path())) {
        let bytes = std::fs::read(path).map_err(|e| Failure(format!("{}: {e}", path.display())))?;
        bytes.hash(&mut h);
    }
    knob.name().hash(&mut h);
    values.iter().for_each(|v| v.to_bits().hash(&mut h));
    seed.hash(&mut h);
    env!("CARGO_PKG_VERSION").hash(&mut h);
    let Some(dir) = crate::files::cache_dir().map(|d| d.join("references")) else {
        eprintln("warning: no cache folder (set RAYTREE_CACHE): the reference is not kept");
        return Ok(None);
    };
    let mut builder = std::fs::DirBuilder::new();
    builder.recursive(true);
    // Private to the user: a reference read back from a folder others can write to could be
    // swapped for another image.
    #[cfg(unix)]
    {
        use std::os::unix::fs::DirBuilderExt;
        builder.mode(0o700);
    }
    if let Err(e) = builder.create(&dir) {
        eprintln(&format!(
            "warning: {}: cannot create the folder: {e}: the reference is not kept",
            dir.display()
        ));
        return Ok(None);
    }
    Ok(Some(dir.join(format!("{:016x}.exr", h.finish()))))
}

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    match a.measure {
        Measure::Sweep {
            scene: scene_path,
            knob,
            values,
            reference,
            seed,
            threads,
            csv,
            plot,
            clamp,
            runs,
            format,
        } => {
            for &v in &values {
                knob.check(v)?;
            }
            let plot_kind = plot.as_deref().map(PlotKind::of).transpose()?;
            // The outputs are written after the sweep: found wrong before it.
            for path in csv.iter().chain(&plot) {
                crate::render::check_output(path)?;
            }
            let pool = super::args::thread_pool(threads)?;
            // The file itself, also for the reference's cache key.
            let scene_path = super::args::named_lesson_scene(&scene_path);
            let scene = super::args::load_scene(&scene_path, false, super::args::AccelArg::Bvh)?;
            knob.acts_on(&scene)?;
            let (w, h) = (scene.camera.width, scene.camera.height);
            let reference = match reference {
                Some(path) => load_reference(&path, w, h)?,
                None => {
                    // Rendered once at a much higher setting, then kept as a linear EXR in the
                    // user's cache folder, named by everything it depends on.
                    let cache = reference_cache(&scene_path, &scene, knob, &values, seed)?;
                    match cache.as_ref().map(|c| (c, load_reference(c, w, h))) {
                        Some((cache, Ok(reference))) => {
                            eprintln(&format!("reference: {} (cached)", cache.display()));
                            reference
                        }
                        _ => {
                            let image = pool.install(|| {
                                crate::bench::reference_for(&scene, knob, &values, seed)
                            });
                            if let Some(cache) = &cache {
                                // Written whole or not at all, so a sweep stopped meanwhile
                                // leaves no half reference for the next to read.
                                match image.save(cache, crate::render::Encoding::Linear) {
                                    Ok(()) => eprintln(&format!(
                                        "reference: rendered, cached in {}",
                                        cache.display()
                                    )),
                                    Err(e) => eprintln(&format!(
                                        "warning: the reference is not kept: {e}"
                                    )),
                                }
                            }
                            // At the precision the cache keeps, so that this sweep measures
                            // what the next, reading the cache, will.
                            Reference {
                                image: Precision::F32.round(&image),
                                precision: Precision::F32,
                            }
                        }
                    }
                }
            };
            let rows = pool.install(|| {
                crate::bench::sweep(
                    &scene,
                    knob,
                    &values,
                    &reference,
                    seed,
                    clamp,
                    runs as usize,
                )
            });
            match format {
                Format::Text => print(&crate::bench::sweep_table(knob, &rows))?,
                Format::Json => print_json(serde_json::json!({
                    "scene": scene_path.display().to_string(),
                    "knob": knob.name(),
                    "seed": seed,
                    "clamp": clamp,
                    "rows": rows.iter().map(|r| serde_json::json!({
                        "value": r.value,
                        "seconds": r.seconds,
                        "rays": r.rays,
                        "rmse": r.rmse,
                        "rel_mse": r.rel_mse,
                        "max_abs": r.max_abs,
                        "psnr": finite(r.psnr),
                        "efficiency": r.efficiency(),
                        "exact": r.exact(),
                    })).collect::<Vec<_>>(),
                }))?,
            }
            if let Some(path) = csv {
                crate::render::write_atomically(
                    &path,
                    crate::bench::sweep_csv(knob, &rows).as_bytes(),
                )?;
            }
            if let (Some(path), Some(kind)) = (plot, plot_kind) {
                let svg = crate::bench::sweep_plot_svg(knob, &rows)?;
                let bytes = match kind {
                    PlotKind::Svg => svg.into_bytes(),
                    PlotKind::Png => {
                        if !raster::have_fonts() {
                            eprintln(
                                "warning: no fonts found on this system: the PNG has no labels",
                            );
                        }
                        raster::png(&svg)?
                    }
                };
                crate::render::write_atomically(&path, &bytes)?;
            }
        }
        Measure::Scaling {
            max_spheres,
            max_brute,
            max_brute_triangles,
            max_subdivisions,
            format,
        } => {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
            // The sweep is long: the table is printed a row at a time, as each is measured.
            let text = format == Format::Text;
            if text {
                print(&table_header())?;
            }
            let rows = pool.install(|| -> Result<Vec<Row>, Failure> {
                let mut rows = vec![];
                let mut show = |row: Row| -> Result<(), Failure> {
                    if text {
                        print(&table_row(&row))?;
                    }
                    rows.push(row);
                    Ok(())
                };
                let sizes = [MIN_SPHERES, 100, 1_000, 10_000, MAX_SPHERES].map(|n| n as usize);
                for n in sizes.into_iter().filter(|&n| n as u64 <= max_spheres) {
                    show(measure("spheres", n, &spheres(n), n <= max_brute)?)?;
                }
                for k in MIN_SUBDIVISIONS..=max_subdivisions {
                    let n = 20 * 4usize.pow(k);
                    show(measure("mesh", n, &mesh(k), n <= max_brute_triangles)?)?;
                }
                Ok(rows)
            })?;
            if !text {
                print_json(serde_json::json!({
                    "rows": rows.iter().map(|r| serde_json::json!({
                        "kind": r.kind,
                        "n": r.n,
                        "build_seconds": r.build,
                        "bvh_built": r.bvh_ns.is_some(),
                        "bvh_ns_per_ray": r.bvh_ns,
                        "brute_ns_per_ray": r.brute_ns,
                        "nodes_per_ray": r.nodes_per_ray,
                        "primitives_per_ray": r.prims_per_ray,
                        "bytes_per_triangle": r.bytes_per_triangle,
                    })).collect::<Vec<_>>(),
                }))?;
            }
        }
        Measure::Threads {
            scene: scene_path,
            threads: n,
            runs,
            format,
        } => {
            let scene_path = super::args::named_lesson_scene(&scene_path);
            let scene = super::args::load_scene(&scene_path, false, super::args::AccelArg::Bvh)?;
            let cores = std::thread::available_parallelism().map_or(2, |n| n.get());
            let n = n.map_or(cores.max(2), |n| n as usize);
            eprintln(&format!(
                "{}: {runs} round{} of 1 and {n} threads, scene and control alternating",
                scene_path.display(),
                if runs == 1 { "" } else { "s" }
            ));
            let rounds = thread_rounds(&scene, n, runs as usize)?;
            match format {
                Format::Text => print(&threads_table(&rounds, n))?,
                Format::Json => print_json(serde_json::json!({
                    "scene": scene_path.display().to_string(),
                    "threads": n,
                    "rays": rounds.rays,
                    "renders_per_figure": rounds.repeats,
                    "runs": rounds.runs.iter().map(|r| serde_json::json!({
                        "render_one_thread_seconds": r.render_one,
                        "render_seconds": r.render_many,
                        "control_one_thread_seconds": r.control_one,
                        "control_seconds": r.control_many,
                    })).collect::<Vec<_>>(),
                }))?,
            }
        }
        Measure::Explorer {
            targets,
            size,
            runs,
            format,
        } => explorer(targets, size, runs as usize, format)?,
    }
    Ok(ExitCode::SUCCESS)
}

/// `bench explorer`: one row per lesson or scene.
fn explorer(
    targets: Vec<std::path::PathBuf>,
    size: (u16, u16),
    runs: usize,
    format: Format,
) -> Result<(), Failure> {
    let targets: Vec<std::path::PathBuf> = if targets.is_empty() {
        let root = crate::lessons::lessons_root().map_err(|e| Failure(e.to_string()))?;
        crate::lessons::all_lessons(&root)
            .map_err(|e| Failure(e.to_string()))?
            .into_iter()
            .map(|l| l.dir)
            .collect()
    } else {
        targets
            .iter()
            .map(|t| crate::lessons::find_lesson(t))
            .collect()
    };
    let ms = |d: std::time::Duration| d.as_secs_f64() * 1e3;
    let mut rows = vec![];
    for target in &targets {
        let l =
            crate::tui::latency::measure(target, size, runs).map_err(|e| Failure(e.to_string()))?;
        let name = target
            .file_name()
            .map_or(target.display().to_string(), |n| n.to_string_lossy().into());
        rows.push((name, l));
    }
    match format {
        Format::Text => {
            let mut out = format!(
                "{} × {} terminal, {} (ms)\n{:<24} {:>9} {:>8} {:>8} {:>8} {:>8}\n",
                size.0,
                size.1,
                match runs {
                    1 => "one run".to_string(),
                    n => format!("medians of {n} runs"),
                },
                "scene",
                "preview",
                "draft",
                "full",
                "pick",
                "reload"
            );
            for (name, l) in &rows {
                let draft = l.draft.map_or("—".to_string(), |d| format!("{:.1}", ms(d)));
                out += &format!(
                    "{:<24} {:>9} {:>8} {:>8.1} {:>8.2} {:>8.1}\n",
                    name,
                    format!("{}×{}", l.preview.0, l.preview.1),
                    draft,
                    ms(l.full),
                    ms(l.pick),
                    ms(l.reload)
                );
            }
            print(&out)?;
        }
        Format::Json => print_json(serde_json::json!({
            "terminal": [size.0, size.1],
            "runs": runs,
            "scenes": rows.iter().map(|(name, l)| serde_json::json!({
                "scene": name,
                "preview": [l.preview.0, l.preview.1],
                "draft_ms": l.draft.map(ms),
                "full_ms": ms(l.full),
                "pick_ms": ms(l.pick),
                "reload_ms": ms(l.reload),
            })).collect::<Vec<_>>(),
        }))?,
    }
    Ok(())
}
