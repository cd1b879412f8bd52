//! Tests of tidy's checks, each on a small input that fails it, and of the repository itself.

use super::*;
use tack_fields::Kind;

const FIELDS: &[Field] = &[
    Field {
        name: "grid.n",
        kind: Kind::Number,
        meaning: "elements per side",
    },
    Field {
        name: "grid.dx",
        kind: Kind::Number,
        meaning: "element size",
    },
    Field {
        name: "geometry.radius",
        kind: Kind::Number,
        meaning: "radius",
    },
    Field {
        name: "geometry.shape",
        kind: Kind::Number,
        meaning: "the body",
    },
    Field {
        name: "protocol.indent",
        kind: Kind::Number,
        meaning: "one step",
    },
];

#[test]
fn files_must_open_with_a_module_doc() {
    assert_eq!(missing_module_doc("//! A module.\nfn f() {}\n"), None);
    assert_eq!(missing_module_doc("\n\n//! After blank lines.\n"), None);
    assert_eq!(missing_module_doc("/// An item doc.\nfn f() {}\n"), Some(1));
    assert_eq!(missing_module_doc("\nuse std::fs;\n//! late\n"), Some(2));
    assert_eq!(missing_module_doc(""), Some(1));
}

#[test]
fn field_literals_in_code_are_found_with_their_line() {
    let text = "//! Doc.\nfn f() {\n    let a = \"grid.dx\";\n    let b = format!(\"{x} \
                    and geometry.radius = {}\", 1);\n}\n";
    assert_eq!(
        field_literals(text, FIELDS),
        vec![(3, "grid.dx"), (4, "geometry.radius")]
    );
    // The line of the field within a literal spanning lines.
    let text = "const M: &str = \"first line \\\n    then grid.n here\";\n";
    assert_eq!(field_literals(text, FIELDS), vec![(2, "grid.n")]);
    let raw = "const R: &str = r#\"a \"quoted\" grid.dx\"#;\n";
    assert_eq!(field_literals(raw, FIELDS), vec![(1, "grid.dx")]);
}

#[test]
fn field_names_count_only_whole() {
    let text = "fn f() { g(\"grid.nx\", \"my_grid.n\", \"grid.n.x\", \"grid.n, grid.dx/2\"); }";
    assert_eq!(
        field_literals(text, FIELDS),
        vec![(1, "grid.dx"), (1, "grid.n")]
    );
    let text = "fn f() { g(\"refine grid.dx.\") }";
    assert_eq!(field_literals(text, FIELDS), vec![(1, "grid.dx")]);
}

#[test]
fn comments_and_test_items_are_skipped() {
    let text = r##"//! Mentions "grid.dx" in the module doc.
/// An item doc: `f("grid.dx")`.
fn f() -> char {
    // A comment "grid.dx".
    /* A block "grid.n" /* nested "grid.n" */ still "grid.n" */
    let _lifetime: &'static str = "plain";
    let _quote = '"';
    let _escaped = '\'';
    g("geometry.shape")
}

#[cfg(test)]
mod tests {
    fn t() { let s = "grid.dx"; let inner = { "grid.n" }; }
}

#[cfg(test)]
use std::fmt;

fn after() { h("protocol.indent") }
"##;
    assert_eq!(
        field_literals(text, FIELDS),
        vec![(9, "geometry.shape"), (20, "protocol.indent")]
    );
}

#[test]
fn tests_examples_benches_and_the_fields_crate_are_not_scanned() {
    assert!(scans_for_fields("crates/tack/src/problem.rs"));
    assert!(scans_for_fields("xtask/src/main.rs"));
    assert!(!scans_for_fields("crates/tack/tests/readme.rs"));
    assert!(!scans_for_fields("crates/tack/examples/hertz.rs"));
    assert!(!scans_for_fields("crates/tack-solver/benches/cg.rs"));
    assert!(!scans_for_fields("tests/adhesion.rs"));
    assert!(!scans_for_fields("crates/tack-fields/src/lib.rs"));
    assert_eq!(
        constant_name("protocol.unload_step"),
        "PROTOCOL_UNLOAD_STEP"
    );
}

const SCENES: &str = "# Scenes

## `[geometry]` (required)

`shape` selects the body.

| `shape` | keys | body |
|---|---|---|
| `\"sphere\"` | `radius` (> 0) | paraboloid |

## `[grid]` (required)

| key | meaning | allowed |
|---|---|---|
| `nx`, `ny` | elements, `n` is mentioned in the meaning only | 1.. |
| `dx` | element size | > 0 |

## `[protocol]` (optional)

| key | meaning |
|---|---|
| `start` | first approach |

## Memory

| key | meaning |
|---|---|
| `indent` | not in a section of its own |
";

#[test]
fn fields_must_have_a_row_in_their_section() {
    let missing = undocumented_fields(SCENES, FIELDS);
    let named: Vec<(usize, &str)> = missing
        .iter()
        .map(|(line, m)| (*line, m.split(' ').nth(2).unwrap()))
        .collect();
    assert_eq!(named, vec![(11, "grid.n"), (18, "protocol.indent")]);
    let fixed = SCENES.replace("| `start` |", "| `indent` | one step |\n| `start` |");
    let fixed = fixed.replace("| `nx`, `ny` |", "| `n` | square |\n| `nx`, `ny` |");
    assert!(undocumented_fields(&fixed, FIELDS).is_empty());
    // A section without a heading of its own.
    let gone = fixed.replace("## `[protocol]` (optional)", "## Protocol");
    let missing = undocumented_fields(&gone, FIELDS);
    assert_eq!(missing.len(), 1);
    assert!(
        missing[0].1.contains("no `## [protocol]` heading"),
        "{missing:?}"
    );
}

#[test]
fn keys_in_backticks() {
    assert_eq!(
        backticked_keys("`punch = \"circle\"` with `radius` (> 0), or `half_side`"),
        vec!["punch", "radius", "half_side"]
    );
    assert!(backticked_keys("`\"sphere\"`, `tack_solver::KAPPA`, —").is_empty());
}

const MAIN: &str = r#"//! xtask.
const USAGE: &str = "usage: cargo xtask <command>

commands:
  reproduce [FIG...]      the figures,
                          continued
  bench-jkr [RATIOS...]   a benchmark
  bench [--full]          every table";

fn main() {}
"#;

#[test]
fn modules_that_import_each_other_are_a_circle() {
    let modules = |pairs: &[(&str, &str)]| -> BTreeMap<String, String> {
        pairs
            .iter()
            .map(|(n, t)| (n.to_string(), t.to_string()))
            .collect()
    };
    let circle = modules(&[
        ("scene", "use crate::overrides::apply;\n"),
        ("overrides", "use crate::{error::E, scene::SceneError};\n"),
        ("error", "// crate::scene in a comment does not count\n"),
    ]);
    let cycle = import_cycle(&circle).expect("a circle");
    assert!(cycle.contains(&"scene".to_owned()) && cycle.contains(&"overrides".to_owned()));
    let line = modules(&[
        ("scene", "use crate::overrides::apply;\n"),
        (
            "overrides",
            "use crate::error::SceneError; // crate::scene\n",
        ),
        ("error", "pub struct SceneError;\n"),
    ]);
    assert_eq!(import_cycle(&line), None);
}

#[test]
fn usage_commands_must_be_in_the_architecture() {
    assert_eq!(
        usage_commands(MAIN),
        vec![
            (5, "reproduce".to_owned()),
            (7, "bench-jkr".to_owned()),
            (8, "bench".to_owned())
        ]
    );
    let arch = "Run `cargo xtask reproduce` and `cargo xtask bench-jkr`.";
    assert!(mentions_command(arch, "reproduce"));
    assert!(mentions_command(arch, "bench-jkr"));
    assert!(!mentions_command(arch, "bench"));
    assert!(mentions_command("`cargo xtask bench [--full]`", "bench"));
}

#[test]
fn the_repository_is_read() {
    // The real main.rs lists tidy itself among its commands.
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
    let main = read(root, "xtask/src/main.rs").unwrap();
    assert!(usage_commands(&main).iter().any(|(_, c)| c == "tidy"));
    let mut files = Vec::new();
    rust_files(&root.join("xtask"), &mut files).unwrap();
    assert!(files.iter().any(|f| f.ends_with("tidy.rs")));
}

/// A source whose function `f` (in `impl S` when `method`) spans `lines` lines.
fn function_of(lines: usize) -> String {
    let body: String = (0..lines - 2)
        .map(|i| format!("    let _x{i} = \"}}{i}\";\n"))
        .collect();
    format!("//! Doc.\nstruct S;\nimpl S {{\n    fn f() {{\n{body}    }}\n}}\n")
}

#[test]
fn functions_over_150_lines_fail_in_library_code_only() {
    let findings = |rel: &str, text: String| length_findings(&[(rel.to_owned(), text)]);
    assert!(findings("crates/x/src/a.rs", function_of(150)).is_empty());
    let long = findings("crates/x/src/a.rs", function_of(151));
    assert_eq!(long.len(), 1);
    assert_eq!(long[0].line, 4);
    assert!(
        long[0].message.contains("`S::f` is 151 lines long"),
        "{}",
        long[0]
    );
    assert_eq!(findings("xtask/src/bench.rs", function_of(151)).len(), 1);
    assert_eq!(findings("tests/lib.rs", function_of(151)).len(), 1);
    // Integration tests, examples, benches and test modules in files of their own are test code.
    for rel in [
        "crates/x/tests/a.rs",
        "tests/adhesion.rs",
        "crates/x/examples/a.rs",
        "crates/x/benches/a.rs",
    ] {
        assert!(findings(rel, function_of(151)).is_empty(), "{rel}");
    }
    let parent = (
        "crates/x/src/a.rs".to_owned(),
        "//! Doc.\n#[cfg(test)]\nmod tests;\n".to_owned(),
    );
    let child = ("crates/x/src/a/tests.rs".to_owned(), function_of(151));
    assert!(length_findings(&[child.clone(), parent]).is_empty());
    assert_eq!(length_findings(&[child]).len(), 1);
    assert_eq!(child_module_dir("crates/x/src/lib.rs"), "crates/x/src/");
    assert_eq!(child_module_dir("crates/x/src/a/mod.rs"), "crates/x/src/a/");
    assert_eq!(child_module_dir("crates/x/src/a/b.rs"), "crates/x/src/a/b/");
}

#[test]
fn inline_test_modules_over_300_lines_fail() {
    let module = |lines: usize| {
        let body: String = (0..lines - 2)
            .map(|i| format!("    // line {i}\n"))
            .collect();
        format!("//! Doc.\nfn f() {{}}\n#[cfg(test)]\nmod tests {{\n{body}}}\n")
    };
    let findings = |text: String| length_findings(&[("crates/x/tests/t.rs".to_owned(), text)]);
    assert!(findings(module(300)).is_empty());
    let long = findings(module(301));
    assert_eq!(long.len(), 1);
    assert_eq!(long[0].line, 4);
    assert!(
        long[0].message.contains("`mod tests` is 301 lines long"),
        "{}",
        long[0]
    );
    // A file syn cannot parse is a finding of its own.
    assert_eq!(findings("fn broken( {".to_owned()).len(), 1);
}

#[test]
fn test_files_must_be_named_in_the_architecture() {
    let files = [
        "crates/tack/tests/crop.rs".to_owned(),
        "crates/tack-solver/tests/layer.rs".to_owned(),
        "tests/crop.rs".to_owned(),
        "tests/adhesion.rs".to_owned(),
    ];
    let arch = "`crates/tack/tests/crop.rs`: the crop; `tests/adhesion.rs`, and \
                crates/tack-solver/tests/layer.rsx is another file.";
    assert_eq!(
        unmapped_test_files(arch, &files),
        ["crates/tack-solver/tests/layer.rs", "tests/crop.rs"]
    );
    let arch = format!("{arch} Also tests/crop.rs. And crates/tack-solver/tests/layer.rs.");
    assert!(unmapped_test_files(&arch, &files).is_empty());
}

#[test]
fn the_repository_passes_tidy() {
    // The same checks as `cargo xtask tidy`, so that `cargo test --workspace` runs them.
    let root = repository_root().unwrap();
    let (findings, _pending) = split_pending(check_repository(&root).unwrap());
    let listed: Vec<String> = findings.iter().map(|f| f.to_string()).collect();
    assert!(
        findings.is_empty(),
        "cargo xtask tidy fails:\n{}",
        listed.join("\n")
    );
}
