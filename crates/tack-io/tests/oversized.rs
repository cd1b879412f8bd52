//! Corrupt files that declare more data than they hold: every dataset's declared size is checked
//! before it is read, so a file saying its curve has 2⁴⁰ entries (or a height map 2²⁰ × 2²⁰)
//! is refused with an error naming the file and the dataset, never an allocation failure.
//!
//! Before these checks such files made the reader abort the whole process ("memory allocation
//! of N bytes failed"), so every test runs its body in a child process (this test binary,
//! running that one test): an abort fails the test instead of killing the harness. The parent
//! opens no HDF5 file, so the children inherit no locks.

use std::path::{Path, PathBuf};
use std::process::Command;

use ndarray::{Array2, array};
use tack_io::{
    Curve, IoError, MAX_DATASET_BYTES, POINT_OK, Provenance, RunResult, Snapshot, Summary,
    SweepTable, describe, read_height_map_h5, read_result, read_sweep_table, write_result,
    write_sweep_table,
};

/// Set in the child process to the name of the test it runs.
const CHILD: &str = "TACK_IO_OVERSIZED_CHILD";

/// Runs `body` in a child process running only the test `name`; fails when the child fails in
/// any way (a failed assertion, a panic, or an abort).
fn isolated(name: &str, body: fn()) {
    if std::env::var(CHILD).as_deref() == Ok(name) {
        body();
        return;
    }
    let exe = std::env::current_exe().expect("the test binary's path");
    let out = Command::new(exe)
        .args([name, "--exact", "--test-threads=1", "--nocapture"])
        .env(CHILD, name)
        .output()
        .expect("the test binary could not be started");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "{name} failed in its child process ({}):\n{stdout}\n{stderr}",
        out.status
    );
    assert!(
        stdout.contains("1 passed"),
        "the child did not run {name}:\n{stdout}"
    );
}

/// A fresh directory under the system temp dir, removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(tag: &str) -> Self {
        let path =
            std::env::temp_dir().join(format!("tack-io-oversized-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&path);
        std::fs::create_dir_all(&path).unwrap();
        Self(path)
    }

    fn join(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

const HUGE: usize = 1 << 40;
const SIDE: usize = 1 << 20;

/// A small valid result: a 5-step curve, a 4 × 3 surface and two snapshots.
fn small() -> RunResult {
    let pressure = Array2::from_shape_fn((4, 3), |(i, j)| i as f64 - j as f64);
    RunResult {
        provenance: Provenance {
            scene: "version = 1\n".into(),
            ..Provenance::current("abc123", "2026-01-01T00:00:00Z")
        },
        curve: Curve {
            law_columns: Vec::new(),
            time: None,
            approach: vec![0.0, 0.25, 0.5, 0.25, 0.0],
            force: vec![0.0, 1.5, 3.0, 0.5, -0.75],
            area: vec![0.0, 0.1, 0.2, 0.1, 0.05],
            n_bonded: vec![0, 10, 20, 10, 5],
            n_clusters: vec![0, 1, 1, 1, 1],
            iterations: vec![0, 17, 23, 5, 1],
            active_set_iterations: vec![0, 2, 3, 1, 1],
            converged: vec![true; 5],
            mean_pressure: Some(vec![0.0, 0.1, 0.2, 0.1, 0.0]),
            full_contact: Some(vec![false; 5]),
        },
        surface: Some((Array2::from_elem((4, 3), 0.5), 0.125)),
        gamma: None,
        snapshots: vec![
            Snapshot {
                step: 1,
                approach: 0.25,
                pressure: pressure.clone(),
                bonded: pressure.mapv(|p| p > 0.0),
            },
            Snapshot {
                step: 3,
                approach: 0.25,
                pressure: pressure.clone(),
                bonded: pressure.mapv(|p| p > 1.0),
            },
        ],
        summary: Summary {
            pull_off_force: -0.75,
            f_jkr: -1.0,
            pull_off_ratio: 0.75,
            ..Summary::default()
        },
    }
}

/// Replaces dataset `name` of the file at `path` with an empty chunked one of `shape` (no data
/// written: the file stays small whatever the shape says), optionally deflate-compressed.
fn replace_with_empty(path: &Path, name: &str, shape: &[usize], f64s: bool) {
    let file = hdf5::File::open_rw(path).unwrap();
    if file.link_exists(name) {
        file.unlink(name).unwrap();
    }
    let chunk: Vec<usize> = shape.iter().map(|&n| n.min(64)).collect();
    let builder = if f64s {
        file.new_dataset::<f64>()
    } else {
        file.new_dataset::<u8>()
    };
    builder
        .shape(shape)
        .chunk(chunk)
        .create(name)
        .unwrap_or_else(|e| panic!("creating {name}: {e}"));
    file.close().unwrap();
}

/// Overwrites the dimensions of every HDF5 dataspace message (version 1, rank
/// `from.len()`) whose dimensions are `from` with `to` (the maximum dimensions too, when
/// stored); returns how many it patched.
fn patch_dims(path: &Path, from: &[u64], to: &[u64]) -> usize {
    let mut bytes = std::fs::read(path).unwrap();
    let rank = from.len();
    let encode = |dims: &[u64]| -> Vec<u8> { dims.iter().flat_map(|d| d.to_le_bytes()).collect() };
    let (old, new) = (encode(from), encode(to));
    let mut count = 0;
    let mut i = 0;
    while i + 8 + 16 * rank <= bytes.len() {
        let header = &bytes[i..i + 8];
        let is_space = header[0] == 1
            && header[1] as usize == rank
            && header[2] <= 1
            && header[3..8] == [0; 5]
            && bytes[i + 8..i + 8 + 8 * rank] == old[..];
        if is_space {
            let with_max = header[2] == 1;
            bytes[i + 8..i + 8 + 8 * rank].copy_from_slice(&new);
            if with_max && bytes[i + 8 + 8 * rank..i + 8 + 16 * rank] == old[..] {
                bytes[i + 8 + 8 * rank..i + 8 + 16 * rank].copy_from_slice(&new);
            }
            count += 1;
            i += 8 + 8 * rank;
        } else {
            i += 1;
        }
    }
    std::fs::write(path, bytes).unwrap();
    count
}

fn file_len(path: &Path) -> u64 {
    std::fs::metadata(path).unwrap().len()
}

/// Checks the error names the file and `dataset`.
fn assert_names(err: &IoError, path: &Path, dataset: &str) -> String {
    let msg = err.to_string();
    assert!(
        msg.starts_with(&path.display().to_string()) && msg.contains(dataset),
        "the error should name {} and {dataset}: {msg}",
        path.display()
    );
    msg
}

#[test]
fn a_curve_declaring_2_pow_40_entries_is_refused_before_reading() {
    isolated(
        "a_curve_declaring_2_pow_40_entries_is_refused_before_reading",
        || {
            let dir = TempDir::new("curve");
            let path = dir.join("run.h5");
            write_result(&path, &small()).unwrap();
            replace_with_empty(&path, "/curve/approach", &[HUGE], true);
            assert!(file_len(&path) < 100_000, "{}", file_len(&path));
            let err = read_result(&path).unwrap_err();
            assert!(matches!(err, IoError::Oversized { .. }), "{err:?}");
            let msg = assert_names(&err, &path, "`/curve/approach`");
            assert!(msg.contains("1099511627776"), "{msg}");
            let err = describe(&path).unwrap_err();
            assert_names(&err, &path, "`/curve/approach`");

            // One column huge, the others fine: refused as unequal lengths before reading.
            write_result(&path, &small()).unwrap();
            replace_with_empty(&path, "/curve/force", &[HUGE], true);
            let err = read_result(&path).unwrap_err();
            assert!(
                matches!(
                    &err,
                    IoError::ColumnLength {
                        column,
                        len: HUGE,
                        expected: 5,
                        ..
                    } if column == "force"
                ),
                "{err:?}"
            );
            write_result(&path, &small()).unwrap();
            replace_with_empty(&path, "/curve/converged", &[HUGE], false);
            let err = read_result(&path).unwrap_err();
            assert!(
                matches!(
                    &err,
                    IoError::ColumnLength { column, .. } if column == "converged"
                ),
                "{err:?}"
            );
        },
    );
}

#[test]
fn patched_dataspaces_are_refused_before_reading() {
    isolated("patched_dataspaces_are_refused_before_reading", || {
        let dir = TempDir::new("patched");
        let path = dir.join("run.h5");
        // Every curve column 2⁴⁰ long: the lengths agree, the file is far too small.
        write_result(&path, &small()).unwrap();
        assert_eq!(patch_dims(&path, &[5], &[HUGE as u64]), 10);
        let err = read_result(&path).unwrap_err();
        assert!(matches!(err, IoError::Oversized { .. }), "{err:?}");
        let msg = assert_names(&err, &path, "/curve/");
        assert!(msg.contains("bytes"), "{msg}");

        // One byte changed: the 7th byte of a curve column's length (5 → 5 + 3·2⁴⁸).
        write_result(&path, &small()).unwrap();
        let one_byte = 5 + (3 << 48);
        assert_eq!(patch_dims(&path, &[5], &[one_byte]), 10);
        let err = read_result(&path).unwrap_err();
        assert!(matches!(err, IoError::Oversized { .. }), "{err:?}");
        assert_names(&err, &path, "/curve/");

        // The surface and both snapshots 2²⁰ × 2²⁰.
        write_result(&path, &small()).unwrap();
        let side = SIDE as u64;
        assert_eq!(patch_dims(&path, &[4, 3], &[side, side]), 5);
        let err = read_result(&path).unwrap_err();
        assert!(matches!(err, IoError::Oversized { .. }), "{err:?}");
        assert_names(&err, &path, "`/surface/heights`");
        assert!(err.to_string().contains("1048576 × 1048576"), "{err}");
    });
}

#[test]
fn snapshots_must_have_the_surface_shape_and_fit_the_file() {
    isolated(
        "snapshots_must_have_the_surface_shape_and_fit_the_file",
        || {
            let dir = TempDir::new("snapshots");
            let path = dir.join("run.h5");
            // Pressure and bonded agree with each other, not with the file's size.
            write_result(&path, &small()).unwrap();
            replace_with_empty(&path, "/snapshots/3/pressure", &[SIDE, SIDE], true);
            replace_with_empty(&path, "/snapshots/3/bonded", &[SIDE, SIDE], false);
            let err = read_result(&path).unwrap_err();
            let msg = assert_names(&err, &path, "/snapshots/3/");
            assert!(msg.contains("1048576 × 1048576"), "{msg}");

            // Small, but not the shape of the surface.
            write_result(&path, &small()).unwrap();
            replace_with_empty(&path, "/snapshots/1/pressure", &[5, 5], true);
            replace_with_empty(&path, "/snapshots/1/bonded", &[5, 5], false);
            let err = read_result(&path).unwrap_err();
            let msg = assert_names(&err, &path, "/snapshots/1/");
            assert!(msg.contains("5 × 5") && msg.contains("4 × 3"), "{msg}");

            // Without a surface the snapshots must agree with one another.
            let mut r = small();
            r.surface = None;
            write_result(&path, &r).unwrap();
            replace_with_empty(&path, "/snapshots/3/pressure", &[5, 5], true);
            replace_with_empty(&path, "/snapshots/3/bonded", &[5, 5], false);
            let err = read_result(&path).unwrap_err();
            let msg = assert_names(&err, &path, "/snapshots/3/");
            assert!(msg.contains("5 × 5") && msg.contains("4 × 3"), "{msg}");

            // The writer refuses what the reader would.
            let mut r = small();
            r.snapshots[0].pressure = Array2::zeros((5, 5));
            r.snapshots[0].bonded = Array2::from_elem((5, 5), false);
            let err = write_result(&dir.join("other.h5"), &r).unwrap_err();
            assert!(err.to_string().contains("4 × 3"), "{err}");
        },
    );
}

/// Writes a height map as a user's tool would: `heights` with a `dx` attribute.
fn height_file(path: &Path, shape: &[usize], deflate: bool) {
    let file = hdf5::File::create(path).unwrap();
    let chunk: Vec<usize> = shape.iter().map(|&n| n.min(256)).collect();
    let mut builder = file.new_dataset::<f64>().shape(shape).chunk(chunk);
    if deflate {
        builder = builder.deflate(6);
    }
    let ds = builder.create("heights").unwrap();
    ds.new_attr::<f64>()
        .create("dx")
        .unwrap()
        .write_scalar(&0.5)
        .unwrap();
    file.close().unwrap();
}

#[test]
fn a_huge_height_map_is_refused_before_reading() {
    isolated("a_huge_height_map_is_refused_before_reading", || {
        let dir = TempDir::new("heights");
        let path = dir.join("map.h5");
        height_file(&path, &[SIDE, SIDE], false);
        // The grid's shape is known: refused for not being it.
        let err = read_height_map_h5(&path, None, Some((32, 32))).unwrap_err();
        let msg = assert_names(&err, &path, "`heights`");
        assert!(
            msg.contains("1048576 × 1048576") && msg.contains("32 × 32"),
            "{msg}"
        );
        // Unknown grid: refused for declaring more than the (uncompressed) file holds.
        let err = read_height_map_h5(&path, None, None).unwrap_err();
        assert!(matches!(err, IoError::Oversized { .. }), "{err:?}");
        assert_names(&err, &path, "`heights`");

        // Compressed: the file bound does not apply, the absolute limit does.
        height_file(&path, &[SIDE, SIDE], true);
        let err = read_height_map_h5(&path, None, None).unwrap_err();
        assert!(matches!(err, IoError::Oversized { .. }), "{err:?}");
        let msg = assert_names(&err, &path, "`heights`");
        assert!(msg.contains(&MAX_DATASET_BYTES.to_string()), "{msg}");

        // Our own result files: `/surface/heights`, patched.
        let ours = dir.join("run.h5");
        write_result(&ours, &small()).unwrap();
        let side = SIDE as u64;
        patch_dims(&ours, &[4, 3], &[side, side]);
        let err = read_height_map_h5(&ours, None, Some((4, 3))).unwrap_err();
        let msg = assert_names(&err, &ours, "`/surface/heights`");
        assert!(msg.contains("1048576 × 1048576"), "{msg}");
        let err = read_height_map_h5(&ours, None, None).unwrap_err();
        assert_names(&err, &ours, "`/surface/heights`");
    });
}

#[test]
fn compressed_height_maps_larger_than_their_file_still_read() {
    isolated(
        "compressed_height_maps_larger_than_their_file_still_read",
        || {
            let dir = TempDir::new("compressed");
            let path = dir.join("map.h5");
            let h = Array2::from_shape_fn((512, 512), |(i, j)| ((i / 64 + j / 64) % 2) as f64);
            let file = hdf5::File::create(&path).unwrap();
            let ds = file
                .new_dataset_builder()
                .with_data(&h)
                .chunk((128, 128))
                .deflate(9)
                .create("heights")
                .unwrap();
            ds.new_attr::<f64>()
                .create("dx")
                .unwrap()
                .write_scalar(&0.5)
                .unwrap();
            file.close().unwrap();
            assert!(file_len(&path) < 512 * 512 * 8 / 4, "{}", file_len(&path));
            let read = read_height_map_h5(&path, None, Some((512, 512))).unwrap();
            assert_eq!(read, (h.clone(), 0.5));
            assert_eq!(read_height_map_h5(&path, None, None).unwrap(), (h, 0.5));
            // A grid of another shape is named.
            let err = read_height_map_h5(&path, None, Some((256, 512))).unwrap_err();
            assert!(
                err.to_string().contains("512 × 512") && err.to_string().contains("256 × 512"),
                "{err}"
            );
        },
    );
}

#[test]
fn a_sweep_table_with_a_huge_column_is_refused() {
    isolated("a_sweep_table_with_a_huge_column_is_refused", || {
        let dir = TempDir::new("table");
        let path = dir.join("sweep.h5");
        let table = SweepTable {
            sweep: "version = 1\n".into(),
            provenance: Provenance::current("abc", "2026-01-01T00:00:00Z"),
            index: vec![0, 1],
            status: vec![POINT_OK; 2],
            error: vec![String::new(); 2],
            result_status: vec!["complete".into(); 2],
            warnings: vec![String::new(); 2],
            parameters: Vec::new(),
            results: vec![("pull_off_force".into(), vec![-1.0, -2.0])],
        };
        write_sweep_table(&path, &table).unwrap();
        assert_eq!(read_sweep_table(&path).unwrap(), table);
        replace_with_empty(&path, "/results/pull_off_force", &[HUGE], true);
        let err = read_sweep_table(&path).unwrap_err();
        assert!(matches!(err, IoError::Oversized { .. }), "{err:?}");
        assert_names(&err, &path, "`/results/pull_off_force`");
    });
}

#[test]
fn valid_files_still_read() {
    isolated("valid_files_still_read", || {
        let dir = TempDir::new("valid");
        let path = dir.join("run.h5");
        let r = small();
        write_result(&path, &r).unwrap();
        let back = read_result(&path).unwrap();
        assert_eq!(back, r);
        // A surface-only file: empty curve.
        let mut s = small();
        s.curve = Curve::default();
        s.snapshots.clear();
        write_result(&path, &s).unwrap();
        assert_eq!(read_result(&path).unwrap(), s);
        let h = array![[0.0, 1.0], [2.0, 3.0]];
        let map = dir.join("map.h5");
        let file = hdf5::File::create(&map).unwrap();
        let ds = file
            .new_dataset_builder()
            .with_data(&h)
            .create("heights")
            .unwrap();
        ds.new_attr::<f64>()
            .create("dx")
            .unwrap()
            .write_scalar(&0.5)
            .unwrap();
        file.close().unwrap();
        assert_eq!(
            read_height_map_h5(&map, None, Some((2, 2))).unwrap(),
            (h, 0.5)
        );
    });
}
