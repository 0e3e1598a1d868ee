//! G^1 caps at cone points of Catmull-Clark and Loop: an interior vertex of infinite sharpness
//! (the corner rule keeps it) with no infinitely sharp edge, or with one. No two sharp edges
//! span a tangent plane there: the limit surface has a tangent cone at the vertex, not a plane.
//! The hole is closed by the cap of `bezier::g1::Fan::Cone`: every spoke tangent zero (the
//! cap's corners at the apex are singular), the G^1 relation with `w(0) = 2 cos(pi / n)` on
//! every spoke but a sharp one, so each pair of sectors shares the tangent plane along their
//! spoke up to the apex. Until 2026-12-05 these holes kept the C^0 Hermite fill: `check` at 3
//! rings measured 2.1 rad on OpenSubdiv's `cc_corner_tags` (and the fill was not C^1 to its
//! ring: 2.6e-2) and 1.1 rad on `loop_icosa_infsharp`.
//!
//! Tests, at 1, 2 and 3 rings: every ring and regular patch exact against uniform refinement,
//! every join C^0, every join but the sharp ones G^1 below 1e-8 rad (at the apex: along the
//! join, `analysis::continuity`), no fill patch left, one cone cap per cone point, centred at
//! the vertex with zero spoke tangents, no piece folded over; the probed patch table
//! re-applies; `--stencils` names the fans `cone` and `cone/dart`.
//!
//! No piece folds over: the neighbouring normals of a 40 x 40 grid of every cone piece are
//! within 25 degrees (cosine above 0.9; 0.92 at the least, `cc_corner_tags`; a cone of two
//! sectors, the split-edge cube's valence-2 vertex tagged, within 40 degrees, 0.765), except where the
//! scheme's own mesh folds. On Loop's flat net of valence 3 with the tag and one sharp edge the
//! two smooth spoke ends approach the sharp edge's direction level by level (at 115, 74 and 19
//! degrees from it at levels 1, 2 and 3, on both sides): from level 2 the middle triangle of
//! the vertex's fan is upside down in the refined mesh itself, and the cap, C^1 to that ring,
//! folds with it. OpenSubdiv's rules give the same mesh.

use crate::sharp_helpers::support;

use fairsub::geom::{cross, dist, dot};
use fairsub::mesh::nets::{CnetShape, cnet, loop_net};
use fairsub::mesh::{Extras, PolyMesh, SharpEdges};
use fairsub::surface::table::probe;
use support::{check_capped, osd};

/// `m` with vertex 0 of sharpness 10 and sharp chains along its spokes `spokes` (none or one).
fn coned(m: PolyMesh, spokes: &[usize]) -> PolyMesh {
    let pairs = support::sharp_chains(&m, spokes);
    m.with_extras(Some(Extras {
        sharp_edges: SharpEdges::ByPair(pairs),
        sharp_vertices: vec![(0, 10.0)],
        ..Extras::default()
    }))
}

/// A test net: name, net, cone points (vertex, or `None` where its index is not tracked),
/// whether it is closed, whether it has a sharp edge.
type Net = (String, PolyMesh, Vec<Option<u32>>, bool, bool);

/// The nets with a cone point at vertex 0: Catmull-Clark's c-nets or Loop's nets, without and
/// with one sharp edge.
fn nets(loop_: bool) -> Vec<Net> {
    let mut out = Vec::new();
    for spokes in [vec![], vec![0]] {
        let kind = if spokes.is_empty() {
            "cone"
        } else {
            "cone, one sharp edge"
        };
        let sharp = !spokes.is_empty();
        if loop_ {
            for n in [3, 4, 5, 6, 7, 9] {
                let m = coned(loop_net(n, 3), &spokes);
                out.push((
                    format!("loop net {n} {kind}"),
                    m,
                    vec![Some(0)],
                    false,
                    sharp,
                ));
            }
        } else {
            for n in [3, 4, 5, 6, 8] {
                for shape in [CnetShape::Convex, CnetShape::Saddle] {
                    let m = coned(cnet(n, shape, 3), &spokes);
                    let name = format!("cnet-{n}-{} {kind}", shape.name());
                    out.push((name, m, vec![Some(0)], false, sharp));
                }
            }
        }
    }
    out
}

/// The net whose own mesh folds at its cone point after one level (module documentation).
const FOLDS: &str = "loop net 3 cone, one sharp edge";

/// Whether the level's mesh folds over at the cone point of `hole`, capped by `pieces`: a
/// sector whose spoke chords `E_s - C, E_(s+1) - C` turn against its piece's normal near the
/// ring (the ring's, to which the piece is C^1).
fn mesh_folds(hole: &fairsub::bezier::g1::Hole, pieces: &[fairsub::bezier::BezierPatch]) -> bool {
    let n = hole.sectors.len();
    let chord = |s: usize| {
        // a dart's fan: spoke n is spoke 0
        let e = hole.sectors[s % n][0].boundary[0];
        fairsub::geom::sub(e, hole.centre)
    };
    (0..n).any(|s| {
        let d = pieces[s].derivatives(0.9, 0.9);
        dot(cross(chord(s), chord(s + 1)), cross(d.du, d.dv)) < 0.0
    })
}

/// The smallest cosine between the unit normals of neighbouring points of a 40 x 40 grid of
/// `p` (its corners at the apex excluded): near -1 where the piece folds over.
fn smallest_turn(p: &fairsub::bezier::BezierPatch) -> f64 {
    let g = 40;
    let unit = |i: usize, j: usize| {
        let d = p.derivatives(i as f64 / g as f64, j as f64 / g as f64);
        let n = cross(d.du, d.dv);
        fairsub::geom::scale(n, 1.0 / dot(n, n).sqrt())
    };
    let mut worst: f64 = 1.0;
    for i in 1..g {
        for j in 1..g {
            let n0 = unit(i, j);
            worst = worst
                .min(dot(n0, unit(i + 1, j)))
                .min(dot(n0, unit(i, j + 1)));
        }
    }
    worst
}

/// Checks every net at 1..3 rings and the probed patch table at 2 (module documentation).
fn cones_are_capped(loop_: bool, nets: Vec<Net>) {
    for (name, m, cones, closed, sharp) in nets {
        let (scheme, samples) = support::scheme_of(loop_, &m);
        let size = probe::net_size(m.positions());
        for rings in 1..=3 {
            let what = format!("{name}, {rings} rings");
            let c = support::complex_of(loop_, &m, rings);
            check_capped(&what, &m, &c, scheme.as_ref(), samples, closed, sharp);
            let caps: Vec<_> = c.caps.iter().filter(|s| s.hole.kind.is_cone()).collect();
            assert_eq!(caps.len(), cones.len(), "{what}: cone caps");
            for (s, x) in caps.iter().zip(&cones) {
                assert_eq!(s.hole.kind.is_dart(), sharp, "{what}: the dart's fan");
                if let Some(x) = x {
                    let d = dist(s.hole.centre, m.positions()[*x as usize]);
                    assert!(d < 1e-14 * size, "{what}: centre {d:e} off the vertex");
                }
                for k in s.first as usize..(s.first + s.count) as usize {
                    let p = &c.patches[k];
                    // zero spoke tangents: the apex's first two neighbours are the apex
                    let apex = p.cp(0, 0);
                    assert!(dist(p.cp(1, 0), apex) < 1e-14 * size, "{what}: T along u");
                    assert!(dist(p.cp(0, 1), apex) < 1e-14 * size, "{what}: T along v");
                    // not folded: neighbouring normals of a fine grid agree, unless the
                    // scheme's own mesh folds there (module documentation)
                    let turn = smallest_turn(p);
                    if mesh_folds(&s.hole, &c.patches[s.first as usize..]) {
                        assert!(
                            name.starts_with(FOLDS) && rings > 1,
                            "{what}: the mesh folds"
                        );
                    } else {
                        // two sectors make a sharper apex: neighbouring normals there turn
                        // by up to 40 degrees (0.765 at 1 to 3 rings), still far from a fold
                        // (a flipped normal, cosine below 0)
                        let least = if s.hole.valence() == 2 { 0.75 } else { 0.9 };
                        assert!(turn > least, "{what}: piece {k} folds ({turn:.3})");
                    }
                }
            }
        }
        let scheme_name = if loop_ { "loop" } else { "catmull-clark" };
        let in_table = support::table_reapplies(scheme_name, &name, &m, |h| h.kind.is_cone());
        assert_eq!(in_table, cones.len(), "{name}: cone caps in the table");
    }
}

#[test]
fn catmull_clark_cone_points_are_capped_g1_along_every_spoke() {
    let mut all = nets(false);
    // OpenSubdiv's cube with a corner tag 10 on a vertex without sharp edges (its other tags
    // semi-sharp, spent by level 3)
    all.push((
        "cc_corner_tags".into(),
        osd("cc_corner_tags"),
        vec![None],
        true,
        false,
    ));
    // a cone point of valence 2: the split-edge cube's vertex 8 tagged (two sectors, the
    // half-turn chart's w(0) = 2 cos(pi / 2) = 0)
    let two = fairsub::gallery::split_edge_cube().with_extras(Some(Extras {
        sharp_vertices: vec![(8, 10.0)],
        ..Extras::default()
    }));
    all.push((
        "split-edge cube, cone of 2".into(),
        two,
        vec![Some(8)],
        true,
        false,
    ));
    cones_are_capped(false, all);
}

#[test]
fn loop_cone_points_are_capped_g1_along_every_spoke() {
    let mut all = nets(true);
    // OpenSubdiv's icosahedron: a corner tag 10 with one sharp edge (a cone with a dart's fan)
    // besides a corner of three sharp edges
    let m = osd("loop_icosa_infsharp");
    all.push(("loop_icosa_infsharp".into(), m, vec![None], true, true));
    cones_are_capped(true, all);
}

/// `subdivide --stencils` names the cone fans `cone` and `cone/dart`, and the files read back
/// with one cap line per cap of the table.
#[test]
fn stencil_files_name_cone_fans_and_read_back() {
    for (net, scheme, word) in [
        ("cc_corner_tags", "catmull-clark", "cone"),
        ("loop_icosa_infsharp", "loop", "cone/dart"),
    ] {
        assert_eq!(
            support::stencil_caps_named(net, scheme, word),
            1,
            "{net}: {word}"
        );
    }
}
