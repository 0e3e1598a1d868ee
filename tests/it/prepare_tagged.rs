//! The preparation on nets that tag infinitely sharp features (issue 45): the dual steps carry
//! no crease or hole, so the net is cut along its creases (hole faces removed) first and the
//! steps follow on the cut net (`fairsub::schemes::prepare`). OpenSubdiv's
//! `catmark_hole_test3/4`, `catmark_fvar_project0` and `loop_triangle_edgenone` were refused by
//! TPS and adjustable TPS for this; the nets here are small ones with the same features.

use fairsub::analysis::continuity;
use fairsub::bezier::complex::PatchComplex;
use fairsub::geom::{Point, dist};
use fairsub::mesh::tags::{BoundaryInterpolation, SubdOptions};
use fairsub::mesh::{Extras, PolyMesh, SharpEdges};
use fairsub::schemes::registry::registry;
use fairsub::surface::ComplexOptions;

const OPTS: ComplexOptions = ComplexOptions {
    rings: 3,
    fill: true,
};

/// Builds `mesh` under `scheme`: the complex and the notes.
fn build(scheme: &str, mesh: &PolyMesh) -> (PatchComplex, Vec<String>) {
    let spec = registry().lookup(scheme).expect("registered");
    let out = fairsub::surface::build(&spec, mesh, OPTS, &mut |_| {})
        .unwrap_or_else(|e| panic!("{scheme}: {e}"));
    (out.complex, out.notes)
}

/// Patches sorted by the centroid of their control points, for comparing two builds whose
/// vertices and faces are numbered differently.
fn sorted(patches: &[fairsub::bezier::BezierPatch]) -> Vec<Vec<Point>> {
    let mut out: Vec<(Point, Vec<Point>)> = patches
        .iter()
        .map(|p| {
            let n = p.cps.len() as f64;
            let c = p.cps.iter().fold([0.0; 3], |a, q| {
                [a[0] + q[0] / n, a[1] + q[1] / n, a[2] + q[2] / n]
            });
            (c, p.cps.clone())
        })
        .collect();
    out.sort_by(|a, b| a.0.partial_cmp(&b.0).expect("finite"));
    out.into_iter().map(|(_, c)| c).collect()
}

/// The schemes whose patches took these nets only through the cut before the steps.
const TPS: &[&str] = &["tps", "tps-adjustable"];

#[test]
fn a_hole_beside_boundary_vertices_of_three_faces_is_removed_before_the_dual_step() {
    // face 5 a hole: its four vertices become boundary vertices of three faces, which TPS's
    // rules do not take (catmark_hole_test4): removed, then one Doo-Sabin and one
    // Catmull-Clark step
    let (pos, faces) = crate::common::bowl_grid();
    let tagged = PolyMesh::new(pos.clone(), &faces)
        .expect("the grid")
        .with_extras(Some(Extras {
            holes: vec![5],
            ..Extras::default()
        }));
    let kept: Vec<Vec<usize>> = faces
        .iter()
        .enumerate()
        .filter(|&(f, _)| f != 5)
        .map(|(_, f)| f.clone())
        .collect();
    let deleted = PolyMesh::new(pos, &kept).expect("the grid without face 5");
    for name in TPS.iter().chain(&["bi2-mixed", "polar-bi2"]) {
        let (c, notes) = build(name, &tagged);
        let all = notes.join(" | ");
        assert!(all.contains("1 hole faces removed"), "{name}: {all}");
        let (want, _) = build(name, &deleted);
        let (a, b) = (sorted(&c.patches), sorted(&want.patches));
        assert!(!a.is_empty(), "{name}: no patches");
        assert_eq!(a.len(), b.len(), "{name}: patch counts");
        let worst = a
            .iter()
            .zip(&b)
            .flat_map(|(p, q)| p.iter().zip(q).map(|(x, y)| dist(*x, *y)))
            .fold(0.0f64, f64::max);
        assert!(worst < 1e-12, "{name}: control points differ by {worst:e}");
        let r = continuity::check(&c);
        eprintln!(
            "{name} hole: {} patches, open {}, C0 {:.1e}, G1 {:.1e}",
            c.len(),
            r.open_sides,
            r.all.c0,
            r.all.g1
        );
        assert!(r.all.g1 < 1e-8, "{name}: G1 {:e}", r.all.g1);
        if TPS.contains(name) {
            assert!(all.contains("Doo-Sabin step"), "{name}: {all}");
        }
    }
}

/// The gallery cube refined twice by Catmull-Clark (96 quads), with the infinitely sharp
/// crease loop `z = 0` and the half meridian `x = 0, z >= 0` over the top: two T junctions on
/// the equator, each leaving a sector of two faces below the equator, a crease end that
/// TPS's, polar bi-2's and the mixed scheme's boundary rules do not keep.
fn cube_with_junctions(mode: Option<BoundaryInterpolation>) -> PolyMesh {
    let cube = fairsub::gallery::all()
        .into_iter()
        .find(|(n, _)| n == "cube")
        .expect("gallery cube")
        .1;
    let cc = fairsub::schemes::by_name("catmull-clark").expect("catmull-clark");
    let m = fairsub::schemes::refine_levels(cc.as_ref(), &cube, 2, |_| {}).expect("refine");
    let p = m.positions();
    let mut sharp = Vec::new();
    for e in 0..m.num_edges() {
        let h = m.edge_halfedge(e);
        let (a, b) = (p[m.he_from(h) as usize], p[m.he_to(h) as usize]);
        let equator = a[2].abs() < 1e-12 && b[2].abs() < 1e-12;
        let meridian = a[0].abs() < 1e-12 && b[0].abs() < 1e-12 && a[2] > -1e-12 && b[2] > -1e-12;
        if equator || meridian {
            sharp.push((e as u32, 10.0));
        }
    }
    m.with_extras(Some(Extras {
        sharp_edges: SharpEdges::ById(sharp),
        options: SubdOptions {
            boundary: mode,
            ..SubdOptions::default()
        },
        ..Extras::default()
    }))
}

#[test]
fn creases_with_junctions_are_cut_before_the_dual_step_and_stay_closed() {
    let net = cube_with_junctions(None);
    for name in TPS.iter().chain(&["bi2-mixed", "polar-bi2"]) {
        let (c, notes) = build(name, &net);
        let all = notes.join(" | ");
        assert!(all.contains("cut along its creases"), "{name}: {all}");
        let r = continuity::check(&c);
        eprintln!(
            "{name} T junctions: {} patches, open {}, C0 {:.1e}, G1 {:.1e}, sharp {} (C0 {:.1e})",
            c.len(),
            r.open_sides,
            r.all.c0,
            r.all.g1,
            r.sharp.pieces,
            r.sharp.c0
        );
        // closed along the creases (sharp joins, no crack), G^1 everywhere else
        assert_eq!(r.open_sides, 0, "{name}: cracks");
        assert!(r.all.c0 < 1e-12 && r.sharp.c0 < 1e-12, "{name}");
        assert!(r.sharp.pieces > 0, "{name}: no sharp join");
        assert!(r.all.g1 < 1e-8, "{name}: G1 {:e}", r.all.g1);
    }
    // without the preparation the crease end is refused, as before
    let mut spec = registry().lookup("tps").expect("tps");
    spec.params.prepare = fairsub::schemes::prepare::Mode::None;
    let err = fairsub::surface::build(&spec, &net, OPTS, &mut |_| {}).expect_err("refused");
    assert!(err.to_string().contains("crease end or junction"), "{err}");
}

#[test]
fn creases_under_edge_only_are_cut_before_the_dual_step() {
    // catmark_fvar_project0: creases on an open net under edge-only, whose corners of one
    // face TPS's rules do not take; the cut net gets the Doo-Sabin step, which makes every
    // boundary vertex regular
    let (pos, faces) = crate::common::bowl_grid();
    let m = PolyMesh::new(pos, &faces).expect("the grid");
    // the crease along row y = 2 (vertices 10..14), boundary to boundary
    let sharp: Vec<([u32; 2], f32)> = (10..14).map(|a| ([a, a + 1], 10.0)).collect();
    let net = m.with_extras(Some(Extras {
        sharp_edges: SharpEdges::ByPair(sharp),
        options: SubdOptions {
            boundary: Some(BoundaryInterpolation::EdgeOnly),
            ..SubdOptions::default()
        },
        ..Extras::default()
    }));
    for name in TPS.iter().chain(&["bi2-mixed", "polar-bi2"]) {
        let (c, notes) = build(name, &net);
        let all = notes.join(" | ");
        let r = continuity::check(&c);
        eprintln!(
            "{name} edge-only crease: {} patches, open {}, C0 {:.1e}, G1 {:.1e}, sharp {} (C0 \
             {:.1e}); {all}",
            c.len(),
            r.open_sides,
            r.all.c0,
            r.all.g1,
            r.sharp.pieces,
            r.sharp.c0
        );
        assert!(
            r.sharp.pieces > 0 && r.sharp.c0 < 1e-12,
            "{name}: the crease"
        );
        assert!(r.all.c0 < 1e-12, "{name}");
        assert!(r.all.g1 < 1e-8, "{name}: G1 {:e}", r.all.g1);
    }
}
