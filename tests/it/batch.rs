//! `fairsub batch` on a manifest of a few hundred jobs that the test makes: gallery nets and
//! generated nets under several schemes, formats and options, with corrupt, oversized and
//! unsupported inputs among them. Every good job's output equals the single-file command's
//! bytes, every bad job has an error row that names the problem, nothing is half-written, a
//! second run does no work, and a third run after an output was deleted, another changed and
//! a row corrupted redoes exactly those jobs.

use crate::common::scratch;
use serde_json::{Value, json};
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_fairsub");

/// Runs the binary; returns (success, stderr). IGES files carry their date: a fixed one
/// (`SOURCE_DATE_EPOCH`, as reproducible builds set it) makes them comparable.
fn fairsub(args: &[&str]) -> (bool, String) {
    let o = Command::new(BIN)
        .args(args)
        .env("SOURCE_DATE_EPOCH", "1700000000")
        .output()
        .unwrap();
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// `fairsub batch MANIFEST --out OUT --jobs 2`.
fn run_batch(manifest: &Path, out: &Path) -> (bool, String) {
    let (m, o) = (manifest.to_str().unwrap(), out.to_str().unwrap());
    fairsub(&["batch", m, "--out", o, "--jobs", "2"])
}

/// The rows of `results.jsonl` (every line must be a row).
fn rows(out: &Path) -> Vec<Value> {
    std::fs::read_to_string(out.join("results.jsonl"))
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}")))
        .collect()
}

/// A w x h grid of quads, lifted by a smooth bump that depends on `seed`, as OBJ text.
fn grid_obj(w: usize, h: usize, seed: usize) -> String {
    let mut s = String::new();
    for j in 0..=h {
        for i in 0..=w {
            let z = ((i * 7 + j * 3 + seed) % 11) as f64 / 10.0;
            s += &format!("v {i} {j} {z}\n");
        }
    }
    for j in 0..h {
        for i in 0..w {
            let a = j * (w + 1) + i + 1;
            s += &format!("f {} {} {} {}\n", a, a + 1, a + w + 2, a + w + 1);
        }
    }
    s
}

/// A w x h grid of triangles as OFF text.
fn tri_off(w: usize, h: usize, seed: usize) -> String {
    let mut v = Vec::new();
    for j in 0..=h {
        for i in 0..=w {
            v.push(format!("{i} {j} {}", ((i + 2 * j + seed) % 5) as f64 / 4.0));
        }
    }
    let mut f = Vec::new();
    for j in 0..h {
        for i in 0..w {
            let a = j * (w + 1) + i;
            f.push(format!("3 {} {} {}", a, a + 1, a + w + 2));
            f.push(format!("3 {} {} {}", a, a + w + 2, a + w + 1));
        }
    }
    format!(
        "OFF\n{} {} 0\n{}\n{}\n",
        v.len(),
        f.len(),
        v.join("\n"),
        f.join("\n")
    )
}

/// A job line.
fn job(input: &str, scheme: &str, how: (&str, usize), output: &str, options: Value) -> Value {
    let mut j = json!({"input": input, "scheme": scheme, how.0: how.1, "output": output});
    if options != json!({}) {
        j["options"] = options;
    }
    j
}

/// The manifest: good jobs (with the words of the single-file command) and bad jobs (with a
/// part of the message their error row must have).
struct Manifest {
    good: Vec<(Value, Vec<String>)>,
    bad: Vec<(Value, String)>,
}

fn make_inputs(dir: &Path) -> Manifest {
    let nets = dir.join("nets");
    std::fs::create_dir_all(&nets).unwrap();
    let mut good = Vec::new();
    let mut add =
        |j: Value, words: &[&str]| good.push((j, words.iter().map(|w| w.to_string()).collect()));
    let gallery = [
        "cube",
        "tetrahedron",
        "octahedron",
        "torus-evs",
        "prism-5",
        "cnet-3-saddle",
        "cnet-5-convex",
        "cnet-6-raised",
    ];
    for (k, g) in gallery.iter().enumerate() {
        let input = format!("gallery:{g}");
        for (scheme, ext) in [
            ("catmull-clark", "obj"),
            ("doo-sabin", "off"),
            ("pgs", "ply"),
        ] {
            let out = format!("gallery/{g}-{scheme}.{ext}");
            add(
                job(&input, scheme, ("levels", 2), &out, json!({})),
                &[&input, "--scheme", scheme, "--levels", "2"],
            );
        }
        let out = format!("gallery/{g}-cc.bv");
        add(
            job(&input, "catmull-clark", ("rings", 3), &out, json!({})),
            &[&input, "--scheme", "catmull-clark", "--rings", "3"],
        );
        if k >= 5 {
            let out = format!("gallery/{g}-eg.igs");
            add(
                job(&input, "eg", ("rings", 2), &out, json!({})),
                &[&input, "--scheme", "eg", "--rings", "2"],
            );
        }
    }
    for seed in 0..120 {
        let (w, h) = (2 + seed % 4, 2 + seed % 3);
        let name = format!("grid{seed}.obj");
        std::fs::write(nets.join(&name), grid_obj(w, h, seed)).unwrap();
        let input = format!("nets/{name}");
        let path = dir.join(&input);
        let p = path.to_str().unwrap();
        match seed % 4 {
            0 => add(
                job(
                    &input,
                    "catmull-clark",
                    ("levels", 2),
                    &format!("grids/{seed}.obj"),
                    json!({}),
                ),
                &[p, "--scheme", "catmull-clark", "--levels", "2"],
            ),
            1 => add(
                job(
                    &input,
                    "catmull-clark",
                    ("levels", 1),
                    &format!("grids/{seed}.ply"),
                    json!({"boundary": "edge-only", "limit": true, "format": "ply-ascii"}),
                ),
                &[
                    p,
                    "--scheme",
                    "catmull-clark",
                    "--levels",
                    "1",
                    "--boundary",
                    "edge-only",
                    "--limit",
                    "--format",
                    "ply-ascii",
                ],
            ),
            2 => add(
                job(
                    &input,
                    "doo-sabin",
                    ("levels", 2),
                    &format!("grids/{seed}.off"),
                    json!({}),
                ),
                &[p, "--scheme", "doo-sabin", "--levels", "2"],
            ),
            _ => add(
                job(
                    &input,
                    "catmull-clark",
                    ("rings", 2),
                    &format!("grids/{seed}.obj"),
                    json!({"tess": 3}),
                ),
                &[
                    p,
                    "--scheme",
                    "catmull-clark",
                    "--rings",
                    "2",
                    "--tess",
                    "3",
                ],
            ),
        }
    }
    for seed in 0..60 {
        let name = format!("tri{seed}.off");
        std::fs::write(nets.join(&name), tri_off(2 + seed % 3, 2 + seed % 2, seed)).unwrap();
        let input = format!("nets/{name}");
        let p = dir.join(&input).to_str().unwrap().to_string();
        add(
            job(
                &input,
                "loop",
                ("levels", 1 + seed % 2),
                &format!("tris/{seed}.obj"),
                json!({}),
            ),
            &[
                &p,
                "--scheme",
                "loop",
                "--levels",
                &(1 + seed % 2).to_string(),
            ],
        );
    }
    let mut bad = Vec::new();
    let mut add_bad =
        |name: &str, text: &[u8], scheme: &str, how: (&str, usize), expect: String| {
            std::fs::write(nets.join(name), text).unwrap();
            let out = format!("bad/{name}.obj");
            bad.push((
                job(&format!("nets/{name}"), scheme, how, &out, json!({})),
                expect,
            ));
        };
    for k in 0..10 {
        let name = format!("corrupt{k}.obj");
        add_bad(
            &name,
            format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 {}\n", 9 + k).as_bytes(),
            "catmull-clark",
            ("levels", 1),
            format!("{name}:4: face refers to vertex {}", 9 + k),
        );
        let name = format!("garbage{k}.obj");
        add_bad(
            &name,
            format!("v 0 0 zero{k}\n").as_bytes(),
            "catmull-clark",
            ("levels", 1),
            format!("{name}:1"),
        );
        let name = format!("huge{k}.off");
        add_bad(
            &name,
            format!("OFF\n{}000000000 1 0\n0 0 0\n", k + 1).as_bytes(),
            "catmull-clark",
            ("levels", 1),
            name.clone(),
        );
        let name = format!("quads{k}.obj");
        add_bad(
            &name,
            grid_obj(2, 2, k).as_bytes(),
            "loop",
            ("levels", 1),
            "needs a triangle net".into(),
        );
        let name = format!("deep{k}.obj");
        add_bad(
            &name,
            grid_obj(3, 3, k).as_bytes(),
            "catmull-clark",
            ("levels", 13 + k % 3),
            "too large".into(),
        );
    }
    let cube = "gallery:cube";
    let cc = "catmull-clark";
    for (input, scheme, output, options, expect) in [
        (
            "nets/no-such-file.obj",
            cc,
            "bad/missing.obj",
            json!({}),
            "no-such-file.obj",
        ),
        (
            cube,
            "no-such-scheme",
            "bad/unknown.obj",
            json!({}),
            "unknown scheme 'no-such-scheme'",
        ),
        (
            cube,
            cc,
            "../outside.obj",
            json!({}),
            "must be a file path relative to --out",
        ),
        (
            cube,
            cc,
            "bad/option.obj",
            json!({"no-such-option": 1}),
            "--no-such-option",
        ),
    ] {
        bad.push((
            job(input, scheme, ("levels", 1), output, options),
            expect.into(),
        ));
    }
    Manifest { good, bad }
}

/// Writes the manifest (good and bad jobs interleaved, and one line that is not JSON) and
/// returns its path.
fn write_manifest(dir: &Path, m: &Manifest) -> PathBuf {
    let mut lines: Vec<String> = m.good.iter().map(|(j, _)| j.to_string()).collect();
    for (k, (j, _)) in m.bad.iter().enumerate() {
        lines.insert((k * 7) % lines.len(), j.to_string());
    }
    lines.push("{\"input\": \"gallery:cube\", this is not JSON".into());
    let path = dir.join("manifest.jsonl");
    std::fs::write(&path, lines.join("\n") + "\n").unwrap();
    path
}

/// Every file under `dir` (relative names), except the lock and the results.
fn files(dir: &Path) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap().flatten() {
            if e.file_type().unwrap().is_dir() {
                stack.push(e.path());
            } else {
                let rel = e
                    .path()
                    .strip_prefix(dir)
                    .unwrap()
                    .to_string_lossy()
                    .into_owned();
                if rel != "results.jsonl" && rel != ".fairsub-batch.lock" {
                    out.insert(rel);
                }
            }
        }
    }
    out
}

/// The rows of one run (the rows after the first `skip`), by output.
fn by_output(rows: &[Value], skip: usize) -> BTreeMap<String, Value> {
    rows[skip..]
        .iter()
        .filter_map(|r| Some((r["output"].as_str()?.to_string(), r.clone())))
        .collect()
}

#[test]
fn a_few_hundred_jobs_with_bad_ones_resume_and_equal_the_single_file_command() {
    let dir = scratch("main");
    let m = make_inputs(&dir);
    assert!(
        m.good.len() >= 200 && m.bad.len() >= 50,
        "{} good, {} bad",
        m.good.len(),
        m.bad.len()
    );
    let manifest = write_manifest(&dir, &m);
    let out = dir.join("out");
    let (ok, err) = run_batch(&manifest, &out);
    assert!(!ok, "failed jobs make the exit code non-zero");
    assert!(
        err.contains(&format!(
            "{} of {} jobs failed",
            m.bad.len() + 1,
            m.good.len() + m.bad.len() + 1
        )),
        "{err}"
    );
    let first = rows(&out);
    assert_eq!(
        first.len(),
        m.good.len() + m.bad.len() + 1,
        "one row per job"
    );
    let run1 = by_output(&first, 0);
    // good jobs: ok, and the same bytes as the single-file command
    let reference = dir.join("reference");
    for (j, words) in &m.good {
        let o = j["output"].as_str().unwrap();
        let row = &run1[o];
        assert_eq!(row["status"], "ok", "{row}");
        let r = reference.join(o);
        std::fs::create_dir_all(r.parent().unwrap()).unwrap();
        let mut args = vec!["subdivide".to_string()];
        args.extend(words.iter().cloned());
        args.extend(["-o".into(), r.to_str().unwrap().into()]);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let (ok, err) = fairsub(&args);
        assert!(ok, "{args:?}: {err}");
        let (a, b) = (
            std::fs::read(out.join(o)).unwrap(),
            std::fs::read(&r).unwrap(),
        );
        assert!(a == b, "{o} differs from `fairsub {}`", args.join(" "));
        let listed = &row["outputs"][0];
        assert_eq!(listed["bytes"], a.len() as u64);
        assert_eq!(listed["sha256"].as_str().unwrap().len(), 64);
    }
    // bad jobs: an error row naming the problem, no output
    for (j, expect) in &m.bad {
        let o = j["output"].as_str().unwrap();
        let row = &run1[o];
        assert_eq!(row["status"], "error", "{row}");
        let msg = row["error"].as_str().unwrap();
        assert!(
            msg.contains(expect.as_str()),
            "{o}: '{msg}' does not say '{expect}'"
        );
        assert!(!out.join(o).exists() && !dir.join("outside.obj").exists());
    }
    let not_json: Vec<&Value> = first.iter().filter(|r| r["input"].is_null()).collect();
    assert_eq!(not_json.len(), 1);
    assert!(
        not_json[0]["error"]
            .as_str()
            .unwrap()
            .contains("manifest.jsonl line")
    );
    // nothing half-written: exactly the good outputs, no temporary files
    let expected: BTreeSet<String> = m
        .good
        .iter()
        .map(|(j, _)| j["output"].as_str().unwrap().to_string())
        .collect();
    assert_eq!(files(&out), expected);

    // the second run does no work: every good job skipped, its file untouched
    let stamp = |o: &str| std::fs::metadata(out.join(o)).unwrap().modified().unwrap();
    let before: Vec<_> = expected.iter().map(|o| stamp(o)).collect();
    run_batch(&manifest, &out);
    let second = rows(&out);
    let run2 = by_output(&second, first.len());
    assert_eq!(second.len(), 2 * first.len());
    for o in &expected {
        assert_eq!(run2[o]["status"], "skipped", "{}", run2[o]);
        assert_eq!(run2[o]["outputs"], run1[o]["outputs"]);
    }
    assert_eq!(
        before,
        expected.iter().map(|o| stamp(o)).collect::<Vec<_>>()
    );
    // failed jobs are tried again (and fail again)
    assert!(
        m.bad
            .iter()
            .all(|(j, _)| run2[j["output"].as_str().unwrap()]["status"] == "error")
    );

    // delete one output, change another's bytes, corrupt a third's row of the first run
    let names: Vec<&String> = expected.iter().collect();
    let (deleted, changed, corrupted) = (names[3].clone(), names[40].clone(), names[100].clone());
    std::fs::remove_file(out.join(&deleted)).unwrap();
    let mut bytes = std::fs::read(out.join(&changed)).unwrap();
    let mid = bytes.len() / 2;
    bytes[mid] ^= 1;
    std::fs::write(out.join(&changed), bytes).unwrap();
    let text = std::fs::read_to_string(out.join("results.jsonl")).unwrap();
    let needle = format!("\"output\":\"{corrupted}\",\"status\":\"ok\"");
    let at = text.find(&needle).unwrap();
    let text = format!("{}{}", &text[..at], &text[at + 12..]);
    std::fs::write(out.join("results.jsonl"), text).unwrap();
    let (_, err) = run_batch(&manifest, &out);
    assert!(err.contains("are not result rows"), "{err}");
    let third = rows_tolerant(&out);
    let redone: BTreeSet<String> = third[second.len() - 1..]
        .iter()
        .filter(|r| r["status"] == "ok")
        .map(|r| r["output"].as_str().unwrap().to_string())
        .collect();
    assert_eq!(
        redone,
        BTreeSet::from([deleted.clone(), changed.clone(), corrupted.clone()])
    );
    for o in [&deleted, &changed] {
        let r = reference.join(o);
        assert_eq!(
            std::fs::read(out.join(o)).unwrap(),
            std::fs::read(r).unwrap()
        );
    }
    assert_eq!(files(&out), expected);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The rows, skipping lines that are not JSON (the corrupted one).
fn rows_tolerant(out: &Path) -> Vec<Value> {
    std::fs::read_to_string(out.join("results.jsonl"))
        .unwrap()
        .lines()
        .filter_map(|l| serde_json::from_str(l).ok())
        .collect()
}

#[test]
fn csv_manifests_defaults_duplicates_and_the_time_limit() {
    let dir = scratch("csv");
    std::fs::create_dir_all(dir.join("nets")).unwrap();
    std::fs::write(dir.join("nets/g.obj"), grid_obj(3, 2, 1)).unwrap();
    // the same jobs as JSON Lines (with a defaults line) and as CSV
    let jsonl = [
        json!({"defaults": {"scheme": "catmull-clark", "options": {"boundary": "edge-only"}}}),
        json!({"input": "nets/g.obj", "levels": 2, "output": "a.obj"}),
        json!({"input": "gallery:cnet-5-saddle", "scheme": "eg", "rings": 3, "output": "b.bv", "measure": true, "options": {"boundary": null}}),
        json!({"input": "gallery:cube", "levels": 1, "output": "a.obj"}),
    ];
    let lines: Vec<String> = jsonl.iter().map(Value::to_string).collect();
    std::fs::write(dir.join("m.jsonl"), lines.join("\n")).unwrap();
    let csv = "input,scheme,levels,rings,output,options,measure\n\
               nets/g.obj,catmull-clark,2,,a.obj,\"{\"\"boundary\"\": \"\"edge-only\"\"}\",\n\
               gallery:cnet-5-saddle,eg,,3,b.bv,,true\n\
               gallery:cube,catmull-clark,1,,a.obj,,\n";
    std::fs::write(dir.join("m.csv"), csv).unwrap();
    for m in ["m.jsonl", "m.csv"] {
        let out = dir.join(format!("out-{m}"));
        let (ok, err) = fairsub(&[
            "batch",
            dir.join(m).to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(!ok, "{err}");
        let rs = rows(&out);
        assert_eq!(rs.len(), 3, "{rs:?}");
        let errors: Vec<&Value> = rs.iter().filter(|r| r["status"] == "error").collect();
        assert_eq!(errors.len(), 1, "{errors:?}");
        let dup = errors[0];
        assert!(
            dup["error"]
                .as_str()
                .unwrap()
                .contains("'a.obj' is written by line"),
            "{dup}"
        );
        let measured = rs.iter().find(|r| r["output"] == "b.bv").unwrap();
        let m = &measured["metrics"];
        assert_eq!(
            m["check"]["continuity"]["patches"],
            measured["counts"]["patches"]
        );
        assert!(
            m["check"]["continuity"]["all"]["c0"].as_f64().unwrap() < 1e-9,
            "{m}"
        );
        assert!(
            m["curvature"]["gauss"][0].as_f64().unwrap()
                <= m["curvature"]["gauss"][1].as_f64().unwrap()
        );
    }
    let (a, b) = (dir.join("out-m.jsonl"), dir.join("out-m.csv"));
    for f in ["a.obj", "b.bv"] {
        assert_eq!(
            std::fs::read(a.join(f)).unwrap(),
            std::fs::read(b.join(f)).unwrap(),
            "{f}"
        );
    }
    let r = dir.join("ref.obj");
    fairsub(&[
        "subdivide",
        dir.join("nets/g.obj").to_str().unwrap(),
        "--scheme",
        "catmull-clark",
        "--levels",
        "2",
        "--boundary",
        "edge-only",
        "-o",
        r.to_str().unwrap(),
    ]);
    assert_eq!(
        std::fs::read(a.join("a.obj")).unwrap(),
        std::fs::read(r).unwrap()
    );
    // a job over the time limit is stopped: an error row, no file, the next job still runs
    let slow = [
        json!({"input": "gallery:torus-evs", "scheme": "catmull-clark", "levels": 9, "output": "slow.ply"}),
        json!({"input": "gallery:cube", "scheme": "catmull-clark", "levels": 1, "output": "fast.obj"}),
    ];
    let lines: Vec<String> = slow.iter().map(Value::to_string).collect();
    std::fs::write(dir.join("slow.jsonl"), lines.join("\n")).unwrap();
    let out = dir.join("out-slow");
    let (_, err) = fairsub(&[
        "batch",
        dir.join("slow.jsonl").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--jobs",
        "1",
        "--timeout",
        "0.2",
        "--max-memory",
        "8G",
    ]);
    let rs = rows(&out);
    let slow = rs.iter().find(|r| r["output"] == "slow.ply").unwrap();
    assert!(
        slow["error"]
            .as_str()
            .unwrap()
            .contains("time limit of 0.2 s"),
        "{slow} {err}"
    );
    assert!(
        rs.iter()
            .any(|r| r["output"] == "fast.obj" && r["status"] == "ok")
    );
    assert_eq!(files(&out), BTreeSet::from(["fast.obj".to_string()]));
    std::fs::remove_dir_all(&dir).unwrap();
}
