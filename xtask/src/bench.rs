//! Benchmarks that print ratios measured in the same run (operator time / bare FFT floor).

use anyhow::Result;
use ndarray::Array2;
use std::time::Instant;
use tack_geometry::{Boundary, Grid};
use tack_kernels::operator_for;

/// Median wall time in seconds of `f` over enough repetitions to fill ~0.5 s (at least 5).
pub fn median_time(mut f: impl FnMut()) -> f64 {
    f();
    let probe = Instant::now();
    f();
    let once = probe.elapsed().as_secs_f64().max(1e-9);
    let reps = ((0.5 / once) as usize).clamp(5, 200);
    let mut times: Vec<f64> = (0..reps)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[reps / 2]
}

/// Runs `f` and measures the peak heap bytes it held above what was allocated before it (the
/// xtask's allocator counts every allocation: `peakmem-alloc`).
fn with_peak<T>(f: impl FnOnce() -> Result<T>) -> Result<(T, f64)> {
    use peakmem_alloc::PeakMemAllocTrait;
    crate::GLOBAL.reset_peak_memory();
    let out = f()?;
    Ok((out, crate::GLOBAL.get_peak_memory() as f64))
}

/// Forward + inverse real 2D FFT of an `mx × my` array with the operators' own engine and
/// nothing skipped: the floor any FFT operator pays.
pub fn bare_fft_pair(mx: usize, my: usize) -> impl FnMut() {
    let mut fft = tack_kernels::Fft2::new(mx, my);
    move || fft.round_trip()
}

/// The median time (s) of numpy's `irfft2(rfft2(a))` on an `n²` array, the unit of issue 37's
/// targets, timed by `python3` in this run (`TACK_BENCH_PYTHON` names another interpreter);
/// `None`, said once, where no interpreter with numpy runs. numpy's pocketfft is
/// single-threaded, so the unit does not depend on the bench's threads.
pub fn numpy_fft_pair(n: usize) -> Option<f64> {
    let python = std::env::var("TACK_BENCH_PYTHON").unwrap_or_else(|_| "python3".into());
    let script = format!(
        "import time, numpy as np\n\
         a = np.random.default_rng(1).random(({n}, {n}))\n\
         np.fft.irfft2(np.fft.rfft2(a), s=a.shape)\n\
         t = []\n\
         for _ in range(15):\n    \
         s = time.perf_counter(); np.fft.irfft2(np.fft.rfft2(a), s=a.shape); \
         t.append(time.perf_counter() - s)\n\
         print(sorted(t)[7])\n"
    );
    let out = std::process::Command::new(&python)
        .args(["-c", &script])
        .output();
    let seconds = out
        .ok()
        .filter(|o| o.status.success())
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .and_then(|t| t.trim().parse::<f64>().ok())
        .filter(|t| t.is_finite() && *t > 0.0);
    if seconds.is_none() {
        println!(
            "   ({python} with numpy not found: the numpy-pair columns are NaN; \
             TACK_BENCH_PYTHON names an interpreter)"
        );
    }
    seconds
}

/// The body of a kernel bench row: the half-space, or a bonded incompressible layer of 4Δx.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Body {
    HalfSpace,
    Layer,
}

/// Median times (s) of one application of `body`'s operator on an `n²` grid and of the bare
/// FFT round trip of its padded size.
fn body_vs_floor(n: usize, boundary: Boundary, body: Body) -> Result<(f64, f64)> {
    let grid = Grid::square(n, 1.0, boundary)?;
    let mut op = match body {
        Body::HalfSpace => operator_for(grid, 1.0)?,
        Body::Layer => tack_kernels::layer_operator_for(
            grid,
            1.0,
            &tack_kernels::Layer {
                thickness: 4.0,
                poisson: 0.5,
                interface: tack_kernels::Interface::Bonded,
            },
        )?,
    };
    let p = Array2::from_shape_fn((n, n), |(i, j)| ((i + 2 * j) % 5) as f64);
    let mut u = Array2::zeros((n, n));
    let t_op = median_time(|| op.apply(p.view(), u.view_mut()));
    let m = match boundary {
        Boundary::Free => tack_kernels::padded_size(n),
        Boundary::Periodic => n,
    };
    Ok((t_op, median_time(bare_fft_pair(m, m))))
}

/// `cargo xtask bench-kernels`: operator application vs the bare FFT pair of its padded size.
pub fn kernels() -> Result<()> {
    construction()?;
    println!("operator application vs bare forward+inverse r2c FFT pair of the same padded size");
    println!("(layer: a bonded incompressible film of thickness 4Δx on a rigid base)");
    println!(
        "{:>6} {:>10} {:>11} {:>12} {:>12} {:>8}",
        "N", "boundary", "body", "apply [ms]", "fft [ms]", "ratio"
    );
    for n in [256usize, 512, 1024] {
        for boundary in [Boundary::Free, Boundary::Periodic] {
            for body in [Body::HalfSpace, Body::Layer] {
                let (t_op, t_fft) = body_vs_floor(n, boundary, body)?;
                println!(
                    "{n:>6} {:>10} {:>11} {:>12.3} {:>12.3} {:>8.2}",
                    format!("{boundary:?}").to_lowercase(),
                    match body {
                        Body::HalfSpace => "half-space",
                        Body::Layer => "layer",
                    },
                    t_op * 1e3,
                    t_fft * 1e3,
                    t_op / t_fft
                );
            }
        }
    }
    Ok(())
}

/// Sides of the sub-grid operators of [`construction`]: every pair is built, as a rough-sphere
/// run's sub-grid cache builds operators of many rectangular sizes.
const SUBGRID_SIDES: [usize; 9] = [16, 24, 32, 48, 64, 96, 128, 192, 256];

/// Times the construction of the free operators of every pair of [`SUBGRID_SIDES`] (81
/// operators, each with its two FFT pairs), first in this process (the FFT plans of every
/// length made once, docs of `tack_kernels::Fft2`), then again with every plan already made.
fn construction() -> Result<()> {
    let build_all = || -> Result<f64> {
        let t = Instant::now();
        for &nx in &SUBGRID_SIDES {
            for &ny in &SUBGRID_SIDES {
                let grid = Grid::new(nx, ny, 1.0, Boundary::Free)?;
                std::hint::black_box(operator_for(grid, 1.0)?);
            }
        }
        Ok(t.elapsed().as_secs_f64())
    };
    // The FFT pairs alone, as the free operator plans them (padded and preconditioner sizes).
    let plan_all = || {
        let t = Instant::now();
        for &nx in &SUBGRID_SIDES {
            for &ny in &SUBGRID_SIDES {
                let (px, py) = (tack_kernels::padded_size(nx), tack_kernels::padded_size(ny));
                std::hint::black_box(tack_kernels::Fft2::new(px, py));
                let (fx, fy) = (tack_kernels::fast_size(nx), tack_kernels::fast_size(ny));
                std::hint::black_box(tack_kernels::Fft2::new(fx, fy));
            }
        }
        t.elapsed().as_secs_f64()
    };
    let first = build_all()?;
    let again = build_all()?;
    let plans = plan_all();
    println!(
        "operator construction, {} free sub-grid operators ({:?}²): first {:.1} ms, again {:.1} ms \
         (their FFT pairs alone {:.1} ms)",
        SUBGRID_SIDES.len() * SUBGRID_SIDES.len(),
        SUBGRID_SIDES,
        first * 1e3,
        again * 1e3,
        plans * 1e3
    );
    Ok(())
}

/// One smooth-sphere path with the paper's criterion at `a_c/Δx = ratio`: (seconds, the run).
/// Load to d̂ = 6 in 20 steps, retract in steps of 0.1 while the force is compressive (the
/// pull-off is unchanged to all digits) and 0.01 once it is tensile.
fn jkr_run(ratio: f64) -> (f64, tack_tests::JkrRun) {
    let t = Instant::now();
    let run = tack_tests::JkrSphere {
        coarse_unload_step: Some(0.1),
        ..tack_tests::JkrSphere::new(ratio, tack_solver::KAPPA)
    }
    .run();
    (t.elapsed().as_secs_f64(), run)
}

/// `cargo xtask bench-jkr [RATIOS...]`: speed against error on the smooth JKR sphere with the
/// paper's criterion, and the Richardson extrapolation of every pair `N`, `N/2` in the list.
pub fn jkr(args: &[String]) -> Result<()> {
    let ratios: Vec<f64> = args
        .iter()
        .map(|a| {
            a.parse()
                .map_err(|_| anyhow::anyhow!("ratio `{a}` is not a number"))
        })
        .collect::<Result<_>>()?;
    let ratios = if ratios.is_empty() {
        vec![5.0, 10.0, 20.0, 40.0, 80.0]
    } else {
        ratios
    };
    jkr_table(&ratios);
    Ok(())
}

/// Prints (and returns as rows) the speed-against-error table of the smooth sphere.
fn jkr_table(ratios: &[f64]) -> Vec<Row> {
    println!(
        "smooth sphere, free boundaries, κ = 0.473201; load to d̂ = 6, retract by 0.1 while \
         compressive, by 0.01 once tensile"
    );
    println!(
        "{:>16} {:>8} {:>7} {:>10} {:>10} {:>12} {:>12}",
        "a_c/Δx", "grid", "steps", "CG iters", "time [s]", "F/F_JKR − 1", "jump-off d̂"
    );
    let mut rows = Vec::new();
    let mut done: Vec<(f64, f64, f64)> = Vec::new();
    for &ratio in ratios {
        let (secs, run) = jkr_run(ratio);
        println!(
            "{ratio:>16} {:>8} {:>7} {:>10} {secs:>10.2} {:>+12.4} {:>12.3}",
            format!("{}²", run.grid.nx()),
            run.result.records.len(),
            run.result.cg_iterations(),
            run.pull_off_error,
            run.last_contact_approach
        );
        rows.push(Row {
            table: "jkr",
            label: format!("{ratio}"),
            fields: vec![
                ("ac_over_dx", ratio),
                ("seconds", secs),
                ("cg_iterations", run.result.cg_iterations() as f64),
                ("pull_off_error", run.pull_off_error),
            ],
        });
        done.push((ratio, secs, run.pull_off_error));
    }
    for &(fine, t_fine, e_fine) in &done {
        if let Some(&(_, t_coarse, e_coarse)) = done.iter().find(|c| c.0 * 2.0 == fine) {
            let (secs, err) = (
                t_fine + t_coarse,
                tack_solver::richardson_first_order(e_fine, e_coarse),
            );
            let label = format!("Richardson {fine}+{}", fine / 2.0);
            println!(
                "{label:>16} {:>8} {:>7} {:>10} {secs:>10.2} {err:>+12.4}",
                "", "", ""
            );
            rows.push(Row {
                table: "jkr",
                label,
                fields: vec![
                    ("ac_over_dx", fine),
                    ("seconds", secs),
                    ("pull_off_error", err),
                ],
            });
        }
    }
    rows
}

/// One measured row of `cargo xtask bench`, kept for `results/bench.json`.
pub struct Row {
    table: &'static str,
    fields: Vec<(&'static str, f64)>,
    label: String,
}

impl Row {
    /// A row of `table` labelled `label`.
    pub fn new(table: &'static str, label: String, fields: Vec<(&'static str, f64)>) -> Self {
        Self {
            table,
            fields,
            label,
        }
    }
}

pub fn json(rows: &[Row]) -> String {
    let items: Vec<String> = rows
        .iter()
        .map(|r| {
            let fields: Vec<String> = r
                .fields
                .iter()
                .map(|(k, v)| {
                    if v.is_finite() {
                        format!("\"{k}\": {v}")
                    } else {
                        format!("\"{k}\": null")
                    }
                })
                .collect();
            format!(
                "  {{\"table\": \"{}\", \"label\": \"{}\", {}}}",
                r.table,
                r.label,
                fields.join(", ")
            )
        })
        .collect();
    format!("[\n{}\n]\n", items.join(",\n"))
}

/// Wall time of one pull-off path of a sphere + H = 0.5 roughness on an `n²` L = R grid.
fn rough_sphere_path(n: usize, seed: u64, crop: bool, subgrid: bool) -> Result<(f64, f64, usize)> {
    use tack_geometry::{RoughSpec, Sphere, Surface, rough_surface};
    use tack_solver::{
        AdhesiveOptions, AdhesiveSolver, ApproachPath, KAPPA, SnapshotRequest, contact_window,
    };
    let grid = Grid::square(n, 1.0 / n as f64, Boundary::Free)?;
    let gamma = 2.83e-4; // a_c ≈ 0.1 R with E* = R = 1
    let rough = rough_surface(grid, &RoughSpec::paper_defaults(grid, 5e-4, 0.5, seed))?;
    let mut surface = Surface::from_shape(grid, &Sphere::new(1.0)?);
    surface.add(&rough)?;
    let d_max = 0.02;
    if crop {
        let range = rough.max() - rough.min();
        if let Some(w) = contact_window(&surface, d_max, range, 1.0, gamma) {
            surface = surface.window(&w)?;
        }
    }
    let options = AdhesiveOptions {
        bonded_subgrid: subgrid,
        ..AdhesiveOptions::default()
    };
    let path = ApproachPath {
        start: surface.min() + 0.002,
        max_approach: d_max,
        load_step: 0.002,
        unload_step: 0.0005,
        coarse_unload_step: None,
        refine_pull_off: false,
        retract_to: None,
        max_steps: 10_000,
    };
    let t = Instant::now();
    let op = operator_for(*surface.grid(), 1.0)?;
    let mut solver = AdhesiveSolver::new(op, &surface, gamma, KAPPA, options)?;
    let r = solver.run_path(&path, &SnapshotRequest::None, &mut ())?;
    Ok((
        t.elapsed().as_secs_f64(),
        r.pull_off_force(),
        r.cg_iterations(),
    ))
}

/// `cargo xtask bench [--full]`: every speed table, each timing a ratio measured in the same
/// run; writes `results/bench.json`. `--full` adds a_c/Δx = 80, the 1024² operator and the
/// 1024² refined retraction.
/// A table of another module that `bench` runs: it appends its rows.
pub type Table = fn(&mut Vec<Row>) -> Result<()>;

/// Every table, then the `extra` tables of other modules (a title and the table), and
/// `results/bench.json`.
pub fn all(args: &[String], extra: &[(&str, Table)]) -> Result<()> {
    let full = args.iter().any(|a| a == "--full");
    // 4096² rough-sphere pull-off (about half an hour on 2 cores) only when asked.
    let huge = args.iter().any(|a| a == "--4096");
    let mut rows = Vec::new();

    operator_table(full, &mut rows)?;
    cg_iteration_table(&mut rows)?;
    println!("3. smooth-sphere approach-retract path: speed against error");
    let ratios: &[f64] = if full {
        &[5.0, 10.0, 20.0, 40.0, 80.0]
    } else {
        &[5.0, 10.0, 20.0, 40.0]
    };
    rows.extend(jkr_table(ratios));

    rough_sphere_tables(full, huge, &mut rows)?;
    sweep_point_table(&mut rows)?;

    println!("6. periodic rough non-adhesive contact (H = 0.8, ~7% contact), cold start");
    periodic_scaling(&[256, 512, 1024, 2048, 4096], 1024, &mut rows)?;

    println!("7. one run on 1 and 2 threads (every step compared bit for bit)");
    thread_speed_up(&[512, 1024], &[1024, 2048], &mut rows)?;

    println!("8. free Hertz, 1024², both methods");
    rows.extend(hertz_only(1024)?);

    println!("9. the Dugdale law (bench-dugdale's tables)");
    dugdale_tables(&[], &mut rows)?;

    for (title, table) in extra {
        println!("{title}");
        table(&mut rows)?;
    }

    std::fs::create_dir_all("results")?;
    tack_io::write_text_atomically("results/bench.json".as_ref(), &json(&rows))?;
    println!("wrote results/bench.json");
    Ok(())
}

/// Table 1 of `cargo xtask bench`: one operator application against the bare FFT round trip of
/// the same padded size, half-space and layer, free and periodic (1024² with `full`).
fn operator_table(full: bool, rows: &mut Vec<Row>) -> Result<()> {
    println!("1. operator application vs bare FFT round trip of the same padded size");
    for n in if full {
        vec![256usize, 512, 1024]
    } else {
        vec![256, 512]
    } {
        for (boundary, body) in [
            (Boundary::Free, Body::HalfSpace),
            (Boundary::Periodic, Body::HalfSpace),
            (Boundary::Free, Body::Layer),
            (Boundary::Periodic, Body::Layer),
        ] {
            let (t_op, t_fft) = body_vs_floor(n, boundary, body)?;
            let label = match body {
                Body::HalfSpace => format!("{n}² {boundary:?}"),
                Body::Layer => format!("{n}² {boundary:?} layer"),
            };
            println!(
                "   {label:<16} apply {:8.3} ms  floor {:8.3} ms  ratio {:.2}",
                t_op * 1e3,
                t_fft * 1e3,
                t_op / t_fft
            );
            rows.push(Row {
                table: "operator",
                label,
                fields: vec![
                    ("n", n as f64),
                    ("apply_ms", t_op * 1e3),
                    ("floor_ms", t_fft * 1e3),
                    ("ratio", t_op / t_fft),
                ],
            });
        }
    }
    Ok(())
}

/// Table 2 of `cargo xtask bench`: one CG iteration on a bonded disc (256² free grid, no
/// sub-grid), plain and preconditioned, against the FFT floor.
fn cg_iteration_table(rows: &mut Vec<Row>) -> Result<()> {
    println!("2. one CG iteration on a bonded disc (256² free grid, no sub-grid) vs the floor");
    use tack_geometry::{Sphere, Surface};
    use tack_solver::{AdhesiveOptions, AdhesiveSolver, KAPPA};
    let n = 256;
    let grid = Grid::square(n, 1.0 / n as f64, Boundary::Free)?;
    let surface = Surface::from_shape(grid, &Sphere::new(1.0)?);
    let m = tack_kernels::padded_size(n);
    let t_fft = median_time(bare_fft_pair(m, m));
    for pre in [false, true] {
        let options = AdhesiveOptions {
            preconditioned: pre,
            bonded_subgrid: false,
            ..AdhesiveOptions::default()
        };
        let op = operator_for(grid, 1.0)?;
        let mut s = AdhesiveSolver::new(op, &surface, 0.0, KAPPA, options)?;
        let t = Instant::now();
        let rec = s.step(0.1)?;
        let per_it = t.elapsed().as_secs_f64() / rec.cg_iterations.max(1) as f64;
        let label = if pre { "preconditioned" } else { "plain" };
        println!(
            "   {label:<16} {:5} iterations, {:.3} ms per iteration = {:.2} × floor ({:.3} ms)",
            rec.cg_iterations,
            per_it * 1e3,
            per_it / t_fft,
            t_fft * 1e3
        );
        rows.push(Row {
            table: "cg_iteration",
            label: label.into(),
            fields: vec![
                ("iterations", rec.cg_iterations as f64),
                ("ms_per_iteration", per_it * 1e3),
                ("ratio_to_floor", per_it / t_fft),
            ],
        });
    }
    Ok(())
}

/// Table 4 of `cargo xtask bench`: the rough-sphere pull-off against n (4096² with `huge`),
/// against the exact rounds, the refined retraction and the run without local relaxation
/// (1024² too with `full`).
fn rough_sphere_tables(full: bool, huge: bool, rows: &mut Vec<Row>) -> Result<()> {
    println!(
        "4. sphere + random roughness (H = 0.5, L = R, a_c ≈ 0.078 R) pull-off: scaling with n"
    );
    let threads = rayon::current_num_threads();
    let sizes: &[usize] = if huge {
        &[128, 256, 512, 1024, 2048, 4096]
    } else {
        &[128, 256, 512, 1024, 2048]
    };
    pull_off_scaling(sizes, threads, rows)?;
    println!("   previous version (every detach/attach round solved to 1e-9), one thread:");
    for n in [256, 512] {
        pull_off_before_after(n, rows)?;
    }
    println!(
        "   refined retraction ({}: coarse steps all the way, the pull-off's",
        tack_fields::PROTOCOL_REFINE_PULL_OFF
    );
    println!("   brackets retraced by the fine step), the same scene and threads:");
    let compared: &[usize] = if full { &[256, 512, 1024] } else { &[256, 512] };
    // The default run of each size, against which both the refined retraction and the run
    // without relaxation are set.
    let defaults = compared
        .iter()
        .map(|&n| rough_sphere_pull_off(n, threads, false))
        .collect::<Result<Vec<_>>>()?;
    for (&n, default) in compared.iter().zip(&defaults) {
        refined_vs_fine(n, default, threads, rows)?;
    }

    println!(
        "   local relaxation ({}: each round's released tension relaxed on 16² windows",
        tack_fields::SOLVER_LOCAL_RELAXATION
    );
    println!("   before the next solve; off, so are the predicted releases) against none:");
    let relaxation = Lever {
        field: tack_fields::SOLVER_LOCAL_RELAXATION,
        table: "local_relaxation",
        without: "no relaxation",
    };
    for (&n, default) in compared.iter().zip(&defaults) {
        default_vs_without(n, default, threads, &relaxation, rows)?;
    }
    println!(
        "   predicted releases ({}: what the relaxed tension puts past σ_c (1 + {}) released",
        tack_fields::SOLVER_CASCADE,
        tack_solver::CASCADE_MARGIN
    );
    println!("   before the next solve) against none, the same scene and threads:");
    let cascade = Lever {
        field: tack_fields::SOLVER_CASCADE,
        table: "predicted_releases",
        without: "no prediction",
    };
    for (&n, default) in compared.iter().zip(&defaults) {
        default_vs_without(n, default, threads, &cascade, rows)?;
    }
    Ok(())
}

/// Table 5 of `cargo xtask bench`: a Fig. 7 style sweep point (15 realizations, 128²,
/// H = 0.5) on 1 and 2 threads.
fn sweep_point_table(rows: &mut Vec<Row>) -> Result<()> {
    println!("5. a Fig. 7 style sweep point: 15 realizations (128², H = 0.5), 1 vs 2 threads");
    let mut one = 0.0;
    for threads in [1usize, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()?;
        let t = Instant::now();
        let forces: Vec<f64> = pool.install(|| {
            use rayon::prelude::*;
            (0..15u64)
                .into_par_iter()
                .map(|seed| rough_sphere_path(128, seed, true, true).map(|r| r.1))
                .collect::<Result<_>>()
        })?;
        let secs = t.elapsed().as_secs_f64();
        if threads == 1 {
            one = secs;
        }
        let mean = forces.iter().sum::<f64>() / forces.len() as f64;
        println!(
            "   {threads} thread(s): {secs:7.2} s  speed-up {:.2}×  mean F_min {mean:.6e}",
            one / secs
        );
        rows.push(Row {
            table: "sweep_point",
            label: format!("{threads} threads"),
            fields: vec![
                ("threads", threads as f64),
                ("seconds", secs),
                ("speed_up", one / secs),
                ("mean_pull_off", mean),
            ],
        });
    }
    Ok(())
}

/// One non-adhesive solve from a cold start: (seconds, fine-grid iterations, area fraction,
/// force, converged).
fn contact_solve(
    surface: &tack_geometry::Surface,
    d: f64,
    method: tack_solver::ContactMethod,
    coarse: bool,
    crop: bool,
) -> Result<(f64, usize, f64, f64, bool)> {
    use tack_solver::{ContactSolver, SolverOptions};
    let grid = *surface.grid();
    let t = Instant::now();
    let op = operator_for(grid, 1.0)?;
    let mut s = ContactSolver::with_method(op, surface, SolverOptions::default(), method)?;
    s.set_coarse_start(coarse);
    s.set_crop(crop);
    let st = s.solve(d)?;
    Ok((
        t.elapsed().as_secs_f64(),
        st.iterations,
        st.n_contact as f64 / grid.len() as f64,
        st.force,
        st.converged,
    ))
}

/// `cargo xtask bench-contact [N]`: non-adhesive contact of an N² periodic self-affine surface
/// (H = 0.8, q0 = 2π/L, q1 = π/Δx, about 7% contact) by both methods, and an N² free-boundary
/// Hertz contact (contact radius N/8 elements), each method plain, with the coarse-to-fine
/// start, and cropped to where contact can occur. Times include building the operator.
pub fn contact(args: &[String]) -> Result<Vec<Row>> {
    let n: usize = args.first().map_or(Ok(1024), |a| a.parse())?;
    let mut rows = Vec::new();
    periodic_scaling(&[n], n, &mut rows)?;
    rows.extend(hertz_only(n)?);
    Ok(rows)
}

/// Free Hertz on an `n²` grid, contact radius n/8 elements, both methods, plain, with the
/// coarse-to-fine start, cropped, and both.
fn hertz_only(n: usize) -> Result<Vec<Row>> {
    use tack_geometry::{Sphere, Surface};
    use tack_solver::ContactMethod;
    let mut rows = Vec::new();
    // Free Hertz: R = 1, Δx = 1/n, contact radius a = n/8 elements: d = a²/R.
    let grid = Grid::square(n, 1.0 / n as f64, Boundary::Free)?;
    let surface = Surface::from_shape(grid, &Sphere::new(1.0)?);
    let a: f64 = 0.125;
    let d = a * a;
    let hertz = 4.0 / 3.0 * a.powi(3);
    let t_pair = median_time(bare_fft_pair(n, n));
    for method in [ContactMethod::PolonskyKeer, ContactMethod::ActiveSet] {
        for (label, coarse, crop) in [
            ("plain", false, false),
            ("coarse-to-fine", true, false),
            ("cropped", false, true),
            ("cropped + c2f", true, true),
        ] {
            let (secs, its, _, force, ok) = contact_solve(&surface, d, method, coarse, crop)?;
            println!(
                "   Hertz {n}² free (a = n/8) {:<13} {label:<15} {secs:7.3} s {its:>5} \
                 iterations, {:6.1} pairs of {n}², force error {:+.2e}{}",
                format!("{method:?}"),
                secs / t_pair,
                force / hertz - 1.0,
                if ok { "" } else { " NOT CONVERGED" }
            );
            rows.push(Row {
                table: "hertz",
                label: format!("Hertz {n}² free {method:?} {label}"),
                fields: vec![
                    ("n", n as f64),
                    ("seconds", secs),
                    ("iterations", its as f64),
                    ("fft_pairs", secs / t_pair),
                    ("force_error", force / hertz - 1.0),
                ],
            });
        }
    }
    Ok(rows)
}

/// The crop / sub-grid table of a sphere + H = 0.5 roughness pull-off on an `n²` L = R grid.
fn rough_table(n: usize) -> Result<Vec<Row>> {
    let mut rows = Vec::new();
    let mut reference = None;
    for (crop, sub) in [(false, false), (true, false), (false, true), (true, true)] {
        let (secs, force, its) = rough_sphere_path(n, 1, crop, sub)?;
        let base = *reference.get_or_insert(secs);
        let label = format!("{n}² crop={crop} subgrid={sub}");
        println!(
            "   {label:<28} {secs:8.2} s  speed-up {:5.2}×  {its:>6} CG iterations  F_min {force:.6e}",
            base / secs
        );
        rows.push(Row {
            table: "rough_sphere",
            label,
            fields: vec![
                ("seconds", secs),
                ("speed_up", base / secs),
                ("pull_off_force", force),
            ],
        });
    }

    Ok(rows)
}

/// `cargo xtask bench-rough [N]`: the crop / sub-grid table alone (default N = 512).
pub fn rough(args: &[String]) -> Result<()> {
    let n: usize = args.first().map_or(Ok(512), |a| a.parse())?;
    println!(
        "sphere + random roughness (H = 0.5, L = R) pull-off path on {n}²: crop and sub-grid CG"
    );
    rough_table(n).map(|_| ())
}

/// The rough-sphere pull-off of `cargo xtask bench` on an `n²` grid: R = 1 on a free L = R grid,
/// random roughness H = 0.5, h = 0.0052, seed 1, E* = 1, γ = 1.44868e-4 (a_c ≈ 0.078 R), one
/// load step to d = 0.02255, retraction by 5.5e-4 while compressive and 5.5e-5 once tensile.
/// `round_tolerance = 0` runs the exact detach/attach loop (the previous version).
pub(crate) fn rough_sphere_scene(n: usize, exact_rounds: bool) -> Result<tack::Scene> {
    let solver = if exact_rounds {
        "[solver]\nround_tolerance = 0\n"
    } else {
        ""
    };
    let text = format!(
        "version = 1\n[material]\ne_star = 1.0\ngamma = 1.44868e-4\n[geometry]\nshape = \"sphere\"\n\
         radius = 1.0\n[roughness]\nkind = \"random\"\nh = 0.0052\nhurst = 0.5\nseed = 1\n[grid]\n\
         n = {n}\ndx = {}\nboundary = \"free\"\n[protocol]\nstart = 0.02255\nmax_approach = 0.02255\n\
         load_step = 0.02255\ncoarse_unload_step = 5.5e-4\nunload_step = 5.5e-5\n[output]\n\
         snapshots = \"none\"\n{solver}",
        1.0 / n as f64
    );
    Ok(tack::Scene::parse(&text, ".", &[])?)
}

/// One rough-sphere pull-off run: (seconds, CG iterations, rounds, steps, pull-off force bits).
pub(crate) struct PullOffRun {
    pub(crate) seconds: f64,
    cg: usize,
    rounds: usize,
    pub(crate) steps: usize,
    pub(crate) force: f64,
    /// Every step's force, approach and bonded count, hashed bit for bit.
    curve: u64,
    /// Peak heap bytes the run held (see [`with_peak`]).
    peak_bytes: f64,
}

fn rough_sphere_pull_off(n: usize, threads: usize, exact_rounds: bool) -> Result<PullOffRun> {
    timed_pull_off(&rough_sphere_scene(n, exact_rounds)?, threads)
}

/// Runs `scene` on `threads` and times it; the path must complete with every step converged.
pub(crate) fn timed_pull_off(scene: &tack::Scene, threads: usize) -> Result<PullOffRun> {
    let options = tack::RunOptions {
        threads: Some(threads),
        ..tack::RunOptions::default()
    };
    let ((out, seconds), peak_bytes) = with_peak(|| {
        let t = Instant::now();
        let out = tack::run(scene, &options, &mut ())?;
        Ok((out, t.elapsed().as_secs_f64()))
    })?;
    anyhow::ensure!(
        out.path.completed && out.path.all_converged(),
        "{}²: not converged",
        scene.file.grid.n.unwrap_or(0)
    );
    Ok(PullOffRun {
        seconds,
        cg: out.path.cg_iterations(),
        rounds: out
            .path
            .records
            .iter()
            .map(|r| r.active_set_iterations)
            .sum(),
        steps: out.path.records.len(),
        force: out.path.pull_off_force(),
        curve: {
            use std::hash::{DefaultHasher, Hash, Hasher};
            let mut h = DefaultHasher::new();
            for r in &out.path.records {
                (r.force.to_bits(), r.approach.to_bits(), r.n_bonded).hash(&mut h);
            }
            h.finish()
        },
        peak_bytes,
    })
}

/// Table A: the rough-sphere pull-off against n (time, CG iterations, growth per doubling,
/// FFT-pair equivalents of 1024²), the exact rounds (previous version) at 256² and 512², and
/// the speed-up of 2 threads.
fn pull_off_scaling(sizes: &[usize], threads: usize, rows: &mut Vec<Row>) -> Result<()> {
    let t_pair = median_time(bare_fft_pair(1024, 1024));
    let t_numpy = numpy_fft_pair(1024).unwrap_or(f64::NAN);
    println!(
        "   (bare 1024² rfft2 + irfft2 pair: {:.2} ms; numpy's: {:.2} ms; {threads} thread(s))",
        t_pair * 1e3,
        t_numpy * 1e3
    );
    println!(
        "   {:>6} {:>9} {:>9} {:>8} {:>6} {:>10} {:>12} {:>12} {:>14} {:>9} {:>7}",
        "n",
        "time [s]",
        "× prev n",
        "CG",
        "steps",
        "rounds",
        "1024² pairs",
        "numpy pairs",
        "F_pull-off",
        "peak [MB]",
        "B/elem"
    );
    let mut prev: Option<f64> = None;
    for &n in sizes {
        let r = rough_sphere_pull_off(n, threads, false)?;
        let growth = prev.map_or(f64::NAN, |p| r.seconds / p);
        prev = Some(r.seconds);
        let peak = r.peak_bytes;
        let per_element = peak / (n * n) as f64;
        println!(
            "   {n:>6} {:>9.2} {growth:>9.2} {:>8} {:>6} {:>10} {:>12.0} {:>12.0} {:>14.7e} {:>9.0} {per_element:>7.0}",
            r.seconds,
            r.cg,
            r.steps,
            r.rounds,
            r.seconds / t_pair,
            r.seconds / t_numpy,
            r.force,
            peak / 1e6
        );
        rows.push(Row {
            table: "pull_off_scaling",
            label: format!("{n}²"),
            fields: vec![
                ("n", n as f64),
                ("seconds", r.seconds),
                ("growth_per_doubling", growth),
                ("cg_iterations", r.cg as f64),
                ("rounds", r.rounds as f64),
                ("steps", r.steps as f64),
                ("fft_pairs_1024", r.seconds / t_pair),
                ("numpy_pairs_1024", r.seconds / t_numpy),
                ("pull_off_force", r.force),
                ("threads", threads as f64),
                ("peak_bytes", peak),
                ("bytes_per_element", per_element),
            ],
        });
    }
    Ok(())
}

/// The bench's rough-sphere pull-off at `n²` with the scene assignment `set` on top.
fn rough_sphere_pull_off_with(n: usize, threads: usize, set: String) -> Result<PullOffRun> {
    let scene = rough_sphere_scene(n, false)?;
    timed_pull_off(&tack::Scene::parse(&scene.text, ".", &[set])?, threads)
}

/// The bench's rough-sphere pull-off at `n²` on its fixed fine retraction (`fine`, the default
/// run) and refined (`protocol.refine_pull_off`, the same steps: coarse 5.5e-4, fine 5.5e-5).
fn refined_vs_fine(n: usize, fine: &PullOffRun, threads: usize, rows: &mut Vec<Row>) -> Result<()> {
    let set = format!("{}=true", tack_fields::PROTOCOL_REFINE_PULL_OFF);
    let refined = rough_sphere_pull_off_with(n, threads, set)?;
    let same = fine.force.to_bits() == refined.force.to_bits();
    println!(
        "   {n}²: fine {:.2} s ({} steps, {} CG), refined {:.2} s ({} steps, {} CG): {:.2}× \
         faster, pull-off {:.7e} vs {:.7e} ({})",
        fine.seconds,
        fine.steps,
        fine.cg,
        refined.seconds,
        refined.steps,
        refined.cg,
        fine.seconds / refined.seconds,
        fine.force,
        refined.force,
        if same {
            "same bits".to_string()
        } else {
            // The fine path restarts its lattice at the first tensile step, `d₀ − k·Δd`; the
            // refined one solves `max − n·Δd`: the same approaches up to round-off.
            format!("{:+.1e}", refined.force / fine.force - 1.0)
        }
    );
    rows.push(Row {
        table: "refined_retraction",
        label: format!("{n}²"),
        fields: vec![
            ("fine_seconds", fine.seconds),
            ("refined_seconds", refined.seconds),
            ("speed_up", fine.seconds / refined.seconds),
            ("fine_steps", fine.steps as f64),
            ("refined_steps", refined.steps as f64),
            ("fine_pull_off", fine.force),
            ("refined_pull_off", refined.force),
            ("same_bits", if same { 1.0 } else { 0.0 }),
            ("relative_change", refined.force / fine.force - 1.0),
        ],
    });
    Ok(())
}

/// A lever of the round loop that the default run has on, switched off by `field = false`:
/// its `table` in `results/bench.json` and what the run without it is called.
struct Lever {
    field: &'static str,
    table: &'static str,
    without: &'static str,
}

/// The bench's rough-sphere pull-off at `n²` by the default run (`on`) and with `lever` off.
fn default_vs_without(
    n: usize,
    on: &PullOffRun,
    threads: usize,
    lever: &Lever,
    rows: &mut Vec<Row>,
) -> Result<()> {
    let off = rough_sphere_pull_off_with(n, threads, format!("{}=false", lever.field))?;
    let change = on.force / off.force - 1.0;
    println!(
        "   {n}²: {} {:.2} s ({} CG, {} rounds), default {:.2} s ({} CG, {} rounds): {:.2}× \
         faster, pull-off {:.7e} vs {:.7e} ({change:+.1e})",
        lever.without,
        off.seconds,
        off.cg,
        off.rounds,
        on.seconds,
        on.cg,
        on.rounds,
        off.seconds / on.seconds,
        off.force,
        on.force,
    );
    rows.push(Row {
        table: lever.table,
        label: format!("{n}²"),
        fields: vec![
            ("off_seconds", off.seconds),
            ("on_seconds", on.seconds),
            ("speed_up", off.seconds / on.seconds),
            ("off_cg", off.cg as f64),
            ("on_cg", on.cg as f64),
            ("off_rounds", off.rounds as f64),
            ("on_rounds", on.rounds as f64),
            ("off_pull_off", off.force),
            ("on_pull_off", on.force),
            ("relative_change", change),
        ],
    });
    Ok(())
}

fn pull_off_before_after(n: usize, rows: &mut Vec<Row>) -> Result<()> {
    let exact = rough_sphere_pull_off(n, 1, true)?;
    let inexact = rough_sphere_pull_off(n, 1, false)?;
    println!(
        "   {n}²: exact rounds {:.2} s ({} CG), inexact {:.2} s ({} CG): {:.2}× faster, pull-off \
         {:.7e} vs {:.7e} ({:+.1e})",
        exact.seconds,
        exact.cg,
        inexact.seconds,
        inexact.cg,
        exact.seconds / inexact.seconds,
        exact.force,
        inexact.force,
        inexact.force / exact.force - 1.0
    );
    rows.push(Row {
        table: "inexact_rounds",
        label: format!("{n}²"),
        fields: vec![
            ("exact_seconds", exact.seconds),
            ("inexact_seconds", inexact.seconds),
            ("speed_up", exact.seconds / inexact.seconds),
            ("exact_pull_off", exact.force),
            ("inexact_pull_off", inexact.force),
        ],
    });
    Ok(())
}

/// The periodic self-affine surface of the contact benchmark (H = 0.8, q0 = 2π/L, q1 = π/Δx,
/// h = 1e-3, seed 7) and the approach of about 7% contact (bisection with warm starts).
fn periodic_rough(n: usize) -> Result<(tack_geometry::Surface, f64)> {
    use tack_geometry::{RoughSpec, Surface, rough_surface};
    use tack_solver::{ContactSolver, SolverOptions};
    let grid = Grid::square(n, 1.0 / n as f64, Boundary::Periodic)?;
    let surface = Surface::new(
        grid,
        rough_surface(grid, &RoughSpec::paper_defaults(grid, 1e-3, 0.8, 7))?
            .heights()
            .clone(),
    )?;
    let mut s = ContactSolver::new(operator_for(grid, 1.0)?, &surface, SolverOptions::default())?;
    let (mut lo, mut hi) = (surface.min(), surface.heights().mean().unwrap_or(0.0));
    let mut d = 0.5 * (lo + hi);
    for _ in 0..40 {
        d = 0.5 * (lo + hi);
        let frac = s.solve(d)?.n_contact as f64 / grid.len() as f64;
        if (frac - 0.07).abs() < 0.002 {
            break;
        }
        if frac < 0.07 { lo = d } else { hi = d }
    }
    Ok((surface, d))
}

/// Table B: periodic rough non-adhesive contact at ~7% area, n = 256 … 2048: iterations and
/// FFT-pair equivalents of the active set; Polonsky–Keer alongside up to `pk_max`.
fn periodic_scaling(sizes: &[usize], pk_max: usize, rows: &mut Vec<Row>) -> Result<()> {
    use tack_solver::ContactMethod;
    println!(
        "   {:>6} {:>16} {:>9} {:>6} {:>10} {:>12} {:>9} {:>16} {:>9} {:>7}",
        "n",
        "method",
        "time [s]",
        "CG",
        "pairs (n²)",
        "numpy pairs",
        "contact",
        "force",
        "peak [MB]",
        "B/elem"
    );
    for &n in sizes {
        let (surface, d) = periodic_rough(n)?;
        let t_pair = median_time(bare_fft_pair(n, n));
        // numpy's pair of the same size, up to 2048² (4096² takes seconds a transform).
        let t_numpy = if n <= 2048 {
            numpy_fft_pair(n).unwrap_or(f64::NAN)
        } else {
            f64::NAN
        };
        for method in [ContactMethod::ActiveSet, ContactMethod::PolonskyKeer] {
            if method == ContactMethod::PolonskyKeer && n > pk_max {
                continue;
            }
            let ((secs, its, frac, force, ok), peak) =
                with_peak(|| contact_solve(&surface, d, method, true, true))?;
            anyhow::ensure!(ok, "{n}² {method:?}: not converged");
            let per_element = peak / (n * n) as f64;
            println!(
                "   {n:>6} {:>16} {secs:>9.3} {its:>6} {:>10.1} {:>12.1} {:>8.2}% {force:>16.9e} {:>9.0} {per_element:>7.0}",
                format!("{method:?}"),
                secs / t_pair,
                secs / t_numpy,
                100.0 * frac,
                peak / 1e6
            );
            rows.push(Row {
                table: "periodic_contact",
                label: format!("{n}² {method:?}"),
                fields: vec![
                    ("n", n as f64),
                    ("seconds", secs),
                    ("iterations", its as f64),
                    ("fft_pairs", secs / t_pair),
                    ("numpy_pairs", secs / t_numpy),
                    ("contact_fraction", frac),
                    ("force", force),
                    ("peak_bytes", peak),
                    ("bytes_per_element", per_element),
                ],
            });
        }
    }
    Ok(())
}

/// Table C: 1 against 2 threads on one run; every step's force, approach and bonded count
/// (rough sphere) and the force (periodic contact) must agree bit for bit.
fn thread_speed_up(rough: &[usize], periodic: &[usize], rows: &mut Vec<Row>) -> Result<()> {
    use tack_solver::ContactMethod;
    let mut cases = Vec::new();
    for &n in rough {
        let one = rough_sphere_pull_off(n, 1, false)?;
        let two = rough_sphere_pull_off(n, 2, false)?;
        let same = one.curve == two.curve && one.cg == two.cg;
        anyhow::ensure!(same, "{n}² rough sphere: 1 and 2 threads differ");
        cases.push((
            format!("{n}² rough-sphere pull-off"),
            one.seconds,
            two.seconds,
        ));
    }
    for &n in periodic {
        let (surface, d) = periodic_rough(n)?;
        let in_pool = |threads: usize| -> Result<(f64, usize, f64, f64, bool)> {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()?;
            pool.install(|| contact_solve(&surface, d, ContactMethod::ActiveSet, true, true))
        };
        let (p1, p2) = (in_pool(1)?, in_pool(2)?);
        anyhow::ensure!(
            p1.3.to_bits() == p2.3.to_bits() && p1.1 == p2.1,
            "{n}² periodic: 1 and 2 threads differ"
        );
        cases.push((format!("{n}² periodic contact"), p1.0, p2.0));
    }
    for (label, t1, t2) in cases {
        println!(
            "   {label:<28} 1 thread {t1:7.2} s, 2 threads {t2:7.2} s: {:.2}× (bit-identical)",
            t1 / t2
        );
        rows.push(Row {
            table: "threads",
            label,
            fields: vec![
                ("one_thread", t1),
                ("two_threads", t2),
                ("speed_up", t1 / t2),
                ("bit_identical", 1.0),
            ],
        });
    }
    Ok(())
}

/// The paths of `cargo xtask bench-dugdale`'s smooth sphere.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum DugdaleRun {
    /// From out of range to d = 1 and back, steps of 0.02.
    Cycle,
    /// `ApproachPath::pull_off_only(1, 0.1, 0.02)`.
    PullOff,
    /// `ApproachPath::pull_off_refined(1, 0.2, 0.02)`.
    Refined,
}

/// Maugis λ of the Dugdale bench sphere: Tabor μ = 3 (λ = 1.16 μ).
const DUGDALE_LAMBDA: f64 = 3.0 * 1.16;

/// One Dugdale smooth-sphere run for `cargo xtask bench-dugdale`: R = E* = γ = 1 at Maugis
/// λ = 3.48 (Tabor μ = λ/1.16 = 3) on an `n²` free grid of half-width 3, on the path `run`
/// ([`DugdaleRun`]). Returns (seconds, steps, CG, rounds, pull-off force).
fn dugdale_sphere(n: usize, run: DugdaleRun) -> Result<(f64, usize, usize, usize, f64)> {
    use tack_geometry::{Sphere, Surface};
    use tack_solver::{
        AdhesionLaw, AdhesiveOptions, AdhesiveSolver, ApproachPath, Dugdale, SnapshotRequest,
    };
    let lambda = DUGDALE_LAMBDA;
    let sigma0 = lambda / tack_analytics::maugis_lambda(1.0, 1.0, 1.0, 1.0);
    let grid = Grid::square(n, 6.0 / n as f64, Boundary::Free)?;
    let surface = Surface::from_shape(grid, &Sphere::new(1.0)?);
    let t = Instant::now();
    let op = operator_for(grid, 1.0)?;
    let law = AdhesionLaw::Dugdale(Dugdale { sigma0 });
    let mut solver = AdhesiveSolver::with_law(op, &surface, 1.0, law, AdhesiveOptions::default())?;
    let step = 0.02;
    let path = if run == DugdaleRun::Cycle {
        ApproachPath {
            start: -1.0 / sigma0 - step,
            max_approach: 1.0,
            load_step: step,
            unload_step: step,
            coarse_unload_step: None,
            refine_pull_off: false,
            retract_to: None,
            max_steps: 100_000,
        }
    } else if run == DugdaleRun::PullOff {
        ApproachPath::pull_off_only(1.0, 0.1, step)?
    } else {
        ApproachPath::pull_off_refined(1.0, 0.2, step)?
    };
    let r = solver.run_path(&path, &SnapshotRequest::None, &mut ())?;
    let seconds = t.elapsed().as_secs_f64();
    anyhow::ensure!(r.completed && r.all_converged(), "{n}²: not converged");
    let rounds = r.records.iter().map(|s| s.active_set_iterations).sum();
    Ok((
        seconds,
        r.records.len(),
        r.cg_iterations(),
        rounds,
        r.pull_off_force(),
    ))
}

/// The bench's rough-sphere scene (`rough_sphere_scene`) under the Dugdale law at λ = 3 of
/// R = 1, on the JKR-limit run's own path (one load step, the same retraction).
fn dugdale_rough(n: usize) -> Result<PullOffRun> {
    let scene = rough_sphere_scene(n, false)?;
    let sets = crate::study::dugdale_sets(scene.file.material.gamma, Some(3.0));
    let scene = tack::Scene::parse(&scene.text, ".", &sets)?;
    timed_pull_off(&scene, rayon::current_num_threads())
}

/// `cargo xtask bench-dugdale [N...]`: the Dugdale smooth sphere at Tabor μ = 3 on each `N²`,
/// the cycle and the pull-off protocol, (default 128 256 512) against the bare FFT pair of its padded size, and the Dugdale
/// rough-sphere pull-off at 256² against the JKR-limit run of the same scene and path.
pub fn dugdale(args: &[String]) -> Result<()> {
    let mut rows = Vec::new();
    dugdale_tables(args, &mut rows)
}

fn dugdale_tables(args: &[String], rows: &mut Vec<Row>) -> Result<()> {
    let sizes: Vec<usize> = if args.is_empty() {
        vec![128, 256, 512]
    } else {
        args.iter().map(|a| a.parse()).collect::<Result<_, _>>()?
    };
    let f_md = std::f64::consts::PI * tack_analytics::maugis_pull_off_hat(DUGDALE_LAMBDA);
    println!(
        "D1. Dugdale smooth sphere, Tabor μ = 3 (λ = 3.48): the cycle in steps of 0.02 d̂, and"
    );
    println!(
        "    the pull-off protocol (one step to d = 1, retraction in steps of 0.1, 0.02 once tensile)"
    );
    println!(
        "    and refined (steps of 0.2 all the way, the brackets that may hold the pull-off retraced by 0.02)"
    );
    println!(
        "   {:>5} {:>8} {:>9} {:>6} {:>7} {:>7} {:>11} {:>10}",
        "n", "run", "time [s]", "steps", "CG", "rounds", "FFT pairs", "F/F_MD − 1"
    );
    for &n in &sizes {
        let m = tack_kernels::padded_size(n);
        let t_pair = median_time(bare_fft_pair(m, m));
        for (label, run, table) in [
            ("cycle", DugdaleRun::Cycle, "dugdale_sphere"),
            ("pull-off", DugdaleRun::PullOff, "dugdale_sphere_pull_off"),
            ("refined", DugdaleRun::Refined, "dugdale_sphere_refined"),
        ] {
            let (seconds, steps, cg, rounds, force) = dugdale_sphere(n, run)?;
            let err = force / f_md - 1.0;
            println!(
                "   {n:>5} {label:>8} {seconds:>9.2} {steps:>6} {cg:>7} {rounds:>7} {:>11.0} {err:>+10.4}",
                seconds / t_pair
            );
            rows.push(Row {
                table,
                label: format!("{n}²"),
                fields: vec![
                    ("n", n as f64),
                    ("seconds", seconds),
                    ("steps", steps as f64),
                    ("cg_iterations", cg as f64),
                    ("rounds", rounds as f64),
                    ("fft_pairs", seconds / t_pair),
                    ("pull_off_force", force),
                    ("pull_off_error", err),
                ],
            });
        }
    }
    println!("D2. rough sphere 256² (bench scene, seed 1): Dugdale λ = 3 vs the zero-range run");
    let jkr = rough_sphere_pull_off(256, rayon::current_num_threads(), false)?;
    let dug = dugdale_rough(256)?;
    for (label, r) in [("jkr_limit", &jkr), ("dugdale", &dug)] {
        println!(
            "   {label:<10} {:7.2} s  {:6} CG  {:5} rounds  {:4} steps  F = {:+.5e}",
            r.seconds, r.cg, r.rounds, r.steps, r.force
        );
        rows.push(Row {
            table: "dugdale_rough",
            label: label.into(),
            fields: vec![
                ("seconds", r.seconds),
                ("cg_iterations", r.cg as f64),
                ("rounds", r.rounds as f64),
                ("steps", r.steps as f64),
                ("pull_off_force", r.force),
            ],
        });
    }
    println!(
        "   Dugdale / zero-range time: {:.2}",
        dug.seconds / jkr.seconds
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_peak_counts_what_a_run_held_not_what_came_before() {
        // Other tests allocate on other threads meanwhile: 64 MiB against loose bounds.
        let size = 64usize << 20;
        let before = vec![1u8; size];
        let ((), peak) = with_peak(|| {
            let held = vec![1u8; size];
            std::hint::black_box(&held);
            Ok(())
        })
        .unwrap();
        std::hint::black_box(&before);
        let peak = peak / size as f64;
        assert!((0.75..1.5).contains(&peak), "{peak} × the allocation");
    }
}
