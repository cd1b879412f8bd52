//! A law held in memory ([`Problem::with_law`]): a custom copy of the exponential law run on
//! the example scene without its `[adhesion]` gives the built-in scene's path, crop window,
//! references and force bits, names itself in the result file, and carries into the coarse run
//! of `--richardson`; a scene that also names a law, or lacks what the law needs, is refused
//! naming the field.

use std::path::PathBuf;

use tack::solver::{AdhesionLaw, Curve, Exponential};
use tack::{Problem, RunOptions, Scene};

/// The example scene of the exponential law (ρ = 3.3333e-3, μ = 3, 64²).
fn example() -> String {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/examples/exponential_sphere.toml");
    std::fs::read_to_string(path).unwrap()
}

/// The example without its `[adhesion]` table, with `extra` appended.
fn without_law(extra: &str) -> Scene {
    let text = example().replace(
        "[adhesion]\nmodel = \"exponential\"\nrange = 3.3333e-3\n",
        "",
    );
    assert!(!text.contains("[adhesion]"), "the table is gone");
    Scene::parse(&format!("{text}\n{extra}"), ".", &[]).unwrap()
}

/// The exponential law under another name, through [`AdhesionLaw::custom`].
#[derive(Debug)]
struct Copied(Exponential);

impl Curve for Copied {
    fn name(&self) -> &'static str {
        "exp_copy"
    }
    fn label(&self) -> &'static str {
        "a copy of the exponential law, range rho"
    }
    fn length(&self) -> f64 {
        self.0.length()
    }
    fn meaning(&self) -> &'static str {
        "the range of the copied law"
    }
    fn pressure(&self, gamma: f64, g: f64) -> f64 {
        self.0.pressure(gamma, g)
    }
    fn stiffness(&self, gamma: f64, g: f64) -> f64 {
        self.0.stiffness(gamma, g)
    }
    fn pressure_and_stiffness(&self, gamma: f64, g: f64) -> (f64, f64) {
        self.0.pressure_and_stiffness(gamma, g)
    }
    fn stiffens(&self) -> bool {
        self.0.stiffens()
    }
    fn peak(&self, gamma: f64) -> f64 {
        self.0.peak(gamma)
    }
    fn reach(&self) -> f64 {
        Curve::reach(&self.0)
    }
    fn falls_past_peak(&self) -> bool {
        self.0.falls_past_peak()
    }
}

fn copy(range: f64) -> AdhesionLaw {
    AdhesionLaw::custom(Copied(Exponential { range })).unwrap()
}

#[test]
fn a_law_in_memory_runs_as_the_scene_law_it_copies() {
    let built_in = Scene::parse(&example(), ".", &[]).unwrap();
    let scene = without_law("");
    let (a, b) = (
        Problem::from_scene(&built_in).unwrap(),
        Problem::with_law(&scene, copy(3.3333e-3)).unwrap(),
    );
    assert!(!a.law_in_memory && b.law_in_memory);
    assert_eq!(b.law.name(), "exp_copy");
    assert_eq!(
        a.path, b.path,
        "the default path starts out of the law's reach"
    );
    assert_eq!(a.window, b.window, "the crop window holds the law's reach");
    assert_eq!(a.references.tabor_mu, b.references.tabor_mu);
    assert!(
        b.references
            .tabor_mu
            .is_some_and(|mu| (mu - 3.0).abs() < 1e-3)
    );
    assert_eq!(
        a.warnings, b.warnings,
        "the same mesh warning (0.6 elements per zone)"
    );
    let options = RunOptions::default();
    let x = tack::run(&built_in, &options, &mut ()).unwrap();
    let y = tack::engine::execute(&scene, b, &options, &mut ()).unwrap();
    assert_eq!(x.path.records.len(), y.path.records.len());
    for (r, s) in x.path.records.iter().zip(&y.path.records) {
        assert_eq!(
            r.force.to_bits(),
            s.force.to_bits(),
            "at d = {}",
            r.approach
        );
    }
    // The result names the law and keeps its entries.
    let dir = std::env::temp_dir().join(format!("tack-custom-law-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("copy.h5");
    y.write(&out).unwrap();
    let back = tack::io::read_result(&out).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(back.summary.adhesion_model.as_deref(), Some("exp_copy"));
    // The stored scene cannot hold the law: its first line says so.
    let first = back.provenance.scene.lines().next().unwrap();
    assert!(
        first.starts_with("# The adhesion law was given in memory"),
        "{first}"
    );
    assert!(first.contains("exp_copy"), "{first}");
    let (ex, ey) = (&x.result.summary.extra, &back.summary.extra);
    for key in ["range", "peak_tension", "process_zone_elements", "tabor_mu"] {
        assert_eq!(ex.get(key), ey.get(key), "{key}");
        assert!(ey.contains_key(key), "{key}");
    }
}

/// `--richardson` under the law in memory: its coarse problem keeps the curve, and the coarse
/// and extrapolated pull-offs are the built-in scene's bits.
#[test]
fn the_richardson_coarse_run_keeps_a_law_in_memory() {
    let scene = without_law("");
    let fine = Problem::with_law(&scene, copy(3.3333e-3)).unwrap();
    let coarse = tack::coarse::coarse_problem(&scene, &fine).unwrap();
    assert_eq!(coarse.law, fine.law, "the same curve");
    assert!(coarse.law_in_memory);
    assert_eq!(coarse.grid.dx(), 2.0 * fine.grid.dx());
    let options = RunOptions {
        richardson: true,
        ..RunOptions::default()
    };
    let built_in = Scene::parse(&example(), ".", &[]).unwrap();
    let x = tack::run(&built_in, &options, &mut ()).unwrap();
    let y = tack::engine::execute(&scene, fine, &options, &mut ()).unwrap();
    for key in ["pull_off_force_coarse", "pull_off_force_richardson"] {
        let (a, b) = (
            x.result.summary.extra.get(key),
            y.result.summary.extra.get(key),
        );
        assert!(a.is_some(), "{key}");
        assert_eq!(a.map(|v| v.to_bits()), b.map(|v| v.to_bits()), "{key}");
    }
}

/// The zero-range criterion given in memory brings its κ (the scene may not name one).
#[test]
fn a_criterion_in_memory_brings_its_kappa() {
    let text = example().replace(
        "[adhesion]\nmodel = \"exponential\"\nrange = 3.3333e-3\n",
        "",
    );
    let scene = Scene::parse(&text, ".", &[]).unwrap();
    let law = AdhesionLaw::from(tack::solver::JkrLimit { kappa: 0.5 });
    let p = Problem::with_law(&scene, law).unwrap();
    assert_eq!(p.kappa, 0.5);
    let bad = AdhesionLaw::from(tack::solver::JkrLimit { kappa: -1.0 });
    let e = Problem::with_law(&scene, bad).unwrap_err().to_string();
    assert!(e.contains("solver.kappa"), "{e}");
}

#[test]
fn a_scene_that_also_names_a_law_or_lacks_gamma_is_refused_naming_the_field() {
    let law = copy(3.3333e-3);
    let cases = [
        (
            Scene::parse(&example(), ".", &[]).unwrap(),
            "adhesion.model",
        ),
        (without_law("[adhesion]\nrange = 1e-3\n"), "adhesion.range"),
        (without_law("[adhesion]\nsigma0 = 0.3\n"), "adhesion.sigma0"),
        (without_law("[solver]\nkappa = 0.5\n"), "solver.kappa"),
    ];
    for (scene, field) in cases {
        let e = Problem::with_law(&scene, law.clone())
            .unwrap_err()
            .to_string();
        eprintln!("{e}");
        assert!(e.contains(field) && e.contains("exp_copy"), "{field}: {e}");
    }
    let text = example()
        .replace(
            "[adhesion]\nmodel = \"exponential\"\nrange = 3.3333e-3\n",
            "",
        )
        .replace("gamma = 1.0e-3", "gamma = 0.0");
    let scene = Scene::parse(&text, ".", &[]).unwrap();
    let e = Problem::with_law(&scene, law).unwrap_err().to_string();
    eprintln!("{e}");
    assert!(e.contains("material.gamma"), "{e}");
    // A range on the round-off of the heights: the law's own check.
    let e = Problem::with_law(&without_law(""), copy(1e-16))
        .unwrap_err()
        .to_string();
    eprintln!("{e}");
    assert!(e.contains("adhesion.range"), "{e}");
}
