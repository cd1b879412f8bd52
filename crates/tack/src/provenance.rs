//! Provenance of result files: the build's git revision, UTC timestamps in RFC 3339, and the
//! [`tack_io::Provenance`] record of a run.

use std::time::{SystemTime, UNIX_EPOCH};

use crate::problem::Problem;
use crate::scene::Scene;

/// Git revision of the source tree this binary was built from (`unknown` without git).
pub const GIT_REVISION: &str = env!("TACK_GIT_REVISION");

/// Version of the `tack` crates.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// Formats a time as RFC 3339 in UTC with whole seconds, e.g. `2026-01-31T09:05:00Z`.
/// Times before 1970 are clamped to the epoch.
pub fn rfc3339_utc(time: SystemTime) -> String {
    let secs = time
        .duration_since(UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    let (days, rem) = (secs / 86_400, secs % 86_400);
    let (y, m, d) = civil_from_days(days as i64);
    format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60
    )
}

/// The current time as [`rfc3339_utc`].
pub fn now_rfc3339() -> String {
    rfc3339_utc(SystemTime::now())
}

/// Year, month, day of the proleptic Gregorian calendar for days since 1970-01-01
/// (H. Hinnant's `civil_from_days`).
fn civil_from_days(z: i64) -> (i64, u32, u32) {
    let z = z + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let y = yoe + era * 400;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = (doy - (153 * mp + 2) / 5 + 1) as u32;
    let m = if mp < 10 { mp + 3 } else { mp - 9 } as u32;
    (if m <= 2 { y + 1 } else { y }, m, d)
}

/// The provenance of a run of `scene`: version, revision, `command_line`, the scene's full TOML
/// (after overrides), the current time and the roughness seed.
pub fn provenance(
    scene: &Scene,
    problem: &Problem,
    command_line: impl Into<String>,
) -> tack_io::Provenance {
    tack_io::Provenance {
        tack_version: VERSION.to_owned(),
        git_revision: GIT_REVISION.to_owned(),
        command_line: command_line.into(),
        scene: scene_text(scene, problem),
        created: now_rfc3339(),
        seed: problem.seed,
    }
}

/// The scene's text, headed by a comment naming the law when it was given in memory
/// ([`Problem::with_law`]), which the text cannot hold.
fn scene_text(scene: &Scene, problem: &Problem) -> String {
    if !problem.law_in_memory {
        return scene.text.clone();
    }
    format!(
        "# The adhesion law was given in memory (tack::Problem::with_law), not by this text: {} ({})\n{}",
        problem.law.name(),
        problem
            .law
            .describe(problem.gamma, problem.e_star, problem.grid.dx()),
        scene.text
    )
}

/// This process's command line, arguments joined by spaces (arguments with spaces quoted).
pub fn command_line() -> String {
    std::env::args()
        .map(|a| {
            if a.contains(char::is_whitespace) || a.is_empty() {
                format!("{a:?}")
            } else {
                a
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[test]
    fn formats_known_instants() {
        let at = |s| rfc3339_utc(UNIX_EPOCH + Duration::from_secs(s));
        assert_eq!(at(0), "1970-01-01T00:00:00Z");
        assert_eq!(at(951_782_400), "2000-02-29T00:00:00Z");
        assert_eq!(at(1_700_000_000), "2023-11-14T22:13:20Z");
        assert_eq!(at(4_102_444_799), "2099-12-31T23:59:59Z");
    }

    #[test]
    fn revision_is_never_empty() {
        assert!(!GIT_REVISION.is_empty());
    }
}
