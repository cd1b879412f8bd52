//! `cargo xtask`: project automation: reproduce the paper's datasets and run benchmarks.

mod bench;
mod reproduce;

use anyhow::{Result, bail};

const USAGE: &str = "usage: cargo xtask <command>

commands:
  reproduce [--out DIR]   regenerate every dataset that exists so far (default DIR: results)
  bench-kernels           time the elastic operators against a bare FFT pair of the same size
  bench-jkr [RATIOS...]   smooth-sphere approach-retract path: wall time, CG iterations and
                          pull-off error at a_c/dx = 5 10 20 40 80 (or the ratios given)";

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("reproduce") => reproduce::run(&args[1..]),
        Some("bench-kernels") => bench::kernels(),
        Some("bench-jkr") => bench::jkr(&args[1..]),
        Some("-h" | "--help") | None => {
            println!("{USAGE}");
            Ok(())
        }
        Some(other) => bail!("unknown command `{other}`\n\n{USAGE}"),
    }
}
