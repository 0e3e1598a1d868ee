//! Patch stencil tables (`fairsub::surface::table`): for every scheme in the registry that
//! writes patches, over gallery nets, the table re-applied to randomly moved control points
//! equals the complex the construction computes from the moved net to 1e-12 (same patches in
//! the same order, degrees, provenance, domains, coefficients); per-point data of other
//! dimensions go through the same rows; `subdivide --stencils` writes the table that reads back
//! equal to the library's.

use fairsub::PolyMesh;
use fairsub::schemes::registry::registry;
use fairsub::surface::table::{PatchTable, probe};
use fairsub::surface::{ComplexOptions, PatchComplex};
use rayon::prelude::*;

/// The gallery nets the tables are checked on (each scheme takes some of them).
const NETS: &[&str] = &[
    "cube",
    "torus-evs",
    "prism-5",
    "cnet-3-saddle",
    "cnet-5-convex",
    "cnet-6-raised",
    "open-grid",
    "tetrahedron",
    "icosahedron",
    "tri-grid",
    "nonbox-cube-fcv-1.5",
];

/// Largest coefficient difference, after asserting the same structure.
fn deviation(what: &str, a: &PatchComplex, b: &PatchComplex) -> f64 {
    assert_eq!(a.len(), b.len(), "{what}: patch counts");
    assert_eq!(a.provenance, b.provenance, "{what}: provenance");
    assert_eq!(a.domains, b.domains, "{what}: domains");
    assert_eq!(a.pieces, b.pieces, "{what}: pieces");
    assert_eq!(a.sharp_sides, b.sharp_sides, "{what}: sharp sides");
    let mut worst: f64 = 0.0;
    for (i, (p, q)) in a.patches.iter().zip(&b.patches).enumerate() {
        assert_eq!(
            (p.deg_u, p.deg_v),
            (q.deg_u, q.deg_v),
            "{what}: degrees of patch {i}"
        );
        for (x, y) in p.cps.iter().zip(&q.cps) {
            for k in 0..3 {
                worst = worst.max((x[k] - y[k]).abs());
            }
        }
    }
    worst
}

fn net(name: &str) -> PolyMesh {
    fairsub::gallery::all()
        .into_iter()
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no gallery net {name}"))
        .1
}

#[test]
fn every_scheme_reapplies_to_moved_points() {
    let opts = ComplexOptions {
        rings: 2,
        fill: true,
    };
    // one scheme per task, on the machine's threads (the schemes are independent)
    let entries: Vec<_> = registry()
        .entries()
        .iter()
        .filter(|e| e.capabilities().patches)
        .collect();
    let results: Vec<(String, Vec<String>)> = entries
        .par_iter()
        .map(|e| {
            let spec = registry().lookup(e.name).expect("registered");
            let (mut tested, mut caps, mut failures) = (0, 0, Vec::new());
            for &name in NETS {
                let mesh = net(name);
                if e.descriptor.check_input(&mesh).is_err() {
                    continue;
                }
                let Ok(base) = fairsub::surface::build(&spec, &mesh, opts, &mut |_| {}) else {
                    continue;
                };
                let what = format!("{} on {name}", e.name);
                match assert_reapplies(&spec, &mesh, opts, &base.complex, &what) {
                    Ok(table) => {
                        caps += table.caps().len();
                        tested += 1;
                    }
                    Err(err) => failures.push(err),
                }
            }
            assert!(tested > 0, "{}: no gallery net tested", e.name);
            (
                format!("{} ({tested} nets, {caps} G^1 caps)", e.name),
                failures,
            )
        })
        .collect();
    let summary: Vec<String> = results.iter().map(|(s, _)| s.clone()).collect();
    let failures: Vec<String> = results.into_iter().flat_map(|(_, f)| f).collect();
    eprintln!("patch tables checked: {}", summary.join(", "));
    // Every gallery net gets its table: non-box's Hermite fill at an extraordinary boundary
    // vertex (tri-grid's corners), which projects a chord onto the limit tangent plane and is
    // not linear, gave way to the open-fan cap on 2026-12-04 (the refusal is tested on a fan
    // of more quads than a cap takes, `cli_writes_the_table_the_library_builds`).
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    assert_eq!(summary.len(), registry().names_with(|c| c.patches).len());
}

/// Builds the table of `spec` on `mesh` and asserts that it reproduces `base` (the complex
/// of `mesh`) and, applied to moved points, the complex built from them (1e-12); `Err` when
/// the table cannot be built.
fn assert_reapplies(
    spec: &fairsub::schemes::Spec,
    mesh: &PolyMesh,
    opts: ComplexOptions,
    base: &PatchComplex,
    what: &str,
) -> Result<PatchTable, String> {
    let table = PatchTable::build(spec, mesh, opts).map_err(|err| format!("{what}: {err}"))?;
    assert_eq!(table.num_sources(), mesh.num_vertices(), "{what}");
    // at the net's own points: the complex itself
    let again = table.apply(mesh.positions()).expect("apply");
    let d0 = deviation(what, &again, base);
    assert!(d0 < 1e-12, "{what}: at the net's points {d0:e}");
    for (seed, size) in [(7u64, 0.1), (11, 0.3)] {
        let pts = probe::moved_points(mesh.positions(), size, seed);
        let mut m = mesh.clone();
        m.set_positions(pts.clone());
        let truth = fairsub::surface::build(spec, &m, opts, &mut |_| {})
            .unwrap_or_else(|err| panic!("{what} moved: {err}"));
        let got = table.apply(&pts).expect("apply to moved points");
        let d = deviation(what, &got, &truth.complex);
        assert!(d < 1e-12, "{what}: moved by {size}: deviation {d:e}");
        // into the complex at the net's points, its storage reused: the same bits
        let mut reused = again.clone();
        table.apply_into(&pts, &mut reused).expect("apply_into");
        assert_same(what, &reused, &got);
    }
    Ok(table)
}

/// The half-plane caps of valence-2 vertices are re-applied like every other cap: the
/// split-edge cube under Catmull-Clark (and EG, guided subdivision on its rings) and non-box,
/// the octahedron under `nonbox-4dir`.
#[test]
fn two_sector_caps_reapply_to_moved_points() {
    let opts = ComplexOptions {
        rings: 3,
        fill: true,
    };
    let cube = fairsub::gallery::split_edge_cube();
    let oct = net("octahedron");
    for (scheme, mesh) in [
        ("catmull-clark", &cube),
        ("eg", &cube),
        ("guided-bi5", &cube),
        ("nonbox", &cube),
        ("nonbox-4dir", &oct),
    ] {
        let spec = registry().lookup(scheme).expect("registered");
        let base = fairsub::surface::build(&spec, mesh, opts, &mut |_| {}).expect("complex");
        let what = format!("{scheme} (valence 2)");
        let table = assert_reapplies(&spec, mesh, opts, &base.complex, &what).unwrap();
        let pairs = base.complex.caps.iter().filter(|c| c.hole.valence() == 2);
        assert!(pairs.count() > 0, "{what}: no two-sector cap");
        assert!(!table.caps().is_empty(), "{what}");
    }
}

#[test]
fn per_point_data_go_through_the_same_rows() {
    let opts = ComplexOptions {
        rings: 2,
        fill: true,
    };
    let mesh = net("torus-evs");
    for scheme in ["catmull-clark", "eg", "doo-sabin"] {
        let spec = registry().lookup(scheme).unwrap();
        let table = PatchTable::build(&spec, &mesh, opts).unwrap();
        // 5-dimensional data: x, y, z, then two more values per point
        let d = 5;
        let data: Vec<f64> = mesh
            .positions()
            .iter()
            .enumerate()
            .flat_map(|(i, p)| [p[0], p[1], p[2], i as f64, (i as f64).sin()])
            .collect();
        let out = table.apply_data(&data, d).unwrap();
        assert_eq!(out.len(), table.num_patches());
        // a datum equal to a linear function of the points maps to that function of the
        // patches wherever the patch is linear; every coefficient is an affine combination
        let pos = table.apply(mesh.positions()).unwrap();
        for (p, (o, q)) in out.iter().zip(&pos.patches).enumerate() {
            assert_eq!(o.len(), q.cps.len() * d);
            if table.is_cap_patch(p) {
                continue;
            }
            for (k, c) in q.cps.iter().enumerate() {
                for j in 0..3 {
                    assert!((o[k * d + j] - c[j]).abs() < 1e-12, "{scheme} patch {p}");
                }
            }
        }
        // constant data stay constant everywhere, caps included (affine rows, affine cap map)
        let ones = vec![2.5; mesh.num_vertices()];
        for (p, o) in table.apply_data(&ones, 1).unwrap().iter().enumerate() {
            for x in o {
                assert!((x - 2.5).abs() < 1e-11, "{scheme} patch {p}: {x}");
            }
        }
    }
}

#[test]
fn data_of_dimension_three_equal_positions_except_in_caps() {
    // without caps (EG's rings, no fill: every step linear) apply_data on the positions is
    // apply
    let opts = ComplexOptions {
        rings: 2,
        fill: false,
    };
    let mesh = net("cnet-5-saddle");
    let spec = registry().lookup("eg").unwrap();
    let table = PatchTable::build(&spec, &mesh, opts).unwrap();
    assert!(table.caps().is_empty());
    let flat: Vec<f64> = mesh.positions().iter().flatten().copied().collect();
    let out = table.apply_data(&flat, 3).unwrap();
    let pos = table.apply(mesh.positions()).unwrap();
    for (o, q) in out.iter().zip(&pos.patches) {
        let f: Vec<f64> = q.cps.iter().flatten().copied().collect();
        assert_eq!(o, &f);
    }
}

#[test]
fn wrong_sizes_are_errors() {
    let opts = ComplexOptions {
        rings: 1,
        fill: true,
    };
    let mesh = net("cube");
    let spec = registry().lookup("catmull-clark").unwrap();
    let table = PatchTable::build(&spec, &mesh, opts).unwrap();
    let e = table.apply(&mesh.positions()[1..]).unwrap_err().to_string();
    assert!(e.contains("takes 8 points, not 7"), "{e}");
    let e = table.apply_data(&[0.0; 9], 2).unwrap_err().to_string();
    assert!(e.contains("16 values, not 9"), "{e}");
}

fn fairsub_cli(args: &[&str]) -> (i32, String) {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_fairsub"))
        .args(args)
        .output()
        .unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// An OBJ net: `k` quads around a boundary vertex on a curved half-disc.
fn open_fan_obj(k: usize) -> String {
    let mut out = String::from("v 0 0 0\n");
    for i in 0..=2 * k {
        let t = std::f64::consts::PI * i as f64 / (2 * k) as f64;
        let r = if i % 2 == 0 { 1.0 } else { 1.4 };
        let z = 0.1 * (3.0 * t).sin();
        out += &format!("v {} {} {z}\n", r * t.cos(), r * t.sin());
    }
    for j in 0..k {
        out += &format!("f 1 {} {} {}\n", 2 * j + 2, 2 * j + 3, 2 * j + 4);
    }
    out
}

#[test]
fn cli_writes_the_table_the_library_builds() {
    let dir = std::env::temp_dir().join(format!("fairsub-table-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (bv, tab) = (dir.join("s.bv"), dir.join("s.tab"));
    let (bv_s, tab_s) = (bv.to_str().unwrap(), tab.to_str().unwrap());
    for (scheme, net) in [
        ("catmull-clark", "torus-evs"),
        ("pgs", "prism-5"),
        ("eg", "cnet-5-saddle"),
    ] {
        let gnet = format!("gallery:{net}");
        let (code, err) = fairsub_cli(&[
            "subdivide",
            &gnet,
            "--scheme",
            scheme,
            "--rings",
            "2",
            "-o",
            bv_s,
            "--stencils",
            tab_s,
        ]);
        assert_eq!(code, 0, "{err}");
        assert!(err.contains("wrote the patch table"), "{err}");
        let file = fairsub::io::table::read_table(&tab).unwrap();
        let spec = registry().lookup(scheme).unwrap();
        let opts = ComplexOptions {
            rings: 2,
            fill: true,
        };
        let table = PatchTable::build(&spec, &net_named(net), opts).unwrap();
        // the same rows, weight for weight (shortest round-trip numbers read back exactly)
        assert_eq!(&file.rows, table.rows(), "{scheme}");
        assert_eq!(file.patches.len(), table.num_patches());
        for (p, &(du, dv, first, cap)) in file.patches.iter().enumerate() {
            assert_eq!((du, dv), table.shapes()[p]);
            assert_eq!(first as usize, table.first_row(p));
            assert_eq!(cap, table.is_cap_patch(p));
        }
        assert_eq!(file.caps.len(), table.caps().len());
        // the .bv written beside it is the table applied to the net's points
        let written = fairsub::io::read_bv(&bv).unwrap();
        let again = table.apply(net_named(net).positions()).unwrap();
        let from_bv = fairsub::render::complex_from_bv(&written);
        let mut worst: f64 = 0.0;
        for (a, b) in from_bv.patches.iter().zip(&again.patches) {
            for (x, y) in a.cps.iter().zip(&b.cps) {
                worst = worst.max(fairsub::geom::dist(*x, *y));
            }
        }
        assert_eq!(from_bv.len(), again.len());
        assert!(worst < 1e-12, "{scheme}: .bv against the table {worst:e}");
    }
    // refused without --rings, nothing written
    let other = dir.join("t.tab");
    let (code, err) = fairsub_cli(&[
        "subdivide",
        "gallery:cube",
        "--scheme",
        "catmull-clark",
        "--levels",
        "1",
        "-o",
        dir.join("r.obj").to_str().unwrap(),
        "--stencils",
        other.to_str().unwrap(),
    ]);
    assert_ne!(code, 0);
    assert!(
        err.contains("--stencils writes the patch table of a complex"),
        "{err}"
    );
    assert!(!other.exists());
    // a table the construction cannot give (non-box's fill at a boundary vertex of more quads
    // than a G^1 cap takes projects onto a plane): an error naming the patch, nothing written
    let fan = dir.join("fan.obj");
    std::fs::write(&fan, open_fan_obj(fairsub::bezier::g1::MAX_CAP_VALENCE + 1)).unwrap();
    let (code, err) = fairsub_cli(&[
        "subdivide",
        fan.to_str().unwrap(),
        "--scheme",
        "nonbox",
        "--rings",
        "2",
        "-o",
        bv_s,
        "--stencils",
        other.to_str().unwrap(),
    ]);
    assert_ne!(code, 0);
    assert!(
        err.contains("not linear") && err.contains("cap of vertex"),
        "{err}"
    );
    assert!(!other.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn table_files_are_validated() {
    let dir = std::env::temp_dir().join(format!("fairsub-table-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("bad.tab");
    let good = "fairsub-patch-table 2\nsources 2\npatches 1\nrows 4\nentries 4\ncaps 0\ncapmaps 0\nconstants 0\np 1 1 0 linear regular\nr 1 0 1\nr 1 1 1\nr 1 0 1\nr 1 1 1\nend\n";
    std::fs::write(&p, good).unwrap();
    let t = fairsub::io::table::read_table(&p).unwrap();
    assert_eq!(t.rows.num_rows(), 4);
    for (bad, want) in [
        (
            good.replace("r 1 1 1\nend", "r 1 2 1\nend"),
            ":13: bad source 2",
        ),
        (good.replace("entries 4", "entries 5"), "entries, not 5"),
        (
            good.replace("p 1 1 0", "p 1 1 2"),
            ":9: patch rows out of range",
        ),
        (good.replace("end\n", ""), "missing"),
        (
            good.replace("fairsub-patch-table 2", "fairsub-patch-table 1"),
            ":1: expected",
        ),
    ] {
        std::fs::write(&p, &bad).unwrap();
        let e = fairsub::io::table::read_table(&p).unwrap_err().to_string();
        assert!(e.contains(want), "{want}: {e}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

fn net_named(name: &str) -> PolyMesh {
    net(name)
}

/// `a` and `b` are the same complex, bit for bit (patches, caps, provenance, domains).
fn assert_same(what: &str, a: &PatchComplex, b: &PatchComplex) {
    assert!(a.patches == b.patches, "{what}: patches differ");
    assert!(a.caps == b.caps, "{what}: caps differ");
    assert!(a.provenance == b.provenance, "{what}: provenance differs");
    assert!(a.domains == b.domains, "{what}: domains differ");
    assert!(a.pieces == b.pieces, "{what}: pieces differ");
    assert!(a.sharp_sides == b.sharp_sides, "{what}: sharp sides differ");
}

/// `apply_into` refuses a complex of other shapes and writes nothing then.
#[test]
fn apply_into_refuses_another_complex() {
    let spec = registry().lookup("catmull-clark").expect("registered");
    let opts = ComplexOptions {
        rings: 2,
        fill: true,
    };
    let (cube, prism) = (net("cube"), net("prism-5"));
    let table = PatchTable::build(&spec, &cube, opts).expect("table");
    let other = fairsub::surface::build(&spec, &prism, opts, &mut |_| {})
        .expect("prism")
        .complex;
    let mut target = other.clone();
    let e = table
        .apply_into(cube.positions(), &mut target)
        .expect_err("another net's complex")
        .to_string();
    assert!(e.contains("not this table's"), "{e}");
    assert!(target.patches == other.patches, "nothing written");
    let mut own = table.apply(cube.positions()).expect("apply");
    let e = table
        .apply_into(&cube.positions()[1..], &mut own)
        .expect_err("one point short")
        .to_string();
    assert!(e.contains("takes 8 points"), "{e}");
}
