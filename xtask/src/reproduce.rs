//! `cargo xtask reproduce [FIG...] [--full] [--out DIR] [--threads N]`: regenerates the paper's
//! Figures 1–8 from the specs in `data/figures/` and the non-adhesive validation tables, and
//! writes `DIR/REPORT.md` (plots, measured deviations, wall times) and `DIR/validation.md`.
//! Figures 5 and 7 (and 6, 8, which read 7) run as tack sweeps in `DIR/figN/sweep-<mode>/`: a
//! rerun resumes them, skipping the points already complete.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, Result};

use crate::figures::{self, Ctx, FigureSummary};
use crate::validation;

/// What to reproduce and where.
#[derive(Debug, Clone)]
pub struct Options {
    /// Figures to run, in order.
    pub figures: Vec<u8>,
    /// Also regenerate the validation tables (default when no figure is named).
    pub validation: bool,
    /// Full mode: the paper's settings.
    pub full: bool,
    /// Output directory.
    pub out: PathBuf,
    /// Worker threads for independent runs (engine batches and figure sweeps).
    pub threads: usize,
    /// Directory of the figure specs.
    pub specs: PathBuf,
    /// Recompute the sweep points of Figures 5 and 7 instead of resuming (after a solver
    /// change: points are recognised by their scene text only).
    pub fresh: bool,
}

impl Options {
    /// Parses the command's arguments.
    pub fn parse(args: &[String]) -> Result<Self> {
        let mut o = Self {
            figures: Vec::new(),
            validation: false,
            full: false,
            out: PathBuf::from("results"),
            threads: std::thread::available_parallelism().map_or(1, |n| n.get()),
            specs: default_specs(),
            fresh: false,
        };
        let mut it = args.iter();
        while let Some(a) = it.next() {
            match a.as_str() {
                "--full" => o.full = true,
                "--fresh" => o.fresh = true,
                "--out" => o.out = it.next().context("--out needs a directory")?.into(),
                "--specs" => o.specs = it.next().context("--specs needs a directory")?.into(),
                "--threads" => {
                    let n = it.next().context("--threads needs a number")?;
                    o.threads = n
                        .parse()
                        .ok()
                        .filter(|&n| n >= 1)
                        .with_context(|| format!("--threads {n}: must be an integer ≥ 1"))?;
                }
                "validation" => o.validation = true,
                fig => {
                    let n: u8 = fig
                        .strip_prefix("fig")
                        .unwrap_or(fig)
                        .parse()
                        .ok()
                        .filter(|n| (1..=8).contains(n))
                        .with_context(|| {
                            format!(
                                "unknown argument `{fig}` (allowed: 1..8 or fig1..fig8, \
                                 validation, --full, --fresh, --out DIR, --threads N, --specs DIR)"
                            )
                        })?;
                    if !o.figures.contains(&n) {
                        o.figures.push(n);
                    }
                }
            }
        }
        if o.figures.is_empty() && !o.validation {
            o.figures = (1..=8).collect();
            o.validation = true;
        }
        Ok(o)
    }
}

/// `data/figures` of this workspace.
pub fn default_specs() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../data/figures")
}

/// A figure's summary and wall time.
pub struct Done {
    /// The figure's title (from its spec).
    pub title: String,
    /// The summary.
    pub summary: FigureSummary,
    /// Wall time in seconds.
    pub seconds: f64,
}

/// Runs the selected figures in order (engine runs inside a figure in parallel on the current
/// rayon pool, figure sweeps on `o.threads` threads) and returns their summaries.
pub fn figures(o: &Options) -> Result<Vec<Done>> {
    std::fs::create_dir_all(&o.out).with_context(|| format!("creating {}", o.out.display()))?;
    let ctx = Ctx {
        specs: o.specs.clone(),
        out: o.out.clone(),
        full: o.full,
        threads: o.threads,
    };
    if o.fresh {
        for n in [5u8, 7] {
            let dir = crate::sweeps::sweep_dir(&o.out, n, o.full);
            if o.figures.contains(&n) && dir.exists() {
                println!("--fresh: removing {}", dir.display());
                std::fs::remove_dir_all(&dir)
                    .with_context(|| format!("removing {}", dir.display()))?;
            }
        }
    }
    let mut done = Vec::new();
    for &n in &o.figures {
        println!("fig{n} ({} mode)", if o.full { "full" } else { "quick" });
        let t = Instant::now();
        let title = ctx.spec(n)?.title;
        let summary = figures::run(n, &ctx).with_context(|| format!("figure {n}"))?;
        let seconds = t.elapsed().as_secs_f64();
        print!("{}", summary.text());
        println!("fig{n}: {seconds:.1} s\n");
        done.push(Done {
            title,
            summary,
            seconds,
        });
    }
    Ok(done)
}

/// The command.
pub fn run(args: &[String]) -> Result<()> {
    let o = Options::parse(args)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(o.threads)
        .build()
        .context("starting the worker threads")?;
    let start = Instant::now();
    let done = pool.install(|| figures(&o))?;
    let mut report = format!(
        "# tack: reproduction of Li, Pohrt & Popov (2019)\n\nMode: **{}** ({} threads). \
         Generated by `cargo xtask reproduce`; figure specs in `data/figures/`.\n\n",
        if o.full { "full" } else { "quick" },
        o.threads
    );
    if !done.is_empty() {
        report += "| figure | compared | wall time [s] |\n|---|---|---|\n";
        for d in &done {
            let _ = writeln!(
                report,
                "| [{n}](#figure-{n}) | {} | {:.1} |",
                d.summary.compared.replace('|', "\\|"),
                d.seconds,
                n = d.summary.figure
            );
        }
        report.push('\n');
    }
    for d in &done {
        let n = d.summary.figure;
        let _ = write!(
            report,
            "## Figure {n}: {}\n\n![fig{n}](fig{n}.svg)\n\n{}\n\n{}\nData: `fig{n}.h5`, {}. \
             Wall time {:.1} s.\n\n",
            d.title,
            d.summary.compared,
            d.summary.markdown(),
            figures::runs_location(n, o.full),
            d.seconds
        );
    }
    if o.validation {
        println!("validation (non-adhesive: Hertz, Westergaard)");
        let t = Instant::now();
        let v = validation::report()?;
        write_atomic(&o.out.join("validation.md"), &v)?;
        println!("validation: {:.1} s\n", t.elapsed().as_secs_f64());
        report += &v.replacen("# tack validation report", "## Non-adhesive validation", 1);
    }
    let path = o.out.join("REPORT.md");
    write_atomic(&path, &report)?;
    println!(
        "wrote {} in {:.1} s",
        path.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

fn write_atomic(path: &std::path::Path, text: &str) -> Result<()> {
    tack_io::write_text_atomically(path, text)
        .with_context(|| format!("writing {}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arguments() {
        let o = Options::parse(&["fig2".into(), "7".into(), "--full".into()]).unwrap();
        assert_eq!((o.figures, o.full, o.validation), (vec![2, 7], true, false));
        let o = Options::parse(&[]).unwrap();
        assert_eq!(o.figures, (1..=8).collect::<Vec<_>>());
        assert!(o.validation);
        assert!(Options::parse(&["9".into()]).is_err());
        assert!(Options::parse(&["--threads".into(), "0".into()]).is_err());
        assert!(Options::parse(&["--fresh".into()]).unwrap().fresh);
        assert!(!Options::parse(&[]).unwrap().fresh);
    }

    /// Quick mode of every figure; the rounded summaries are insta snapshots
    /// (`src/snapshots/`). A changed number fails the test until reviewed: `cargo insta review`,
    /// or rerun with `INSTA_UPDATE=always` and inspect the diff of the `.snap` files. Outside CI
    /// a mismatch also leaves a `.snap.new` beside the snapshot; with `CI=true` nothing is written.
    #[test]
    fn quick_mode_summaries() {
        let out = std::env::temp_dir().join(format!("tack-xtask-quick-{}", std::process::id()));
        let o = Options {
            validation: false,
            out: out.clone(),
            ..Options::parse(&[]).unwrap()
        };
        let done = figures(&o);
        let _ = std::fs::remove_dir_all(&out);
        for d in done.unwrap() {
            insta::assert_snapshot!(format!("fig{}", d.summary.figure), d.summary.text());
        }
    }
}
