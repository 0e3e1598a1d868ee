//! Unit tests of the `.bv` writer and reader.

use super::*;
use crate::bezier::BezierPatch;
use crate::error::Error;
use crate::io::testutil;
use crate::mesh::PolyMesh;
use crate::surface::{Element, Provenance};
use std::path::Path;

fn patch(du: usize, dv: usize, seed: f64) -> BezierPatch {
    testutil::patch(du, dv, |i, j, k| {
        [
            i as f64 + seed,
            j as f64 / 3.0,
            (seed * (k as f64 + 1.0)).sin(),
        ]
    })
}

/// Regular patches, a ring-1 and a cap patch of vertex 7, then a regular patch again.
fn complex() -> PatchComplex {
    let e = Element::Vertex(7);
    let items = vec![
        (patch(3, 3, 0.1), None),
        (patch(2, 3, 0.2), None),
        (patch(3, 3, 0.3), Some((1, 0))),
        (patch(3, 3, 0.4), Some((0, 0))),
        (patch(1, 4, 0.5), None),
    ];
    testutil::complex(e, items)
}

#[crate::unit::test]
fn triangular_index_matches_bezierview_picture() {
    // 9 / 7 8 / 4 5 6 / 0 1 2 3 for degree 3: row k, position j.
    assert_eq!(TriPatch::index(3, 0, 0), 0);
    assert_eq!(TriPatch::index(3, 3, 0), 3);
    assert_eq!(TriPatch::index(3, 0, 1), 4);
    assert_eq!(TriPatch::index(3, 2, 1), 6);
    assert_eq!(TriPatch::index(3, 0, 2), 7);
    assert_eq!(TriPatch::index(3, 1, 2), 8);
    assert_eq!(TriPatch::index(3, 0, 3), 9);
    assert_eq!(TriPatch::count(3), 10);
    // Agrees with the loop of b2i_i for several degrees.
    for d in 0..8 {
        for k in 0..=d {
            let lk: usize = (0..k).map(|kk| d + 1 - kk).sum();
            for j in 0..=d - k {
                assert_eq!(TriPatch::index(d, j, k), lk + j);
            }
        }
    }
}

#[crate::unit::test]
fn writer_layout() {
    let s = bv_to_string(&complex()).unwrap();
    let lines: Vec<&str> = s.lines().collect();
    assert_eq!(lines[0], "group 1 regular");
    assert_eq!(lines[1], "4 3");
    assert_eq!(
        lines.len(),
        1 + 1 + 16 + 1 + 12 + 1 + 1 + 16 + 1 + 1 + 16 + 1 + 1 + 10
    );
    assert_eq!(lines[18], "5 2 3");
    assert_eq!(lines[31], "group 2 ring1");
    assert_eq!(lines[49], "group 3 cap");
    assert_eq!(lines[67], "group 1 regular");
    assert_eq!(lines[68], "5 1 4");
    // b[0][1] of the first patch is the second point: row-major, i along u.
    let p: Vec<f64> = lines[3].split(' ').map(|x| x.parse().unwrap()).collect();
    assert_eq!(p, complex().patches[0].cp(0, 1).to_vec());
}

#[crate::unit::test]
fn roundtrip_is_exact_and_keeps_groups() {
    let c = complex();
    let s = bv_to_string(&c).unwrap();
    let f = parse_bv(&s, Path::new("r.bv")).unwrap();
    assert_eq!(f.patches.patches, c.patches);
    assert!(
        f.patches
            .provenance
            .iter()
            .all(|p| *p == Provenance::Unknown)
    );
    let names: Vec<&str> = f.groups.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["regular", "ring1", "cap"]);
    assert_eq!(
        f.patch_groups,
        [Some(0), Some(0), Some(1), Some(2), Some(0)]
    );
    assert!(f.warnings.is_empty());
    // And the BvFile writes back to the same text.
    assert_eq!(f.to_bv_string().unwrap(), s);
}

#[crate::unit::test]
fn reads_foreign_files_leniently() {
    // The tensor example of SurfLab's page, a triangle, a polyhedron with a quad,
    // comments and odd whitespace.
    let src = "# from another tool\nGroup 1 deg2x3\n5\n2 3\n-1.5 1.0 0.0\n-0.5 1.0 0.0\n0.5 1.0 0.0\n1.5 1.0 0.0\n\
               -1.5 0.0 0.0\n-0.5 0.0 0.5\n0.5 0.0 0.5\n1.5 0.0 0.0\n-1.5 -1.0 0.0 -0.5 -1.0 0.0\n\
               0.5\t-1.0 0.0\n1.5 -1.0 0.0\n\n\
               group 4 tri #3\n3 1\n0 0 0\n1 0 0\n0 1 0\n\
               1\n5 2\n0 0 0\n1 0 0\n1 1 0\n0 1 1\n0.5 2 0\n4 0 1 2 3\n3 3 2 4\n\
               8 1 1\n0 0 0 2\n2 0 0 2\n0 2 0 2\n2 2 2 2\n\
               10 1 1 0 0\n0 0 0\n1 0 0\n0 1 0\n1 1 1\n0 0 1\n";
    let f = parse_bv(src, Path::new("f.bv")).unwrap();
    assert_eq!(f.patches.len(), 3);
    let p = &f.patches.patches[0];
    assert_eq!((p.deg_u, p.deg_v), (2, 3));
    assert_eq!(p.cp(1, 1), [-0.5, 0.0, 0.5]);
    assert_eq!(p.cp(2, 0), [-1.5, -1.0, 0.0]);
    assert_eq!(p.cp(2, 1), [-0.5, -1.0, 0.0]);
    let r = &f.patches.patches[1];
    assert_eq!(
        r.cps,
        vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 1.0]]
    );
    assert_eq!(f.patches.patches[2].cp(1, 1), [1.0, 1.0, 1.0]);
    assert_eq!(f.tri_patches.len(), 1);
    assert_eq!(f.tri_patches[0].cp(0, 0, 1), [0.0, 1.0, 0.0]);
    assert_eq!(f.polyhedra.len(), 1);
    assert_eq!(f.polyhedra[0].faces, vec![vec![0, 1, 2, 3], vec![3, 2, 4]]);
    assert_eq!(f.polyhedra[0].positions[3], [0.0, 1.0, 1.0]);
    assert_eq!(
        f.groups,
        vec![
            BvGroup {
                id: 1,
                name: "deg2x3".into()
            },
            BvGroup {
                id: 4,
                name: "tri".into()
            }
        ]
    );
    assert_eq!(f.patch_groups, [Some(0), Some(1), Some(1)]);
    assert_eq!(f.tri_groups, [Some(1)]);
    assert_eq!(f.polyhedra[0].group, Some(1));
    assert_eq!(f.warnings.len(), 2, "{:?}", f.warnings);
    // A polyhedron read back becomes a valid mesh.
    let m = PolyMesh::new(f.polyhedra[0].positions.clone(), &f.polyhedra[0].faces).unwrap();
    assert_eq!(m.num_faces(), 2);
}

#[crate::unit::test]
fn mesh_as_polyhedron_roundtrip() {
    let pos = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.1],
        [0.0, 1.0, 0.0],
        [0.5, 2.0, 0.0],
    ];
    let faces: Vec<Vec<usize>> = vec![vec![0, 1, 2, 3], vec![3, 2, 4]];
    let m = PolyMesh::new(pos.clone(), &faces).unwrap();
    let s = bv_mesh_to_string(&m);
    assert!(s.starts_with("1\n5 2\n"), "{s}");
    let f = parse_bv(&s, Path::new("m.bv")).unwrap();
    assert_eq!(f.polyhedra[0].positions, pos);
    assert_eq!(f.polyhedra[0].faces, faces);
    assert_eq!(f.polyhedra[0].group, None);
}

#[crate::unit::test]
fn errors_name_lines() {
    testutil::assert_parse_errors(
        |s| parse_bv(s, Path::new("e.bv")),
        &[
            (
                "4 1\n0 0 0\n1 0 0\n0 1 0\n1 1 q\n",
                5,
                &["'q'", "control point 3", "line 1"],
            ),
            ("4 1\n0 0 0\n1 0 0\n", 3, &["file ends", "control point 2"]),
            ("\n\n7 1\n", 3, &["unknown patch type 7"]),
            ("1\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n3\n", 7, &["vertex 3"]),
            ("5 2 -1\n", 1, &["degree in v", "is -1"]),
            ("hello\n", 1, &["'hello'"]),
            ("1\n4000000000 1\n0 0 0\n", 3, &["file ends", "vertex 1"]),
            ("5 2 1000000\n", 1, &["1000000"]),
        ],
    );
    // a weight must be positive
    let e = parse_bv(
        "8 1 1\n0 0 0 1\n1 0 0 0\n0 1 0 1\n1 1 0 1\n",
        Path::new("e.bv"),
    )
    .unwrap_err();
    assert!(
        matches!(e, Error::Parse { .. }) && e.to_string().contains("e.bv:3"),
        "{e}"
    );
}

#[crate::unit::test]
fn rational_patches_keep_their_weights_and_round_trip() {
    // homogeneous coefficients: the second point (1, 0, 0) with weight 2
    let f = parse_bv(
        "8 1 1\n0 0 0 1\n2 0 0 2\n0 1 0 1\n1 1 0 1\n",
        Path::new("r.bv"),
    )
    .unwrap();
    let p = &f.patches.patches[0];
    assert_eq!(p.weights.as_deref(), Some(&[1.0, 2.0, 1.0, 1.0][..]));
    assert_eq!(p.cps[1], [1.0, 0.0, 0.0]);
    // along u = 0 (b00 with weight 1, b01 = (1, 0, 0) with weight 2): x = 2 v / (1 + v)
    let q = p.eval(0.5, 0.0);
    assert_eq!(q, [0.0, 0.5, 0.0]);
    let q = p.eval(0.0, 0.5);
    assert!((q[0] - 2.0 / 3.0).abs() < 1e-15 && q[1] == 0.0, "{q:?}");
    let text = bv_to_string(&f.patches).unwrap();
    assert!(text.starts_with("group 1 patches\n8 1 1\n"), "{text}");
    let back = parse_bv(&text, Path::new("r2.bv")).unwrap();
    assert_eq!(back.patches.patches[0], *p);
    assert_eq!(f.counts().rational, 1);
    // equal weights: a polynomial patch, with a note
    let f = parse_bv(
        "8 1 1\n0 0 0 2\n2 0 0 2\n0 2 0 2\n2 2 0 2\n",
        Path::new("r.bv"),
    )
    .unwrap();
    assert!(f.patches.patches[0].weights.is_none() && f.warnings.len() == 1);
}

#[crate::unit::test]
fn writer_rejects_bad_patches() {
    let mut c = complex();
    c.patches[1].cps[4][2] = f64::INFINITY;
    let e = bv_to_string(&c).unwrap_err().to_string();
    assert!(e.contains("patch 1") && e.contains("b[1][0]"), "{e}");
    let mut c = complex();
    c.patches[2].cps.pop();
    let e = bv_to_string(&c).unwrap_err().to_string();
    assert!(
        e.contains("patch 2") && e.contains("15 coefficients"),
        "{e}"
    );
}

#[crate::unit::test]
fn invalid_utf8_is_an_error_outside_comments_only() {
    let f = testutil::assert_text_rule(
        |b| read::parse_bv_bytes(b, Path::new("u.bv")),
        b"# caf\xe9\n4 1 # \xff\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n",
        b"group 1 caf\xe9\n4 1\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n",
        "u.bv:1: invalid UTF-8 at column 12 (byte 0xE9)",
    );
    assert_eq!(f.patches.len(), 1);
}

#[crate::unit::test]
fn many_groups_take_linear_time() {
    // 200,000 distinct group lines (a quadratic lookup took 25 s for 100,000), then a group
    // seen before (its id is updated) and one patch.
    let n = 200_000;
    let mut src = String::new();
    for k in 0..n {
        src.push_str(&format!("group {k} g{k}\n"));
    }
    src.push_str("group 7 g3\n4 1\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n");
    let t = std::time::Instant::now();
    let f = parse_bv(&src, Path::new("g.bv")).unwrap();
    let back = f.to_bv_string().unwrap();
    let secs = t.elapsed().as_secs_f64();
    assert_eq!(f.groups.len(), n);
    assert_eq!(
        f.groups[3],
        BvGroup {
            id: 7,
            name: "g3".into()
        }
    );
    assert_eq!(f.patch_groups, [Some(3)]);
    assert!(back.starts_with("group 7 g3\n4 1\n"), "{}", &back[..40]);
    assert!(
        secs < 10.0,
        "parsing and writing {n} groups took {secs:.1} s"
    );
}
