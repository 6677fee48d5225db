//! The run-time-against-error sweep: one knob turned, each image measured against a reference.

use std::time::Instant;

use crate::render::{render_simple, RenderOptions};
use crate::scene::Antialias;
use crate::scene::Scene;

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
    pub fn check(self, value: f64) -> Result<(), String> {
        let limits = crate::scene::Limits::default();
        let whole = |lo: u32, hi: u32, what: &str| {
            if value.fract() == 0.0 && value >= lo as f64 && value <= hi as f64 {
                Ok(())
            } else {
                Err(format!(
                    "--knob {}: {value} is not a whole number between {lo} and {hi} ({what})",
                    self.name()
                ))
            }
        };
        let within = |lo: f64, hi: f64, what: &str| {
            if (lo..=hi).contains(&value) {
                Ok(())
            } else {
                Err(format!(
                    "--knob {}: {value} is not between {lo} and {hi} ({what})",
                    self.name()
                ))
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

/// One setting of the knob: its cost and its error against the reference.
#[derive(Clone, Debug)]
pub struct SweepRow {
    pub value: f64,
    pub seconds: f64,
    pub rays: u64,
    pub rmse: f64,
    /// Mean of ((x − ref)/(ref + 0.01))²: error relative to brightness.
    pub rel_mse: f64,
    pub max_abs: f64,
    /// 20·log10(1/RMSE) for intensities in [0, 1].
    pub psnr: f64,
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

/// Renders at every value of the knob and measures time and error against `reference`.
pub fn sweep(
    scene: &Scene,
    knob: Knob,
    values: &[f64],
    reference: &crate::render::Image,
    seed: u64,
    clamp: bool,
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
    let reference = &display(reference);
    values
        .iter()
        .map(|&value| {
            let (s, o) = options_for(scene, knob, value, seed);
            let start = Instant::now();
            let (image, stats) = render_simple(&s, o);
            let seconds = start.elapsed().as_secs_f64();
            let (rmse, rel_mse, max_abs) = errors(&display(&image), reference);
            SweepRow {
                value,
                seconds,
                rays: stats.rays(),
                rmse,
                rel_mse,
                max_abs,
                psnr: -20.0 * rmse.max(1e-300).log10(),
            }
        })
        .collect()
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
    if r.rmse == 0.0 {
        "exact".into()
    } else {
        format!("{:.0}", 1.0 / (r.seconds * r.rmse * r.rmse))
    }
}

pub fn sweep_table(knob: Knob, rows: &[SweepRow]) -> String {
    let mut s = format!(
        "{:>10} {:>10} {:>14} {:>11} {:>11} {:>10} {:>8} {:>14}\n",
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
            "{:>10} {:>10.3} {:>14} {:>11.5} {:>11.5} {:>10.4} {:>8.2} {:>14}\n",
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

pub fn sweep_csv(knob: Knob, rows: &[SweepRow]) -> String {
    let mut s = format!("{},seconds,rays,rmse,rel_mse,max_abs,psnr\n", knob.name());
    for r in rows {
        s.push_str(&format!(
            "{},{},{},{},{},{},{}\n",
            r.value, r.seconds, r.rays, r.rmse, r.rel_mse, r.max_abs, r.psnr
        ));
    }
    s
}

/// A log-log plot of RMSE against seconds: white background, axes numbered by decade, one dot
/// per row labelled with the knob's value and joined by lines, and a dashed line of slope −½
/// (error ∝ 1/√time) through the first point.
pub fn sweep_plot(knob: Knob, rows: &[SweepRow]) -> crate::render::Image {
    use crate::plot_font::{decade, pixels, width};
    use glam::DVec3;
    let (w, h, m) = (640u32, 480u32, 50.0);
    let mut img = crate::render::Image::new(w, h);
    img.pixels.iter_mut().for_each(|p| *p = DVec3::ONE);
    let pts: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.seconds > 0.0 && r.rmse > 0.0)
        .map(|r| (r.seconds.log10(), r.rmse.log10()))
        .collect();
    if pts.is_empty() {
        return img;
    }
    let (x0, x1) = pts
        .iter()
        .fold((f64::MAX, f64::MIN), |a, p| (a.0.min(p.0), a.1.max(p.0)));
    let (y0, y1) = pts
        .iter()
        .fold((f64::MAX, f64::MIN), |a, p| (a.0.min(p.1), a.1.max(p.1)));
    let (x0, x1, y0, y1) = (x0 - 0.2, x1 + 0.2, y0 - 0.2, y1 + 0.2);
    let to_px = |x: f64, y: f64| {
        let px = m + (x - x0) / (x1 - x0) * (w as f64 - 2.0 * m);
        let py = h as f64 - m - (y - y0) / (y1 - y0) * (h as f64 - 2.0 * m);
        (px, py)
    };
    let mut put = |x: f64, y: f64, c: DVec3| {
        if x >= 0.0 && y >= 0.0 && (x as u32) < w && (y as u32) < h {
            img.pixels[(y as u32 * w + x as u32) as usize] = c;
        }
    };
    let line = |a: (f64, f64),
                b: (f64, f64),
                c: DVec3,
                dashed: bool,
                put: &mut dyn FnMut(f64, f64, DVec3)| {
        let steps = ((b.0 - a.0).abs().max((b.1 - a.1).abs()) as usize).max(1);
        for k in 0..=steps {
            if dashed && (k / 6) % 2 == 1 {
                continue;
            }
            let t = k as f64 / steps as f64;
            put(a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1), c);
        }
    };
    let black = DVec3::ZERO;
    line(to_px(x0, y0), to_px(x1, y0), black, false, &mut put);
    line(to_px(x0, y0), to_px(x0, y1), black, false, &mut put);
    let text = |t: &str, x: f64, y: f64, c: DVec3, put: &mut dyn FnMut(f64, f64, DVec3)| {
        for (px, py) in pixels(t, x, y, 2.0) {
            put(px, py, c);
        }
    };
    // Decade ticks on both axes, numbered.
    for d in (x0.ceil() as i32)..=(x1.floor() as i32) {
        let (px, py) = to_px(d as f64, y0);
        line((px, py), (px, py - 8.0), black, false, &mut put);
        let label = decade(d);
        text(
            &label,
            px - width(&label, 2.0) / 2.0,
            py + 6.0,
            black,
            &mut put,
        );
    }
    for d in (y0.ceil() as i32)..=(y1.floor() as i32) {
        let (px, py) = to_px(x0, d as f64);
        line((px, py), (px + 8.0, py), black, false, &mut put);
        let label = decade(d);
        text(
            &label,
            px - width(&label, 2.0) - 4.0,
            py - 5.0,
            black,
            &mut put,
        );
    }
    let title = "SECONDS";
    text(
        title,
        (w as f64 - width(title, 2.0)) / 2.0,
        h as f64 - m + 22.0,
        black,
        &mut put,
    );
    text("RMSE", 8.0, 12.0, black, &mut put);
    let legend = format!("DOTS: {}   DASHED: SLOPE -1/2", knob.name().to_uppercase());
    text(
        &legend,
        w as f64 - width(&legend, 2.0) - 12.0,
        12.0,
        black,
        &mut put,
    );
    let grey = DVec3::splat(0.6);
    let first = pts[0];
    line(
        to_px(first.0, first.1),
        to_px(x1, first.1 - 0.5 * (x1 - first.0)),
        grey,
        true,
        &mut put,
    );
    let blue = DVec3::new(0.1, 0.3, 0.9);
    for pair in pts.windows(2) {
        line(
            to_px(pair[0].0, pair[0].1),
            to_px(pair[1].0, pair[1].1),
            blue,
            false,
            &mut put,
        );
    }
    for (p, r) in pts
        .iter()
        .zip(rows.iter().filter(|r| r.seconds > 0.0 && r.rmse > 0.0))
    {
        let (px, py) = to_px(p.0, p.1);
        text(
            &format!("{}", r.value),
            px + 7.0,
            py - 14.0,
            DVec3::new(0.8, 0.1, 0.1),
            &mut put,
        );
        for dy in -3..=3 {
            for dx in -3..=3 {
                put(px + dx as f64, py + dy as f64, DVec3::new(0.9, 0.1, 0.1));
            }
        }
    }
    img
}
