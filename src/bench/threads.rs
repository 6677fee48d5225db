//! The thread-scaling measurement: a scene rendered on one thread and on N, alternately, beside
//! a control job of pure arithmetic split the same way over the same thread pool.
//!
//! The control touches no memory and shares nothing between threads, so its speed-up is the
//! most this machine gives N threads at that moment: less than N where two "cores" are the
//! hyper-threads of one physical core or the host is busy. The renderer's speed-up is judged
//! against it, in the same run, so that a shortfall can be told apart from the machine's own.

use std::hint::black_box;
use std::time::Instant;

use crate::render::{render_simple, RenderOptions};
use crate::scene::Scene;

/// One alternating round: the scene and the control, each on one thread and on N.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThreadRun {
    /// Seconds to render the scene on one thread.
    pub render_one: f64,
    /// Seconds to render the scene on N threads.
    pub render_many: f64,
    /// Seconds for the control job on one thread.
    pub control_one: f64,
    /// Seconds for the control job on N threads.
    pub control_many: f64,
}

/// Sixty-four independent chains of multiply-adds: more independent operations than the
/// floating-point units can start each cycle, so the units set the pace, not the chains'
/// latency, with nothing read from or written to memory. Two hyper-threads of one core would
/// share those units and speed this up by little more than 1×; two cores give 2×.
fn arithmetic(iterations: u64, seed: f64) -> f64 {
    let mut chains: [f64; 64] = std::array::from_fn(|k| 1.0 + k as f64 * 1e-3 + seed);
    for _ in 0..black_box(iterations) {
        for x in &mut chains {
            *x = *x * 0.999_999_9 + 1e-7;
        }
    }
    black_box(chains).iter().sum()
}

/// Seconds for `iterations` of the control job, shared evenly by the threads of `pool`.
fn control(pool: &rayon::ThreadPool, iterations: u64) -> f64 {
    let share = iterations / pool.current_num_threads() as u64;
    let start = Instant::now();
    let sums = pool.broadcast(|ctx| arithmetic(share, ctx.index() as f64));
    black_box(sums);
    start.elapsed().as_secs_f64()
}

/// Seconds per render of the scene (loading excluded) on the threads of `pool`, rendered
/// `repeats` times over, and its rays.
fn render(pool: &rayon::ThreadPool, scene: &Scene, repeats: u32) -> (f64, u64) {
    let start = Instant::now();
    let mut rays = 0;
    for _ in 0..repeats {
        let (_, stats) = pool.install(|| render_simple(scene, RenderOptions::of(scene)));
        rays = stats.rays();
    }
    (start.elapsed().as_secs_f64() / repeats as f64, rays)
}

/// How long one measurement lasts at least: a render of a few milliseconds measures little
/// more than waking the pool's threads and the timer's own jitter, so a small scene is rendered
/// again and again for that long.
const MEASURED_SECONDS: f64 = 0.2;

/// The threads' rounds of a scene.
pub struct ThreadRounds {
    /// The rounds, in the order they ran.
    pub runs: Vec<ThreadRun>,
    /// The scene's rays (one render).
    pub rays: u64,
    /// Renders per measurement (each figure is their mean).
    pub repeats: u32,
}

/// `runs` rounds of: the scene on one thread, on `n`, then the control job on one and on `n`.
/// Each figure is the mean over `repeats` renders (or the control's share of that), enough to
/// last `MEASURED_SECONDS` on one thread. The control is sized to take about as long as a
/// one-thread render, so both meet the machine in the same state.
pub fn thread_rounds(
    scene: &Scene,
    n: usize,
    runs: usize,
) -> Result<ThreadRounds, rayon::ThreadPoolBuildError> {
    let one = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let many = rayon::ThreadPoolBuilder::new().num_threads(n).build()?;
    // Warm-up (caches, page faults, the pools' threads), and the size of the measurements.
    let (seconds, rays) = render(&one, scene, 1);
    let repeats = (MEASURED_SECONDS / seconds.max(1e-6))
        .ceil()
        .clamp(1.0, 10_000.0) as u32;
    let probe = 1 << 22;
    let rate = probe as f64 / control(&one, probe).max(1e-9);
    let iterations = ((rate * seconds * repeats as f64) as u64).max(n as u64);
    let per_render = |s: f64| s / repeats as f64;
    let runs = (0..runs)
        .map(|_| ThreadRun {
            render_one: render(&one, scene, repeats).0,
            render_many: render(&many, scene, repeats).0,
            control_one: per_render(control(&one, iterations)),
            control_many: per_render(control(&many, iterations)),
        })
        .collect();
    Ok(ThreadRounds {
        runs,
        rays,
        repeats,
    })
}

/// The middle value (the mean of the two middle ones for an even count).
fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    match n {
        0 => f64::NAN,
        _ if n % 2 == 1 => values[n / 2],
        _ => (values[n / 2 - 1] + values[n / 2]) / 2.0,
    }
}

/// The table of medians: seconds on one thread and on N, and the speed-up (median of the
/// rounds' own ratios, with their range) for the scene and the control, then the scene's
/// speed-up as a share of the control's.
pub fn threads_table(rounds: &ThreadRounds, threads: usize) -> String {
    let (runs, rays) = (&rounds.runs, rounds.rays);
    let speedups = |f: fn(&ThreadRun) -> (f64, f64)| {
        let ratios: Vec<f64> = runs
            .iter()
            .map(|r| {
                let (one, many) = f(r);
                one / many
            })
            .collect();
        let lo = ratios.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = ratios.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        (median(ratios), lo, hi)
    };
    let render = speedups(|r| (r.render_one, r.render_many));
    let control = speedups(|r| (r.control_one, r.control_many));
    let seconds = |f: fn(&ThreadRun) -> f64| median(runs.iter().map(f).collect());
    let (r1, rn) = (seconds(|r| r.render_one), seconds(|r| r.render_many));
    let (c1, cn) = (seconds(|r| r.control_one), seconds(|r| r.control_many));
    let mrays = |s: f64| rays as f64 / s / 1e6;
    let many = format!("{threads} threads s");
    let mut s = format!(
        "{:<11} {:>12} {:>12} {:>24}\n",
        "", "1 thread s", many, "speed-up (median, range)"
    );
    for (name, one, n, (mid, lo, hi)) in
        [("scene", r1, rn, render), ("arithmetic", c1, cn, control)]
    {
        let range = format!("{mid:.2}× ({lo:.2}–{hi:.2})");
        let (one, n) = (super::seconds(one), super::seconds(n));
        s.push_str(&format!("{name:<11} {one:>12} {n:>12} {range:>24}\n"));
    }
    let each = match rounds.repeats {
        1 => String::new(),
        k => format!(", each the mean of {k} renders"),
    };
    let runs = match runs.len() {
        1 => "one run".to_string(),
        n => format!("{n} runs, medians"),
    };
    s.push_str(&format!(
        "rays per second: {:.1} M on 1 thread, {:.1} M on {threads} ({runs}{each})\n",
        mrays(r1),
        mrays(rn),
    ));
    s.push_str(&format!(
        "the scene's speed-up is {:.0} % of the arithmetic's, the most this machine gave\n",
        100.0 * render.0 / control.0
    ));
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn medians_of_odd_and_even_counts() {
        assert_eq!(median(vec![3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(vec![4.0, 1.0, 3.0, 2.0]), 2.5);
        assert!(median(vec![]).is_nan());
    }

    /// Three rounds worked by hand. Scene ratios 2.0/1.0 = 2, 2.2/1.25 = 1.76, 1.8/1.0 = 1.8:
    /// median 1.80, range 1.76–2.00. Control ratios 1.9, 2.0, 1.6: median 1.90, range
    /// 1.60–2.00. 1.80 / 1.90 = 94.7 %. Median seconds: scene 2.0 and 1.0, control 1.9 and 1.0;
    /// 40 M rays in 2.0 s and 1.0 s are 20 and 40 M rays per second.
    #[test]
    fn the_table_reports_medians_of_each_rounds_ratio() {
        let run = |render_one, render_many, control_one, control_many| ThreadRun {
            render_one,
            render_many,
            control_one,
            control_many,
        };
        let rounds = ThreadRounds {
            runs: vec![
                run(2.0, 1.0, 1.9, 1.0),
                run(2.2, 1.25, 2.0, 1.0),
                run(1.8, 1.0, 1.6, 1.0),
            ],
            rays: 40_000_000,
            repeats: 1,
        };
        let table = threads_table(&rounds, 2);
        let lines: Vec<&str> = table.lines().collect();
        assert!(lines[1].starts_with("scene"), "{table}");
        assert!(lines[1].contains("2.000"), "{table}");
        assert!(lines[1].contains("1.000"), "{table}");
        assert!(lines[1].ends_with("1.80× (1.76–2.00)"), "{table}");
        assert!(lines[2].contains("1.900"), "{table}");
        assert!(lines[2].ends_with("1.90× (1.60–2.00)"), "{table}");
        assert!(
            lines[3].contains("20.0 M on 1 thread, 40.0 M on 2"),
            "{table}"
        );
        assert!(lines[4].contains("is 95 % of"), "{table}");
        // Measurements of several renders say so; the figures are per render all the same.
        let table = threads_table(
            &ThreadRounds {
                repeats: 40,
                ..rounds
            },
            2,
        );
        assert!(
            table.contains(
                "20.0 M on 1 thread, 40.0 M on 2 (3 runs, medians, each the mean of 40 renders)"
            ),
            "{table}"
        );
    }

    /// The control job computes what its chains say, split over the threads: each thread's
    /// share starts from its own seed, so the sums differ by thread and never fold away.
    #[test]
    fn the_control_job_runs_every_iteration() {
        // After one step each chain is x·0.9999999 + 1e−7; with x = 1 + k·1e−3 + seed.
        let expected: f64 = (0..64)
            .map(|k| (1.0 + k as f64 * 1e-3) * 0.999_999_9 + 1e-7)
            .sum();
        assert_eq!(arithmetic(1, 0.0), expected);
        let start: f64 = (0..64).map(|k| 1.0 + k as f64 * 1e-3).sum();
        assert_eq!(arithmetic(0, 0.0), start);
        assert_ne!(arithmetic(10, 0.0), arithmetic(10, 1.0));
    }
}
