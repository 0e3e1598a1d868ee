//! G^1 caps at Catmull-Clark's crease vertices: an extraordinary interior vertex with two
//! infinitely sharp edges (OpenSubdiv's crease rule). Each side of `k >= 3` quads is closed by
//! an open-fan cap in the plane of the crease tangent and the side's across-boundary eigen
//! tangent, its boundary spokes the crease's exact cubic curve (`bezier::g1::fairsub::bezier::g1::Fan::Crease`); a
//! side of two quads is regular crease patches, a side of one quad a crease fan of one sector
//! (its spokes the crease's two halves). Until 2026-12-04 these holes kept the C^0
//! Hermite fill: `check` at 3 rings measured 4.5e-2 rad between its pieces on OpenSubdiv's
//! `cc_crease_extraordinary`.
//!
//! Tests, at 1, 2 and 3 rings: every ring and regular patch is exact against the limit points
//! of uniform refinement, every join C^0 (the crease too: both sides share the crease curve),
//! every join but the crease's G^1 below 1e-8 rad, no fill patch left, one crease cap per side
//! of three or more quads, its centre the crease's limit point and its boundary spokes on the
//! crease's limit curve; the probed patch table re-applies to moved points.

use crate::sharp_helpers::support;

use fairsub::bezier::complex::PatchComplex;
use fairsub::geom::dist;
use fairsub::host::ComplexOptions;
use fairsub::mesh::nets::{CnetShape, cnet, loop_net};
use fairsub::mesh::{Extras, PolyMesh, SharpEdges};
use fairsub::schemes::Scheme;
use fairsub::schemes::catmull_clark::Configured;
use fairsub::schemes::catmull_clark::surface::catmull_clark_complex_with;
use fairsub::schemes::loop_subdivision::Configured as LoopConfigured;
use fairsub::schemes::loop_subdivision::surface::loop_complex_with;
use fairsub::schemes::registry::registry;
use fairsub::surface::table::{PatchTable, probe};
use support::{
    check_capped, file_options, limit_points, nearest, osd, quad_samples, triangle_samples,
};

/// The c-net of valence `n` (3 rings) with an infinitely sharp crease through its centre along
/// its spokes `0` and `j` ([`creased`]).
fn creased_cnet(n: usize, j: usize, shape: CnetShape) -> PolyMesh {
    creased(cnet(n, shape, 3), j)
}

/// `m` with an infinitely sharp crease through vertex 0 along its spokes `0` and `j`, each
/// continued straight (across regular vertices: valence 4 for quads, 6 for triangles) to the
/// boundary.
fn creased(m: PolyMesh, j: usize) -> PolyMesh {
    let pairs = support::sharp_chains(&m, &[0, j]);
    m.with_extras(Some(Extras {
        sharp_edges: SharpEdges::ByPair(pairs),
        ..Extras::default()
    }))
}

/// The nets: name, net, crease caps expected (sides of three or more quads).
fn nets() -> Vec<(String, PolyMesh, usize)> {
    let mut out = vec![(
        "cc_crease_extraordinary".to_string(),
        osd("cc_crease_extraordinary"),
        1,
    )];
    // the cube with its top face's edge loop creased: four crease vertices of valence 3, one
    // face on the top side (a crease fan of one sector each), two regular crease patches below
    let loop4 = [[4, 5], [5, 7], [7, 6], [6, 4]]
        .map(|e| (e, 10.0f32))
        .to_vec();
    let cube = osd("cc_cube_infsharp").with_extras(Some(Extras {
        sharp_edges: SharpEdges::ByPair(loop4),
        ..Extras::default()
    }));
    out.push(("cube, top loop creased".to_string(), cube, 4));
    for (n, j, caps) in [
        (5, 2, 1),
        (6, 3, 2),
        (6, 2, 1),
        (7, 3, 2),
        (8, 4, 2),
        (9, 3, 2),
    ] {
        for shape in [CnetShape::Convex, CnetShape::Saddle] {
            let name = format!("cnet-{n}-{} creased 0/{j}", shape.name());
            out.push((name, creased_cnet(n, j, shape), caps));
        }
    }
    out
}

/// Checks the complex `c` of `m` (`what`): rings and regular patches exact against `scheme`'s
/// limit points (`samples` its parameter lattice), every join C^0, the crease sharp, every
/// other join G^1 below 1e-8 rad, no fill patch, `want` crease caps, each centred at the
/// crease's limit point with its boundary spokes on the crease's limit curve.
fn check_crease_complex(
    what: &str,
    m: &PolyMesh,
    c: &PatchComplex,
    scheme: &dyn Scheme,
    samples: fn(usize) -> Vec<(f64, f64)>,
    want: usize,
) {
    check_capped(what, m, c, scheme, samples, false, true);
    let creases: Vec<_> = c
        .caps
        .iter()
        .filter(|s| s.hole.kind == fairsub::bezier::g1::Fan::Crease)
        .collect();
    assert_eq!(creases.len(), want, "{what}: crease caps");
    let levels = c.provenance.iter().filter_map(support::level_of).max();
    let pts = limit_points(scheme, m, levels.unwrap_or(0) + 2);
    let size = probe::net_size(m.positions());
    for s in creases {
        let d = nearest(&pts, s.hole.centre);
        assert!(d < 1e-12 * size, "{what}: centre {d:e} off the limit");
        // the boundary spokes run on the crease's limit curve: their points at the dyadic
        // parameters of two more levels are limit points
        let (first, last) = (s.first as usize, (s.first + s.count - 1) as usize);
        for t in [0.25, 0.5, 0.75] {
            for p in [c.patches[first].eval(t, 0.0), c.patches[last].eval(0.0, t)] {
                let d = nearest(&pts, p);
                assert!(d < 1e-11 * size, "{what}: crease spoke {d:e} off the limit");
            }
        }
        let d = dist(c.patches[first].eval(0.0, 0.0), s.hole.centre);
        assert!(d < 1e-14 * size, "{what}");
    }
}

#[test]
fn crease_vertices_get_one_g1_cap_per_side_sharing_the_crease() {
    for (name, m, want) in nets() {
        let subd = file_options(&m);
        let scheme = Configured { options: subd };
        for rings in [1, 2, 3] {
            let what = format!("{name}, {rings} rings");
            let opts = ComplexOptions { rings, fill: true };
            let c = catmull_clark_complex_with(&m, opts, subd, |_| {}).expect(&what);
            check_crease_complex(&what, &m, &c, &scheme, quad_samples, want);
        }
    }
}

/// Loop: each side of one, two, or four and more triangles is an open triangle fan on the
/// crease, a side of three triangles regular crease patches.
#[test]
fn loop_crease_vertices_get_one_g1_cap_per_side_sharing_the_crease() {
    for (n, j, want) in [
        (5, 2, 1),
        (5, 3, 1),
        (6, 2, 2),
        (7, 3, 1),
        (8, 4, 2),
        (8, 2, 2),
        (9, 4, 2),
        (4, 1, 1),
    ] {
        let m = creased(loop_net(n, 3), j);
        let subd = file_options(&m);
        let scheme = LoopConfigured { options: subd };
        for rings in [1, 2, 3] {
            let what = format!("loop net {n} creased 0/{j}, {rings} rings");
            let opts = ComplexOptions { rings, fill: true };
            let c = loop_complex_with(&m, opts, subd, |_| {}).expect(&what);
            check_crease_complex(&what, &m, &c, &scheme, triangle_samples, want);
        }
    }
}

#[test]
fn crease_caps_reapply_through_the_patch_table() {
    for (name, m, _) in nets().into_iter().step_by(3) {
        let creases = support::table_reapplies("catmull-clark", &name, &m, |h| {
            h.kind == fairsub::bezier::g1::Fan::Crease
        });
        assert!(creases > 0, "{name}: crease caps in the table");
    }
}

/// A boundary vertex of one quad under the crease rule (edge-only boundary interpolation) is a
/// crease fan of one sector: C^1 to its ring, its spokes the boundary curve's two halves (exact
/// limit points), no fill left. Until 2026-12-05 the fill: 4.0e-3 rad to the ring on
/// `cc_boundary_edgeonly_tag` at 1 ring, 5.2e-4 on `cc_boundary_tags`.
#[test]
fn edge_only_boundary_corners_get_one_piece_caps_on_the_boundary_curve() {
    for name in ["cc_boundary_edgeonly_tag", "cc_boundary_tags"] {
        let m = osd(name);
        let subd = file_options(&m);
        let scheme = Configured { options: subd };
        for rings in [1, 2, 3] {
            let what = format!("{name}, {rings} rings");
            let opts = ComplexOptions { rings, fill: true };
            let c = catmull_clark_complex_with(&m, opts, subd, |_| {}).expect(&what);
            check_capped(&what, &m, &c, &scheme, quad_samples, false, false);
            let corners: Vec<_> = c
                .caps
                .iter()
                .filter(|s| s.hole.kind == fairsub::bezier::g1::Fan::Crease && s.count == 1)
                .collect();
            assert!(!corners.is_empty(), "{what}: no one-piece cap");
            let levels = c.provenance.iter().filter_map(support::level_of).max();
            let pts = limit_points(&scheme, &m, levels.unwrap_or(0) + 2);
            for s in corners {
                let p = &c.patches[s.first as usize];
                for t in [0.0, 0.25, 0.5, 0.75, 1.0] {
                    for x in [p.eval(t, 0.0), p.eval(0.0, t)] {
                        let d = nearest(&pts, x);
                        assert!(d < 1e-11, "{what}: boundary {d:e} off the limit");
                    }
                }
            }
        }
    }
}

/// `subdivide --stencils` writes crease fans with their own FAN word, and the file reads back
/// with one cap line per cap of the table.
#[test]
fn the_stencil_file_names_crease_fans_and_reads_back() {
    let dir = std::env::temp_dir().join(format!("fairsub-crease-tab-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (bv, tab) = (dir.join("c.bv"), dir.join("c.tab"));
    let net = support::osd_path("cc_crease_extraordinary");
    let args = [
        "subdivide",
        &net,
        "-s",
        "catmull-clark",
        "--rings",
        "2",
        "-o",
    ];
    let (bv_s, tab_s) = (bv.to_str().unwrap(), tab.to_str().unwrap());
    let (code, _, err) = support::run(&[&args[..], &[bv_s, "--stencils", tab_s]].concat());
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&tab).unwrap();
    let creases = text
        .lines()
        .filter(|l| l.starts_with("c ") && l.split_whitespace().nth(7) == Some("crease"))
        .count();
    assert_eq!(creases, 1, "one crease fan");
    let file = fairsub::io::table::read_table(&tab).unwrap();
    let spec = registry().lookup("catmull-clark").unwrap();
    let opts = ComplexOptions {
        rings: 2,
        fill: true,
    };
    let table = PatchTable::build(&spec, &osd("cc_crease_extraordinary"), opts).unwrap();
    assert_eq!(file.caps.len(), table.caps().len());
    assert_eq!(&file.rows, table.rows());
    std::fs::remove_dir_all(&dir).ok();
}
