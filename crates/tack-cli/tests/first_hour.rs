//! What a new user meets in the first hour with `tack run` and `tack check`: a sphere or a
//! measured height map pulled off with no `[protocol]` (the default pull-off path), a one-line
//! indentation without adhesion (no pull-off talk), periodic full contact flagged, and memory
//! bounds from the path's real step count.

mod common;

use common::{Scratch, examples_dir, run, text};

/// The smooth JKR example scene without its `[protocol]` section.
fn sphere_without_protocol() -> String {
    let text = std::fs::read_to_string(examples_dir().join("smooth_jkr_sphere.toml"))
        .expect("the example scene");
    let head = text.split("[protocol]").next().expect("a protocol section");
    // Drop everything after [protocol] but keep later sections.
    let tail = text
        .split("[protocol]")
        .nth(1)
        .and_then(|rest| rest.find("\n[").map(|i| rest[i..].to_owned()))
        .unwrap_or_default();
    format!("{head}{tail}")
}

fn run_scene(scratch: &Scratch, name: &str, scene: &str, extra: &[&str]) -> (bool, String) {
    let path = scratch.join(&format!("{name}.toml"));
    std::fs::write(&path, scene).expect("write scene");
    let out = scratch.join(&format!("{name}.h5"));
    let mut args = vec![
        "run",
        path.to_str().expect("utf-8"),
        "-o",
        out.to_str().expect("utf-8"),
        "--quiet",
    ];
    args.extend_from_slice(extra);
    let o = run(&args);
    let (stdout, stderr) = text(&o);
    (o.status.success(), format!("{stdout}{stderr}"))
}

#[test]
fn a_sphere_without_a_protocol_is_pulled_off_by_the_default_rule() {
    let scratch = Scratch::new("first-hour-sphere");
    let (ok, out) = run_scene(&scratch, "sphere", &sphere_without_protocol(), &[]);
    assert!(ok, "{out}");
    assert!(
        out.contains("default pull-off path of R = 8 (given)"),
        "{out}"
    );
    assert!(out.contains("F/F_JKR = 1.1"), "{out}");
    assert!(!out.contains("WARNING"), "{out}");
}

#[test]
fn a_height_map_without_a_protocol_gets_a_fitted_radius() {
    let scratch = Scratch::new("first-hour-map");
    // The example's sphere written out as a map, then run as geometry "none" + the map.
    let sphere = scratch.join("sphere.toml");
    std::fs::write(&sphere, sphere_without_protocol()).expect("write");
    let surf = scratch.join("surf.h5");
    let o = run(&[
        "surface",
        sphere.to_str().expect("utf-8"),
        "-o",
        surf.to_str().expect("utf-8"),
    ]);
    assert!(o.status.success(), "{}", text(&o).1);
    let (heights, dx) = tack_io::read_result(&surf)
        .expect("read")
        .surface
        .expect("heights");
    let scene = format!(
        "version = 1\n[material]\ne_star = 1.0\ngamma = 0.125\n[geometry]\nshape = \"none\"\n\
         [roughness]\nkind = \"file\"\npath = \"surf.h5\"\n[grid]\nn = {}\ndx = {dx}\n",
        heights.nrows()
    );
    let (ok, out) = run_scene(&scratch, "map", &scene, &[]);
    assert!(ok, "{out}");
    assert!(out.contains("default pull-off path of R = 8"), "{out}");
    assert!(out.contains("(fitted)"), "{out}");
    // The fitted radius gives the JKR reference.
    assert!(out.contains("F/F_JKR = 1.1"), "{out}");
    // A flat map has no radius: refused, naming the fields to give.
    let flat = scratch.join("flat.csv");
    std::fs::write(&flat, "# dx = 0.5\n0, 0\n0, 0\n").expect("write");
    let scene = "version = 1\n[material]\ne_star = 1.0\ngamma = 0.125\n[geometry]\n\
                 shape = \"none\"\n[roughness]\nkind = \"file\"\npath = \"flat.csv\"\n[grid]\n\
                 n = 2\ndx = 0.5\n";
    let (ok, out) = run_scene(&scratch, "flat", scene, &[]);
    assert!(!ok, "{out}");
    assert!(
        out.contains("protocol.max_approach is required") && out.contains("sphere-like"),
        "{out}"
    );
}

#[test]
fn an_indentation_without_adhesion_is_one_line_and_no_pull_off() {
    let scratch = Scratch::new("first-hour-indent");
    let scene = format!("{}[protocol]\nindent = 0.2\n", sphere_without_protocol())
        .replace("gamma = 0.125", "gamma = 0.0");
    let (ok, out) = run_scene(&scratch, "indent", &scene, &[]);
    assert!(ok, "{out}");
    assert!(out.contains("indentation: one step to d = 0.2"), "{out}");
    assert!(out.contains("force       F = "), "{out}");
    for absent in ["pull-off", "WARNING", "STOPPED", "and back", "retraction"] {
        assert!(!out.contains(absent), "{absent:?} in:\n{out}");
    }
    // Without [protocol] and without adhesion: told to use indent.
    let no_path = sphere_without_protocol().replace("gamma = 0.125", "gamma = 0.0");
    let (ok, out) = run_scene(&scratch, "nothing", &no_path, &[]);
    assert!(!ok, "{out}");
    assert!(out.contains("protocol.indent"), "{out}");
}

#[test]
fn periodic_full_contact_is_reported() {
    let scratch = Scratch::new("first-hour-full");
    let scene = "version = 1\n[material]\ne_star = 1.0\ngamma = 0.0\n[geometry]\n\
                 shape = \"none\"\n[roughness]\nkind = \"waviness2d\"\nh = 0.01\nlambda = 1.0\n\
                 [grid]\nn = 16\nlength = 1.0\nboundary = \"periodic\"\n[protocol]\nindent = 0.03\n";
    let (ok, out) = run_scene(&scratch, "full", scene, &[]);
    assert!(ok, "{out}");
    assert!(out.contains("FULL CONTACT in 1 of 1 steps"), "{out}");
    assert!(
        out.contains("WARNING     full contact in 1 of 1 steps"),
        "{out}"
    );
    let summary = tack_io::read_result(&scratch.join("full.h5"))
        .expect("read")
        .summary;
    assert_eq!(summary.extra["full_contact_steps"], 1.0);
    // Partial contact: nothing said.
    let (ok, out) = run_scene(&scratch, "partial", &scene.replace("0.03", "0.004"), &[]);
    assert!(ok, "{out}");
    assert!(!out.to_lowercase().contains("full contact"), "{out}");
}

#[test]
fn check_bounds_memory_by_the_steps_the_path_takes() {
    let scratch = Scratch::new("first-hour-memory");
    // Every field of a 512² indentation: one step, not the 100000-step cap (439.6 GiB).
    let scene = "version = 1\n[material]\ne_star = 1.0\ngamma = 0.125\n[geometry]\n\
                 shape = \"sphere\"\nradius = 8.0\n[grid]\nn = 512\ndx = 0.03\n[protocol]\n\
                 indent = 0.2\n[output]\nsnapshots = \"all\"\n";
    let path = scratch.join("big.toml");
    std::fs::write(&path, scene).expect("write");
    let o = run(&["check", path.to_str().expect("utf-8")]);
    let (stdout, stderr) = text(&o);
    assert!(o.status.success(), "{stderr}");
    assert!(
        stdout.contains("(1 steps: the path's own count)"),
        "{stdout}"
    );
    assert!(
        stdout.contains("indentation: one step to d = 0.2") && !stdout.contains("unload step"),
        "{stdout}"
    );
    assert!(stdout.contains("MiB"), "{stdout}");
    assert!(!stdout.contains("GiB"), "{stdout}");
}
