//! Unit tests of Loop's plain rules: published weights, the face check, kernels against the
//! generic path.

use super::*;

/// Regular interior (valence 6) weights, Warren's n = 3 value, and the limit masks.
#[crate::unit::test]
fn published_weights() {
    assert_eq!(Loop::vertex_beta(6), 1.0 / 16.0);
    assert_eq!(Loop::vertex_beta(3), 3.0 / 16.0);
    assert_eq!(Loop::vertex_beta(4), (0.625 - 0.375 * 0.375) / 4.0);
    assert!((Loop::limit_chi(6) - 1.0 / 12.0).abs() < 1e-16);
    // n = 5: beta = (5/8 - (3/8 + cos(72 deg)/4)^2)/5 = 0.0790924...
    let c = (2.0 * std::f64::consts::PI / 5.0).cos();
    let beta5 = (0.625 - (0.375 + 0.25 * c).powi(2)) / 5.0;
    assert!((Loop::vertex_beta(5) - beta5).abs() < 1e-16);
    assert!((Loop::vertex_beta(5) - 0.084_093_2).abs() < 1e-7);
}

#[crate::unit::test]
fn quad_face_is_named() {
    let pos = vec![
        [0.0; 3],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [2.0; 3],
    ];
    let m = PolyMesh::new(pos, &[vec![0, 1, 4], vec![0, 4, 2, 3]]).unwrap();
    let msg = Loop.refine(&m).unwrap_err().to_string();
    assert!(msg.contains("face 1 has 4 corners"), "{msg}");
    assert!(
        msg.contains("triangulate the net or use catmull-clark"),
        "{msg}"
    );
    assert!(Loop.limit_stencils(&m).is_err());
    assert!(Loop.limit_tangent_stencils(&m).is_err());
}

#[crate::unit::test]
fn direct_child_and_one_shot_levels_equal_the_generic_path() {
    let dist = |a: &[Point], b: &[Point]| {
        a.iter()
            .zip(b)
            .map(|(p, q)| crate::geom::dist(*p, *q))
            .fold(0.0, f64::max)
    };
    let nets: Vec<(String, PolyMesh)> = crate::gallery::all()
        .into_iter()
        .filter(|(_, m)| m.is_all_triangles())
        .collect();
    assert!(nets.len() >= 4);
    for (name, mesh) in nets {
        let mut m = mesh.clone();
        for level in 0..2 {
            let what = format!("{name} level {level}");
            let st = Loop::stencils(&m).unwrap();
            let pts = st.apply(m.positions());
            let direct = Loop::child_mesh(&m, pts.clone()).unwrap();
            let (fs, c) = (direct.face_starts().to_vec(), direct.corners().to_vec());
            let generic = PolyMesh::from_refinement(pts.clone(), fs, c).unwrap();
            crate::mesh::assert_same_topology(&direct, &generic, &what);
            let fused = Loop::refine_points(&m, m.positions()).unwrap();
            assert!(dist(&fused, &pts) < 1e-13, "{what}");
            m = direct;
        }
        for levels in 0..=3 {
            let what = format!("{name}, {levels} levels");
            let fast = Loop::refine_uniform(&mesh, levels, |_| {}).unwrap();
            let mut slow = mesh.clone();
            for _ in 0..levels {
                slow = Loop.refine(&slow).unwrap().mesh;
            }
            assert!(dist(fast.positions(), slow.positions()) < 1e-12, "{what}");
            crate::mesh::assert_same_topology(&fast, &slow, &what);
        }
    }
}
