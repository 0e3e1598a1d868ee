//! The triangle 1-4 split (Loop's and the butterfly scheme's topology), without any weights:
//! every edge gets a point and every triangle becomes four. A scheme supplies the masks of the
//! vertex points and edge points.
//!
//! Layout of the child: vertex `v < V` is parent vertex `v`, vertex `V + e` the point of parent
//! edge `e` (the mesh's edge numbering). Parent triangle `f = (a, b, c)` with edge points `ab`,
//! `bc`, `ca` becomes child faces `4f .. 4f + 3` = `(a, ab, ca)`, `(b, bc, ab)`, `(c, ca, bc)`,
//! `(ab, bc, ca)`, oriented like the parent (the layout of `schemes::loop_subdivision`).

use super::PolyMesh;
use crate::error::{Error, Result};

/// The child triangles of one 1-4 split of the triangle net `mesh` (three corners each, in the
/// layout of the [module](self)). Errors name the first face that is not a triangle.
pub fn tri_split(mesh: &PolyMesh) -> Result<Vec<u32>> {
    let nv = mesh.num_vertices() as u32;
    if nv as usize + mesh.num_edges() > u32::MAX as usize {
        return Err(Error::Unsupported(
            "one 1-4 split would create more points than 32-bit indices allow".into(),
        ));
    }
    let mut corners = Vec::with_capacity(12 * mesh.num_faces());
    for f in 0..mesh.num_faces() {
        require_triangle(mesh, f, "the triangle 1-4 split")?;
        let h = mesh.face_halfedge(f);
        let hs = [h, mesh.he_next(h), mesh.he_prev(h)];
        let [a, b, c] = hs.map(|h| mesh.he_from(h));
        let [ab, bc, ca] = hs.map(|h| nv + mesh.he_edge(h));
        corners.extend_from_slice(&[a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca]);
    }
    Ok(corners)
}

/// The error of a split that needs triangles (`what`) when face `f` is not one.
pub(crate) fn require_triangle(mesh: &PolyMesh, f: usize, what: &str) -> Result<()> {
    let k = mesh.face_size(f);
    if k == 3 {
        return Ok(());
    }
    Err(Error::UnsupportedFace {
        face: f,
        msg: format!("{what} needs a triangle net, but face {f} has {k} corners"),
    })
}

/// The child rows and parent columns of the one-ring of vertex `v` in one 1-4 split of
/// `mesh`: `v` and the points of its edges, `v` and its neighbours, both counter-clockwise
/// from the same edge (the local matrix of a scheme on this split is its table's rows `rows`
/// restricted to the sources `cols`).
pub fn one_ring_rows(mesh: &PolyMesh, v: usize) -> (Vec<usize>, Vec<usize>) {
    let nv = mesh.num_vertices();
    let mut rows = vec![v];
    rows.extend(mesh.outgoing(v).map(|h| nv + mesh.he_edge(h) as usize));
    let mut cols = vec![v];
    cols.extend(mesh.vertex_neighbors(v).iter().map(|&u| u as usize));
    (rows, cols)
}

/// Face offsets of a child made of `corners.len() / 3` triangles.
pub fn triangle_starts(corners: &[u32]) -> Vec<u32> {
    (0..=corners.len() as u32 / 3).map(|f| 3 * f).collect()
}
