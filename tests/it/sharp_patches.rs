//! Catmull-Clark patch output (`--rings`) with OpenSubdiv's sharp features: every emitted ring
//! or regular patch is exact, i.e. its points at the dyadic parameters of its level are limit
//! points of the uniformly refined net (`--levels N --limit`, which agrees with OpenSubdiv);
//! the crease curve is the cubic B-spline of the crease vertices and shared by the patches on
//! both sides; hole faces are not written.

use crate::sharp_helpers::support;

use fairsub::bezier::complex::{PatchComplex, Provenance};
use fairsub::geom::Point;
use fairsub::host::ComplexOptions;
use fairsub::mesh::tags::{BoundaryInterpolation, SubdOptions};
use fairsub::mesh::{Extras, PolyMesh, SharpEdges};
use fairsub::schemes::catmull_clark::Configured;
use fairsub::schemes::catmull_clark::surface::catmull_clark_complex_with;
use support::{
    check_net, file_options, has_infinite_crease, level_of, nearest, osd, quad_samples,
    rings_and_check, run,
};

/// The limit points of `mesh` refined `levels` times with OpenSubdiv's rules, sorted by x.
fn limit_points(mesh: &PolyMesh, subd: SubdOptions, levels: usize) -> Vec<Point> {
    support::limit_points(&Configured { options: subd }, mesh, levels)
}

/// [`support::check_exact`] for quads.
fn check_exact(c: &PatchComplex, pts: &[Point], levels: usize) -> (usize, usize, f64) {
    support::check_exact(c, pts, levels, quad_samples)
}

fn complex(m: &PolyMesh, subd: SubdOptions, rings: usize, fill: bool) -> PatchComplex {
    catmull_clark_complex_with(m, ComplexOptions { rings, fill }, subd, |_| {}).unwrap()
}

/// A 6 x 6 grid (a bump in z) with an infinitely sharp crease along the line j = 3.
fn creased_grid(sharpness: f32) -> PolyMesh {
    let m = fairsub::mesh::nets::quad_grid(6, |x, y| 0.1 * (x * y).sin() + 0.05 * x * x);
    let row = |i: u32| 3 * 7 + i;
    let edges = (0..6).map(|i| ([row(i), row(i + 1)], sharpness)).collect();
    m.with_extras(Some(Extras {
        sharp_edges: SharpEdges::ByPair(edges),
        ..Extras::default()
    }))
}

#[test]
fn creased_grid_is_regular_patches_sharing_the_crease_b_spline() {
    let m = creased_grid(10.0);
    let subd = SubdOptions::default();
    let c = complex(&m, subd, 3, true);
    // every face is regular: crease vertices of valence 4 and the crease's ends, corners of
    // one face on each side (three sharp edges at a boundary vertex)
    assert_eq!(c.len(), 36);
    assert!(
        c.provenance
            .iter()
            .all(|p| matches!(p, Provenance::Regular { .. }))
    );
    let pts = limit_points(&m, subd, 3);
    let (patches, samples, worst) = check_exact(&c, &pts, 3);
    assert_eq!((patches, samples), (36, 36 * 81));
    assert!(worst < 1e-9);
    // every limit point is on some patch: the complex covers the whole surface
    let mut all: Vec<Point> = Vec::new();
    for p in &c.patches {
        for i in 0..=8 {
            for j in 0..=8 {
                all.push(p.eval(i as f64 / 8.0, j as f64 / 8.0));
            }
        }
    }
    all.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let far = pts.iter().filter(|&&q| nearest(&all, q) > 1e-9).count();
    assert_eq!(far, 0);
    // the crease curve: the sides on y = 3 of the patches below and above are the cubic
    // B-spline of the crease vertices (ghosts 2 P - Q at its ends), the same on both sides
    let pos = m.positions();
    let crease = |i: i64| -> Point {
        let at = |i: i64| pos[(3 * 7 + i) as usize];
        match i {
            -1 => fairsub::geom::sub(fairsub::geom::scale(at(0), 2.0), at(1)),
            7 => fairsub::geom::sub(fairsub::geom::scale(at(6), 2.0), at(5)),
            _ => at(i),
        }
    };
    let mut checked = 0;
    for i in 0..6i64 {
        for t in [0.0, 0.25, 0.5, 0.8, 1.0] {
            // uniform cubic B-spline of segment i at t
            let want = support::bspline(std::array::from_fn(|k| crease(i - 1 + k as i64)), t);
            // face (i, 2) below has its side v = 1 on the crease, face (i, 3) above v = 0
            let below = c.patches[(2 * 6 + i) as usize].eval(t, 1.0);
            let above = c.patches[(3 * 6 + i) as usize].eval(t, 0.0);
            assert!(
                fairsub::geom::dist(below, want) < 1e-12,
                "{below:?} {want:?}"
            );
            assert!(
                fairsub::geom::dist(above, want) < 1e-12,
                "{above:?} {want:?}"
            );
            checked += 1;
        }
    }
    assert_eq!(checked, 30);
    // check: C^2 away from the crease, the crease's six pieces a sharp (C^0) join
    let r = fairsub::analysis::continuity::check(&c);
    assert_eq!(r.sharp.pieces, 6);
    assert!(r.sharp.c0 < 1e-12 && r.sharp.g1 > 0.05, "{:?}", r.sharp);
    assert!(r.all.pieces > 0);
    assert!(
        r.all.c0 < 1e-12 && r.all.c1 < 1e-9 && r.all.c2 < 1e-9,
        "{:?}",
        r.all
    );
    // sharp: the cross derivatives jump at the crease (the surface is not C^1 there)
    let d_below = c.patches[2 * 6 + 2].derivatives(0.5, 1.0).dv;
    let d_above = c.patches[3 * 6 + 2].derivatives(0.5, 0.0).dv;
    assert!(fairsub::geom::dist(d_below, d_above) > 1e-3);
}

#[test]
fn semi_sharp_crease_refines_until_spent() {
    // sharpness 2: the faces at the crease become regular two levels down
    let m = creased_grid(2.0);
    let subd = SubdOptions::default();
    let c = complex(&m, subd, 4, true);
    let rings: Vec<usize> = c.provenance.iter().filter_map(level_of).collect();
    assert_eq!(
        rings.len(),
        c.len(),
        "no fill: the sharpness is spent within the rings"
    );
    assert_eq!(rings.iter().max(), Some(&2));
    let pts = limit_points(&m, subd, 2);
    let (patches, _, worst) = check_exact(&c, &pts, 2);
    assert_eq!(patches, c.len());
    assert!(worst < 1e-9);
    // faces two rows away from the crease are regular at level 0
    let regular = rings.iter().filter(|&&l| l == 0).count();
    assert_eq!(regular, 36 - 2 * 6);
}

/// The nets of OpenSubdiv's test set with sharp features: every ring and regular patch is
/// exact; the counts of patches per kind are those of this construction.
#[test]
fn osd_nets_patches_are_limit_exact() {
    let cases: &[(&str, Option<BoundaryInterpolation>)] = &[
        ("cc_cube_infsharp", None),
        ("cc_cube_semisharp", None),
        ("cc_corner_tags", None),
        ("cc_torus_dart", None),
        ("cc_holes", None),
        ("cc_crease_extraordinary", None),
        ("cc_boundary_tags", None),
        ("cc_boundary_tags", Some(BoundaryInterpolation::EdgeOnly)),
        (
            "cc_boundary_tags",
            Some(BoundaryInterpolation::EdgeAndCorner),
        ),
        (
            "cc_boundary_valences",
            Some(BoundaryInterpolation::EdgeOnly),
        ),
        ("cc_boundary_valences", Some(BoundaryInterpolation::None)),
        ("cc_boundary_edgeonly_tag", None),
    ];
    let closed = [
        "cc_cube_infsharp",
        "cc_cube_semisharp",
        "cc_corner_tags",
        "cc_torus_dart",
    ];
    for &(name, boundary) in cases {
        let m = osd(name);
        let mut subd = file_options(&m);
        if boundary.is_some() {
            subd.boundary = boundary;
        }
        let c = complex(&m, subd, 3, true);
        // an infinitely sharp crease inside the surface gives sharp joins
        let sharp = has_infinite_crease(&m) && name != "cc_boundary_tags";
        let scheme = Configured { options: subd };
        eprint!("{boundary:?} ");
        let closed = closed.contains(&name);
        check_net(name, &m, &c, &scheme, quad_samples, closed, sharp);
    }
}

#[test]
fn holes_are_not_written() {
    let m = osd("cc_holes");
    let subd = file_options(&m);
    let c = complex(&m, subd, 2, true);
    // the torus is regular: 24 faces, three of them holes
    assert_eq!(c.len(), 21);
    for p in &c.provenance {
        match p {
            Provenance::Regular { face } => assert!(![0, 1, 14].contains(face)),
            other => panic!("unexpected {other:?}"),
        }
    }
}

#[test]
fn cli_rings_take_creases_and_check_reports_them_sharp() {
    // the top loop's four edges and vertex 0's three, each a join of two pieces or more
    let (err, _) = rings_and_check("catmull-clark", "cc_cube_infsharp", "2", 7);
    assert!(err.contains("wrote 60 patches"), "{err}");
    let net = support::osd_path("cc_cube_infsharp");
    // the cap schemes take the net: Catmull-Clark's sharp rules near the features (the same
    // sharp joins as Catmull-Clark's), their own caps where the c-net is clear, a note
    let report = |scheme: &str| {
        let (code, json, err) = run(&["check", &net, "-s", scheme, "--rings", "3", "--json"]);
        assert_eq!(code, 0, "{scheme}: {err}");
        let v: serde_json::Value = serde_json::from_str(&json).unwrap();
        (v["continuity"].clone(), err)
    };
    let (cc, _) = report("catmull-clark");
    for scheme in ["eg", "qas-plus", "guided-bi6"] {
        let (c, err) = report(scheme);
        assert!(
            err.contains("is next to a sharp feature"),
            "{scheme}: {err}"
        );
        assert_eq!(c["sharp"]["pieces"], cc["sharp"]["pieces"], "{scheme}");
        assert!(c["sharp"]["c0"].as_f64().unwrap() < 1e-9, "{scheme}");
        assert!(c["all"]["c0"].as_f64().unwrap() < 1e-9, "{scheme}");
        // no join worse than Catmull-Clark's worst (its fill at the crease vertices)
        let (g, g_cc) = (
            c["all"]["g1"].as_f64().unwrap(),
            cc["all"]["g1"].as_f64().unwrap(),
        );
        assert!(g <= g_cc + 1e-9, "{scheme}: G1 {g} against {g_cc}");
        assert_eq!(c["open_sides"].as_u64(), Some(0), "{scheme}");
        // more patches than Catmull-Clark: the cap scheme's own rings where the c-net is clear
        assert!(
            c["all"]["pieces"].as_u64() > cc["all"]["pieces"].as_u64(),
            "{scheme}"
        );
    }
    // pgs cuts the net along its creases, but this one has darts (edges 0-1, 0-2 end inside
    // the surface): refused by name, nothing written (non-box takes it: its creases ending at
    // darts stay inside the surface, closed by the fill, see `tests/it/sharp_bi2_nonbox.rs`)
    {
        let (scheme, expect) = ("pgs", "vertex 1 is a dart");
        let out = std::env::temp_dir().join(format!("fairsub-{scheme}-{}.bv", std::process::id()));
        let (code, _, err) = run(&[
            "subdivide",
            &net,
            "-s",
            scheme,
            "--rings",
            "2",
            "-o",
            out.to_str().unwrap(),
        ]);
        assert!(!out.exists());
        assert_eq!(code, 1, "{err}");
        assert!(err.contains(expect), "{scheme}: {err}");
    }
}
