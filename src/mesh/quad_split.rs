//! The quad split with face points (Catmull-Clark's topology, also non-box's adaptive levels),
//! without any weights: every vertex, edge and face gets a point and every face of `k` corners
//! becomes `k` quads. A scheme supplies the masks.
//!
//! Layout of the child (see [`super::split`]): vertex `v < V` is the point of parent vertex
//! `v`, vertex `V + e` that of parent edge `e`, vertex `V + E + f` that of parent face `f`.
//! Child face `h` is the quad of parent corner (half-edge) `h`: (vertex point, point of the
//! outgoing edge, face point, point of the incoming edge), oriented like the parent. Child
//! half-edge `4h + k` is side `k` of child face `h`.

use super::split::{UniformSplit, edge_half, general_child_topology};
use super::{FaceIndex, MeshView, NONE, PolyMesh, Topology, number_edges};
use rayon::prelude::*;
use std::ops::Range;

/// Child points (or parent half-edges) per parallel task.
const BLOCK: usize = 4096;

/// The quad split with face points (the [module](self)'s layout).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct QuadSplit;

impl UniformSplit for QuadSplit {
    const ARITY: u32 = 4;

    fn num_points(mesh: &PolyMesh) -> usize {
        mesh.num_vertices() + mesh.num_edges() + mesh.num_faces()
    }

    /// Child face `h` is `(from(h), edge point of h, face point of h, edge point of prev(h))`.
    fn corners(
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

    /// Twins are known combinatorially: `4h` and `4 next(twin h) + 3`, `4h + 1` and
    /// `4 next(h) + 2`; the edges are numbered as [`number_edges`] numbers them and the vertex
    /// half-edges follow the generic build's rule (the boundary outgoing half-edge, else the
    /// smallest).
    fn manifold_halfedges(mesh: &PolyMesh) -> Topology {
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
        Topology::of_uniform_manifold(twin, he_edge, edge_he, vert_he)
    }

    /// The child edges: the two halves of every parent edge, and one edge per parent corner
    /// from its edge point to the face point.
    fn general_halfedges(mesh: &PolyMesh, child_corners: &[u32]) -> Topology {
        let m = mesh.view();
        let nh = mesh.num_halfedges() as u32;
        let ne32 = mesh.num_edges() as u32;
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
        general_child_topology(
            mesh,
            child_corners,
            4,
            &raw,
            nh as usize,
            Self::num_points(mesh),
        )
    }

    /// Side 0 of child face `h` at the start of `h`, side 3 of child face `next(h)` at its end.
    #[inline]
    fn half_side(m: &MeshView<'_>, h: u32, at_to: bool) -> u32 {
        if at_to {
            4 * m.faces.next(h) + 3
        } else {
            4 * h
        }
    }

    /// One child per corner: the face's half-edges.
    fn face_children(m: &MeshView<'_>, f: u32) -> Range<u32> {
        let s = m.faces.start(f as usize);
        s..s + m.face_corners(f as usize).len() as u32
    }
}

/// Face offsets of the child of a net with `num_halfedges` corners (all quads).
pub(crate) fn quad_starts(num_halfedges: usize) -> Vec<u32> {
    (0..num_halfedges + 1)
        .into_par_iter()
        .map(|h| 4 * h as u32)
        .collect()
}
