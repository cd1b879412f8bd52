//! Parameter sweeps end to end with the built `tack` binary: sharded runs in separate processes
//! merge to the same table as one process, bit for bit; a killed sweep resumes without rerunning
//! completed points and merges to the same table; failing points are recorded and reported while
//! the others complete; bad sweep files and arguments fail with clear messages; a zipped entry
//! sets its fields together and merges to one column per field.

mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Output, Stdio};
use std::time::{Duration, Instant, SystemTime};

use common::{Scratch, run, tack, text};
use tack_io::{
    POINT_FAILED, POINT_INCOMPLETE, POINT_MISSING, POINT_OK, ParameterColumn, SweepTable,
};

/// A smooth sphere small enough that one run takes a few hundredths of a second; `unload_step`
/// sets the length of the path (and so the time per point).
fn base_scene(unload_step: f64) -> String {
    format!(
        r#"version = 1
[material]
e_star = 1.0
gamma = 0.125
[geometry]
shape = "sphere"
radius = 8.0
[grid]
n = 24
dx = 0.6
[protocol]
max_approach = 3.0
load_step = 0.15
unload_step = {unload_step}
[output]
surface = false
"#
    )
}

/// Writes `base.toml` and `sweep.toml` (which refers to it) into `dir`; returns the sweep.
fn write_sweep(dir: &Path, unload_step: f64, vary: &str) -> PathBuf {
    std::fs::write(dir.join("base.toml"), base_scene(unload_step)).expect("base scene");
    let sweep = dir.join("sweep.toml");
    let text = format!(
        "version = 1\nscene = \"base.toml\"\n\
         collect = [\"pull_off_force\", \"pull_off_ratio\", \"d_jkr\", \"alpha_star\"]\n\
         [vary]\n{vary}\n"
    );
    std::fs::write(&sweep, text).expect("sweep file");
    sweep
}

/// 4 × 3 = 12 points.
const GAMMA_RADIUS: &str = "material.gamma = { from = 0.08, to = 0.14, steps = 4 }\n\
                            geometry.radius = [7.0, 8.0, 9.0]";

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

fn assert_ok(out: &Output, what: &str) -> (String, String) {
    let (stdout, stderr) = text(out);
    assert!(
        out.status.success(),
        "{what} failed\nstdout: {stdout}\nstderr: {stderr}"
    );
    (stdout, stderr)
}

/// `tack merge dir -o out` (must succeed) and the table read back.
fn merge(dir: &Path, out: &Path) -> SweepTable {
    assert_ok(&run(&["merge", s(dir), "-o", s(out)]), "tack merge");
    tack_io::read_sweep_table(out).expect("the merged table reads back")
}

fn bits(values: &[f64]) -> Vec<u64> {
    values.iter().map(|x| x.to_bits()).collect()
}

/// The tables agree in everything but provenance, results compared bit for bit.
fn assert_same_table(a: &SweepTable, b: &SweepTable) {
    assert_eq!(a.sweep, b.sweep);
    assert_eq!(a.provenance.scene, b.provenance.scene);
    assert_eq!(a.index, b.index);
    assert_eq!(a.status, b.status);
    assert_eq!(a.error, b.error);
    assert_eq!(a.parameters, b.parameters);
    assert_eq!(a.results.len(), b.results.len());
    for ((name_a, va), (name_b, vb)) in a.results.iter().zip(&b.results) {
        assert_eq!(name_a, name_b);
        assert_eq!(bits(va), bits(vb), "/results/{name_a} differs");
    }
}

/// Result files in `dir/points`, by name.
fn point_files(dir: &Path) -> BTreeMap<String, PathBuf> {
    std::fs::read_dir(dir.join("points"))
        .map(|entries| {
            entries
                .filter_map(|e| e.ok())
                .map(|e| (e.file_name().to_string_lossy().into_owned(), e.path()))
                .collect()
        })
        .unwrap_or_default()
}

fn completed(dir: &Path) -> BTreeMap<String, PathBuf> {
    point_files(dir)
        .into_iter()
        .filter(|(name, _)| !name.starts_with('.') && name.ends_with(".h5"))
        .collect()
}

#[test]
fn shards_in_separate_processes_merge_to_the_single_process_table() {
    let scratch = Scratch::new("sweep-shards");
    let sweep = write_sweep(&scratch.0, 0.02, GAMMA_RADIUS);
    let single = scratch.join("single");
    let (stdout, _) = assert_ok(
        &run(&[
            "sweep",
            s(&sweep),
            "-o",
            s(&single),
            "--threads",
            "2",
            "--quiet",
        ]),
        "single-process sweep",
    );
    assert!(stdout.contains("12 of 12 points"), "{stdout}");
    assert!(stdout.contains("12 run, 0 failed"), "{stdout}");

    let sharded = scratch.join("sharded");
    let children: Vec<_> = (1..=4)
        .map(|i| {
            tack()
                .args(["sweep", s(&sweep), "-o", s(&sharded), "--threads", "1"])
                .args(["--shard", &format!("{i}/4")])
                .stdout(Stdio::piped())
                .stderr(Stdio::piped())
                .spawn()
                .expect("spawn a shard")
        })
        .collect();
    for (i, child) in children.into_iter().enumerate() {
        let out = child.wait_with_output().expect("shard output");
        let (stdout, _) = assert_ok(&out, &format!("shard {}/4", i + 1));
        assert!(
            stdout.contains(&format!("3 of 12 points, shard {}/4", i + 1)),
            "{stdout}"
        );
    }
    // The shards are disjoint and cover the sweep: 12 files, none twice, no temporaries.
    let names: Vec<String> = point_files(&sharded).into_keys().collect();
    let want: Vec<String> = (0..12).map(|i| format!("{i:05}.h5")).collect();
    assert_eq!(names, want);

    let a = merge(&single, &scratch.join("single.h5"));
    let b = merge(&sharded, &scratch.join("sharded.h5"));
    assert_same_table(&a, &b);
    assert_eq!(a.len(), 12);
    assert!(a.status.iter().all(|&st| st == POINT_OK));
    // Points are ordered with the first [vary] field outermost.
    assert_eq!(a.parameters[0].0, "material.gamma");
    assert_eq!(a.parameters[1].0, "geometry.radius");
    let ParameterColumn::Float(radius) = &a.parameters[1].1 else {
        panic!("radius is not f64: {:?}", a.parameters[1].1);
    };
    assert_eq!(&radius[..4], &[7.0, 8.0, 9.0, 7.0]);
    let (name, pull_off) = &a.results[0];
    assert_eq!(name, "pull_off_force");
    assert!(pull_off.iter().all(|f| *f < 0.0), "{pull_off:?}");
    // Not defined for a smooth sphere: NaN, not dropped.
    assert_eq!(a.results[3].0, "alpha_star");
    assert!(a.results[3].1.iter().all(|x| x.is_nan()));

    // The point files themselves agree bit for bit (curves), whatever the process and threads.
    for name in &want {
        let x = tack_io::read_result(&single.join("points").join(name)).expect("single point");
        let y = tack_io::read_result(&sharded.join("points").join(name)).expect("sharded point");
        assert_eq!(x.provenance.scene, y.provenance.scene);
        assert_eq!(bits(&x.curve.force), bits(&y.curve.force), "{name}");
        assert_eq!(bits(&x.curve.area), bits(&y.curve.area), "{name}");
    }
}

#[cfg(unix)]
#[test]
fn killed_sweep_resumes_without_rerunning_completed_points() {
    let scratch = Scratch::new("sweep-kill");
    // 16 points of about 0.15 s each on one thread: killed after a few points are complete.
    let vary = "material.gamma = { from = 0.08, to = 0.14, steps = 4 }\n\
                geometry.radius = [6.5, 7.0, 8.0, 9.0]";
    let sweep = write_sweep(&scratch.0, 0.004, vary);
    let dir = scratch.join("out");
    let mut child = tack()
        .args([
            "sweep",
            s(&sweep),
            "-o",
            s(&dir),
            "--threads",
            "1",
            "--quiet",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("spawn the sweep");
    let started = Instant::now();
    while completed(&dir).len() < 3 {
        assert!(
            started.elapsed() < Duration::from_secs(120),
            "no points completed in two minutes"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().expect("kill -9 the sweep");
    child.wait().expect("reap the sweep");
    let before = completed(&dir);
    assert!(
        before.len() < 16,
        "the sweep finished before it could be killed: make its points slower"
    );
    let mtimes: BTreeMap<String, SystemTime> = before
        .iter()
        .map(|(name, path)| {
            let meta = std::fs::metadata(path).expect("point file");
            (name.clone(), meta.modified().expect("mtime"))
        })
        .collect();

    // Merging the interrupted sweep reports the missing points and writes nothing ...
    let partial = scratch.join("partial.h5");
    let out = run(&["merge", s(&dir), "-o", s(&partial)]);
    let (_, stderr) = text(&out);
    assert!(
        !out.status.success(),
        "merge of an incomplete sweep succeeded"
    );
    assert!(stderr.contains("is missing: no result file"), "{stderr}");
    assert!(stderr.contains("again for the missing points"), "{stderr}");
    assert!(!partial.exists());
    // ... unless asked to, with status 2 and NaN for them.
    assert_ok(
        &run(&["merge", s(&dir), "-o", s(&partial), "--allow-missing"]),
        "merge --allow-missing",
    );
    let t = tack_io::read_sweep_table(&partial).expect("partial table");
    let missing = t.status.iter().filter(|&&st| st == POINT_MISSING).count();
    assert_eq!(missing, 16 - before.len());
    for (k, &st) in t.status.iter().enumerate() {
        assert_eq!(st == POINT_OK, !t.results[0].1[k].is_nan());
    }

    // A temporary as a kill during a write leaves it (`write_result`: temp file + rename).
    std::fs::write(dir.join("points/.00015.h5.tmp-999999-0"), "half").expect("temporary");
    eprintln!("killed after {} of 16 points", before.len());

    // The rerun completes the rest, touching none of the completed points.
    let (stdout, _) = assert_ok(
        &run(&["sweep", s(&sweep), "-o", s(&dir), "--quiet"]),
        "resumed sweep",
    );
    let expect = format!(
        "{} already complete, {} run, 0 failed",
        before.len(),
        16 - before.len()
    );
    assert!(stdout.contains(&expect), "{stdout}\nexpected: {expect}");
    for (name, mtime) in &mtimes {
        let now = std::fs::metadata(dir.join("points").join(name))
            .and_then(|m| m.modified())
            .expect("point file after the rerun");
        assert_eq!(*mtime, now, "{name} was rewritten");
    }
    // Every point once, no temporaries of the killed run left behind.
    let names: Vec<String> = point_files(&dir).into_keys().collect();
    let want: Vec<String> = (0..16).map(|i| format!("{i:05}.h5")).collect();
    assert_eq!(names, want);

    let resumed = merge(&dir, &scratch.join("resumed.h5"));
    let fresh = scratch.join("fresh");
    assert_ok(
        &run(&["sweep", s(&sweep), "-o", s(&fresh), "--quiet"]),
        "uninterrupted sweep",
    );
    let uninterrupted = merge(&fresh, &scratch.join("fresh.h5"));
    assert_same_table(&resumed, &uninterrupted);
}

#[test]
fn failing_points_are_recorded_and_reported_while_the_others_complete() {
    let scratch = Scratch::new("sweep-fail");
    let vary = "material.e_star = [1.0, -1.0]\nmaterial.gamma = [0.1, 0.125]";
    let sweep = write_sweep(&scratch.0, 0.02, vary);
    let dir = scratch.join("out");
    let out = run(&["sweep", s(&sweep), "-o", s(&dir), "--quiet"]);
    let (stdout, stderr) = text(&out);
    assert!(!out.status.success(), "a sweep with failed points exits 0");
    assert!(stdout.contains("2 run, 2 failed"), "{stdout}");
    assert!(
        stderr.contains("error: 2 of 4 points failed"),
        "the count is printed at the end: {stderr}"
    );
    assert!(
        stderr.contains(
            "point 2 (material.e_star = -1.0, material.gamma = 0.1) failed: material.e_star = -1 \
             is invalid: must be a finite number > 0"
        ),
        "{stderr}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    let names: Vec<String> = point_files(&dir).into_keys().collect();
    assert_eq!(names, ["00000.h5", "00001.h5", "00002.err", "00003.err"]);
    let err = std::fs::read_to_string(dir.join("points/00003.err")).expect("error file");
    assert!(err.contains("material.e_star = -1 is invalid"), "{err}");

    // Merge reports the failures with their errors and keeps their rows (status 1, NaN).
    let table_path = scratch.join("table.h5");
    let out = run(&["merge", s(&dir), "-o", s(&table_path)]);
    let (stdout, stderr) = assert_ok(&out, "merge with failed points");
    assert!(
        stdout.contains("4 points: 2 complete, 2 failed, 0 missing"),
        "{stdout}"
    );
    assert!(
        stderr.contains("point 3 (material.e_star = -1.0, material.gamma = 0.125) failed: material.e_star = -1 is invalid"),
        "{stderr}"
    );
    let t = tack_io::read_sweep_table(&table_path).expect("table");
    assert_eq!(t.status, [POINT_OK, POINT_OK, POINT_FAILED, POINT_FAILED]);
    assert!(t.error[0].is_empty() && t.error[2].contains("material.e_star = -1"));
    let force = &t.results[0].1;
    assert!(force[0] < 0.0 && force[1] < force[0], "{force:?}");
    assert!(force[2].is_nan() && force[3].is_nan());
    assert_eq!(
        t.parameters[0],
        (
            "material.e_star".to_owned(),
            ParameterColumn::Float(vec![1.0, 1.0, -1.0, -1.0])
        )
    );

    // A rerun retries the failed points only.
    let out = run(&["sweep", s(&sweep), "-o", s(&dir), "--quiet"]);
    let (stdout, _) = text(&out);
    assert!(!out.status.success());
    assert!(
        stdout.contains("2 already complete, 0 run, 2 failed"),
        "{stdout}"
    );
}

#[test]
fn merge_marks_points_whose_run_stopped_at_max_steps_as_incomplete() {
    let scratch = Scratch::new("sweep-incomplete");
    // Point 0 stops after 20 steps, long before detachment; point 1 runs to the end.
    let sweep = write_sweep(&scratch.0, 0.02, "protocol.max_steps = [20, 100000]");
    let dir = scratch.join("out");
    assert_ok(
        &run(&["sweep", s(&sweep), "-o", s(&dir), "--quiet"]),
        "tack sweep",
    );
    let table_path = scratch.join("table.h5");
    let out = run(&["merge", s(&dir), "-o", s(&table_path)]);
    let (stdout, stderr) = assert_ok(&out, "merge with an incomplete point");
    assert!(
        stdout.contains("2 points: 1 complete, 1 incomplete"),
        "the summary line counts the incomplete point: {stdout}"
    );
    assert!(
        stderr.contains(
            "point 0 (protocol.max_steps = 20) is incomplete: status `stopped at \
             protocol.max_steps`; incomplete: the path stopped at protocol.max_steps = 20"
        ),
        "{stderr}"
    );
    let t = tack_io::read_sweep_table(&table_path).expect("table");
    assert_eq!(t.status, [POINT_INCOMPLETE, POINT_OK]);
    assert_eq!(
        t.result_status,
        [
            tack_io::Summary::STOPPED_AT_MAX_STEPS,
            tack_io::Summary::COMPLETE
        ]
    );
    assert!(t.warnings[0].contains("protocol.max_steps = 20"), "{t:?}");
    assert!(t.warnings[1].is_empty(), "{t:?}");
    // The incomplete point's numbers are kept (its status says what they are worth).
    assert!(t.results[0].1.iter().all(|f| f.is_finite()), "{t:?}");
}

/// Runs `args`, which must fail with `expected` in a message starting `error: `.
fn assert_fails(args: &[&str], expected: &str) {
    let out = run(args);
    let (stdout, stderr) = text(&out);
    assert!(
        !out.status.success(),
        "{args:?}: expected failure, got success\nstdout: {stdout}"
    );
    assert!(
        stderr.contains(expected),
        "{args:?}: stderr does not contain {expected:?}\nstderr: {stderr}"
    );
    assert!(stderr.starts_with("error: "), "{args:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
}

#[test]
fn bad_sweep_files_and_arguments_fail_clearly() {
    let scratch = Scratch::new("sweep-bad");
    let dir = scratch.join("out");
    let good = write_sweep(&scratch.0, 0.02, "material.gamma = [0.1, 0.125]");
    let cases = [
        (
            "version = 1\nscene = \"base.toml\"\ncolect = [\"pull_off_force\"]\n[vary]\nmaterial.gamma = [0.1]\n",
            "unknown field `colect`",
        ),
        (
            "version = 1\nscene = \"base.toml\"\n[vary]\n",
            "[vary] is empty",
        ),
        ("version = 1\nscene = \"base.toml\"\n", "[vary] is empty"),
        (
            "version = 1\nscene = \"base.toml\"\n[vary]\nmaterial.gama = [0.1, 0.2]\n",
            "unknown field `gama`",
        ),
        (
            "version = 1\nscene = \"base.toml\"\n[vary]\nmaterial.gamma = { from = 0.1, to = 0.2 }\n",
            "vary.material.gamma: the range needs `steps`",
        ),
        (
            "version = 1\nscene = \"nowhere.toml\"\n[vary]\nmaterial.gamma = [0.1]\n",
            // The sweep file (case 5), its `scene` field and the missing file.
            "bad5.toml`: scene = \"nowhere.toml\": cannot read the base scene `",
        ),
        (
            "version = 3\nscene = \"base.toml\"\n[vary]\nmaterial.gamma = [0.1]\n",
            "version = 3 is not supported",
        ),
        (
            "version = 1\nscene = \"base.toml\"\ncollect = [\"force\"]\n[vary]\nmaterial.gamma = [0.1]\n",
            "collect: `force` is not a summary quantity",
        ),
    ];
    for (k, (text, expected)) in cases.iter().enumerate() {
        let path = scratch.join(&format!("bad{k}.toml"));
        std::fs::write(&path, text).expect("bad sweep");
        assert_fails(&["sweep", s(&path), "-o", s(&dir)], expected);
        assert!(!dir.exists(), "a bad sweep created its output directory");
    }
    for shard in ["5/4", "0/4", "1/0", "2", "x/4"] {
        assert_fails(
            &["sweep", s(&good), "-o", s(&dir), "--shard", shard],
            &format!("`{shard}` is not a shard"),
        );
    }
    assert_fails(
        &["sweep", s(&good), "-o", s(&dir), "--threads", "0"],
        "--threads",
    );

    // A different sweep in the same directory is refused, naming the directory.
    assert_ok(
        &run(&["sweep", s(&good), "-o", s(&dir), "--quiet"]),
        "good sweep",
    );
    let other = scratch.join("other.toml");
    std::fs::write(
        &other,
        "version = 1\nscene = \"base.toml\"\n[vary]\nmaterial.gamma = [0.2]\n",
    )
    .expect("other sweep");
    assert_fails(
        &["sweep", s(&other), "-o", s(&dir)],
        &format!("{}: holds a different sweep", dir.display()),
    );
    // So is a changed base scene.
    std::fs::write(scratch.join("base.toml"), base_scene(0.03)).expect("base");
    assert_fails(
        &["sweep", s(&good), "-o", s(&dir)],
        "the base scene has changed since this sweep started",
    );
    // An unrelated, non-empty directory is not taken over.
    let junk = scratch.join("junk");
    std::fs::create_dir(&junk).expect("junk dir");
    std::fs::write(junk.join("notes.txt"), "mine").expect("junk file");
    assert_fails(
        &["sweep", s(&good), "-o", s(&junk)],
        "is not a sweep directory",
    );
    assert_fails(
        &["merge", s(&junk), "-o", s(&scratch.join("t.h5"))],
        "not a sweep directory",
    );
    assert_eq!(std::fs::read_dir(&junk).expect("junk").count(), 1);
}

#[test]
fn example_sweeps_are_valid_at_every_point_and_the_jkr_example_runs() {
    let dir = common::repo_root().join("data/sweeps");
    let sweeps = common::files_with_extension(&dir, "toml")
        .into_iter()
        .filter(|p| std::fs::read_to_string(p).is_ok_and(|t| t.contains("[vary]")))
        .collect::<Vec<_>>();
    assert!(sweeps.len() >= 2, "{sweeps:?}");
    for path in &sweeps {
        let sweep =
            tack_sweep::Sweep::load(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        for i in 0..sweep.len() {
            let scene = sweep.point_scene(i).expect("point scene");
            if let Err(e) = tack::Problem::from_scene(&scene) {
                panic!("{} point {i} ({}): {e}", path.display(), sweep.label(i));
            }
        }
    }
    let scratch = Scratch::new("sweep-example");
    let out = scratch.join("jkr");
    let (stdout, _) = assert_ok(
        &run(&[
            "sweep",
            s(&dir.join("jkr_sphere_gamma.toml")),
            "-o",
            s(&out),
            "--quiet",
        ]),
        "the JKR example sweep",
    );
    assert!(stdout.contains("12 run, 0 failed"), "{stdout}");
    let t = merge(&out, &scratch.join("jkr.h5"));
    assert!(t.status.iter().all(|&st| st == POINT_OK));
    let (name, ratio) = &t.results[2];
    assert_eq!(name, "pull_off_ratio");
    // a_c/dx between 4 and 7 here: the discrete criterion overshoots F_JKR by 20-50%.
    assert!(ratio.iter().all(|r| (1.0..1.6).contains(r)), "{ratio:?}");
}

#[test]
fn zipped_sweep_runs_and_merges_every_field_as_a_column() {
    let scratch = Scratch::new("sweep-zipped");
    // 3 rows of (radius, gamma) × 2 load steps = 6 points, the zipped entry outermost.
    let vary = "\"geometry.radius, material.gamma\" = [\n  [7.0, 0.08],\n  [8.0, 0.1],\n  \
                [9.0, 0.12],\n]\nprotocol.load_step = [0.15, 0.2]";
    let sweep = write_sweep(&scratch.0, 0.02, vary);
    let dir = scratch.join("out");
    let (stdout, _) = assert_ok(
        &run(&["sweep", s(&sweep), "-o", s(&dir), "--quiet"]),
        "zipped sweep",
    );
    assert!(stdout.contains("6 of 6 points"), "{stdout}");
    let t = merge(&dir, &scratch.join("zipped.h5"));
    let fields: Vec<&str> = t.parameters.iter().map(|(f, _)| f.as_str()).collect();
    assert_eq!(
        fields,
        ["geometry.radius", "material.gamma", "protocol.load_step"]
    );
    let column = |k: usize| match &t.parameters[k].1 {
        ParameterColumn::Float(v) => v.clone(),
        other => panic!("{other:?}"),
    };
    assert_eq!(column(0), [7.0, 7.0, 8.0, 8.0, 9.0, 9.0]);
    assert_eq!(column(1), [0.08, 0.08, 0.1, 0.1, 0.12, 0.12]);
    assert_eq!(column(2), [0.15, 0.2, 0.15, 0.2, 0.15, 0.2]);
    // Each point's result records its row, and was run with it: F_JKR = −(3/2)πγR.
    let (pull_off, ratio) = (&t.results[0].1, &t.results[1].1);
    for k in 0..6 {
        let scene = tack_io::read_result(&dir.join(format!("points/{k:05}.h5")))
            .expect("point file")
            .provenance
            .scene;
        let parsed = tack::Scene::parse(&scene, ".", &[]).expect("recorded scene");
        let (r, g) = (column(0)[k], column(1)[k]);
        assert_eq!(
            parsed.file.geometry,
            tack::scene::Geometry::Sphere { radius: r }
        );
        assert_eq!(parsed.file.material.gamma, g);
        assert_eq!(parsed.file.protocol.load_step, Some(column(2)[k]));
        let f_jkr = -1.5 * std::f64::consts::PI * g * r;
        assert!(
            pull_off[k] < 0.0 && (pull_off[k] / ratio[k] / f_jkr - 1.0).abs() < 1e-12,
            "point {k}: {} / {} vs {f_jkr}",
            pull_off[k],
            ratio[k]
        );
    }
    // The same rows with one value missing: rejected before anything runs, naming the fields.
    let bad = scratch.join("bad.toml");
    std::fs::write(
        &bad,
        "version = 1\nscene = \"base.toml\"\n[vary]\n\"geometry.radius, material.gamma\" = \
         [[7.0, 0.08], [8.0]]\n",
    )
    .expect("bad sweep");
    let other = scratch.join("other");
    assert_fails(
        &["sweep", s(&bad), "-o", s(&other)],
        "vary.\"geometry.radius, material.gamma\": row 1 has 1 values but the entry names 2 \
         fields (geometry.radius, material.gamma)",
    );
    assert!(!other.exists());
}

#[test]
fn an_absurd_thread_count_is_refused_before_anything_is_written() {
    let dir = Scratch::new("threads");
    let sweep = write_sweep(&dir.0, 0.05, "material.gamma = [0.05, 0.1]");
    let out = dir.join("out");
    let run = tack()
        .args(["sweep", s(&sweep), "-o", s(&out), "--threads", "30000"])
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(1), "{run:?}");
    let err = String::from_utf8_lossy(&run.stderr);
    assert!(
        err.contains("--threads = 30000 is invalid") && err.contains("1 to 1024"),
        "{err}"
    );
    assert!(!out.exists(), "nothing may be written");
}
