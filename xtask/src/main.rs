//! `cargo xtask`: project automation: reproduce the paper's datasets, run benchmarks, tidy the
//! sources.

mod bench;
mod bench_laws;
mod bench_visco;
mod convergence;
mod engine;
mod figures;
mod plot;
mod reproduce;
mod spec;
mod study;
mod study_rate;
mod sweeps;
mod tidy;
mod validation;

use anyhow::{Result, bail};

/// Every allocation is counted, so `cargo xtask bench` can report each run's peak heap bytes.
#[global_allocator]
static GLOBAL: &peakmem_alloc::PeakMemAlloc<std::alloc::System> =
    &peakmem_alloc::INSTRUMENTED_SYSTEM;

const USAGE: &str = "usage: cargo xtask <command>

commands:
  reproduce [FIG...] [--full] [--fresh] [--out DIR] [--threads N]
                          the paper's Figures 1-8 (FIG: 1..8 or fig1..fig8, default all, plus
                          the non-adhesive validation tables) from data/figures/*.toml, in quick
                          mode (minutes) or --full mode (the paper's settings); writes figN.h5,
                          figN.svg, figN/<run>.h5 and REPORT.md to DIR (default: results);
                          Figures 5 and 7 (read by 6 and 8) run as tack sweeps in
                          DIR/figN/sweep-quick|full/, which a rerun resumes (--fresh
                          recomputes them, e.g. after a solver change);
                          --specs DIR reads the figure specs from elsewhere
  bench-kernels           time the elastic operators against a bare FFT pair of the same size
  bench-jkr [RATIOS...]   smooth-sphere approach-retract path: wall time, CG iterations and
                          pull-off error at a_c/dx = 5 10 20 40 80 (or the ratios given)
  bench-contact [N]        non-adhesive contact: N² periodic rough surface (H = 0.8, ~7%
                          contact) and N² free Hertz, plain / coarse-to-fine / cropped
  bench-dugdale [N...]     Dugdale smooth sphere at Tabor mu = 3 on N² (default 128 256 512),
                           cycle, pull-off protocol and refined, against the FFT floor; Dugdale vs
                           zero-range rough sphere at 256²
  bench-laws [--full|--levels] [--seed N]
                          every adhesion law (exponential, Dugdale, zero-range)
                          on the peers' case (R = 1, E* = 1, gamma = 1e-3, L = 1, mu = 3) at
                          64² and 128² (--full: 256²): time, FFT pairs, products and error
                          against the same law's converged pull-off, beside the peers' figures;
                          the bench's rough sphere at 256², exponential mu = 3 against
                          zero-range (--full, or --levels alone: both laws on its surface
                          up to 1024² and 2048², the ratio at equal error, ~10 min;
                          --seed N: another surface, default 1);
                          writes results/bench_laws.json (also table 11 of bench)
  bench-visco [N...]       viscoelastic pull-off (the example scene viscoelastic_sphere, no hold)
                          against the elastic one of the same grid and steps on N² (default
                          48 96 192): both times, their ratio, FFT pairs
  bench-rough [N]          sphere + H = 0.5 roughness pull-off on an N² L = R grid (default
                          512): plain, cropped, sub-grid CG, both
  bench [--full] [--4096] every speed table (operator, CG iteration, JKR path, rough-sphere
                          pull-off 128² … 2048² with peak heap bytes per element, 4096² with
                          --4096; inexact against exact rounds; refined against fine retraction;
                          15-realization sweep point and one run on 1 and 2 threads, compared
                          bit for bit; periodic contact 256² … 4096²; free Hertz; bench-dugdale's
                          and bench-visco's tables); writes results/bench.json
  convergence [N...]      pull-off convergence on smooth, wavy (α = 0.5, 1) and band-limited
                          rough spheres (H = 0.3, 0.7, three seeds) at n = 64 … 1024 (or
                          the N given): Richardson, observed order, error estimate against the
                          distance to the finest Richardson value, time per level; writes
                          results/convergence.json
  study <loading|dissipation|jkr-limit|rate> [--n N] [--first-seed F] [--seeds S]
        [--lambdas L,..|none] [--mus M,..] [--steps K,..] [--ratios R,..]
                          finite-range studies. loading: a rough sphere (H = 0.5, R = L, N²
                          default 256, seeds F..S default 0..4, seed 0 the smooth sphere),
                          |F/F_JKR| against the number of load steps (K default 1,5,20,80)
                          under the zero-range law, the Dugdale law at each Maugis λ (default
                          1,2,3) and the exponential law at each Tabor μ (--mus, default none);
                          dissipation: the loop's dissipated energy against
                          α* = 0.2..0.7 under the same laws (loaded in 320 steps unless
                          --steps), and
                          results/study-dissipation.svg; jkr-limit: the smooth sphere's
                          Dugdale pull-off at each λ beside the criterion at a_c/dx = R
                          (default 20,40,80, each double the last); rate: a standard linear
                          solid under the exponential law, the smooth sphere's pull-off against
                          the retraction speed (results/study-rate.svg), the hold and the
                          preload (96²), rough spheres at α* = 0.3, 0.7 at three speeds (N²
                          default 128, seeds 1..S default 3); writes results/study-<name>.md
  tidy                    source checks beyond clippy: every .rs file opens with a //! line,
                          every scene field of tack_fields::FIELDS is documented in
                          docs/scenes.md, no scene field spelled as a string literal outside
                          tack-fields (test code aside), every command here is mentioned in
                          ARCHITECTURE.md, no import circle, no library function over 150 lines,
                          no inline test module over 300, every integration-test file named in
                          ARCHITECTURE.md; prints path:line: finding, fails on any (but those
                          listed as pending in tidy.rs); also run by `cargo test -p xtask`";

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    // Benchmarks run inside a pool of all cores (or RAYON_NUM_THREADS), as `tack run` does:
    // solves called from outside a pool stay on the calling thread.
    let pool = || rayon::ThreadPoolBuilder::new().build();
    match args.first().map(String::as_str) {
        Some("reproduce") => reproduce::run(&args[1..]),
        Some("bench-kernels") => pool()?.install(bench::kernels),
        Some("bench-jkr") => pool()?.install(|| bench::jkr(&args[1..])),
        Some("bench-contact") => pool()?.install(|| bench::contact(&args[1..]).map(|_| ())),
        Some("bench-rough") => pool()?.install(|| bench::rough(&args[1..])),
        Some("bench-dugdale") => pool()?.install(|| bench::dugdale(&args[1..])),
        Some("bench-laws") => pool()?.install(|| bench_laws::run_table(&args[1..])),
        Some("bench-visco") => pool()?.install(|| bench_visco::run(&args[1..])),
        Some("bench") => pool()?.install(|| {
            let visco: bench::Table = |rows| bench_visco::table(&[], rows);
            let title = "10. a viscoelastic pull-off against the elastic one (bench-visco's table)";
            let laws: bench::Table = bench_laws::tables;
            let laws_title = "11. every adhesion law on the peers' case, speed against error \
                              (bench-laws' tables, 64² and 128²)";
            bench::all(&args[1..], &[(title, visco), (laws_title, laws)])
        }),
        Some("convergence") => pool()?.install(|| convergence::run(&args[1..])),
        Some("study") => pool()?.install(|| study::run(&args[1..])),
        Some("tidy") => tidy::run(&args[1..]),
        Some("-h" | "--help") | None => {
            println!("{USAGE}");
            Ok(())
        }
        Some(other) => bail!("unknown command `{other}`\n\n{USAGE}"),
    }
}
