//! OpenSubdiv's `catmark_val2_foldover`: flat nets folded onto themselves (a quad and two
//! triangles covering it the other way round, a closed sheet of no thickness, with interior
//! vertices of valence 2). The acceptance sweep measured G^1 = pi under pgs, polar-bi2 and
//! bi2-mixed and 0 under doo-sabin and Catmull-Clark. This is a real fold, not a defect of the
//! PGS family: every scheme's surface lies exactly in the net's plane and its normal takes both
//! signs (the sheet folds back at its rim), so a join's G^1 is 0 or pi according to whether a
//! fold line happens to run along a patch join (PGS's C^0 fill of the degenerate caps) or
//! inside patches (Doo-Sabin's, Catmull-Clark's).

use fairsub::analysis::continuity;
use fairsub::mesh::PolyMesh;
use fairsub::schemes::registry::registry;
use fairsub::surface::ComplexOptions;

/// Shape 1 of `catmark_val2_foldover` (in the plane z = 0): the quad and the two triangles
/// that cover it reversed.
fn foldover() -> PolyMesh {
    let pos = vec![
        [-1.4, 0.6, 0.0],
        [-0.6, 0.6, 0.0],
        [-0.6, 1.4, 0.0],
        [-1.4, 1.4, 0.0],
    ];
    PolyMesh::new(pos, &[vec![0, 1, 2, 3], vec![0, 3, 2], vec![0, 2, 1]]).expect("the net")
}

#[test]
fn the_folded_sheet_is_planar_and_folds_under_every_scheme() {
    let net = foldover();
    let opts = ComplexOptions {
        rings: 3,
        fill: true,
    };
    for name in [
        "pgs",
        "polar-bi2",
        "bi2-mixed",
        "doo-sabin",
        "catmull-clark",
    ] {
        let spec = registry().lookup(name).expect("registered");
        let out = fairsub::surface::build(&spec, &net, opts, &mut |_| {})
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let c = &out.complex;
        assert!(!c.patches.is_empty(), "{name}: no patches");
        // exactly planar: every control point in the net's plane
        let off = c
            .patches
            .iter()
            .flat_map(|p| p.cps.iter().map(|q| q[2].abs()))
            .fold(0.0f64, f64::max);
        assert!(off == 0.0, "{name}: a control point {off:e} off the plane");
        // the normal (0, 0, +-1) takes both signs: the sheet folds over
        let (mut up, mut down) = (0usize, 0usize);
        for p in &c.patches {
            for (u, v) in [(0.25, 0.25), (0.5, 0.5), (0.75, 0.25), (0.25, 0.75)] {
                let n = p.normal(u, v);
                if n[2] > 0.5 {
                    up += 1;
                } else if n[2] < -0.5 {
                    down += 1;
                }
            }
        }
        let r = continuity::check(c);
        eprintln!(
            "{name}: {} patches, normal up {up}, down {down}, G1 {:.3}",
            c.len(),
            r.all.g1
        );
        assert!(up > 0 && down > 0, "{name}: up {up}, down {down}");
        // a planar surface's joins are flat or folded: G^1 is 0 or pi
        let g1 = r.all.g1;
        assert!(
            g1 < 1e-8 || (g1 - std::f64::consts::PI).abs() < 1e-6,
            "{name}: G1 {g1}"
        );
    }
}
