//! The gallery of control nets: small, carefully chosen inputs that show shape quality.
//!
//! The papers judge schemes on small nets where the extraordinary region dominates: extended
//! c-nets (three rings of quads around one extraordinary vertex) of valence 3 to 10 in convex,
//! saddle, planar-sector and single-raised-node shapes, prisms with n-gon caps, closed solids
//! (cube, tetrahedron, octahedron, icosahedron, a torus with extraordinary vertices), open meshes
//! and triangle meshes, and the FCV-scale series of the non-box paper (the cube triangulated
//! around scaled face control vertices). Every net here is built by a function, so the files in
//! the repository's `gallery/` folder are reproducible (`fairsub gallery -o gallery` writes them; a test checks
//! they are in sync).

use crate::mesh::PolyMesh;
pub use crate::mesh::nets::*;

/// The cube of [`cube`] with face control vertices `scale` times the face barycentres (scaled
/// about the origin; the non-box paper's Fig. 10 takes 0.5, 1 and 1.5), as the
/// quasi-four-directional triangle net of non-box subdivision: the 8 corners, then the 6 FCVs
/// (the type-2 vertices, last), each face fanned into four triangles around its FCV. For
/// `--scheme nonbox-4dir`; the quad variant reaches the same surface from `gallery:cube` with an
/// FCV scale ([`crate::schemes::nonbox::FcvNet::scaled`]).
pub fn nonbox_cube_fcv(scale: f64) -> PolyMesh {
    use crate::schemes::nonbox::{FcvNet, fourdir::triangulate};
    let net = FcvNet::scaled(cube(), scale).expect("finite scale");
    triangulate(&net).mesh
}

/// The default net of `fairsub demo`: the convex extended c-net of valence 5.
pub fn default_net() -> PolyMesh {
    cnet(5, CnetShape::Convex, 3)
}

/// Every gallery net with its file stem.
pub fn all() -> Vec<(String, PolyMesh)> {
    let mut out = vec![
        ("cube".to_string(), cube()),
        ("tetrahedron".to_string(), tetrahedron()),
        ("octahedron".to_string(), octahedron()),
        ("icosahedron".to_string(), icosahedron()),
        ("torus-evs".to_string(), torus_with_evs()),
        ("open-grid".to_string(), open_grid()),
        ("open-pipe".to_string(), open_pipe()),
        ("tri-grid".to_string(), tri_grid()),
    ];
    for n in [3, 5, 6, 8] {
        out.push((format!("prism-{n}"), prism(n)));
    }
    for (name, s) in [("0.5", 0.5), ("1", 1.0), ("1.5", 1.5)] {
        out.push((format!("nonbox-cube-fcv-{name}"), nonbox_cube_fcv(s)));
    }
    for n in 3..=10 {
        for shape in CnetShape::ALL {
            out.push((format!("cnet-{n}-{}", shape.name()), cnet(n, shape, 3)));
        }
    }
    out
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn cnets_have_one_extraordinary_vertex() {
        for n in 3..=10 {
            let m = cnet(n, CnetShape::Convex, 3);
            assert_eq!(m.num_vertices(), 1 + 12 * n);
            assert_eq!(m.num_faces(), 9 * n);
            assert_eq!(m.valence(0), n);
            let interior_irregular: Vec<usize> = m
                .extraordinary_vertices()
                .into_iter()
                .filter(|&v| !m.is_boundary_vertex(v))
                .collect();
            if n == 4 {
                assert!(interior_irregular.is_empty());
            } else {
                assert_eq!(interior_irregular, vec![0]);
            }
        }
    }

    #[crate::unit::test]
    fn torus_has_four_valence_3_and_four_valence_5() {
        let m = torus_with_evs();
        let mut v3 = 0;
        let mut v5 = 0;
        for v in 0..m.num_vertices() {
            match m.valence(v) {
                3 => v3 += 1,
                5 => v5 += 1,
                4 => {}
                k => panic!("valence {k}"),
            }
        }
        assert_eq!((v3, v5), (4, 4));
        assert!(m.boundary_loops().is_empty());
        // Euler characteristic of a torus.
        assert_eq!(
            m.num_vertices() as i64 - m.num_edges() as i64 + m.num_faces() as i64,
            0
        );
    }

    #[crate::unit::test]
    fn closed_solids_are_closed() {
        for m in [cube(), tetrahedron(), octahedron(), icosahedron(), prism(5)] {
            assert!(m.boundary_loops().is_empty());
            assert_eq!(
                m.num_vertices() as i64 - m.num_edges() as i64 + m.num_faces() as i64,
                2
            );
        }
        assert_eq!(open_pipe().boundary_loops().len(), 2);
    }
}

#[cfg(feature = "unit-tests")]
mod cnet_walk_tests {
    use super::*;

    #[crate::unit::test]
    fn cnet_indices_reproduce_the_gallery_order() {
        for n in 3..=8 {
            let m = cnet(n, CnetShape::Saddle, 3);
            let idx = m.cnet_indices(0, 3).unwrap();
            let expect: Vec<u32> = (0..m.num_vertices() as u32).collect();
            assert_eq!(idx, expect, "n = {n}");
        }
    }
}
