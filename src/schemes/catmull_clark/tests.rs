//! Unit tests of Catmull-Clark's plain rules: hand values, kernels against tables, one-shot
//! levels against repeated steps.

use super::*;
use crate::geom;

#[crate::unit::test]
fn cube_one_level_by_hand() {
    let m = crate::mesh::nets::unit_cube();
    let r = CatmullClark.refine(&m).unwrap();
    assert_eq!(r.mesh.num_vertices(), 8 + 12 + 6);
    assert_eq!(r.mesh.num_faces(), 24);
    // Vertex (0,0,0), valence 3: Q = mean of face points of the 3 faces at it
    // = ((0.5,0.5,0)+(0.5,0,0.5)+(0,0.5,0.5))/3 = (1/3,1/3,1/3);
    // R = mean of edge midpoints = ((0.5,0,0)+(0,0.5,0)+(0,0,0.5))/3 = (1/6,1/6,1/6);
    // V' = (Q + 2R + (n-3) v)/n = (1/3 + 1/3)/3 = 2/9 per coordinate.
    let p = r.mesh.position(0);
    for c in p {
        assert!((c - 2.0 / 9.0).abs() < 1e-15, "{p:?}");
    }
    // Edge (0,0,0)-(1,0,0): (a + b + F1 + F2)/4 with F1=(0.5,0.5,0), F2=(0.5,0,0.5):
    // (0.5, 0.125, 0.125).
    let e = (0..m.num_edges()).find(|&e| {
        let [a, b] = m.edge(e);
        (a.min(b), a.max(b)) == (0, 1)
    });
    let q = r.mesh.position(8 + e.unwrap());
    assert!(
        (q[0] - 0.5).abs() < 1e-15 && (q[1] - 0.125).abs() < 1e-15 && (q[2] - 0.125).abs() < 1e-15
    );
    // Face point of the bottom face.
    assert_eq!(r.mesh.position(20), [0.5, 0.5, 0.0]);
    assert!(r.mesh.is_all_quads());
}

#[crate::unit::test]
fn limit_is_fixed_under_refinement() {
    // Limit of a vertex equals the limit of its child (vertex points keep their index).
    let m = crate::mesh::nets::unit_cube();
    let l0 = CatmullClark::limit_stencils(&m).apply(m.positions());
    let r = CatmullClark.refine(&m).unwrap();
    let l1 = CatmullClark::limit_stencils(&r.mesh).apply(r.mesh.positions());
    for v in 0..8 {
        assert!(geom::dist(l0[v], l1[v]) < 1e-14);
    }
}

fn max_dist(a: &[Point], b: &[Point]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(p, q)| geom::dist(*p, *q))
        .fold(0.0, f64::max)
}

#[crate::unit::test]
fn direct_child_equals_generic_build_and_kernel_equals_table() {
    for (name, mesh) in crate::gallery::all() {
        let mut m = mesh;
        for level in 0..2 {
            let what = format!("{name} level {level}");
            let st = CatmullClark::stencils(&m);
            let pts = st.apply(m.positions());
            let direct = CatmullClark::child_mesh(&m, pts.clone());
            let (fs, c) = CatmullClark::child_topology(&m);
            let generic = PolyMesh::from_refinement(pts.clone(), fs, c).unwrap();
            crate::mesh::assert_same_topology(&direct, &generic, &what);
            let fused = CatmullClark::refine_points(&m, m.positions());
            assert!(max_dist(&fused, &pts) < 1e-13, "{what}");
            // Rows built by the rules equal the single-point stencils.
            let rules = Rules::new(&m, &Opts::default());
            for v in 0..m.num_vertices() {
                assert_eq!(st.stencil(v), rules.vertex_stencil(v), "{what}");
            }
            for e in 0..m.num_edges() {
                let r = m.num_vertices() + e;
                assert_eq!(st.stencil(r), rules.edge_stencil(e), "{what}");
            }
            m = direct;
        }
    }
}

#[crate::unit::test]
fn one_shot_levels_equal_repeated_steps() {
    for (name, mesh) in crate::gallery::all() {
        for levels in 0..=3 {
            let what = format!("{name}, {levels} levels");
            let mut calls = Vec::new();
            let fast = CatmullClark::refine_uniform(&mesh, levels, |l| calls.push(l)).unwrap();
            assert_eq!(calls, (1..=levels).collect::<Vec<_>>());
            let mut slow = mesh.clone();
            for _ in 0..levels {
                slow = CatmullClark.refine(&slow).unwrap().mesh;
            }
            assert!(
                max_dist(fast.positions(), slow.positions()) < 1e-12,
                "{what}"
            );
            // The last level's connectivity is built on first use and agrees.
            crate::mesh::assert_same_topology(&fast, &slow, &what);
        }
    }
    // Through the trait, as the CLI calls it; other data widths through the kernel.
    let m = crate::mesh::nets::unit_cube();
    let r = super::super::refine_levels(&CatmullClark, &m, 2, |_| {}).unwrap();
    assert_eq!(r.num_faces(), 96);
    let colours: Vec<[f64; 1]> = (0..8).map(|v| [v as f64]).collect();
    let c1 = CatmullClark::refine_points(&m, &colours);
    let t = CatmullClark::stencils(&m).apply(&colours);
    assert!(c1.iter().zip(&t).all(|(a, b)| (a[0] - b[0]).abs() < 1e-14));
}
