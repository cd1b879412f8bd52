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
//!
//! Each finding is printed as `path:line: what is wrong`; any finding fails the command.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use tack_fields::{FIELDS, Field};

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
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .context("xtask has no parent directory")?
        .to_owned();
    let findings = check_repository(&root)?;
    for finding in &findings {
        println!("{finding}");
    }
    if findings.is_empty() {
        println!("tidy: all checks passed");
        Ok(())
    } else {
        bail!("tidy: {} finding(s)", findings.len())
    }
}

/// All findings of the checks on the repository at `root`.
pub fn check_repository(root: &Path) -> Result<Vec<Finding>> {
    let mut findings = Vec::new();
    let mut files = Vec::new();
    for dir in ["crates", "xtask", "tests"] {
        rust_files(&root.join(dir), &mut files)?;
    }
    files.sort();
    for path in &files {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        let rel = relative(root, path);
        if let Some(line) = missing_module_doc(&text) {
            findings.push(Finding {
                path: rel.clone(),
                line,
                message: "the file does not start with a `//!` line saying what it is for"
                    .to_owned(),
            });
        }
        if scans_for_fields(&rel) {
            for (line, name) in field_literals(&text, FIELDS) {
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
        let modules = module_texts(&krate)?;
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
/// `a`), each with the text of its non-test code (files of a module directory joined).
fn module_texts(src: &Path) -> Result<BTreeMap<String, String>> {
    let mut files = Vec::new();
    rust_files(src, &mut files)?;
    let mut modules: BTreeMap<String, String> = BTreeMap::new();
    for path in files {
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
mod tests {
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
}
