//! Arguments shared by several subcommands, and their parsers.

use std::path::{Path, PathBuf};

use glam::DVec3;

use super::Failure;
use crate::geometry::Ray;
use crate::scene::format::MAX_MAGNITUDE;
use crate::scene::{Accel, Antialias, Integrator, Limits, Scene, DEFAULT_THRESHOLD};

/// `X,Y`
pub fn parse_pixel(s: &str) -> Result<[u32; 2], String> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    match parts.as_slice() {
        [x, y] => match (x.parse(), y.parse()) {
            (Ok(x), Ok(y)) => Ok([x, y]),
            _ => Err(format!(
                "expected a pixel X,Y of two whole numbers, got `{s}`"
            )),
        },
        _ => Err(format!("expected a pixel X,Y, got `{s}`")),
    }
}

/// `X,Y,Z`, three numbers within ±`limit`.
fn parse_vec3(s: &str, limit: f64) -> Result<DVec3, String> {
    let v: Result<Vec<f64>, _> = s.split(',').map(|p| p.trim().parse::<f64>()).collect();
    match v {
        Ok(v) if v.len() == 3 && v.iter().all(|x| x.abs() <= limit) => {
            Ok(DVec3::new(v[0], v[1], v[2]))
        }
        _ if limit == f64::MAX => Err(format!("expected three finite numbers x,y,z, got `{s}`")),
        _ => Err(format!(
            "expected three numbers x,y,z within ±{limit:e} (as in a scene file), got `{s}`"
        )),
    }
}

/// `OX,OY,OZ:DX,DY,DZ`; the direction is normalised.
pub fn parse_ray(s: &str) -> Result<Ray, String> {
    let (o, d) = s
        .split_once(':')
        .ok_or_else(|| format!("expected a ray OX,OY,OZ:DX,DY,DZ, got `{s}`"))?;
    // The origin is a point of the scene, held to the scene file's bounds; the direction is
    // only a direction, normalised below whatever its size.
    let (o, d) = (parse_vec3(o, MAX_MAGNITUDE)?, parse_vec3(d, f64::MAX)?);
    if d == DVec3::ZERO {
        return Err("the ray direction must not be zero".into());
    }
    // Scaled by its largest component first, the direction's length lies in [1, √3]: its
    // square neither underflows (1e-320) nor overflows (1e308) on the way to a unit vector.
    Ok(Ray::new(o, d / d.abs().max_element()))
}

/// Most worker threads asked for: more than any machine raytree runs on has cores, and few
/// enough to start at once.
pub const MAX_THREADS: usize = 1024;

/// The stack of each render worker: the fast wing's waves of secondary rays take tens of
/// kilobytes a level on it (`fast::packet_trace`), and a tree may be 64 levels deep. Only the
/// pages a render touches are ever given memory.
pub const RENDER_STACK: usize = 32 * 1024 * 1024;

/// A pool of `--threads N` workers (default: one per core), each with a `RENDER_STACK`, or a
/// clear error before any is started.
pub fn thread_pool(threads: Option<usize>) -> Result<rayon::ThreadPool, Failure> {
    if let Some(n) = threads {
        if !(1..=MAX_THREADS).contains(&n) {
            return Err(Failure(format!(
                "--threads must be between 1 and {MAX_THREADS}, got {n}"
            )));
        }
    }
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .stack_size(RENDER_STACK)
        .build()
        .map_err(|e| {
            Failure(format!(
                "cannot start {} worker threads: {e}",
                threads.map_or("the".to_string(), |n| n.to_string())
            ))
        })
}

#[derive(clap::ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AccelArg {
    /// Test every object against every ray.
    None,
    /// A bounding volume hierarchy.
    #[default]
    Bvh,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Format {
    /// Lines for people to read.
    #[default]
    Text,
    /// One JSON document (with "raytree_version") for programs.
    Json,
}

/// How a scene is loaded.
#[derive(clap::Args, Debug, Clone)]
pub struct SceneArgs {
    /// The scene file (YAML), or a lesson's folder or name for its scene.yaml.
    #[arg(value_parser = scene_path)]
    pub scene: PathBuf,
    /// Go beyond the budgets that keep a mistake from exhausting memory: 64 million pixels,
    /// 16 MiB scene files, 256 MiB mesh files, 200 000 objects, 4 million triangles.
    #[arg(long)]
    pub allow_huge: bool,
    /// Intersection acceleration: a bounding volume hierarchy, or testing every object.
    #[arg(long, value_enum, default_value_t = AccelArg::Bvh)]
    pub accel: AccelArg,
}

impl SceneArgs {
    pub fn load(&self) -> Result<Scene, Failure> {
        load_scene(&self.scene, self.allow_huge, self.accel)
    }
}

/// A scene given on the command line: a folder that holds a `scene.yaml` (a lesson's) stands
/// for that file, as `raytree explore` takes it.
pub fn scene_path(arg: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(arg);
    let lesson_scene = path.join("scene.yaml");
    Ok(if path.is_dir() && lesson_scene.is_file() {
        lesson_scene
    } else {
        path
    })
}

/// Where no file or folder `path` exists, the lessons' file it names (`08-pixel-intensity/
/// scene.yaml`, `lessons/examples/cornell.yaml`) or the scene.yaml of the lesson it names (the
/// lessons folder is known only once the command line is read: `--lessons`); else `path`.
pub fn named_lesson_scene(path: &Path) -> PathBuf {
    if path.exists() {
        return path.to_path_buf();
    }
    let found = crate::lessons::find_lesson(path);
    if found.is_file() {
        return found;
    }
    let scene = found.join("scene.yaml");
    if scene.is_file() {
        scene
    } else {
        path.to_path_buf()
    }
}

/// The budgets a command works within: the defaults, or `--allow-huge`'s.
pub fn limits(allow_huge: bool) -> Limits {
    if allow_huge {
        Limits::huge()
    } else {
        Limits::default()
    }
}

/// Loads a scene, printing its warnings. A name that is no path (`08-pixel-intensity`) stands
/// for the scene of the lesson of that name, as `raytree explore` finds it.
pub fn load_scene(path: &Path, allow_huge: bool, accel: AccelArg) -> Result<Scene, Failure> {
    let path = &named_lesson_scene(path);
    let mut scene = crate::scene::load(path, &limits(allow_huge)).map_err(Failure::scene)?;
    for (pos, warning) in &scene.warnings {
        super::output::eprintln(&format!(
            "raytree: {}:{}:{}: warning: {warning}",
            path.display(),
            pos.line,
            pos.column
        ));
    }
    if accel == AccelArg::None {
        scene.set_accel(Accel::None);
    }
    Ok(scene)
}

/// A pixel or an explicit ray: where an inspection starts.
#[derive(clap::Args, Debug, Clone)]
#[group(required = true, multiple = false)]
pub struct Target {
    /// The pixel X,Y ((0,0) is top-left).
    #[arg(long, value_parser = parse_pixel)]
    pub pixel: Option<[u32; 2]>,
    /// An explicit ray OX,OY,OZ:DX,DY,DZ.
    #[arg(long, value_parser = parse_ray, allow_hyphen_values = true)]
    pub ray: Option<Ray>,
}

impl Target {
    /// The ray to follow; checks the pixel lies in the image.
    pub fn ray(&self, scene: &Scene) -> Result<Ray, Failure> {
        match (self.pixel, self.ray) {
            (Some([x, y]), _) => {
                let (w, h) = (scene.camera.width, scene.camera.height);
                if x >= w || y >= h {
                    return Err(Failure(format!(
                        "pixel {x},{y} is outside the {w} × {h} image"
                    )));
                }
                Ok(scene.camera.pixel_ray(x, y))
            }
            (None, Some(r)) => Ok(r),
            (None, None) => Err(Failure(
                "give --pixel X,Y or --ray OX,OY,OZ:DX,DY,DZ".into(),
            )),
        }
    }
}

/// Checks a --depth override.
pub fn depth(scene: &Scene, depth: Option<u32>) -> Result<u32, Failure> {
    match depth {
        None => Ok(scene.max_depth),
        Some(d) if (1..=64).contains(&d) => Ok(d),
        Some(d) => Err(Failure(format!(
            "--depth must be between 1 and 64, got {d}"
        ))),
    }
}

/// The image a render makes, as `render` and `inspect` take it: its size and how its pixels
/// are sampled, each the scene's unless given.
#[derive(clap::Args, Debug, Default)]
pub struct FilmArgs {
    /// Image width in pixels (default: the scene camera's); the field of view is kept.
    #[arg(long)]
    pub width: Option<u32>,
    /// Image height in pixels (default: the scene camera's).
    #[arg(long)]
    pub height: Option<u32>,
    /// Primary rays per pixel (a square number gives a regular grid).
    #[arg(long)]
    pub spp: Option<u32>,
    /// Where a pixel's primary rays go: grid, jittered or adaptive (default: the scene's); a
    /// path-traced scene takes adaptive only (else its samples form a Sobol net).
    #[arg(long, value_enum)]
    pub aa: Option<AaArg>,
    /// Adaptive antialiasing: split a square whose corners differ by more than this (sum of
    /// |Δr| + |Δg| + |Δb|; default the scene's aa_threshold, else 0.3 as POV-Ray).
    #[arg(long, value_name = "T")]
    pub aa_threshold: Option<f64>,
}

impl FilmArgs {
    /// The image's width and height.
    pub fn size(&self, scene: &Scene) -> Result<(u32, u32), Failure> {
        let w = self.width.unwrap_or(scene.camera.width);
        let h = self.height.unwrap_or(scene.camera.height);
        if w == 0 || h == 0 || w > 1_000_000 || h > 1_000_000 {
            return Err(Failure(format!(
                "image size {w} × {h} must be between 1 and 1000000 pixels each way"
            )));
        }
        Ok((w, h))
    }

    /// The scene with its camera resized and its sampling set as given.
    pub fn apply(&self, scene: &mut Scene, limits: &Limits) -> Result<(), Failure> {
        let (w, h) = self.size(scene)?;
        // The budget a scene file's own size is held to (`render` checks its frames first).
        let pixels = w as u64 * h as u64;
        if pixels > limits.max_pixels {
            return Err(Failure(format!(
                "an image of {w} × {h} holds {pixels} pixels, over the budget of {} pixels ({})",
                limits.max_pixels,
                Limits::RAISE
            )));
        }
        let spp = self.spp.unwrap_or(scene.spp);
        if !(1..=limits.max_spp).contains(&spp) {
            return Err(Failure(format!(
                "--spp must be between 1 and {}, got {spp}",
                limits.max_spp
            )));
        }
        scene.antialias = antialias(scene, self.aa, self.aa_threshold)?;
        scene.camera = scene.camera.resized(w, h);
        scene.spp = spp;
        Ok(())
    }

    /// The flags as given, for a command line that repeats them.
    pub fn flags(&self) -> String {
        let mut flags = String::new();
        let mut add = |name: &str, value: Option<String>| {
            if let Some(v) = value {
                flags += &format!(" --{name} {v}");
            }
        };
        add("width", self.width.map(|w| w.to_string()));
        add("height", self.height.map(|h| h.to_string()));
        add("spp", self.spp.map(|s| s.to_string()));
        let aa = self
            .aa
            .and_then(|aa| clap::ValueEnum::to_possible_value(&aa));
        add("aa", aa.map(|v| v.get_name().to_string()));
        add("aa-threshold", self.aa_threshold.map(|t| t.to_string()));
        flags
    }
}

/// `--aa`: the antialiasing modes.
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum AaArg {
    /// A regular √spp × √spp grid in each pixel.
    Grid,
    /// One random point in each cell of that grid.
    Jittered,
    /// Corners first, squares split where they differ by more than --aa-threshold.
    Adaptive,
}

/// The scene's antialiasing, changed by `--aa` and `--aa-threshold`.
fn antialias(
    scene: &Scene,
    mode: Option<AaArg>,
    threshold: Option<f64>,
) -> Result<Antialias, Failure> {
    let scene_threshold = match scene.antialias {
        Antialias::Adaptive { threshold } => threshold,
        _ => DEFAULT_THRESHOLD,
    };
    let threshold_given = threshold.is_some();
    let threshold = match threshold {
        Some(t) if !(0.0..=3.0).contains(&t) => {
            return Err(Failure(format!(
                "--aa-threshold must be between 0 and 3, got {t}"
            )))
        }
        Some(t) => t,
        None => scene_threshold,
    };
    let chosen = match mode {
        None => match scene.antialias {
            Antialias::Adaptive { .. } => Antialias::Adaptive { threshold },
            other => other,
        },
        Some(AaArg::Grid) => Antialias::Grid,
        Some(AaArg::Jittered) => Antialias::Jittered,
        Some(AaArg::Adaptive) => Antialias::Adaptive { threshold },
    };
    if scene.integrator == Integrator::Path {
        if let Some(AaArg::Grid | AaArg::Jittered) = mode {
            return Err(Failure(format!(
                "--aa {} is not for a path-traced scene: the path tracer spreads a pixel's samples as a scrambled Sobol net (only --aa adaptive changes how it samples)",
                chosen.name()
            )));
        }
    }
    if threshold_given && !matches!(chosen, Antialias::Adaptive { .. }) {
        return Err(Failure(
            "--aa-threshold is for adaptive antialiasing: add --aa adaptive".into(),
        ));
    }
    Ok(chosen)
}
