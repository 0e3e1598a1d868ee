//! Every BezierView patch kind, from files fairsub writes with its own library, through `check`
//! and `render`: a sphere of eight rational octants (type 8), quadratic triangular patches of a
//! paraboloid (type 3), a tetrahedron as a polyhedron (type 1), and a file mixing them. The
//! numbers are the surfaces' own: the sphere's Gaussian curvature is 1 and its joins are G^1,
//! the paraboloid's curvature runs from 4/25 to 4, the tetrahedron's faces meet at the angle
//! arccos(-1/3) between their normals.

use crate::common;
use fairsub::bezier::BezierPatch;
use fairsub::io::{BvFile, BvPolyhedron, TriPatch};
use fairsub::surface::Provenance;
use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

/// `fairsub ARGS`, which must succeed: its stdout.
fn fairsub(args: &[&str]) -> String {
    let (code, out, err) = common::run(args);
    assert_eq!(code, 0, "fairsub {args:?}: {err}");
    out
}

fn dir() -> PathBuf {
    common::scratch("bv-kinds")
}

/// The octant of the unit sphere with signs `sg`, as a rational bi-quadratic patch (the pole
/// side collapsed), oriented with the outward normal `du x dv`.
fn octant(sg: [f64; 3]) -> BezierPatch {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let circle = [([1.0, 0.0], 1.0), ([1.0, 1.0], h), ([0.0, 1.0], 1.0)];
    let (mut cps, mut ws) = (Vec::new(), Vec::new());
    for &(a, wa) in &circle {
        for &(b, wb) in &circle {
            cps.push([sg[0] * a[0] * b[0], sg[1] * a[1] * b[0], sg[2] * b[1]]);
            ws.push(wa * wb);
        }
    }
    let p = BezierPatch::rational(2, 2, cps, ws).unwrap();
    let q = p.eval(0.4, 0.3);
    let n = p.normal(0.4, 0.3);
    if n[0] * q[0] + n[1] * q[1] + n[2] * q[2] < 0.0 {
        p.transposed()
    } else {
        p
    }
}

fn sphere() -> BvFile {
    let mut f = BvFile::default();
    for k in 0..8 {
        let sg = [0, 1, 2].map(|b| if k >> b & 1 == 1 { -1.0 } else { 1.0 });
        f.patches.push(octant(sg), Provenance::Unknown);
    }
    f
}

/// `z = x^2 + y^2` over the triangles (0,0),(1,0),(0,1) and (1,0),(1,1),(0,1): quadratic
/// triangular patches whose coefficients are the blossom's values.
fn paraboloid() -> BvFile {
    let f = |p: [f64; 2], q: [f64; 2]| p[0] * q[0] + p[1] * q[1];
    let tri = |a: [f64; 2], b: [f64; 2], c: [f64; 2]| {
        let mid = |p: [f64; 2], q: [f64; 2]| [(p[0] + q[0]) / 2.0, (p[1] + q[1]) / 2.0];
        let pt = |x: [f64; 2], z: f64| [x[0], x[1], z];
        // b[i][j][k] for (u, v, w) at (a, b, c); BezierView order: rows by k, within by j
        let mut cps = vec![[0.0; 3]; 6];
        cps[TriPatch::index(2, 0, 0)] = pt(a, f(a, a));
        cps[TriPatch::index(2, 1, 0)] = pt(mid(a, b), f(a, b));
        cps[TriPatch::index(2, 2, 0)] = pt(b, f(b, b));
        cps[TriPatch::index(2, 0, 1)] = pt(mid(a, c), f(a, c));
        cps[TriPatch::index(2, 1, 1)] = pt(mid(b, c), f(b, c));
        cps[TriPatch::index(2, 0, 2)] = pt(c, f(c, c));
        TriPatch { deg: 2, cps }
    };
    BvFile {
        tri_patches: vec![
            tri([0., 0.], [1., 0.], [0., 1.]),
            tri([1., 0.], [1., 1.], [0., 1.]),
        ],
        tri_groups: vec![None, None],
        ..BvFile::default()
    }
}

fn tetrahedron() -> BvPolyhedron {
    BvPolyhedron {
        positions: vec![[1., 1., 1.], [1., -1., -1.], [-1., 1., -1.], [-1., -1., 1.]],
        faces: vec![vec![0, 1, 2], vec![0, 3, 1], vec![0, 2, 3], vec![1, 3, 2]],
        group: None,
    }
}

fn check(path: &Path) -> Value {
    serde_json::from_str(&fairsub(&["check", path.to_str().unwrap(), "--json"])).unwrap()
}

/// `render --json` in `mode`: the report (the picture must cover part of the frame).
fn render(path: &Path, mode: &str) -> Value {
    let png = path.with_extension(format!("{mode}.png"));
    let out = fairsub(&[
        "render",
        path.to_str().unwrap(),
        "--mode",
        mode,
        "--size",
        "160x120",
        "--json",
        "-o",
        png.to_str().unwrap(),
    ]);
    let r: Value = serde_json::from_str(&out).unwrap();
    assert!(
        r["frame"]["covered"].as_u64().unwrap() > 2000,
        "{}: {r}",
        path.display()
    );
    assert!(std::fs::metadata(&png).unwrap().len() > 1000);
    r
}

#[test]
fn rational_sphere_is_exact_and_g1() {
    let path = dir().join("sphere.bv");
    fairsub::io::bv::write_bv_file(&path, &sphere()).unwrap();
    assert!(
        std::fs::read_to_string(&path)
            .unwrap()
            .contains("\n8 2 2\n")
    );
    let c = check(&path);
    assert_eq!(c["kinds"]["rational"], 8, "{c}");
    let k = &c["continuity"];
    assert_eq!(k["open_sides"], 0, "{k}");
    assert!(k["all"]["pieces"].as_u64().unwrap() >= 12, "{k}");
    assert!(k["all"]["c0"].as_f64().unwrap() < 1e-15, "{k}");
    assert!(k["all"]["g1"].as_f64().unwrap() < 1e-7, "{k}");
    let r = render(&path, "gauss");
    // every pixel's exact ray-patch point: K = 1 to single precision
    let f = &r["frame"]["gauss"];
    for x in [&f[0], &f[1]] {
        assert!((x.as_f64().unwrap() - 1.0).abs() < 1e-6, "{f}");
    }
    // the per-patch grid includes the poles, where each octant's side collapses and the
    // curvature is taken a little inside, from nearly parallel partials: measured 1.0e-4
    let g = &r["groups"][0];
    for x in [&g["gauss"][0], &g["gauss"][1]] {
        assert!((x.as_f64().unwrap() - 1.0).abs() < 2e-4, "{g}");
    }
}

#[test]
fn triangular_patches_are_the_paraboloid() {
    let path = dir().join("paraboloid.bv");
    fairsub::io::bv::write_bv_file(&path, &paraboloid()).unwrap();
    let c = check(&path);
    assert_eq!(c["kinds"]["triangular"], 2, "{c}");
    let k = &c["continuity"];
    // one shared side (the diagonal), tangent-plane continuous: one polynomial on both sides
    // (parametric C^1 does not hold: each triangle's collapsed square runs its own way)
    assert_eq!(k["all"]["pieces"], 1, "{k}");
    assert_eq!(k["open_sides"], 4, "{k}");
    assert!(k["all"]["c0"].as_f64().unwrap() < 1e-15, "{k}");
    assert!(k["all"]["g1"].as_f64().unwrap() < 1e-14, "{k}");
    let r = render(&path, "gauss");
    let g = &r["groups"][0]["gauss"];
    let (lo, hi) = (g[0].as_f64().unwrap(), g[1].as_f64().unwrap());
    // K = 4 / (1 + 4 r^2)^2 for r^2 in [0, 2]: the samples include (1, 0) (r^2 = 1) and (1, 1)
    assert!((lo - 4.0 / 81.0).abs() < 1e-9, "{g}");
    assert!(hi > 3.99 && hi < 4.0 + 1e-9, "{g}");
}

#[test]
fn polyhedra_are_flat_patches_with_sharp_joins() {
    let path = dir().join("tetra.bv");
    let f = BvFile {
        polyhedra: vec![tetrahedron()],
        ..BvFile::default()
    };
    fairsub::io::bv::write_bv_file(&path, &f).unwrap();
    let c = check(&path);
    assert_eq!(c["kinds"]["polyhedra"], 1, "{c}");
    assert_eq!(c["kinds"]["polyhedron_faces"], 4, "{c}");
    let sharp = &c["continuity"]["sharp"];
    assert_eq!(sharp["pieces"], 6, "{sharp}");
    assert!(sharp["c0"].as_f64().unwrap() < 1e-15, "{sharp}");
    // the outward normals of two faces meet at arccos(-1/3) (the dihedral angle's supplement)
    let angle = (-1.0f64 / 3.0).acos();
    assert!(
        (sharp["g1"].as_f64().unwrap() - angle).abs() < 1e-12,
        "{sharp}"
    );
    render(&path, "shaded");
}

#[test]
fn a_file_of_every_kind_is_read_and_drawn_whole() {
    let path = dir().join("mixed.bv");
    let mut f = sphere();
    let p = paraboloid();
    f.tri_patches = p.tri_patches;
    f.tri_groups = p.tri_groups;
    let mut t = tetrahedron();
    for q in &mut t.positions {
        q[0] += 4.0;
    }
    f.polyhedra.push(t);
    f.patches.push(
        BezierPatch::new(
            1,
            2,
            vec![
                [0., 3., 0.],
                [1., 3., 1.],
                [2., 3., 0.],
                [0., 4., 0.],
                [1., 4., 1.],
                [2., 4., 0.],
            ],
        ),
        Provenance::Unknown,
    );
    fairsub::io::bv::write_bv_file(&path, &f).unwrap();
    let c = check(&path);
    let k = &c["kinds"];
    assert_eq!(
        [
            &k["tensor"],
            &k["rational"],
            &k["triangular"],
            &k["polyhedron_faces"]
        ],
        [1, 8, 2, 4],
        "{c}"
    );
    assert_eq!(c["continuity"]["patches"], 1 + 8 + 2 + 4, "{c}");
    render(&path, "mean");
    // an empty file is an error, not 0 patches
    let empty = dir().join("empty.bv");
    std::fs::write(&empty, "group 1 nothing\n").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .args(["check", empty.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("no patches"));
}
