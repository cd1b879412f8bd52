//! Tests of `problem.rs` (moved out of line: more than 300 lines).

use super::*;
use std::f64::consts::PI;
use tack_geometry::Sphere;
use tack_solver::{Dugdale, Exponential, JkrLimit, LennardJones};

const SPHERE: &str = r#"
version = 1
[material]
e_star = 1.0
gamma = 0.1
[geometry]
shape = "sphere"
radius = 1.0
[grid]
n = 64
dx = 0.05
[protocol]
max_approach = 0.5
load_step = 0.05
"#;

fn build(text: &str, sets: &[&str]) -> Result<Problem, SceneError> {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    Problem::from_scene(&Scene::parse(text, ".", &sets)?)
}

fn err(sets: &[&str]) -> String {
    build(SPHERE, sets).unwrap_err().to_string()
}

/// [`SPHERE`] without its `[protocol]`.
fn no_protocol() -> &'static str {
    SPHERE.split("[protocol]").next().unwrap()
}

#[test]
fn a_scene_without_a_protocol_gets_the_pull_off_rule_of_its_sphere() {
    let p = build(no_protocol(), &[]).unwrap();
    let rule = crate::pull_off_path::default_pull_off_path(1.0, 0.1, 1.0, 0.0, 0.05);
    assert_eq!(p.path.max_approach, rule.max_approach);
    // One load step straight to the deepest approach, then the rule's retraction.
    assert_eq!(p.path.start, rule.max_approach);
    assert_eq!(p.path.unload_step, rule.unload_step);
    assert_eq!(p.path.coarse_unload_step, Some(rule.coarse_unload_step));
    assert_eq!(p.path.retract_to, None);
    // d_s = (R γ²/E*²)^(1/3) = 0.1^(2/3): 3 d_s deep, 0.02 d_s steps.
    let d_s = 0.1_f64.powf(2.0 / 3.0);
    assert!((p.path.max_approach - 3.0 * d_s).abs() < 1e-12);
    // The same numbers as the pull-off of the sphere given as an array.
    let grid = p.grid;
    let heights = Surface::from_shape(grid, &Sphere::new(1.0).unwrap()).into_heights();
    let spec = crate::heights::PullOffSpec {
        radius: Some(1.0),
        ..crate::heights::PullOffSpec::new(0.05, 1.0, 0.1)
    };
    let plan = crate::heights::pull_off_scene(&heights, &spec).unwrap();
    let q = crate::heights::problem(&plan.scene, &plan.body(&heights)).unwrap();
    assert!((q.path.max_approach - p.path.max_approach).abs() < 1e-12);
    assert_eq!(q.path.unload_step, p.path.unload_step);
    // Steps given in the scene are kept.
    let p = build(no_protocol(), &["protocol.unload_step=0.001"]).unwrap();
    assert_eq!(p.path.unload_step, 0.001);
    // Roughness raises the load depth by its top.
    let rough = format!(
        "{}[roughness]\nkind = \"waviness2d\"\nh = 0.01\nlambda = 0.8\n",
        no_protocol()
    );
    let p = build(&rough, &[]).unwrap();
    assert!(
        p.path.max_approach > rule.max_approach + 0.009,
        "{:?}",
        p.path
    );
}

#[test]
fn a_scene_without_a_path_is_refused_where_no_rule_applies() {
    let e = build(no_protocol(), &["material.gamma=0"])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("protocol.max_approach is required") && e.contains("protocol.indent"),
        "{e}"
    );
    let punch = no_protocol().replace(
        "shape = \"sphere\"\nradius = 1.0",
        "shape = \"flat_punch\"\npunch = \"circle\"\nradius = 0.5",
    );
    let e = build(&punch, &[]).unwrap_err().to_string();
    assert!(e.contains("sphere-like"), "{e}");
    let e = build(no_protocol(), &["protocol.load_step=0.1"])
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("protocol.max_approach is required"), "{e}");
    // max_approach alone is the default pull-off path to that depth (one load step).
    let p = build(no_protocol(), &["protocol.max_approach=0.1"]).unwrap();
    assert_eq!((p.path.start, p.path.max_approach), (0.1, 0.1));
    assert!(p.path_rule.is_some_and(|r| r.path.max_approach == 0.1));
    // A body without a radius then needs the retraction step.
    let e = build(&punch, &["protocol.max_approach=0.1"])
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("protocol.unload_step is required"), "{e}");
    let p = build(
        &punch,
        &["protocol.max_approach=0.1", "protocol.unload_step=0.01"],
    )
    .unwrap();
    assert_eq!(p.path.coarse_unload_step, Some(0.1));
    assert!(p.path_rule.is_none());
}

#[test]
fn a_body_in_memory_with_a_radius_loads_from_its_own_apex() {
    // The sphere given as an array with its radius, on geometry "none" and no [protocol]:
    // the same depth as the sphere scene (the array's highest point is far off the apex).
    let sphere = build(no_protocol(), &[]).unwrap();
    let heights = Surface::from_shape(sphere.grid, &Sphere::new(1.0).unwrap()).into_heights();
    let flat = no_protocol().replace("shape = \"sphere\"\nradius = 1.0", "shape = \"none\"");
    let scene = Scene::parse(&flat, ".", &[]).unwrap();
    let body = HeightBody {
        heights: &heights,
        roughness_range: Some(0.0),
        radius: Some(1.0),
        gamma: None,
    };
    let p = crate::heights::problem(&scene, &body).unwrap();
    assert!(
        (p.path.max_approach - sphere.path.max_approach).abs() < 1e-9,
        "{} vs {}",
        p.path.max_approach,
        sphere.path.max_approach
    );
    assert_eq!(p.path.unload_step, sphere.path.unload_step);
    assert!(!p.path_rule.unwrap().fitted);
    // Too deep for the array: the contact-fits check of the pull-off applies.
    let small = Surface::from_shape(
        Grid::square(12, 0.05, Boundary::Free).unwrap(),
        &Sphere::new(1.0).unwrap(),
    )
    .into_heights();
    let scene = Scene::parse(&flat.replace("n = 64", "n = 12"), ".", &[]).unwrap();
    let e = crate::heights::problem(
        &scene,
        &HeightBody {
            heights: &small,
            ..body
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("too small for the pull-off"), "{e}");
}

#[test]
fn an_indentation_is_one_step_and_excludes_the_path_fields() {
    let text = format!("{}[protocol]\nindent = 0.1\n", no_protocol());
    let p = build(&text, &[]).unwrap();
    assert!(p.path.is_indentation());
    assert_eq!((p.path.start, p.path.max_approach), (0.1, 0.1));
    assert_eq!(p.path.step_bound(), 1);
    let e = build(&text, &["protocol.load_step=0.01"])
        .unwrap_err()
        .to_string();
    assert!(e.contains("leave out protocol.load_step"), "{e}");
    let e = build(&text, &["protocol.indent=-0.5"])
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("protocol.indent = -0.5 never touches the surface"),
        "{e}"
    );
    let e = build(&text, &["protocol.indent=\"deep\""])
        .unwrap_err()
        .to_string();
    assert!(e.contains("protocol.indent"), "{e}");
    // Richardson extrapolates a pull-off, which an indentation does not have.
    let scene = Scene::parse(&text, ".", &[]).unwrap();
    let e = crate::coarse::coarse_problem(&scene, &p)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("an indentation (protocol.indent) has none"),
        "{e}"
    );
    // A load-only path of several steps is not an indentation.
    let load_only = build(SPHERE, &["protocol.retract_to=0.5"]).unwrap();
    assert!(!load_only.path.is_indentation());
    // Too deep for the grid: the message names protocol.indent.
    let e = build(&text, &["protocol.indent=3.0"])
        .unwrap_err()
        .to_string();
    assert!(e.contains("at protocol.indent = 3"), "{e}");
}

#[test]
fn the_memory_bound_counts_the_steps_a_finite_path_takes() {
    // Every field kept on a 512² grid: an indentation keeps one, not 100000 (439.6 GiB).
    let text = format!(
        "{}[protocol]\nindent = 0.1\n[output]\nsnapshots = \"all\"\n",
        no_protocol()
    )
    .replace("n = 64", "n = 512");
    let p = build(&text, &[]).unwrap();
    let e = p.memory_estimate();
    assert_eq!((e.steps, e.snapshots), (1.0, 1.0));
    assert!(e.total() < 1e9, "{e:?}");
    // A path down to retract_to: its load and retraction steps, an upper bound.
    let p = build(SPHERE, &["protocol.retract_to=0.0"]).unwrap();
    let loads = ((0.5 - p.path.start) / 0.05).ceil() + 1.0;
    assert_eq!(p.path.step_bound() as f64, loads + (0.5_f64 / 0.05).floor());
    // A retraction until contact is lost: only max_steps bounds it.
    let p = build(SPHERE, &[]).unwrap();
    assert_eq!(p.path.step_bound(), p.path.max_steps);
}

#[test]
fn sphere_problem_has_jkr_references_and_first_touch_start() {
    let p = build(SPHERE, &[]).unwrap();
    assert_eq!(p.first_touch, 0.0);
    assert_eq!(p.path.start, 0.05);
    assert_eq!(p.path.unload_step, 0.05);
    assert_eq!(p.path.max_steps, DEFAULT_MAX_STEPS);
    assert_eq!(p.kappa, KAPPA);
    let f_jkr = p.references.f_jkr.unwrap();
    assert!((f_jkr + 1.5 * PI * 0.1).abs() < 1e-12);
    assert!(p.references.johnson_alpha.is_none());
}

#[test]
fn coarse_retraction_and_pull_off_snapshots_reach_the_solver() {
    let sets = [
        "protocol.coarse_unload_step=0.2",
        "protocol.unload_step=0.01",
        "output.snapshots=\"pull_off\"",
        "grid.n=128",
    ];
    let p = build(SPHERE, &sets).unwrap();
    assert_eq!(p.path.coarse_unload_step, Some(0.2));
    assert_eq!(p.snapshots, SnapshotRequest::PullOff);
    assert!(p.window.is_some(), "the test wants a cropped run");
    let path = crate::engine::solve(&p, &mut ()).unwrap();
    let r = &path.records;
    // Retraction from 0.5 by 0.2 while compressive, then by 0.01.
    let first = path
        .phases
        .iter()
        .position(|ph| *ph == tack_solver::Phase::Unload);
    assert_eq!(r[first.unwrap()].approach, 0.5 - 0.2);
    let pull_off = (0..r.len())
        .min_by(|&a, &b| r[a].force.total_cmp(&r[b].force))
        .unwrap();
    let last = r.iter().rposition(|s| s.n_bonded > 0).unwrap();
    let steps: Vec<usize> = path.snapshots.iter().map(|s| s.step).collect();
    assert_eq!(steps, [pull_off, last]);
    // On the full grid, as the result file stores them.
    for s in &path.snapshots {
        assert_eq!(s.bonded.dim(), p.grid.shape());
        assert_eq!(s.bonded.iter().filter(|&&b| b).count(), r[s.step].n_bonded);
    }
}

#[test]
fn the_refined_retraction_reaches_the_solver_and_needs_a_coarse_step() {
    let sets = [
        "protocol.coarse_unload_step=0.2",
        "protocol.unload_step=0.01",
        "protocol.refine_pull_off=true",
    ];
    let p = build(SPHERE, &sets).unwrap();
    assert!(p.path.refine_pull_off && p.path.coarse_unload_step == Some(0.2));
    // Its saved states count in the memory estimate.
    let plain = build(SPHERE, &sets[..2]).unwrap();
    let extra = p.memory_estimate().fields - plain.memory_estimate().fields;
    assert_eq!(
        extra,
        64.0 * 64.0 * 8.0 * crate::memory::REFINED_STATE_FIELDS
    );
    let e = build(SPHERE, &[sets[1], sets[2]]).unwrap_err().to_string();
    assert!(
        e.contains(
            "protocol.refine_pull_off = true needs a coarse step: set protocol.coarse_unload_step"
        ),
        "{e}"
    );
    let e = build(SPHERE, &["protocol.refine_pull_off=1"])
        .unwrap_err()
        .to_string();
    assert!(e.contains("protocol.refine_pull_off"), "{e}");
    // The default path takes it too (its coarse step is the rule's), and is fine without.
    assert!(!build(no_protocol(), &[]).unwrap().path.refine_pull_off);
    let p = build(no_protocol(), &[sets[2]]).unwrap();
    assert!(p.path.refine_pull_off && p.path.coarse_unload_step.is_some());
    let e = build(no_protocol(), &["protocol.indent=0.1", sets[2]])
        .unwrap_err()
        .to_string();
    assert!(e.contains("leave out protocol.refine_pull_off"), "{e}");
}

#[test]
fn a_punch_on_an_even_grid_needs_its_spare_element_on_the_short_side() {
    let punch = include_str!("../../../../data/examples/flat_punch.toml");
    // a = 1, Δx = 0.1: the face needs centres out to 1.1 on both sides. An even n = 22
    // reaches only 1.0 on its positive side (the origin is element 11); n = 23 reaches 1.1.
    let e = build(punch, &["grid.n=22"]).unwrap_err().to_string();
    assert!(
        e.contains("geometry.radius = 1") && e.contains("23 × 23"),
        "{e}"
    );
    assert!(build(punch, &["grid.n=21"]).is_err());
    // The issue's case: a = 2 on n = 42 (reaches 2.0), accepted before and then touching
    // the edge in every step.
    let e = build(punch, &["grid.n=42", "geometry.radius=2"]).unwrap_err();
    assert!(e.to_string().contains("43 × 43"), "{e}");
    // A huge punch (below the 1e300 bound) is refused at once, in readable numbers.
    let started = std::time::Instant::now();
    let e = build(punch, &["geometry.radius=1e299"])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("geometry.radius = 1e299") && e.contains("2.000e300 × 2.000e300"),
        "{e}"
    );
    assert!(!e.contains("inf"), "{e}");
    assert!(started.elapsed() < std::time::Duration::from_secs(1));
    for n in [23, 24] {
        let p = build(
            punch,
            &[&format!("grid.n={n}"), "protocol.unload_step=0.05"],
        )
        .unwrap();
        let path = crate::engine::solve(&p, &mut ()).unwrap();
        assert!(path.records.iter().all(|r| !r.edge_contact), "n = {n}");
    }
}

#[test]
fn field_errors_name_the_field_and_range() {
    assert!(
        err(&["material.e_star=-1"])
            .contains("material.e_star = -1 is invalid: must be a finite number > 0")
    );
    assert!(err(&["material.e_star=nan"]).contains("material.e_star = NaN"));
    assert!(err(&["material.gamma=-0.1"]).contains("material.gamma = -0.1"));
    assert!(err(&["grid.n=0"]).contains("grid.n = 0 is invalid"));
    assert!(err(&["grid.n=65536"]).contains("grid.n = 65536 × 65536 is too large"));
    assert!(err(&["grid.dx=-1"]).contains("grid.dx = -1"));
    assert!(err(&["grid.length=3.2"]).contains("exactly one of `dx` and `length`"));
    assert!(err(&["geometry.radius=0"]).contains("geometry.radius = 0"));
    assert!(err(&["solver.tolerance=2"]).contains("solver.tolerance = 2"));
    for t in ["5e-324", "1e-15", "0.5", "nan"] {
        let e = err(&[&format!("solver.tolerance={t}")]);
        let shown = if t == "nan" { "NaN" } else { t };
        assert!(
            e.contains(&format!(
                "solver.tolerance = {shown} is invalid: must be a number in 1e-14..=0.1"
            )),
            "{t}: {e}"
        );
    }
    let e = err(&["grid.dx=1e306"]);
    assert!(
        e.contains("grid.dx = 1e306 give the element area Δx² = an overflow") && !e.contains("inf"),
        "{e}"
    );
    for t in ["1e-14", "0.1", "1e-9"] {
        assert!(
            build(SPHERE, &[&format!("solver.tolerance={t}")]).is_ok(),
            "{t}"
        );
    }
    assert!(err(&["solver.kappa=-1"]).contains("solver.kappa = -1"));
    assert!(err(&["protocol.load_step=0"]).contains("protocol.load_step = 0"));
    assert!(err(&["protocol.retract_to=1"]).contains("protocol.retract_to = 1"));
    assert!(
        err(&["protocol.coarse_unload_step=0"])
            .contains("protocol.coarse_unload_step = 0 is invalid: must be a finite number > 0")
    );
}

#[test]
fn runs_that_cannot_fit_in_memory_are_refused_before_they_run() {
    // Every step's fields of a 2048² grid over 100000 steps: 6.9 TiB.
    let e = err(&["grid.n=2048", "output.snapshots=\"all\""]);
    assert!(
        e.contains("may need about 6.9 TiB")
            && e.contains("output.snapshots = \"all\"")
            && e.contains("protocol.max_steps = 100000")
            && e.contains("grid.n = 2048 × 2048"),
        "{e}"
    );
    // 10^18 step records.
    let e = err(&["protocol.max_steps=1000000000000000000"]);
    assert!(
        e.contains("for 1000000000000000000 step records")
            && e.contains("protocol.max_steps = 1000000000000000000"),
        "{e}"
    );
    // A bounded path with every field fits.
    assert!(
        build(
            SPHERE,
            &["output.snapshots=\"all\"", "protocol.max_steps=2000"]
        )
        .is_ok()
    );
}

#[test]
fn scene_level_checks() {
    let e = err(&["protocol.max_approach=-0.1"]);
    assert!(
        e.contains("protocol.max_approach = -0.1 never touches") && e.contains("first touch"),
        "{e}"
    );
    let e = err(&["protocol.max_approach=4"]);
    assert!(e.contains("grid.n = 64 is too small"), "{e}");
    let e = err(&[
        "roughness.kind=waviness2d",
        "roughness.h=0.01",
        "roughness.lambda=0.1",
    ]);
    assert!(
        e.contains("roughness.lambda = 0.1 is invalid: must be ≥ 4·grid.dx"),
        "{e}"
    );
    let e = err(&[
        "roughness.kind=random",
        "roughness.h=0.01",
        "roughness.hurst=0.5",
        "roughness.q1=100",
    ]);
    assert!(e.contains("roughness.q0/q1"), "{e}");
}

#[test]
fn a_height_map_path_that_is_no_file_says_what_it_is() {
    let dir = std::env::temp_dir();
    let dir = dir.to_str().unwrap();
    for (path, what) in [
        (dir, "is a directory, not a map file"),
        ("/dev/null", "is not a regular file"),
        ("/no/such/map.txt", "no such file"),
    ] {
        let e = err(&["roughness.kind=file", &format!("roughness.path=\"{path}\"")]);
        assert!(
            e.contains(&format!("roughness.path = `{path}`")) && e.contains(what),
            "{path}: {e}"
        );
    }
}

#[test]
fn rough_sphere_has_alpha_star_and_seed() {
    let p = build(
        SPHERE,
        &[
            "roughness.kind=random",
            "roughness.h=0.001",
            "roughness.hurst=0.5",
            "roughness.seed=7",
        ],
    )
    .unwrap();
    assert_eq!(p.seed, Some(7));
    assert!(p.first_touch < 0.0);
    assert!(p.references.alpha_star.unwrap() > 0.0);
}

#[test]
fn periodic_waviness_must_fit_the_period() {
    let strip = r#"
version = 1
[material]
e_star = 1.0
gamma = 0.0
[geometry]
shape = "none"
[roughness]
kind = "waviness1d"
h = 0.01
lambda = 1.0
[grid]
nx = 64
ny = 1
length = 1.0
boundary = "periodic"
[protocol]
max_approach = 0.01
load_step = 0.001
"#;
    let p = build(strip, &[]).unwrap();
    assert!(p.references.johnson_alpha.is_some());
    let e = build(strip, &["roughness.lambda=0.3"])
        .unwrap_err()
        .to_string();
    assert!(e.contains("does not fit the periodic grid"), "{e}");
}

mod adhesion_tests {
    use super::*;

    fn build(sets: &[&str]) -> Result<Problem, SceneError> {
        let text = "version = 1\n[material]\ne_star = 1.0\ngamma = 0.1\n[geometry]\nshape = \
                \"sphere\"\nradius = 1.0\n[grid]\nn = 128\ndx = 0.02\n";
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        Problem::from_scene(&Scene::parse(text, ".", &sets)?)
    }

    fn err(sets: &[&str]) -> String {
        build(sets).unwrap_err().to_string()
    }

    #[test]
    fn power_law_bodies_are_read_checked_and_referenced() {
        let scene = |c: &str, m: &str| {
            format!(
                "version = 1\n[material]\ne_star = 1.0\ngamma = 0.05\n[geometry]\nshape = \
             \"power_law\"\nc = {c}\nexponent = {m}\n[grid]\nn = 80\ndx = 0.1\n\
             [protocol]\nmax_approach = 1.44\nload_step = 1.44\n"
            )
        };
        let p =
            Problem::from_scene(&Scene::parse(&scene("0.5", "1.0"), ".", &[]).unwrap()).unwrap();
        let f = p.references.f_mdr.unwrap();
        assert!((f + 0.343775).abs() < 1e-6, "{f}");
        assert!(p.references.f_jkr.is_none());
        for (c, m, field) in [
            ("0.0", "1.0", "geometry.c"),
            ("0.5", "0.5", "geometry.exponent"),
            ("1e300", "16.0", "geometry.c"),
        ] {
            let e = Problem::from_scene(&Scene::parse(&scene(c, m), ".", &[]).unwrap())
                .unwrap_err()
                .to_string();
            assert!(e.contains(field), "{e}");
        }
        // No reference on a periodic grid, with a warning.
        let periodic =
            scene("0.5", "1.0").replace("dx = 0.1\n", "dx = 0.1\nboundary = \"periodic\"\n");
        let p = Problem::from_scene(&Scene::parse(&periodic, ".", &[]).unwrap()).unwrap();
        assert!(p.references.f_mdr.is_none());
        assert!(
            p.warnings.iter().any(|w| w.contains("no F_MDR reference")),
            "{:?}",
            p.warnings
        );
        // A grid too small for the penetrated disc names the grid size.
        let small = scene("0.5", "1.0").replace("n = 80", "n = 30");
        let e = Problem::from_scene(&Scene::parse(&small, ".", &[]).unwrap())
            .unwrap_err()
            .to_string();
        assert!(e.contains("grid.n") && e.contains("power-law"), "{e}");
    }

    #[test]
    fn loaded_steps_count_the_steps_beyond_the_first_touch() {
        let path = |start: f64, max: f64, step: f64| tack_solver::ApproachPath {
            start,
            max_approach: max,
            load_step: step,
            unload_step: step,
            coarse_unload_step: None,
            refine_pull_off: false,
            retract_to: None,
            max_steps: 1000,
        };
        // One step straight to the depth; loads 0.1, 0.2, …, 1.0 beyond a touch at 0.35.
        let all = usize::MAX;
        assert_eq!(loaded_steps(&path(1.0, 1.0, 1.0), 0.0, all), 1);
        assert_eq!(loaded_steps(&path(1.0, 1.0, 1.0), 2.0, all), 0);
        assert_eq!(loaded_steps(&path(0.1, 1.0, 0.1), 0.35, all), 7);
        assert_eq!(loaded_steps(&path(-0.5, 1.0, 0.5), 0.0, all), 2);
        assert_eq!(loaded_steps(&path(0.5, 1.0, 0.5), -1.0, all), 2);
        // Beyond the deepest approach nothing is loaded; the solver's own steps (0.88 + k·0.01
        // below 1.04, then 1.04: 17); a tiny step is counted only up to the limit.
        assert_eq!(loaded_steps(&path(0.0, 1.0, 0.5), 2.0, all), 0);
        assert_eq!(loaded_steps(&path(0.88, 1.04, 0.01), 0.0, all), 17);
        assert_eq!(loaded_steps(&path(-1.0, 1.0, 1e-20), 0.0, 2), 0);
        assert_eq!(loaded_steps(&path(-1.0, 1.0, 1e-2), 0.0, 2), 2);
    }

    #[test]
    fn a_rough_body_loaded_in_steps_under_the_zero_range_law_is_warned() {
        let rough = [
            "roughness.kind=\"random\"",
            "roughness.h=0.002",
            "roughness.hurst=0.5",
            "roughness.seed=1",
        ];
        let warned = |p: &Problem| p.warnings.iter().any(|w| w.contains("loading history"));
        // The default path loads in one step: no warning.
        assert!(!warned(&build(&rough).unwrap()));
        let mut stepped = rough.to_vec();
        stepped.extend([
            "protocol.start=-0.02",
            "protocol.max_approach=0.1",
            "protocol.load_step=0.01",
            "protocol.unload_step=0.001",
        ]);
        let p = build(&stepped).unwrap();
        assert!(warned(&p), "{:?}", p.warnings);
        // Not for the smooth sphere, nor a waviness (its figures load in steps on purpose),
        // nor under the Dugdale law.
        assert!(!warned(&build(&stepped[4..]).unwrap()));
        let mut wavy = vec![
            "roughness.kind=\"waviness2d\"",
            "roughness.h=0.002",
            "roughness.lambda=0.2",
        ];
        wavy.extend(&stepped[4..]);
        assert!(!warned(&build(&wavy).unwrap()));
        let mut dugdale = stepped.clone();
        dugdale.extend(["adhesion.model=\"dugdale\"", "adhesion.sigma0=1.0"]);
        assert!(!warned(&build(&dugdale).unwrap()));
    }

    #[test]
    fn the_smooth_laws_are_read_and_their_inputs_are_checked() {
        let exp = ["adhesion.model=\"exponential\"", "adhesion.range=0.05"];
        let p = build(&exp).unwrap();
        assert_eq!(p.law, AdhesionLaw::Exponential(Exponential { range: 0.05 }));
        // Tabor's μ of the sphere R = 1 (E* = 1, γ = 0.1): (Rγ²/(E*²ρ³))^(1/3) = 0.1^(2/3)/0.05.
        let mu = p.references.tabor_mu.unwrap();
        assert!((mu - 0.1f64.powf(2.0 / 3.0) / 0.05).abs() < 1e-12, "{mu}");
        // The default path starts where the law's tension is 1e-4 of the peak, ln(1e4) ρ = 9.2 ρ
        // before the first touch (the reach, 18.4 ρ, is where it is 1e-8), to 1% (the scan).
        let ahead = -(p.path.start + p.path.load_step);
        assert!(
            (ahead / (1e4f64.ln() * 0.05) - 1.0).abs() < 0.01,
            "{}",
            p.path.start
        );
        let lj = build(&["adhesion.model=\"lennard_jones\"", "adhesion.range=0.05"]).unwrap();
        assert_eq!(
            lj.law,
            AdhesionLaw::LennardJones(LennardJones { range: 0.05 })
        );
        assert!(err(&["adhesion.model=\"exponential\""]).contains("adhesion.range is required"));
        for bad in ["0.0", "-1.0", "nan", "inf"] {
            let message = err(&[
                "adhesion.model=\"exponential\"",
                &format!("adhesion.range={bad}"),
            ]);
            assert!(message.starts_with("adhesion.range = "), "{message}");
            assert!(message.contains("a finite number > 0"), "{message}");
        }
        // A range below the round-off of the heights, another law's parameter, κ, no γ.
        assert!(
            err(&["adhesion.model=\"exponential\"", "adhesion.range=1e-20"])
                .contains("above 1e-12 of the largest height")
        );
        assert!(
            err(&[exp[0], exp[1], "adhesion.sigma0=1"])
                .contains("adhesion.sigma0 = 1 is read by adhesion.model = \"dugdale\" or \"smoothed_dugdale\" only")
        );
        assert!(
            err(&[
                "adhesion.model=\"dugdale\"",
                "adhesion.sigma0=1",
                "adhesion.range=0.1"
            ])
            .contains(
                "adhesion.range = 0.1 is read by adhesion.model = \"exponential\" or \
                 \"lennard_jones\" only"
            )
        );
        assert!(err(&["adhesion.range=0.1"]).contains("\"jkr_limit\" does not read it"));
        assert!(
            err(&[exp[0], exp[1], "solver.kappa=0.5"])
                .contains("solver.kappa = 0.5 is read by adhesion.model = \"jkr_limit\" only")
        );
        assert!(err(&[exp[0], exp[1], "material.gamma=0"]).contains("needs material.gamma > 0"));
        // A smooth law loads from out of reach in steps of at least ρ/50
        // (`STEPS_PER_LENGTH`), up to the coarse retraction step: range 20, from 9.2 ρ = 184,
        // in steps of min(20/50, coarse) = the coarse step, where the fine step would have
        // taken 100 000 or more (and been refused, below).
        let long = ["adhesion.model=\"exponential\"", "adhesion.range=20"];
        let p = build(&long).unwrap();
        let coarse = p.path.coarse_unload_step.unwrap();
        assert!(coarse < 20.0 / 50.0, "{coarse}");
        assert_eq!(p.path.load_step, coarse);
        let steps = ((p.path.max_approach - p.path.start) / p.path.load_step).ceil();
        let fine = ((p.path.max_approach - p.path.start) / p.path.unload_step).ceil();
        assert!(
            steps < 0.1 * fine && fine >= 100_000.0,
            "{steps} against {fine}"
        );
        // Range 0.05: ρ/50 = 1e-3 is shorter than the retraction step, which stays.
        let p = build(&exp).unwrap();
        assert_eq!(p.path.load_step, p.path.unload_step);
        // A reach so long that the default path would spend every step of the default cap
        // loading is refused, naming the cap and what to give instead (a Dugdale law of σ0 =
        // 1e-4, range γ/σ0 = 1000, loads in retraction steps); a cap the scene sets is its own
        // (a short look at the load: range 0.05, 18.4 ρ = 0.92 of reach, in 100 steps), and
        // with the cap raised past its load steps the long reach is taken too.
        let long = ["adhesion.model=\"dugdale\"", "adhesion.sigma0=1e-4"];
        let message = err(&long);
        assert!(
            message.starts_with("the default path loads from out of the law's reach")
                && message.contains("the default protocol.max_steps = 100000")
                && message.contains("(adhesion.sigma0)"),
            "{message}"
        );
        let p = build(&[exp[0], exp[1], "protocol.max_steps=100"]).unwrap();
        assert_eq!(p.path.max_steps, 100);
        let p = build(&[long[0], long[1], "protocol.max_steps=2000000"]).unwrap();
        assert_eq!(p.path.max_steps, 2_000_000);
        // The round loop's settings are refused under a smooth law, which has none.
        for set in [
            "solver.tolerance=1e-12",
            "solver.max_active_set_iterations=1",
            "solver.round_tolerance=0",
            "solver.local_relaxation=false",
            "solver.cascade=false",
        ] {
            let message = err(&[exp[0], exp[1], set]);
            let field = set.split('=').next().unwrap();
            assert!(
                message.starts_with(&format!("{field} = "))
                    && message.contains("is read by adhesion.model = \"jkr_limit\"")
                    && message.contains("has no detach/attach rounds")
                    && message.ends_with(&format!("leave {field} out")),
                "{message}"
            );
        }
        // The local relaxation is the criterion's: refused under the Dugdale law too, whose
        // rounds read the round loop's settings.
        let dugdale = ["adhesion.model=\"dugdale\"", "adhesion.sigma0=1.0"];
        for set in ["solver.local_relaxation=false", "solver.cascade=true"] {
            let message = err(&[dugdale[0], dugdale[1], set]);
            assert!(
                message.contains("is read by adhesion.model = \"jkr_limit\" only: the Dugdale"),
                "{message}"
            );
        }
        assert!(build(&[dugdale[0], dugdale[1], "solver.round_tolerance=0"]).is_ok());
        assert!(build(&["solver.cascade=false"]).is_ok());
        assert!(build(&[exp[0], exp[1], "solver.max_iterations=100"]).is_ok());
        // A path out of contact but within a finite-range law's reach (18.4 ρ = 0.92 here) is
        // a path; one that never comes within the reach is refused, and under the criterion a
        // path at or below the first touch still never touches.
        let near = [
            "protocol.start=-0.5",
            "protocol.max_approach=-0.1",
            "protocol.load_step=0.01",
        ];
        let p = build(&[exp[0], exp[1], near[0], near[1], near[2]]).unwrap();
        assert_eq!((p.path.start, p.path.max_approach), (-0.5, -0.1));
        let p = build(&[exp[0], exp[1], "protocol.indent=-0.1"]).unwrap();
        assert!(p.path.is_indentation());
        let far = [
            "protocol.start=-1.5",
            "protocol.max_approach=-1.0",
            "protocol.load_step=0.01",
        ];
        let message = err(&[exp[0], exp[1], far[0], far[1], far[2]]);
        assert!(
            message.starts_with(
                "protocol.max_approach = -1 never comes within the law's reach of the surface"
            ) && message.contains("must be > -0.92"),
            "{message}"
        );
        let message = err(&near);
        assert!(
            message.starts_with("protocol.max_approach = -0.1 never touches the surface"),
            "{message}"
        );
        // The pull-off radius' mesh rule is the criterion's: a_c = 0.707 spans 3.5 elements at
        // Δx = 0.2; the smooth law warns of its own zone only.
        let flagged = |p: &Problem| {
            p.warnings
                .iter()
                .any(|w| w.starts_with("under-resolved pull-off:"))
        };
        assert!(flagged(&build(&["grid.dx=0.2"]).unwrap()));
        let p = build(&[exp[0], exp[1], "grid.dx=0.2"]).unwrap();
        assert!(!flagged(&p), "{:?}", p.warnings);
        assert!(
            p.warnings
                .iter()
                .any(|w| w.starts_with("under-resolved process zone")),
            "{:?}",
            p.warnings
        );
        // A range the grid cannot resolve to round-off is refused before running (Δx = 0.02,
        // γ = 0.1: the least is 2.7e-5), naming the least; the least itself is taken.
        let message = err(&["adhesion.model=\"exponential\"", "adhesion.range=1e-6"]);
        assert!(
            message.starts_with("adhesion.range = 1e-6 is invalid: must be at least ")
                && message.contains("\"jkr_limit\""),
            "{message}"
        );
    }

    #[test]
    fn a_viscoelastic_solid_is_read_and_its_inputs_are_checked() {
        let exp = ["adhesion.model=\"exponential\"", "adhesion.range=0.05"];
        let path = [
            "protocol.max_approach=0.5",
            "protocol.load_step=0.05",
            "protocol.speed=0.1",
        ];
        let visco = [
            exp[0],
            exp[1],
            path[0],
            path[1],
            path[2],
            "material.prony=[[9.0, 2.0]]",
        ];
        let p = build(&visco).unwrap();
        let (prony, rates) = p.viscoelastic.as_ref().expect("a viscoelastic solid");
        assert_eq!((prony.relaxed(), prony.instantaneous()), (1.0, 10.0));
        assert_eq!(
            (rates.speed, rates.unload_speed, rates.dwell),
            (0.1, 0.1, 0.0)
        );
        fn with<'a>(base: &[&'a str], extra: &[&'a str]) -> Vec<&'a str> {
            [base, extra].concat()
        }
        let held = build(&with(
            &visco,
            &["protocol.dwell=3.0", "protocol.unload_speed=1.0"],
        ))
        .unwrap();
        let rates = held.viscoelastic.unwrap().1;
        assert_eq!(
            (rates.unload_speed, rates.dwell, rates.dwell_steps),
            (1.0, 3.0, 20)
        );
        assert!(p.solver(None).unwrap().viscoelastic().is_some());
        // Rates without a viscoelastic solid.
        for rate in [
            "protocol.speed=1.0",
            "protocol.dwell=1.0",
            "protocol.unload_speed=1.0",
        ] {
            let message = err(&[exp[0], exp[1], path[0], path[1], rate]);
            assert!(
                message.contains("read only for a viscoelastic solid"),
                "{message}"
            );
        }
        // Bad arms, named.
        for bad in ["[[-1.0, 1.0]]", "[[1.0, 0.0]]", "[[1.0, nan]]", "[]"] {
            let arms = format!("material.prony={bad}");
            let message = err(&with(&visco[..5], &[&arms]));
            assert!(message.starts_with("material.prony = "), "{bad}: {message}");
        }
        // The criterion with adhesion, no speed, no path in time, refined retraction, a film.
        let criterion = [path[0], path[1], path[2], "material.prony=[[9.0, 2.0]]"];
        let message = err(&criterion);
        assert!(
            message.contains("needs a finite-range law")
                && message.ends_with(
                    "\"dugdale\", \"exponential\", \"lennard_jones\" or \"smoothed_dugdale\""
                ),
            "{message}"
        );
        let no_speed = [
            exp[0],
            exp[1],
            path[0],
            path[1],
            "material.prony=[[9.0, 2.0]]",
        ];
        assert!(err(&no_speed).contains("needs protocol.speed"));
        let default_path = [exp[0], exp[1], path[2], "material.prony=[[9.0, 2.0]]"];
        assert!(err(&default_path).contains("needs a path in time"));
        assert!(
            err(&with(
                &visco,
                &[
                    "protocol.coarse_unload_step=0.1",
                    "protocol.refine_pull_off=true"
                ]
            ))
            .contains("protocol.refine_pull_off retraces steps")
        );
        assert!(
            err(&with(&visco, &["protocol.dwell_steps=4"])).contains("give protocol.dwell too")
        );
        for bad in [
            "protocol.speed=-1.0",
            "protocol.dwell=-1.0",
            "protocol.unload_speed=0.0",
        ] {
            let message = err(&with(&visco, &[bad]));
            let field = bad.split('=').next().unwrap();
            assert!(message.starts_with(&format!("{field} = ")), "{message}");
        }
        let film = with(
            &visco,
            &[
                "body.kind=\"layer\"",
                "body.thickness=1.0",
                "body.poisson=0.3",
                "grid.boundary=\"periodic\"",
            ],
        );
        let message = err(&film);
        assert!(
            message.contains("viscoelastic solids are half-spaces"),
            "{message}"
        );
    }

    #[test]
    fn the_smoothed_dugdale_law_is_bound_to_the_grid() {
        let p = build(&["adhesion.model=\"smoothed_dugdale\"", "adhesion.sigma0=1.0"]).unwrap();
        // γ = 0.1 and E* = 1 of the test scene, on its own grid's elements.
        let dx = p.grid.dx();
        let expected = tack_solver::SmoothedDugdale::on_mesh(1.0, 0.1, 1.0, dx).unwrap();
        assert_eq!(p.law, AdhesionLaw::SmoothedDugdale(expected));
        assert!(p.law.is_smooth() && p.law.convergence_order() == 1.0);
        let lambda = p.references.maugis_lambda.unwrap();
        assert!((lambda - tack_analytics::maugis_lambda(1.0, 0.1, 1.0, 1.0)).abs() < 1e-12);
        assert!(
            err(&["adhesion.model=\"smoothed_dugdale\""])
                .contains("adhesion.sigma0 is required with")
        );
        assert!(
            err(&[
                "adhesion.model=\"smoothed_dugdale\"",
                "adhesion.sigma0=1",
                "adhesion.range=0.1"
            ])
            .contains("adhesion.range = 0.1 is read by")
        );
        for bad in ["0.0", "-1.0", "nan", "inf"] {
            let message = err(&[
                "adhesion.model=\"smoothed_dugdale\"",
                &format!("adhesion.sigma0={bad}"),
            ]);
            assert!(message.starts_with("adhesion.sigma0 = "), "{message}");
        }
    }

    #[test]
    fn the_dugdale_law_is_read_and_its_inputs_are_checked() {
        let p = build(&["adhesion.model=\"dugdale\"", "adhesion.sigma0=1.0"]).unwrap();
        assert_eq!(p.law, AdhesionLaw::Dugdale(Dugdale { sigma0: 1.0 }));
        // The default path approaches from out of range (h0 = γ/σ0 = 0.1) in its fine step.
        assert!(p.path.start < -0.1 && p.path.load_step == p.path.unload_step);
        let lambda = p.references.maugis_lambda.unwrap();
        assert!((lambda - tack_analytics::maugis_lambda(1.0, 0.1, 1.0, 1.0)).abs() < 1e-12);
        assert!(p.references.f_maugis.unwrap() < 0.0);
        assert!(build(&[]).unwrap().law == AdhesionLaw::JkrLimit(JkrLimit { kappa: KAPPA }));
        assert!(
            err(&["adhesion.sigma0=1.0"])
                .contains("adhesion.sigma0 = 1 is read by adhesion.model = \"dugdale\" or \"smoothed_dugdale\" only")
        );
        assert!(err(&["adhesion.model=\"dugdale\""]).contains("adhesion.sigma0 is required with"));
        for bad in ["0.0", "-1.0", "nan", "inf"] {
            let message = err(&[
                "adhesion.model=\"dugdale\"",
                &format!("adhesion.sigma0={bad}"),
            ]);
            assert!(message.starts_with("adhesion.sigma0 = "), "{message}");
            assert!(message.contains("a finite number > 0"), "{message}");
        }
        assert!(
            err(&["adhesion.model=\"dugdale\"", "adhesion.sigma0=1e20"])
                .contains("exceeds 1e-12 of the largest height")
        );
        assert!(
            err(&[
                "adhesion.model=\"dugdale\"",
                "adhesion.sigma0=1",
                "solver.kappa=0.5"
            ])
            .contains("solver.kappa = 0.5 is read by adhesion.model = \"jkr_limit\" only")
        );
        assert!(
            err(&[
                "adhesion.model=\"dugdale\"",
                "adhesion.sigma0=1",
                "material.gamma=0"
            ])
            .contains("needs material.gamma > 0")
        );
        assert!(err(&["adhesion.model=\"dmt\""]).contains("adhesion.model"));
    }

    #[test]
    fn an_unresolved_cohesive_zone_warns() {
        // l = πE*γ/(4σ0²) = 0.0785 at σ0 = 1: 3.9 elements of 0.02; at σ0 = 2: 0.98.
        let fine = build(&["adhesion.model=\"dugdale\"", "adhesion.sigma0=1.0"]).unwrap();
        assert!(!fine.warnings.iter().any(|w| w.contains("cohesive zone")));
        let coarse = build(&["adhesion.model=\"dugdale\"", "adhesion.sigma0=2.0"]).unwrap();
        assert!(
            coarse
                .warnings
                .iter()
                .any(|w| w.starts_with("under-resolved cohesive zone") && w.contains("0.98")),
            "{:?}",
            coarse.warnings
        );
    }
}

/// A path of the scene's own whose load alone takes the default cap would stop before
/// retracting: refused, naming the count, the cap and what to change; a cap the scene sets is
/// its own (a short look at the load runs).
#[test]
fn a_load_longer_than_the_default_cap_is_refused() {
    // From the first touch 0 + 5e-6 to 0.5 in steps of 5e-6: 100 000 load steps.
    let message = err(&["protocol.load_step=5e-6"]);
    assert!(
        message
            .starts_with("the path loads from d = 5e-6 to 0.5 in steps of 5e-6: 100000 load steps")
            && message.contains("the default protocol.max_steps = 100000")
            && message.contains("raise protocol.load_step"),
        "{message}"
    );
    // One step fewer than the cap runs (its retraction has one step).
    assert!(build(SPHERE, &["protocol.load_step=5.00006e-6"]).is_ok());
    let p = build(
        SPHERE,
        &["protocol.load_step=5e-6", "protocol.max_steps=10"],
    )
    .unwrap();
    assert_eq!((p.path.max_steps, p.path.load_steps()), (10, 100_000.0));
}
