//! G^1 caps at extraordinary vertices next to OpenSubdiv hole faces, under Catmull-Clark and
//! Loop. A hole face is refined but has no surface, so the limit around such a vertex is its
//! smooth limit with the hole's sectors cut away: each run of `k` present faces of the `n`
//! around it is closed by an open fan over `2 pi k / n` (`bezier::g1::Fan::Wedge`) centred at
//! the vertex's plain limit point in its tangent plane, its first and last spokes free on the
//! hole's border. Until 2026-12-05 these holes kept the C^0 Hermite fill: `check` at 3 rings
//! measured 0.32 rad on the valence-12 c-net with a hole face at its centre and 1.6e-2 on
//! OpenSubdiv's `loop_holes_isolated`.
//!
//! Tests, at 1, 2 and 3 rings: every ring and regular patch is exact against the limit points
//! of uniform refinement, every join C^0 and G^1 below 1e-8 rad, no fill patch left, one wedge
//! cap per run of present faces, centred at a limit point; the probed patch table re-applies
//! to moved points.

use crate::sharp_helpers::support;

use fairsub::mesh::nets::{CnetShape, cnet, loop_net};
use fairsub::mesh::{Extras, PolyMesh};
use fairsub::surface::table::probe;
use support::{check_capped, limit_points, nearest, osd};

/// `m` with the faces at positions `which` around vertex 0 (in the order of its outgoing
/// half-edges) made holes.
fn with_holes(m: PolyMesh, which: &[usize]) -> PolyMesh {
    let hs = m.outgoing_halfedges(0);
    let holes = which.iter().map(|&i| m.he_face(hs[i])).collect();
    m.with_extras(Some(Extras {
        holes,
        ..Extras::default()
    }))
}

/// A test net: name, net, wedge caps expected.
type Net = (String, PolyMesh, usize);

/// Nets with holes at vertex 0: one face, two adjacent faces (one run each), two faces apart
/// (two runs; at `n = 3` one present face, a wedge of one sector).
fn nets(loop_: bool) -> Vec<Net> {
    let mut out = Vec::new();
    let valences: &[usize] = if loop_ { &[4, 5, 7, 8] } else { &[3, 5, 6, 8] };
    for &n in valences {
        let mut cases = vec![(vec![0], 1), (vec![0, 1], 1)];
        if n >= 4 {
            cases.push((vec![0, n / 2], 2));
        }
        for (which, runs) in cases {
            let (name, m) = if loop_ {
                (format!("loop net {n}"), loop_net(n, 3))
            } else {
                (format!("cnet-{n}-saddle"), cnet(n, CnetShape::Saddle, 3))
            };
            out.push((
                format!("{name}, holes {which:?}"),
                with_holes(m, &which),
                runs,
            ));
        }
    }
    out
}

/// Checks every net (module documentation).
fn wedges_are_capped(loop_: bool, nets: Vec<Net>) {
    for (name, m, runs) in nets {
        let (scheme, samples) = support::scheme_of(loop_, &m);
        for rings in 1..=3 {
            let what = format!("{name}, {rings} rings");
            let c = support::complex_of(loop_, &m, rings);
            let r = check_capped(&what, &m, &c, scheme.as_ref(), samples, false, false);
            assert!(r.open_sides > 0, "{what}: the holes' borders are open");
            let wedges: Vec<_> = c
                .caps
                .iter()
                .filter(|s| s.hole.kind.wedge().is_some())
                .collect();
            assert_eq!(wedges.len(), runs, "{what}: wedge caps");
            let levels = c.provenance.iter().filter_map(support::level_of).max();
            let pts = limit_points(scheme.as_ref(), &m, levels.unwrap_or(0) + 1);
            let size = probe::net_size(m.positions());
            for s in wedges {
                let d = nearest(&pts, s.hole.centre);
                assert!(d < 1e-12 * size, "{what}: centre {d:e} off the limit");
            }
        }
        let scheme_name = if loop_ { "loop" } else { "catmull-clark" };
        let in_table =
            support::table_reapplies(scheme_name, &name, &m, |h| h.kind.wedge().is_some());
        assert_eq!(in_table, runs, "{name}: wedge caps in the table");
    }
}

#[test]
fn catmull_clark_vertices_next_to_holes_get_wedge_caps() {
    wedges_are_capped(false, nets(false));
}

#[test]
fn loop_vertices_next_to_holes_get_wedge_caps() {
    let mut all = nets(true);
    // OpenSubdiv's icosahedron with two adjacent hole faces: the valence-5 vertices around
    // them lose one or two of their triangles
    all.push((
        "loop_holes_isolated".to_string(),
        osd("loop_holes_isolated"),
        4,
    ));
    wedges_are_capped(true, all);
}

/// OpenSubdiv's `loop_triangle_edgenone` under Catmull-Clark: the boundary mode `none` makes
/// holes of the faces at boundary vertices without a sharp boundary edge, so the vertices along
/// the boundary edges tagged sharp keep one or two of their three quads. Each run is a wedge of
/// the open fan (`pi / n` apart), centred at the boundary limit point: no fill patch is left
/// (the fill measured 1.4e-2 rad at 3 rings until 2026-12-07; 7.4e-14 now), every join G^1
/// below 1e-8, the table re-applies to moved points.
#[test]
fn boundary_vertices_next_to_holes_get_open_wedge_caps() {
    let name = "loop_triangle_edgenone";
    let m = osd(name);
    let (scheme, samples) = support::scheme_of(false, &m);
    let mut counts = Vec::new();
    for rings in 1..=3 {
        let what = format!("{name}, {rings} rings");
        let c = support::complex_of(false, &m, rings);
        check_capped(&what, &m, &c, scheme.as_ref(), samples, false, false);
        // the open fans' wedges: 2 n sectors in all, of them the run's
        counts.push(
            c.caps
                .iter()
                .filter(|s| s.hole.kind.wedge() == Some(6))
                .count(),
        );
    }
    assert_eq!(counts, [15, 15, 15]);
    // with the net's options, as `subdivide` reads them
    let mut spec = fairsub::schemes::registry::registry()
        .lookup("catmull-clark")
        .unwrap();
    spec.params.subd = support::file_options(&m);
    let in_table = support::spec_table_reapplies(&spec, name, &m, |h| h.kind.wedge() == Some(6));
    assert_eq!(in_table, 15);
}
