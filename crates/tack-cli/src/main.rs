//! The `tack` command line. Scene files, runs and result files arrive with the CLI issue; today
//! it answers `--help` and `--version`.

use clap::Parser;

/// Adhesive strength of rough elastic contacts (Li, Pohrt & Popov 2019), by FFT-accelerated BEM.
#[derive(Debug, Parser)]
#[command(name = "tack", version, about)]
struct Cli {}

fn main() {
    let _ = Cli::parse();
    println!(
        "tack {}: no subcommands yet; see README.md",
        env!("CARGO_PKG_VERSION")
    );
}
