//! The sweep's plot: RMSE against seconds on log-log axes, drawn by `plotters` as SVG (the PNG
//! is the same SVG rasterised by the command line).

use plotters::coord::combinators::BindKeyPoints;
use plotters::prelude::*;

use super::error::BenchError;
use super::sweep::{Knob, SweepRow};

/// The plot's size in pixels.
pub const WIDTH: u32 = 800;
pub const HEIGHT: u32 = 560;

/// Ticks for a log axis over `[lo, hi]` (both positive): the powers of ten when the range holds
/// at least two, else 1-2-5 of each decade, else every whole mantissa 1…9, else evenly spaced
/// round numbers; so a range shorter than a decade is numbered too.
pub fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let (lo, hi) = (lo.min(hi), lo.max(hi));
    if !(lo > 0.0 && hi.is_finite()) {
        return vec![];
    }
    let within = |mantissas: &[f64]| -> Vec<f64> {
        let mut out = vec![];
        for e in (lo.log10().floor() as i32 - 1)..=(hi.log10().ceil() as i32) {
            for &m in mantissas {
                let v = round_sig(m * 10f64.powi(e));
                if v >= lo && v <= hi {
                    out.push(v);
                }
            }
        }
        out
    };
    for mantissas in [
        &[1.0][..],
        &[1.0, 2.0, 5.0],
        &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0],
    ] {
        let ticks = within(mantissas);
        if ticks.len() >= 2 {
            return ticks;
        }
    }
    linear_ticks(lo, hi)
}

/// Three to six round numbers in `[lo, hi]`, a step of 1, 2 or 5 times a power of ten apart.
fn linear_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let span = hi - lo;
    if span <= 0.0 {
        return vec![round_sig(lo)];
    }
    let raw = span / 4.0;
    let decade = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|&s| span / s <= 5.0)
        .unwrap_or(10.0 * decade);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|k| round_sig(k as f64 * step)).collect()
}

/// `v` rounded to 12 significant digits: 3 × 0.1 becomes 0.3, as a label shows it.
fn round_sig(v: f64) -> f64 {
    if v == 0.0 || !v.is_finite() {
        return v;
    }
    format!("{v:.11e}").parse().unwrap_or(v)
}

/// A tick's label: plain decimals from 0.001 to 10 000 (`0.02`, `150`), else powers of ten
/// written `2e-5`; at most four significant digits, no trailing zeros.
pub fn tick_label(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        return "0".into();
    }
    if (1e-3..1e4).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{v:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        let s = format!("{v:.3e}");
        let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
        let m = m.trim_end_matches('0').trim_end_matches('.');
        format!("{m}e{e}")
    }
}

/// `[lo, hi]` widened on a log scale so that the points sit inside the frame.
fn padded(values: impl Iterator<Item = f64> + Clone) -> (f64, f64) {
    let lo = values.clone().fold(f64::INFINITY, f64::min);
    let hi = values.fold(0.0, f64::max);
    let pad = (hi / lo).powf(0.08).max(1.15);
    (lo / pad, hi * pad)
}

/// The slope −½ line's dashes and the gaps between them, in pixels.
const DASH: i32 = 8;
const GAP: i32 = 6;

/// The sweep as an SVG plot: RMSE against seconds on log-log axes numbered even within a
/// decade, one point per row labelled with the knob's value and joined in order, a dashed line
/// of slope −½ (error ∝ 1/√time, Monte Carlo's rate) through the first point, axis titles and
/// a legend. Rows without a positive time and error cannot sit on log axes and are left out;
/// if none is left the plot says so.
pub fn sweep_plot_svg(knob: Knob, rows: &[SweepRow]) -> Result<String, BenchError> {
    let mut svg = String::new();
    draw(knob, rows, &mut svg).map_err(|e| BenchError::Plot(e.to_string()))?;
    Ok(svg)
}

fn draw(knob: Knob, rows: &[SweepRow], svg: &mut String) -> Result<(), Box<dyn std::error::Error>> {
    let root = SVGBackend::with_string(svg, (WIDTH, HEIGHT)).into_drawing_area();
    root.fill(&WHITE)?;
    let name = knob.name();
    let pts: Vec<(f64, f64, f64)> = rows
        .iter()
        .filter(|r| r.seconds > 0.0 && r.rmse > 0.0 && r.seconds.is_finite() && r.rmse.is_finite())
        .map(|r| (r.seconds, r.rmse, r.value))
        .collect();
    let caption = format!("RMSE against run time, bench sweep --knob {name}");
    if pts.is_empty() {
        root.titled(&caption, ("sans-serif", 22))?.draw(&Text::new(
            "no row has a positive time and error (every image equals the reference?)",
            (40, (HEIGHT / 2) as i32),
            ("sans-serif", 18),
        ))?;
        root.present()?;
        return Ok(());
    }
    let (x0, x1) = padded(pts.iter().map(|p| p.0));
    let (y0, y1) = padded(pts.iter().map(|p| p.1));
    let mut chart = ChartBuilder::on(&root)
        .caption(&caption, ("sans-serif", 22))
        .margin(16)
        .x_label_area_size(50)
        .y_label_area_size(80)
        .build_cartesian_2d(
            (x0..x1).log_scale().with_key_points(log_ticks(x0, x1)),
            (y0..y1).log_scale().with_key_points(log_ticks(y0, y1)),
        )?;
    chart
        .configure_mesh()
        .x_desc("seconds (log scale)")
        .y_desc("RMSE (log scale)")
        .x_label_formatter(&|v| tick_label(*v))
        .y_label_formatter(&|v| tick_label(*v))
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17))
        .bold_line_style(RGBColor(225, 225, 225))
        .draw()?;

    // Slope −½ on log-log axes: rmse = rmse₀·(t/t₀)^−½, drawn across the frame.
    let (t0, e0, _) = pts[0];
    let guide = |t: f64| e0 * (t / t0).powf(-0.5);
    let grey = RGBColor(130, 130, 130);
    chart
        .draw_series(DashedLineSeries::new(
            (0..=40).map(|k| {
                let t = (x0.ln() + (x1 / x0).ln() * k as f64 / 40.0).exp();
                (t, guide(t))
            }),
            DASH,
            GAP,
            grey.stroke_width(2),
        ))?
        .label("slope -1/2 (error ∝ 1/√time)")
        // The legend's sample: two dashes of the line it stands for.
        .legend(move |(x, y)| {
            EmptyElement::at((x, y))
                + PathElement::new(vec![(0, 0), (DASH, 0)], grey.stroke_width(2))
                + PathElement::new(
                    vec![(DASH + GAP, 0), (2 * DASH + GAP, 0)],
                    grey.stroke_width(2),
                )
        });

    let blue = RGBColor(30, 80, 220);
    chart
        .draw_series(LineSeries::new(
            pts.iter().map(|&(t, e, _)| (t, e)),
            blue.stroke_width(2),
        ))?
        .label(format!("RMSE at each --knob {name} value"))
        .legend(move |(x, y)| {
            EmptyElement::at((x + 12, y))
                + PathElement::new(vec![(-12, 0), (12, 0)], blue.stroke_width(2))
                + Circle::new((0, 0), 4, blue.filled())
        });
    chart.draw_series(pts.iter().map(|&(t, e, v)| {
        EmptyElement::at((t, e))
            + Circle::new((0, 0), 4, blue.filled())
            + Text::new(format!("{name} {v}"), (7, -18), ("sans-serif", 14))
    }))?;
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .label_font(("sans-serif", 15))
        .draw()?;
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{log_ticks, sweep_plot_svg, tick_label};
    use crate::bench::{Knob, SweepRow};

    fn row(value: f64, seconds: f64, rmse: f64) -> SweepRow {
        SweepRow {
            value,
            seconds,
            rays: 0,
            rmse,
            rel_mse: 0.0,
            max_abs: 0.0,
            psnr: 0.0,
        }
    }

    /// The text of every `<text>` element of an SVG document, entities decoded.
    fn texts(svg: &str) -> Vec<String> {
        let doc = resvg::usvg::roxmltree::Document::parse(svg).expect("well-formed SVG");
        doc.descendants()
            .filter(|n| n.has_tag_name("text"))
            .map(|n| {
                let text: String = n.children().filter_map(|d| d.text()).collect();
                text.trim().to_string()
            })
            .collect()
    }

    #[test]
    fn a_sweep_within_a_decade_has_numbered_axes_labels_and_a_legend() {
        // 0.2 … 0.6 s and RMSE 0.03 … 0.08: neither spans a decade.
        let rows = [
            row(0.0, 0.6, 0.03),
            row(0.01, 0.35, 0.05),
            row(0.1, 0.2, 0.08),
        ];
        let svg = sweep_plot_svg(Knob::Adaptive, &rows).unwrap();
        let t = texts(&svg);
        let has = |s: &str| t.iter().any(|x| x == s);
        // Padded by the factor 1.15, the axes cover 0.174 … 0.69 s and 0.026 … 0.092: ticks
        // at 0.2 and 0.5 (1-2-5), and at 0.03 … 0.09 (every mantissa).
        for tick in ["0.2", "0.5", "0.03", "0.05", "0.09"] {
            assert!(has(tick), "tick {tick} in {t:?}");
        }
        assert!(has("seconds (log scale)"), "{t:?}");
        assert!(has("RMSE (log scale)"), "{t:?}");
        assert!(has("RMSE at each --knob adaptive value"), "{t:?}");
        assert!(has("slope -1/2 (error ∝ 1/√time)"), "{t:?}");
        for point in ["adaptive 0", "adaptive 0.01", "adaptive 0.1"] {
            assert!(has(point), "point label {point} in {t:?}");
        }
    }

    /// The slope −½ line is dashed in the plot and in its legend alike: every grey stroke is
    /// one dash, and the legend's sample (the horizontal ones) has more than one.
    #[test]
    fn the_legend_draws_the_slope_line_dashed_as_the_plot_does() {
        let rows = [
            row(1.0, 0.01, 0.2),
            row(4.0, 0.04, 0.1),
            row(16.0, 0.16, 0.05),
        ];
        let svg = sweep_plot_svg(Knob::Spp, &rows).unwrap();
        let doc = resvg::usvg::roxmltree::Document::parse(&svg).expect("well-formed SVG");
        let strokes: Vec<Vec<(f64, f64)>> = doc
            .descendants()
            .filter(|n| n.has_tag_name("polyline") && n.attribute("stroke") == Some("#828282"))
            .map(|n| {
                let points = n.attribute("points").unwrap_or("");
                points
                    .split_whitespace()
                    .map(|p| {
                        let (x, y) = p.split_once(',').unwrap();
                        (x.parse().unwrap(), y.parse().unwrap())
                    })
                    .collect()
            })
            .collect();
        assert!(strokes.len() > 2, "{svg}");
        for stroke in &strokes {
            let length: f64 = stroke
                .windows(2)
                .map(|w| (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1))
                .sum();
            assert!(length <= 9.0, "a grey stroke of {length} px: {stroke:?}");
        }
        let level = |s: &&Vec<(f64, f64)>| s.iter().all(|p| p.1 == s[0].1);
        assert!(strokes.iter().filter(level).count() >= 2, "{strokes:?}");
    }

    #[test]
    fn a_sweep_without_error_says_so() {
        let svg = sweep_plot_svg(Knob::Spp, &[row(1.0, 0.5, 0.0)]).unwrap();
        assert!(texts(&svg)
            .iter()
            .any(|x| x.contains("no row has a positive time")));
    }

    #[test]
    fn decades_when_the_range_spans_two() {
        assert_eq!(log_ticks(0.005, 2.0), vec![0.01, 0.1, 1.0]);
    }

    #[test]
    fn one_two_five_within_a_decade_and_a_bit() {
        // 0.15 … 0.9: no power of ten inside, 0.2 and 0.5 are.
        assert_eq!(log_ticks(0.15, 0.9), vec![0.2, 0.5]);
    }

    #[test]
    fn every_mantissa_in_a_narrow_range() {
        assert_eq!(log_ticks(0.25, 0.45), vec![0.3, 0.4]);
    }

    #[test]
    fn round_steps_in_a_very_narrow_range() {
        // 1.21 … 1.29: span 0.08, a quarter of it 0.02 → step 0.02.
        assert_eq!(log_ticks(1.21, 1.29), vec![1.22, 1.24, 1.26, 1.28]);
    }

    #[test]
    fn labels_are_short() {
        assert_eq!(tick_label(0.02), "0.02");
        assert_eq!(tick_label(150.0), "150");
        assert_eq!(tick_label(1.0), "1");
        assert_eq!(tick_label(0.001), "0.001");
        assert_eq!(tick_label(2e-5), "2e-5");
        assert_eq!(tick_label(1e5), "1e5");
        assert_eq!(tick_label(1.25), "1.25");
    }
}
