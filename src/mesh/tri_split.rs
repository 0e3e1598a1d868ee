//! The triangle 1-4 split (Loop's and the butterfly scheme's topology), without any weights:
//! every edge gets a point and every triangle becomes four. A scheme supplies the masks of the
//! vertex points and edge points.
//!
//! Layout of the child: vertex `v < V` is parent vertex `v`, vertex `V + e` the point of parent
//! edge `e` (the mesh's edge numbering). Parent triangle `f = (a, b, c)` with edge points `ab`,
//! `bc`, `ca` becomes child faces `4f .. 4f + 3` = `(a, ab, ca)`, `(b, bc, ab)`, `(c, ca, bc)`,
//! `(ab, bc, ca)`, oriented like the parent (the layout of `schemes::loop_subdivision`).
//! Child face `4f + i` (`i < 3`) is the corner triangle at the start of parent half-edge
//! `h = 3f + i`; its sides are `3(4f + i) + k`: `k = 0` from the vertex along `h`, `1` across
//! the parent face, `2` back along `prev(h)`. The middle face `4f + 3` has side `k` from the
//! point of edge `3f + k` to the next. Loop subdivision (uniform and adaptive levels) and the
//! modified butterfly scheme refine on it (`TriSplit`, `super::split`).

use super::split::{UniformSplit, edge_half, general_child_topology};
use super::{FaceIndex, MeshView, NONE, PolyMesh, Topology, number_edges};
use crate::error::{Error, Result};
use rayon::prelude::*;
use std::ops::Range;

/// Child points (or parent half-edges) per parallel task.
const BLOCK: usize = 4096;

/// Whether one 1-4 split of `mesh` can be made: a triangle net whose child points fit
/// fairsub's 32-bit indices. Errors name the first face that is not a triangle.
pub fn check(mesh: &PolyMesh) -> Result<()> {
    let nv = mesh.num_vertices() as u32;
    if nv as usize + mesh.num_edges() > u32::MAX as usize {
        return Err(Error::Unsupported(
            "one 1-4 split would create more points than 32-bit indices allow".into(),
        ));
    }
    require_triangles(mesh, "the triangle 1-4 split needs", "")
}

/// The error naming the first face of `mesh` that is not a triangle: "`needs` a triangle net,
/// but face .. has .. corners`hint`" (`needs` says who needs triangles, "Loop patches need").
pub(crate) fn require_triangles(mesh: &PolyMesh, needs: &str, hint: &str) -> Result<()> {
    if mesh.uniform_face_size() == Some(3) {
        return Ok(());
    }
    (0..mesh.num_faces()).try_for_each(|f| require_triangle(mesh, f, needs, hint))
}

/// The error of [`require_triangles`] when face `f` is not a triangle.
pub(crate) fn require_triangle(mesh: &PolyMesh, f: usize, needs: &str, hint: &str) -> Result<()> {
    let k = mesh.face_size(f);
    if k == 3 {
        return Ok(());
    }
    Err(Error::UnsupportedFace {
        face: f,
        msg: format!("{needs} a triangle net, but face {f} has {k} corners{hint}"),
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

/// Child face of the corner where parent half-edge `h` starts: `4f + i` for `h = 3f + i`.
#[inline]
fn corner_face(h: u32) -> u32 {
    h + h / 3
}

/// The triangle 1-4 split (the [module](self)'s layout; triangle nets only).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct TriSplit;

impl UniformSplit for TriSplit {
    const ARITY: u32 = 3;

    fn num_points(mesh: &PolyMesh) -> usize {
        mesh.num_vertices() + mesh.num_edges()
    }

    /// Parent triangle `f = (a, b, c)` becomes `(a, ab, ca)`, `(b, bc, ab)`, `(c, ca, bc)`,
    /// `(ab, bc, ca)`.
    fn corners(
        _faces: FaceIndex<'_>,
        corners: &[u32],
        he_edge: &[u32],
        nv: usize,
        _ne: usize,
    ) -> Vec<u32> {
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

    /// Side 0 of `h` pairs with side 2 at `next(twin h)`, side 1 with a side of the middle
    /// face; edges numbered as [`number_edges`] numbers them, vertex half-edges by the generic
    /// build's rule (the boundary outgoing half-edge, else the smallest).
    fn manifold_halfedges(mesh: &PolyMesh) -> Topology {
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
        Topology::of_uniform_manifold(twin, he_edge, edge_he, vert_he)
    }

    /// The child edges: the two halves of every parent edge and three edges inside each
    /// parent triangle.
    fn general_halfedges(mesh: &PolyMesh, child_corners: &[u32]) -> Topology {
        let m = mesh.view();
        let nf = mesh.num_faces();
        let ne32 = mesh.num_edges() as u32;
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
        general_child_topology(mesh, child_corners, 3, &raw, 3 * nf, Self::num_points(mesh))
    }

    /// Side 0 of the corner triangle at the start of `h`, side 2 of the one at its end.
    #[inline]
    fn half_side(m: &MeshView<'_>, h: u32, at_to: bool) -> u32 {
        if at_to {
            3 * corner_face(m.faces.next(h)) + 2
        } else {
            3 * corner_face(h)
        }
    }

    /// The four children `4f .. 4f + 4`.
    fn face_children(_m: &MeshView<'_>, f: u32) -> Range<u32> {
        4 * f..4 * f + 4
    }
}
