//! `cargo xtask bench-visco [N...]`: a viscoelastic pull-off against the elastic one of the same
//! scene, grid and steps, both timed in the same run (issue "Rate-dependent adhesion": at most
//! 3× the elastic cost), and the bare FFT pair of the padded size beside them.

use anyhow::Result;

use crate::bench::{Row, bare_fft_pair, median_time};

/// The example scene `data/examples/viscoelastic_sphere.toml` on `n²` elements over its length
/// (1.2), without its hold, and the elastic scene of the same steps (without the arms and the
/// rates: the relaxed modulus E0).
fn scenes(n: usize) -> Result<(tack::Scene, tack::Scene)> {
    let text = std::fs::read_to_string("data/examples/viscoelastic_sphere.toml")?;
    let keep = |drop: &[&str]| -> String {
        text.lines()
            .filter(|l| !drop.iter().any(|d| l.starts_with(d)))
            .map(|l| format!("{l}\n"))
            .collect()
    };
    let visco = keep(&["dwell"]);
    let elastic = keep(&["dwell", "prony", "speed"]);
    let sets = vec![
        format!("{}={n}", tack::fields::GRID_N),
        format!("{}={}", tack::fields::GRID_DX, 1.2 / n as f64),
        format!("{}=\"none\"", tack::fields::OUTPUT_SNAPSHOTS),
    ];
    Ok((
        tack::Scene::parse(&visco, ".", &sets)?,
        tack::Scene::parse(&elastic, ".", &sets)?,
    ))
}

/// Seconds, steps and pull-off of one run of `scene` on every thread of the pool; it must
/// complete and converge (`bench`'s timed run).
fn timed(scene: &tack::Scene) -> Result<(f64, usize, f64)> {
    let r = crate::bench::timed_pull_off(scene, rayon::current_num_threads())?;
    Ok((r.seconds, r.steps, r.force))
}

/// Prints and records the table at each `n` (default 48 96 192).
pub fn table(args: &[String], rows: &mut Vec<Row>) -> Result<()> {
    let sizes: Vec<usize> = if args.is_empty() {
        vec![48, 96, 192]
    } else {
        args.iter().map(|a| a.parse()).collect::<Result<_, _>>()?
    };
    println!(
        "V. viscoelastic pull-off (standard linear solid, E∞/E0 = 10, exponential law, speed 0.01)"
    );
    println!("   against the elastic one (E0) of the same grid and steps");
    println!(
        "   {:>5} {:>12} {:>12} {:>7} {:>7} {:>10} {:>12} {:>12}",
        "n", "elastic [s]", "visco [s]", "ratio", "steps", "FFT pairs", "F elastic", "F visco"
    );
    for n in sizes {
        let (visco, elastic) = scenes(n)?;
        let m = tack_kernels::padded_size(n);
        let t_pair = median_time(bare_fft_pair(m, m));
        let (te, se, fe) = timed(&elastic)?;
        let (tv, sv, fv) = timed(&visco)?;
        println!(
            "   {n:>5} {te:>12.3} {tv:>12.3} {:>7.2} {:>7} {:>10.0} {fe:>12.5e} {fv:>12.5e}",
            tv / te,
            format!("{se}/{sv}"),
            tv / t_pair
        );
        rows.push(Row::new(
            "viscoelastic_pull_off",
            format!("{n}²"),
            vec![
                ("n", n as f64),
                ("elastic_seconds", te),
                ("viscoelastic_seconds", tv),
                ("ratio", tv / te),
                ("elastic_steps", se as f64),
                ("viscoelastic_steps", sv as f64),
                ("fft_pairs", tv / t_pair),
                ("elastic_pull_off", fe),
                ("viscoelastic_pull_off", fv),
            ],
        ));
    }
    Ok(())
}

/// `cargo xtask bench-visco [N...]`: [`table`] alone.
pub fn run(args: &[String]) -> Result<()> {
    let mut rows = Vec::new();
    table(args, &mut rows)
}
