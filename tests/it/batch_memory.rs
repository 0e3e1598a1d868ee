//! `fairsub batch --max-memory SIZE` is the budget of each job, not of the run: a job whose
//! estimate is over it gets an error row that names the budget (and writes nothing) while the
//! jobs under it run; the same job passes under a budget it fits, also when two jobs run at
//! once (the budget is not shared by the slots when it is given).

use crate::common::scratch;
use serde_json::{Value, json};
use std::path::Path;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_fairsub");

/// `fairsub batch MANIFEST --out OUT --jobs 2 --max-memory SIZE`: (success, stderr, rows by
/// output).
fn batch(manifest: &Path, out: &Path, size: &str) -> (bool, String, Vec<Value>) {
    let o = Command::new(BIN)
        .args(["batch", manifest.to_str().unwrap(), "--out"])
        .arg(out)
        .args(["--jobs", "2", "--max-memory", size])
        .output()
        .unwrap();
    let rows = std::fs::read_to_string(out.join("results.jsonl"))
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
        rows,
    )
}

fn status<'a>(rows: &'a [Value], output: &str) -> (&'a str, &'a str) {
    let r = rows.iter().find(|r| r["output"] == output).unwrap();
    (
        r["status"].as_str().unwrap(),
        r["error"].as_str().unwrap_or(""),
    )
}

#[test]
fn max_memory_bounds_each_job() {
    let dir = scratch("main");
    let jobs = [
        json!({"input": "gallery:torus-evs", "scheme": "catmull-clark", "levels": 6, "output": "big-a.obj"}),
        json!({"input": "gallery:torus-evs", "scheme": "catmull-clark", "levels": 6, "output": "big-b.obj"}),
        json!({"input": "gallery:cube", "scheme": "catmull-clark", "levels": 1, "output": "small.obj"}),
    ];
    let lines: Vec<String> = jobs.iter().map(Value::to_string).collect();
    let manifest = dir.join("m.jsonl");
    std::fs::write(&manifest, lines.join("\n")).unwrap();

    // 1 MiB: the level-6 jobs are refused up front, the small one runs
    let tight = dir.join("tight");
    let (ok, err, rows) = batch(&manifest, &tight, "1M");
    assert!(!ok, "{err}");
    assert!(err.contains("2 of 3 jobs failed"), "{err}");
    for big in ["big-a.obj", "big-b.obj"] {
        let (s, e) = status(&rows, big);
        assert_eq!(s, "error");
        assert!(e.contains("too large") && e.contains("--max-memory"), "{e}");
        assert!(!tight.join(big).exists());
    }
    assert_eq!(status(&rows, "small.obj").0, "ok");

    // 256 MiB each, two at once: both level-6 jobs fit (the budget is per job)
    let roomy = dir.join("roomy");
    let (ok, err, rows) = batch(&manifest, &roomy, "256M");
    assert!(ok, "{err}");
    for o in ["big-a.obj", "big-b.obj", "small.obj"] {
        assert_eq!(status(&rows, o).0, "ok", "{rows:?}");
        assert!(roomy.join(o).exists());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
