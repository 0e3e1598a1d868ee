//! Unit tests of the mesh: connectivity, validation errors, dropped vertices.

use super::*;
use crate::error::Error;

#[crate::unit::test]
fn grid_connectivity() {
    let m = crate::mesh::nets::quad_grid(3, |_, _| 0.0);
    assert_eq!(m.num_vertices(), 16);
    assert_eq!(m.num_faces(), 9);
    assert_eq!(m.num_edges(), 24);
    assert_eq!(m.valence(5), 4);
    assert!(!m.is_boundary_vertex(5));
    assert_eq!(m.valence(0), 2);
    assert_eq!(m.valence(1), 3);
    assert_eq!(m.boundary_loops().len(), 1);
    assert_eq!(m.boundary_loops()[0].len(), 12);
    assert_eq!(m.one_ring(5).len(), 8);
    assert_eq!(m.two_ring(5).len(), 7);
    assert!(m.extraordinary_vertices().is_empty());
    // Counter-clockwise neighbours of interior vertex 5 (at (1,1)).
    let nb = m.vertex_neighbors(5);
    assert_eq!(nb.len(), 4);
    let p5 = m.position(5);
    let ang: Vec<f64> = nb
        .iter()
        .map(|&w| {
            let p = m.position(w as usize);
            (p[1] - p5[1]).atan2(p[0] - p5[0])
        })
        .collect();
    for k in 0..4 {
        let d = (ang[(k + 1) % 4] - ang[k]).rem_euclid(2.0 * std::f64::consts::PI);
        assert!(
            (d - std::f64::consts::FRAC_PI_2).abs() < 1e-12,
            "not counter-clockwise"
        );
    }
    // Boundary vertex neighbours run from one boundary neighbour to the other.
    let nb1 = m.vertex_neighbors(1);
    assert_eq!(nb1.len(), 3);
    assert!(m.is_boundary_vertex(nb1[0] as usize) && m.is_boundary_vertex(nb1[2] as usize));
}

#[crate::unit::test]
fn errors_name_the_element() {
    let p = vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]];
    let e = PolyMesh::new(p.clone(), &[vec![0, 1]]).unwrap_err();
    assert!(matches!(
        e,
        Error::Mesh(MeshError::FaceTooSmall { face: 0, len: 2 })
    ));
    let e = PolyMesh::new(p.clone(), &[vec![0, 1, 7]]).unwrap_err();
    assert!(matches!(
        e,
        Error::Mesh(MeshError::IndexOutOfRange {
            face: 0,
            index: 7,
            ..
        })
    ));
    let e = PolyMesh::new(p.clone(), &[vec![0, 1, 1]]).unwrap_err();
    assert!(matches!(
        e,
        Error::Mesh(MeshError::RepeatedVertex { face: 0, vertex: 1 })
    ));
    let e = PolyMesh::new(p.clone(), &[vec![0, 1, 2], vec![0, 1, 3]]).unwrap_err();
    assert!(matches!(
        e,
        Error::Mesh(MeshError::InconsistentOrientation { .. })
    ));
    let mut q = p.clone();
    q[2][1] = f64::NAN;
    let e = PolyMesh::new(q, &[vec![0, 1, 2]]).unwrap_err();
    assert!(matches!(
        e,
        Error::Mesh(MeshError::NonFiniteCoordinate { vertex: 2 })
    ));
    let e = PolyMesh::new(p.clone(), &Vec::<Vec<usize>>::new()).unwrap_err();
    assert!(matches!(e, Error::Mesh(MeshError::Empty)));
    // Three triangles on edge 0-1.
    let mut r = p.clone();
    r.push([0.0, 0.0, 1.0]);
    let e = PolyMesh::new(r, &[vec![0, 1, 2], vec![1, 0, 3], vec![0, 1, 4]]).unwrap_err();
    assert!(
        matches!(
            e,
            Error::Mesh(MeshError::NonManifoldEdge { edge: [0, 1], .. })
        ),
        "{e}"
    );
    // Bow-tie: two triangles sharing only vertex 0.
    let mut s = p.clone();
    s.push([-1.0, 0.0, 0.0]);
    s.push([0.0, -1.0, 0.0]);
    let e = PolyMesh::new(s, &[vec![0, 1, 2], vec![0, 4, 5]]).unwrap_err();
    assert!(
        matches!(
            e,
            Error::Mesh(MeshError::NonManifoldVertex { vertex: 0, .. })
        ),
        "{e}"
    );
}

#[crate::unit::test]
fn parallel_build_reports_the_first_problem() {
    // A grid with more half-edges than one parallel block, with two flipped faces: the
    // error names the first one in half-edge order, as a sequential scan would.
    let n = 150;
    let m = crate::mesh::nets::quad_grid(n, |_, _| 0.0);
    let mut faces: Vec<Vec<usize>> = m
        .faces()
        .map(|f| f.iter().map(|&v| v as usize).collect())
        .collect();
    let (f1, f2) = (9000, 20000);
    faces[f1].reverse();
    faces[f2].reverse();
    let e = PolyMesh::new(m.positions().to_vec(), &faces).unwrap_err();
    match e {
        Error::Mesh(MeshError::InconsistentOrientation { faces, .. }) => {
            // Every conflicting edge lies between a flipped face and a neighbour.
            assert!(faces.contains(&f1), "{faces:?}");
        }
        other => panic!("{other:?}"),
    }
    // Uniform meshes store no face per half-edge and agree with arithmetic.
    assert_eq!(m.uniform_face_size(), Some(4));
    assert!(m.topology().he_face.is_empty());
    assert_eq!(m.num_edges(), 2 * n * (n + 1));
    let g = gallery_mixed();
    assert_eq!(g.uniform_face_size(), None);
    for h in 0..g.num_halfedges() as u32 {
        let f = g.he_face(h) as usize;
        assert!(g.face_starts()[f] <= h && h < g.face_starts()[f + 1]);
    }
}

/// A quad and a triangle sharing an edge.
fn gallery_mixed() -> PolyMesh {
    let p = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [2.0, 0.5, 0.0],
    ];
    PolyMesh::new(p, &[vec![0, 1, 2, 3], vec![1, 4, 2]]).unwrap()
}

#[crate::unit::test]
fn unused_vertices_dropped() {
    let p = vec![[0.0; 3], [9.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let m = PolyMesh::new(p, &[vec![0, 2, 3]]).unwrap();
    assert_eq!(m.dropped_vertices(), &[1]);
    assert_eq!(m.num_vertices(), 3);
    assert_eq!(m.face(0), &[0, 1, 2]);
}

#[crate::unit::test]
fn one_walker_around_fan_vertices() {
    // Three triangles fanned around vertex 0 (a boundary vertex); vertex 1 lies in one face only.
    let pos = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [-1.0, 0.0, 0.0],
    ];
    let m = PolyMesh::new(pos, &[vec![0, 1, 2], vec![0, 2, 3], vec![0, 3, 4]]).unwrap();
    // Half-edge h is corner h: 0->1, 1->2, 2->0 | 0->2, 2->3, 3->0 | 0->3, 3->4, 4->0.
    assert_eq!(m.outgoing(0).collect::<Vec<_>>(), vec![0, 3, 6]);
    assert_eq!(m.outgoing_halfedges(0), vec![0, 3, 6]);
    assert_eq!(m.outgoing(2).collect::<Vec<_>>(), vec![4, 2]);
    assert_eq!(m.vertex_neighbors(0), vec![1, 2, 3, 4]);
    assert_eq!(m.boundary_neighbors(0), (1, 4));
    assert_eq!(m.boundary_neighbors(2), (3, 1));
    assert_eq!(m.valence(0), 4);
    assert!(m.is_corner(1) && m.is_corner(4) && !m.is_corner(0) && !m.is_corner(2));
    assert_eq!(m.view().outgoing(3).count(), 2);
}

#[crate::unit::test]
fn interior_rings_close_or_fail() {
    let m = crate::mesh::nets::quad_grid(3, |_, _| 0.0);
    let hs = m.outgoing_halfedges(5);
    assert_eq!(hs.len(), 4);
    let ring = m.interior_ring_from(hs[1]).unwrap();
    assert_eq!(ring, vec![hs[1], hs[2], hs[3], hs[0]]);
    assert_eq!(m.interior_ring_from(m.vertex_halfedge(1)), None);
}

#[crate::unit::test]
fn vertex_data_goes_through_a_table_and_is_stored_by_its_kind() {
    // Two points, five channels (two groups of `VertexData::GROUP`); a table with a negative
    // weight takes the colours past their range.
    let d = VertexData {
        names: ["red", "green", "blue", "alpha", "quality"]
            .map(String::from)
            .to_vec(),
        kinds: vec![
            ScalarKind::U8,
            ScalarKind::U8,
            ScalarKind::I8,
            ScalarKind::F32,
            ScalarKind::F64,
        ],
        values: vec![
            255.0, 0.0, -128.0, 0.25, 1.0, //
            100.0, 10.0, 100.0, 0.5, 3.0,
        ],
    };
    let mut t = crate::stencil::StencilTable::new(2);
    t.push(crate::stencil::Stencil::from_pairs([(0, 1.5), (1, -0.5)]));
    t.push(crate::stencil::Stencil::from_pairs([(0, 0.5), (1, 0.5)]));
    let r = d.through(&t);
    assert_eq!(r.num_points(), 2);
    assert_eq!(r.names, d.names);
    let want = [
        332.5, -5.0, -242.0, 0.125, 0.0, //
        177.5, 5.0, -14.0, 0.375, 2.0,
    ];
    for (a, b) in r.values.iter().zip(want) {
        assert!((a - b).abs() < 1e-12, "{a} vs {b}");
    }
    let stored: Vec<f64> = r.values[..5]
        .iter()
        .zip(&r.kinds)
        .map(|(&x, k)| k.stored(x))
        .collect();
    assert_eq!(stored, [255.0, 0.0, -128.0, 0.125, 0.0]);
    assert_eq!(ScalarKind::U8.stored(177.5), 178.0);
    assert_eq!(ScalarKind::I16.stored(-40000.2), -32768.0);
    assert_eq!(ScalarKind::F32.stored(0.1), f64::from(0.1f32));
}
