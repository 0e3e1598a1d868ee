//! Performance machinery that must stay correct: precomputed multi-level stencil tables
//! re-applied to moved control points (animation) reproduce a fresh refinement of the moved net,
//! the parallel application gives the same bits on one thread as on two, and the lean one-shot
//! kernels agree with the table path.

use fairsub::PolyMesh;
use fairsub::geom::{Point, dist};
use fairsub::schemes::{self, CatmullClark, Loop, Scheme};
use fairsub::stencil::{PackedStencilTable, StencilTable};

/// The net with every control point moved (a smooth, non-affine deformation: an animation
/// frame).
fn moved(mesh: &PolyMesh, t: f64) -> PolyMesh {
    let pos: Vec<Point> = mesh
        .positions()
        .iter()
        .map(|p| {
            [
                p[0] + 0.3 * (t + 1.7 * p[1]).sin(),
                p[1] * (1.0 + 0.2 * (t * p[2]).cos()),
                p[2] + 0.1 * p[0] * p[1],
            ]
        })
        .collect();
    PolyMesh::from_flat(pos, mesh.face_starts().to_vec(), mesh.corners().to_vec())
        .expect("same topology")
}

/// An `m x n` quad torus (all vertices regular).
fn quad_torus(m: usize, n: usize) -> PolyMesh {
    let mut pos = Vec::new();
    for i in 0..m {
        let u = std::f64::consts::TAU * i as f64 / m as f64;
        for j in 0..n {
            let v = std::f64::consts::TAU * j as f64 / n as f64;
            let r = 3.0 + v.cos();
            pos.push([r * u.cos(), r * u.sin(), v.sin()]);
        }
    }
    let id = |i: usize, j: usize| (i % m) * n + j % n;
    let faces: Vec<[usize; 4]> = (0..m * n)
        .map(|f| {
            let (i, j) = (f / n, f % n);
            [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]
        })
        .collect();
    PolyMesh::new(pos, &faces).unwrap()
}

fn max_dist(a: &[Point], b: &[Point]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(p, q)| dist(*p, *q))
        .fold(0.0, f64::max)
}

/// Applies the level table to the moved net and compares with refining the moved net.
fn check_reapply(scheme: &dyn Scheme, mesh: &PolyMesh, levels: usize) {
    let (fine, table) = schemes::level_stencils(scheme, mesh, levels).unwrap();
    assert_eq!(table.num_sources(), mesh.num_vertices());
    assert_eq!(table.num_rows(), fine.num_vertices());
    assert!(table.max_affine_defect() < 1e-12);
    // The table reproduces the refinement it was built from ...
    let direct = schemes::refine_levels(scheme, mesh, levels, |_| {}).unwrap();
    assert!(max_dist(&table.apply(mesh.positions()), direct.positions()) < 1e-12);
    // ... and, re-applied to new control points, the refinement of the moved net.
    let mut out = vec![[0.0; 3]; table.num_rows()];
    for frame in 1..=3 {
        let m = moved(mesh, frame as f64);
        table.apply_into(m.positions(), &mut out);
        let fresh = schemes::refine_levels(scheme, &m, levels, |_| {}).unwrap();
        let d = max_dist(&out, fresh.positions());
        assert!(d < 1e-12, "{}: frame {frame} differs by {d}", scheme.name());
        assert_eq!(fresh.corners(), fine.corners());
    }
}

#[test]
fn level_tables_reapply_to_moved_control_points() {
    // Extraordinary vertices of valence 3 and 5, and a net with boundary and corners.
    check_reapply(&CatmullClark, &fairsub::gallery::torus_with_evs(), 3);
    check_reapply(&CatmullClark, &fairsub::gallery::open_grid(), 2);
    check_reapply(&Loop, &fairsub::gallery::icosahedron(), 3);
    check_reapply(&Loop, &fairsub::gallery::tri_grid(), 2);
    // Zero levels: the identity.
    let m = fairsub::gallery::cube();
    let (same, id) = schemes::level_stencils(&CatmullClark, &m, 0).unwrap();
    assert_eq!(same.positions(), m.positions());
    assert_eq!(id, StencilTable::identity(8));
}

#[test]
fn parallel_application_is_deterministic() {
    // Big enough for several parallel blocks.
    let mesh = fairsub::gallery::torus_with_evs();
    let (_, table) = schemes::level_stencils(&CatmullClark, &mesh, 4).unwrap();
    assert!(table.num_rows() > 10_000);
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let mut out = vec![[0.0; 3]; table.num_rows()];
        pool.install(|| table.apply_into(mesh.positions(), &mut out));
        out
    };
    assert_eq!(run(1), run(2));
    // The packed form gives the same bits, on one thread and on two; on a net with large regular
    // regions it stores a small fraction of the weights.
    let packed = PackedStencilTable::new(&table);
    let run_packed = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let mut out = vec![[0.0; 3]; table.num_rows()];
        pool.install(|| packed.apply_into(mesh.positions(), &mut out));
        out
    };
    assert_eq!(run_packed(1), run(1));
    assert_eq!(run_packed(2), run(1));
    let big = quad_torus(60, 40);
    let (_, table) = schemes::level_stencils(&CatmullClark, &big, 3).unwrap();
    let packed = PackedStencilTable::new(&table);
    let share = packed.num_stored_weights() as f64 / table.num_entries() as f64;
    println!(
        "packed: {} of {} weights stored ({:.1} %)",
        packed.num_stored_weights(),
        table.num_entries(),
        100.0 * share
    );
    assert!(share < 0.01, "packed table keeps {share} of its weights");
}

#[test]
fn one_shot_kernels_match_the_tables() {
    // Catmull-Clark with an n-gon (the first step makes quads) and Loop: the fused kernels of
    // `refine_uniform` and the table path give the same points and faces.
    let prism = fairsub::gallery::prism(5);
    let a = CatmullClark::refine_uniform(&prism, 3, |_| {}).unwrap();
    let (b, t) = schemes::level_stencils(&CatmullClark, &prism, 3).unwrap();
    assert!(max_dist(a.positions(), b.positions()) < 1e-12);
    assert!(max_dist(a.positions(), &t.apply(prism.positions())) < 1e-12);
    assert_eq!(a.corners(), b.corners());
    assert_eq!(a.face_starts(), b.face_starts());
    let ico = fairsub::gallery::icosahedron();
    let a = Loop::refine_uniform(&ico, 3, |_| {}).unwrap();
    let (b, _) = schemes::level_stencils(&Loop, &ico, 3).unwrap();
    assert!(max_dist(a.positions(), b.positions()) < 1e-12);
    assert_eq!(a.corners(), b.corners());
    assert_eq!(a.num_faces(), 20 * 64);
}

#[test]
fn limit_points_are_the_same_from_every_level() {
    // The limit point of a vertex does not depend on the level it is computed from: a check of
    // the (allocation-free, parallel) limit stencils independent of their formulas. Nets with
    // boundary and corners, extraordinary vertices, and an n-gon (limits through the child).
    for mesh in [
        fairsub::gallery::open_grid(),
        fairsub::gallery::torus_with_evs(),
        fairsub::gallery::prism(5),
    ] {
        let coarse = CatmullClark::limit_stencils(&mesh).apply(mesh.positions());
        let fine = schemes::refine_levels(&CatmullClark, &mesh, 3, |_| {}).unwrap();
        let limits = CatmullClark::limit_stencils(&fine).apply(fine.positions());
        let d = max_dist(&coarse, &limits[..coarse.len()]);
        assert!(d < 1e-12, "limit points move by {d} under refinement");
        // And the refined points approach them.
        let far = max_dist(&coarse, &fine.positions()[..coarse.len()]);
        assert!(
            far > 1e-6 && far < 0.1,
            "level 3 points are {far} from their limits"
        );
    }
}
