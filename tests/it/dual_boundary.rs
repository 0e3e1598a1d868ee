//! The boundary modes of the dual (bi-2) schemes (`schemes::doo_sabin`, "Boundary modes"):
//! `edge-only` refines the boundary polygon by Chaikin's rule through the corners (no kept
//! corner), `none` leaves out everything a boundary rule makes (the refined net loses its
//! boundary strip, the patch output the patches of boundary vertices). Counts, boundary curves
//! and agreement between `--levels` and `--rings` are asserted in numbers.

use fairsub::analysis::continuity;
use fairsub::bezier::Side;
use fairsub::bezier::complex::PatchComplex;
use fairsub::geom::{Point, dist};
use fairsub::host::ComplexOptions;
use fairsub::mesh::tags::{BoundaryInterpolation, SubdOptions};
use fairsub::mesh::{Extras, PolyMesh};
use fairsub::schemes::registry::registry;

/// An open `n x n` grid of quads over a wavy, sheared height field (no two boundary sides
/// alike), with the boundary mode `mode` (`None`: no extras).
fn grid(n: usize, mode: Option<BoundaryInterpolation>) -> PolyMesh {
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut pos = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
            pos.push([
                x + 0.1 * y * y,
                y + 0.05 * x,
                0.3 * (3.0 * x).sin() * (2.0 * y).cos() + 0.2 * x * y,
            ]);
        }
    }
    let mut corners = Vec::new();
    for j in 0..n {
        for i in 0..n {
            corners.extend_from_slice(&[id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let face_start = (0..=(n * n) as u32).map(|f| 4 * f).collect();
    let m = PolyMesh::from_flat(pos, face_start, corners).expect("grid");
    with_mode(m, mode)
}

fn with_mode(m: PolyMesh, mode: Option<BoundaryInterpolation>) -> PolyMesh {
    match mode {
        None => m,
        Some(b) => m.with_extras(Some(Extras {
            options: SubdOptions {
                boundary: Some(b),
                ..SubdOptions::default()
            },
            ..Extras::default()
        })),
    }
}

/// The 4 x 4 grid with faces 1 and 2 (on the boundary) merged into a hexagon: an
/// extraordinary element whose corners 1, 2, 3 are boundary vertices (2 keeps one face).
fn grid_with_hexagon(mode: Option<BoundaryInterpolation>) -> PolyMesh {
    let g = grid(4, None);
    let mut faces: Vec<Vec<usize>> = (0..g.num_faces())
        .filter(|&f| f != 1 && f != 2)
        .map(|f| g.face(f).iter().map(|&v| v as usize).collect())
        .collect();
    faces.push(vec![1, 2, 3, 8, 7, 6]);
    with_mode(
        PolyMesh::new(g.positions().to_vec(), &faces).expect("net"),
        mode,
    )
}

fn refine(scheme: &str, m: &PolyMesh, levels: usize) -> PolyMesh {
    let s = fairsub::schemes::by_name(scheme).expect("scheme");
    fairsub::schemes::refine_levels(s.as_ref(), m, levels, |_| {}).expect("refine")
}

fn build(scheme: &str, mesh: &PolyMesh, rings: usize) -> fairsub::error::Result<PatchComplex> {
    let spec = registry().lookup(scheme)?;
    let opts = ComplexOptions { rings, fill: true };
    fairsub::surface::build(&spec, mesh, opts, &mut |_| {}).map(|o| o.complex)
}

/// One Chaikin step of a closed polygon.
fn chaikin(p: &[Point]) -> Vec<Point> {
    let n = p.len();
    let mix = |a: Point, b: Point, t: f64| std::array::from_fn(|k| (1.0 - t) * a[k] + t * b[k]);
    (0..n)
        .flat_map(|i| {
            let (a, b) = (p[i], p[(i + 1) % n]);
            [mix(a, b, 0.25), mix(a, b, 0.75)]
        })
        .collect()
}

/// The one boundary loop of `m` as points.
fn boundary_loop(m: &PolyMesh) -> Vec<Point> {
    let loops = m.boundary_loops();
    assert_eq!(loops.len(), 1);
    loops[0]
        .iter()
        .map(|&v| m.positions()[v as usize])
        .collect()
}

/// Whether the closed polygons `a` and `b` are the same cyclic sequence to `tol`.
fn same_loop(a: &[Point], b: &[Point], tol: f64) -> bool {
    a.len() == b.len()
        && (0..b.len()).any(|s| (0..a.len()).all(|i| dist(a[i], b[(i + s) % b.len()]) < tol))
}

fn near_any(pts: &[Point], q: Point, tol: f64) -> bool {
    pts.iter().any(|&p| dist(p, q) < tol)
}

#[test]
fn levels_counts_and_boundary_polygons() {
    // 4 x 4 quads: 25 vertices, 64 corners, 16 boundary edges, 4 corners.
    for scheme in ["doo-sabin", "doo-sabin-cc", "pgs"] {
        let counts = |mode| {
            let r = refine(scheme, &grid(4, mode), 1);
            (r.num_vertices(), r.num_faces())
        };
        // edge-and-corner: 64 corner points + 32 Chaikin points + 4 kept corners; faces
        // 16 F + 40 E + 25 V.
        assert_eq!(counts(None), (100, 81), "{scheme}");
        assert_eq!(
            counts(Some(BoundaryInterpolation::EdgeAndCorner)),
            (100, 81)
        );
        // edge-only: no kept corner, the corners' V-faces are triangles.
        assert_eq!(counts(Some(BoundaryInterpolation::EdgeOnly)), (96, 81));
        let r = refine(scheme, &grid(4, Some(BoundaryInterpolation::EdgeOnly)), 1);
        let tris = (0..r.num_faces()).filter(|&f| r.face_size(f) == 3).count();
        assert_eq!(tris, 4, "{scheme}: the corners' V-faces");
        // none: the boundary strip is not made: 16 F + 24 interior E + 9 interior V faces, an
        // 7 x 7 grid of 64 corner points.
        assert_eq!(counts(Some(BoundaryInterpolation::None)), (64, 49));
        let r = refine(scheme, &grid(4, Some(BoundaryInterpolation::None)), 2);
        assert_eq!((r.num_vertices(), r.num_faces()), (14 * 14, 13 * 13));
    }
    // The boundary polygon after two steps: Chaikin's corner cutting of the closed boundary
    // polygon (edge-only); with the corners doubled (edge-and-corner) it is not.
    let m = grid(4, Some(BoundaryInterpolation::EdgeOnly));
    let expect = chaikin(&chaikin(&boundary_loop(&m)));
    let r = refine("doo-sabin", &m, 2);
    assert!(same_loop(&boundary_loop(&r), &expect, 1e-14));
    let r = refine("doo-sabin", &grid(4, None), 2);
    assert!(!same_loop(&boundary_loop(&r), &expect, 1e-3));
}

#[test]
fn none_keeps_exactly_the_rule_free_points() {
    // Every point of the net refined under none is a point of the net refined under
    // edge-and-corner (the interior rules alone make it), here with a hexagon at the
    // boundary, for two levels.
    for (scheme, levels) in [
        ("doo-sabin", 2),
        ("doo-sabin-cc", 2),
        ("pgs", 1),
        ("pgs-dscc", 2),
    ] {
        let full = refine(scheme, &grid_with_hexagon(None), levels);
        let none = refine(
            scheme,
            &grid_with_hexagon(Some(BoundaryInterpolation::None)),
            levels,
        );
        assert!(none.num_vertices() < full.num_vertices());
        assert!(none.boundary_loops().len() == 1, "{scheme}: one boundary");
        for &p in none.positions() {
            assert!(near_any(full.positions(), p, 1e-14), "{scheme}: {p:?}");
        }
    }
}

#[test]
fn pgs_refuses_a_facet_on_the_trimmed_boundary() {
    // PGS's rule for the hexagon's F-face reads the quads across its edges; after one step
    // under none the F-face touches the boundary where the strip was left out.
    let s = fairsub::schemes::by_name("pgs").unwrap();
    let m = grid_with_hexagon(Some(BoundaryInterpolation::None));
    let e = fairsub::schemes::refine_levels(s.as_ref(), &m, 2, |_| {})
        .unwrap_err()
        .to_string();
    assert!(e.contains("(6 sides)") && e.contains("none"), "{e}");
}

#[test]
fn limit_points_per_mode() {
    let m = grid(4, Some(BoundaryInterpolation::EdgeOnly));
    let p = m.positions();
    let s = fairsub::schemes::by_name("doo-sabin").unwrap();
    // corner 0 with boundary neighbours 1 and 5: on the Chaikin curve, not kept
    let t = s.limit_stencils(&m).unwrap();
    let lim = t.apply(p);
    let q: Point = std::array::from_fn(|k| (p[1][k] + 6.0 * p[0][k] + p[5][k]) / 8.0);
    assert!(dist(lim[0], q) < 1e-15, "{:?} {q:?}", lim[0]);
    let lim = s.limit_stencils(&grid(4, None)).unwrap().apply(p);
    assert_eq!(lim[0], p[0]);
    // the limit of the level-3 edge-only net's boundary vertices agrees with Chaikin's curve
    // of the input boundary: each is the limit point of a boundary vertex of the level-3
    // Chaikin polygon
    let r = refine("doo-sabin", &m, 3);
    let lim = s.limit_stencils(&r).unwrap().apply(r.positions());
    let lp = {
        let mut l = boundary_loop(&m);
        for _ in 0..3 {
            l = chaikin(&l);
        }
        l
    };
    let n = lp.len();
    let curve: Vec<Point> = (0..n)
        .map(|i| {
            let (u, v, w) = (lp[(i + n - 1) % n], lp[i], lp[(i + 1) % n]);
            std::array::from_fn(|k| (u[k] + 6.0 * v[k] + w[k]) / 8.0)
        })
        .collect();
    for v in r.boundary_loops()[0].iter() {
        assert!(near_any(&curve, lim[*v as usize], 1e-14));
    }
    for scheme in ["doo-sabin", "pgs"] {
        let s = fairsub::schemes::by_name(scheme).unwrap();
        let e = s
            .limit_stencils(&grid(4, Some(BoundaryInterpolation::None)))
            .unwrap_err()
            .to_string();
        assert!(e.contains("vertex 0 is on the boundary"), "{e}");
    }
}

/// The sides of the complex that lie on no other patch's side (end points and midpoint, each
/// near a point of another side at a parameter `k / 64`: sides of patches of different levels
/// meet in T-joints), as those three points.
fn open_sides(c: &PatchComplex) -> Vec<[Point; 3]> {
    let side_at = |p: &fairsub::bezier::BezierPatch, s: Side, t: f64| {
        let [u, v] = s.domain_point(t);
        p.eval(u, v)
    };
    const SIDES: [Side; 4] = [Side::U0, Side::U1, Side::V0, Side::V1];
    let samples: Vec<(usize, Point)> = c
        .patches
        .iter()
        .enumerate()
        .flat_map(|(i, p)| {
            SIDES.into_iter().flat_map(move |s| {
                (0..=64).map(move |k| (4 * i + s.index(), side_at(p, s, k as f64 / 64.0)))
            })
        })
        .collect();
    let mut open = Vec::new();
    for (i, p) in c.patches.iter().enumerate() {
        for s in SIDES {
            let pts = [0.0, 0.5, 1.0].map(|t| side_at(p, s, t));
            let me = 4 * i + s.index();
            let on_other = |q: Point| {
                samples
                    .iter()
                    .any(|&(j, x)| j / 4 != me / 4 && dist(x, q) < 1e-10)
            };
            // a side shared along its length: its midpoint and quarter points lie on others
            let quarters = [0.25, 0.5, 0.75].map(|t| side_at(p, s, t));
            if !quarters.iter().all(|&q| on_other(q)) {
                open.push(pts);
            }
        }
    }
    open
}

#[test]
fn edge_only_patches_end_on_the_chaikin_curve_through_the_corners() {
    let m = grid(4, Some(BoundaryInterpolation::EdgeOnly));
    // The limit points of the boundary vertices of the Chaikin polygons of levels 0..8 and
    // their edge midpoints (the joints of the pieces): the quadratic B-spline of the closed
    // boundary polygon at the dyadic parameters.
    let mut curve = Vec::new();
    let mut l = boundary_loop(&m);
    for _ in 0..8 {
        let n = l.len();
        curve.extend((0..n).flat_map(|i| {
            let (u, v, w) = (l[(i + n - 1) % n], l[i], l[(i + 1) % n]);
            [
                std::array::from_fn::<f64, 3, _>(|k| (u[k] + 6.0 * v[k] + w[k]) / 8.0),
                std::array::from_fn::<f64, 3, _>(|k| (v[k] + w[k]) / 2.0),
            ]
        }));
        l = chaikin(&l);
    }
    for scheme in ["doo-sabin", "doo-sabin-cc", "pgs"] {
        let c = build(scheme, &m, 3).unwrap();
        let report = continuity::check(&c);
        let open = open_sides(&c);
        eprintln!(
            "{scheme}: {} patches, open {}, c0 {:.2e}, g1 {:.2e}",
            c.patches.len(),
            report.open_sides,
            report.all.c0,
            report.all.g1
        );
        assert!(open.len() >= report.open_sides.min(1), "{scheme}");
        assert!(report.all.c0 < 1e-12, "{scheme}: C0 {}", report.all.c0);
        // every open side ends and is halved on the curve
        for s in &open {
            for &p in s {
                assert!(near_any(&curve, p, 1e-12), "{scheme}: {p:?} off the curve");
            }
        }
        // and the corner is not on the surface any more
        let corner = m.positions()[0];
        assert!(
            c.patches
                .iter()
                .flat_map(|p| [
                    p.eval(0.0, 0.0),
                    p.eval(1.0, 1.0),
                    p.eval(1.0, 0.0),
                    p.eval(0.0, 1.0)
                ])
                .all(|q| dist(q, corner) > 1e-3),
            "{scheme}"
        );
    }
}

#[test]
fn none_patches_are_the_interior_vertices_patches() {
    for scheme in ["doo-sabin", "doo-sabin-cc", "pgs"] {
        // a regular grid: the 9 patches of its 3 x 3 interior vertices, each one of the
        // edge-and-corner complex's
        let full = build(scheme, &grid(4, None), 3).unwrap();
        let none = build(scheme, &grid(4, Some(BoundaryInterpolation::None)), 3).unwrap();
        assert_eq!(none.patches.len(), 9, "{scheme}");
        let same = |a: &fairsub::bezier::BezierPatch, b: &fairsub::bezier::BezierPatch| {
            a.cps.iter().zip(&b.cps).all(|(p, q)| dist(*p, *q) < 1e-14)
        };
        for p in &none.patches {
            assert!(full.patches.iter().any(|q| same(p, q)), "{scheme}");
        }
        // with a hexagon at the boundary: a subset of the edge-and-corner complex's patches
        // (caps aside), closed inside (C0), fewer patches
        let full = build(scheme, &grid_with_hexagon(None), 3).unwrap();
        let none = build(
            scheme,
            &grid_with_hexagon(Some(BoundaryInterpolation::None)),
            3,
        )
        .unwrap();
        let report = continuity::check(&none);
        eprintln!(
            "{scheme} hexagon: {} of {} patches, open {}, c0 {:.2e}",
            none.patches.len(),
            full.patches.len(),
            report.open_sides,
            report.all.c0
        );
        assert!(none.patches.len() < full.patches.len());
        assert!(report.all.c0 < 1e-12, "{scheme}: C0 {}", report.all.c0);
        let shared = none
            .patches
            .iter()
            .filter(|p| full.patches.iter().any(|q| same(p, q)))
            .count();
        assert!(shared + 5 >= none.patches.len(), "{scheme}: {shared}");
    }
}

#[test]
fn none_levels_and_rings_agree() {
    // The none surface of the net refined once under none is the none surface of the net:
    // on the regular grid its 36 patches are the quarters of the 9, so their corners are the
    // 9 patches' points at the half parameters.
    for scheme in ["doo-sabin", "pgs"] {
        let m = grid(4, Some(BoundaryInterpolation::None));
        let c0 = build(scheme, &m, 3).unwrap();
        let c1 = build(scheme, &refine(scheme, &m, 1), 3).unwrap();
        assert_eq!(c1.patches.len(), 36, "{scheme}");
        let halves: Vec<Point> = c0
            .patches
            .iter()
            .flat_map(|p| (0..9).map(move |k| p.eval(0.5 * (k % 3) as f64, 0.5 * (k / 3) as f64)))
            .collect();
        for p in &c1.patches {
            for q in [
                p.eval(0.0, 0.0),
                p.eval(1.0, 0.0),
                p.eval(0.0, 1.0),
                p.eval(1.0, 1.0),
            ] {
                assert!(near_any(&halves, q, 1e-13), "{scheme}: {q:?}");
            }
        }
    }
}

#[test]
fn schemes_without_the_modes_get_them_by_preparation() {
    // The preparation stage's step (TPS: Doo-Sabin then Catmull-Clark; mixed and polar: PGS's
    // construction) gives these schemes the boundary modes their own rules lack: G^1 surfaces (TPS under
    // `none` excepted).
    for scheme in ["tps", "polar-bi2", "bi2-mixed"] {
        for mode in [BoundaryInterpolation::EdgeOnly, BoundaryInterpolation::None] {
            if scheme == "tps" && mode == BoundaryInterpolation::None {
                // TPS's preparation has no step for `none`: refused by name.
                let e = build(scheme, &grid(4, Some(mode)), 2)
                    .unwrap_err()
                    .to_string();
                assert!(e.contains("boundary mode none"), "{e}");
                continue;
            }
            let c = build(scheme, &grid(4, Some(mode)), 2)
                .unwrap_or_else(|e| panic!("{scheme} {mode:?}: {e}"));
            assert!(!c.patches.is_empty(), "{scheme} {mode:?}");
            let g1 = fairsub::analysis::continuity::check(&c)
                .by_kind
                .values()
                .map(|d| d.g1)
                .fold(0.0f64, f64::max);
            assert!(g1 < 1e-8, "{scheme} {mode:?}: G^1 {g1:e}");
        }
    }
}

#[test]
fn the_command_line_option_sets_the_mode() {
    let dir = std::env::temp_dir().join(format!("fairsub-dual-boundary-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let net = dir.join("grid.obj");
    fairsub::io::write_mesh(&net, &grid(4, None), fairsub::io::MeshFormat::Obj).unwrap();
    let run = |scheme: &str, mode: &str, out: &str| {
        std::process::Command::new(env!("CARGO_BIN_EXE_fairsub"))
            .args([
                "subdivide",
                "--scheme",
                scheme,
                "--levels",
                "1",
                "--boundary",
                mode,
            ])
            .arg("-o")
            .arg(dir.join(out))
            .arg(&net)
            .output()
            .unwrap()
    };
    for (mode, points) in [("edge-and-corner", 100), ("edge-only", 96), ("none", 64)] {
        let o = run("doo-sabin", mode, "out.obj");
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let m = fairsub::io::read_mesh(&dir.join("out.obj")).unwrap().mesh;
        assert_eq!(m.num_vertices(), points, "{mode}");
    }
    // a scheme without the modes refuses the option by name
    let o = run("tps", "none", "tps.obj");
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("--boundary"));
    let _ = std::fs::remove_dir_all(&dir);
}
