//! What a new user reads after `tack run`, `tack check`, `tack info` and `tack plot` on the
//! example scenes must be true and readable: PNG figures by default, errors that name the
//! user's output, paths described as they were walked, no apparent γ of 0 beside an adhesive
//! pull-off, no loop quantity the refined retraction cannot measure, plots whose force axis
//! shows the pull-off, every number rounded, and counts named for what they count.

mod common;

use std::path::Path;

use common::{Scratch, examples_dir, run, text};

fn s(p: &Path) -> String {
    p.to_str().expect("utf-8 path").to_owned()
}

/// `tack run` on an example (with `--set` overrides): its printed report and the result file.
fn run_example(scratch: &Scratch, name: &str, sets: &[&str]) -> (String, std::path::PathBuf) {
    let scene = examples_dir().join(format!("{name}.toml"));
    let out = scratch.join(&format!("{name}.h5"));
    let mut args = vec![
        "run".to_owned(),
        s(&scene),
        "-o".to_owned(),
        s(&out),
        "--quiet".to_owned(),
    ];
    for set in sets {
        args.extend(["--set".to_owned(), (*set).to_owned()]);
    }
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let o = run(&args);
    let (stdout, stderr) = text(&o);
    assert!(o.status.success(), "tack run {name}: {stderr}");
    (stdout, out)
}

/// Numbers printed with more than 7 significant digits (runs of 8 or more digits after the
/// leading zeros, a decimal point allowed among them).
fn long_numbers(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut current = String::new();
    for c in text.chars().chain(std::iter::once(' ')) {
        if c.is_ascii_digit() || (c == '.' && !current.is_empty()) {
            current.push(c);
        } else {
            let significant = current.trim_start_matches(['0', '.']);
            if significant.chars().filter(char::is_ascii_digit).count() >= 8 {
                out.push(current.clone());
            }
            current.clear();
        }
    }
    out
}

/// Built with `--no-default-features`: PNG is refused naming the user's output (not a
/// temporary) and the feature to build with.
#[cfg(not(feature = "png"))]
#[test]
fn png_without_the_feature_names_the_output_and_the_feature() {
    let scratch = Scratch::new("truth-no-png");
    let (_, h5) = run_example(&scratch, "flat_punch", &[]);
    let png = scratch.join("punch.png");
    let o = run(&["plot", &s(&h5), "-o", &s(&png)]);
    let (_, stderr) = text(&o);
    assert_eq!(o.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains(&format!("{}: PNG output is not built", s(&png)))
            && stderr.contains("`png` feature")
            && !stderr.contains(".tmp-"),
        "{stderr}"
    );
    assert_eq!(scratch.files(), vec!["flat_punch.h5".to_owned()]);
}

#[cfg(feature = "png")]
#[test]
fn png_figures_are_built_by_default() {
    let scratch = Scratch::new("truth-png");
    let (_, h5) = run_example(&scratch, "flat_punch", &[]);
    let png = scratch.join("punch.png");
    let o = run(&["plot", &s(&h5), "-o", &s(&png)]);
    let (stdout, stderr) = text(&o);
    assert!(o.status.success(), "{stderr}");
    assert!(
        !stderr.contains(".tmp-") && !stdout.contains(".tmp-"),
        "{stderr}"
    );
    let bytes = std::fs::read(&png).expect("the PNG was not written");
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "not a PNG");
    // Text is drawn (a font is bundled): a figure of labels and curves, not a blank image.
    assert!(bytes.len() > 10_000, "{} bytes", bytes.len());
    assert_eq!(
        scratch.files(),
        vec!["flat_punch.h5".to_owned(), "punch.png".to_owned()],
        "stray files"
    );
    // An output tack cannot write is named as the user gave it, with no temporary's name.
    let bad = scratch.join("missing/dir/punch.png");
    let o = run(&["plot", &s(&h5), "-o", &s(&bad)]);
    let (_, stderr) = text(&o);
    assert_eq!(o.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains(&s(&bad)) && !stderr.contains(".tmp-"),
        "{stderr}"
    );
}

#[test]
fn the_soft_film_report_says_what_the_run_was() {
    let scratch = Scratch::new("truth-film");
    let (report, h5) = run_example(&scratch, "soft_film", &[]);
    // One load step, then a retraction: not "d from 0.877205 to 0.877205 and back".
    assert!(!report.contains("and back"), "{report}");
    assert!(
        report.contains("steps: one load step to d = 0.877205, ")
            && report.contains(" retraction steps to d = -0.")
            && report.contains("(coarse while compressive)"),
        "{report}"
    );
    // The rule's numbers rounded: not "then by 0.002245187067947507".
    assert!(
        report.contains("retraction by 0.0584804 while compressive, then by 0.00224519"),
        "{report}"
    );
    assert!(long_numbers(&report).is_empty(), "{report}");
    // A pull-off of 1.55 F_JKR is adhesive: no apparent γ of 0 (a JKR fit does not apply to a
    // film on a rigid base), and F_JKR said to be the half-space's.
    assert!(!report.contains("apparent gamma"), "{report}");
    assert!(report.contains("F/F_JKR = 1.55"), "{report}");
    assert!(report.contains("(Eq. 7, of a half-space)"), "{report}");
    let summary = tack_io::read_result(&h5).expect("read").summary;
    assert!(!summary.extra.contains_key("apparent_gamma_retraction"));

    // `tack info`: rounded too.
    let o = run(&["info", &s(&h5)]);
    let (info, stderr) = text(&o);
    assert!(o.status.success(), "{stderr}");
    assert!(info.contains("pull_off_ratio = 1.55103"), "{info}");
    // Every line but the one with the git revision (40 hex digits).
    let numbers: String = info.lines().filter(|l| !l.contains("(git ")).collect();
    let long = long_numbers(&numbers);
    assert!(long.is_empty(), "{long:?} in\n{info}");

    // The figure's force axis shows the pull-off: the 400 F_JKR load is cut and marked.
    let svg_path = scratch.join("film.svg");
    let o = run(&["plot", &s(&h5), "-o", &s(&svg_path)]);
    assert!(o.status.success(), "{}", text(&o).1);
    let svg = std::fs::read_to_string(&svg_path).expect("svg");
    assert!(svg.contains("off scale above 7.7"), "the load is not cut");
    assert!(
        !svg.contains(">400<") && !svg.contains(">300<"),
        "ticks up to 400"
    );

    // `tack check` describes the same path before the run.
    let o = run(&["check", &s(&examples_dir().join("soft_film.toml"))]);
    let (check, stderr) = text(&o);
    assert!(o.status.success(), "{stderr}");
    assert!(
        check.contains(
            "path: one load step to d = 0.877205, retraction by 0.0584804 while compressive, \
             then by 0.00224519 until contact is lost"
        ),
        "{check}"
    );
    assert!(long_numbers(&check).is_empty(), "{check}");
}

#[test]
fn no_apparent_gamma_of_zero_beside_an_adhesive_pull_off() {
    let scratch = Scratch::new("truth-rough");
    let (report, h5) = run_example(&scratch, "sphere_random_roughness", &[]);
    // The retraction pulls off at 0.28 F_JKR: "retraction 0" would be false.
    assert!(!report.contains("retraction 0"), "{report}");
    let summary = tack_io::read_result(&h5).expect("read").summary;
    assert!(summary.pull_off_force < 0.0);
    assert_ne!(
        summary.extra.get("apparent_gamma_retraction"),
        Some(&0.0),
        "{report}"
    );
    // A gradual load from out of contact: the load steps and where the retraction ended.
    assert!(
        report.contains(" load steps from d = -1.25426 to 2.5, "),
        "{report}"
    );
}

#[test]
fn the_refined_retraction_does_not_report_the_loop_as_measured() {
    let scratch = Scratch::new("truth-refined");
    let (plain, plain_h5) = run_example(&scratch, "dugdale_sphere", &[]);
    let plain = (
        plain,
        tack_io::read_result(&plain_h5).expect("read").summary,
    );
    assert!(plain.0.contains("cycle       dissipated"), "{}", plain.0);
    assert!(plain.1.extra.contains_key("dissipated_energy"));
    assert!(plain.1.extra["dissipated_energy_sampling"] >= 0.0);
    std::fs::remove_file(&plain_h5).expect("rm");
    let (refined, h5) = run_example(
        &scratch,
        "dugdale_sphere",
        &["protocol.refine_pull_off=true"],
    );
    let summary = tack_io::read_result(&h5).expect("read").summary;
    for key in [
        "dissipated_energy",
        "dissipated_energy_sampling",
        "jump_out_approach",
        "jump_out_force",
    ] {
        assert!(
            !summary.extra.contains_key(key),
            "{key} reported: {refined}"
        );
    }
    // The loading branch is measured as before: the jump in stays.
    assert_eq!(
        summary.extra["jump_in_force"],
        plain.1.extra["jump_in_force"]
    );
    assert!(!refined.contains("dissipated ∮F dd"), "{refined}");
    assert!(
        refined.contains(
            "dissipated energy and jump-out not measured: the refined retraction \
             (protocol.refine_pull_off = true)"
        ),
        "{refined}"
    );
    assert!(refined.contains("(refined: coarse steps"), "{refined}");
    assert!(long_numbers(&refined).is_empty(), "{refined}");
}

#[test]
fn every_example_report_is_rounded() {
    let scratch = Scratch::new("truth-rounded");
    // The default-rule examples whose rule line printed 16-digit numbers (and the ellipsoid's
    // radius is √(Rx·Ry), not given).
    let (report, _) = run_example(&scratch, "elliptic_tip", &[]);
    assert!(long_numbers(&report).is_empty(), "{report}");
    assert!(
        report.contains("default pull-off path of R = 2 (√(Rx·Ry))"),
        "{report}"
    );
    let (report, _) = run_example(&scratch, "wavy_1d_periodic", &[]);
    assert!(report.contains("dx = 0.00195312"), "{report}");
    assert!(long_numbers(&report).is_empty(), "{report}");
}

/// The wall-time line names what its count counts: CG iterations under the criterion, operator
/// products under a smooth law (its Newton's Krylov iterations and line-search trials are not
/// CG iterations).
#[test]
fn the_wall_time_line_names_what_it_counts() {
    let scratch = Scratch::new("truth-work");
    let (report, _) = run_example(&scratch, "exponential_sphere", &[]);
    assert!(report.contains(" operator products)"), "{report}");
    assert!(!report.contains("CG iterations"), "{report}");
    let (report, _) = run_example(&scratch, "smooth_jkr_sphere", &[]);
    assert!(report.contains(" CG iterations)"), "{report}");
    assert!(!report.contains("operator products"), "{report}");
}
