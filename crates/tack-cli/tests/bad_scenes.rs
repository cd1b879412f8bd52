//! Bad input never panics and never leaves a result behind: every scene in `tests/scenes/bad`
//! fails with a non-zero exit and the message in its sibling `.expected` file; bad `--set`
//! overrides fail the same way; an interrupted run leaves nothing under the final name.

mod common;

use std::process::Stdio;
use std::time::{Duration, Instant};

use common::{Scratch, bad_scenes_dir, examples_dir, files_with_extension, run, tack, text};

/// Runs `args` (which write `out` when they succeed) and checks the failure contract.
fn assert_fails_cleanly(args: &[&str], expected: &str, scratch: &Scratch, what: &str) {
    let out = run(args);
    let (stdout, stderr) = text(&out);
    assert!(
        !out.status.success(),
        "{what}: expected failure, got success\nstdout: {stdout}"
    );
    assert!(
        stderr.contains(expected),
        "{what}: stderr does not contain {expected:?}\nstderr: {stderr}"
    );
    assert!(
        stderr.starts_with("error: "),
        "{what}: message must start with `error: `\nstderr: {stderr}"
    );
    assert!(!stderr.contains("panicked"), "{what}: panicked\n{stderr}");
    assert!(
        scratch.files().is_empty(),
        "{what}: left files behind: {:?}",
        scratch.files()
    );
}

#[test]
fn every_bad_scene_fails_with_its_expected_message() {
    let scenes = files_with_extension(&bad_scenes_dir(), "toml");
    assert!(scenes.len() >= 9, "too few bad scenes: {scenes:?}");
    let scratch = Scratch::new("bad-scenes");
    let out = scratch.join("out.h5");
    let out = out.to_str().expect("utf-8 scratch path");
    for scene in &scenes {
        let expected_file = scene.with_extension("expected");
        let expected = std::fs::read_to_string(&expected_file)
            .unwrap_or_else(|e| panic!("{}: {e}", expected_file.display()));
        let expected = expected.trim();
        assert!(!expected.is_empty(), "{}", expected_file.display());
        let scene = scene.to_str().expect("utf-8 path");
        let runs: [&[&str]; 2] = [
            &["run", scene, "-o", out, "--quiet"],
            &["surface", scene, "-o", out],
        ];
        for args in runs {
            assert_fails_cleanly(args, expected, &scratch, &args.join(" "));
        }
        assert_fails_cleanly(&["check", scene], expected, &scratch, scene);
    }
}

#[test]
fn bad_overrides_fail_through_the_schema() {
    let scratch = Scratch::new("bad-overrides");
    let scene = examples_dir().join("smooth_jkr_sphere.toml");
    let scene = scene.to_str().expect("utf-8 path");
    let out = scratch.join("out.h5");
    let out = out.to_str().expect("utf-8 path");
    for (set, expected) in [
        ("material.colour=1", "unknown field `colour`"),
        ("material.e_star=-1", "material.e_star = -1 is invalid"),
        ("material.e_star=nan", "material.e_star = NaN is invalid"),
        ("grid.n=0", "grid.n = 0 is invalid"),
        ("material=3", "material = 3 is invalid: must be a table"),
        ("material.gamma", "expected key=value"),
        ("version=3", "version = 3 is not supported"),
        (
            "geometry.shape=cube",
            "--set geometry.shape=cube: geometry.shape = \"cube\" is invalid: must be one of",
        ),
        (
            "grid.n=32.0",
            "--set grid.n=32.0: grid.n = 32.0 is invalid: must be an integer in 1..=65536",
        ),
    ] {
        assert_fails_cleanly(
            &["run", scene, "-o", out, "--quiet", "--set", set],
            expected,
            &scratch,
            set,
        );
    }
}

#[test]
fn runs_that_cannot_fit_and_meaningless_tolerances_are_refused_at_check() {
    let scene = examples_dir().join("smooth_jkr_sphere.toml");
    let scene = scene.to_str().expect("utf-8 path");
    for (sets, expected) in [
        (
            &["output.snapshots=\"all\"", "grid.n=2048"][..],
            "for up to 100000 snapshots (output.snapshots = \"all\" over 100000 steps at most: \
             protocol.max_steps = 100000",
        ),
        (
            &["protocol.max_steps=1000000000000000000"],
            "for 1000000000000000000 step records; lower protocol.max_steps",
        ),
        (
            &["solver.tolerance=5e-324"],
            "solver.tolerance = 5e-324 is invalid: must be a number in 1e-14..=0.1",
        ),
        (
            &["protocol.unload_step=1e308"],
            "protocol.unload_step = 1e308 is invalid",
        ),
    ] {
        let mut args = vec!["check", scene];
        for set in sets {
            args.extend(["--set", set]);
        }
        let started = Instant::now();
        let out = run(&args);
        let (stdout, stderr) = text(&out);
        assert_eq!(out.status.code(), Some(1), "{sets:?}: {stdout}{stderr}");
        assert!(stderr.contains(expected), "{sets:?}: {stderr}");
        assert!(
            started.elapsed() < Duration::from_secs(5),
            "{sets:?} took long"
        );
    }
    // The estimate is printed for what passes.
    let out = run(&["check", scene]);
    let (stdout, stderr) = text(&out);
    assert!(out.status.success(), "{stderr}");
    assert!(stdout.contains("memory: at most about"), "{stdout}");
}

#[test]
fn missing_files_and_bad_outputs_name_the_path() {
    let scratch = Scratch::new("bad-paths");
    let out = scratch.join("out.h5");
    let out = out.to_str().expect("utf-8 path");
    assert_fails_cleanly(
        &["run", "no/such/scene.toml", "-o", out],
        "no/such/scene.toml",
        &scratch,
        "missing scene",
    );
    assert_fails_cleanly(
        &["info", "no/such/result.h5"],
        "no/such/result.h5",
        &scratch,
        "missing result",
    );
    assert_fails_cleanly(
        &["plot", "no/such/result.h5", "-o", out],
        "no/such/result.h5",
        &scratch,
        "missing result to plot",
    );
    let scene = examples_dir().join("flat_punch.toml");
    let scene = scene.to_str().expect("utf-8 path");
    let nested = scratch.join("missing-dir/out.h5");
    assert_fails_cleanly(
        &["run", scene, "-o", nested.to_str().expect("utf-8")],
        "does not exist",
        &scratch,
        "missing output directory",
    );
    // A scene file is not an HDF5 result.
    assert_fails_cleanly(&["info", scene], "flat_punch.toml", &scratch, "not HDF5");
}

/// Creates a FIFO at `path` with `mkfifo`; `false` (and a visible SKIPPED line) without it.
#[cfg(unix)]
fn make_fifo(path: &std::path::Path) -> bool {
    let made = std::process::Command::new("mkfifo")
        .arg(path)
        .status()
        .is_ok_and(|s| s.success());
    if !made {
        use std::io::Write;
        let _ = writeln!(
            std::io::stderr(),
            "SKIPPED: outputs that are FIFOs (mkfifo is not available)"
        );
    }
    made
}

#[cfg(unix)]
#[test]
fn outputs_that_are_not_regular_files_are_refused_and_kept() {
    use std::os::unix::fs::FileTypeExt;
    let scratch = Scratch::new("special-outputs");
    // `.svg`: `tack plot` picks the format from the name, the others take any name.
    let fifo = scratch.join("pipe.svg");
    if !make_fifo(&fifo) {
        return;
    }
    let fifo_s = fifo.to_str().expect("utf-8 path");
    let scene = examples_dir().join("flat_punch.toml");
    let scene = scene.to_str().expect("utf-8 path");
    // A valid result to plot, made outside the scratch directory.
    let elsewhere = Scratch::new("special-outputs-result");
    let result = elsewhere.join("r.h5");
    let result = result.to_str().expect("utf-8 path");
    let made = run(&["run", scene, "-o", result, "--quiet"]);
    assert!(made.status.success(), "{:?}", text(&made));
    let runs: [&[&str]; 4] = [
        &["run", scene, "-o", fifo_s, "--quiet"],
        &["surface", scene, "-o", fifo_s],
        &["plot", result, "-o", fifo_s],
        &["merge", "no-such-sweep-dir", "-o", fifo_s],
    ];
    for args in runs {
        let started = Instant::now();
        let out = run(args);
        let (stdout, stderr) = text(&out);
        assert_eq!(out.status.code(), Some(1), "{args:?}\n{stdout}{stderr}");
        assert!(
            stderr.contains(fifo_s) && stderr.contains("is a FIFO"),
            "{args:?}: the message names the path and what it is\n{stderr}"
        );
        assert!(!stderr.contains("panicked"), "{stderr}");
        assert!(started.elapsed() < Duration::from_secs(10), "{args:?} hung");
        let kind = std::fs::symlink_metadata(&fifo).expect("the FIFO is still there");
        assert!(kind.file_type().is_fifo(), "{args:?} replaced the FIFO");
        assert_eq!(scratch.files(), ["pipe.svg"], "{args:?} left files behind");
    }
    // A device and a directory likewise (the device only after the FIFO was refused above: the
    // same check, so /dev/null is never at risk here).
    let dir = scratch.join("a-directory");
    std::fs::create_dir(&dir).expect("scratch directory");
    for (path, what) in [
        ("/dev/null", "is a character device"),
        (dir.to_str().expect("utf-8 path"), "is a directory"),
    ] {
        let out = run(&["run", scene, "-o", path, "--quiet"]);
        let (_, stderr) = text(&out);
        assert_eq!(out.status.code(), Some(1), "{path}: {stderr}");
        assert!(
            stderr.contains(path) && stderr.contains(what),
            "{path}: {stderr}"
        );
    }
    let null = std::fs::metadata("/dev/null").expect("/dev/null");
    assert!(null.file_type().is_char_device(), "/dev/null was replaced");
}

#[test]
fn usage_errors_exit_non_zero() {
    for args in [&["run"][..], &["frobnicate"], &["run", "x.toml"], &[]] {
        let out = run(args);
        assert!(!out.status.success(), "{args:?}");
        assert!(!text(&out).1.contains("panicked"), "{args:?}");
    }
}

/// Whether this process ignores SIGINT (`SigIgn` of `/proc/self/status`, bit 1): a child
/// inherits the disposition, and a shell without job control (a `( … & )` subshell) starts
/// background commands with it. `false` where that cannot be read.
#[cfg(target_os = "linux")]
fn sigint_ignored() -> bool {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("SigIgn:"))
        .and_then(|mask| u64::from_str_radix(mask.trim(), 16).ok())
        .is_some_and(|mask| mask & (1 << 1) != 0)
}

#[cfg(unix)]
#[test]
fn interrupted_run_leaves_no_result_under_the_final_name() {
    // The child inherits an ignored SIGINT and would run to its end: say so rather than time
    // out with "did not stop".
    #[cfg(target_os = "linux")]
    assert!(
        !sigint_ignored(),
        "this test process ignores SIGINT (inherited from the shell that started it, e.g. a \
         background job of a shell without job control), so tack would too: run the tests \
         from a shell that delivers SIGINT"
    );
    let scratch = Scratch::new("interrupt");
    let out = scratch.join("long.h5");
    let scene = examples_dir().join("smooth_jkr_sphere.toml");
    // A fine grid and tiny unload steps: minutes of work, interrupted after about a second.
    let mut child = tack()
        .arg("run")
        .arg(&scene)
        .arg("-o")
        .arg(&out)
        .args(["--quiet", "--set", "grid.n=240", "--set", "grid.dx=0.06"])
        .args(["--set", "protocol.unload_step=0.0001"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("cannot start tack");
    let started = Instant::now();
    while started.elapsed() < Duration::from_secs(1) {
        if scratch.files().iter().any(|f| f.contains(".tmp-")) {
            break;
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(
        child.try_wait().expect("try_wait").is_none(),
        "the long run finished too early to be interrupted"
    );
    let killed = std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("cannot run kill");
    assert!(killed.success());
    let deadline = Instant::now() + Duration::from_secs(20);
    let status = loop {
        if let Some(status) = child.try_wait().expect("try_wait") {
            break status;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            panic!("tack did not stop on SIGINT");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    assert!(!status.success());
    assert!(
        !out.exists(),
        "an interrupted run left {} behind",
        out.display()
    );
    // At most a stray temporary may remain; the scratch directory is removed on drop.
    for stray in scratch.files() {
        assert!(
            stray.starts_with(".long.h5.tmp-"),
            "unexpected file {stray}"
        );
    }
}

#[test]
fn a_reader_that_closes_the_pipe_early_ends_the_output_quietly() {
    // `tack check … | head -1`: the reader is gone before the first write (its end of the
    // pipe dropped at once), so every write meets a broken pipe. `println!` panicked there
    // (exit 101); the output now ends quietly with the command's own status.
    let scratch = Scratch::new("pipe");
    let scene = examples_dir().join("smooth_jkr_sphere.toml");
    let surface = scratch.join("s.h5");
    let commands: [&[&std::ffi::OsStr]; 2] = [
        &["check".as_ref(), scene.as_os_str()],
        &[
            "surface".as_ref(),
            scene.as_os_str(),
            "-o".as_ref(),
            surface.as_os_str(),
        ],
    ];
    for args in commands {
        let mut child = tack()
            .args(args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("the tack binary could not be started");
        drop(child.stdout.take());
        let out = child.wait_with_output().expect("tack ran");
        let (_, err) = text(&out);
        assert!(out.status.success(), "{args:?}: {:?}\n{err}", out.status);
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
    assert!(
        surface.is_file(),
        "the surface file is written all the same"
    );
}
