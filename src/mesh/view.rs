//! Borrowed views of a mesh's arrays for hot loops, the face index of half-edges, and the one
//! vertex-ring walker ([`Outgoing`]): every walk around a vertex in the crate (the
//! [`PolyMesh`](super::PolyMesh) accessors, the schemes' refinement and surface code) goes through
//! [`MeshView::outgoing`], [`MeshView::boundary_neighbors`] and [`MeshView::is_corner`].

use super::NONE;

/// A borrowed view of a mesh's arrays for hot loops: the same walks as the [`PolyMesh`]
/// accessors, without re-fetching the topology on every call.
#[derive(Clone, Copy)]
pub(crate) struct MeshView<'a> {
    pub corners: &'a [u32],
    pub faces: FaceIndex<'a>,
    pub twin: &'a [u32],
    pub he_edge: &'a [u32],
    pub edge_he: &'a [u32],
    pub vert_he: &'a [u32],
}

impl<'a> MeshView<'a> {
    /// Vertex half-edge `h` starts at.
    #[inline]
    pub fn from(&self, h: u32) -> u32 {
        self.corners[h as usize]
    }

    /// Vertex half-edge `h` ends at.
    #[inline]
    pub fn to(&self, h: u32) -> u32 {
        self.corners[self.faces.next(h) as usize]
    }

    /// Opposite half-edge or [`NONE`].
    #[inline]
    pub fn twin(&self, h: u32) -> u32 {
        self.twin[h as usize]
    }

    /// Face of half-edge `h`.
    #[inline]
    pub fn face(&self, h: u32) -> u32 {
        self.faces.face(h)
    }

    /// Corner vertices of face `f`.
    #[inline]
    pub fn face_corners(&self, f: usize) -> &'a [u32] {
        let k = self.faces.uniform as usize;
        if k != 0 {
            &self.corners[k * f..k * f + k]
        } else {
            let fs = self.faces.face_start;
            &self.corners[fs[f] as usize..fs[f + 1] as usize]
        }
    }

    /// Whether vertex `v` lies on the boundary.
    #[inline]
    pub fn is_boundary_vertex(&self, v: usize) -> bool {
        self.twin[self.vert_he[v] as usize] == NONE
    }

    /// Whether boundary vertex `v` has a single face (a corner, valence 2).
    #[inline]
    pub fn is_corner(&self, v: usize) -> bool {
        let h = self.vert_he[v];
        self.twin[h as usize] == NONE && self.twin[self.faces.prev(h) as usize] == NONE
    }

    /// Outgoing half-edges of `v`, counter-clockwise from [`PolyMesh::vertex_halfedge`]
    /// (the order of [`PolyMesh::outgoing_halfedges`]).
    #[inline]
    pub fn outgoing(&self, v: usize) -> Outgoing<'a> {
        self.outgoing_from(self.vert_he[v])
    }

    /// Outgoing half-edges of the start vertex of `h`, counter-clockwise from `h` (up to the
    /// boundary, or once around).
    #[inline]
    pub fn outgoing_from(&self, start: u32) -> Outgoing<'a> {
        Outgoing {
            view: *self,
            start,
            next: start,
        }
    }

    /// The two boundary neighbours of boundary vertex `v`: the end of its outgoing boundary
    /// half-edge and the start of its incoming one.
    #[inline]
    pub fn boundary_neighbors(&self, v: usize) -> (u32, u32) {
        let out = self.vert_he[v];
        let last = self.outgoing(v).last().unwrap_or(out);
        (self.to(out), self.from(self.faces.prev(last)))
    }
}

/// The outgoing half-edges of a vertex, counter-clockwise; for a boundary vertex starting at its
/// boundary half-edge (rotating from `h` to `twin(prev(h))`). Built by `MeshView::outgoing` or
/// [`PolyMesh::outgoing`](super::PolyMesh::outgoing); walks without allocating.
pub struct Outgoing<'a> {
    view: MeshView<'a>,
    start: u32,
    next: u32,
}

impl Iterator for Outgoing<'_> {
    type Item = u32;

    #[inline(always)]
    fn next(&mut self) -> Option<u32> {
        let h = self.next;
        if h == NONE {
            return None;
        }
        let t = self.view.twin[self.view.faces.prev(h) as usize];
        self.next = if t == self.start { NONE } else { t };
        Some(h)
    }

    /// The valence (the walk without the generic `fold`, which the hot refinement loops would
    /// otherwise call out of line).
    #[inline(always)]
    fn count(mut self) -> usize {
        let mut n = 0;
        while self.next().is_some() {
            n += 1;
        }
        n
    }
}

/// Face lookup on flat face arrays: `he_face` when sizes differ, arithmetic otherwise.
#[derive(Clone, Copy)]
pub(crate) struct FaceIndex<'a> {
    /// Face offsets (may be empty when `uniform != 0`).
    pub face_start: &'a [u32],
    /// Face of each half-edge (empty when `uniform != 0`).
    pub he_face: &'a [u32],
    /// Common face size or 0.
    pub uniform: u32,
}

impl<'a> FaceIndex<'a> {
    /// The lookup of faces with offsets `face_start` and face of each half-edge `he_face` (both
    /// may be empty when all faces have `uniform` corners).
    #[inline]
    pub fn new(face_start: &'a [u32], he_face: &'a [u32], uniform: u32) -> FaceIndex<'a> {
        FaceIndex {
            face_start,
            he_face,
            uniform,
        }
    }

    /// First half-edge of face `f`.
    #[inline]
    pub fn start(&self, f: usize) -> u32 {
        if self.uniform != 0 {
            self.uniform * f as u32
        } else {
            self.face_start[f]
        }
    }

    /// Face of half-edge `h`.
    #[inline]
    pub fn face(&self, h: u32) -> u32 {
        match self.uniform {
            4 => h >> 2,
            3 => h / 3,
            0 => self.he_face[h as usize],
            k => h / k,
        }
    }

    /// Next half-edge in the same face.
    #[inline]
    pub fn next(&self, h: u32) -> u32 {
        match self.uniform {
            4 => (h & !3) | ((h + 1) & 3),
            0 => {
                let f = self.he_face[h as usize] as usize;
                if h + 1 < self.face_start[f + 1] {
                    h + 1
                } else {
                    self.face_start[f]
                }
            }
            k => {
                if !(h + 1).is_multiple_of(k) {
                    h + 1
                } else {
                    h + 1 - k
                }
            }
        }
    }

    /// Previous half-edge in the same face.
    #[inline]
    pub fn prev(&self, h: u32) -> u32 {
        match self.uniform {
            4 => (h & !3) | (h.wrapping_sub(1) & 3),
            0 => {
                let f = self.he_face[h as usize] as usize;
                if h > self.face_start[f] {
                    h - 1
                } else {
                    self.face_start[f + 1] - 1
                }
            }
            k => {
                if !h.is_multiple_of(k) {
                    h - 1
                } else {
                    h + k - 1
                }
            }
        }
    }
}
