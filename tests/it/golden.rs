//! Golden outputs: every command's output for every scheme on representative gallery nets,
//! recorded once and compared on every run, so a refactoring that must not change results
//! (issue 14) is checked byte by byte, or number by number to 1e-14 where only the float
//! summation order may differ.
//!
//! The cases are in [`cases`]; the recorded outputs are in `tests/golden/` (one folder per case:
//! `exit`, `stdout`, `stderr` and the files the command wrote). To record them again after an
//! intended change of results, run
//!
//! ```sh
//! FAIRSUB_BLESS=1 cargo test --release --test it golden::
//! ```
//!
//! and commit the changed files with a message that says which results changed and why.
//!
//! Comparison: text outputs token by token, numbers equal to a relative 1e-14 of the largest
//! magnitude in the file (so a changed summation order passes, a changed rule does not), other
//! tokens exactly; binary outputs (PNG, binary PLY) byte for byte. Files over [`BIG`] bytes are
//! recorded as a digest (`NAME.digest`: token count and a hash of the tokens with numbers
//! rounded to 12 significant digits; binary files: a hash of the bytes), to keep the repository
//! small.

use rayon::prelude::*;
use std::path::{Path, PathBuf};
use std::process::Command;

/// One recorded command: its folder name and its arguments (`{out}` is the output folder).
struct Case {
    name: String,
    args: Vec<String>,
}

fn case(name: &str, args: &[&str]) -> Case {
    Case {
        name: name.to_string(),
        args: args.iter().map(|s| s.to_string()).collect(),
    }
}

/// The schemes with refinement and with patch output, and nets that fit them.
fn cases() -> Vec<Case> {
    let mut v = Vec::new();
    let quad_nets = ["cube", "cnet-5-saddle", "torus-evs"];
    let refine = [
        ("catmull-clark", &quad_nets[..]),
        ("doo-sabin", &["cube", "prism-5", "open-grid"][..]),
        ("doo-sabin-cc", &["cube", "prism-5"][..]),
        ("loop", &["octahedron", "icosahedron", "tri-grid"][..]),
        ("nonbox", &["nonbox-cube-fcv-1", "cnet-5-convex"][..]),
        ("nonbox-4dir", &["nonbox-cube-fcv-1"][..]),
        ("pgs", &["cube", "prism-5", "open-grid"][..]),
        ("pgs-dscc", &["prism-5"][..]),
        ("polar-bi2", &["prism-5"][..]),
        ("tps", &["cube", "cnet-5-saddle"][..]),
        ("tps-adjustable", &["cube", "cnet-3-convex"][..]),
        ("bi2-mixed", &["cube"][..]),
    ];
    for (s, nets) in refine {
        for n in nets {
            v.push(case(
                &format!("levels-{s}-{n}"),
                &[
                    "subdivide",
                    &format!("gallery:{n}"),
                    "--scheme",
                    s,
                    "--levels",
                    "2",
                    "-o",
                    "{out}/net.obj",
                ],
            ));
        }
    }
    v.push(case(
        "levels-limit-catmull-clark-cube",
        &[
            "subdivide",
            "gallery:cube",
            "--scheme",
            "catmull-clark",
            "--levels",
            "1",
            "--limit",
            "-o",
            "{out}/net.obj",
        ],
    ));
    let rings = [
        ("catmull-clark", &["cube", "cnet-5-saddle", "open-grid"][..]),
        ("doo-sabin", &["cube", "prism-5"][..]),
        ("doo-sabin-cc", &["prism-5"][..]),
        ("loop", &["octahedron", "tri-grid"][..]),
        ("nonbox", &["nonbox-cube-fcv-1", "cnet-5-convex"][..]),
        ("nonbox-4dir", &["nonbox-cube-fcv-1"][..]),
        ("eg", &["cube", "cnet-5-saddle", "cnet-6-convex"][..]),
        ("qas-plus", &["cnet-5-saddle", "cnet-7-convex", "cube"][..]),
        ("qas-plus-bi3", &["cnet-5-saddle"][..]),
        ("qas-0.4", &["cnet-6-saddle"][..]),
        ("qas-0.5-0.4", &["cnet-5-convex"][..]),
        ("pgs", &["cube", "prism-5"][..]),
        ("pgs-dscc", &["prism-3"][..]),
        ("polar-bi2", &["prism-5"][..]),
        ("tps", &["cube", "cnet-5-saddle"][..]),
        ("tps-adjustable", &["cnet-3-convex"][..]),
        ("bi2-mixed", &["prism-5"][..]),
        ("guided-bi5", &["cnet-5-saddle", "cnet-3-convex"][..]),
        ("guided-bi6", &["cnet-5-convex"][..]),
        ("guided-bi4-macro", &["cnet-5-saddle"][..]),
        ("guided-bi3-macro", &["cnet-6-convex"][..]),
    ];
    for (s, nets) in rings {
        for n in nets {
            v.push(case(
                &format!("rings-{s}-{n}"),
                &[
                    "subdivide",
                    &format!("gallery:{n}"),
                    "--scheme",
                    s,
                    "--rings",
                    "2",
                    "-o",
                    "{out}/surface.bv",
                ],
            ));
        }
        v.push(case(
            &format!("check-{s}-{}", nets[0]),
            &[
                "check",
                &format!("gallery:{}", nets[0]),
                "--scheme",
                s,
                "--rings",
                "3",
                "--json",
            ],
        ));
    }
    v.push(case(
        "rings-igs-catmull-clark-cube",
        &[
            "subdivide",
            "gallery:cube",
            "--scheme",
            "catmull-clark",
            "--rings",
            "2",
            "--faces",
            "patches",
            "-o",
            "{out}/surface.igs",
        ],
    ));
    v.push(case(
        "rings-ply-eg-cnet-5-convex",
        &[
            "subdivide",
            "gallery:cnet-5-convex",
            "--scheme",
            "eg",
            "--rings",
            "2",
            "--tess",
            "4",
            "-o",
            "{out}/surface.ply",
        ],
    ));
    v.push(case(
        "rings-nofill-qas-plus-cnet-5-convex",
        &[
            "subdivide",
            "gallery:cnet-5-convex",
            "--scheme",
            "qas-plus",
            "--rings",
            "2",
            "--no-fill",
            "-o",
            "{out}/surface.bv",
        ],
    ));
    let analyzed = [
        "catmull-clark",
        "doo-sabin",
        "loop",
        "nonbox",
        "nonbox-4dir",
        "eg",
        "qas-plus",
        "qas-plus-bi3",
        "pgs",
        "polar-bi2",
        "tps",
        "tps-adjustable",
        "guided-bi5",
        "guided-bi6",
    ];
    for s in analyzed {
        for n in ["3", "5", "6"] {
            v.push(case(
                &format!("analyze-{s}-{n}"),
                &["analyze", "--scheme", s, "--valence", n, "--json"],
            ));
        }
    }
    v.push(case(
        "analyze-text-eg-5",
        &["analyze", "--scheme", "eg", "--valence", "5"],
    ));
    v.push(case(
        "analyze-text-qas-plus-6",
        &["analyze", "--scheme", "qas-plus", "--valence", "6"],
    ));
    for s in ["catmull-clark", "eg", "pgs", "guided-bi5", "nonbox"] {
        v.push(case(
            &format!("charmap-{s}-5"),
            &[
                "charmap",
                "--scheme",
                s,
                "--valence",
                "5",
                "-o",
                "{out}/chi.bv",
                "--json",
            ],
        ));
    }
    for n in ["cube", "torus-evs", "prism-5", "open-grid"] {
        v.push(case(
            &format!("info-{n}"),
            &["info", &format!("gallery:{n}"), "--json"],
        ));
    }
    v.push(case("schemes", &["schemes"]));
    v.push(case("schemes-json", &["schemes", "--json"]));
    v.push(case(
        "render-highlight-eg",
        &[
            "render",
            "gallery:cnet-5-saddle",
            "--scheme",
            "eg",
            "--rings",
            "3",
            "--mode",
            "highlight",
            "--size",
            "96x96",
            "--json",
            "-o",
            "{out}/r.png",
        ],
    ));
    v.push(case(
        "render-mean-cc",
        &[
            "render",
            "gallery:cnet-5-saddle",
            "--scheme",
            "catmull-clark",
            "--rings",
            "3",
            "--mode",
            "mean",
            "--size",
            "96x96",
            "-o",
            "{out}/r.png",
        ],
    ));
    v.push(case("demo", &["demo", "--out", "{out}/demo"]));
    // Errors are outputs too: the message and the exit code.
    v.push(case(
        "error-eg-levels",
        &[
            "subdivide",
            "gallery:cube",
            "--scheme",
            "eg",
            "--levels",
            "1",
            "-o",
            "{out}/x.obj",
        ],
    ));
    v.push(case(
        "error-unknown-scheme",
        &[
            "subdivide",
            "gallery:cube",
            "--scheme",
            "nope",
            "--levels",
            "1",
            "-o",
            "{out}/x.obj",
        ],
    ));
    v.push(case(
        "error-loop-quads",
        &[
            "subdivide",
            "gallery:cube",
            "--scheme",
            "loop",
            "--levels",
            "1",
            "-o",
            "{out}/x.obj",
        ],
    ));
    v.push(case(
        "error-eg-fallback",
        &[
            "subdivide",
            // The gallery's c-nets stop at 10, where EG has derived rules; no construction
            // covers 17 (gallery::cnet(17, Convex, 3) written as OBJ).
            "tests/data/cnet-17-convex.obj",
            "--scheme",
            "eg",
            "--rings",
            "2",
            "--fallback",
            "error",
            "-o",
            "{out}/x.bv",
        ],
    ));
    v
}

/// Files larger than this are recorded as digests.
const BIG: usize = 96 * 1024;

/// FNV-1a, 64 bit: a hash that stays the same across Rust versions.
fn fnv(bytes: impl IntoIterator<Item = u8>) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= b as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h
}

/// The digest of a file's content (see the module documentation).
fn digest(p: &Path, bytes: &[u8]) -> String {
    if is_binary(p, bytes) {
        return format!(
            "bytes {}\nhash {:016x}\n",
            bytes.len(),
            fnv(bytes.iter().copied())
        );
    }
    let text = String::from_utf8_lossy(bytes);
    let ts = tokens(&text);
    let mut h = Vec::new();
    for t in &ts {
        match t.parse::<f64>() {
            // -0 and 0 round alike; tiny values (below 1e-13 of typical coordinates) count as 0.
            Ok(x) if x.is_finite() => {
                let x = if x.abs() < 1e-13 { 0.0 } else { x };
                h.extend(format!("{x:.11e} ").bytes())
            }
            _ => h.extend(format!("{t} ").bytes()),
        }
    }
    format!("tokens {}\nhash {:016x}\n", ts.len(), fnv(h))
}

fn golden_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

/// Runs a case into `dir` (emptied first); the command's files are written under `dir/files`.
fn run_case(c: &Case, dir: &Path) {
    let _ = std::fs::remove_dir_all(dir);
    let files = dir.join("files");
    std::fs::create_dir_all(&files).unwrap();
    let out = files.to_str().unwrap();
    let args: Vec<String> = c.args.iter().map(|a| a.replace("{out}", out)).collect();
    let o = Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .args(&args)
        .env("RAYON_NUM_THREADS", "1")
        .output()
        .unwrap();
    let code = o.status.code().unwrap_or(-1);
    // Paths in messages name the scratch folder: make them relative.
    let clean = |b: &[u8]| String::from_utf8_lossy(b).replace(out, "{out}");
    std::fs::write(dir.join("exit"), format!("{code}\n")).unwrap();
    for f in list(&files) {
        if f.extension().is_some_and(|e| e == "igs") {
            let p = files.join(f);
            let text = std::fs::read_to_string(&p).unwrap();
            std::fs::write(&p, without_timestamps(&text)).unwrap();
        }
    }
    std::fs::write(dir.join("stdout"), clean(&o.stdout)).unwrap();
    std::fs::write(dir.join("stderr"), clean(&o.stderr)).unwrap();
}

/// An IGES file with its time stamps (`15HYYYYMMDD.HHMMSS` in the global section) zeroed, the
/// record layout kept.
fn without_timestamps(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(i) = rest.find("15H") {
        let (head, tail) = rest.split_at(i + 3);
        out.push_str(head);
        let stamp = tail.get(..15).unwrap_or("");
        let is_stamp = stamp.len() == 15
            && stamp
                .char_indices()
                .all(|(k, c)| if k == 8 { c == '.' } else { c.is_ascii_digit() });
        if is_stamp {
            out.push_str("00000000.000000");
            rest = &tail[15..];
        } else {
            rest = tail;
        }
    }
    out.push_str(rest);
    out
}

/// All files under `dir`, relative, sorted.
fn list(dir: &Path) -> Vec<PathBuf> {
    let mut v = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                v.push(p.strip_prefix(dir).unwrap().to_path_buf());
            }
        }
    }
    v.sort();
    v
}

fn is_binary(p: &Path, bytes: &[u8]) -> bool {
    p.extension().is_some_and(|e| e == "png") || std::str::from_utf8(bytes).is_err()
}

/// Tokens of a text: numbers and everything else, split at whitespace and the JSON / OBJ
/// punctuation that can touch a number.
fn tokens(s: &str) -> Vec<&str> {
    s.split(|c: char| c.is_whitespace() || ",[]{}:/\"".contains(c))
        .filter(|t| !t.is_empty())
        .collect()
}

/// Compares two texts; `Err` names the first difference.
fn compare_text(a: &str, b: &str) -> Result<(), String> {
    let (ta, tb) = (tokens(a), tokens(b));
    if ta.len() != tb.len() {
        return Err(format!("{} tokens recorded, {} now", ta.len(), tb.len()));
    }
    let scale = ta
        .iter()
        .filter_map(|t| t.parse::<f64>().ok())
        .filter(|x| x.is_finite())
        .fold(1.0f64, |m, x| m.max(x.abs()));
    for (i, (x, y)) in ta.iter().zip(&tb).enumerate() {
        if x == y {
            continue;
        }
        match (x.parse::<f64>(), y.parse::<f64>()) {
            (Ok(p), Ok(q)) if (p - q).abs() <= 1e-14 * scale => {}
            _ => return Err(format!("token {i}: recorded '{x}', now '{y}'")),
        }
    }
    Ok(())
}

#[test]
fn outputs_match_the_recorded_ones() {
    let bless = std::env::var_os("FAIRSUB_BLESS").is_some();
    let root = golden_root();
    let scratch = std::env::temp_dir().join(format!("fairsub-golden-{}", std::process::id()));
    let cs = cases();
    let mut names: Vec<&str> = cs.iter().map(|c| c.name.as_str()).collect();
    names.sort();
    names.dedup();
    assert_eq!(names.len(), cs.len(), "case names are unique");
    // the cases run in parallel (each is one or a few runs of the command line); the failures
    // are reported in the cases' order
    let failures: Vec<String> = cs
        .par_iter()
        .flat_map_iter(|c| check_case(c, bless, &root, &scratch))
        .collect();
    let _ = std::fs::remove_dir_all(&scratch);
    if bless {
        // Drop folders of cases that no longer exist.
        for e in std::fs::read_dir(&root).unwrap() {
            let p = e.unwrap().path();
            let n = p.file_name().unwrap().to_string_lossy().to_string();
            if !names.contains(&n.as_str()) {
                std::fs::remove_dir_all(p).unwrap();
            }
        }
        return;
    }
    assert!(
        failures.is_empty(),
        "{} of {} golden cases differ (FAIRSUB_BLESS=1 records new ones):\n{}",
        failures.len(),
        cs.len(),
        failures.join("\n")
    );
}

/// Runs one case into `scratch` and compares its files with the recorded ones under `root`
/// (or, with `bless`, records them): the differences found, each a line.
fn check_case(c: &Case, bless: bool, root: &Path, scratch: &Path) -> Vec<String> {
    let mut failures = Vec::new();
    if bless {
        let dir = root.join(&c.name);
        run_case(c, &dir);
        for f in list(&dir) {
            let p = dir.join(&f);
            let bytes = std::fs::read(&p).unwrap();
            if bytes.len() > BIG {
                let mut d = p.clone().into_os_string();
                d.push(".digest");
                std::fs::write(d, digest(&f, &bytes)).unwrap();
                std::fs::remove_file(p).unwrap();
            }
        }
        return Vec::new();
    }
    let now = scratch.join(&c.name);
    run_case(c, &now);
    let rec = root.join(&c.name);
    let lr = list(&rec);
    let ln: Vec<PathBuf> = list(&now)
        .into_iter()
        .map(|f| {
            let mut d = f.clone().into_os_string();
            d.push(".digest");
            let d = PathBuf::from(d);
            if lr.contains(&d) { d } else { f }
        })
        .collect();
    if lr != ln {
        return vec![format!("{}: files recorded {lr:?}, now {ln:?}", c.name)];
    }
    for f in lr {
        if f.extension().is_some_and(|e| e == "digest") {
            let orig = f.with_extension("");
            let recorded = std::fs::read_to_string(rec.join(&f)).unwrap();
            let d = digest(&orig, &std::fs::read(now.join(&orig)).unwrap());
            if recorded != d {
                failures.push(format!(
                    "{} {}: digest recorded {recorded:?}, now {d:?}",
                    c.name,
                    orig.display()
                ));
            }
            continue;
        }
        let (a, b) = (
            std::fs::read(rec.join(&f)).unwrap(),
            std::fs::read(now.join(&f)).unwrap(),
        );
        if a == b {
            continue;
        }
        let r = if is_binary(&f, &a) {
            Err("binary files differ".to_string())
        } else {
            compare_text(&String::from_utf8_lossy(&a), &String::from_utf8_lossy(&b))
        };
        if let Err(e) = r {
            failures.push(format!("{} {}: {e}", c.name, f.display()));
        }
    }
    failures
}
