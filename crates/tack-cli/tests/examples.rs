//! End to end: every example scene runs with `tack run`, its result file is described by
//! `tack info`, plotted by `tack plot`, read back by tack-io (and by h5py when installed), and
//! carries provenance and a summary that fit the scene.

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::{Scratch, examples_dir, files_with_extension, have_h5py, run, text};

/// The examples this file tests, one `#[test]` each (see `example!`).
const EXAMPLES: [&str; 16] = [
    "cone",
    "dugdale_sphere",
    "elliptic_tip",
    "exponential_sphere",
    "flat_punch",
    "patterned_punch",
    "smooth_jkr_sphere",
    "smoothed_dugdale_sphere",
    "soft_film",
    "sphere_gamma_checkerboard",
    "sphere_gamma_random",
    "sphere_gamma_stripes",
    "sphere_random_roughness",
    "sphere_waviness_2d",
    "viscoelastic_sphere",
    "wavy_1d_periodic",
];

/// Runs the full pipeline on one example and returns the result read back.
fn pipeline(name: &str) -> (tack_io::RunResult, String) {
    let scratch = Scratch::new(&format!("example-{name}"));
    let scene = examples_dir().join(format!("{name}.toml"));
    let out = scratch.join(&format!("{name}.h5"));
    let fig = scratch.join(&format!("{name}.svg"));
    let s = |p: &Path| p.to_str().expect("utf-8 path").to_owned();

    let o = run(&["run", &s(&scene), "-o", &s(&out), "--quiet"]);
    let (stdout, stderr) = text(&o);
    assert!(o.status.success(), "tack run {name}: {stderr}");
    assert!(stdout.contains("pull-off"), "{stdout}");
    assert!(stdout.contains("converged"), "{stdout}");
    assert!(out.is_file(), "{name}: no result file");
    assert_eq!(
        scratch.files(),
        vec![format!("{name}.h5")],
        "stray files next to the result"
    );

    let o = run(&["info", &s(&out)]);
    let (info, stderr) = text(&o);
    assert!(o.status.success(), "tack info {name}: {stderr}");
    assert!(
        info.contains("curve:") && info.contains("summary:"),
        "{info}"
    );

    let o = run(&["plot", &s(&out), "-o", &s(&fig)]);
    assert!(o.status.success(), "tack plot {name}: {}", text(&o).1);
    let svg = std::fs::read_to_string(&fig).expect("the figure was not written");
    assert!(
        svg.contains("<svg") && svg.contains("</svg>"),
        "{name}: not SVG"
    );
    assert!(svg.contains("approach"), "{name}: axis label missing");

    let result = tack_io::read_result(&out).expect("tack-io cannot read the result");
    let text_of_scene = std::fs::read_to_string(&scene).expect("scene");
    let p = &result.provenance;
    assert_eq!(p.scene, text_of_scene, "the scene is recorded verbatim");
    assert!(p.command_line.contains("run") && p.command_line.contains(name));
    assert!(!p.git_revision.is_empty());
    assert_eq!(p.tack_version, env!("CARGO_PKG_VERSION"));
    assert!(
        p.created.len() == 20 && p.created.ends_with('Z') && p.created.as_bytes()[10] == b'T',
        "created = {}",
        p.created
    );
    let c = &result.curve;
    assert!(c.len() > 10, "{name}: only {} steps", c.len());
    assert!(
        c.converged.iter().all(|&ok| ok),
        "{name}: non-converged steps"
    );
    let min = c.force.iter().copied().fold(f64::INFINITY, f64::min);
    assert_eq!(result.summary.pull_off_force, min);
    assert!(min < 0.0, "{name}: no adhesive pull-off");
    assert!(result.surface.is_some(), "{name}: surface not stored");
    assert!(!result.snapshots.is_empty(), "{name}: no snapshots");

    if have_h5py(&format!("the h5py check of {name}")) {
        check_with_h5py(&out, c.len());
    }
    (result, info)
}

/// h5py (no tack code) reads the curve and the attributes.
fn check_with_h5py(file: &Path, steps: usize) {
    let script = "import h5py, sys\n\
                  with h5py.File(sys.argv[1], 'r') as f:\n\
                  \x20   print(len(f['curve/force']), len(f['curve/approach']))\n\
                  \x20   print(','.join(sorted(f.attrs.keys())))\n\
                  \x20   print(','.join(sorted(f['summary'].attrs.keys())))\n\
                  \x20   print(f.attrs['scene'][:11])\n";
    let o = Command::new("python3")
        .args(["-c", script])
        .arg(file)
        .output()
        .expect("python3");
    let (stdout, stderr) = text(&o);
    assert!(o.status.success(), "h5py failed: {stderr}");
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines[0], format!("{steps} {steps}"), "{stdout}");
    for attr in [
        "command_line",
        "created",
        "git_revision",
        "scene",
        "tack_version",
    ] {
        assert!(lines[1].split(',').any(|a| a == attr), "{attr}: {stdout}");
    }
    for attr in ["f_jkr", "pull_off_force", "pull_off_ratio"] {
        assert!(lines[2].split(',').any(|a| a == attr), "{attr}: {stdout}");
    }
}

macro_rules! example {
    ($name:ident, $check:expr) => {
        #[test]
        fn $name() {
            let (result, info) = pipeline(stringify!($name));
            let check: fn(&tack_io::RunResult, &str) = $check;
            check(&result, &info);
        }
    };
}

example!(dugdale_sphere, |r, info| {
    let s = &r.summary;
    assert_eq!(s.adhesion_model.as_deref(), Some("dugdale"));
    assert!(info.contains("adhesion_model = dugdale"), "{info}");
    // λ = 1 with 6.7 elements per zone: about +12% beyond Maugis' −1.601 πγR at this mesh
    // (first order in Δx, docs/theory.md §3.7).
    let ratio = s.pull_off_force / s.extra["f_maugis"];
    assert!((1.0..1.2).contains(&ratio), "F/F_MD = {ratio}");
    assert!((s.extra["maugis_lambda"] - 1.0).abs() < 1e-3);
    // Both branches: out of range first, the jump in with tension, a loop that dissipates.
    assert_eq!(r.curve.force[0], 0.0);
    assert!(s.extra["jump_in_force"] < 0.0 && s.extra["dissipated_energy"] > 0.0);
    assert!(
        r.curve
            .law_column("n_cohesive")
            .is_some_and(|z| z.values.iter().any(|&n| n > 0))
    );
});

example!(smoothed_dugdale_sphere, |r, info| {
    let s = &r.summary;
    assert_eq!(s.adhesion_model.as_deref(), Some("smoothed_dugdale"));
    assert!(info.contains("adhesion_model = smoothed_dugdale"), "{info}");
    // The same sphere and mesh as dugdale_sphere: +0.85% beyond Maugis' −1.601 πγR, where the
    // Dugdale law is +12% (docs/theory.md §3.7); 2% bounds it.
    let ratio = s.pull_off_force / s.extra["f_maugis"];
    assert!((1.0..1.02).contains(&ratio), "F/F_MD = {ratio}");
    assert!((s.extra["maugis_lambda"] - 1.0).abs() < 1e-3);
    // The smooth laws' entries: the range h0 = γ/σ0 and the peak σ0.
    assert!((s.extra["range"] - 0.125 / 0.2218).abs() < 1e-9);
    assert!((s.extra["peak_tension"] - 0.2218).abs() < 1e-12);
    assert_eq!(r.curve.force[0], 0.0);
    assert!(s.extra["jump_in_force"] < 0.0 && s.extra["dissipated_energy"] > 0.0);
});

example!(viscoelastic_sphere, |r, info| {
    let s = &r.summary;
    assert_eq!(s.adhesion_model.as_deref(), Some("exponential"));
    assert!(info.contains("e_instantaneous"), "{info}");
    assert_eq!(s.extra["e_instantaneous"], 10.0);
    assert_eq!((s.extra["speed"], s.extra["dwell"]), (0.01, 1.0));
    // Every step's time: 0.1τ per step of 0.001 at speed 0.01, the hold of τ in 10 steps.
    let time = r.curve.time.as_ref().expect("a time column");
    assert_eq!(time.len(), r.curve.len());
    assert_eq!(time[0], 0.0);
    assert!(
        time.windows(2).all(|w| (w[1] - w[0] - 0.1).abs() < 1e-9),
        "{time:?}"
    );
    // The arms' dissipation at the crack: the pull-off beyond both elastic limits (1.12 and
    // 1.27 F_JKR at E0 and E∞ on this grid; measured 2.59 F_JKR with the hold).
    assert!(
        s.pull_off_ratio > 2.0 && s.pull_off_ratio < 3.2,
        "{}",
        s.pull_off_ratio
    );
    assert!(s.warnings.is_empty(), "{:?}", s.warnings);
});

example!(exponential_sphere, |r, info| {
    let s = &r.summary;
    assert_eq!(s.adhesion_model.as_deref(), Some("exponential"));
    assert!(info.contains("adhesion_model = exponential"), "{info}");
    assert!((s.extra["tabor_mu"] - 3.0).abs() < 1e-3);
    // μ = 3 between JKR (1.5 πγR) and DMT (2 πγR); the process zone spans 0.6 elements here,
    // which puts the pull-off about 6% above the converged 1.54 πγR (docs/theory.md §3.9).
    let hat = s.pull_off_force / (-std::f64::consts::PI * 1e-3);
    assert!((1.5..1.75).contains(&hat), "F/(πγR) = {hat}");
    assert!(s.extra["process_zone_elements"] < 1.0);
    assert!(
        s.warnings
            .iter()
            .any(|w| w.contains("under-resolved process zone")),
        "{:?}",
        s.warnings
    );
    // Both branches: the jump in with tension, a loop that dissipates, a zone of tension.
    assert!(s.extra["jump_in_force"] < 0.0 && s.extra["dissipated_energy"] > 0.0);
    assert!(
        r.curve
            .law_column("n_cohesive")
            .is_some_and(|z| z.values.iter().any(|&n| n > 0))
    );
    // The jump in is the snap into contact (the first step in contact), with most of the
    // pull-off's tension (−4.64e-3 against −5.2e-3), not the first step whose tension passes
    // 1% of the peak, 28 steps earlier at −6.4e-5, where it was reported before.
    let first = r
        .curve
        .n_bonded
        .iter()
        .position(|&n| n > 0)
        .expect("contact");
    assert_eq!(s.extra["jump_in_approach"], r.curve.approach[first]);
    assert!(
        s.extra["jump_in_force"] < 0.5 * s.pull_off_force,
        "{} against {}",
        s.extra["jump_in_force"],
        s.pull_off_force
    );
});

example!(cone, |r, _| {
    let s = &r.summary;
    assert!(
        s.f_jkr.is_nan() && s.pull_off_ratio.is_nan(),
        "not a sphere"
    );
    // The exact MDR pull-off of the cone c·r (c = 0.5, E* = 1, γ = 0.05): −0.3438 N; the
    // criterion is +25.4% above it at a_F/Δx = 11.5 (measured 1.2543; +21% at a_F/Δx = 10 in
    // power_law.rs: the cone is not yet monotone in Δx at these meshes). Tolerance ±0.03.
    let f_mdr = s.extra["f_mdr"];
    assert!((f_mdr + 0.343775).abs() < 1e-6, "{f_mdr}");
    let ratio = s.pull_off_force / f_mdr;
    assert!((1.2243..1.2843).contains(&ratio), "F/F_MDR = {ratio}");
});

example!(patterned_punch, |r, info| {
    let s = &r.summary;
    // Rim γ = 0.01 on 0.7 < r ≤ 1, core γ = 0.08: the exact zero-range pull-off is the core's
    // Kendall force √(8π r1³E*γ_core) = 0.8305 N (crates/tack-solver/tests/pattern.rs);
    // measured 0.988 of it at a/Δx = 20.
    let exact = (8.0 * std::f64::consts::PI * 0.7f64.powi(3) * 0.08).sqrt();
    let ratio = -s.pull_off_force / exact;
    assert!((0.97..1.01).contains(&ratio), "F/F_exact = {ratio}");
    assert_eq!((s.extra["gamma_min"], s.extra["gamma_max"]), (0.01, 0.08));
    // The map is in the file, with the surface's shape.
    let gamma = r.gamma.as_ref().expect("/surface/gamma");
    assert_eq!(gamma.dim(), r.surface.as_ref().expect("surface").0.dim());
    assert!(info.contains("work of adhesion: 44 x 44 map"), "{info}");
});

/// A sphere whose γ is a pattern of 0.02 (`material.gamma`, the reference of F_JKR) and
/// 0.06 N/mm: its pull-off lies between the uniform spheres of either (1 and 3 F_JKR, the
/// criterion adding about +4% at a_c/Δx = 33); `measured` pins the value of this build (±2%).
fn gamma_pattern_sphere(r: &tack_io::RunResult, measured: f64) {
    let s = &r.summary;
    let ratio = s.pull_off_ratio;
    assert!((1.0..3.2).contains(&ratio), "F/F_JKR = {ratio}");
    assert!(
        (ratio / measured - 1.0).abs() < 0.02,
        "F/F_JKR = {ratio}, was {measured}"
    );
    assert_eq!(s.extra["edge_contact_steps"], 0.0);
    assert!(r.gamma.is_some(), "/surface/gamma");
}

example!(sphere_gamma_stripes, |r, _| gamma_pattern_sphere(r, 2.2125));

example!(sphere_gamma_checkerboard, |r, _| gamma_pattern_sphere(
    r, 2.4227
));

example!(sphere_gamma_random, |r, _| {
    // A log-normal field of mean 0.02 (contrast 0.5): the weak and strong patches nearly
    // balance, 1.25 F_JKR of the mean (the uniform sphere at this mesh: about 1.04).
    gamma_pattern_sphere(r, 1.2474);
    assert!((r.summary.extra["gamma_mean"] / 0.02 - 1.0).abs() < 0.01);
});

example!(elliptic_tip, |r, _| {
    let s = &r.summary;
    assert!(s.f_jkr.is_nan(), "no sphere reference for an ellipsoid");
    // Johnson–Greenwood's approximate pull-off: the criterion at this mesh is about +10%
    // above it (Richardson +6%, +3.8%: crates/tack-solver/tests/ellipsoid.rs); measured 1.0991.
    let ratio = s.pull_off_force / s.extra["f_elliptic_jkr"];
    assert!((1.07..1.13).contains(&ratio), "F/F_JG = {ratio}");
    assert_eq!(s.extra["edge_contact_steps"], 0.0);
});

example!(soft_film, |r, _| {
    let s = &r.summary;
    assert_eq!(
        (s.extra["layer_thickness"], s.extra["layer_poisson"]),
        (0.5, 0.5)
    );
    // The confined incompressible film (a/h ≈ 2 at pull-off) holds about 1.55 times the
    // half-space's F_JKR (measured 1.5510; the half-space at this mesh gives ≈ 1.07).
    assert!(
        (1.50..1.60).contains(&s.pull_off_ratio),
        "F/F_JKR = {}",
        s.pull_off_ratio
    );
});

example!(smooth_jkr_sphere, |r, _| {
    let s = &r.summary;
    assert!(s.f_jkr < 0.0);
    // Pohrt–Popov at a_c/Δx = 10 overshoots F_JKR by about 14% (docs/theory.md §9).
    assert!(
        (1.0..1.3).contains(&s.pull_off_ratio),
        "F/F_JKR = {}",
        s.pull_off_ratio
    );
    assert!(s.extra.contains_key("d_jkr"));
    assert!(s.johnson_alpha.is_none() && s.alpha_star.is_none());
    assert!(r.provenance.seed.is_none());
});

example!(wavy_1d_periodic, |r, _| {
    let s = &r.summary;
    assert!(
        s.f_jkr.is_nan() && s.pull_off_ratio.is_nan(),
        "not a sphere"
    );
    let alpha = s.johnson_alpha.expect("johnson_alpha");
    let want = tack::analytics::johnson_alpha(1.0, 5e-5, 0.01, 1.0); // = 1/π
    assert!((alpha - want).abs() < 1e-12, "{alpha}");
    // Johnson (Eq. 2) at α = 0.318: the least mean pressure is about −0.10 p*.
    let ratio = s.extra["min_mean_pressure"] / s.extra["p_star"];
    assert!((-0.2..-0.05).contains(&ratio), "p/p* = {ratio}");
    let (nx, ny) = r.surface.as_ref().expect("surface").0.dim();
    assert_eq!((nx, ny), (512, 1));
});

example!(sphere_waviness_2d, |r, _| {
    let s = &r.summary;
    assert!(s.f_jkr < 0.0 && s.pull_off_ratio > 0.0);
    let alpha = s.johnson_alpha.expect("johnson_alpha");
    assert!((alpha - 1.0).abs() < 0.01, "{alpha}");
});

example!(sphere_random_roughness, |r, info| {
    let s = &r.summary;
    assert!(s.alpha_star.is_some() && s.johnson_alpha.is_none());
    assert_eq!(r.provenance.seed, Some(1));
    assert!(info.contains("seed: 1"), "{info}");
    assert!(s.pull_off_ratio > 0.0);
});

example!(flat_punch, |r, _| {
    let s = &r.summary;
    assert!(
        s.f_jkr.is_nan() && s.pull_off_ratio.is_nan(),
        "not a sphere"
    );
    let kendall = s.extra["f_kendall"];
    let ratio = s.pull_off_force / kendall;
    assert!((0.9..1.15).contains(&ratio), "F/F_Kendall = {ratio}");
    let steps: Vec<usize> = r.snapshots.iter().map(|s| s.step).collect();
    assert_eq!(steps, [0, 50, 100]);
});

#[test]
fn every_example_scene_is_tested() {
    let found: Vec<String> = files_with_extension(&examples_dir(), "toml")
        .iter()
        .filter_map(|p| p.file_stem().map(|s| s.to_string_lossy().into_owned()))
        .collect();
    assert_eq!(found, EXAMPLES, "add a test for each example scene");
}

#[test]
fn overrides_are_applied_and_recorded() {
    let scratch = Scratch::new("overrides");
    let scene = examples_dir().join("flat_punch.toml");
    let out = scratch.join("punch.h5");
    let o = run(&[
        "run",
        scene.to_str().expect("utf-8"),
        "-o",
        out.to_str().expect("utf-8"),
        "--quiet",
        "--set",
        "protocol.unload_step=0.01",
        "--set",
        "output.snapshots=\"none\"",
        "--set",
        "output.surface=false",
    ]);
    assert!(o.status.success(), "{}", text(&o).1);
    let r = tack_io::read_result(&out).expect("read");
    assert!(r.provenance.scene.contains("unload_step = 0.01"));
    assert!(r.provenance.command_line.contains("--set"));
    assert!(r.snapshots.is_empty() && r.surface.is_none());
    let steps = r.curve.approach.windows(2).filter(|w| w[1] < w[0]).count();
    assert!(
        steps < 100,
        "the coarser unload step was not applied: {steps}"
    );
}

#[test]
fn gamma_maps_round_trip_from_result_files_not_their_heights() {
    // `tack surface` of a patterned scene stores the map (/surface/gamma) beside the heights;
    // given back as `adhesion.gamma_map` (HDF5 and text), it must be read as γ, not as heights.
    let scratch = Scratch::new("gamma-map");
    let scene = examples_dir().join("sphere_gamma_checkerboard.toml");
    let surf = scratch.join("surf.h5");
    let s = |p: &Path| p.to_str().expect("utf-8").to_owned();
    let o = run(&["surface", &s(&scene), "-o", &s(&surf)]);
    assert!(o.status.success(), "{}", text(&o).1);
    let original = tack_io::read_result(&surf).expect("read surface");
    let gamma = original.gamma.clone().expect("/surface/gamma");
    let (heights, dx) = original.surface.clone().expect("heights");
    assert_ne!(gamma, heights);
    let csv = scratch.join("gamma.csv");
    let rows: Vec<String> = gamma
        .rows()
        .into_iter()
        .map(|r| {
            r.iter()
                .map(|g| format!("{g:e}"))
                .collect::<Vec<_>>()
                .join(", ")
        })
        .collect();
    std::fs::write(&csv, format!("# dx = {dx}\n{}\n", rows.join("\n"))).expect("write csv");
    let text_of = std::fs::read_to_string(&scene).expect("scene");
    let plain: String = text_of
        .lines()
        .filter(|l| {
            !["pattern", "gamma_b", "period"]
                .iter()
                .any(|k| l.starts_with(k))
        })
        .collect::<Vec<_>>()
        .join("\n");
    for map in [&surf, &csv] {
        let file_scene = scratch.join("from_map.toml");
        let with_map = plain.replace(
            "[adhesion]",
            &format!(
                "[adhesion]\ngamma_map = \"{}\"",
                map.file_name().expect("name").to_string_lossy()
            ),
        );
        std::fs::write(&file_scene, with_map).expect("write scene");
        let again = scratch.join("again.h5");
        let o = run(&["surface", &s(&file_scene), "-o", &s(&again)]);
        assert!(o.status.success(), "{}: {}", map.display(), text(&o).1);
        let read = tack_io::read_result(&again).expect("read");
        assert_eq!(read.gamma.as_ref(), Some(&gamma), "{}", map.display());
        std::fs::remove_file(&again).expect("rm");
    }
}

/// `tack surface` output is a valid `roughness.kind = "file"` input (HDF5 and text), and the
/// heights survive the round trip exactly.
#[test]
fn surface_files_round_trip_as_height_maps() {
    let scratch = Scratch::new("surface");
    let scene = examples_dir().join("sphere_random_roughness.toml");
    let surf = scratch.join("surf.h5");
    let o = run(&[
        "surface",
        scene.to_str().expect("utf-8"),
        "-o",
        surf.to_str().expect("utf-8"),
    ]);
    assert!(o.status.success(), "{}", text(&o).1);
    let original = tack_io::read_result(&surf).expect("read surface");
    assert!(original.curve.is_empty());
    let (heights, dx) = original.surface.clone().expect("heights");
    assert_eq!(original.provenance.seed, Some(1));

    let csv = scratch.join("surf.csv");
    let rows: Vec<String> = heights
        .rows()
        .into_iter()
        .map(|r| {
            r.iter()
                .map(|h| format!("{h:e}"))
                .collect::<Vec<_>>()
                .join(", ")
        })
        .collect();
    std::fs::write(&csv, format!("# dx = {dx}\n{}\n", rows.join("\n"))).expect("write csv");

    for map in [&surf, &csv] {
        let file_scene = scratch.join("from_file.toml");
        std::fs::write(
            &file_scene,
            format!(
                "version = 1\n[material]\ne_star = 1.0\ngamma = 0.125\n[geometry]\nshape = \"none\"\n\
                 [roughness]\nkind = \"file\"\npath = \"{}\"\n[grid]\nn = {}\ndx = {dx}\n\
                 [protocol]\nmax_approach = 2.5\nload_step = 0.15\n",
                map.file_name().expect("name").to_string_lossy(),
                heights.nrows()
            ),
        )
        .expect("write scene");
        let again = scratch.join("again.h5");
        let o = run(&[
            "surface",
            file_scene.to_str().expect("utf-8"),
            "-o",
            again.to_str().expect("utf-8"),
        ]);
        assert!(o.status.success(), "{}: {}", map.display(), text(&o).1);
        let (h2, dx2) = tack_io::read_result(&again)
            .expect("read")
            .surface
            .expect("heights");
        assert_eq!(dx2, dx);
        assert_eq!(h2, heights, "{}: heights changed", map.display());
        let o = run(&["check", file_scene.to_str().expect("utf-8")]);
        assert!(o.status.success(), "{}", text(&o).1);
        std::fs::remove_file(&again).expect("rm");
    }
}

#[test]
fn help_and_version() {
    let o = run(&["--version"]);
    assert!(o.status.success());
    assert!(text(&o).0.contains(env!("CARGO_PKG_VERSION")));
    for sub in ["run", "surface", "check", "info", "plot"] {
        let o = run(&[sub, "--help"]);
        assert!(o.status.success(), "{sub} --help");
        assert!(text(&o).0.contains("Usage: tack"), "{sub}");
    }
    let o = run(&["--help"]);
    let help = text(&o).0;
    for sub in ["run", "surface", "check", "info", "plot"] {
        assert!(help.contains(sub), "{sub} missing from --help");
    }
}

/// `tack plot` refuses formats it cannot write, before touching the output.
#[test]
fn plot_rejects_unknown_formats() {
    let scratch = Scratch::new("plot-format");
    let scene = examples_dir().join("flat_punch.toml");
    let out = scratch.join("p.h5");
    let o = run(&[
        "run",
        scene.to_str().expect("utf-8"),
        "-o",
        out.to_str().expect("utf-8"),
        "--quiet",
    ]);
    assert!(o.status.success());
    let pdf: PathBuf = scratch.join("p.pdf");
    let o = run(&[
        "plot",
        out.to_str().expect("utf-8"),
        "-o",
        pdf.to_str().expect("utf-8"),
    ]);
    assert!(!o.status.success());
    assert!(text(&o).1.contains(".svg or .png"), "{}", text(&o).1);
    assert!(!pdf.exists());
}

/// Cropping changes the cost, not the answer: the rough-sphere example on a grid twice as wide
/// as it needs, with and without crop.
#[test]
fn crop_gives_the_same_pull_off() {
    let dir = common::Scratch::new("crop");
    let scene = common::examples_dir().join("sphere_random_roughness.toml");
    let mut forces = Vec::new();
    for crop in ["true", "false"] {
        let out = dir.join(&format!("crop-{crop}.h5"));
        let set = format!("grid.crop={crop}");
        let args = [
            "run",
            scene.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--quiet",
        ];
        let run = common::run(&[&args[..], &["--set", &set, "--set", "grid.n=128"]].concat());
        assert!(run.status.success(), "{:?}", common::text(&run));
        let stdout = common::text(&run).0;
        assert_eq!(crop == "true", stdout.contains("cropped to"), "{stdout}");
        forces.push(tack_io::read_result(&out).unwrap().summary.pull_off_force);
    }
    assert!(
        (forces[0] - forces[1]).abs() <= 1e-9 * forces[1].abs(),
        "{forces:?}"
    );
}
