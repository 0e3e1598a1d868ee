//! The child net of one Loop step: its corners, its half-edge connectivity (derived from the
//! parent's without search, for manifold and non-manifold parents alike) and the sharp
//! features it inherits.
//!
//! Child face `4f + i` (`i < 3`) is the corner triangle at the start of parent half-edge
//! `h = 3f + i`; its sides are `3(4f + i) + k`: `k = 0` from the vertex along `h`, `1` across
//! the parent face, `2` back along `prev(h)`. The middle face `4f + 3` has side `k` from the
//! point of edge `3f + k` to the next.

use crate::mesh::{NONE, PolyMesh, Topology, number_edges};
use crate::schemes::catmull_clark::{edge_half, general_child_topology, half_child_edge};
use crate::schemes::sdc::crease::SharpLevel;
use rayon::prelude::*;

/// Child points (or parent half-edges) per parallel task.
pub(super) const BLOCK: usize = 4096;

/// Child face of the corner where parent half-edge `h` starts: `4f + i` for `h = 3f + i`.
#[inline]
fn corner_face(h: u32) -> u32 {
    h + h / 3
}

/// Child corners of one step from the parent's arrays: parent triangle `f = (a, b, c)` becomes
/// `(a, ab, ca)`, `(b, bc, ab)`, `(c, ca, bc)`, `(ab, bc, ca)`.
pub(super) fn child_corners(corners: &[u32], he_edge: &[u32], nv: usize) -> Vec<u32> {
    let nf = corners.len() / 3;
    let nv = nv as u32;
    let mut child = crate::buffers::zeroed(12 * nf, 0u32);
    child
        .par_chunks_mut(12 * BLOCK)
        .enumerate()
        .for_each(|(c, chunk)| {
            for (k, out) in chunk.chunks_exact_mut(12).enumerate() {
                let h0 = 3 * (c * BLOCK + k);
                let [a, b, cc] = [corners[h0], corners[h0 + 1], corners[h0 + 2]];
                let ab = nv + he_edge[h0];
                let bc = nv + he_edge[h0 + 1];
                let ca = nv + he_edge[h0 + 2];
                out.copy_from_slice(&[a, ab, ca, b, bc, ab, cc, ca, bc, ab, bc, ca]);
            }
        });
    child
}

/// Half-edge topology of the child of a manifold parent. Side 0 of `h` pairs with side 2 at
/// `next(twin h)`, side 1 with a side of the middle face; edges numbered as [`number_edges`]
/// numbers them, vertex half-edges by the generic build's rule (the boundary outgoing
/// half-edge, else the smallest), so the result is what [`PolyMesh::from_refinement`] builds.
pub(super) fn manifold_halfedges(mesh: &PolyMesh) -> Topology {
    let m = mesh.view();
    let (nv, ne, nf) = (mesh.num_vertices(), mesh.num_edges(), mesh.num_faces());
    let twin: Vec<u32> = (0..12 * nf)
        .into_par_iter()
        .with_min_len(12 * BLOCK)
        .map(|c| {
            let f = (c / 12) as u32;
            let r = (c % 12) as u32;
            if r >= 9 {
                // Middle face side k: pairs with side 1 of corner face k + 1.
                let k = r - 9;
                return 12 * f + 3 * ((k + 1) % 3) + 1;
            }
            let (i, side) = (r / 3, r % 3);
            let h = 3 * f + i;
            match side {
                0 => match m.twin(h) {
                    NONE => NONE,
                    t => 3 * corner_face(m.faces.next(t)) + 2,
                },
                1 => 12 * f + 9 + (i + 2) % 3,
                _ => match m.twin(m.faces.prev(h)) {
                    NONE => NONE,
                    t => 3 * corner_face(t),
                },
            }
        })
        .collect();
    let (he_edge, edge_he) = number_edges(&twin);
    let vert_he = (0..nv + ne)
        .into_par_iter()
        .with_min_len(BLOCK)
        .map(|i| {
            if i < nv {
                return 3 * corner_face(m.vert_he[i]);
            }
            let h = m.edge_he[i - nv];
            let side = |h: u32| {
                let f = h / 3;
                (3 * corner_face(h) + 1)
                    .min(12 * f + 9 + h % 3)
                    .min(3 * corner_face(m.faces.next(h)) + 2)
            };
            let last = 3 * corner_face(m.faces.next(h)) + 2;
            match m.twin(h) {
                NONE => last,
                t => side(h).min(side(t)),
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

/// Half-edge topology of the child of any parent, non-manifold ones included: the tolerant
/// build fed with the child's edges as the parent determines them (the two halves of every
/// parent edge, shared by all its faces, and three edges inside each parent triangle), with
/// non-manifold flags passed from parent edges and vertices to their children. For a manifold
/// parent it equals [`manifold_halfedges`].
pub(super) fn general_halfedges(mesh: &PolyMesh, child_corners: &[u32]) -> Topology {
    let m = mesh.view();
    let (nv, ne, nf) = (mesh.num_vertices(), mesh.num_edges(), mesh.num_faces());
    let ne32 = ne as u32;
    // The edge inside the parent face from the point of edge(h) to that of edge(prev h).
    let inner = |h: u32| 2 * ne32 + h;
    let mut raw = Vec::with_capacity(12 * nf);
    for f in 0..nf as u32 {
        for i in 0..3 {
            let h = 3 * f + i;
            let p = m.faces.prev(h);
            raw.extend_from_slice(&[edge_half(&m, h, true), inner(h), edge_half(&m, p, false)]);
        }
        for k in 0..3 {
            raw.push(inner(3 * f + (k + 1) % 3));
        }
    }
    general_child_topology(mesh, child_corners, 3, &raw, 3 * nf, nv + ne)
}

/// The sharp features of the child (see `sdc::crease`); `topo` is the child's
/// connectivity, or `None` when the child is not given one (sharp edges named by end points).
pub(super) fn child_extras(
    mesh: &PolyMesh,
    sharp: &SharpLevel<'_>,
    topo: Option<&Topology>,
) -> crate::mesh::Extras {
    let m = mesh.view();
    let nv = mesh.num_vertices() as u32;
    sharp.child_extras(
        |h, at_to| {
            let c = if at_to {
                3 * corner_face(m.faces.next(h)) + 2
            } else {
                3 * corner_face(h)
            };
            half_child_edge(&m, nv, topo, h, at_to, c)
        },
        |f, out| out.extend(4 * f..4 * f + 4),
    )
}
