//! The child net of one uniform split step (the mesh layer's [`UniformSplit`]: Catmull-Clark's
//! quads, Loop's triangles) with the sharp features it inherits by OpenSubdiv's rules
//! (`sdc::crease`): written once for every split, the split only says which child
//! half-edge lies on each half of a parent edge and which child faces a parent face has.

use crate::geom::Point;
use crate::mesh::split::UniformSplit;
use crate::mesh::{Extras, FaceIndex, MeshParts, MeshView, PolyMesh, Topology};
use crate::schemes::sdc::crease::{ChildEdge, SharpLevel};

/// The child net of one step of `mesh` with the child points `positions` (one per child
/// vertex), its half-edges derived from the parent's without search (for a manifold parent
/// what [`PolyMesh::from_refinement`] would build), carrying the sharp features of `sharp`.
///
/// # Panics
/// Panics when `positions` does not have one point per child vertex.
pub(crate) fn child_mesh<S: UniformSplit>(
    mesh: &PolyMesh,
    positions: Vec<Point>,
    sharp: Option<&SharpLevel<'_>>,
) -> PolyMesh {
    assert_eq!(
        positions.len(),
        S::num_points(mesh),
        "one point per child vertex"
    );
    let corners = S::child_corners(mesh);
    let topo = S::child_halfedges(mesh, &corners);
    let extras = sharp.map(|sl| child_extras::<S>(mesh, sl, Some(&topo)));
    PolyMesh::from_trusted_uniform(positions, S::ARITY, corners, Some(topo)).with_extras(extras)
}

/// The sharp features of the child: edge halves and vertex sharpness by OpenSubdiv's rules,
/// holes to their child faces. `topo` is the child's connectivity, or `None` when the child
/// is not given one (then the sharp edges are named by their end points).
pub(crate) fn child_extras<S: UniformSplit>(
    mesh: &PolyMesh,
    sharp: &SharpLevel<'_>,
    topo: Option<&Topology>,
) -> Extras {
    let m = mesh.view();
    let nv = mesh.num_vertices() as u32;
    sharp.child_extras(
        |h, at_to| half_child_edge(&m, nv, topo, h, at_to, S::half_side(&m, h, at_to)),
        |f, out| out.extend(S::face_children(&m, f)),
    )
}

/// The child edge of the half of parent edge(h) at its end (`at_to`) or start: the child
/// half-edge `c` on it when the child's connectivity `topo` is given, else the half's end
/// points (the edge point is `nv + edge(h)`, `nv` the parent's vertex count).
fn half_child_edge(
    m: &MeshView<'_>,
    nv: u32,
    topo: Option<&Topology>,
    h: u32,
    at_to: bool,
    c: u32,
) -> ChildEdge {
    match topo {
        Some(t) => ChildEdge::Id(t.he_edge[c as usize]),
        None => {
            let ep = nv + m.he_edge[h as usize];
            ChildEdge::Pair(if at_to {
                [ep, m.to(h)]
            } else {
                [m.from(h), ep]
            })
        }
    }
}

/// The child of a borrowed manifold parent without half-edges (built on first use, if ever).
pub(crate) fn bare_child<S: UniformSplit>(mesh: &PolyMesh, positions: Vec<Point>) -> PolyMesh {
    PolyMesh::from_trusted_uniform(positions, S::ARITY, S::child_corners(mesh), None)
}

/// The child of an owned manifold parent without half-edges: consumes the parent, keeping only
/// what the child faces need (its corners, face offsets and edge numbers) before the child's
/// faces are allocated.
pub(crate) fn last_child<S: UniformSplit>(parent: PolyMesh, positions: Vec<Point>) -> PolyMesh {
    let nv = parent.num_vertices();
    let ne = parent.num_edges();
    let MeshParts {
        positions: parent_positions,
        face_start,
        corners,
        uniform,
        topo,
    } = parent.into_parts();
    drop(parent_positions);
    let Topology {
        he_face, he_edge, ..
    } = topo.expect("an intermediate level has its topology");
    let faces = FaceIndex {
        face_start: &face_start,
        he_face: &he_face,
        uniform,
    };
    let child = S::corners(faces, &corners, &he_edge, nv, ne);
    drop((face_start, corners, he_face, he_edge));
    PolyMesh::from_trusted_uniform(positions, S::ARITY, child, None)
}
