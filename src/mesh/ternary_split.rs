//! The ternary 1-9 split of a quad net (the topology of the primal ternary bi-2 schemes, TPS
//! and adjustable TPS), without any weights: every edge gets two points, every face corner one
//! (inside the face), and every quad becomes a 3 x 3 grid of quads; along the boundary a layer
//! of outer points closes one strip of three quads per boundary edge and one quad per corner
//! (a boundary vertex of one quad). A scheme supplies the masks (and, for knot widths, reads
//! which cell of its parent each child face is: [`TernaryCell`]).
//!
//! Layout of the child: vertex `v < V` is the child of parent vertex `v`; `V + 2e + k` the
//! points of edge `e` (`k = 0` next to the start of the edge's half-edge, `1` next to its end);
//! `V + 2E + h` the face point next to the start of half-edge `h`; then the boundary layer:
//! per boundary vertex in vertex order one outer point (two quads) or three (a corner: outer
//! along its outgoing boundary edge, outer along its incoming one, the corner's corner), then
//! two per boundary edge in edge order (near the start of its half-edge, near its end). Child
//! faces: the nine of each face in face order (cell `(i, j)` of its grid, `j` outer), then the
//! strips in boundary edge order, then the corner quads in vertex order.

use super::{NONE, PolyMesh};

/// Which cell of its parent a child face of the ternary split is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TernaryCell {
    /// Cell `(i, j)` of the 3 x 3 grid of face `face` (in its chart from its first half-edge:
    /// [`grid`]).
    Inner {
        /// The parent face.
        face: u32,
        /// Along the chart's `u`.
        i: u8,
        /// Along the chart's `v`.
        j: u8,
    },
    /// Quad `q` (from the start of its half-edge) of the strip along boundary edge `edge`.
    Strip {
        /// The parent edge.
        edge: u32,
        /// Position along the edge.
        q: u8,
    },
    /// The corner quad of a boundary vertex of one quad.
    Corner(u32),
}

/// One ternary step's child points and faces (see the [module](self) documentation).
#[derive(Debug, Clone)]
pub struct TernarySplit {
    /// Per boundary vertex its outer points: `[outer, -, -]` for two quads, `[out, in,
    /// corner's corner]` for a corner; [`NONE`] elsewhere.
    pub outer: Vec<[u32; 3]>,
    /// Per boundary edge the first of its two outer points; [`NONE`] elsewhere.
    pub outer_edge: Vec<u32>,
    /// The number of child points.
    pub num_points: usize,
    /// Child face offsets into `corners`.
    pub face_start: Vec<u32>,
    /// Child face corners.
    pub corners: Vec<u32>,
    /// What each child face is, in order.
    pub cells: Vec<TernaryCell>,
}

/// The child point of the edge of half-edge `h` next to `from(h)` (`near_from`) or to `to(h)`.
pub fn edge_child(mesh: &PolyMesh, h: u32, near_from: bool) -> u32 {
    let e = mesh.he_edge(h);
    let g = mesh.edge_halfedge(e as usize);
    let k = u32::from(if g == h { !near_from } else { near_from });
    mesh.num_vertices() as u32 + 2 * e + k
}

/// The face point next to `from(h)` in the face of `h`.
pub fn face_child(mesh: &PolyMesh, h: u32) -> u32 {
    (mesh.num_vertices() + 2 * mesh.num_edges()) as u32 + h
}

/// The 4 x 4 child points `g[i][j]` of quad `f` in its chart rotated to start at its corner
/// `k`: `u` (`i`) along half-edge `k` of the face, `v` (`j`) along the reversed half-edge
/// `k + 3`; the corners are the parent's vertices.
pub fn grid(mesh: &PolyMesh, f: usize, k: usize) -> [[u32; 4]; 4] {
    let h0f = mesh.face_halfedge(f);
    let hk = |j: usize| h0f + ((k + j) % 4) as u32;
    let (h0, h1, h2, h3) = (hk(0), hk(1), hk(2), hk(3));
    let mut g = [[0u32; 4]; 4];
    g[0][0] = mesh.he_from(h0);
    g[3][0] = mesh.he_from(h1);
    g[3][3] = mesh.he_from(h2);
    g[0][3] = mesh.he_from(h3);
    let ec = |h: u32, near_from: bool| edge_child(mesh, h, near_from);
    g[1][0] = ec(h0, true);
    g[2][0] = ec(h0, false);
    g[3][1] = ec(h1, true);
    g[3][2] = ec(h1, false);
    g[2][3] = ec(h2, true);
    g[1][3] = ec(h2, false);
    g[0][2] = ec(h3, true);
    g[0][1] = ec(h3, false);
    g[1][1] = face_child(mesh, h0);
    g[2][1] = face_child(mesh, h1);
    g[2][2] = face_child(mesh, h2);
    g[1][2] = face_child(mesh, h3);
    g
}

impl TernarySplit {
    /// The split of the quad net `mesh`, whose boundary vertices have one or two quads (the
    /// caller refuses other nets, naming the element).
    pub fn new(mesh: &PolyMesh) -> TernarySplit {
        let (nv, ne, nh) = (mesh.num_vertices(), mesh.num_edges(), mesh.num_halfedges());
        let corner = |v: usize| mesh.is_boundary_vertex(v) && mesh.is_corner(v);
        let mut next = (nv + 2 * ne + nh) as u32;
        let mut outer = vec![[NONE; 3]; nv];
        for (v, slot) in outer.iter_mut().enumerate() {
            if corner(v) {
                *slot = [next, next + 1, next + 2];
                next += 3;
            } else if mesh.is_boundary_vertex(v) {
                slot[0] = next;
                next += 1;
            }
        }
        let mut outer_edge = vec![NONE; ne];
        for (e, slot) in outer_edge.iter_mut().enumerate() {
            if mesh.is_boundary_edge(e) {
                *slot = next;
                next += 2;
            }
        }
        let mut s = TernarySplit {
            outer,
            outer_edge,
            num_points: next as usize,
            face_start: vec![0],
            corners: Vec::with_capacity(9 * nh + 16 * ne),
            cells: Vec::with_capacity(9 * mesh.num_faces()),
        };
        for f in 0..mesh.num_faces() {
            let g = grid(mesh, f, 0);
            for i in 0..3 {
                for j in 0..3 {
                    let quad = [g[i][j], g[i + 1][j], g[i + 1][j + 1], g[i][j + 1]];
                    let (face, i, j) = (f as u32, i as u8, j as u8);
                    s.push(quad, TernaryCell::Inner { face, i, j });
                }
            }
        }
        for e in 0..ne {
            let oe = s.outer_edge[e];
            if oe == NONE {
                continue;
            }
            let h = mesh.edge_halfedge(e);
            let (a, b) = (mesh.he_from(h) as usize, mesh.he_to(h) as usize);
            let g = s.edge_grid(mesh, h);
            // a corner's first outer point lies along its outgoing boundary edge, its second
            // along the incoming one
            let ob = s.outer[b][usize::from(corner(b))];
            let row = [g[0][0], g[1][0], g[2][0], g[3][0]];
            let out = [s.outer[a][0], oe, oe + 1, ob];
            for q in 0..3 {
                let quad = [out[q], out[q + 1], row[q + 1], row[q]];
                let (edge, q) = (e as u32, q as u8);
                s.push(quad, TernaryCell::Strip { edge, q });
            }
        }
        for v in (0..nv).filter(|&v| corner(v)) {
            let [o_out, o_in, cc] = s.outer[v];
            s.push([cc, o_out, v as u32, o_in], TernaryCell::Corner(v as u32));
        }
        s
    }

    /// The grid of the face of half-edge `h` in its chart from `h`.
    pub fn edge_grid(&self, mesh: &PolyMesh, h: u32) -> [[u32; 4]; 4] {
        let f = mesh.he_face(h) as usize;
        grid(mesh, f, (h - mesh.face_halfedge(f)) as usize)
    }

    fn push(&mut self, quad: [u32; 4], cell: TernaryCell) {
        self.corners.extend_from_slice(&quad);
        self.face_start.push(self.corners.len() as u32);
        self.cells.push(cell);
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;
    use crate::mesh::nets;

    #[crate::unit::test]
    fn closed_and_open_quad_nets() {
        // closed: V + 2E + H points, nine quads per face, no boundary layer
        let cube = nets::cube();
        let s = TernarySplit::new(&cube);
        assert_eq!(s.num_points, 8 + 24 + 24);
        assert_eq!(s.cells.len(), 54);
        assert!(s.outer.iter().all(|o| o[0] == NONE));
        // a 3 x 3 grid: 8 boundary vertices of two quads, 4 corners, 12 boundary edges
        let open = nets::quad_grid(3, |_, _| 0.0);
        let s = TernarySplit::new(&open);
        assert_eq!(s.num_points, 16 + 48 + 36 + 8 + 3 * 4 + 2 * 12);
        assert_eq!(s.cells.len(), 81 + 3 * 12 + 4);
        assert!(matches!(s.cells[81], TernaryCell::Strip { q: 0, .. }));
        assert_eq!(s.cells[81 + 36], TernaryCell::Corner(0));
        // every child point is a corner of some child face, each once per face
        let mut used = vec![false; s.num_points];
        for &c in &s.corners {
            used[c as usize] = true;
        }
        assert!(used.iter().all(|&u| u));
        // a face's grid has its corners at the parent's vertices and shares its edge points
        // with the neighbour across each edge
        let g = grid(&cube, 0, 0);
        assert_eq!(g[0][0], cube.face(0)[0]);
        let h = cube.face_halfedge(0);
        let t = cube.he_twin(h).unwrap();
        assert_eq!(edge_child(&cube, h, true), edge_child(&cube, t, false));
    }
}
