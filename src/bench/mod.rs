//! `raytree bench`: measured sweeps, one module each.

mod error;
mod plot;
mod scaling;
mod sweep;
mod threads;

pub use error::BenchError;
pub use plot::{log_ticks, sweep_plot_svg, tick_label};
pub use scaling::{measure, mesh, spheres, table, table_header, table_row, Row};
pub use sweep::{
    errors, reference_for, sweep, sweep_csv, sweep_table, Knob, Precision, Reference, SweepRow,
};
pub use threads::{thread_rounds, threads_table, ThreadRounds, ThreadRun};

/// A time in seconds for a table: three decimals, and more for a time under 0.1 s, so that it
/// keeps three significant digits (a render of 0.2 ms reads 0.000200, not 0.000).
pub fn seconds(s: f64) -> String {
    let decimals = if s > 0.0 && s.is_finite() {
        (2 - s.log10().floor() as i32).clamp(3, 9) as usize
    } else {
        3
    };
    format!("{s:.decimals$}")
}

#[cfg(all(test, feature = "cli"))]
mod tests {
    use super::{seconds, Knob};
    use clap::ValueEnum;

    /// Times keep three significant digits however short, and three decimals from 0.1 s up.
    #[test]
    fn seconds_keep_three_significant_digits() {
        assert_eq!(seconds(12.34567), "12.346");
        assert_eq!(seconds(0.123456), "0.123");
        assert_eq!(seconds(0.0123456), "0.0123");
        assert_eq!(seconds(0.000_123_456), "0.000123");
        assert_eq!(seconds(0.0), "0.000");
    }

    /// Table headers and error messages name each knob as `--knob` spells it.
    #[test]
    fn knob_names_are_the_command_line_values() {
        for k in Knob::value_variants() {
            let flag = k.to_possible_value().unwrap();
            assert_eq!(k.name(), flag.get_name());
        }
    }
}
