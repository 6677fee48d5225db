//! The run-time-against-error sweep: one knob turned, each image measured against a reference.

use std::time::Instant;

use super::error::BenchError;
use crate::render::antialias::adaptive_levels;
use crate::render::{render_simple, Image, RenderOptions};
use crate::scene::Antialias;
use crate::scene::{Integrator, Scene};
use crate::stats::Stats;

/// The knob a run-time-against-error sweep turns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Knob {
    /// Samples per pixel.
    Spp,
    /// Maximum depth (rays per path).
    Depth,
    /// Adaptive depth control: the weight below which a ray is not traced.
    Adaptive,
    /// Rays per glossy or frosted hit (every lobe of the scene gets this many).
    Glossy,
    /// Adaptive antialiasing: the corner difference above which a square is split.
    AaThreshold,
}

impl Knob {
    /// Whether the knob can take `value`: the bounds `render` and the scene format put on the
    /// setting it turns, so a sweep renders nothing `render` would refuse.
    pub fn check(self, value: f64) -> Result<(), BenchError> {
        let limits = crate::scene::Limits::default();
        let whole = |lo: u32, hi: u32, what: &'static str| {
            if value.fract() == 0.0 && value >= lo as f64 && value <= hi as f64 {
                Ok(())
            } else {
                Err(BenchError::NotWhole {
                    knob: self,
                    value,
                    lo,
                    hi,
                    what,
                })
            }
        };
        let within = |lo: f64, hi: f64, what: &'static str| {
            if (lo..=hi).contains(&value) {
                Ok(())
            } else {
                Err(BenchError::OutOfRange {
                    knob: self,
                    value,
                    lo,
                    hi,
                    what,
                })
            }
        };
        match self {
            Knob::Spp => whole(1, limits.max_spp, "as render's --spp"),
            Knob::Depth => whole(1, limits.max_depth, "as render's --depth"),
            Knob::Adaptive => within(0.0, 1.0, "as the scene's adaptive_threshold"),
            Knob::Glossy => whole(1, 1024, "as a lobe's samples"),
            Knob::AaThreshold => within(0.0, 3.0, "as render's --aa-threshold"),
        }
    }

    /// Whether turning the knob can change `scene`'s image: an error saying what the scene
    /// lacks when it cannot (a sweep of it would measure nothing). Samples per pixel move
    /// every image's primary rays, and so does the antialiasing threshold where a pixel has
    /// a grid of samples to split into; the others act only on rays after the first hit.
    pub fn acts_on(self, scene: &Scene) -> Result<(), BenchError> {
        let path = scene.integrator == Integrator::Path;
        let features = &scene.features;
        let recursion = features.reflective || features.transparent;
        let why = match self {
            // Adaptive antialiasing splits a pixel's square no finer than the √spp grid.
            Knob::AaThreshold if adaptive_levels(scene.spp) == 0 => Some(
                "the scene renders one sample a pixel (spp: 1), and adaptive antialiasing splits a pixel no finer than its √spp grid: give the scene spp: 4 or more",
            ),
            Knob::Spp | Knob::AaThreshold => None,
            // The path tracer's paths bounce off anything.
            Knob::Depth if path => None,
            Knob::Adaptive if path => Some("the path tracer (integrator: path) has no adaptive depth control"),
            Knob::Glossy if path => Some(
                "the path tracer (integrator: path) follows one ray per bounce, whatever a lobe's samples",
            ),
            Knob::Depth | Knob::Adaptive if !recursion => Some(
                "nothing reflects or refracts (no material with kr > 0 or kt > 0), so no ray is traced past the first hit",
            ),
            Knob::Depth | Knob::Adaptive => None,
            Knob::Glossy => (!scene.leaves.iter().any(|leaf| {
                let m = &scene.materials[leaf.material as usize];
                (m.glossy.is_some() && m.reflective()) || (m.frosted.is_some() && m.transparent())
            }))
            .then_some(
                "it has no glossy or frosted material (a glossy lobe with kr > 0, or a frosted one with kt > 0)",
            ),
        };
        match why {
            Some(why) => Err(BenchError::Idle { knob: self, why }),
            None => Ok(()),
        }
    }

    /// The name used on the command line and in table headers.
    pub fn name(self) -> String {
        match self {
            Knob::Spp => "spp",
            Knob::Depth => "depth",
            Knob::Adaptive => "adaptive",
            Knob::Glossy => "glossy",
            Knob::AaThreshold => "aa-threshold",
        }
        .to_string()
    }
}

/// How finely a reference keeps its intensities. A render is rounded the same way before it is
/// measured: one equal to the reference to the reference's own precision has no error, and
/// reads "exact" whether the reference was rendered in this run or read from a file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Precision {
    /// As computed: the render is measured as it is.
    Full,
    /// f32, as an EXR file stores a render's f64 intensities.
    F32,
    /// 8-bit sRGB, as a PNG stores a render: display values, clamped to [0, 1].
    Srgb8,
}

impl Precision {
    /// `image` with every channel rounded to this precision.
    pub fn round(self, image: &Image) -> Image {
        let mut out = image.clone();
        for p in &mut out.pixels {
            *p = match self {
                Precision::Full => *p,
                Precision::F32 => p.as_vec3().as_dvec3(),
                Precision::Srgb8 => p.map(|c| {
                    Precision::srgb8_to_linear(crate::render::encode(
                        c,
                        crate::render::Encoding::Srgb,
                    ))
                }),
            };
        }
        out
    }

    /// The linear intensity an 8-bit sRGB value stands for.
    pub fn srgb8_to_linear(byte: u8) -> f64 {
        crate::shading::texture::srgb_to_linear(byte as f64 / 255.0)
    }
}

/// The image a sweep measures its renders against, and the precision it was kept at. Renders
/// measured against an 8-bit sRGB reference are measured as display values (clamped), as the
/// reference holds them.
#[derive(Clone, Debug)]
pub struct Reference {
    /// Linear intensities.
    pub image: Image,
    /// How finely `image` holds them.
    pub precision: Precision,
}

/// One setting of the knob: its cost and its error against the reference.
#[derive(Clone, Debug)]
pub struct SweepRow {
    /// The knob's setting.
    pub value: f64,
    /// Wall-clock seconds to render the image.
    pub seconds: f64,
    /// Rays traced: primary, shadow, reflected and refracted.
    pub rays: u64,
    /// Root mean square error against the reference, over every channel of every pixel.
    pub rmse: f64,
    /// Mean of ((x − ref)/(ref + 0.01))²: error relative to brightness.
    pub rel_mse: f64,
    /// The largest absolute difference from the reference, over every channel.
    pub max_abs: f64,
    /// 20·log10(1/RMSE) for intensities in [0, 1]: infinite for an exact image.
    pub psnr: f64,
}

impl SweepRow {
    /// Whether the image equals the reference (to the reference's precision).
    pub fn exact(&self) -> bool {
        self.rmse == 0.0
    }

    /// 1/(seconds·MSE): higher is better; None for an exact image, whose MSE is 0.
    pub fn efficiency(&self) -> Option<f64> {
        (!self.exact()).then(|| 1.0 / (self.seconds * self.rmse * self.rmse))
    }
}

/// RMSE, relative MSE and the largest absolute difference, over all channels.
pub fn errors(image: &crate::render::Image, reference: &crate::render::Image) -> (f64, f64, f64) {
    let n = (image.pixels.len() * 3) as f64;
    let (mut se, mut rel, mut max) = (0.0, 0.0, 0.0f64);
    for (a, b) in image.pixels.iter().zip(&reference.pixels) {
        for c in 0..3 {
            let d = a[c] - b[c];
            se += d * d;
            rel += (d / (b[c].abs() + 0.01)).powi(2);
            max = max.max(d.abs());
        }
    }
    ((se / n).sqrt(), rel / n, max)
}

fn options_for(scene: &Scene, knob: Knob, value: f64, seed: u64) -> (Scene, RenderOptions) {
    let mut s = scene.clone();
    let mut o = RenderOptions {
        seed,
        ..RenderOptions::of(scene)
    };
    match knob {
        Knob::Spp => o.spp = value as u32,
        Knob::Depth => o.max_depth = value as u32,
        Knob::Adaptive => s.adaptive_threshold = value,
        Knob::Glossy => {
            for m in &mut s.materials {
                for lobe in [&mut m.glossy, &mut m.frosted].into_iter().flatten() {
                    lobe.samples = value.max(1.0) as u32;
                }
            }
        }
        Knob::AaThreshold => o.antialias = Antialias::Adaptive { threshold: value },
    }
    (s, o)
}

/// Renders at every value of the knob and measures time and error against `reference`, each
/// render rounded to the reference's precision.
pub fn sweep(
    scene: &Scene,
    knob: Knob,
    values: &[f64],
    reference: &Reference,
    seed: u64,
    clamp: bool,
    runs: usize,
) -> Vec<SweepRow> {
    let display = |img: &crate::render::Image| {
        let mut out = img.clone();
        if clamp {
            out.pixels
                .iter_mut()
                .for_each(|p| *p = p.clamp(glam::DVec3::ZERO, glam::DVec3::ONE));
        }
        out
    };
    let reference_image = &display(&reference.image);
    values
        .iter()
        .map(|&value| {
            let (s, o) = options_for(scene, knob, value, seed);
            let (image, stats, seconds) = timed_renders(&s, o, runs);
            let image = reference.precision.round(&image);
            let (rmse, rel_mse, max_abs) = errors(&display(&image), reference_image);
            SweepRow {
                value,
                seconds,
                rays: stats.rays(),
                rmse,
                rel_mse,
                max_abs,
                psnr: -20.0 * rmse.log10(),
            }
        })
        .collect()
}

/// The scene rendered `runs` times (`timed`), and the median of the renders' times.
fn timed_renders(scene: &Scene, options: RenderOptions, runs: usize) -> (Image, Stats, f64) {
    let ((image, stats), seconds) = timed(runs, || render_simple(scene, options));
    (image, stats, seconds)
}

/// `work` done `runs` times, after once untimed when more than once is asked for (which
/// warms the caches and the thread pool), and the median of the timed runs' seconds. The
/// work gives the same result each time: the last is returned.
fn timed<T>(runs: usize, mut work: impl FnMut() -> T) -> (T, f64) {
    if runs > 1 {
        work();
    }
    let mut times = vec![];
    let mut last = None;
    for _ in 0..runs.max(1) {
        let start = Instant::now();
        last = Some(work());
        times.push(start.elapsed().as_secs_f64());
    }
    (last.expect("at least one run"), median(times))
}

/// The middle of the values (the upper middle of an even count).
fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// The reference when none is given: the same scene at a much higher setting (16× the largest
/// sample count or glossy ray count, 8 levels deeper, no adaptive cut-off, or the full grid that
/// adaptive antialiasing approximates).
pub fn reference_for(scene: &Scene, knob: Knob, values: &[f64], seed: u64) -> crate::render::Image {
    let value = match knob {
        Knob::Spp => values.iter().cloned().fold(1.0, f64::max) * 16.0,
        // Eight levels beyond the deepest setting: a glass surface doubles the rays at every
        // level, so "unlimited" would never finish.
        Knob::Depth => values.iter().cloned().fold(1.0, f64::max) + 8.0,
        Knob::Adaptive | Knob::AaThreshold => 0.0,
        Knob::Glossy => values.iter().cloned().fold(1.0, f64::max) * 16.0,
    };
    let (s, mut o) = options_for(scene, knob, value, seed ^ 0x5eed);
    if knob == Knob::AaThreshold {
        // What adaptive sampling approximates: the full grid of the same sample count.
        o.antialias = Antialias::Grid;
    }
    render_simple(&s, o).0
}

/// 1/(seconds·MSE), or "exact" when the image equals the reference.
fn efficiency(r: &SweepRow) -> String {
    match r.efficiency() {
        None => "exact".into(),
        Some(e) => format!("{e:.0}"),
    }
}

/// The sweep as a text table: a line per setting, with PSNR in dB and the efficiency
/// 1/(seconds·MSE) (higher is better).
pub fn sweep_table(knob: Knob, rows: &[SweepRow]) -> String {
    // The first column as wide as the knob's name ("aa-threshold") where it is wider.
    let w = knob.name().chars().count().max(10);
    let mut s = format!(
        "{:>w$} {:>10} {:>14} {:>11} {:>11} {:>10} {:>8} {:>14}\n",
        knob.name(),
        "seconds",
        "rays",
        "RMSE",
        "rel MSE",
        "max |err|",
        "PSNR",
        "1/(s·MSE)"
    );
    for r in rows {
        s.push_str(&format!(
            "{:>w$} {:>10} {:>14} {:>11.5} {:>11.5} {:>10.4} {:>8} {:>14}\n",
            r.value,
            super::seconds(r.seconds),
            r.rays,
            r.rmse,
            r.rel_mse,
            r.max_abs,
            match r.psnr {
                p if p.is_finite() => format!("{p:.2}"),
                _ => "∞".into(),
            },
            efficiency(r)
        ));
    }
    s
}

/// The sweep as CSV, the columns of the table: a header line (the knob's name, then seconds,
/// rays, rmse, rel_mse, max_abs, psnr, efficiency) and a line per setting. The efficiency is
/// the table's 1/(seconds·MSE), rounded the same way and "exact" where the table says so;
/// the PSNR of an exact image is `inf`.
pub fn sweep_csv(knob: Knob, rows: &[SweepRow]) -> String {
    let mut s = format!(
        "{},seconds,rays,rmse,rel_mse,max_abs,psnr,efficiency\n",
        knob.name()
    );
    for r in rows {
        s.push_str(&format!(
            "{},{},{},{},{},{},{},{}\n",
            r.value,
            r.seconds,
            r.rays,
            r.rmse,
            r.rel_mse,
            r.max_abs,
            r.psnr,
            efficiency(r)
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene(materials: &str, integrator: &str) -> Scene {
        let yaml = format!(
            "camera: {{ eye: [0, 0, -5], look_at: [0, 0, 0], width: 8, height: 6 }}\nspp: 4\n\
             {integrator}lights: [ {{ point: [2, 3, -4] }} ]\nmaterials: {{ {materials} }}\n\
             objects: [ {{ sphere: {{ center: [0, 0, 0], radius: 1 }}, material: m }} ]\n"
        );
        crate::scene::parse(&yaml, "test", None, &crate::scene::Limits::default()).unwrap()
    }

    /// Which knobs can change which scenes (of 4 samples a pixel): depth and adaptive need a
    /// ray past the first hit, glossy a lobe on a material that reflects or refracts; the
    /// path tracer bounces off anything but has neither adaptive control nor lobe samples.
    /// The antialiasing threshold needs a grid to split a pixel into: 2 samples or more.
    #[test]
    fn a_knob_acts_only_on_a_scene_that_has_what_it_turns() {
        use Knob::*;
        let cases = [
            ("m: { kd: 1 }", "", [Spp, AaThreshold].as_slice()),
            (
                "m: { kd: 0.5, kr: 0.5 }",
                "",
                &[Spp, AaThreshold, Depth, Adaptive],
            ),
            (
                "m: { kd: 0.5, kt: 0.5 }",
                "",
                &[Spp, AaThreshold, Depth, Adaptive],
            ),
            // A lobe on a material that neither reflects nor refracts sends no rays.
            (
                "m: { kd: 1, glossy: { spread: 5 } }",
                "",
                &[Spp, AaThreshold],
            ),
            (
                "m: { kd: 0.5, kr: 0.5, glossy: { spread: 5 } }",
                "",
                &[Spp, AaThreshold, Depth, Adaptive, Glossy],
            ),
            (
                "m: { kt: 0.5, frosted: { spread: 5 } }",
                "",
                &[Spp, AaThreshold, Depth, Adaptive, Glossy],
            ),
            (
                "m: { kd: 0.5, kr: 0.5, glossy: { spread: 5 } }",
                "integrator: path\n",
                &[Spp, AaThreshold, Depth],
            ),
        ];
        for (materials, integrator, acting) in cases {
            let s = scene(materials, integrator);
            for knob in [Spp, Depth, Adaptive, Glossy, AaThreshold] {
                let acts = knob.acts_on(&s);
                assert_eq!(
                    acts.is_ok(),
                    acting.contains(&knob),
                    "{knob:?} on {integrator}{materials}: {acts:?}"
                );
                if let Err(e) = acts {
                    assert!(e
                        .to_string()
                        .starts_with(&format!("--knob {} ", knob.name())));
                }
            }
        }
        for (spp, acts) in [(1, false), (2, true), (4, true), (16, true)] {
            let mut s = scene("m: { kd: 1 }", "");
            s.spp = spp;
            assert_eq!(AaThreshold.acts_on(&s).is_ok(), acts, "spp {spp}");
        }
    }

    /// One run is timed as it is; three are timed after a fourth, untimed.
    #[test]
    fn timed_runs_once_or_warms_up_first() {
        for (runs, calls) in [(1, 1), (3, 4), (5, 6)] {
            let mut n = 0;
            let (last, _) = timed(runs, || {
                n += 1;
                n
            });
            assert_eq!((n, last), (calls, calls), "{runs} runs");
        }
    }

    /// Rounded to f32, 0.1 becomes the f32 nearest it (0.100000001490116…), which an EXR of
    /// the image holds; kept in full, it stays 0.1.
    #[test]
    fn a_render_is_rounded_as_its_reference_keeps_it() {
        let image = Image {
            width: 1,
            height: 1,
            pixels: vec![glam::DVec3::new(0.1, 0.5, 3.0)],
        };
        let f32 = Precision::F32.round(&image).pixels[0];
        assert_eq!(f32.x, 0.100_000_001_490_116_12);
        assert_eq!((f32.y, f32.z), (0.5, 3.0));
        assert_eq!(Precision::Full.round(&image).pixels[0].x, 0.1);
    }

    /// Rounded as a PNG keeps it: clamped to [0, 1], then to the nearest of the 256 sRGB
    /// levels. 0.5 encodes as 1.055·0.5^(1/2.4) − 0.055 = 0.7354, level 188 (187.5 rounds up),
    /// which decodes to ((188/255 + 0.055)/1.055)^2.4 = 0.5029; 3.0 becomes 1 and −0.2 becomes 0.
    #[test]
    fn a_render_measured_against_a_png_is_rounded_to_its_8_bits() {
        let image = Image {
            width: 1,
            height: 1,
            pixels: vec![glam::DVec3::new(0.5, 3.0, -0.2)],
        };
        let p = Precision::Srgb8.round(&image).pixels[0];
        let level = ((188.0 / 255.0 + 0.055) / 1.055f64).powf(2.4);
        assert!((p.x - level).abs() < 1e-15, "{}", p.x);
        assert!((p.x - 0.5029).abs() < 5e-5, "{}", p.x);
        assert_eq!((p.y, p.z), (1.0, 0.0));
    }

    /// The table's columns line up under their headers whatever the knob's name, and an exact
    /// row's PSNR reads ∞ (20·log10(1/0)), not a large number.
    #[test]
    fn the_table_lines_up_and_an_exact_rows_psnr_is_infinite() {
        let row = |value: f64, rmse: f64| SweepRow {
            value,
            seconds: 0.5,
            rays: 1000,
            rmse,
            rel_mse: rmse * rmse,
            max_abs: rmse,
            psnr: -20.0 * rmse.log10(),
        };
        let rows = [row(0.1, 0.01), row(0.0, 0.0)];
        assert_eq!(rows[0].psnr, 40.0);
        assert_eq!(rows[1].psnr, f64::INFINITY);
        for knob in [Knob::Spp, Knob::AaThreshold] {
            let table = sweep_table(knob, &rows);
            let lines: Vec<&str> = table.lines().collect();
            // Each column ends where its header ends.
            let ends = |line: &str| -> Vec<usize> {
                let chars: Vec<char> = line.chars().collect();
                (0..chars.len())
                    .filter(|&i| chars[i] != ' ' && chars.get(i + 1).is_none_or(|c| *c == ' '))
                    .collect()
            };
            // Two headers are two words ("rel MSE", "max |err|"): every end of a row's eight
            // fields is one of the header's ends.
            let header = ends(lines[0]);
            for line in &lines[1..] {
                let row = ends(line);
                assert_eq!(row.len(), 8, "{table}");
                assert!(
                    row.iter().all(|e| header.contains(e)),
                    "{}:\n{table}",
                    knob.name()
                );
            }
            let psnr: Vec<&str> = lines[1..]
                .iter()
                .map(|l| l.split_whitespace().nth(6).unwrap())
                .collect();
            assert_eq!(psnr, ["40.00", "∞"], "{table}");
        }
    }

    /// The median of hand-picked times: the middle one, whatever the order.
    #[test]
    fn the_median_is_the_middle_time() {
        assert_eq!(median(vec![0.9, 0.2, 0.4]), 0.4);
        assert_eq!(median(vec![3.0]), 3.0);
        assert_eq!(median(vec![5.0, 1.0, 2.0, 4.0, 3.0]), 3.0);
    }
}
