//! How the retraction step moves the pull-off: the smooth JKR sphere on its default pull-off
//! path (`tack::pull_off_path`) at a_c/Δx = 10 … 80, with tensile retraction steps from
//! 0.02 d_s down, against the closed form F_JKR, with and without Richardson (2Δx).
//!
//! The path's share of the error is the change of F against the finest step; the criterion's
//! own error is what remains at the finest step. Prints a Markdown table (the README's).
//!
//! ```text
//! cargo run --release -p tack --example retraction_step            # a_c/Δx = 10, 20, 40, 80
//! cargo run --release -p tack --example retraction_step -- 10 20    # chosen levels
//! ```

use tack::{RunOptions, Scene};

/// JKR units: E* = γ = R = 1, so d_s = 1 and a_c = (9π/8)^(1/3).
fn scene(ac_over_dx: f64, unload_step: Option<f64>) -> Result<Scene, tack::Error> {
    let a_c = tack::analytics::jkr_pull_off_radius(1.0, 1.0, 1.0);
    let dx = a_c / ac_over_dx;
    // The loaded contact (about 1.6 a_c) with the 30% margin of the fit check, even sides.
    let n = 2 * (2.4 * ac_over_dx).ceil() as usize;
    let step = unload_step.map_or_else(String::new, |s| format!("unload_step = {s}\n"));
    let text = format!(
        "version = 1\n[material]\ne_star = 1.0\ngamma = 1.0\n[geometry]\nshape = \"sphere\"\n\
         radius = 1.0\n[grid]\nn = {n}\ndx = {dx}\n[protocol]\n{step}"
    );
    Ok(Scene::parse(&text, ".", &[])?)
}

fn main() -> Result<(), tack::Error> {
    let levels: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("a_c/Δx levels are numbers"))
        .collect();
    let levels = if levels.is_empty() {
        vec![10.0, 20.0, 40.0, 80.0]
    } else {
        levels
    };
    let options = RunOptions {
        richardson: true,
        ..RunOptions::default()
    };
    println!("| a_c/Δx | unload step / d_s | F/F_JKR − 1 | Richardson − 1 | steps | wall s |");
    println!("|---:|---:|---:|---:|---:|---:|");
    for &level in &levels {
        let default = scene(level, None)?;
        let default_step = tack::Problem::from_scene(&default)?.path.unload_step;
        let mut steps = vec![
            None,
            Some(0.02),
            Some(0.01),
            Some(0.005),
            Some(0.0025),
            Some(0.00125),
        ];
        steps.retain(|s| s.is_none_or(|s| s < 0.0201 && (s - default_step).abs() > 1e-12));
        for step in steps {
            let outcome = tack::run(&scene(level, step)?, &options, &mut ())?;
            let s = &outcome.result.summary;
            let label = match step {
                None => format!("{default_step:.5} (default)"),
                Some(s) => format!("{s:.5}"),
            };
            println!(
                "| {level} | {label} | {:+.2}% | {:+.2}% | {} | {:.1} |",
                100.0 * (s.pull_off_ratio - 1.0),
                100.0 * (s.extra["pull_off_ratio_richardson"] - 1.0),
                outcome.path.records.len(),
                outcome.total_wall_time().as_secs_f64()
            );
        }
    }
    Ok(())
}
