//! The program that opens the crate's README is `examples/sweep_readme.rs`, so the README cannot
//! drift from code that compiles and runs.

#[test]
fn the_readme_opens_with_the_readme_example() {
    let readme = include_str!("../README.md");
    let example = include_str!("../examples/sweep_readme.rs");
    let start = readme.find("```rust\n").expect("a ```rust block") + "```rust\n".len();
    let block = &readme[start..];
    let block = &block[..block.find("```").expect("the block's end")];
    let program: String = example
        .lines()
        .filter(|l| !l.starts_with("//!"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_eq!(
        block, program,
        "README.md's first rust block != examples/sweep_readme.rs"
    );
    let before = &readme[..start - "```rust\n".len()];
    assert!(
        !before.contains("```"),
        "a code block comes before the program"
    );
}
