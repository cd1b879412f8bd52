//! The `tack` binary: run scenes and parameter sweeps, write and inspect HDF5 result files,
//! plot them.
//!
//! Exit status 0 on success; on any error a message `error: ...` naming the field or file goes
//! to stderr and the status is 1 (2 for command-line usage errors, from clap).

use std::num::NonZeroUsize;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::{Parser, Subcommand};
use tack::RunOptions;
use tack::engine;
use tack::problem::Problem;
use tack::provenance;
use tack::scene::Scene;
use tack_cli::plot;
use tack_cli::progress::{Progress, SweepProgress};
use tack_cli::report::{self, rounded};
use tack_sweep::{MergeOptions, Shard, Sweep, SweepOptions};

/// Adhesive strength of rough elastic contacts (Li, Pohrt & Popov 2019), by FFT-accelerated BEM.
///
/// A scene file (TOML, see docs/scenes.md) describes material, body, grid and approach path;
/// `tack run` solves it and writes an HDF5 result file readable by h5py and h5dump.
#[derive(Debug, Parser)]
#[command(name = "tack", version, propagate_version = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Run a scene: load, unload, write the result file and print a summary.
    Run {
        /// The scene file (TOML).
        scene: PathBuf,
        /// The result file to write (HDF5; written atomically: temporary file + rename).
        #[arg(short, long, value_name = "OUT.h5")]
        output: PathBuf,
        /// Do not draw the progress bar (it is drawn only on a terminal anyway).
        #[arg(short, long)]
        quiet: bool,
        /// Override a scene value before validation, e.g. `--set roughness.h=0.002`
        /// (value parsed as TOML, else taken as a string). Repeatable.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Also run on a grid of twice the element size and record the Richardson extrapolation
        /// of the pull-off force at the law's order (`/summary` `pull_off_force_richardson`,
        /// `richardson_order`): 2·F(Δx) − F(2Δx) for the criterion and the Dugdale law,
        /// F(Δx) + (F(Δx) − F(2Δx))/3 for the smooth laws;
        /// the body must be the same on both grids: random roughness needs an explicit
        /// `roughness.q1 ≤ π/(2Δx)`, a height map must be band-limited to π/(2Δx), and random
        /// roughness and periodic grids need even sides (docs/theory.md §9).
        #[arg(long)]
        richardson: bool,
        /// Threads for the solve (1 to 1024; default: all cores). The result is bit-identical
        /// for any count.
        #[arg(long, value_name = "N")]
        threads: Option<usize>,
    },
    /// Write only the generated surface (heights and dx) of a scene to an HDF5 file.
    Surface {
        /// The scene file (TOML).
        scene: PathBuf,
        /// The file to write (HDF5; `/surface/heights` with attribute `dx`).
        #[arg(short, long, value_name = "SURF.h5")]
        output: PathBuf,
        /// Override a scene value, as for `tack run`. Repeatable.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
    },
    /// Validate a scene without running it: print the grid, first touch and path.
    Check {
        /// The scene file (TOML).
        scene: PathBuf,
        /// Override a scene value, as for `tack run`. Repeatable.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
    },
    /// Describe a result file: provenance, curve, surface, snapshots, summary.
    Info {
        /// The result file (HDF5).
        file: PathBuf,
    },
    /// Run a parameter sweep (docs/sweeps.md): every point, or one shard of them, in parallel,
    /// one result file per point in DIR/points; a rerun skips completed points.
    Sweep {
        /// The sweep file (TOML).
        sweep: PathBuf,
        /// The output directory (created; a rerun must use the same sweep file).
        #[arg(short, long, value_name = "DIR")]
        output: PathBuf,
        /// Points to run at once (default: all cores). Results do not depend on it.
        #[arg(long, value_name = "N")]
        threads: Option<NonZeroUsize>,
        /// Run only shard I of N (1 ≤ I ≤ N, e.g. `--shard $SLURM_ARRAY_TASK_ID/8`): the points
        /// whose index i has i % N == I - 1.
        #[arg(long, value_name = "I/N")]
        shard: Option<Shard>,
        /// Do not draw the progress bar (it is drawn only on a terminal anyway).
        #[arg(short, long)]
        quiet: bool,
    },
    /// Merge a sweep directory into one HDF5 table: parameters, collected results, status.
    Merge {
        /// The sweep's output directory (as given to `tack sweep -o`).
        dir: PathBuf,
        /// The table to write (HDF5, atomically).
        #[arg(short, long, value_name = "SWEEP.h5")]
        output: PathBuf,
        /// Write the table even if points are missing (status 2, NaN results).
        #[arg(long)]
        allow_missing: bool,
    },
    /// Plot the force–approach curve (and stored contact snapshots) of a result file.
    Plot {
        /// The result file (HDF5).
        file: PathBuf,
        /// The figure to write: `.svg` or `.png`, by the extension (PNG needs the default `png`
        /// feature of tack-cli).
        #[arg(short, long, value_name = "FIG.svg")]
        output: PathBuf,
    },
}

/// Writes `text` to standard output. A reader that closed the pipe early (`tack check … |
/// head -1`) ends the output quietly, as for any Unix tool, where `println!` panicked.
fn out(text: &str) -> anyhow::Result<()> {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    match stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
    {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        r => Ok(r?),
    }
}

/// `println!` through [`out`].
macro_rules! say {
    ($($arg:tt)*) => {
        out(&format!("{}\n", format_args!($($arg)*)))?
    };
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match execute(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

fn execute(command: Command) -> anyhow::Result<()> {
    match command {
        Command::Run {
            scene,
            output,
            quiet,
            set,
            richardson,
            threads,
        } => {
            let options = RunOptions {
                command_line: None,
                richardson,
                threads,
            };
            let scene = Scene::load(&scene, &set)?;
            let outcome =
                engine::run_to_file(&scene, &output, &options, &mut Progress::new(quiet))?;
            out(&report::report(&scene, &outcome, Some(&output)))?;
        }
        Command::Surface { scene, output, set } => {
            let scene = Scene::load(&scene, &set)?;
            engine::check_output_path(&output)?;
            let problem = Problem::from_scene(&scene)?;
            let prov = provenance::provenance(&scene, &problem, provenance::command_line());
            tack_io::write_result(&output, &tack::summary::surface_file(&problem, prov))?;
            let g = problem.grid;
            say!(
                "wrote {}: {} x {} heights, dx = {}, min {}, max {}",
                output.display(),
                g.nx(),
                g.ny(),
                rounded(g.dx()),
                rounded(problem.surface.min()),
                rounded(problem.surface.max())
            );
        }
        Command::Check { scene, set } => {
            let loaded = Scene::load(&scene, &set)?;
            let p = Problem::from_scene(&loaded)?;
            say!(
                "{}: ok\n  grid {} x {}, dx = {}",
                scene.display(),
                p.grid.nx(),
                p.grid.ny(),
                rounded(p.grid.dx()),
            );
            say!(
                "  first touch at d = {}; path: {}",
                rounded(p.first_touch),
                report::describe_planned_path(&p.path, &p.law, p.viscoelastic.is_some())
            );
            if let Some(rule) = &p.path_rule {
                say!("  {rule}");
            }
            if let Some((prony, rates)) = &p.viscoelastic {
                say!("  {}", report::describe_viscoelastic(prony, rates));
            }
            let steps = p.path.step_bound();
            let bound = if steps < p.path.max_steps {
                format!("{steps} steps: the path's own count")
            } else {
                format!(
                    "{} = {steps} steps: retraction ends when contact is lost",
                    tack::fields::PROTOCOL_MAX_STEPS
                )
            };
            say!(
                "  memory: at most about {} ({bound})",
                tack::memory::bytes(p.memory_estimate().total()),
            );
            let loads = p.path.load_steps();
            if loads >= p.path.max_steps as f64 {
                say!(
                    "  note: the load takes {} steps, at least {} = {}: the run stops there, \
                     before retracting",
                    rounded(loads),
                    tack::fields::PROTOCOL_MAX_STEPS,
                    p.path.max_steps
                );
            }
        }
        Command::Sweep {
            sweep,
            output,
            threads,
            shard,
            quiet,
        } => {
            let loaded = Sweep::load(&sweep)?;
            let options = SweepOptions {
                threads: threads.map(NonZeroUsize::get),
                shard: shard.unwrap_or_default(),
                command_line: None,
            };
            let report =
                tack_sweep::run_sweep(&loaded, &output, &options, &SweepProgress::new(quiet))?;
            say!("{report}");
            if !report.failed.is_empty() {
                anyhow::bail!(
                    "{} of {} points failed (errors above and in {}/points/*.err); the other \
                     points completed",
                    report.failed.len(),
                    report.in_shard,
                    output.display()
                );
            }
        }
        Command::Merge {
            dir,
            output,
            allow_missing,
        } => {
            let options = MergeOptions {
                allow_missing,
                command_line: None,
            };
            let report = tack_sweep::merge(&dir, &output, &options)?;
            eprint!("{}", report.issues());
            if report.written {
                say!("{report}; wrote {}", output.display());
            } else {
                anyhow::bail!(
                    "{report}; nothing written: run `tack sweep` on {} again for the missing \
                     points (or pass --allow-missing to merge what there is)",
                    dir.display()
                );
            }
        }
        Command::Info { file } => {
            let text = tack_io::describe(&file)?;
            out(&text)?;
        }
        Command::Plot { file, output } => {
            plot::plot_file(&file, &output)
                .with_context(|| format!("plotting {}", file.display()))?;
            say!("wrote {}", output.display());
        }
    }
    Ok(())
}
