//! Foundation acceptance: Catmull-Clark on a regular grid is the bi-3 B-spline surface, its
//! limit points lie on the exact patches, and the gallery files are in sync with the code.

use fairsub::PolyMesh;
use fairsub::bezier::BezierPatch;
use fairsub::geom::dist;
use fairsub::schemes::{CatmullClark, Scheme};
use fairsub::surface::{ComplexOptions, Provenance, complex};

/// Uniform cubic B-spline basis on [0, 1] (independent of the Bezier conversion tables).
fn bspline3(t: f64) -> [f64; 4] {
    let s = 1.0 - t;
    [
        s * s * s / 6.0,
        (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0,
        (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0,
        t * t * t / 6.0,
    ]
}

fn grid(n: usize) -> PolyMesh {
    let mut pos = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64, j as f64);
            pos.push([x, y, (0.7 * x).sin() * (0.4 * y).cos() + 0.05 * x * y]);
        }
    }
    let mut faces = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            faces.push(vec![a, a + 1, a + n + 2, a + n + 1]);
        }
    }
    PolyMesh::new(pos, &faces).unwrap()
}

#[test]
fn regular_grid_patches_are_the_bicubic_bspline() {
    let n = 7;
    let m = grid(n);
    let c = complex(
        "catmull-clark",
        &m,
        ComplexOptions {
            rings: 3,
            fill: true,
        },
        |_| {},
    )
    .unwrap();
    assert_eq!(c.len(), n * n);
    assert!(
        c.provenance
            .iter()
            .all(|p| matches!(p, Provenance::Regular { .. }))
    );
    let at = |i: usize, j: usize| m.position(j * (n + 1) + i);
    // Interior faces: compare with the B-spline sum over the 4x4 grid points.
    let mut checked = 0;
    for (p, prov) in c.patches.iter().zip(&c.provenance) {
        let Provenance::Regular { face } = prov else {
            unreachable!()
        };
        let (fi, fj) = (*face as usize % n, *face as usize / n);
        if fi == 0 || fj == 0 || fi == n - 1 || fj == n - 1 {
            continue;
        }
        for &(u, v) in &[(0.0, 0.0), (0.3, 0.7), (0.5, 0.5), (1.0, 0.25), (0.9, 1.0)] {
            let (bu, bv) = (bspline3(u), bspline3(v));
            let mut s = [0.0; 3];
            for (a, wa) in bu.iter().enumerate() {
                for (b, wb) in bv.iter().enumerate() {
                    let q = at(fi + a - 1, fj + b - 1);
                    for k in 0..3 {
                        s[k] += wa * wb * q[k];
                    }
                }
            }
            assert!(dist(p.eval(u, v), s) < 1e-13, "face {face} at ({u},{v})");
        }
        checked += 1;
    }
    assert_eq!(checked, (n - 2) * (n - 2));
}

/// Limit positions of refined vertices (Catmull-Clark limit stencils, an independent formula)
/// lie on the exact patches, on the regular grid and around extraordinary vertices.
#[test]
fn limit_points_lie_on_the_patches() {
    for m in [
        grid(5),
        fairsub::gallery::cnet(5, fairsub::gallery::CnetShape::Saddle, 3),
        fairsub::gallery::cube(),
    ] {
        let c = complex(
            "catmull-clark",
            &m,
            ComplexOptions {
                rings: 3,
                fill: false,
            },
            |_| {},
        )
        .unwrap();
        let mut fine = m.clone();
        for _ in 0..2 {
            fine = CatmullClark.refine(&fine).unwrap().mesh;
        }
        let lim = CatmullClark::limit_stencils(&fine).apply(fine.positions());
        // Every patch corner and mid-edge point (parameters k/2) is the limit of a level-2 vertex
        // for rings up to 1; check that every patch's corners are among the limit points.
        let corners: Vec<[f64; 3]> = c
            .patches
            .iter()
            .zip(&c.provenance)
            .filter(|(_, p)| !matches!(p, Provenance::Ring { ring: 2.., .. }))
            .flat_map(|(p, _): (&BezierPatch, _)| {
                [p.eval(0.0, 0.0), p.eval(0.5, 0.5), p.eval(1.0, 0.5)]
            })
            .collect();
        for q in corners {
            let best = lim
                .iter()
                .map(|l| dist(*l, q))
                .fold(f64::INFINITY, f64::min);
            assert!(
                best < 1e-12,
                "patch point {q:?} is {best} from every limit point"
            );
        }
    }
}

#[test]
fn gallery_files_are_in_sync_with_the_code() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("gallery");
    for (name, mesh) in fairsub::gallery::all() {
        let path = dir.join(format!("{name}.obj"));
        let on_disk = std::fs::read_to_string(&path).unwrap_or_else(|_| {
            panic!(
                "{} missing: run `fairsub gallery -o gallery`",
                path.display()
            )
        });
        let mut expect = Vec::new();
        fairsub::io::write_polygons_to(
            &mut expect,
            mesh.positions(),
            mesh.face_starts(),
            mesh.corners(),
            fairsub::io::MeshFormat::Obj,
        )
        .unwrap();
        assert_eq!(
            on_disk.as_bytes(),
            &expect[..],
            "{name}.obj differs from gallery::all(): run `fairsub gallery -o gallery`"
        );
    }
}
