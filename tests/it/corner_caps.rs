//! G^1 caps at Catmull-Clark's and Loop's corners with sharp edges: an interior vertex with three or more
//! infinitely sharp edges, or of infinite sharpness with two (OpenSubdiv's corner rule: the
//! vertex is its own limit). Each side of two or more quads between consecutive sharp edges is
//! closed by an open fan (`bezier::g1::Fan::Corner`) centred at the vertex, its spokes over a
//! quarter-turn (three quarters on a reflex side), its boundary spokes the sharp edges' exact
//! limit curves (`T0, T1` their derivatives at the corner, pinned), so every side shares its
//! sharp edges with its neighbours. Until 2026-12-05 these holes kept the C^0 Hermite fill.
//!
//! Tests, at 1, 2 and 3 rings: every ring and regular patch is exact against the limit points
//! of uniform refinement, every join C^0 (the sharp ones too), every join but the sharp ones
//! G^1 below 1e-8 rad, no fill patch left, one corner cap per side of two or more quads,
//! centred at the corner with its boundary spokes on the sharp edges' limit curves, and no
//! side folded over (the caps' normals at the corner turn the way the ring does); the probed
//! patch table re-applies to moved points.

use crate::sharp_helpers::support;

use fairsub::geom::{cross, dot};
use fairsub::mesh::nets::{CnetShape, cnet, loop_net};
use fairsub::mesh::{Extras, PolyMesh, SharpEdges};
use fairsub::surface::table::probe;
use support::{check_capped, limit_points, nearest, sharp_chains, table_reapplies};

/// `m` with sharp chains along the spokes `spokes` of its vertex 0, which is of infinite
/// sharpness when `tagged`.
fn cornered(m: PolyMesh, spokes: &[usize], tagged: bool) -> PolyMesh {
    let pairs = sharp_chains(&m, spokes);
    m.with_extras(Some(Extras {
        sharp_edges: SharpEdges::ByPair(pairs),
        sharp_vertices: if tagged { vec![(0, 10.0)] } else { Vec::new() },
        ..Extras::default()
    }))
}

/// The nets: name, net, corner caps expected (sides of two or more faces).
fn nets(loop_: bool) -> Vec<(String, PolyMesh, usize)> {
    let mut out = Vec::new();
    if loop_ {
        for (n, spokes, tagged, caps) in [
            // the side of one triangle is a regular corner patch
            (5, vec![0, 2, 3], false, 2),
            (7, vec![0, 2, 4], false, 3),
            (8, vec![0, 3, 5], false, 3),
            (4, vec![0, 1], true, 1),
            (9, vec![0, 4], true, 2),
        ] {
            let name = format!(
                "loop net {n} sharp {spokes:?}{}",
                if tagged { ", tag" } else { "" }
            );
            out.push((name, cornered(loop_net(n, 3), &spokes, tagged), caps));
        }
        return out;
    }
    for (n, spokes, tagged, caps) in [
        (6, vec![0, 2, 4], false, 3),
        (7, vec![0, 2, 4], false, 3),
        (8, vec![0, 3, 5], false, 3),
        (9, vec![0, 1, 4, 6], false, 3),
        (5, vec![0, 2], true, 2),
        (12, vec![0, 5], true, 2),
    ] {
        for shape in [CnetShape::Convex, CnetShape::Saddle] {
            let name = format!(
                "cnet-{n}-{} sharp {spokes:?}{}",
                shape.name(),
                if tagged { ", corner tag" } else { "" }
            );
            out.push((name, cornered(cnet(n, shape, 3), &spokes, tagged), caps));
        }
    }
    out
}

/// Checks the nets of one scheme (module documentation).
fn corners_are_capped(loop_: bool) {
    for (name, m, want) in nets(loop_) {
        let (scheme, samples) = support::scheme_of(loop_, &m);
        for rings in [1, 2, 3] {
            let what = format!("{name}, {rings} rings");
            let c = support::complex_of(loop_, &m, rings);
            check_capped(&what, &m, &c, scheme.as_ref(), samples, false, true);
            let corners: Vec<_> = c
                .caps
                .iter()
                .filter(|s| s.hole.kind.corner().is_some())
                .collect();
            assert_eq!(corners.len(), want, "{what}: corner caps");
            let levels = c.provenance.iter().filter_map(support::level_of).max();
            let pts = limit_points(scheme.as_ref(), &m, levels.unwrap_or(0) + 2);
            let size = probe::net_size(m.positions());
            for s in corners {
                assert!(fairsub::geom::dist(s.hole.centre, m.positions()[0]) < 1e-14 * size);
                let (first, last) = (s.first as usize, (s.first + s.count - 1) as usize);
                for t in [0.25, 0.5, 0.75] {
                    for p in [c.patches[first].eval(t, 0.0), c.patches[last].eval(0.0, t)] {
                        let d = nearest(&pts, p);
                        assert!(d < 1e-11 * size, "{what}: sharp spoke {d:e} off the limit");
                    }
                }
                // not folded: every piece's normal near the corner agrees with its normal
                // near the ring (the same side of the sector's surface)
                for k in first..=last {
                    let p = &c.patches[k];
                    let normal = |u: f64, v: f64| {
                        let d = p.derivatives(u, v);
                        cross(d.du, d.dv)
                    };
                    let (inner, outer) = (normal(0.1, 0.1), normal(0.9, 0.9));
                    assert!(dot(inner, outer) > 0.0, "{what}: piece {k} folds");
                }
            }
        }
    }
}

#[test]
fn catmull_clark_corners_get_one_g1_cap_per_side_sharing_the_sharp_edges() {
    corners_are_capped(false);
}

#[test]
fn loop_corners_get_one_g1_cap_per_side_sharing_the_sharp_edges() {
    corners_are_capped(true);
}

#[test]
fn corner_caps_reapply_through_the_patch_table() {
    for loop_ in [false, true] {
        let scheme = if loop_ { "loop" } else { "catmull-clark" };
        for (name, m, want) in nets(loop_).into_iter().step_by(3) {
            let corners = table_reapplies(scheme, &name, &m, |h| h.kind.corner().is_some());
            assert_eq!(corners, want, "{name}: corner caps in the table");
        }
    }
}
