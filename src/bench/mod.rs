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

#[cfg(all(test, feature = "cli"))]
mod tests {
    use super::Knob;
    use clap::ValueEnum;

    /// Table headers and error messages name each knob as `--knob` spells it.
    #[test]
    fn knob_names_are_the_command_line_values() {
        for k in Knob::value_variants() {
            let flag = k.to_possible_value().unwrap();
            assert_eq!(k.name(), flag.get_name());
        }
    }
}
