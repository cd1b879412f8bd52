//! The program that opens the crate's README is `examples/readme.rs`, and the repository
//! README's library section is `examples/library.rs` (CI runs both from the repository root),
//! so the READMEs cannot drift from code that compiles and runs.

/// The first ```` ```rust ```` block after `heading` in `readme`, and the program `example`
/// without its `//!` lines.
fn block_and_program(readme: &str, heading: &str, example: &str) -> (String, String) {
    let after = &readme[readme.find(heading).expect("the heading")..];
    let start = after.find("```rust\n").expect("a ```rust block") + "```rust\n".len();
    let block = &after[start..];
    let block = &block[..block.find("```").expect("the block's end")];
    let program: String = example
        .lines()
        .filter(|l| !l.starts_with("//!"))
        .map(|l| format!("{l}\n"))
        .collect();
    (block.to_owned(), program)
}

#[test]
fn the_repository_readme_shows_the_library_example() {
    let (block, program) = block_and_program(
        include_str!("../../../README.md"),
        "## Use it as a library",
        include_str!("../examples/library.rs"),
    );
    assert_eq!(
        block, program,
        "README.md's library section != crates/tack/examples/library.rs"
    );
}

#[test]
fn the_readme_opens_with_the_readme_example() {
    let readme = include_str!("../README.md");
    let (block, program) =
        block_and_program(readme, "# tack", include_str!("../examples/readme.rs"));
    assert_eq!(
        block, program,
        "README.md's first rust block != examples/readme.rs"
    );
    // The first code block of the README is that program, not something before it.
    assert_eq!(
        readme.find("```"),
        readme.find("```rust\n"),
        "a code block comes before the program"
    );
}
