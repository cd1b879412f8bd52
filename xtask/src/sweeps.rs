//! Figures run as tack sweeps (Figures 5 and 7, which Figures 6 and 8 read): the figure's point
//! scenes become one sweep file (the base scene inline, one zipped `[vary]` entry of the fields
//! that differ between points, one row per point), run by `tack_sweep::run_sweep` into
//! `OUT/figN/sweep-<mode>/` (one HDF5 result per point, resumable), then read back with
//! `tack_io::read_result`.
//!
//! A rerun of the same figure in the same mode finds the directory's `sweep.toml` equal to the
//! generated text and skips every point whose result file records exactly its scene; a
//! directory made from other parameters is refused, never reused (see [`FigureSweep::run`]).
//! Points are recognised by their scene text only: results made by an older build of the
//! solver are kept; delete the directory to recompute them.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use tack::SceneSchema;
// The sections of a scene, in the order docs/scenes.md documents them.
use tack_fields::SECTIONS;
use tack_sweep::{SWEEP_COPY, Sweep, SweepOptions, point_path, run_sweep, verify_point};

/// One point of a figure sweep: its scene and a note for the row comment (`H = 0.1, α* = 0.2`).
pub struct PointScene {
    /// What the point is, for a reader of the sweep file.
    pub note: String,
    /// The scene, exactly as the figure built it.
    pub scene: SceneSchema,
}

/// A figure's sweep: the generated file, where it runs, and its points in order.
pub struct FigureSweep {
    /// `OUT/figN/sweep-<mode>`.
    pub dir: PathBuf,
    /// The parsed sweep (its `text` is the generated file).
    pub sweep: Sweep,
    /// The points' notes, in point order.
    pub notes: Vec<String>,
}

/// The output directory of figure `figure`'s sweep in a mode: `OUT/figN/sweep-quick` or
/// `OUT/figN/sweep-full` (the modes never share points).
pub fn sweep_dir(out: &Path, figure: u8, full: bool) -> PathBuf {
    out.join(format!("fig{figure}"))
        .join(format!("sweep-{}", mode(full)))
}

fn mode(full: bool) -> &'static str {
    if full { "full" } else { "quick" }
}

/// Every scene field as `(dotted path, value)`, in the serialisation's order; tables are
/// followed down to their values (`output.snapshots = { every = 2 }` gives
/// `output.snapshots.every`).
fn leaves(table: &toml::Table) -> Vec<(String, toml::Value)> {
    fn walk(table: &toml::Table, prefix: &str, out: &mut Vec<(String, toml::Value)>) {
        for (key, value) in table {
            let path = if prefix.is_empty() {
                key.clone()
            } else {
                format!("{prefix}.{key}")
            };
            match value {
                toml::Value::Table(inner) => walk(inner, &path, out),
                other => out.push((path, other.clone())),
            }
        }
    }
    let mut out = Vec::new();
    walk(table, "", &mut out);
    out
}

/// Removes the dotted `path` from `table` (it exists: it came from [`leaves`]).
fn remove(table: &mut toml::Table, path: &str) {
    match path.split_once('.') {
        None => {
            table.remove(path);
        }
        Some((head, rest)) => {
            if let Some(toml::Value::Table(inner)) = table.get_mut(head) {
                remove(inner, rest);
            }
        }
    }
}

impl FigureSweep {
    /// The sweep of `points` for figure `figure` in the given mode, collecting `collect`.
    ///
    /// The base scene is what all points share; the fields whose values differ between points
    /// form one zipped `[vary]` entry with a row per point (a plain list when only one field
    /// differs). The generated file is parsed back and every point's scene is checked to equal
    /// the figure's scene exactly (same values, bit for bit), so the sweep runs precisely what
    /// the figure asked for.
    pub fn new(
        out: &Path,
        figure: u8,
        full: bool,
        about: &str,
        collect: &[&str],
        points: Vec<PointScene>,
    ) -> Result<Self> {
        let Some(first) = points.first() else {
            bail!("figure {figure}: the sweep has no points");
        };
        let tables = points
            .iter()
            .map(|p| match toml::Value::try_from(&p.scene) {
                Ok(toml::Value::Table(t)) => Ok(t),
                Ok(_) => bail!("figure {figure}: a scene serialises to a table"),
                Err(e) => {
                    Err(e).with_context(|| format!("figure {figure}: serialising a point's scene"))
                }
            })
            .collect::<Result<Vec<_>>>()?;
        let all: Vec<Vec<(String, toml::Value)>> = tables.iter().map(leaves).collect();
        let fields: Vec<&str> = all[0].iter().map(|(f, _)| f.as_str()).collect();
        for (k, point) in all.iter().enumerate() {
            let these: Vec<&str> = point.iter().map(|(f, _)| f.as_str()).collect();
            if these != fields {
                bail!(
                    "figure {figure}: point {k} ({}) sets other scene fields than point 0 ({}); \
                     a figure sweep varies values only",
                    points[k].note,
                    first.note
                );
            }
        }
        // The varied fields in the order of the scene's sections (as docs/scenes.md lists
        // them), alphabetical within a section.
        let section = |field: &str| {
            let head = field.split('.').next().unwrap_or(field);
            SECTIONS
                .iter()
                .position(|s| *s == head)
                .unwrap_or(SECTIONS.len())
        };
        let mut varied: Vec<usize> = (0..fields.len())
            .filter(|&i| all.iter().any(|p| p[i].1 != all[0][i].1))
            .collect();
        if varied.is_empty() {
            // One point, or points that are all alike: a sweep needs a field in [vary], so the
            // first field of the scene is listed with its (one) value.
            varied.extend(
                (0..fields.len())
                    .filter(|&i| fields[i] != "version")
                    .min_by_key(|&i| (section(fields[i]), fields[i])),
            );
        }
        varied.sort_by_key(|&i| (section(fields[i]), fields[i]));
        let mut base = tables[0].clone();
        for &i in &varied {
            remove(&mut base, fields[i]);
        }
        let mut doc = toml::Table::new();
        doc.insert("scene".into(), toml::Value::Table(base));
        let scene_text = toml::to_string(&doc).context("serialising the base scene")?;

        let dir = sweep_dir(out, figure, full);
        let mut text = format!(
            "# Figure {figure} of `cargo xtask reproduce`, {} mode: {about}.\n\
             # Generated from data/figures/fig{figure}.toml; a rerun of the figure regenerates \
             this file and resumes\n\
             # the sweep in this directory (a directory made from other parameters is refused).\n\
             # One point per row of [vary]. By hand: `tack sweep sweep.toml -o .` in this \
             directory,\n\
             # `tack merge . -o table.h5` for the collected table.\n\
             version = 1\ncollect = [{}]\n\n[vary]\n",
            mode(full),
            collect
                .iter()
                .map(|c| format!("{c:?}"))
                .collect::<Vec<_>>()
                .join(", ")
        );
        let key: Vec<&str> = varied.iter().map(|&i| fields[i]).collect();
        let _ = writeln!(text, "{:?} = [", key.join(", "));
        for (k, (point, p)) in all.iter().zip(&points).enumerate() {
            let row: Vec<String> = varied.iter().map(|&i| point[i].1.to_string()).collect();
            let note = p.note.replace('\n', " ");
            // One field is a plain entry (a list of values), several a zipped one (rows).
            let row = match row.as_slice() {
                [one] => one.clone(),
                _ => format!("[{}]", row.join(", ")),
            };
            let _ = writeln!(text, "  {row},  # point {k}: {note}");
        }
        text += "]\n\n";
        text += &scene_text;

        let sweep = Sweep::parse_text(&text, &dir.join(SWEEP_COPY))
            .with_context(|| format!("figure {figure}: the generated sweep"))?;
        if sweep.len() != points.len() {
            bail!(
                "figure {figure}: the generated sweep has {} points, the figure {}",
                sweep.len(),
                points.len()
            );
        }
        for (i, p) in points.iter().enumerate() {
            let scene = sweep
                .point_scene(i)
                .with_context(|| format!("figure {figure}: point {i} ({})", p.note))?;
            if scene.file != p.scene {
                bail!(
                    "figure {figure}: point {i} ({}) of the generated sweep is not the figure's \
                     scene",
                    p.note
                );
            }
        }
        Ok(Self {
            dir,
            sweep,
            notes: points.into_iter().map(|p| p.note).collect(),
        })
    }

    /// Runs the points that are not complete yet (`threads` at a time, a progress bar on a
    /// terminal) and reads every point's result back, in point order.
    ///
    /// The directory must be new or hold this very sweep: a `sweep.toml` that differs (the
    /// spec's parameters changed, or another mode's or figure's sweep) stops with an error
    /// rather than mixing results. Within the sweep, a point is only skipped when its result
    /// file records exactly the point's scene (`tack_sweep::verify_point`).
    ///
    /// A point whose scene is refused or whose run fails does not stop the figure: its slot is
    /// `None` and it is listed in [`SweepRuns::failed`] (its error is in `points/<i>.err`), so
    /// that one unlucky realization of a 675-run sweep costs one point, not the figure. Only a
    /// sweep in which every point failed is an error.
    pub fn run(&self, threads: usize) -> Result<SweepRuns> {
        let copy = self.dir.join(SWEEP_COPY);
        if copy.is_file() {
            let old = std::fs::read_to_string(&copy)
                .with_context(|| format!("reading {}", copy.display()))?;
            if old != self.sweep.text {
                bail!(
                    "{} holds a sweep made from other parameters than the figure specs now give \
                     (the spec changed since it ran): delete {} to start this figure's sweep \
                     over, or choose another --out",
                    copy.display(),
                    self.dir.display()
                );
            }
        }
        let total = self.sweep.len();
        let complete = (0..total)
            .filter(|&i| point_path(&self.dir, i, total, "h5").is_file())
            .count();
        println!(
            "  {} points in {} ({complete} result files already there, verified before they \
             are skipped), {threads} threads",
            total,
            self.dir.display()
        );
        let options = SweepOptions {
            threads: Some(threads),
            ..SweepOptions::default()
        };
        let report = run_sweep(&self.sweep, &self.dir, &options, &PrintFailures)?;
        println!("  {report}");
        let failed: Vec<FailedPoint> = report
            .failed
            .iter()
            .map(|f| FailedPoint {
                index: f.index,
                note: self.notes[f.index].clone(),
                message: f.message.clone(),
            })
            .collect();
        if failed.len() == total {
            bail!(
                "all {total} points of {} failed (errors in points/*.err); the first: {}",
                self.dir.display(),
                failed.first().map_or(String::new(), |f| f.to_string())
            );
        }
        let runs = (0..total)
            .map(|i| {
                if failed.iter().any(|f| f.index == i) {
                    return Ok(None);
                }
                let file = point_path(&self.dir, i, total, "h5");
                let text = self.sweep.point_text(i)?;
                let result = verify_point(&file, &text).map_err(anyhow::Error::msg)?;
                Ok(Some(PointRun { file, result }))
            })
            .collect::<Result<_>>()?;
        Ok(SweepRuns { runs, failed })
    }
}

/// What [`FigureSweep::run`] read back.
pub struct SweepRuns {
    /// Every point in order; `None` where the point failed.
    pub runs: Vec<Option<PointRun>>,
    /// The failed points, in order.
    pub failed: Vec<FailedPoint>,
}

impl SweepRuns {
    /// One summary note per failed point (none when every point ran).
    pub fn notes(&self) -> Vec<String> {
        self.failed
            .iter()
            .map(|f| format!("left out (failed): {f}"))
            .collect()
    }
}

/// A point of a figure's sweep that failed.
#[derive(Debug, Clone)]
pub struct FailedPoint {
    /// Its index in the sweep.
    pub index: usize,
    /// What it is (the figure's note).
    pub note: String,
    /// Why it failed.
    pub message: String,
}

impl std::fmt::Display for FailedPoint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "point {} ({}): {}", self.index, self.note, self.message)
    }
}

/// A completed point: its result file and what it holds.
pub struct PointRun {
    /// `DIR/points/<index>.h5`.
    pub file: PathBuf,
    /// The result read back.
    pub result: tack_io::RunResult,
}

impl PointRun {
    /// |F_ad/F_JKR| of the point.
    pub fn ratio(&self) -> f64 {
        self.result.summary.pull_off_ratio.abs()
    }
    /// Index of the pull-off step (`tack_solver::pull_off_step`: the least force over the
    /// steps not in periodic full contact, the first on ties).
    pub fn pull_off_step(&self) -> usize {
        let c = &self.result.curve;
        let full = |i: usize| c.full_contact.as_ref().is_some_and(|f| f[i]);
        let steps = c.force.iter().enumerate().map(|(i, &f)| (f, full(i)));
        tack_solver::pull_off_step(steps).unwrap_or(0)
    }
    /// The stored fields of step `step` (on the full grid), if any.
    pub fn snapshot(&self, step: usize) -> Option<&tack_io::Snapshot> {
        self.result.snapshots.iter().find(|s| s.step == step)
    }
}

/// Prints each failed point as it happens (the figure's summary names it again).
struct PrintFailures;

impl tack_sweep::SweepObserver for PrintFailures {
    fn on_point(&self, index: usize, label: &str, failure: Option<&str>) {
        if let Some(message) = failure {
            eprintln!("  point {index} ({label}) failed: {message}");
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene(gamma: f64, radius: f64, n: usize) -> SceneSchema {
        let text = format!(
            "version = 1\n[material]\ne_star = 1.0\ngamma = {gamma}\n[geometry]\n\
             shape = \"sphere\"\nradius = {radius}\n[grid]\nn = {n}\ndx = 0.6\n[protocol]\n\
             max_approach = 3.0\nload_step = 0.15\n[output]\nsurface = false\n"
        );
        tack::Scene::parse(&text, ".", &[]).unwrap().file
    }

    #[test]
    fn the_varied_fields_become_one_zipped_entry_and_points_round_trip() {
        let out = std::env::temp_dir().join(format!("tack-xtask-sweeps-{}", std::process::id()));
        // Values that do not print short: they must come back bit for bit.
        let g = [0.1 + 0.2, 1.0 / 3.0, 2.82942e-4];
        let points: Vec<PointScene> = (0..3)
            .map(|k| PointScene {
                note: format!("note {k}"),
                scene: scene(g[k], 8.0 + k as f64, 24 + 2 * k),
            })
            .collect();
        let mut with_snapshots = points
            .iter()
            .map(|p| PointScene {
                note: p.note.clone(),
                scene: p.scene.clone(),
            })
            .collect::<Vec<_>>();
        with_snapshots[0].scene.output.snapshots = tack::scene::Snapshots::PullOff;
        let fs = FigureSweep::new(&out, 7, false, "test", &["pull_off_ratio"], points).unwrap();
        assert_eq!(fs.dir, out.join("fig7/sweep-quick"));
        let fields: Vec<&str> = fs.sweep.axes.iter().map(|a| a.field.as_str()).collect();
        assert_eq!(fields, ["material.gamma", "geometry.radius", "grid.n"]);
        assert!(
            fs.sweep
                .text
                .contains("\"material.gamma, geometry.radius, grid.n\" = [\n")
        );
        assert!(fs.sweep.axes.iter().all(|a| a.entry == 0));
        assert_eq!(fs.sweep.len(), 3);
        assert!(
            fs.sweep.text.contains("],  # point 2: note 2\n"),
            "{}",
            fs.sweep.text
        );
        // The base scene leaves the varied fields to the points.
        assert!(
            !fs.sweep.base_text.contains("gamma"),
            "{}",
            fs.sweep.base_text
        );
        let fs =
            FigureSweep::new(&out, 5, true, "test", &["pull_off_ratio"], with_snapshots).unwrap();
        assert_eq!(fs.dir, out.join("fig5/sweep-full"));
        let fields: Vec<&str> = fs.sweep.axes.iter().map(|a| a.field.as_str()).collect();
        assert!(fields.contains(&"output.snapshots"), "{fields:?}");
        // A single point still makes a valid sweep (its first field listed with one value).
        let one = vec![PointScene {
            note: String::new(),
            scene: scene(0.1, 8.0, 24),
        }];
        let fs = FigureSweep::new(&out, 5, false, "t", &["pull_off_force"], one).unwrap();
        assert_eq!(fs.sweep.len(), 1);
        assert_eq!(fs.sweep.axes[0].field, "material.e_star");
        assert!(
            fs.sweep
                .text
                .contains("\"material.e_star\" = [\n  1.0,  # point 0")
        );
        assert!(!out.exists(), "building a sweep writes nothing");
    }

    #[test]
    fn a_failed_point_is_left_out_and_listed_not_fatal() {
        let out =
            std::env::temp_dir().join(format!("tack-xtask-sweeps-fail-{}", std::process::id()));
        // Point 1's grid (12² at Δx = 0.6) cannot hold the Hertz contact at the deepest approach.
        let points: Vec<PointScene> = [24, 12, 26]
            .iter()
            .map(|&n| PointScene {
                note: format!("n = {n}"),
                scene: scene(0.2, 8.0, n),
            })
            .collect();
        let fs = FigureSweep::new(&out, 5, false, "test", &["pull_off_ratio"], points).unwrap();
        let done = fs.run(1).unwrap();
        assert_eq!(done.runs.len(), 3);
        assert!(done.runs[0].is_some() && done.runs[2].is_some());
        assert!(done.runs[1].is_none());
        assert_eq!(done.failed.len(), 1);
        assert_eq!(done.failed[0].index, 1);
        assert_eq!(done.failed[0].note, "n = 12");
        assert!(
            done.failed[0].message.contains("grid.n"),
            "{}",
            done.failed[0].message
        );
        let notes = done.notes();
        assert_eq!(notes.len(), 1);
        assert!(
            notes[0].starts_with("left out (failed): point 1 (n = 12): "),
            "{}",
            notes[0]
        );
        // The runs that did run are real pull-offs.
        assert!(done.runs[0].as_ref().unwrap().ratio() > 0.5);
        // A sweep whose every point fails is an error that names the first failure.
        let bad = vec![PointScene {
            note: "tiny".into(),
            scene: scene(0.2, 8.0, 10),
        }];
        let fs = FigureSweep::new(&out, 7, false, "test", &["pull_off_ratio"], bad).unwrap();
        let err = fs.run(1).err().expect("every point failed").to_string();
        assert!(
            err.contains("all 1 points") && err.contains("tiny"),
            "{err}"
        );
        std::fs::remove_dir_all(&out).unwrap();
    }
}
