//! Result files: provenance of a run (and, as the CLI issue lands, the HDF5 schema); the only
//! crate that will link the HDF5 library.

/// Where a result came from: written as root attributes of every result file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Provenance {
    /// `tack` version that produced the file.
    pub tack_version: String,
    /// Git revision of the source tree, or `unknown`.
    pub git_revision: String,
    /// The command line that produced the file.
    pub command_line: String,
    /// Creation time, RFC 3339 in UTC.
    pub created: String,
}

impl Provenance {
    /// Provenance of the current process with a caller-supplied revision and timestamp.
    pub fn current(git_revision: impl Into<String>, created: impl Into<String>) -> Self {
        Self {
            tack_version: env!("CARGO_PKG_VERSION").to_owned(),
            git_revision: git_revision.into(),
            command_line: std::env::args().collect::<Vec<_>>().join(" "),
            created: created.into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn current_records_version_and_command_line() {
        let p = Provenance::current("abc123", "2026-01-01T00:00:00Z");
        assert_eq!(p.tack_version, env!("CARGO_PKG_VERSION"));
        assert_eq!(p.git_revision, "abc123");
        assert!(!p.command_line.is_empty());
    }
}
