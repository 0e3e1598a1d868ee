//! Issue 20's hostile-input cases through the `fairsub` command line, each with its expected
//! message: outputs are valid or not written, jobs over the memory budget are refused up front,
//! side files are checked against the net, readers share one text rule, and a k-gon ten times
//! larger costs at most fifteen times the time (no quadratic face walk).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("fairsub-harden-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run(args: &[&str]) -> (i32, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .args(args)
        .output()
        .unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// Runs a command that must be refused with exit code 1, a message containing `expect` and
/// no output file at `out`.
fn refused(args: &[&str], expect: &str, out: &Path) {
    let (code, err) = run(args);
    assert_eq!(code, 1, "{args:?}: {err}");
    assert!(
        err.contains(expect),
        "{args:?}: expected {expect:?} in {err}"
    );
    assert!(!out.exists(), "{args:?} left {}", out.display());
}

#[test]
fn huge_fcvs_give_an_error_not_an_empty_mesh() {
    let d = scratch("fcv");
    let fcv = d.join("f.fcv");
    std::fs::write(&fcv, "1e100 0 0\n*\n*\n*\n*\n*\n").unwrap();
    let out = d.join("out.obj");
    refused(
        &[
            "subdivide",
            "gallery:cube",
            "--scheme",
            "nonbox",
            "--fcv-file",
            fcv.to_str().unwrap(),
            "--rings",
            "2",
            "-o",
            out.to_str().unwrap(),
        ],
        "invalid output: ",
        &out,
    );
}

#[test]
fn jobs_over_the_budget_are_refused_with_the_estimate_and_the_option() {
    let d = scratch("limits");
    let obj = d.join("out.obj");
    let o = obj.to_str().unwrap();
    refused(
        &[
            "subdivide",
            "gallery:cube",
            "--scheme",
            "catmull-clark",
            "--levels",
            "30",
            "-o",
            o,
        ],
        "too large: 30 refinement step(s) of catmull-clark",
        &obj,
    );
    refused(
        &[
            "--max-memory",
            "64M",
            "subdivide",
            "gallery:cube",
            "--scheme",
            "catmull-clark",
            "--levels",
            "12",
            "-o",
            o,
        ],
        "lower --levels (--levels ",
        &obj,
    );
    refused(
        &[
            "--max-memory",
            "256M",
            "subdivide",
            "gallery:cube",
            "--scheme",
            "catmull-clark",
            "--rings",
            "2",
            "--tess",
            "1000",
            "-o",
            o,
        ],
        "a tessellation of ",
        &obj,
    );
    let png = d.join("out.png");
    refused(
        &[
            "render",
            "gallery:cube",
            "--size",
            "8192x8192",
            "-o",
            png.to_str().unwrap(),
        ],
        "8192x8192 pixels with 2x2 samples each is 268435456 samples",
        &png,
    );
    refused(
        &[
            "--max-memory",
            "64M",
            "render",
            "gallery:cube",
            "--size",
            "4000x4000",
            "-o",
            png.to_str().unwrap(),
        ],
        "raise the budget with --max-memory SIZE",
        &png,
    );
    let (code, err) = run(&["analyze", "--scheme", "catmull-clark", "--valence", "10000"]);
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("too large: valence 10000"), "{err}");
    let (code, err) = run(&["--max-memory", "4X", "info", "gallery:cube"]);
    assert_ne!(code, 0, "{err}");
}

#[test]
fn q_file_vertices_are_checked_against_the_net() {
    let d = scratch("qfile");
    let q = d.join("e.q");
    std::fs::write(&q, "# expansions\nvertex 9999\n").unwrap();
    let out = d.join("out.bv");
    refused(
        &[
            "subdivide",
            "gallery:cube",
            "--scheme",
            "qas-plus",
            "--q-file",
            q.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ],
        "e.q:2: vertex 9999 does not exist: the net has 8 vertices",
        &out,
    );
}

#[test]
fn invalid_utf8_in_an_obj_comment_is_read_by_every_scheme() {
    let d = scratch("utf8");
    let obj = d.join("net.obj");
    let mut text = b"# caf\xe9\n".to_vec();
    text.extend_from_slice(
        b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
          f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n",
    );
    std::fs::write(&obj, text).unwrap();
    for scheme in ["catmull-clark", "nonbox"] {
        let out = d.join(format!("{scheme}.bv"));
        let (code, err) = run(&[
            "subdivide",
            obj.to_str().unwrap(),
            "--scheme",
            scheme,
            "-o",
            out.to_str().unwrap(),
        ]);
        assert_eq!(code, 0, "{scheme}: {err}");
        assert!(out.exists());
    }
}

/// One k-gon (a disc: one face) in OBJ.
fn kgon(path: &Path, k: usize) {
    use std::fmt::Write;
    let mut s = String::new();
    for i in 0..k {
        let t = i as f64 / k as f64 * std::f64::consts::TAU;
        writeln!(s, "v {} {} 0", t.cos(), t.sin()).unwrap();
    }
    s.push('f');
    for i in 1..=k {
        write!(s, " {i}").unwrap();
    }
    s.push('\n');
    std::fs::write(path, s).unwrap();
}

#[test]
fn info_on_a_kgon_scales_linearly() {
    let d = scratch("scaling");
    let time = |k: usize| {
        let p = d.join(format!("k{k}.obj"));
        kgon(&p, k);
        // best of three, against the noise of a shared machine
        (0..3)
            .map(|_| {
                let t = Instant::now();
                let (code, err) = run(&["info", p.to_str().unwrap()]);
                assert_eq!(code, 0, "{err}");
                t.elapsed().as_secs_f64()
            })
            .fold(f64::INFINITY, f64::min)
    };
    let small = time(20_000);
    let large = time(200_000);
    assert!(
        large <= 15.0 * small,
        "info on a 200k-gon took {large:.3} s, on a 20k-gon {small:.3} s"
    );
}
