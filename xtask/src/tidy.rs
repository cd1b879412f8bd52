//! `cargo xtask tidy`: checks of the sources that neither the compiler nor clippy makes.
//!
//! 1. Every `.rs` file under `crates/`, `xtask/` and `tests/` opens with a `//!` line (after
//!    optional blank lines): each module says what it is for.
//! 2. Every field of [`tack_fields::FIELDS`] is documented in `docs/scenes.md`: a table under
//!    the heading of its section (``## `[protocol]` ...``) names its key in backticks in the
//!    table's key column (`key`, or `keys` for the tables of shapes and roughness kinds, whose
//!    selecting key, `shape` or `kind`, heads the first column).
//! 3. No string literal of non-test Rust code outside `crates/tack-fields` spells a scene
//!    field (`"... grid.dx ..."`): the constants of `tack_fields` name them. Skipped: the
//!    items marked `#[cfg(test)]`, `tests/`, `examples/` and `benches/` directories, and
//!    comments (doc comments included), all of which may spell what the user sees.
//! 4. Every command listed in the `USAGE` text of `xtask/src/main.rs` is mentioned in
//!    `ARCHITECTURE.md` as `cargo xtask <command>`.
//! 5. No import circle between the top-level modules of a crate.
//! 6. No function of non-test code is longer than 150 lines (`lengths.rs`, on the syntax tree
//!    `syn` parses): the library sources (`crates/*/src`, `xtask/src`, `tests/lib.rs`), leaving
//!    out `#[cfg(test)]` items, `#[test]` functions and the test modules kept in files of their
//!    own (`#[cfg(test)] mod tests;`); integration tests (`crates/*/tests/`, the test targets of
//!    `tests/`), examples and benches are not read.
//! 7. No inline `#[cfg(test)]` module is longer than 300 lines, in any source: a longer one
//!    goes in its own file (`#[cfg(test)] mod tests;`, the file at `src/<module>/tests.rs`).
//! 8. Every integration-test file (`crates/*/tests/*.rs`, `tests/*.rs`) is named in
//!    `ARCHITECTURE.md` by its path from the repository root (the code map of the tests).
//!
//! Each finding is printed as `path:line: what is wrong`; any finding fails the command, except
//! those of [`PENDING`] (printed apart). The test `the_repository_passes_tidy` runs the same
//! checks, so `cargo test --workspace` fails where `cargo xtask tidy` does.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use tack_fields::{FIELDS, Field};

mod lengths;

use lengths::{MAX_FUNCTION_LINES, MAX_TEST_MODULE_LINES};

/// Findings tolerated for now, as `(path, item)`: the functions (and test modules, as
/// `mod tests`) of files being rewritten on other branches at the time these checks came in.
/// A finding is pending when its path is the entry's and it names the item in backticks.
/// Remove an entry with the rewrite that fixes it; `cargo xtask tidy` lists the entries that
/// no longer match anything.
pub const PENDING: &[(&str, &str)] = &[];

/// One thing tidy found wrong: the file (relative to the repository root), the line
/// (1-based) and what is wrong there.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Finding {
    /// The file, relative to the repository root.
    pub path: String,
    /// The line, 1-based.
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for Finding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: {}", self.path, self.line, self.message)
    }
}

/// Runs every check on the repository at `root`, prints the findings and fails when there are
/// any.
pub fn run(args: &[String]) -> Result<()> {
    if let Some(extra) = args.first() {
        bail!("tidy takes no arguments (got `{extra}`)");
    }
    let (findings, pending) = split_pending(check_repository(&repository_root()?)?);
    for finding in &pending {
        println!("pending: {finding}");
    }
    for (path, item) in stale_pending(&pending) {
        println!(
            "note: PENDING lists `{item}` in {path}, which no check finds any more: remove it"
        );
    }
    for finding in &findings {
        println!("{finding}");
    }
    if findings.is_empty() {
        println!("tidy: all checks passed ({} pending)", pending.len());
        Ok(())
    } else {
        bail!("tidy: {} finding(s)", findings.len())
    }
}

/// The repository root: the parent of the xtask crate.
pub fn repository_root() -> Result<PathBuf> {
    Ok(Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .context("xtask has no parent directory")?
        .to_owned())
}

/// `findings` split into those that fail tidy and those of [`PENDING`].
pub fn split_pending(findings: Vec<Finding>) -> (Vec<Finding>, Vec<Finding>) {
    findings
        .into_iter()
        .partition(|f| !PENDING.iter().any(|entry| is_pending(f, *entry)))
}

fn is_pending(finding: &Finding, (path, item): (&str, &str)) -> bool {
    finding.path == path && finding.message.contains(&format!("`{item}`"))
}

/// The entries of [`PENDING`] that none of the `pending` findings matches.
fn stale_pending(pending: &[Finding]) -> Vec<(&'static str, &'static str)> {
    PENDING
        .iter()
        .copied()
        .filter(|entry| !pending.iter().any(|f| is_pending(f, *entry)))
        .collect()
}

/// All findings of the checks on the repository at `root`.
pub fn check_repository(root: &Path) -> Result<Vec<Finding>> {
    let mut findings = Vec::new();
    let mut files = Vec::new();
    for dir in ["crates", "xtask", "tests"] {
        rust_files(&root.join(dir), &mut files)?;
    }
    files.sort();
    let mut texts = Vec::with_capacity(files.len());
    for path in &files {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        texts.push((relative(root, path), text));
    }
    findings.extend(length_findings(&texts));
    let test_modules = test_module_files(&texts);
    for (rel, text) in &texts {
        let (rel, text) = (rel.clone(), text.as_str());
        if let Some(line) = missing_module_doc(text) {
            findings.push(Finding {
                path: rel.clone(),
                line,
                message: "the file does not start with a `//!` line saying what it is for"
                    .to_owned(),
            });
        }
        if scans_for_fields(&rel) && !is_test_module_file(&test_modules, &rel) {
            for (line, name) in field_literals(text, FIELDS) {
                findings.push(Finding {
                    path: rel.clone(),
                    line,
                    message: format!(
                        "string literal spells the scene field \"{name}\": use the constant \
                         tack_fields::{}",
                        constant_name(name)
                    ),
                });
            }
        }
    }
    for krate in crate_sources(root)? {
        let modules = module_texts(root, &krate, &test_modules)?;
        if let Some(cycle) = import_cycle(&modules) {
            findings.push(Finding {
                path: relative(root, &krate),
                line: 1,
                message: format!(
                    "the modules import each other in a circle: {} (move the helper that closes \
                     it to the module it belongs to)",
                    cycle.join(" → ")
                ),
            });
        }
    }
    let scenes = read(root, "docs/scenes.md")?;
    findings.extend(
        undocumented_fields(&scenes, FIELDS)
            .into_iter()
            .map(|(line, message)| Finding {
                path: "docs/scenes.md".to_owned(),
                line,
                message,
            }),
    );
    let main = read(root, "xtask/src/main.rs")?;
    let architecture = read(root, "ARCHITECTURE.md")?;
    for rel in unmapped_test_files(&architecture, &test_files(root)?) {
        findings.push(Finding {
            path: rel.clone(),
            line: 1,
            message: format!(
                "the test file is not named in ARCHITECTURE.md: add `{rel}` to the map of the \
                 tests with what it checks"
            ),
        });
    }
    for (line, command) in usage_commands(&main) {
        if !mentions_command(&architecture, &command) {
            findings.push(Finding {
                path: "xtask/src/main.rs".to_owned(),
                line,
                message: format!(
                    "the command `{command}` of USAGE is not mentioned in ARCHITECTURE.md as \
                     `cargo xtask {command}`"
                ),
            });
        }
    }
    Ok(findings)
}

/// Checks 6 and 7 on the sources `texts` (`(path relative to the root, text)`): functions of
/// library code over [`MAX_FUNCTION_LINES`], inline test modules over
/// [`MAX_TEST_MODULE_LINES`], and every file `syn` cannot parse.
fn length_findings(texts: &[(String, String)]) -> Vec<Finding> {
    let mut findings = Vec::new();
    let mut measured = Vec::new();
    for (rel, text) in texts {
        match lengths::measure(text) {
            Ok(lengths) => measured.push((rel, lengths)),
            Err(error) => findings.push(Finding {
                path: rel.clone(),
                line: error.span().start().line,
                message: format!("syn cannot parse the file: {error}"),
            }),
        }
    }
    let test_files = test_module_files(texts);
    for (rel, lengths) in measured {
        let test_file = is_test_module_file(&test_files, rel);
        if is_library_code(rel) && !test_file {
            for f in lengths
                .functions
                .iter()
                .filter(|f| f.lines > MAX_FUNCTION_LINES)
            {
                findings.push(Finding {
                    path: rel.clone(),
                    line: f.line,
                    message: format!(
                        "the function `{}` is {} lines long (at most {MAX_FUNCTION_LINES}): split \
                         it into named steps",
                        f.name, f.lines
                    ),
                });
            }
        }
        for m in lengths
            .test_modules
            .iter()
            .filter(|m| m.lines > MAX_TEST_MODULE_LINES)
        {
            findings.push(Finding {
                path: rel.clone(),
                line: m.line,
                message: format!(
                    "the inline test module `mod {}` is {} lines long (at most \
                     {MAX_TEST_MODULE_LINES}): move it to its own file (`#[cfg(test)] mod {};`)",
                    m.name, m.lines, m.name
                ),
            });
        }
    }
    findings
}

/// The files of `texts` that hold test modules declared by their parent
/// (`#[cfg(test)] mod tests;` in `src/a.rs` makes `src/a/tests.rs` and `src/a/tests/` test
/// code), as relative paths, directories ending in `/`. Files that do not parse declare none.
fn test_module_files(texts: &[(String, String)]) -> BTreeSet<String> {
    let mut files = BTreeSet::new();
    for (rel, text) in texts {
        if let Ok(lengths) = lengths::measure(text) {
            let dir = child_module_dir(rel);
            for name in &lengths.test_module_files {
                files.insert(format!("{dir}{name}.rs"));
                files.insert(format!("{dir}{name}/"));
            }
        }
    }
    files
}

/// Whether the file at `rel` is one of `test_files` ([`test_module_files`]) or lies in one of
/// its directories.
fn is_test_module_file(test_files: &BTreeSet<String>, rel: &str) -> bool {
    test_files
        .iter()
        .any(|t| rel == t || (t.ends_with('/') && rel.starts_with(t.as_str())))
}

/// The directory (relative, ending in `/`) holding the files of the modules that the file at
/// `rel` declares: beside it for `lib.rs`, `main.rs` and `mod.rs`, else in the directory named
/// after it (`src/a.rs` declares `src/a/b.rs`).
fn child_module_dir(rel: &str) -> String {
    let (dir, file) = rel.rsplit_once('/').unwrap_or(("", rel));
    let dir = if dir.is_empty() {
        String::new()
    } else {
        format!("{dir}/")
    };
    if matches!(file, "lib.rs" | "main.rs" | "mod.rs") {
        dir
    } else {
        format!("{dir}{}/", file.trim_end_matches(".rs"))
    }
}

/// Whether check 6 reads the file at `rel`: the sources of a library or binary
/// (`crates/*/src/`, `xtask/src/`) and the library of the top-level tests crate (`tests/lib.rs`).
fn is_library_code(rel: &str) -> bool {
    let parts: Vec<&str> = rel.split('/').collect();
    matches!(
        parts.as_slice(),
        ["crates", _, "src", ..] | ["xtask", "src", ..] | ["tests", "lib.rs"]
    )
}

/// Check 8's files: `crates/*/tests/*.rs` and `tests/*.rs`, relative to `root`, sorted.
fn test_files(root: &Path) -> Result<Vec<String>> {
    let mut dirs = vec![root.join("tests")];
    let crates = root.join("crates");
    for entry in
        std::fs::read_dir(&crates).with_context(|| format!("cannot read {}", crates.display()))?
    {
        dirs.push(entry?.path().join("tests"));
    }
    let mut out = Vec::new();
    for dir in dirs.iter().filter(|d| d.is_dir()) {
        for entry in
            std::fs::read_dir(dir).with_context(|| format!("cannot list {}", dir.display()))?
        {
            let path = entry?.path();
            if path.is_file() && path.extension().is_some_and(|e| e == "rs") {
                out.push(relative(root, &path));
            }
        }
    }
    out.sort();
    Ok(out)
}

/// Check 8: the files of `files` (paths from the repository root) that `architecture` does not
/// name. A path counts when it stands whole: `tests/crop.rs` is not named by
/// `crates/tack/tests/crop.rs`, nor `tests/crop.rs` by `tests/crop.rsx`.
fn unmapped_test_files(architecture: &str, files: &[String]) -> Vec<String> {
    let path_char = |c: char| c.is_alphanumeric() || matches!(c, '_' | '-' | '/' | '.');
    files
        .iter()
        .filter(|file| {
            !architecture.match_indices(file.as_str()).any(|(at, _)| {
                let before = architecture[..at].chars().next_back();
                let after = architecture[at + file.len()..].chars().next();
                !before.is_some_and(path_char)
                    && !after.is_some_and(|c| c.is_alphanumeric() || c == '_')
            })
        })
        .cloned()
        .collect()
}

/// The `src/` directories of the crates under `crates/` and of `xtask/`.
fn crate_sources(root: &Path) -> Result<Vec<PathBuf>> {
    let mut out = vec![root.join("xtask/src")];
    let crates = root.join("crates");
    for entry in
        std::fs::read_dir(&crates).with_context(|| format!("cannot read {}", crates.display()))?
    {
        let src = entry?.path().join("src");
        if src.is_dir() {
            out.push(src);
        }
    }
    out.sort();
    Ok(out)
}

/// The top-level modules of the crate whose sources are in `src` (`a.rs` and `a/…` make module
/// `a`), each with the text of its non-test code (files of a module directory joined; the
/// `test_files` of [`test_module_files`], relative to `root`, left out).
fn module_texts(
    root: &Path,
    src: &Path,
    test_files: &BTreeSet<String>,
) -> Result<BTreeMap<String, String>> {
    let mut files = Vec::new();
    rust_files(src, &mut files)?;
    let mut modules: BTreeMap<String, String> = BTreeMap::new();
    for path in files {
        if is_test_module_file(test_files, &relative(root, &path)) {
            continue;
        }
        let rel = path.strip_prefix(src).unwrap_or(&path);
        let first = rel
            .components()
            .next()
            .map(|c| c.as_os_str().to_string_lossy().into_owned())
            .unwrap_or_default();
        let name = first.trim_end_matches(".rs").to_owned();
        if name == "lib" || name == "main" {
            continue;
        }
        let text = std::fs::read_to_string(&path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        let code = match text.find("#[cfg(test)]") {
            Some(cut) => &text[..cut],
            None => &text[..],
        };
        let entry = modules.entry(name).or_default();
        entry.push_str(code);
        entry.push('\n');
    }
    Ok(modules)
}

/// A circle of `crate::` references between top-level modules (in code, not comments), as the
/// module names around it, or `None`.
fn import_cycle(modules: &BTreeMap<String, String>) -> Option<Vec<String>> {
    let mut edges: BTreeMap<&str, BTreeSet<&str>> = BTreeMap::new();
    for (name, text) in modules {
        let targets = edges.entry(name.as_str()).or_default();
        for line in text.lines() {
            let code = line.split("//").next().unwrap_or("");
            for (i, _) in code.match_indices("crate::") {
                let rest = &code[i + "crate::".len()..];
                let end = rest.find(|c: char| !ident(c)).unwrap_or(rest.len());
                if let Some((other, _)) = modules.get_key_value(&rest[..end])
                    && other != name
                {
                    targets.insert(other.as_str());
                }
            }
            // `use crate::{a::x, b::y}`.
            if let Some(start) = code.find("crate::{") {
                let inner = &code[start + "crate::{".len()..];
                for part in inner.split([',', '{', '}']) {
                    let head = part.trim().split("::").next().unwrap_or("");
                    if let Some((other, _)) = modules.get_key_value(head)
                        && other != name
                    {
                        targets.insert(other.as_str());
                    }
                }
            }
        }
    }
    // Depth-first search for a back edge.
    fn visit<'a>(
        node: &'a str,
        edges: &BTreeMap<&'a str, BTreeSet<&'a str>>,
        path: &mut Vec<&'a str>,
        done: &mut BTreeSet<&'a str>,
    ) -> Option<Vec<String>> {
        if let Some(at) = path.iter().position(|n| *n == node) {
            let mut cycle: Vec<String> = path[at..].iter().map(|s| s.to_string()).collect();
            cycle.push(node.to_owned());
            return Some(cycle);
        }
        if done.contains(node) {
            return None;
        }
        path.push(node);
        for next in edges.get(node).into_iter().flatten() {
            if let Some(cycle) = visit(next, edges, path, done) {
                return Some(cycle);
            }
        }
        path.pop();
        done.insert(node);
        None
    }
    let mut done = BTreeSet::new();
    for node in edges.keys() {
        if let Some(cycle) = visit(node, &edges, &mut Vec::new(), &mut done) {
            return Some(cycle);
        }
    }
    None
}

fn read(root: &Path, rel: &str) -> Result<String> {
    std::fs::read_to_string(root.join(rel)).with_context(|| format!("cannot read {rel}"))
}

fn relative(root: &Path, path: &Path) -> String {
    let rel = path.strip_prefix(root).unwrap_or(path);
    rel.components()
        .map(|c| c.as_os_str().to_string_lossy())
        .collect::<Vec<_>>()
        .join("/")
}

/// Collects the `.rs` files under `dir`, leaving out build output (`target`) and hidden
/// directories.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) -> Result<()> {
    if !dir.is_dir() {
        return Ok(());
    }
    let entries =
        std::fs::read_dir(dir).with_context(|| format!("cannot list {}", dir.display()))?;
    for entry in entries {
        let entry = entry?;
        let path = entry.path();
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if entry.file_type()?.is_dir() {
            if name != "target" && !name.starts_with('.') {
                rust_files(&path, out)?;
            }
        } else if name.ends_with(".rs") {
            out.push(path);
        }
    }
    Ok(())
}

/// Check 1: the line to blame when `text` does not open with a `//!` line after optional
/// blank lines (the first line that is not blank, or 1 for an empty file).
fn missing_module_doc(text: &str) -> Option<usize> {
    for (i, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        return if line.starts_with("//!") {
            None
        } else {
            Some(i + 1)
        };
    }
    Some(1)
}

/// Whether check 3 reads the file at `rel` (relative, `/`-separated): non-test sources outside
/// `crates/tack-fields`.
fn scans_for_fields(rel: &str) -> bool {
    let parts: Vec<&str> = rel.split('/').collect();
    let test_dir = parts[..parts.len().saturating_sub(1)]
        .iter()
        .any(|p| matches!(*p, "tests" | "examples" | "benches"));
    !test_dir && !rel.starts_with("crates/tack-fields/")
}

/// `PROTOCOL_UNLOAD_STEP` for `protocol.unload_step`.
fn constant_name(field: &str) -> String {
    field.replace('.', "_").to_uppercase()
}

/// Check 3: `(line, field)` for every scene field of `fields` that a string literal of the
/// non-test code of `text` spells. Comments, and the item after each `#[cfg(test)]`, are
/// skipped; a field counts when it stands alone (`grid.n` is not in `"grid.nx"` or
/// `"my_grid.n"`).
fn field_literals(text: &str, fields: &[Field]) -> Vec<(usize, &'static str)> {
    let mut found = Vec::new();
    for literal in string_literals(text) {
        for field in fields {
            let mut from = 0;
            while let Some(at) = literal.text[from..].find(field.name) {
                let start = from + at;
                let end = start + field.name.len();
                let word = |c: char| c.is_ascii_alphanumeric() || c == '_';
                let before = literal.text[..start].chars().next_back();
                let mut after = literal.text[end..].chars();
                // A field may end a sentence (`refine grid.dx.`), but `grid.n.x` is no field.
                let continued = match after.next() {
                    Some('.') => after.next().is_some_and(word),
                    next => next.is_some_and(word),
                };
                if !before.is_some_and(|c| word(c) || c == '.') && !continued {
                    let line = literal.line + literal.text[..start].matches('\n').count();
                    found.push((line, field.name));
                }
                from = end;
            }
        }
    }
    found.sort();
    found
}

/// A string literal of Rust source: its text as written (escapes kept) and the line it starts
/// on.
struct Literal {
    line: usize,
    text: String,
}

/// The string literals (`"..."`, `r#"..."#`, `b"..."`, `c"..."`) of the code of `text`,
/// leaving out comments, character literals and every item marked `#[cfg(test)]` (up to the
/// `;` or the `}` closing it).
fn string_literals(text: &str) -> Vec<Literal> {
    let chars: Vec<char> = text.chars().collect();
    let mut literals = Vec::new();
    let mut line = 1;
    let mut i = 0;
    // Inside an item marked `#[cfg(test)]`: the brace depth within it, once it has opened.
    let mut test_item: Option<Option<usize>> = None;
    let at = |i: usize, s: &str| {
        s.chars()
            .enumerate()
            .all(|(k, c)| chars.get(i + k) == Some(&c))
    };
    while i < chars.len() {
        let c = chars[i];
        if c == '\n' {
            line += 1;
            i += 1;
        } else if at(i, "//") {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if at(i, "/*") {
            let mut depth = 0;
            while i < chars.len() {
                if at(i, "/*") {
                    depth += 1;
                    i += 2;
                } else if at(i, "*/") {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    if chars[i] == '\n' {
                        line += 1;
                    }
                    i += 1;
                }
            }
        } else if let Some(hashes) = raw_string_start(&chars, i) {
            // r"..." / r#"..."# / br#"..."#: no escapes, ends at `"` and the same hashes.
            let open = i + chars[i..].iter().position(|&c| c == '"').unwrap_or(0);
            let start_line = line;
            let mut j = open + 1;
            let close: String = std::iter::once('"')
                .chain("#".repeat(hashes).chars())
                .collect();
            while j < chars.len() && !at(j, &close) {
                j += 1;
            }
            let body: String = chars[open + 1..j.min(chars.len())].iter().collect();
            line += body.matches('\n').count();
            if test_item.is_none() {
                literals.push(Literal {
                    line: start_line,
                    text: body,
                });
            }
            i = j + close.len();
        } else if c == '"' || ((c == 'b' || c == 'c') && chars.get(i + 1) == Some(&'"')) {
            let open = if c == '"' { i } else { i + 1 };
            let start_line = line;
            let mut j = open + 1;
            while j < chars.len() && chars[j] != '"' {
                if chars[j] == '\\' {
                    j += 1;
                }
                j += 1;
            }
            let body: String = chars[open + 1..j.min(chars.len())].iter().collect();
            line += body.matches('\n').count();
            if test_item.is_none() {
                literals.push(Literal {
                    line: start_line,
                    text: body,
                });
            }
            i = j + 1;
        } else if c == '\'' {
            // A character literal ('"', '\'', '\u{22}') or a lifetime ('a).
            if chars.get(i + 1) == Some(&'\\') {
                let mut j = i + 3;
                while j < chars.len() && chars[j] != '\'' {
                    j += 1;
                }
                i = j + 1;
            } else if chars.get(i + 2) == Some(&'\'') {
                i += 3;
            } else {
                i += 1;
            }
        } else if c.is_alphanumeric() || c == '_' {
            // A whole identifier (or number), so that a `b"` or `r"` ending one is no literal.
            while i < chars.len() && ident(chars[i]) {
                i += 1;
            }
        } else {
            if at(i, "#[cfg(test)]") {
                test_item = Some(None);
                i += "#[cfg(test)]".len();
                continue;
            }
            if let Some(depth) = &mut test_item {
                match (c, depth.as_mut()) {
                    ('{', None) => *depth = Some(1),
                    ('{', Some(d)) => *d += 1,
                    ('}', Some(d)) => {
                        *d -= 1;
                        if *d == 0 {
                            test_item = None;
                        }
                    }
                    (';', None) => test_item = None,
                    _ => {}
                }
            }
            i += 1;
        }
    }
    literals
}

fn ident(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// The number of `#` of a raw string literal (`r"`, `r#"`, `br##"`, `cr"`) starting at `i`.
fn raw_string_start(chars: &[char], i: usize) -> Option<usize> {
    if i > 0 && ident(chars[i - 1]) {
        return None;
    }
    let mut j = i;
    if matches!(chars.get(j), Some('b' | 'c')) {
        j += 1;
    }
    if chars.get(j) != Some(&'r') {
        return None;
    }
    j += 1;
    let hashes = chars[j..].iter().take_while(|&&c| c == '#').count();
    (chars.get(j + hashes) == Some(&'"')).then_some(hashes)
}

/// Check 2: `(line, message)` for every field of `fields` that `scenes` (the text of
/// `docs/scenes.md`) does not document: no table under the heading of its section
/// (``## `[section]` ...``) names its key in backticks in the key column.
fn undocumented_fields(scenes: &str, fields: &[Field]) -> Vec<(usize, String)> {
    let sections = documented_keys(scenes);
    let mut missing = Vec::new();
    for field in fields {
        let (section, key) = (field.section(), field.key());
        match sections.iter().find(|s| s.name == section) {
            None => missing.push((
                1,
                format!(
                    "no `## [{section}]` heading documents the field {}",
                    field.name
                ),
            )),
            Some(s) if !s.keys.iter().any(|k| k == key) => missing.push((
                s.line,
                format!(
                    "the field {} is not documented: no table under `## [{section}]` has a row \
                     naming `{key}` in its key column ({})",
                    field.name, field.meaning
                ),
            )),
            Some(_) => {}
        }
    }
    missing
}

/// A section of `docs/scenes.md`: its name, the line of its heading and the keys its tables
/// name.
struct DocSection {
    name: String,
    line: usize,
    keys: Vec<String>,
}

fn documented_keys(scenes: &str) -> Vec<DocSection> {
    let mut sections: Vec<DocSection> = Vec::new();
    // The key column of the table being read, once its header is seen.
    let mut key_column: Option<usize> = None;
    for (i, line) in scenes.lines().enumerate() {
        if let Some(heading) = line.strip_prefix("## ") {
            key_column = None;
            let name = heading
                .split_once("`[")
                .and_then(|(_, rest)| rest.split_once("]`"))
                .map(|(name, _)| name.to_owned());
            if let Some(name) = name {
                sections.push(DocSection {
                    name,
                    line: i + 1,
                    keys: Vec::new(),
                });
            } else {
                // A heading of something else ends the section.
                sections.push(DocSection {
                    name: String::new(),
                    line: i + 1,
                    keys: Vec::new(),
                });
            }
            continue;
        }
        let Some(section) = sections.last_mut() else {
            continue;
        };
        let trimmed = line.trim();
        if !trimmed.starts_with('|') {
            key_column = None;
            continue;
        }
        let cells: Vec<&str> = trimmed
            .trim_matches('|')
            .split('|')
            .map(str::trim)
            .collect();
        if cells
            .iter()
            .all(|c| c.chars().all(|c| c == '-' || c == ':'))
        {
            continue;
        }
        match key_column {
            None => {
                // The header: the key column, and a selecting key heading the first column.
                key_column = Some(
                    cells
                        .iter()
                        .position(|c| *c == "key" || *c == "keys")
                        .unwrap_or(0),
                );
                if let Some(first) = cells.first() {
                    section.keys.extend(backticked_keys(first));
                }
            }
            Some(column) => {
                if let Some(cell) = cells.get(column) {
                    section.keys.extend(backticked_keys(cell));
                }
            }
        }
    }
    sections.retain(|s| !s.name.is_empty());
    sections
}

/// The keys a table cell names in backticks: `` `h` (rms), `punch = "circle"` `` names `h` and
/// `punch`; `` `"sphere"` `` and `` `tack_solver::KAPPA` `` name none.
fn backticked_keys(cell: &str) -> Vec<String> {
    cell.split('`')
        .skip(1)
        .step_by(2)
        .filter_map(|code| {
            let key: String = code
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            let rest = &code[key.len()..];
            (!key.is_empty() && (rest.is_empty() || rest.starts_with(' '))).then_some(key)
        })
        .collect()
}

/// Check 4: `(line, command)` for every command listed in the `USAGE` text of `main` (the text
/// of `xtask/src/main.rs`): the lines after `commands:` that start with two spaces and a name.
fn usage_commands(main: &str) -> Vec<(usize, String)> {
    let mut commands = Vec::new();
    let mut in_usage = false;
    let mut in_commands = false;
    for (i, line) in main.lines().enumerate() {
        if !in_usage {
            in_usage = line.contains("const USAGE");
            continue;
        }
        if line.trim() == "commands:" {
            in_commands = true;
        } else if in_commands
            && let Some(rest) = line.strip_prefix("  ")
            && rest.starts_with(|c: char| c.is_ascii_alphanumeric())
        {
            let name: String = rest
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '-' || *c == '_')
                .collect();
            commands.push((i + 1, name));
        }
        if line.trim_end().ends_with("\";") {
            break;
        }
    }
    commands
}

/// Whether `text` mentions `cargo xtask <command>` with `command` whole (`cargo xtask bench`
/// is not mentioned by `cargo xtask bench-jkr`).
fn mentions_command(text: &str, command: &str) -> bool {
    let needle = format!("cargo xtask {command}");
    text.match_indices(&needle).any(|(at, _)| {
        !text[at + needle.len()..]
            .chars()
            .next()
            .is_some_and(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
    })
}

#[cfg(test)]
mod tests;
