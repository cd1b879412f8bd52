//! Corrupt HDF5 inputs through the binary: result files and height maps whose datasets declare
//! more data than the file holds (a curve of 2⁴⁰ entries, a 2²⁰ × 2²⁰ height map) make
//! `tack info`, `plot`, `check`, `run`, `merge` and `sweep` fail cleanly (exit 1, `error: `
//! naming the file and the dataset) or treat the point as missing, never abort.
//!
//! The files are valid files written by `tack` with the dimensions in their dataspace
//! messages overwritten, as a fuzzer (or a flipped bit) would. Before the size checks in
//! tack-io every one of these commands aborted ("memory allocation of N bytes failed",
//! SIGABRT, exit 134).

mod common;

use std::path::Path;
use std::process::Output;

use common::{Scratch, run, text};
use tack_io::{POINT_MISSING, POINT_OK};

const HUGE: u64 = 1 << 40;
const SIDE: u64 = 1 << 20;

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

/// Overwrites the dimensions of at most `limit` HDF5 dataspace messages (version 1, rank
/// `from.len()`) whose dimensions are `from` with `to` (and their maximum dimensions, when
/// stored and equal); returns how many it patched.
fn patch_dims(path: &Path, from: &[u64], to: &[u64], limit: usize) -> usize {
    let mut bytes = std::fs::read(path).expect("read the file to patch");
    let rank = from.len();
    let encode = |dims: &[u64]| -> Vec<u8> { dims.iter().flat_map(|d| d.to_le_bytes()).collect() };
    let (old, new) = (encode(from), encode(to));
    let (mut count, mut i) = (0, 0);
    while count < limit && i + 8 + 16 * rank <= bytes.len() {
        let header = &bytes[i..i + 8];
        let dims = i + 8..i + 8 + 8 * rank;
        let is_space = header[0] == 1
            && header[1] as usize == rank
            && header[2] <= 1
            && header[3..8] == [0; 5]
            && bytes[dims.clone()] == old[..];
        if !is_space {
            i += 1;
            continue;
        }
        let with_max = header[2] == 1;
        bytes[dims.clone()].copy_from_slice(&new);
        let max = dims.end..dims.end + 8 * rank;
        if with_max && bytes[max.clone()] == old[..] {
            bytes[max].copy_from_slice(&new);
        }
        count += 1;
        i = dims.end;
    }
    std::fs::write(path, bytes).expect("write the patched file");
    count
}

/// The command failed with exit status 1 and an `error: ` message, its stderr containing every
/// one of `expected`; no abort, no panic, no HDF5 diagnostics.
fn assert_clean_failure(out: &Output, expected: &[&str], what: &str) -> String {
    let (stdout, stderr) = text(out);
    assert_eq!(
        out.status.code(),
        Some(1),
        "{what}: expected exit status 1, got {}\nstdout: {stdout}\nstderr: {stderr}",
        out.status
    );
    // `tack merge` lists the points first, then fails.
    assert!(
        stderr.lines().any(|l| l.starts_with("error: ")),
        "{what}: {stderr}"
    );
    for e in expected {
        assert!(
            stderr.contains(e),
            "{what}: stderr lacks {e:?}\nstderr: {stderr}"
        );
    }
    for bad in ["memory allocation", "panicked", "HDF5-DIAG"] {
        assert!(!stderr.contains(bad), "{what}: {bad}\nstderr: {stderr}");
    }
    stderr
}

fn assert_ok(out: &Output, what: &str) -> (String, String) {
    let (stdout, stderr) = text(out);
    assert!(
        out.status.success(),
        "{what} failed ({})\nstdout: {stdout}\nstderr: {stderr}",
        out.status
    );
    (stdout, stderr)
}

/// A small smooth-sphere scene on a 32² grid (a few hundredths of a second per run);
/// `roughness` is appended as is.
fn scene(roughness: &str) -> String {
    format!(
        r#"version = 1
[material]
e_star = 1.0
gamma = 0.1
[geometry]
shape = "sphere"
radius = 1.0
[grid]
n = 32
dx = 0.05
[protocol]
max_approach = 0.2
load_step = 0.02
[output]
surface = true
snapshots = {{ every = 5 }}
{roughness}"#
    )
}

/// Runs the small scene into `dir/run.h5`; returns the path and its curve length.
fn result_file(scratch: &Scratch) -> (std::path::PathBuf, u64) {
    let scene_path = scratch.join("scene.toml");
    std::fs::write(&scene_path, scene("")).expect("scene");
    let out = scratch.join("run.h5");
    assert_ok(
        &run(&["run", s(&scene_path), "-o", s(&out), "--quiet"]),
        "tack run",
    );
    let steps = tack_io::read_result(&out)
        .expect("a fresh result")
        .curve
        .len() as u64;
    (out, steps)
}

#[test]
fn info_and_plot_refuse_a_curve_declaring_2_pow_40_entries() {
    let scratch = Scratch::new("corrupt-curve");
    let (good, steps) = result_file(&scratch);
    let fig = scratch.join("fig.svg");
    let cases: [(&str, u64, usize); 2] = [
        // Every curve column 2⁴⁰ long: consistent, and far beyond the file.
        ("all.h5", HUGE, usize::MAX),
        // One byte changed: the 7th byte of one column's length.
        ("one-byte.h5", steps + (3 << 48), 1),
    ];
    for (name, to, limit) in cases {
        let bad = scratch.join(name);
        std::fs::copy(&good, &bad).expect("copy");
        let patched = patch_dims(&bad, &[steps], &[to], limit);
        assert!(patched >= 1, "{name}: no curve dataspace found");
        let out = run(&["info", s(&bad)]);
        assert_clean_failure(&out, &[s(&bad), "/curve/"], &format!("tack info {name}"));
        let out = run(&["plot", s(&bad), "-o", s(&fig)]);
        assert_clean_failure(&out, &[s(&bad), "/curve/"], &format!("tack plot {name}"));
        assert!(!fig.exists(), "tack plot {name} left a figure");
    }
    // The surface and every snapshot 2²⁰ × 2²⁰.
    let bad = scratch.join("fields.h5");
    std::fs::copy(&good, &bad).expect("copy");
    assert!(patch_dims(&bad, &[32, 32], &[SIDE, SIDE], usize::MAX) >= 2);
    let out = run(&["info", s(&bad)]);
    assert_clean_failure(&out, &[s(&bad), "1048576 × 1048576"], "tack info fields.h5");
    // The original still reads.
    assert_ok(&run(&["info", s(&good)]), "tack info of the good file");
}

#[test]
fn check_and_run_refuse_a_huge_height_map_before_reading_it() {
    let scratch = Scratch::new("corrupt-map");
    let plain = scratch.join("plain.toml");
    std::fs::write(&plain, scene("")).expect("scene");
    let map = scratch.join("map.h5");
    assert_ok(&run(&["surface", s(&plain), "-o", s(&map)]), "tack surface");
    let rough = scratch.join("rough.toml");
    std::fs::write(
        &rough,
        scene("[roughness]\nkind = \"file\"\npath = \"map.h5\"\n"),
    )
    .expect("scene");
    assert_ok(&run(&["check", s(&rough)]), "tack check with the good map");

    assert_eq!(patch_dims(&map, &[32, 32], &[SIDE, SIDE], usize::MAX), 1);
    let expected = ["roughness.path = `map.h5`", "1048576 × 1048576", "32 × 32"];
    assert_clean_failure(&run(&["check", s(&rough)]), &expected, "tack check");
    let out = scratch.join("out.h5");
    assert_clean_failure(
        &run(&["run", s(&rough), "-o", s(&out), "--quiet"]),
        &expected,
        "tack run",
    );
    assert!(!out.exists());
}

/// A two-point sweep of the small scene in `scratch/out`, run to completion; returns the
/// sweep file and the output directory.
fn two_point_sweep(scratch: &Scratch) -> (std::path::PathBuf, std::path::PathBuf) {
    std::fs::write(scratch.join("base.toml"), scene("")).expect("base scene");
    let sweep = scratch.join("sweep.toml");
    std::fs::write(
        &sweep,
        "version = 1\nscene = \"base.toml\"\ncollect = [\"pull_off_force\"]\n\
         [vary]\nmaterial.gamma = [0.1, 0.125]\n",
    )
    .expect("sweep file");
    let dir = scratch.join("out");
    assert_ok(
        &run(&["sweep", s(&sweep), "-o", s(&dir), "--quiet"]),
        "tack sweep",
    );
    (sweep, dir)
}

/// Overwrites the curve length of `point` with 2⁴⁰; returns the point file.
fn corrupt_point(dir: &Path, point: usize) -> std::path::PathBuf {
    let file = dir.join(format!("points/{point:05}.h5"));
    let steps = tack_io::read_result(&file).expect("point file").curve.len() as u64;
    assert!(patch_dims(&file, &[steps], &[HUGE], usize::MAX) >= 8);
    file
}

#[test]
fn merge_lists_a_corrupt_point_as_missing_and_writes_the_table_when_allowed() {
    let scratch = Scratch::new("corrupt-merge");
    let (_, dir) = two_point_sweep(&scratch);
    let bad = corrupt_point(&dir, 1);
    let table = scratch.join("table.h5");

    let out = run(&["merge", s(&dir), "-o", s(&table)]);
    let stderr = assert_clean_failure(
        &out,
        &[
            "point 1 (material.gamma = 0.125) is missing",
            s(&bad),
            "/curve/",
        ],
        "tack merge",
    );
    assert!(stderr.contains("nothing written"), "{stderr}");
    assert!(!table.exists());

    let out = run(&["merge", s(&dir), "-o", s(&table), "--allow-missing"]);
    let (stdout, stderr) = assert_ok(&out, "tack merge --allow-missing");
    assert!(
        stdout.contains("2 points: 1 complete, 0 failed, 1 missing"),
        "{stdout}"
    );
    assert!(
        stderr.contains("point 1 (material.gamma = 0.125) is missing"),
        "{stderr}"
    );
    let t = tack_io::read_sweep_table(&table).expect("the table reads back");
    assert_eq!(t.status, [POINT_OK, POINT_MISSING]);
    assert!(t.error[1].contains("/curve/"), "{:?}", t.error);
    let force = &t.results[0].1;
    assert!(force[0] < 0.0 && force[1].is_nan(), "{force:?}");
}

#[test]
fn sweep_resume_reruns_a_corrupt_point() {
    let scratch = Scratch::new("corrupt-resume");
    let (sweep, dir) = two_point_sweep(&scratch);
    let bad = corrupt_point(&dir, 0);
    let out = run(&[
        "sweep",
        s(&sweep),
        "-o",
        s(&dir),
        "--quiet",
        "--threads",
        "1",
    ]);
    let (stdout, _) = assert_ok(&out, "the resumed sweep");
    assert!(
        stdout.contains("1 already complete, 1 run, 0 failed"),
        "{stdout}"
    );
    tack_io::read_result(&bad).expect("the rerun point reads back");
    let table = scratch.join("table.h5");
    assert_ok(&run(&["merge", s(&dir), "-o", s(&table)]), "tack merge");
    let t = tack_io::read_sweep_table(&table).expect("table");
    assert_eq!(t.status, [POINT_OK, POINT_OK]);
}
