//! `raytree bench`: measured sweeps.

use std::process::ExitCode;

use super::Failure;
use crate::bench::{measure, mesh, spheres, table};

#[derive(clap::Args, Debug)]
pub struct Args {
    #[command(subcommand)]
    sweep: Sweep,
}

#[derive(clap::Subcommand, Debug)]
enum Sweep {
    /// Time per ray against the number of spheres (10 … 100 000) and mesh triangles
    /// (≈10³ … 10⁶), with and without the BVH, on one thread.
    Scaling {
        /// Largest N to test without the BVH (brute force is O(N) per ray).
        #[arg(long, default_value_t = 100_000)]
        max_brute: usize,
        /// Largest icosphere subdivision level (20·4^k triangles; 8 is 1.3 million).
        #[arg(long, default_value_t = 8)]
        max_subdivisions: u32,
    },
}

pub fn run(a: Args) -> Result<ExitCode, Failure> {
    match a.sweep {
        Sweep::Scaling {
            max_brute,
            max_subdivisions,
        } => {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
            let mut rows = vec![];
            pool.install(|| -> Result<(), Failure> {
                for n in [10, 100, 1_000, 10_000, 100_000] {
                    rows.push(measure("spheres", n, &spheres(n), n <= max_brute)?);
                    eprint!(
                        "{}",
                        table(&rows[rows.len() - 1..])
                            .lines()
                            .nth(1)
                            .unwrap_or("")
                            .to_string()
                            + "\n"
                    );
                }
                for k in 3..=max_subdivisions {
                    let n = 20 * 4usize.pow(k);
                    rows.push(measure("mesh", n, &mesh(k), n <= max_brute.min(25_000))?);
                    eprint!(
                        "{}",
                        table(&rows[rows.len() - 1..])
                            .lines()
                            .nth(1)
                            .unwrap_or("")
                            .to_string()
                            + "\n"
                    );
                }
                Ok(())
            })?;
            print!("{}", table(&rows));
        }
    }
    Ok(ExitCode::SUCCESS)
}
