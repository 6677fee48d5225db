//! `raytree bench`: measured sweeps, one module each.

mod plot;
mod scaling;
mod sweep;
mod threads;

pub use plot::{log_ticks, sweep_plot_svg, tick_label};
pub use scaling::{measure, mesh, spheres, table, table_header, table_row, Row};
pub use sweep::{errors, reference_for, sweep, sweep_csv, sweep_table, Knob, SweepRow};
pub use threads::{thread_rounds, threads_table, ThreadRun};
