//! `raytree bench`: measured sweeps, one module each.

mod scaling;
mod sweep;
mod threads;

pub use scaling::{measure, mesh, spheres, table, table_header, table_row, Row};
pub use sweep::{errors, reference_for, sweep, sweep_csv, sweep_plot, sweep_table, Knob, SweepRow};
pub use threads::{thread_rounds, threads_table, ThreadRun};
