//! Face-varying data through PLY and OFF (issue 16): PLY texture coordinates (per vertex `u v`
//! and face `texcoord` lists) are read into the same channel as OBJ `vt`, refined the same way
//! (the same nets as OBJ give the same UVs at every face corner, and the OBJ nets are the ones
//! `tests/it/osd_peer.rs` checks against OpenSubdiv), and written back to PLY; OFF output warns
//! that it drops them.

use crate::common::scratch;
use fairsub::io;
use fairsub::mesh::PolyMesh;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// `fairsub subdivide ARGS`: (success, stderr).
fn subdivide(args: &[&str]) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .arg("subdivide")
        .args(args)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `fairsub subdivide SRC --scheme SCHEME --levels 2 --fvar FVAR EXTRA.. -o OUT`, which must
/// succeed.
fn refine2(src: &Path, scheme: &str, fvar: &str, extra: &[&str], out: &Path) {
    let mut args = vec![src.to_str().unwrap(), "--scheme", scheme, "--levels", "2"];
    args.extend(["--fvar", fvar]);
    args.extend(extra);
    args.extend(["-o", out.to_str().unwrap()]);
    let (ok, err) = subdivide(&args);
    assert!(ok, "{args:?}: {err}");
}

/// An OBJ net with `f v/vt` faces: positions, UVs, faces as (vertex, uv) corners.
struct Net {
    v: Vec<[f64; 3]>,
    vt: Vec<[f64; 2]>,
    f: Vec<Vec<(usize, usize)>>,
}

fn read_obj(path: &Path) -> Net {
    let mut n = Net {
        v: vec![],
        vt: vec![],
        f: vec![],
    };
    for l in std::fs::read_to_string(path).unwrap().lines() {
        let t: Vec<&str> = l.split_whitespace().collect();
        let num = |i: usize| t[i].parse::<f64>().unwrap();
        match t.first() {
            Some(&"v") => n.v.push([num(1), num(2), num(3)]),
            Some(&"vt") => n.vt.push([num(1), num(2)]),
            Some(&"f") => n.f.push(
                t[1..]
                    .iter()
                    .map(|c| {
                        let mut p = c.split('/').map(|x| x.parse::<usize>().unwrap() - 1);
                        (p.next().unwrap(), p.next().unwrap())
                    })
                    .collect(),
            ),
            _ => {}
        }
    }
    n
}

/// The net as ascii PLY: texture coordinates per vertex (`u v`, the net must be
/// vertex-consistent) or as face `texcoord` lists (double, 2 per corner).
fn ply_text(n: &Net, per_vertex: bool) -> String {
    let mut s = format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty double x\nproperty double y\n\
         property double z\n",
        n.v.len()
    );
    let mut vuv = vec![[0.0; 2]; n.v.len()];
    if per_vertex {
        s += "property double u\nproperty double v\n";
        for face in &n.f {
            for &(v, t) in face {
                vuv[v] = n.vt[t];
            }
        }
    }
    s += &format!(
        "element face {}\nproperty list uchar int vertex_indices\n",
        n.f.len()
    );
    if !per_vertex {
        s += "property list uchar double texcoord\n";
    }
    s += "end_header\n";
    for (p, t) in n.v.iter().zip(&vuv) {
        s += &format!("{} {} {}", p[0], p[1], p[2]);
        if per_vertex {
            s += &format!(" {} {}", t[0], t[1]);
        }
        s += "\n";
    }
    for face in &n.f {
        s += &face.len().to_string();
        for &(v, _) in face {
            s += &format!(" {v}");
        }
        if !per_vertex {
            s += &format!(" {}", 2 * face.len());
            for &(_, t) in face {
                s += &format!(" {} {}", n.vt[t][0], n.vt[t][1]);
            }
        }
        s += "\n";
    }
    s
}

/// Every face corner's (position, UV) of a mesh with face-varying data.
fn corner_uvs(m: &PolyMesh) -> Vec<([f64; 3], [f64; 2])> {
    let uv = m
        .extras()
        .and_then(|e| e.uv.as_ref())
        .expect("texture coordinates");
    m.corners()
        .iter()
        .zip(&uv.corners)
        .map(|(&v, &t)| (m.positions()[v as usize], uv.values[t as usize]))
        .collect()
}

fn assert_same_corners(a: &PolyMesh, b: &PolyMesh, what: &str) {
    let (ca, cb) = (corner_uvs(a), corner_uvs(b));
    assert_eq!(ca.len(), cb.len(), "{what}: corner counts");
    for (i, (x, y)) in ca.iter().zip(&cb).enumerate() {
        let d = (0..3).map(|k| (x.0[k] - y.0[k]).abs()).fold(0.0, f64::max);
        let e = (0..2).map(|k| (x.1[k] - y.1[k]).abs()).fold(0.0, f64::max);
        assert!(d < 1e-12 && e < 1e-12, "{what}: corner {i}: {x:?} vs {y:?}");
    }
}

/// PLY nets (per-vertex `u v` and face `texcoord` lists) refine to the same UVs at every face
/// corner as the same nets (without tags) in OBJ, for several face-varying options; PLY output (ascii and
/// binary) holds them too.
#[test]
fn ply_texture_coordinates_refine_as_obj_uvs() {
    let dir = scratch("ply");
    let cases = [
        ("cc_grid_uv_seam.obj", false, "catmull-clark"),
        ("cc_repeated_vertex_uvs.obj", false, "catmull-clark"),
        ("cc_repeated_vertex_uvs_shared.obj", true, "catmull-clark"),
        ("loop_octa_uv.obj", false, "loop"),
    ];
    for (net, per_vertex, scheme) in cases {
        let obj = root().join("tests/data/osd").join(net);
        let n = read_obj(&obj);
        let ply = dir.join(net.replace(".obj", ".ply"));
        std::fs::write(&ply, ply_text(&n, per_vertex)).unwrap();
        let read = io::read_mesh_as(&ply, true).unwrap().mesh;
        let uv = read.extras().and_then(|e| e.uv.as_ref()).expect("UVs read");
        // Corners of one vertex with equal values share one value: as many as the OBJ has.
        let distinct: std::collections::BTreeSet<_> = n.f.iter().flatten().map(|c| c.1).collect();
        assert_eq!(uv.values.len(), distinct.len(), "{net}: values");
        for fvar in ["none", "corners-plus1", "boundaries", "all"] {
            let out_obj = dir.join(format!("{net}-{fvar}-obj.obj"));
            let out_ply = dir.join(format!("{net}-{fvar}-ply.obj"));
            for (src, out) in [(&obj, &out_obj), (&ply, &out_ply)] {
                refine2(src, scheme, fvar, &[], out);
            }
            let a = io::read_mesh_as(&out_obj, true).unwrap().mesh;
            let b = io::read_mesh_as(&out_ply, true).unwrap().mesh;
            assert_same_corners(&a, &b, &format!("{net} --fvar {fvar}"));
        }
        // PLY output keeps them (per vertex when consistent, else per corner).
        let out_obj = dir.join(format!("{net}-none-obj.obj"));
        let reference = io::read_mesh_as(&out_obj, true).unwrap().mesh;
        for format in ["ply-ascii", "ply-binary"] {
            let out = dir.join(format!("{net}-{format}.ply"));
            refine2(&ply, scheme, "none", &["--format", format], &out);
            let bytes = std::fs::read(&out).unwrap();
            let head = String::from_utf8_lossy(&bytes[..bytes.len().min(600)]).into_owned();
            let by_vertex = head.contains("property double u\n");
            assert_eq!(
                by_vertex,
                !head.contains("texcoord"),
                "{net} {format}: one layout: {head}"
            );
            // The shared net stays vertex-consistent; the others have seams.
            assert_eq!(by_vertex, per_vertex, "{net} {format}: {head}");
            let back = io::read_mesh_as(&out, true).unwrap().mesh;
            assert_same_corners(&reference, &back, &format!("{net} as {format}"));
        }
    }
    std::fs::remove_dir_all(dir).unwrap();
}

/// A `texcoord` list that does not hold two values per corner is an error naming the face and
/// its line.
#[test]
fn ply_texcoord_of_wrong_length_names_the_face() {
    let dir = scratch("bad");
    let p = dir.join("bad.ply");
    std::fs::write(
        &p,
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
         property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
         property list uchar float texcoord\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 4 0 0 1 0\n",
    )
    .unwrap();
    let e = io::read_mesh(&p).unwrap_err().to_string();
    assert!(
        e.contains("bad.ply:14") && e.contains("face 0") && e.contains("holds 4 values"),
        "{e}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

/// OFF cannot hold texture coordinates: the net is written, with a warning that names what is
/// dropped.
#[test]
fn off_output_warns_that_uvs_are_dropped() {
    let dir = scratch("off");
    let net = root().join("tests/data/osd/cc_grid_uv_seam.obj");
    for ext in ["off", "obj"] {
        let out = dir.join(format!("out.{ext}"));
        let (ok, err) = subdivide(&[
            net.to_str().unwrap(),
            "--scheme",
            "catmull-clark",
            "--levels",
            "1",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(ok, "{err}");
        // OBJ output of the same net keeps them, without the warning.
        let warned =
            err.contains("warning:") && err.contains("OFF cannot hold texture coordinates");
        assert_eq!(warned, ext == "off", "{ext}: {err}");
        let m = io::read_mesh(&out).unwrap().mesh;
        assert_eq!(m.num_faces(), 4 * 12);
        assert_eq!(m.extras().is_some_and(|e| e.uv.is_some()), ext == "obj");
    }
    std::fs::remove_dir_all(dir).unwrap();
}

/// A 3 x 3 quad grid (vertex `(i, j)` at index `4 j + i`, UV `(i, j) / 3`) whose interior
/// vertex 5 = (1, 1) takes, in the two faces right of it (faces 1 and 4), the extra UV value
/// 17: `gap` apart from vertex 5's own value 6 in u when `split`, else those faces share value 6.
fn grid_with_seam_at_5(split: bool, gap: f64) -> String {
    let mut s = String::new();
    for j in 0..4 {
        for i in 0..4 {
            s += &format!("v {i} {j} {}\n", 0.1 * f64::from(i * j));
        }
    }
    for j in 0..4 {
        for i in 0..4 {
            s += &format!("vt {} {}\n", f64::from(i) / 3.0, f64::from(j) / 3.0);
        }
    }
    s += &format!("vt {} {}\n", 1.0 / 3.0 + gap, 1.0 / 3.0);
    for j in 0..3 {
        for i in 0..3 {
            let f = 3 * j + i;
            s += "f";
            for (a, b) in [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)] {
                let v = 4 * b + a;
                let t = if split && v == 5 && (f == 1 || f == 4) {
                    17
                } else {
                    v + 1
                };
                s += &format!(" {}/{t}", v + 1);
            }
            s += "\n";
        }
    }
    s
}

/// A vertex with two face-varying values that are distinct but close (5e-5 apart, below
/// Blender's 1e-4 UV grouping limit, which the Blender add-on applies before fairsub sees the
/// net): fairsub keeps them as two values (a seam, as OpenSubdiv's value indices make it), and
/// refines them linearly in the values. Against the same seam with equal values (value 17 =
/// value 6), every corner of the two-step Catmull-Clark result moves by at most the gap, in u
/// only, and with linear boundaries (`boundaries`, `all`) the vertex point of vertex 5 keeps
/// both values exactly, each on the child faces of its own side, where the net without the
/// seam has one; the positions and faces are those of the net without a seam.
#[test]
fn close_distinct_values_of_a_vertex_stay_two_values() {
    let dir = scratch("fvar-close");
    let gap = 5e-5;
    let write = |name: &str, split: bool, gap: f64| {
        let p = dir.join(name);
        std::fs::write(&p, grid_with_seam_at_5(split, gap)).unwrap();
        p
    };
    let shared = write("shared.obj", false, 0.0);
    let equal = write("equal.obj", true, 0.0);
    let close = write("close.obj", true, gap);
    let (u5, u17) = (1.0 / 3.0, 1.0 / 3.0 + gap);
    for fvar in ["none", "corners-only", "corners-plus1", "boundaries", "all"] {
        let out = |src: &Path, tag: &str| {
            let o = dir.join(format!("{tag}-{fvar}.obj"));
            refine2(src, "catmull-clark", fvar, &[], &o);
            read_obj(&o)
        };
        let (s, e, c) = (
            out(&shared, "shared"),
            out(&equal, "equal"),
            out(&close, "close"),
        );
        assert_eq!((s.v.len(), s.f.len()), (169, 144), "{fvar}: counts");
        for other in [&e, &c] {
            assert_eq!(other.v, s.v, "{fvar}: positions");
            let verts = |n: &Net| -> Vec<Vec<usize>> {
                n.f.iter()
                    .map(|f| f.iter().map(|x| x.0).collect())
                    .collect()
            };
            assert_eq!(verts(other), verts(&s), "{fvar}: faces");
        }
        let mut largest: f64 = 0.0;
        for (fe, fc) in e.f.iter().zip(&c.f) {
            for (&(_, te), &(_, tc)) in fe.iter().zip(fc) {
                let (a, b) = (e.vt[te], c.vt[tc]);
                assert!(b[1] == a[1], "{fvar}: v moved: {a:?} -> {b:?}");
                let d = b[0] - a[0];
                assert!(
                    (-1e-15..=gap * (1.0 + 1e-9)).contains(&d),
                    "{fvar}: u moved by {d}"
                );
                largest = largest.max(d);
            }
        }
        let values_at_5 = |n: &Net, side: &dyn Fn(usize) -> bool| -> Vec<f64> {
            let mut u: Vec<f64> = (0..n.f.len())
                .filter(|&k| side(k / 16))
                .flat_map(|k| n.f[k].iter().filter(|x| x.0 == 5).map(|x| n.vt[x.1][0]))
                .collect();
            u.dedup();
            u
        };
        let right = |f: usize| f == 1 || f == 4;
        let left = |f: usize| !right(f);
        if fvar == "boundaries" || fvar == "all" {
            assert!(
                (largest - gap).abs() < 1e-15,
                "{fvar}: largest move {largest}"
            );
            assert_eq!(values_at_5(&c, &left), [u5], "{fvar}: left of the seam");
            assert_eq!(values_at_5(&c, &right), [u17], "{fvar}: right of the seam");
            // without the seam vertex 5 takes its own smooth rule: one value, on the linear
            // UV field where it was
            let one = values_at_5(&s, &|_| true);
            assert!(
                one.len() == 1 && (one[0] - u5).abs() < 1e-12,
                "{fvar}: {one:?}"
            );
        } else {
            assert!(largest > 0.0, "{fvar}: the gap moved nothing");
        }
    }
}
