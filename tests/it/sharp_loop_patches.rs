//! Loop patch output (`--rings`) with OpenSubdiv's sharp features: every emitted regular or ring
//! triangle is exact, i.e. its points at the dyadic lattice points of its level are limit
//! points of the uniformly refined net (`--levels N --limit`, which the peer test checks against
//! OpenSubdiv); the crease curve is the cubic B-spline of the crease vertices and shared by the
//! triangles on both sides; semi-sharp creases are refined until spent; hole faces are not
//! written; `check` reports the crease joins as sharp.

use crate::sharp_helpers::support;

use fairsub::bezier::complex::{PatchComplex, Provenance};
use fairsub::geom::{self, Point};
use fairsub::host::ComplexOptions;
use fairsub::mesh::tags::{BoundaryInterpolation, CreaseMethod, SubdOptions};
use fairsub::mesh::{Extras, PolyMesh, SharpEdges};
use fairsub::schemes::loop_subdivision::Configured;
use fairsub::schemes::loop_subdivision::surface::loop_complex_with;
use support::{
    check_net, file_options, has_infinite_crease, level_of, osd, rings_and_check, triangle_samples,
};

fn limit_points(mesh: &PolyMesh, subd: SubdOptions, levels: usize) -> Vec<Point> {
    support::limit_points(&Configured { options: subd }, mesh, levels)
}

fn check_exact(c: &PatchComplex, pts: &[Point], levels: usize) -> (usize, usize, f64) {
    support::check_exact(c, pts, levels, triangle_samples)
}

fn complex(m: &PolyMesh, subd: SubdOptions, rings: usize) -> PatchComplex {
    let opts = ComplexOptions { rings, fill: true };
    loop_complex_with(m, opts, subd, |_| {}).unwrap()
}

/// The deepest ring of `c` (0 when all patches are regular).
fn depth(c: &PatchComplex) -> usize {
    c.provenance.iter().filter_map(level_of).max().unwrap_or(0)
}

/// A grid of `n x n` quads, each split along its diagonal from corner (i, j), on a torus
/// (`periodic`: every vertex of valence 6) or open, with the edges of the row `j = 3` of
/// sharpness `sharpness` (on the torus a closed crease loop) and the faces `holes` tagged as
/// holes. Vertex (i, j) is `j n + i` on the torus, `j (n + 1) + i` open.
fn creased_grid(n: usize, periodic: bool, sharpness: f32, holes: &[u32]) -> PolyMesh {
    let w = if periodic { n } else { n + 1 };
    let id = |i: usize, j: usize| (j % w) * w + i % w;
    let mut pts = Vec::new();
    for j in 0..w {
        for i in 0..w {
            let (a, b) = (
                std::f64::consts::TAU * i as f64 / n as f64,
                std::f64::consts::TAU * j as f64 / n as f64,
            );
            pts.push(if periodic {
                let r = 3.0 + (b.cos() + 0.2 * (2.0 * a).sin());
                [r * a.cos(), r * a.sin(), b.sin() + 0.1 * a.cos()]
            } else {
                let (x, y) = (i as f64, j as f64);
                [x + 0.1 * y, y, 0.1 * (x * y).sin() + 0.05 * x * x]
            });
        }
    }
    let mut faces = Vec::new();
    for j in 0..n {
        for i in 0..n {
            faces.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            faces.push(vec![id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let m = PolyMesh::new(pts, &faces).unwrap();
    let edges = (0..n)
        .map(|i| ([id(i, 3) as u32, id(i + 1, 3) as u32], sharpness))
        .collect();
    m.with_extras(Some(Extras {
        sharp_edges: SharpEdges::ByPair(edges),
        holes: holes.to_vec(),
        ..Extras::default()
    }))
}

fn creased_torus(n: usize, sharpness: f32, holes: &[u32]) -> PolyMesh {
    creased_grid(n, true, sharpness, holes)
}

#[test]
fn open_creased_grid_is_exact_with_corner_triangles() {
    // the crease ends on the boundary: there each boundary vertex is a corner (three sharp
    // edges) with one triangle on one side (regular) and two on the other (ringed); the grid's
    // own corners have one triangle (regular under the corner rule) or two (ringed)
    let n = 6;
    let m = creased_grid(n, false, 10.0, &[]);
    let subd = SubdOptions::default();
    let c = complex(&m, subd, 3);
    let levels = depth(&c);
    assert_eq!(levels, 3);
    let pts = limit_points(&m, subd, levels);
    let (patches, _, worst) = check_exact(&c, &pts, levels);
    assert!(worst < 1e-9);
    let regular: Vec<u32> = c
        .provenance
        .iter()
        .filter_map(|p| match p {
            Provenance::Regular { face } => Some(*face),
            _ => None,
        })
        .collect();
    // the corner triangle of the grid's corner (n, 0), face 2 (n - 1), is one exact patch
    assert!(regular.contains(&(2 * (n as u32 - 1))), "{regular:?}");
    eprintln!(
        "open creased grid: {} patches, {} regular, {patches} exact",
        c.len(),
        regular.len()
    );
    let r = fairsub::analysis::continuity::check(&c);
    assert!(r.sharp.pieces >= n, "{:?}", r.sharp);
    assert!(r.sharp.c0 < 1e-12 && r.all.c0 < 1e-9);
}

#[test]
fn creased_torus_is_regular_triangles_sharing_the_crease_b_spline() {
    let n = 6;
    let m = creased_torus(n, 10.0, &[]);
    let subd = SubdOptions::default();
    let c = complex(&m, subd, 3);
    // every triangle is regular: crease vertices have three triangles on each side
    assert_eq!(c.len(), 2 * n * n);
    assert!(
        c.provenance
            .iter()
            .all(|p| matches!(p, Provenance::Regular { .. }))
    );
    let pts = limit_points(&m, subd, 3);
    let (patches, samples, worst) = check_exact(&c, &pts, 3);
    assert_eq!((patches, samples), (2 * n * n, 2 * n * n * 45));
    assert!(worst < 1e-9);
    // the crease curve: the sides on the edges (i, 3) -> (i + 1, 3) of the triangles above
    // and below are the uniform cubic B-spline of the crease vertices
    let pos = m.positions();
    let crease = |i: usize| pos[3 * n + i % n];
    let mut checked = 0;
    for i in 0..n {
        for t in [0.0, 0.25, 0.5, 0.8, 1.0] {
            let want = support::bspline(std::array::from_fn(|k| crease(i + n - 1 + k)), t);
            // above: face 2 (3 n + i) is [(i,3), (i+1,3), (i+1,4)], edge P0 P1 on v = 0
            let above = c.patches[2 * (3 * n + i)].eval(t, 0.0);
            // below: face 2 (2 n + i) + 1 is [(i,2), (i+1,3), (i,3)]: its edge P1 P2 (u = 1)
            // runs from (i+1, 3) to (i, 3)
            let below = c.patches[2 * (2 * n + i) + 1].eval(1.0, 1.0 - t);
            assert!(geom::dist(above, want) < 1e-12, "{above:?} {want:?}");
            assert!(geom::dist(below, want) < 1e-12, "{below:?} {want:?}");
            checked += 1;
        }
    }
    assert_eq!(checked, 5 * n);
    // check: smooth away from the crease (G^1: the triangles' collapsed parametrisations
    // differ from side to side, so the parametric C^1 defect is not zero), the crease's
    // pieces sharp (C^0) joins
    let r = fairsub::analysis::continuity::check(&c);
    assert_eq!(r.sharp.pieces, n, "{:?}", r.sharp);
    assert!(r.sharp.c0 < 1e-12 && r.sharp.g1 > 0.05, "{:?}", r.sharp);
    assert_eq!(r.open_sides, 0);
    assert_eq!(r.all.pieces, 3 * n * n - n);
    assert!(r.all.c0 < 1e-12 && r.all.g1 < 1e-9, "{:?}", r.all);
}

#[test]
fn semi_sharp_crease_refines_until_spent() {
    // sharpness 2: the triangles at the crease become regular two levels down
    let n = 6;
    let m = creased_torus(n, 2.0, &[]);
    for method in [CreaseMethod::Uniform, CreaseMethod::Chaikin] {
        let subd = SubdOptions {
            crease_method: Some(method),
            ..SubdOptions::default()
        };
        let c = complex(&m, subd, 4);
        let rings: Vec<usize> = c.provenance.iter().filter_map(level_of).collect();
        assert_eq!(
            rings.len(),
            c.len(),
            "{method:?}: no fill, the sharpness is spent"
        );
        assert_eq!(rings.iter().max(), Some(&2), "{method:?}");
        let pts = limit_points(&m, subd, 2);
        let (patches, _, worst) = check_exact(&c, &pts, 2);
        assert_eq!(patches, c.len());
        assert!(worst < 1e-9, "{method:?}");
        // triangles without a corner on the crease row are regular at level 0
        let regular = rings.iter().filter(|&&l| l == 0).count();
        assert_eq!(regular, 2 * n * n - 4 * n, "{method:?}");
        // a spent crease is smooth: no sharp join, no open side
        let r = fairsub::analysis::continuity::check(&c);
        assert_eq!(r.sharp.pieces, 0);
        assert_eq!(r.open_sides, 0);
    }
}

/// OpenSubdiv's triangle nets (all but the non-manifold one, which patch output refuses):
/// every ring and regular triangle is exact; no crack.
#[test]
fn osd_nets_patches_are_limit_exact() {
    use BoundaryInterpolation::{EdgeAndCorner, EdgeOnly, None as NoBoundary};
    let cases: &[(&str, Option<BoundaryInterpolation>, Option<CreaseMethod>)] = &[
        ("loop_icosa_infsharp", None, None),
        ("loop_octa_semisharp", None, None),
        ("loop_dart_corner", None, None),
        ("loop_chain_chaikin", None, None),
        ("loop_chain_chaikin", None, Some(CreaseMethod::Chaikin)),
        ("loop_tri_grid", Some(EdgeAndCorner), None),
        ("loop_tri_grid", Some(EdgeOnly), None),
        ("loop_tri_grid", Some(NoBoundary), None),
        ("loop_grid_uv_seam", Some(EdgeOnly), None),
        ("loop_holes_isolated", None, None),
        // without features: the plain path, exact too (Loop ignores the smooth-triangle tag)
        ("loop_icosa", None, None),
        ("loop_octa_uv", None, None),
        ("loop_smoothtri_tag", None, None),
    ];
    let closed = ["loop_icosa_infsharp", "loop_octa_semisharp"];
    for &(name, boundary, method) in cases {
        let m = osd(name);
        let mut subd = file_options(&m);
        if boundary.is_some() {
            subd.boundary = boundary;
        }
        if method.is_some() {
            subd.crease_method = method;
        }
        let c = complex(&m, subd, 3);
        let scheme = Configured { options: subd };
        eprint!("{boundary:?} {method:?} ");
        let (closed, sharp) = (closed.contains(&name), has_infinite_crease(&m));
        check_net(name, &m, &c, &scheme, triangle_samples, closed, sharp);
    }
}

#[test]
fn holes_are_not_written() {
    let n = 6;
    let holes = [0, 1, 20];
    let m = creased_torus(n, 10.0, &holes);
    let c = complex(&m, SubdOptions::default(), 2);
    // the creased torus is regular: 72 triangles, three of them holes
    assert_eq!(c.len(), 2 * n * n - holes.len());
    for p in &c.provenance {
        match p {
            Provenance::Regular { face } => assert!(!holes.contains(face), "{face}"),
            other => panic!("unexpected {other:?}"),
        }
    }
    let pts = limit_points(&m, SubdOptions::default(), 2);
    let (patches, _, worst) = check_exact(&c, &pts, 2);
    assert_eq!(patches, c.len());
    assert!(worst < 1e-9);
    // the icosahedron with two hole faces: no patch in them (rings and caps alike)
    let m = osd("loop_holes_isolated");
    let c = complex(&m, file_options(&m), 2);
    let faces: Vec<u32> = (0..c.len())
        .filter_map(|i| c.domain(i).map(|d| d.face))
        .collect();
    assert_eq!(faces.len(), c.len(), "every patch knows its input face");
    assert!(faces.iter().all(|f| *f != 0 && *f != 1), "{faces:?}");
    assert!(faces.contains(&2));
}

#[test]
fn cli_rings_take_creases_and_check_reports_them_sharp() {
    // the loop of five crease edges, vertex 3's three and the dart's edge
    let (err, _) = rings_and_check("loop", "loop_icosa_infsharp", "2", 9);
    assert!(err.contains("wrote 209 patches"), "{err}");
}
