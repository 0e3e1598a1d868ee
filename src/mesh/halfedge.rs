//! The half-edge accessors of a [`PolyMesh`]: from, to, face, next, previous and twin of a
//! half-edge, the edges and their half-edges, a vertex's half-edge and boundary test.

use super::{NONE, PolyMesh};

impl PolyMesh {
    /// First half-edge (corner) of face `f`.
    #[inline]
    pub fn face_halfedge(&self, f: usize) -> u32 {
        if self.uniform != 0 {
            assert!(f < self.num_faces(), "face {f} out of range");
            self.uniform * f as u32
        } else {
            self.offsets()[f]
        }
    }

    /// Vertex a half-edge starts at.
    #[inline]
    pub fn he_from(&self, h: u32) -> u32 {
        self.corners[h as usize]
    }

    /// Vertex a half-edge ends at.
    #[inline]
    pub fn he_to(&self, h: u32) -> u32 {
        self.corners[self.he_next(h) as usize]
    }

    /// Face of a half-edge.
    #[inline]
    pub fn he_face(&self, h: u32) -> u32 {
        self.face_index().face(h)
    }

    /// Next half-edge in the same face.
    #[inline]
    pub fn he_next(&self, h: u32) -> u32 {
        self.face_index().next(h)
    }

    /// Previous half-edge in the same face.
    #[inline]
    pub fn he_prev(&self, h: u32) -> u32 {
        self.face_index().prev(h)
    }

    /// Opposite half-edge, `None` on the boundary.
    #[inline]
    pub fn he_twin(&self, h: u32) -> Option<u32> {
        let t = self.topology().twin[h as usize];
        (t != NONE).then_some(t)
    }

    /// Undirected edge of a half-edge.
    #[inline]
    pub fn he_edge(&self, h: u32) -> u32 {
        self.topology().he_edge[h as usize]
    }

    /// End points of edge `e`.
    pub fn edge(&self, e: usize) -> [u32; 2] {
        let h = self.topology().edge_he[e];
        [self.he_from(h), self.he_to(h)]
    }

    /// All edges as vertex pairs.
    pub fn edges(&self) -> &[[u32; 2]] {
        self.edges.get_or_init(|| {
            self.topology()
                .edge_he
                .iter()
                .map(|&h| [self.he_from(h), self.he_to(h)])
                .collect()
        })
    }

    /// One half-edge of edge `e` (the one with a face on the boundary).
    #[inline]
    pub fn edge_halfedge(&self, e: usize) -> u32 {
        self.topology().edge_he[e]
    }

    /// Whether edge `e` lies on the boundary.
    #[inline]
    pub fn is_boundary_edge(&self, e: usize) -> bool {
        let t = self.topology();
        t.twin[t.edge_he[e] as usize] == NONE
    }

    /// One outgoing half-edge of vertex `v`: for a boundary vertex the one whose counter-clockwise
    /// rotation visits all faces around it.
    #[inline]
    pub fn vertex_halfedge(&self, v: usize) -> u32 {
        self.topology().vert_he[v]
    }

    /// Whether vertex `v` lies on the boundary.
    #[inline]
    pub fn is_boundary_vertex(&self, v: usize) -> bool {
        let t = self.topology();
        t.twin[t.vert_he[v] as usize] == NONE
    }
}
