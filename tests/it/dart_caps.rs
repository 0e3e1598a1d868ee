//! G^1 caps at Catmull-Clark's and Loop's darts: an interior vertex with exactly one infinitely
//! sharp edge (a crease ending inside the surface). The dart's fan is closed by the cap of
//! `bezier::g1::Fan::Dart`: `n` sectors over a full turn from the sharp edge, which is the
//! cap's only spoke without the G^1 relation (C^0, shared by its two sides), centred at the
//! dart's own limit point in its own tangent plane (`schemes::catmull_clark::dart`,
//! `schemes::loop_subdivision::dart`). Until 2026-12-05 these holes kept the C^0 Hermite
//! fill: `check` at 3 rings measured 0.29 rad on OpenSubdiv's `cc_torus_dart`, 4.9e-2 on
//! `cc_cube_infsharp`, 0.86 on `cc_cube_semisharp`, 5.7e-3 on `cc_grid_uv_creases` and 1.3
//! on `loop_octa_semisharp`; a dart of valence 2 (the split-edge cube with one sharp edge)
//! kept it until 2026-12-05 too (3.14 rad).
//!
//! Tests, at 1, 2 and 3 rings: every ring and regular patch is exact against the limit points
//! of uniform refinement, every join C^0 (the sharp ones too), every join but the sharp ones
//! G^1 below 1e-8 rad, no fill patch left, one dart cap per dart, centred at the dart's limit
//! point. The dart masks are checked against the scheme's own refinement: the limit mask
//! applied to a dart's 1-ring gives the same point at every level (it is a left eigenvector
//! of the refinement's local matrix), which the smooth mask (OpenSubdiv's choice at a dart)
//! does not.

use crate::sharp_helpers::support;

use fairsub::geom::{Point, axpy, dist};
use fairsub::mesh::nets::{CnetShape, cnet, loop_net};
use fairsub::mesh::{Extras, PolyMesh, SharpEdges};
use fairsub::schemes::{catmull_clark, loop_subdivision, refine_levels};
use fairsub::surface::table::probe;
use support::{check_capped, osd};

/// `m` with an infinitely sharp edge chain from vertex 0 along its first spoke, continued
/// straight across regular vertices (valence 4 for quads, 6 for triangles) to the boundary: a
/// dart at vertex 0.
fn with_dart(m: PolyMesh) -> PolyMesh {
    let pairs = support::sharp_chains(&m, &[0]);
    m.with_extras(Some(Extras {
        sharp_edges: SharpEdges::ByPair(pairs),
        ..Extras::default()
    }))
}

/// A test net: name, net, its darts `(vertex, other end of its sharp edge)` (input indices;
/// `(0, 0)` where not given), whether it is closed.
type Net = (String, PolyMesh, Vec<(u32, u32)>, bool);

/// The nets with a dart at vertex 0: Catmull-Clark's c-nets (`loop = false`) or Loop's nets.
fn nets(loop_: bool) -> Vec<Net> {
    let mut out = Vec::new();
    let mut push = |name: String, m: PolyMesh| {
        let m = with_dart(m);
        let e0 = m.he_to(m.outgoing_halfedges(0)[0]);
        out.push((name, m, vec![(0, e0)], false));
    };
    if loop_ {
        for n in [3, 4, 5, 7, 8] {
            push(format!("loop net {n} dart"), loop_net(n, 3));
        }
    } else {
        for n in [3, 5, 6, 7] {
            for shape in [CnetShape::Convex, CnetShape::Saddle] {
                push(format!("cnet-{n}-{} dart", shape.name()), cnet(n, shape, 3));
            }
        }
    }
    out
}

/// The limit mask of a dart of valence `n` under Catmull-Clark or Loop.
fn limit_mask(loop_: bool, n: usize) -> Vec<f64> {
    if loop_ {
        loop_subdivision::dart::dart_masks(n).unwrap().limit.clone()
    } else {
        catmull_clark::dart::dart_masks(n).unwrap().limit.clone()
    }
}

/// The 1-ring of vertex `x` of `m` from its edge to `e0`: `x`, the edge neighbours in fan
/// order from `e0`, the far corners of its quads in the same order (the order of the dart
/// masks; a triangle fan has no far corners).
fn ring(m: &PolyMesh, x: u32, e0: u32) -> Vec<Point> {
    let mut hs = m.outgoing_halfedges(x as usize);
    let k = hs
        .iter()
        .position(|&h| m.he_to(h) == e0)
        .expect("sharp edge");
    hs.rotate_left(k);
    let pos = m.positions();
    let mut pts = vec![pos[x as usize]];
    pts.extend(hs.iter().map(|&h| pos[m.he_to(h) as usize]));
    for &h in &hs {
        let f = m.he_face(h) as usize;
        let face = m.face(f);
        if face.len() == 4 {
            let c = face.iter().position(|&v| v == x).expect("corner");
            pts.push(pos[face[(c + 2) % 4] as usize]);
        }
    }
    pts
}

fn apply(w: &[f64], pts: &[Point]) -> Point {
    w.iter()
        .zip(pts)
        .fold([0.0; 3], |acc, (&wi, &p)| axpy(acc, wi, p))
}

/// The dart's limit mask gives one point at every level of the scheme's own refinement; the
/// smooth limit mask of the same valence does not (its value moves by more than 1e-4 of the
/// net's size between levels 0 and 3).
#[test]
fn dart_limit_mask_is_invariant_under_the_schemes_refinement() {
    for loop_ in [false, true] {
        for (name, m, darts, _) in nets(loop_) {
            let (scheme, _) = support::scheme_of(loop_, &m);
            let (x, mut e0) = darts[0];
            let mask = limit_mask(loop_, m.outgoing_halfedges(x as usize).len());
            // the smooth limit mask at a dart (OpenSubdiv's), from the scheme's limit stencils
            let smooth = |m: &PolyMesh| {
                let st = scheme.limit_stencils(m).unwrap();
                st.apply(m.positions())[x as usize]
            };
            let size = probe::net_size(m.positions());
            let mut level = m.clone();
            let c0 = apply(&mask, &ring(&m, x, e0));
            let s0 = smooth(&m);
            let mut s3 = s0;
            for k in 1..=3 {
                let nv = level.num_vertices() as u32;
                let edge = level.find_edge(x, e0).expect("sharp edge");
                let next = refine_levels(scheme.as_ref(), &level, 1, |_| {}).unwrap();
                // vertex points first, then one edge point per parent edge
                e0 = nv + edge;
                let ck = apply(&mask, &ring(&next, x, e0));
                assert!(
                    dist(ck, c0) < 1e-12 * size,
                    "{name} level {k}: {:e}",
                    dist(ck, c0)
                );
                s3 = smooth(&next);
                level = next;
            }
            assert!(
                dist(s3, s0) > 1e-4 * size,
                "{name}: smooth mask {:e}",
                dist(s3, s0)
            );
        }
    }
}

/// Checks every net at 1..3 rings (module documentation) and the probed patch table at 2.
fn darts_are_capped(loop_: bool, nets: Vec<Net>) {
    for (name, m, darts, closed) in nets {
        let (scheme, samples) = support::scheme_of(loop_, &m);
        for rings in 1..=3 {
            let what = format!("{name}, {rings} rings");
            let c = support::complex_of(loop_, &m, rings);
            check_capped(&what, &m, &c, scheme.as_ref(), samples, closed, true);
            let dart_caps: Vec<_> = c.caps.iter().filter(|s| s.hole.kind.is_dart()).collect();
            assert_eq!(dart_caps.len(), darts.len(), "{what}: dart caps");
            // the test nets' dart: centred at the dart's limit point (level 0's mask)
            if let [(x, e0)] = darts[..]
                && e0 != 0
            {
                let mask = limit_mask(loop_, m.outgoing_halfedges(x as usize).len());
                let want = apply(&mask, &ring(&m, x, e0));
                let got = dart_caps[0].hole.centre;
                assert!(
                    dist(got, want) < 1e-12,
                    "{what}: centre {:e}",
                    dist(got, want)
                );
            }
        }
        // the probed table re-applies to moved points
        let scheme_name = if loop_ { "loop" } else { "catmull-clark" };
        let in_table = support::table_reapplies(scheme_name, &name, &m, |h| h.kind.is_dart());
        assert_eq!(in_table, darts.len(), "{name}: dart caps in the table");
    }
}

#[test]
fn catmull_clark_darts_are_capped_g1_and_c0_along_their_sharp_edge() {
    let mut all = nets(false);
    // OpenSubdiv's nets: the torus whose sharp chain of two edges ends at two darts, the cube
    // whose three sharp edges at a corner end at two darts (the third in the creased loop),
    // the cube whose one sharp edge has two darts once the semi-sharp ones are spent, the grid
    // whose sharp edge ends inside at both ends
    for (name, darts) in [
        ("cc_torus_dart", 2),
        ("cc_cube_infsharp", 2),
        ("cc_cube_semisharp", 2),
        ("cc_grid_uv_creases", 2),
    ] {
        let closed = name != "cc_grid_uv_creases";
        all.push((name.to_string(), osd(name), vec![(0, 0); darts], closed));
    }
    // a dart of valence 2: the split-edge cube's vertex 8 (valence 2 after the first step)
    // with a sharp edge to vertex 4, whose other end is a dart too (masks from the two
    // positive modes, `catmull_clark::dart`; the fill measured 3.14 rad there)
    let two = fairsub::gallery::split_edge_cube().with_extras(Some(Extras {
        sharp_edges: SharpEdges::ByPair(vec![([4, 8], 10.0)]),
        ..Extras::default()
    }));
    all.push((
        "split-edge cube, dart of 2".into(),
        two,
        vec![(0, 0); 2],
        true,
    ));
    darts_are_capped(false, all);
}

#[test]
fn loop_darts_are_capped_g1_and_c0_along_their_sharp_edge() {
    let mut all = nets(true);
    // the octahedron's one sharp edge: two darts of valence 4 once the semi-sharp edges at
    // them are spent
    all.push((
        "loop_octa_semisharp".to_string(),
        osd("loop_octa_semisharp"),
        vec![(0, 0); 2],
        true,
    ));
    darts_are_capped(true, all);
}

/// `subdivide --stencils` names dart fans `dart` and wedges `wedge/M` (the valence of the
/// vertex they are cut from), and the files read back with one cap line per cap of the table.
#[test]
fn stencil_files_name_dart_and_wedge_fans_and_read_back() {
    for (net, scheme, word, count) in [
        ("cc_torus_dart", "catmull-clark", "dart", 2),
        ("loop_holes_isolated", "loop", "wedge/5", 4),
    ] {
        let named = support::stencil_caps_named(net, scheme, word);
        assert_eq!(named, count, "{net}: {word} caps");
    }
}
