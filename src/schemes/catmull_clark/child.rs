//! The child net of one Catmull-Clark step: its corners, its half-edge connectivity (derived
//! from the parent's without any search, for manifold and non-manifold parents alike) and the
//! sharp features it inherits.
//!
//! Child face `h` is the quad of parent corner (half-edge) `h`: (vertex point, edge point of
//! the outgoing edge, face point, edge point of the incoming edge). Child half-edge `4h + k` is
//! side `k` of child face `h`.

use crate::geom::Point;
use crate::mesh::{FaceIndex, MeshParts, MeshView, NONE, PolyMesh, Topology, number_edges};
use crate::schemes::sdc::crease::{ChildEdge, SharpLevel};
use rayon::prelude::*;

/// Child points (or parent half-edges) per parallel task.
pub(super) const BLOCK: usize = 4096;

/// Child corners of one step from the parent's arrays: child face `h` is
/// `(from(h), edge point of h, face point of h, edge point of prev(h))`.
pub(super) fn child_corners(
    faces: FaceIndex<'_>,
    corners: &[u32],
    he_edge: &[u32],
    nv: usize,
    ne: usize,
) -> Vec<u32> {
    let nh = corners.len();
    let (nv, nve) = (nv as u32, (nv + ne) as u32);
    let mut child = crate::buffers::zeroed(4 * nh, 0u32);
    child
        .par_chunks_mut(4 * BLOCK)
        .enumerate()
        .for_each(|(b, chunk)| {
            let h0 = b * BLOCK;
            for (k, quad) in chunk.chunks_exact_mut(4).enumerate() {
                let h = (h0 + k) as u32;
                quad.copy_from_slice(&[
                    corners[h as usize],
                    nv + he_edge[h as usize],
                    nve + faces.face(h),
                    nv + he_edge[faces.prev(h) as usize],
                ]);
            }
        });
    child
}

/// Half-edge topology of the child of a manifold parent. Twins are known combinatorially:
/// `4h` and `4 next(twin h) + 3`, `4h + 1` and `4 next(h) + 2`; the edges are numbered as
/// [`number_edges`] numbers them and the vertex half-edges follow the generic build's rule (the
/// boundary outgoing half-edge, else the smallest), so the result is what
/// [`PolyMesh::from_refinement`] would build.
pub(super) fn manifold_halfedges(mesh: &PolyMesh) -> Topology {
    let m = mesh.view();
    let (nv, ne, nf) = (mesh.num_vertices(), mesh.num_edges(), mesh.num_faces());
    let nh = mesh.num_halfedges();
    let twin: Vec<u32> = (0..4 * nh)
        .into_par_iter()
        .with_min_len(4 * BLOCK)
        .map(|c| {
            let h = (c / 4) as u32;
            match c % 4 {
                0 => match m.twin(h) {
                    NONE => NONE,
                    t => 4 * m.faces.next(t) + 3,
                },
                1 => 4 * m.faces.next(h) + 2,
                2 => 4 * m.faces.prev(h) + 1,
                _ => match m.twin(m.faces.prev(h)) {
                    NONE => NONE,
                    t => 4 * t,
                },
            }
        })
        .collect();
    let (he_edge, edge_he) = number_edges(&twin);
    let vert_he = (0..nv + ne + nf)
        .into_par_iter()
        .with_min_len(BLOCK)
        .map(|i| {
            if i < nv {
                4 * m.vert_he[i]
            } else if i < nv + ne {
                let h = m.edge_he[i - nv];
                let a = 4 * m.faces.next(h) + 3;
                match m.twin(h) {
                    NONE => a,
                    t => a.min(4 * h + 1).min(4 * t + 1).min(4 * m.faces.next(t) + 3),
                }
            } else {
                4 * m.faces.start(i - nv - ne) + 2
            }
        })
        .collect();
    Topology {
        he_face: Vec::new(),
        twin,
        he_edge,
        edge_he,
        vert_he,
        nm: None,
    }
}

/// The end (0 or 1) of edge(h) at which the start of half-edge `h` lies.
#[inline]
fn end_at_from(m: &MeshView<'_>, h: u32) -> u32 {
    let first = m.edge_he[m.he_edge[h as usize] as usize];
    u32::from(!(h == first || m.from(h) == m.from(first)))
}

/// Half-edge topology of the child of any parent, non-manifold ones included (the tolerant
/// build of `mesh::general` fed with the child's edges as the parent determines them, as
/// OpenSubdiv's refinement does: the two halves of every parent edge, shared by all its faces,
/// and one edge per parent corner from its edge point to the face point). Non-manifold flags
/// pass from parent edges to their halves and edge points, from parent vertices to their
/// vertex points. For a manifold parent it equals [`manifold_halfedges`].
pub(super) fn general_halfedges(mesh: &PolyMesh, child_corners: &[u32]) -> Topology {
    let m = mesh.view();
    let (nv, ne, nf) = (mesh.num_vertices(), mesh.num_edges(), mesh.num_faces());
    let nh = mesh.num_halfedges() as u32;
    let ne32 = ne as u32;
    let mut raw = Vec::with_capacity(4 * nh as usize);
    for h in 0..nh {
        let p = m.faces.prev(h);
        raw.extend_from_slice(&[
            edge_half(&m, h, true),
            2 * ne32 + h,
            2 * ne32 + p,
            edge_half(&m, p, false),
        ]);
    }
    general_child_topology(mesh, child_corners, 4, &raw, nh as usize, nv + ne + nf)
}

/// The raw child edge of the half of parent edge(h) at the start (`at_from`) or the end of
/// `h`: `2 e + end`, the two halves of every parent edge shared by all its faces.
#[inline]
pub(crate) fn edge_half(m: &MeshView<'_>, h: u32, at_from: bool) -> u32 {
    let e = m.he_edge[h as usize];
    let end = end_at_from(m, h);
    2 * e + if at_from { end } else { 1 - end }
}

/// The tolerant build of a uniform child (faces of `arity` corners, `num_points` points) from
/// its raw edges per child half-edge: the halves of the parent edges ([`edge_half`]) and then
/// `inner` edges inside the parent faces. Non-manifold flags pass from parent edges to their
/// halves and edge points (numbered after the `nv` vertex points), from parent vertices to
/// their vertex points. Catmull-Clark's and Loop's [`general_halfedges`] end here.
pub(crate) fn general_child_topology(
    mesh: &PolyMesh,
    child_corners: &[u32],
    arity: u32,
    raw: &[u32],
    inner: usize,
    num_points: usize,
) -> Topology {
    let (nv, ne) = (mesh.num_vertices(), mesh.num_edges());
    let mut raw_nm = vec![false; 2 * ne + inner];
    let mut nm_vertex = vec![false; num_points];
    if let Some(nm) = mesh.topology().nm.as_deref() {
        for e in 0..ne {
            if nm.edge[e] {
                raw_nm[2 * e] = true;
                raw_nm[2 * e + 1] = true;
                nm_vertex[nv + e] = true;
            }
        }
        nm_vertex[..nv].copy_from_slice(&nm.vertex);
    }
    let faces = FaceIndex {
        face_start: &[],
        he_face: &[],
        uniform: arity,
    };
    Topology::build_general(
        num_points,
        faces,
        child_corners,
        raw,
        2 * ne + inner,
        &raw_nm,
        &nm_vertex,
    )
}

/// The child edge of the half of parent edge(h) at its end (`at_to`) or start: the child
/// half-edge `c` on it when the child's connectivity `topo` is given, else the half's end
/// points (the edge point is `nv + edge(h)`, `nv` the parent's vertex count). Catmull-Clark's and Loop's `child_extras` name
/// sharp halves with it.
pub(crate) fn half_child_edge(
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

/// The sharp features of the child: edge halves and vertex sharpness by OpenSubdiv's rules,
/// holes to their child faces. `topo` is the child's connectivity, or `None` when the child
/// is not given one (then the sharp edges are named by their end points).
pub(super) fn child_extras(
    mesh: &PolyMesh,
    sharp: &SharpLevel<'_>,
    topo: Option<&Topology>,
) -> crate::mesh::Extras {
    let m = mesh.view();
    let nv = mesh.num_vertices() as u32;
    sharp.child_extras(
        |h, at_to| {
            // The child half-edge on the half: side 0 of child face h at the start of h, side
            // 3 of child face next(h) at its end.
            let c = if at_to {
                4 * m.faces.next(h) + 3
            } else {
                4 * h
            };
            half_child_edge(&m, nv, topo, h, at_to, c)
        },
        |f, out| {
            let s = m.faces.start(f as usize);
            let k = m.face_corners(f as usize).len() as u32;
            out.extend(s..s + k);
        },
    )
}

/// The last step of [`super::CatmullClark::refine_uniform`]: consumes the parent, keeping only
/// what the child faces need (its corners, face offsets and edge numbers).
pub(super) fn last_child(parent: PolyMesh, positions: Vec<Point>) -> PolyMesh {
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
    let child = child_corners(faces, &corners, &he_edge, nv, ne);
    drop((face_start, corners, he_face, he_edge));
    PolyMesh::from_trusted_uniform(positions, 4, child, None)
}
