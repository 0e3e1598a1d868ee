//! G^1 caps at extraordinary boundary vertices: the open fans of `bezier::g1`
//! (`Layout::OpenQuad`) that Catmull-Clark and every scheme falling back to its loop there (EG,
//! the QAS+ family, guided subdivision and its macro variants) put into the hole at a boundary
//! vertex of `k >= 3` quads. Until 2026-12-04 these holes kept the C^0 Hermite-Coons fill
//! (6.9e-3 rad between its pieces on the L-shape, 0.34 rad on the notched c-net, 0.10 rad on
//! OpenSubdiv's `cc_boundary_valences` at 3 rings).
//!
//! Tests: `check` finds every join G^1 below 1e-8 rad, the cap C^1 to the last ring, and the
//! hole closed by an open cap (not a fill); the cap's centre is the boundary curve's limit
//! point and its tangent plane does not depend on the rings (the cross-boundary tangent is a
//! left eigenvector: a wrong mask would tilt with the level); `eval` agrees with the written
//! patches and is continuous; the patch table is tracked and re-applies to moved points.

use fairsub::analysis::continuity::check;
use fairsub::geom::{dist, norm, sub};
use fairsub::mesh::PolyMesh;
use fairsub::schemes::registry::registry;
use fairsub::surface::table::{PatchTable, probe};
use fairsub::surface::{ComplexOptions, complex};
use std::path::Path;

use crate::eval_helpers::faces;
use crate::eval_helpers::open_caps;
use crate::eval_helpers::support;
use faces::{agrees_with, largest_jump, surface_of};
use open_caps::{centre_and_normal, open_caps, table_reapplies};
use support::{irregular_boundary_nets, via_obj, written_from};

/// Catmull-Clark and the schemes that run its loop at extraordinary boundary vertices, and
/// non-box (its own open-fan cap, centred in the plane of its own local matrix).
const SCHEMES: [&str; 12] = [
    "nonbox",
    "nonbox-4dir",
    "catmull-clark",
    "eg",
    "qas-plus",
    "qas-plus-bi3",
    "qas-0.4",
    "qas-0.5-0.4",
    "guided-bi5",
    "guided-bi6",
    "guided-bi4-macro",
    "guided-bi3-macro",
];

/// The boundary vertices of more than two quads (each gets an open cap).
fn boundary_evs(m: &PolyMesh) -> Vec<usize> {
    (0..m.num_vertices())
        .filter(|&v| m.is_boundary_vertex(v) && m.vertex_faces(v).len() > 2)
        .collect()
}

/// The L-shape (one boundary vertex of 3 quads), the notched c-net (the centre, of 4 quads,
/// and the removed face's three other corners, of 3 quads each) and OpenSubdiv's
/// `cc_boundary_valences` (boundary vertices of 3 and 5 quads), with the number of open caps
/// each must get.
fn nets() -> Vec<(String, PolyMesh, usize)> {
    let p = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/osd/cc_boundary_valences.obj");
    let osd = fairsub::io::read_mesh(&p).expect("osd net").mesh;
    let out: Vec<(String, PolyMesh)> = irregular_boundary_nets()
        .into_iter()
        .map(|(n, m)| (n.to_string(), m))
        .chain([("cc_boundary_valences".to_string(), osd)])
        .collect();
    let want: Vec<usize> = out.iter().map(|(_, m)| boundary_evs(m).len()).collect();
    assert_eq!(want, [1, 4, 2]);
    out.into_iter()
        .zip(want)
        .map(|((n, m), w)| (n, m, w))
        .collect()
}

#[test]
fn every_join_is_g1_and_the_holes_get_open_caps() {
    for (name, mesh, want) in nets() {
        for scheme in SCHEMES {
            for rings in [2, 3] {
                let what = format!("{name} under {scheme}, {rings} rings");
                let c = complex(scheme, &mesh, ComplexOptions { rings, fill: true }, |_| {})
                    .unwrap_or_else(|e| panic!("{what}: {e}"));
                assert_eq!(open_caps(&c), want, "{what}: open caps");
                let r = check(&c);
                for (kind, d) in &r.by_kind {
                    assert!(
                        d.g1 < 1e-8,
                        "{what}, {kind}: G^1 {:e} at {:?}",
                        d.g1,
                        d.g1_at
                    );
                    if kind.contains("cap")
                        && kind.contains("ring")
                        && !scheme.starts_with("nonbox")
                    {
                        // C^1 to the last ring (the two outer layers are the ring's; non-box's
                        // ring triangles are collapsed bi-3 patches, C^1 only in the cells'
                        // chart, so there G^1 is the measure)
                        assert!(d.c1 < 1e-10, "{what}, {kind}: C^1 {:e}", d.c1);
                    }
                }
                assert!(
                    r.by_kind.iter().any(|(k, _)| k == "cap|cap"),
                    "{what}: no join inside a cap"
                );
            }
        }
    }
}

#[test]
fn the_cap_sits_at_the_limit_point_in_one_tangent_plane_at_every_level() {
    for (name, mesh, _) in nets() {
        for x in boundary_evs(&mesh) {
            for scheme in ["catmull-clark", "nonbox"] {
                centre_and_plane(scheme, &name, &mesh, x);
            }
        }
    }
}

fn centre_and_plane(scheme: &str, name: &str, mesh: &PolyMesh, x: usize) {
    {
        let nb = mesh.vertex_neighbors(x);
        let pos = mesh.positions();
        let (a, b) = (pos[nb[0] as usize], pos[*nb.last().unwrap() as usize]);
        // the boundary curve is the cubic B-spline of the boundary polygon
        let limit: [f64; 3] = std::array::from_fn(|i| (a[i] + 4.0 * pos[x][i] + b[i]) / 6.0);
        let mut normals = Vec::new();
        for rings in [1, 2, 3, 5, 7] {
            let c = complex(scheme, mesh, ComplexOptions { rings, fill: true }, |_| {})
                .expect("complex");
            let (centre, n) = centre_and_normal(&c, limit);
            assert!(
                dist(centre, limit) < 1e-13,
                "{name} under {scheme}, vertex {x}, {rings} rings: centre"
            );
            // the normal is perpendicular to the boundary curve's tangent at the centre
            assert!(
                fairsub::geom::dot(n, sub(a, b)).abs() < 1e-12 * norm(sub(a, b)),
                "{name} under {scheme}, {rings} rings: boundary tangent not in the plane"
            );
            normals.push(n);
        }
        for n in &normals[1..] {
            assert!(
                dist(*n, normals[0]) < 1e-12,
                "{name} under {scheme}: the tangent plane moves with the level: {n:?} against {:?}",
                normals[0]
            );
        }
    }
}

#[test]
fn eval_agrees_with_the_written_caps() {
    for (name, mesh) in irregular_boundary_nets() {
        let (mesh, src) = via_obj(&mesh, &format!("open-{name}"));
        for scheme in ["catmull-clark", "eg", "guided-bi3-macro", "nonbox"] {
            let written = written_from(&src, name, scheme, 3);
            assert_eq!(
                open_caps(&written),
                0,
                "a .bv file does not keep the cap steps"
            );
            let want = boundary_evs(&mesh).len();
            let (mesh, s) = surface_of(mesh.clone(), scheme, 3);
            assert_eq!(open_caps(s.complex()), want, "{name} under {scheme}");
            let (worst, in_caps) = agrees_with(&written, &mesh, &s, &|_, _| true);
            let jump = largest_jump(&mesh, &s, 1 << 6, 1e-10, &|_, _| true);
            eprintln!(
                "{name} under {scheme}: largest difference {worst:.3e}, {in_caps} points on \
                 caps, largest jump {jump:.3e}"
            );
            assert!(worst <= 1e-12, "{name} under {scheme}: {worst:e}");
            assert!(in_caps > 0, "{name} under {scheme}: no point on a cap");
            assert!(jump < 1e-7, "{name} under {scheme}: jump {jump:e}");
        }
    }
}

#[test]
fn patch_tables_track_open_caps_and_reapply() {
    let spec = registry().lookup("catmull-clark").expect("registered");
    for (name, mesh, want) in nets() {
        for rings in [2, 3] {
            let what = format!("{name}, {rings} rings");
            let opts = ComplexOptions { rings, fill: true };
            let (base, table) = PatchTable::tracked(&spec, &mesh, opts)
                .expect(&what)
                .unwrap_or_else(|| panic!("{what}: not tracked"));
            let open = table
                .caps()
                .iter()
                .filter(|c| c.step.hole.is_open())
                .count();
            assert_eq!(open, want, "{what}: open caps in the table");
            let s = probe::net_size(mesh.positions());
            for seed in [3, 4] {
                let moved = probe::moved_points(mesh.positions(), 0.05 * s, seed);
                let mut m = mesh.clone();
                m.set_positions(moved.clone());
                let truth = fairsub::surface::build(&spec, &m, opts, &mut |_| {})
                    .expect(&what)
                    .complex;
                let got = table.apply(&moved).expect(&what);
                let (d, _) = probe::max_deviation(&got, &truth);
                assert!(d <= 1e-12 * s, "{what}: moved points (seed {seed}) {d:.3e}");
                let mut reused = base.clone();
                table.apply_into(&moved, &mut reused).expect(&what);
                assert!(reused.patches == got.patches, "{what}: apply_into");
            }
        }
    }
}

/// Non-box's tables are probed (its construction is not tracked); the open caps' steps go
/// through them like the closed ones.
#[test]
fn nonbox_tables_reapply_with_open_caps() {
    for (name, mesh, want) in nets() {
        table_reapplies("nonbox", &name, &mesh, want, 9);
    }
}
