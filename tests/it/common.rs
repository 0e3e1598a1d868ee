//! Helpers shared by the integration tests: the command line under test, the source tree, fresh
//! scratch folders, the peer programs built under `target/peer`, and the switch that skips the
//! slow tests (`FAIRSUB_SKIP_SLOW`). All tests run in one process, so anything named after the
//! process id alone is shared by every test: scratch folders here are unique per call.

use std::path::PathBuf;
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The `fairsub` command line built for these tests.
pub const BIN: &str = env!("CARGO_BIN_EXE_fairsub");

/// The variable that skips the slow tests (peers and clients) on a laptop; CI never sets it.
pub const SKIP_SLOW: &str = "FAIRSUB_SKIP_SLOW";

/// The crate's folder (`tests/data`, `tests/peer` and `target/peer` are under it).
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A new empty folder under the system's temporary folder, named after `tag`, this process and
/// a counter: two tests (or two calls of one test) never share it.
pub fn scratch(tag: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let n = N.fetch_add(1, Ordering::Relaxed);
    let d = std::env::temp_dir().join(format!("fairsub-it-{}-{n}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("scratch folder");
    d
}

/// `fairsub ARGS` run to the end: exit code, stdout and stderr.
pub fn run(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(BIN).args(args).output().expect("fairsub runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `fairsub ARGS`, which must succeed: its stderr.
pub fn run_ok(args: &[&str]) -> String {
    let (code, _, err) = run(args);
    assert_eq!(code, 0, "fairsub {args:?}: {err}");
    err
}

/// Whether the slow test `what` (a peer or client test) is skipped because `FAIRSUB_SKIP_SLOW` is
/// set; says so on stdout (`--nocapture` shows it). CI fails when the variable is set.
pub fn skip_slow(what: &str) -> bool {
    let skip = std::env::var_os(SKIP_SLOW).is_some_and(|v| !v.is_empty() && v != "0");
    if skip {
        println!("{what}: skipped ({SKIP_SLOW} is set)");
    }
    skip
}

/// The peer program `target/peer/NAME` (built by `tests/peer/SCRIPT`), or `None` when the test
/// skips: `FAIRSUB_SKIP_SLOW` is set, or the program is missing and the variable `require` is
/// unset (with it set, a missing program fails the test).
pub fn peer_program(name: &str, script: &str, require: &str) -> Option<PathBuf> {
    if skip_slow(name) {
        return None;
    }
    let p = root().join("target/peer").join(name);
    if p.exists() {
        return Some(p);
    }
    let msg = format!("{} missing (run tests/peer/{script})", p.display());
    if std::env::var_os(require).is_some() {
        panic!("{require} is set and {msg}");
    }
    println!("{name}: skipped: {msg}");
    None
}

/// A 4 x 4 grid of quads (25 vertices), lifted into a bowl so no patch is planar.
pub fn bowl_grid() -> (Vec<fairsub::geom::Point>, Vec<Vec<usize>>) {
    let mut pos = Vec::new();
    for j in 0..5 {
        for i in 0..5 {
            let (x, y) = (i as f64, j as f64);
            pos.push([x, y, 0.1 * (x - 2.0).powi(2) + 0.07 * (y - 2.0).powi(2)]);
        }
    }
    let mut faces = Vec::new();
    for j in 0..4 {
        for i in 0..4 {
            let a = 5 * j + i;
            faces.push(vec![a, a + 1, a + 6, a + 5]);
        }
    }
    (pos, faces)
}
