//! File-level tests of the `io` module: every writer's output read back through the public
//! readers, atomicity of failed writes, and format choice. Unit tests beside each format cover
//! parsing details and error messages.

use crate::common::scratch;
use fairsub::bezier::BezierPatch;
use fairsub::error::Error;
use fairsub::io::{self, MeshFormat, OutputFormat};
use fairsub::mesh::PolyMesh;
use fairsub::surface::{Element, PatchComplex, Provenance};
use std::path::Path;

fn files_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// A cube with one face split into a triangle and a pentagon-free n-gon mix: 8 vertices,
/// quads plus two triangles replacing the top quad; coordinates that need full precision.
fn cube() -> PolyMesh {
    let s = 1.0 / 3.0;
    let pos = vec![
        [0.0, 0.0, 0.0],
        [1.0 + s, 0.0, 0.0],
        [1.0 + s, 1.0, 0.0],
        [0.0, 1.0, 1e-17],
        [0.0, 0.0, 1.0],
        [1.0 + s, 0.0, 1.0],
        [1.0 + s, 1.0, 1.0],
        [0.0, 1.0, 1.0 - 1e-12],
    ];
    let faces: Vec<Vec<usize>> = vec![
        vec![0, 3, 2, 1],
        vec![4, 5, 6],
        vec![4, 6, 7],
        vec![0, 1, 5, 4],
        vec![1, 2, 6, 5],
        vec![2, 3, 7, 6],
        vec![3, 0, 4, 7],
    ];
    PolyMesh::new(pos, &faces).unwrap()
}

fn same_mesh(a: &PolyMesh, b: &PolyMesh) {
    assert_eq!(a.positions(), b.positions());
    assert_eq!(a.num_faces(), b.num_faces());
    for f in 0..a.num_faces() {
        assert_eq!(a.face(f), b.face(f), "face {f}");
    }
}

#[test]
fn every_mesh_format_roundtrips_through_files() {
    let dir = scratch("mesh");
    let m = cube();
    for (name, fmt) in [
        ("c.obj", MeshFormat::Obj),
        ("c.off", MeshFormat::Off),
        ("a.ply", MeshFormat::PlyAscii),
        ("b.PLY", MeshFormat::PlyBinary),
    ] {
        let p = dir.join(name);
        io::write_mesh(&p, &m, fmt).unwrap();
        let back = io::read_mesh(&p).unwrap();
        same_mesh(&m, &back.mesh);
        assert!(back.warnings.is_empty(), "{name}: {:?}", back.warnings);
        assert_eq!(back.mesh.num_edges(), 12 + 1);
    }
    assert_eq!(files_in(&dir), ["a.ply", "b.PLY", "c.obj", "c.off"]);
    // Binary PLY: header + 8 * 24 bytes of doubles + 5 quads (1 + 16) + 2 triangles (1 + 12).
    let bytes = std::fs::read(dir.join("b.PLY")).unwrap();
    let header_end = bytes
        .windows(11)
        .position(|w| w == b"end_header\n")
        .unwrap()
        + 11;
    assert_eq!(bytes.len() - header_end, 8 * 24 + 5 * 17 + 2 * 13);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn tessellation_is_written_without_a_polymesh() {
    // Two triangles sharing an edge in the same direction: not a valid PolyMesh, but a writer
    // of plain polygons must not care.
    let dir = scratch("poly");
    let pos = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    ];
    let p = dir.join("t.obj");
    io::write_polygons(&p, &pos, &[0, 3, 6], &[0, 1, 2, 0, 1, 3], MeshFormat::Obj).unwrap();
    let text = std::fs::read_to_string(&p).unwrap();
    assert!(text.ends_with("f 1 2 3\nf 1 2 4\n"), "{text}");
    // Reading it back reports the mesh problem at the second face's line.
    match io::read_mesh(&p) {
        Err(Error::Parse { line, msg, .. }) => {
            assert_eq!(line, 7, "{msg}");
            assert!(msg.contains("inconsistent orientation"), "{msg}");
        }
        other => panic!("{other:?}"),
    }
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn failed_writes_leave_no_file() {
    let dir = scratch("fail");
    // Invalid data: checked before any file exists.
    let bad = [[0.0, 0.0, 0.0], [f64::INFINITY, 0.0, 0.0], [0.0, 1.0, 0.0]];
    for fmt in [
        MeshFormat::Obj,
        MeshFormat::Off,
        MeshFormat::PlyAscii,
        MeshFormat::PlyBinary,
    ] {
        let e = io::write_polygons(&dir.join("x.out"), &bad, &[0, 3], &[0, 1, 2], fmt).unwrap_err();
        assert!(matches!(e, Error::InvalidOutput(_)), "{e}");
    }
    let mut c = PatchComplex::new();
    c.push(
        BezierPatch::new(
            1,
            1,
            vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, f64::NAN, 0.0], [1.0; 3]],
        ),
        Provenance::Unknown,
    );
    assert!(io::write_bv(&dir.join("x.bv"), &c).is_err());
    assert!(io::write_iges(&dir.join("x.igs"), &c).is_err());
    // A closure that fails midway after writing plenty.
    let e = io::write_atomically(&dir.join("big.ply"), |w| {
        for _ in 0..64 {
            w.write_all(&[7u8; 1 << 16]).unwrap();
        }
        Err(Error::Unsupported("stop".into()))
    })
    .unwrap_err();
    assert!(matches!(e, Error::Unsupported(_)));
    assert!(files_in(&dir).is_empty(), "{:?}", files_in(&dir));
    std::fs::remove_dir_all(dir).unwrap();
}

fn complex() -> PatchComplex {
    let mut c = PatchComplex::new();
    let e = Element::Vertex(3);
    for (k, (du, dv)) in [(3, 3), (2, 4), (3, 3), (4, 4)].into_iter().enumerate() {
        let cps = (0..(du + 1) * (dv + 1))
            .map(|q| {
                let (i, j) = (q / (dv + 1), q % (dv + 1));
                [
                    i as f64 / du as f64 + k as f64,
                    j as f64 / dv as f64,
                    ((i * j) as f64 / 7.0).exp() - 1.0,
                ]
            })
            .collect();
        let prov = match k {
            0 => Provenance::Regular { face: 0 },
            1 => Provenance::Ring {
                element: e,
                ring: 1,
                sector: 2,
            },
            2 => Provenance::Ring {
                element: e,
                ring: 2,
                sector: 2,
            },
            _ => Provenance::Cap {
                element: e,
                sector: 2,
            },
        };
        c.push(BezierPatch::new(du, dv, cps), prov);
    }
    c
}

#[test]
fn bv_and_iges_roundtrip_through_files() {
    let dir = scratch("patch");
    let c = complex();
    let bv = dir.join("s.bv");
    io::write_bv(&bv, &c).unwrap();
    let f = io::read_bv(&bv).unwrap();
    assert_eq!(f.patches.patches, c.patches);
    let names: Vec<&str> = f.groups.iter().map(|g| g.name.as_str()).collect();
    assert_eq!(names, ["regular", "ring1", "ring2", "cap"]);
    let ids: Vec<i64> = f.groups.iter().map(|g| g.id).collect();
    assert_eq!(ids, [1, 2, 3, 4]);

    let igs = dir.join("s.igs");
    io::write_iges(&igs, &c).unwrap();
    let back = io::read_iges(&igs).unwrap();
    assert_eq!(back.len(), 4);
    for (a, b) in c.patches.iter().zip(&back.patches) {
        assert_eq!((a.deg_u, a.deg_v), (b.deg_u, b.deg_v));
        for (p, q) in a.cps.iter().zip(&b.cps) {
            for k in 0..3 {
                assert!(
                    (p[k] - q[k]).abs() <= 1e-12 * p[k].abs().max(1e-300),
                    "{p:?} {q:?}"
                );
            }
        }
    }
    let text = std::fs::read_to_string(&igs).unwrap();
    assert!(text.lines().all(|l| l.len() == 80));
    assert!(text.contains("5Hs.igs"), "file name in the global section");

    let net = dir.join("net.bv");
    io::write_bv_mesh(&net, &cube()).unwrap();
    let f = io::read_bv(&net).unwrap();
    let m = PolyMesh::new(f.polyhedra[0].positions.clone(), &f.polyhedra[0].faces).unwrap();
    same_mesh(&cube(), &m);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn format_choice_matches_writers() {
    assert_eq!(
        OutputFormat::choose(Path::new("a/b.ply"), None).unwrap(),
        OutputFormat::Mesh(MeshFormat::PlyBinary)
    );
    assert_eq!(
        OutputFormat::choose(Path::new("a/b.ply"), Some("Ply-Ascii")).unwrap(),
        OutputFormat::Mesh(MeshFormat::PlyAscii)
    );
    assert_eq!(MeshFormat::PlyAscii.extension(), "ply");
    assert_eq!(
        OutputFormat::choose(Path::new("b.step"), None).unwrap(),
        OutputFormat::Step
    );
    assert_eq!(
        OutputFormat::choose(Path::new("b.STP"), None).unwrap(),
        OutputFormat::Step
    );
    let e = OutputFormat::choose(Path::new("b.xyz"), None)
        .unwrap_err()
        .to_string();
    assert!(e.contains(".xyz") && e.contains("--format"), "{e}");
}

/// Deterministic mutation fuzzing: corrupted variants of valid files must give errors (or
/// valid results), never panics.
#[test]
fn mutated_inputs_never_panic() {
    let m = cube();
    let mut samples: Vec<(&str, Vec<u8>)> = Vec::new();
    for (ext, fmt) in [
        ("obj", MeshFormat::Obj),
        ("off", MeshFormat::Off),
        ("ply", MeshFormat::PlyAscii),
        ("ply", MeshFormat::PlyBinary),
    ] {
        let mut buf = Vec::new();
        io::write_polygons_to(&mut buf, m.positions(), m.face_starts(), m.corners(), fmt).unwrap();
        samples.push((ext, buf));
    }
    let c = complex();
    samples.push(("bv", io::bv_to_string(&c).unwrap().into_bytes()));
    samples.push(("igs", io::iges_to_string(&c, "f.igs").unwrap().into_bytes()));
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut rnd = move |n: usize| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state % n as u64) as usize
    };
    let alphabet = b" 0123456789-.eE,;/#\n\rHxDfvPGST";
    for (ext, base) in &samples {
        for _ in 0..1500 {
            let mut b = base.clone();
            for _ in 0..1 + rnd(4) {
                let k = rnd(b.len());
                match rnd(3) {
                    0 => b[k] = alphabet[rnd(alphabet.len())],
                    1 => {
                        b.remove(k);
                    }
                    _ => b.insert(k, alphabet[rnd(alphabet.len())]),
                }
            }
            if rnd(10) == 0 {
                b.truncate(rnd(b.len() + 1));
            }
            let path = Path::new("fuzz");
            let _ = match *ext {
                "obj" => io::obj::read_obj_from(&b[..], path).map(|_| ()),
                "off" => io::off::read_off_from(&b[..], path).map(|_| ()),
                "ply" => io::ply::read_ply_from(&b[..], path).map(|_| ()),
                "bv" => io::parse_bv(&String::from_utf8_lossy(&b), path).map(|_| ()),
                _ => io::parse_iges(&String::from_utf8_lossy(&b), path).map(|_| ()),
            };
        }
    }
}

/// One text rule for every reader (issue 20): a byte that is not UTF-8 is fine inside a
/// comment and an error naming the file, line and column elsewhere, through the public readers
/// the commands use (also the non-box OBJ and FCV readers, which used to reject the first case
/// without a line).
#[test]
fn every_reader_allows_invalid_utf8_in_comments_only() {
    let dir = scratch("utf8");
    let cube = fairsub::gallery::cube();
    let mut obj = Vec::new();
    io::write_polygons_to(
        &mut obj,
        cube.positions(),
        cube.face_starts(),
        cube.corners(),
        MeshFormat::Obj,
    )
    .unwrap();
    let mut off = Vec::new();
    io::write_polygons_to(
        &mut off,
        cube.positions(),
        cube.face_starts(),
        cube.corners(),
        MeshFormat::Off,
    )
    .unwrap();
    let mut ply = Vec::new();
    io::write_polygons_to(
        &mut ply,
        cube.positions(),
        cube.face_starts(),
        cube.corners(),
        MeshFormat::PlyAscii,
    )
    .unwrap();
    let bv = io::bv_to_string(&complex()).unwrap().into_bytes();
    // A Latin-1 comment line inserted as line 3 (`ok`), or the byte put into a digit of line
    // `at_line` of the text (`bad`).
    let with = |text: &[u8], comment: &[u8], at_line: usize| -> (Vec<u8>, Vec<u8>) {
        let mut lines: Vec<Vec<u8>> = text.split(|&b| b == b'\n').map(|l| l.to_vec()).collect();
        let mut ok = lines.clone();
        ok.insert(2, comment.to_vec());
        let target = &mut lines[at_line - 1];
        let k = target.iter().position(|b| b.is_ascii_digit()).unwrap();
        target[k] = 0xE9;
        (ok.join(&b'\n'), lines.join(&b'\n'))
    };
    let mesh_cases: [(&str, &[u8], &[u8], usize); 3] = [
        ("c.obj", &obj, b"# caf\xe9", 2),
        ("c.off", &off, b"# caf\xe9", 3),
        ("c.ply", &ply, b"comment caf\xe9", 11),
    ];
    for (name, text, comment, line) in mesh_cases {
        let (ok, bad) = with(text, comment, line);
        let p = dir.join(name);
        std::fs::write(&p, ok).unwrap();
        assert_eq!(io::read_mesh(&p).unwrap().mesh.num_faces(), 6, "{name}");
        if name == "c.obj" {
            let (_, fcvs, _) = io::fcv::read_obj_fcvs(&p).unwrap();
            assert!(fcvs.is_none());
        }
        std::fs::write(&p, bad).unwrap();
        let e = io::read_mesh(&p).unwrap_err().to_string();
        let want = format!("{}:{line}: invalid UTF-8 at column ", p.display());
        assert!(e.starts_with(&want) && e.contains("(byte 0xE9)"), "{e}");
        if name == "c.obj" {
            let e = io::fcv::read_obj_fcvs(&p).unwrap_err().to_string();
            assert!(e.starts_with(&want), "{e}");
        }
    }
    let (ok, bad) = with(&bv, b"# caf\xe9", 3);
    let p = dir.join("s.bv");
    std::fs::write(&p, ok).unwrap();
    assert_eq!(io::read_bv(&p).unwrap().patches.len(), 4);
    std::fs::write(&p, bad).unwrap();
    let e = io::read_bv(&p).unwrap_err().to_string();
    assert!(
        e.starts_with(&format!("{}:3: invalid UTF-8", p.display())),
        "{e}"
    );
    let p = dir.join("c.fcv");
    std::fs::write(&p, b"# caf\xe9\n*\n*\n*\n*\n*\n0 0 9\n").unwrap();
    let net = io::fcv::load_fcv_file(cube.clone(), &p, 1.0).unwrap();
    assert_eq!(net.fcv[5], [0.0, 0.0, 9.0]);
    std::fs::write(&p, b"*\n*\n*\n*\n*\n0 0 \xe9\n").unwrap();
    let e = io::fcv::load_fcv_file(cube, &p, 1.0)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with(&format!("{}:6: invalid UTF-8 at column 5", p.display())),
        "{e}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

/// Binary PLY errors name the file and say in words what was expected (issue 20): no line 0,
/// no raw "failed to fill whole buffer".
#[test]
fn truncated_binary_ply_names_the_file_and_the_element() {
    let dir = scratch("trunc");
    let p = dir.join("m.ply");
    io::write_mesh(&p, &cube(), MeshFormat::PlyBinary).unwrap();
    let bytes = std::fs::read(&p).unwrap();
    let header_end = bytes
        .windows(11)
        .position(|w| w == b"end_header\n")
        .unwrap()
        + 11;
    // 5.5 of the 8 vertices (24 bytes each), then inside the faces.
    for (cut, want) in [
        (
            header_end + 5 * 24 + 12,
            "binary 'vertex' data ends after 5 of the 8 elements",
        ),
        (
            bytes.len() - 1,
            "binary 'face' data ends after 6 of the 7 elements",
        ),
    ] {
        std::fs::write(&p, &bytes[..cut]).unwrap();
        let e = io::read_mesh(&p).unwrap_err().to_string();
        assert_eq!(
            e,
            format!(
                "{}: {want} the header announces (the file is truncated)",
                p.display()
            )
        );
    }
    std::fs::remove_dir_all(dir).unwrap();
}
