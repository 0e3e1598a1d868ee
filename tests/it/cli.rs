//! The `fairsub` command line: every gallery net through every classic scheme into every output
//! format (read back), bad input with its clear error and exit code, and the demo.

use crate::common::scratch;
use rayon::prelude::*;
use std::path::Path;
use std::process::Command;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_fairsub"))
}

fn run(args: &[&str]) -> (i32, String, String) {
    let o = bin().args(args).output().unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

fn schemes_for(mesh: &fairsub::PolyMesh) -> Vec<&'static str> {
    let mut s = vec!["catmull-clark", "doo-sabin", "doo-sabin-cc", "eg"];
    if mesh.is_all_triangles() {
        s.push("loop");
    }
    s
}

#[test]
fn every_gallery_net_every_scheme_every_format() {
    let dir = scratch("gallery");
    let catalog = fairsub::schemes::catalog();
    // Keep the run short: all special nets, and the c-nets of three valences.
    let nets: Vec<_> = fairsub::gallery::all()
        .into_iter()
        .filter(|(name, _)| {
            !name.starts_with("cnet-")
                || ["cnet-3-", "cnet-5-", "cnet-10-"]
                    .iter()
                    .any(|p| name.starts_with(p))
        })
        .collect();
    // one net per task, on the machine's threads; each writes its own files
    let runs: usize = nets
        .par_iter()
        .map(|(name, mesh)| {
            let mut runs = 0;
            let net = format!("gallery:{name}");
            for scheme in schemes_for(mesh) {
                let info = catalog.iter().find(|s| s.name == scheme).unwrap();
                // `fairsub subdivide NET --scheme S ARGS -o OUT`: exit code and stderr
                let subdivide = |args: &[&str], out: &Path| {
                    let mut all = vec!["subdivide", &net, "--scheme", scheme];
                    all.extend_from_slice(args);
                    all.extend(["-o", out.to_str().unwrap()]);
                    let (code, _, err) = run(&all);
                    (code, err)
                };
                // the refined net the mesh formats must hold (once for the three of them)
                let expect = info.refine.then(|| {
                    fairsub::schemes::by_name(scheme)
                        .unwrap()
                        .refine(mesh)
                        .unwrap()
                        .mesh
                });
                // Refined nets in every mesh format (and BezierView polyhedra).
                let net_formats: &[&str] = if info.refine {
                    &["obj", "off", "ply", "bv"]
                } else {
                    &[]
                };
                for &ext in net_formats {
                    let out = dir.join(format!("{name}-{scheme}.{ext}"));
                    let (code, err) = subdivide(&["--levels", "1"], &out);
                    assert_eq!(code, 0, "{name} {scheme} {ext}: {err}");
                    runs += 1;
                    if ext == "bv" {
                        let f = fairsub::io::read_bv(&out).unwrap();
                        assert_eq!(f.polyhedra.len(), 1);
                    } else {
                        let m = fairsub::io::read_mesh(&out).unwrap().mesh;
                        let expect = expect.as_ref().expect("refined above");
                        assert_eq!(
                            (m.num_vertices(), m.num_faces()),
                            (expect.num_vertices(), expect.num_faces())
                        );
                        let worst = m
                            .positions()
                            .iter()
                            .zip(expect.positions())
                            .map(|(a, b)| fairsub::geom::dist(*a, *b))
                            .fold(0.0, f64::max);
                        assert!(
                            worst < 1e-9,
                            "{name} {scheme} {ext}: positions differ by {worst}"
                        );
                    }
                }
                if !info.rings {
                    let out = dir.join(format!("{name}-{scheme}-refused.igs"));
                    let (code, err) = subdivide(&["--rings", "2"], &out);
                    assert_eq!(code, 1, "a scheme without patch output must say so: {err}");
                    assert!(err.contains("no exact patch output"), "{err}");
                    assert!(!out.exists());
                    continue;
                }
                // Exact patches into .bv, .igs and a tessellated .ply.
                let bv = dir.join(format!("{name}-{scheme}-patches.bv"));
                let igs = dir.join(format!("{name}-{scheme}.igs"));
                let ply = dir.join(format!("{name}-{scheme}-tess.ply"));
                for out in [&bv, &igs, &ply] {
                    let (code, err) =
                        subdivide(&["--rings", "2", "--tess", "3", "--faces", "patches"], out);
                    assert_eq!(code, 0, "{name} {scheme} {}: {err}", out.display());
                    runs += 1;
                }
                let from_bv = fairsub::io::read_bv(&bv).unwrap().patches;
                let from_igs = fairsub::io::read_iges(&igs).unwrap();
                assert_eq!(from_bv.len(), from_igs.len());
                for (a, b) in from_bv.patches.iter().zip(&from_igs.patches) {
                    for (p, q) in a.cps.iter().zip(&b.cps) {
                        assert!(fairsub::geom::dist(*p, *q) < 1e-12);
                    }
                }
                let t = fairsub::io::read_mesh(&ply).unwrap().mesh;
                assert!(t.num_faces() > 0);
                // Closed nets give watertight tessellations.
                if mesh.boundary_loops().is_empty() {
                    assert!(
                        t.boundary_loops().is_empty(),
                        "{name} {scheme}: tessellation has a boundary"
                    );
                }
                {
                    let r = fairsub::analysis::continuity::check(&from_bv);
                    assert!(
                        r.all.c0 < 1e-12 * r.size.max(1.0),
                        "{name}: C0 {}",
                        r.all.c0
                    );
                    if mesh.boundary_loops().is_empty() {
                        assert_eq!(r.open_sides, 0, "{name}: cracks");
                    }
                }
            }
            runs
        })
        .sum();
    assert!(runs > 100);
    let _ = std::fs::remove_dir_all(&dir);
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

#[test]
fn bad_input_gives_clear_errors_and_exit_code_1() {
    let dir = scratch("bad");
    let out = dir.join("out.obj");
    let o = out.to_str().unwrap();
    let cases: Vec<(String, &str)> = vec![
        (
            write(&dir, "nan.obj", "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n"),
            "nan.obj:3",
        ),
        (
            write(
                &dir,
                "inf.off",
                "OFF\n3 1 0\n0 0 0\n1 0 0\ninf 1 0\n3 0 1 2\n",
            ),
            "inf.off",
        ),
        (
            write(&dir, "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
            "range.obj:4",
        ),
        (
            write(&dir, "small.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n"),
            "small.obj:4",
        ),
        (
            write(&dir, "repeat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\n"),
            "repeat.obj:4",
        ),
        (write(&dir, "empty.obj", "# nothing\n"), "empty"),
        (
            write(
                &dir,
                "orient.obj",
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 1 2 4\n",
            ),
            "orientation",
        ),
        (
            write(
                &dir,
                "nmedge.obj",
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n",
            ),
            "edge",
        ),
        (
            write(
                &dir,
                "bowtie.obj",
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nv -1 0 0\nv 0 -1 0\nf 1 2 3\nf 1 4 5\n",
            ),
            "vertex",
        ),
        (write(&dir, "garbage.obj", "v 0 0 zero\n"), "garbage.obj:1"),
        (
            write(
                &dir,
                "bad.ply",
                "ply\nformat ascii 1.0\nelement vertex 1\nend_header\n",
            ),
            "bad.ply",
        ),
        (
            dir.join("missing.obj").to_str().unwrap().to_string(),
            "missing.obj",
        ),
    ];
    // Doo-Sabin: Catmull-Clark and Loop accept non-manifold nets and repeated vertices as
    // OpenSubdiv does (tests/it/osd_peer.rs); the other schemes refuse them.
    for (input, needle) in cases {
        let (code, _, err) = run(&[
            "subdivide",
            &input,
            "--scheme",
            "doo-sabin",
            "--levels",
            "1",
            "-o",
            o,
        ]);
        assert_eq!(code, 1, "{input}: {err}");
        assert!(
            err.to_lowercase().contains(&needle.to_lowercase()),
            "{input}: message '{err}' lacks '{needle}'"
        );
        assert!(!out.exists(), "{input}: output written despite the error");
        // `info` reads what Catmull-Clark and Loop refine (non-manifold edges and vertices,
        // repeated corners, inconsistent orientation) and reports it; the rest is bad input.
        let general = ["repeat.obj", "orient.obj", "nmedge.obj", "bowtie.obj"]
            .iter()
            .any(|n| input.ends_with(n));
        let (code, _, err) = run(&["info", &input]);
        assert_eq!(code, if general { 0 } else { 1 }, "info {input}: {err}");
        if general {
            assert!(err.contains("not manifold"), "info {input}: {err}");
        }
    }
    // Loop on quads names the face; unknown scheme and extension are bad input too.
    let (code, _, err) = run(&[
        "subdivide",
        "gallery:cube",
        "--scheme",
        "loop",
        "--levels",
        "1",
        "-o",
        o,
    ]);
    assert_eq!(code, 1);
    assert!(err.contains("face 0"), "{err}");
    let (code, _, err) = run(&[
        "subdivide",
        "gallery:cube",
        "--scheme",
        "nope",
        "--levels",
        "1",
        "-o",
        o,
    ]);
    assert_eq!(code, 1);
    assert!(err.contains("unknown scheme"), "{err}");
    let (code, _, err) = run(&[
        "subdivide",
        "gallery:cube",
        "--scheme",
        "loop",
        "--levels",
        "1",
        "-o",
        "x.xyz",
    ]);
    assert_eq!(code, 1);
    assert!(err.contains(".xyz"), "{err}");
    assert!(!out.exists());
    // Usage errors exit with 2.
    let (code, _, _) = run(&["subdivide", "gallery:cube"]);
    assert_eq!(code, 2);
    let (code, _, _) = run(&["frobnicate"]);
    assert_eq!(code, 2);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn info_reports_counts_and_problems_as_json() {
    let (code, out, _) = run(&["info", "gallery:torus-evs", "--json"]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["vertices"], 48);
    assert_eq!(v["faces"], 48);
    assert_eq!(v["euler_characteristic"], 0);
    assert_eq!(v["extraordinary_vertices"].as_array().unwrap().len(), 8);
    assert!(
        v["problems"][0]
            .as_str()
            .unwrap()
            .contains("join two extraordinary vertices")
    );
    let (code, out, _) = run(&["info", "gallery:prism-5", "--json"]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["extraordinary_faces"].as_array().unwrap().len(), 2);
}

#[test]
fn demo_runs_without_input() {
    let dir = scratch("demo");
    let (code, out, err) = run(&["demo", "--out", dir.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("wrote"));
    let c = fairsub::io::read_bv(&dir.join("demo-catmull-clark.bv"))
        .unwrap()
        .patches;
    // Valence-5 extended c-net: 20 regular faces + 6 rings of 15 patches + 5 fill patches.
    assert_eq!(c.len(), 9 * 5 - 5 + 6 * 15 + 5);
    // Every scheme of the registry is in the demo: the triangle schemes on the net cut into
    // triangles (45 quads, 90 triangles), refined 3 times: Loop and the modified butterfly split
    // each triangle into 4, sqrt(3) into 3.
    let faces = |name: &str| {
        fairsub::io::read_mesh(&dir.join(name))
            .unwrap_or_else(|e| panic!("{name}: {e}"))
            .mesh
            .num_faces()
    };
    assert_eq!(faces("demo-net-triangles.obj"), 90);
    assert_eq!(faces("demo-loop-level3.obj"), 90 * 64);
    assert_eq!(faces("demo-butterfly-level3.obj"), 90 * 64);
    assert_eq!(faces("demo-sqrt3-level3.obj"), 90 * 27);
    for e in fairsub::schemes::registry().entries() {
        if e.capabilities().refine {
            let level3 = dir.join(format!("demo-{}-level3.obj", e.name));
            assert!(level3.exists(), "the demo left out {}", e.name);
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn analyze_and_charmap_commands() {
    let (code, out, _) = run(&[
        "analyze",
        "--scheme",
        "catmull-clark",
        "--valence",
        "5",
        "--json",
    ]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let lambda = v["spectrum"]["lambda"].as_f64().unwrap();
    assert!((lambda - fairsub::analysis::catmull_clark_lambda(5)).abs() < 1e-12);
    assert_eq!(v["characteristic_map"]["injective"], true);
    let dir = scratch("charmap");
    let svg = dir.join("chi.svg");
    let (code, _, _) = run(&[
        "charmap",
        "--scheme",
        "catmull-clark",
        "--valence",
        "6",
        "-o",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(code, 0);
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
    let (code, _, err) = run(&["analyze", "--scheme", "catmull-clark", "--valence", "2"]);
    assert_eq!(code, 1);
    assert!(err.contains("valence 2"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
