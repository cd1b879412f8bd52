//! Helpers shared by the binary's integration tests: running `tack`, scratch directories and
//! the repository's data folders.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The repository root (two levels above this crate).
pub fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `data/examples`.
pub fn examples_dir() -> PathBuf {
    repo_root().join("data/examples")
}

/// `tests/scenes/bad`.
pub fn bad_scenes_dir() -> PathBuf {
    repo_root().join("tests/scenes/bad")
}

/// The built `tack` binary.
pub fn tack() -> Command {
    Command::new(env!("CARGO_BIN_EXE_tack"))
}

/// Runs `tack` with `args` and returns its output.
pub fn run(args: &[&str]) -> Output {
    tack()
        .args(args)
        .output()
        .expect("the tack binary could not be started")
}

/// Stdout and stderr as text, for assertion messages.
pub fn text(out: &Output) -> (String, String) {
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A fresh, empty scratch directory unique to this process and `name`; removed on drop.
pub struct Scratch(pub PathBuf);

impl Scratch {
    /// Creates `$TMPDIR/tack-cli-<name>-<pid>`.
    pub fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("tack-cli-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("cannot create a scratch directory");
        Self(dir)
    }

    /// A path inside the directory.
    pub fn join(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }

    /// Names of the files in the directory, sorted.
    pub fn files(&self) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(&self.0)
            .map(|entries| {
                entries
                    .filter_map(|e| e.ok())
                    .map(|e| e.file_name().to_string_lossy().into_owned())
                    .collect()
            })
            .unwrap_or_default();
        names.sort();
        names
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Whether `python3 -c "import h5py"` works here.
pub fn have_h5py(what: &str) -> bool {
    let present = Command::new("python3")
        .args(["-c", "import h5py"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !present {
        // CI installs h5py (.ci/run): missing there is a failure, not a skip.
        assert!(
            std::env::var_os("CI").is_none(),
            "h5py is missing in CI: {what} cannot be checked"
        );
        // Written past the test harness's capture, so the skip shows.
        use std::io::Write;
        let _ = writeln!(
            std::io::stderr(),
            "SKIPPED: {what} (h5py not installed: pip install h5py)"
        );
    }
    present
}

/// Files in `dir` whose name ends in `.ext`, sorted.
pub fn files_with_extension(dir: &Path, ext: &str) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == ext))
        .collect();
    files.sort();
    files
}
