//! Polygon control nets with half-edge connectivity and validation.
//!
//! A [`PolyMesh`] holds vertex positions and faces of any size (stored flat, face after face),
//! plus a half-edge [`Topology`] built once at construction. Construction validates the input
//! (face sizes, indices, finite coordinates, manifold edges and vertices, consistent orientation)
//! and reports the first problem with the element it concerns, so every scheme downstream can
//! rely on a clean 2-manifold (with or without boundary).
//!
//! Half-edge `h` is face corner `h` in face order: it runs from the corner's vertex to the next
//! corner's vertex, and its face lies to its left (faces are counter-clockwise seen from outside).
//! Rotating counter-clockwise around a vertex goes from outgoing half-edge `h` to
//! `twin(prev(h))`.

use crate::error::{MeshError, Result};
use crate::geom::Point;
use rayon::prelude::*;
use std::sync::OnceLock;

/// Marks a missing half-edge (no twin on a boundary edge).
pub const NONE: u32 = u32::MAX;

/// Half-edge connectivity of a [`PolyMesh`].
///
/// Flat arrays indexed by half-edge, edge or vertex. The face of a half-edge is stored only when
/// the faces differ in size (otherwise it is `h / size`), and edge end points are derived from
/// `edge_he`, so a quad mesh costs 8 bytes per half-edge plus 4 per edge and per vertex.
#[derive(Debug, Clone, Default)]
pub struct Topology {
    /// Face of each half-edge; empty when all faces have the same size.
    pub(crate) he_face: Vec<u32>,
    /// Opposite half-edge, [`NONE`] on the boundary.
    pub(crate) twin: Vec<u32>,
    /// Edge of each half-edge.
    pub(crate) he_edge: Vec<u32>,
    /// First half-edge of each edge (the one with the smaller index; the only one on the
    /// boundary).
    pub(crate) edge_he: Vec<u32>,
    /// One outgoing half-edge per vertex: the boundary one for a boundary vertex, else the one
    /// with the smallest index.
    pub(crate) vert_he: Vec<u32>,
}

/// A validated manifold polygon mesh (a control net).
///
/// The half-edge [`Topology`] of a mesh read from a file is built (and checked) at construction;
/// a mesh produced by refinement may carry a topology built directly from its parent's, or none,
/// in which case it is built on first use (a refined net that is only written out never needs
/// it).
#[derive(Debug, Clone)]
pub struct PolyMesh {
    positions: Vec<Point>,
    /// Face offsets; for a mesh whose faces all have one size they are implicit (`k f`) and
    /// only built if [`PolyMesh::face_starts`] is asked for.
    face_start: OnceLock<Vec<u32>>,
    corners: Vec<u32>,
    /// The common face size, 0 when sizes differ.
    uniform: u32,
    topo: OnceLock<Topology>,
    edges: OnceLock<Vec<[u32; 2]>>,
    dropped: Vec<usize>,
}

/// The parts of a [`PolyMesh`], for refinement kernels that consume their parent level and free
/// what they no longer need as early as possible.
#[derive(Debug)]
pub(crate) struct MeshParts {
    pub positions: Vec<Point>,
    /// Empty when the offsets were implicit.
    pub face_start: Vec<u32>,
    pub corners: Vec<u32>,
    pub uniform: u32,
    pub topo: Option<Topology>,
}

/// Half-edges (or vertices) per parallel task in topology passes.
const CHUNK: usize = 1 << 14;

/// The common size of the faces given by `face_start`, or 0 when sizes differ.
fn uniform_size(face_start: &[u32]) -> u32 {
    if face_start.len() < 2 {
        return 0;
    }
    let k = face_start[1] - face_start[0];
    if face_start.windows(2).all(|w| w[1] - w[0] == k) {
        k
    } else {
        0
    }
}

impl PolyMesh {
    /// Builds and validates a mesh from positions and faces (vertex indices, counter-clockwise).
    ///
    /// Vertices that no face uses are dropped (see [`PolyMesh::dropped_vertices`]); the remaining
    /// vertices keep their relative order. Errors name the face or vertex (input numbering) and
    /// the reason.
    pub fn new<F: AsRef<[usize]>>(positions: Vec<Point>, faces: &[F]) -> Result<PolyMesh> {
        let mut face_start = Vec::with_capacity(faces.len() + 1);
        let mut corners = Vec::new();
        face_start.push(0u32);
        for f in faces {
            for &v in f.as_ref() {
                // Out-of-range indices are caught by `from_flat`; keep them representable.
                corners.push(u32::try_from(v).unwrap_or(u32::MAX));
            }
            face_start.push(corners.len() as u32);
        }
        // Report huge indices faithfully.
        for (fi, f) in faces.iter().enumerate() {
            for &v in f.as_ref() {
                if v >= positions.len() {
                    return Err(MeshError::IndexOutOfRange {
                        face: fi,
                        index: v as i64,
                        count: positions.len(),
                    }
                    .into());
                }
            }
        }
        Self::from_flat(positions, face_start, corners)
    }

    /// Builds and validates a mesh from flat face arrays: face `f` has corners
    /// `corners[face_start[f]..face_start[f + 1]]`.
    pub fn from_flat(
        positions: Vec<Point>,
        face_start: Vec<u32>,
        corners: Vec<u32>,
    ) -> Result<PolyMesh> {
        let nf = face_start.len().saturating_sub(1);
        if nf == 0 || positions.is_empty() {
            return Err(MeshError::Empty.into());
        }
        let nv = positions.len();
        for f in 0..nf {
            let (a, b) = (face_start[f] as usize, face_start[f + 1] as usize);
            let face = &corners[a..b];
            if face.len() < 3 {
                return Err(MeshError::FaceTooSmall {
                    face: f,
                    len: face.len(),
                }
                .into());
            }
            for &v in face {
                if v as usize >= nv {
                    return Err(MeshError::IndexOutOfRange {
                        face: f,
                        index: v as i64,
                        count: nv,
                    }
                    .into());
                }
            }
            for i in 0..face.len() {
                for j in i + 1..face.len() {
                    if face[i] == face[j] {
                        return Err(MeshError::RepeatedVertex {
                            face: f,
                            vertex: face[i] as usize,
                        }
                        .into());
                    }
                }
            }
        }
        for (i, p) in positions.iter().enumerate() {
            if !p.iter().all(|c| c.is_finite()) {
                return Err(MeshError::NonFiniteCoordinate { vertex: i }.into());
            }
        }
        // Drop unused vertices, keeping the order of the used ones.
        let mut used = vec![false; nv];
        for &v in &corners {
            used[v as usize] = true;
        }
        let dropped: Vec<usize> = (0..nv).filter(|&v| !used[v]).collect();
        let (positions, corners, old_of_new) = if dropped.is_empty() {
            (positions, corners, None)
        } else {
            let mut new_of_old = vec![NONE; nv];
            let mut old_of_new = Vec::with_capacity(nv - dropped.len());
            let mut pos = Vec::with_capacity(nv - dropped.len());
            for v in 0..nv {
                if used[v] {
                    new_of_old[v] = old_of_new.len() as u32;
                    old_of_new.push(v);
                    pos.push(positions[v]);
                }
            }
            let corners = corners.iter().map(|&v| new_of_old[v as usize]).collect();
            (pos, corners, Some(old_of_new))
        };
        let uniform = uniform_size(&face_start);
        let topo = Topology::build(positions.len(), &face_start, &corners, uniform, false)
            .map_err(|e| {
                // Report vertices in input numbering.
                match (&old_of_new, e) {
                    (Some(map), MeshError::NonManifoldEdge { edge, faces }) => {
                        MeshError::NonManifoldEdge {
                            edge: [map[edge[0]], map[edge[1]]],
                            faces,
                        }
                    }
                    (Some(map), MeshError::InconsistentOrientation { edge, faces }) => {
                        MeshError::InconsistentOrientation {
                            edge: [map[edge[0]], map[edge[1]]],
                            faces,
                        }
                    }
                    (Some(map), MeshError::NonManifoldVertex { vertex, fans }) => {
                        MeshError::NonManifoldVertex {
                            vertex: map[vertex],
                            fans,
                        }
                    }
                    (_, e) => e,
                }
            })?;
        Ok(PolyMesh {
            positions,
            face_start: OnceLock::from(face_start),
            corners,
            uniform,
            topo: OnceLock::from(topo),
            edges: OnceLock::new(),
            dropped,
        })
    }

    /// Builds a mesh whose validity is guaranteed by construction (refinement output). Still
    /// builds the topology and fails on a broken input instead of producing a wrong mesh.
    pub fn from_refinement(
        positions: Vec<Point>,
        face_start: Vec<u32>,
        corners: Vec<u32>,
    ) -> Result<PolyMesh> {
        let uniform = uniform_size(&face_start);
        let topo = Topology::build(positions.len(), &face_start, &corners, uniform, false)?;
        Ok(PolyMesh {
            positions,
            face_start: OnceLock::from(face_start),
            corners,
            uniform,
            topo: OnceLock::from(topo),
            edges: OnceLock::new(),
            dropped: Vec::new(),
        })
    }

    /// Like [`PolyMesh::from_refinement`], but tolerates non-manifold ("bow-tie") vertices, as
    /// they occur at the cut of a partially refined region. Such a vertex gets one of its fans;
    /// callers must not rely on its one-ring (adaptive refinement marks it incomplete).
    pub fn from_partial_refinement(
        positions: Vec<Point>,
        face_start: Vec<u32>,
        corners: Vec<u32>,
    ) -> Result<PolyMesh> {
        let uniform = uniform_size(&face_start);
        let topo = Topology::build(positions.len(), &face_start, &corners, uniform, true)?;
        Ok(PolyMesh {
            positions,
            face_start: OnceLock::from(face_start),
            corners,
            uniform,
            topo: OnceLock::from(topo),
            edges: OnceLock::new(),
            dropped: Vec::new(),
        })
    }

    /// A mesh whose validity is guaranteed by construction (a refinement kernel's output) and
    /// whose faces all have `size` corners (the face offsets stay implicit), with its topology
    /// when the kernel built it from the parent's, or `None` to build it on first use. Nothing
    /// is checked: the caller guarantees a valid manifold mesh whose `topo` (if given) is the
    /// one [`PolyMesh::from_refinement`] would build.
    pub(crate) fn from_trusted_uniform(
        positions: Vec<Point>,
        size: u32,
        corners: Vec<u32>,
        topo: Option<Topology>,
    ) -> PolyMesh {
        debug_assert!(size >= 3 && corners.len().is_multiple_of(size as usize));
        debug_assert!(topo.as_ref().is_none_or(|t| t.twin.len() == corners.len()
            && t.vert_he.len() == positions.len()
            && t.he_face.is_empty()));
        PolyMesh {
            positions,
            face_start: OnceLock::new(),
            corners,
            uniform: size,
            topo: topo.map(OnceLock::from).unwrap_or_default(),
            edges: OnceLock::new(),
            dropped: Vec::new(),
        }
    }

    /// The face offsets (built now for a uniform mesh that did not have them).
    #[inline]
    fn offsets(&self) -> &[u32] {
        self.face_start.get_or_init(|| {
            let k = self.uniform;
            (0..=(self.corners.len() as u32 / k))
                .map(|f| k * f)
                .collect()
        })
    }

    /// The face offsets the arrays need: none for a uniform mesh.
    #[inline]
    fn stored_offsets(&self) -> &[u32] {
        if self.uniform != 0 {
            &[]
        } else {
            self.offsets()
        }
    }

    /// Splits the mesh into its arrays (the topology only if it was built).
    pub(crate) fn into_parts(self) -> MeshParts {
        MeshParts {
            positions: self.positions,
            face_start: self.face_start.into_inner().unwrap_or_default(),
            corners: self.corners,
            uniform: self.uniform,
            topo: self.topo.into_inner(),
        }
    }

    /// The half-edge topology (built now if this refined mesh did not have it yet).
    #[inline]
    pub(crate) fn topology(&self) -> &Topology {
        self.topo.get_or_init(|| {
            Topology::build(
                self.positions.len(),
                self.stored_offsets(),
                &self.corners,
                self.uniform,
                false,
            )
            .expect("a refinement kernel produced an invalid mesh")
        })
    }

    /// The face lookup of the half-edge arrays ([`FaceIndex`], the one place the face walks
    /// are written); builds the topology only for meshes with mixed face sizes.
    #[inline]
    fn face_index(&self) -> FaceIndex<'_> {
        FaceIndex {
            face_start: self.stored_offsets(),
            he_face: if self.uniform == 0 {
                &self.topology().he_face
            } else {
                &[]
            },
            uniform: self.uniform,
        }
    }

    /// A view of the arrays for hot loops (builds the topology if needed).
    #[inline]
    pub(crate) fn view(&self) -> MeshView<'_> {
        let t = self.topology();
        MeshView {
            corners: &self.corners,
            faces: FaceIndex {
                face_start: self.stored_offsets(),
                he_face: &t.he_face,
                uniform: self.uniform,
            },
            twin: &t.twin,
            he_edge: &t.he_edge,
            edge_he: &t.edge_he,
            vert_he: &t.vert_he,
        }
    }

    /// The size shared by all faces (4 for an all-quad mesh, 3 for a triangle mesh), or `None`
    /// when face sizes differ.
    pub fn uniform_face_size(&self) -> Option<usize> {
        (self.uniform != 0).then_some(self.uniform as usize)
    }

    /// Input indices of the vertices that no face used and that were dropped.
    pub fn dropped_vertices(&self) -> &[usize] {
        &self.dropped
    }

    /// Number of vertices.
    #[inline]
    pub fn num_vertices(&self) -> usize {
        self.positions.len()
    }

    /// Number of faces.
    #[inline]
    pub fn num_faces(&self) -> usize {
        if self.uniform != 0 {
            self.corners.len() / self.uniform as usize
        } else {
            self.offsets().len() - 1
        }
    }

    /// Number of undirected edges.
    #[inline]
    pub fn num_edges(&self) -> usize {
        self.topology().edge_he.len()
    }

    /// Number of half-edges (= face corners).
    #[inline]
    pub fn num_halfedges(&self) -> usize {
        self.corners.len()
    }

    /// Vertex positions.
    #[inline]
    pub fn positions(&self) -> &[Point] {
        &self.positions
    }

    /// Replaces the vertex positions (same count, same connectivity).
    ///
    /// # Panics
    /// Panics when the count differs; this is a programming error, not bad input.
    pub fn set_positions(&mut self, positions: Vec<Point>) {
        assert_eq!(
            positions.len(),
            self.positions.len(),
            "vertex count must not change"
        );
        self.positions = positions;
    }

    /// Position of vertex `v`.
    #[inline]
    pub fn position(&self, v: usize) -> Point {
        self.positions[v]
    }

    /// Corner vertices of face `f`, counter-clockwise.
    #[inline]
    pub fn face(&self, f: usize) -> &[u32] {
        if self.uniform != 0 {
            let k = self.uniform as usize;
            &self.corners[k * f..k * f + k]
        } else {
            let fs = self.offsets();
            &self.corners[fs[f] as usize..fs[f + 1] as usize]
        }
    }

    /// Number of corners of face `f`.
    #[inline]
    pub fn face_size(&self, f: usize) -> usize {
        if self.uniform != 0 {
            assert!(f < self.num_faces(), "face {f} out of range");
            self.uniform as usize
        } else {
            let fs = self.offsets();
            (fs[f + 1] - fs[f]) as usize
        }
    }

    /// Flat face offsets (`num_faces + 1` entries).
    #[inline]
    pub fn face_starts(&self) -> &[u32] {
        self.offsets()
    }

    /// Flat corner array (vertex of each corner, face after face).
    #[inline]
    pub fn corners(&self) -> &[u32] {
        &self.corners
    }

    /// Iterator over faces as vertex slices.
    pub fn faces(&self) -> impl ExactSizeIterator<Item = &[u32]> + '_ {
        (0..self.num_faces()).map(move |f| self.face(f))
    }

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

    /// Outgoing half-edges of `v`, counter-clockwise; for a boundary vertex starting at its
    /// boundary half-edge. The last edge of a boundary vertex (the incoming boundary edge) has no
    /// outgoing half-edge and is not listed; see [`PolyMesh::vertex_neighbors`].
    pub fn outgoing_halfedges(&self, v: usize) -> Vec<u32> {
        let start = self.topology().vert_he[v];
        let mut out = vec![start];
        let mut h = start;
        loop {
            let p = self.he_prev(h);
            match self.he_twin(p) {
                Some(t) if t != start => {
                    out.push(t);
                    h = t;
                }
                _ => break,
            }
        }
        out
    }

    /// Faces around `v`, counter-clockwise (from the boundary for a boundary vertex).
    pub fn vertex_faces(&self, v: usize) -> Vec<u32> {
        self.outgoing_halfedges(v)
            .into_iter()
            .map(|h| self.he_face(h))
            .collect()
    }

    /// Edge neighbours of `v`, counter-clockwise (for a boundary vertex from one boundary
    /// neighbour to the other).
    pub fn vertex_neighbors(&self, v: usize) -> Vec<u32> {
        let hs = self.outgoing_halfedges(v);
        let mut out: Vec<u32> = hs.iter().map(|&h| self.he_to(h)).collect();
        if self.is_boundary_vertex(v) {
            let last = *hs.last().expect("a vertex has a half-edge");
            out.push(self.he_from(self.he_prev(last)));
        }
        out
    }

    /// Valence: the number of edges at `v`.
    pub fn valence(&self, v: usize) -> usize {
        let n = self.outgoing_halfedges(v).len();
        if self.is_boundary_vertex(v) { n + 1 } else { n }
    }

    /// The one-ring of `v`: every vertex of the faces around `v` except `v`, in
    /// counter-clockwise order, without repetition.
    pub fn one_ring(&self, v: usize) -> Vec<u32> {
        let mut out = Vec::new();
        for h in self.outgoing_halfedges(v) {
            let mut g = self.he_next(h);
            while self.he_from(g) != v as u32 {
                let w = self.he_from(g);
                if !out.contains(&w) {
                    out.push(w);
                }
                g = self.he_next(g);
            }
        }
        out
    }

    /// The two-ring of `v`: vertices of faces around one-ring vertices that are neither `v` nor in
    /// its one-ring (sorted by index).
    pub fn two_ring(&self, v: usize) -> Vec<u32> {
        let ring1 = self.one_ring(v);
        let mut out = Vec::new();
        for &w in &ring1 {
            for f in self.vertex_faces(w as usize) {
                for &x in self.face(f as usize) {
                    if x != v as u32 && !ring1.contains(&x) && !out.contains(&x) {
                        out.push(x);
                    }
                }
            }
        }
        out.sort_unstable();
        out
    }

    /// Boundary loops, each as the list of its vertices in the direction of the boundary
    /// half-edges (face on the left).
    pub fn boundary_loops(&self) -> Vec<Vec<u32>> {
        let nh = self.corners.len();
        let mut seen = vec![false; nh];
        let mut loops = Vec::new();
        for h0 in 0..nh as u32 {
            if self.topology().twin[h0 as usize] != NONE || seen[h0 as usize] {
                continue;
            }
            let mut lp = Vec::new();
            let mut h = h0;
            loop {
                seen[h as usize] = true;
                lp.push(self.he_from(h));
                // The next boundary half-edge starts where h ends: the boundary half-edge of that
                // vertex.
                h = self.topology().vert_he[self.he_to(h) as usize];
                if h == h0 || seen[h as usize] {
                    break;
                }
            }
            loops.push(lp);
        }
        loops
    }

    /// Whether every face is a quad.
    pub fn is_all_quads(&self) -> bool {
        (0..self.num_faces()).all(|f| self.face_size(f) == 4)
    }

    /// Whether every face is a triangle.
    pub fn is_all_triangles(&self) -> bool {
        (0..self.num_faces()).all(|f| self.face_size(f) == 3)
    }

    /// Whether `v` is regular in a quad mesh: interior of valence 4, boundary of valence 3, or a
    /// boundary corner of valence 2, with only quads around it.
    pub fn is_regular_quad_vertex(&self, v: usize) -> bool {
        let faces_ok = self
            .vertex_faces(v)
            .iter()
            .all(|&f| self.face_size(f as usize) == 4);
        let n = self.valence(v);
        faces_ok
            && if self.is_boundary_vertex(v) {
                n == 2 || n == 3
            } else {
                n == 4
            }
    }

    /// Extraordinary vertices of a quad-dominant net: vertices that are not
    /// [regular](Self::is_regular_quad_vertex).
    pub fn extraordinary_vertices(&self) -> Vec<usize> {
        (0..self.num_vertices())
            .filter(|&v| !self.is_regular_quad_vertex(v))
            .collect()
    }

    /// Extraordinary facets: faces that are not quads.
    pub fn extraordinary_faces(&self) -> Vec<usize> {
        (0..self.num_faces())
            .filter(|&f| self.face_size(f) != 4)
            .collect()
    }

    /// Half-edge from `a` to `b`, if the edge exists in that direction.
    pub fn find_halfedge(&self, a: usize, b: usize) -> Option<u32> {
        let hs = self.outgoing_halfedges(a);
        hs.into_iter().find(|&h| self.he_to(h) == b as u32)
    }

    /// The cells of the quad grid walked by [`PolyMesh::sector_grid`]: `cells[i][j]` is the
    /// half-edge of cell `(i, j)` leaving its corner `(i, j)` in `+u` direction (its face is
    /// `he_face`), `0 <= i, j < size`.
    pub fn sector_cells(&self, h: u32, size: usize) -> Option<Vec<Vec<u32>>> {
        // cell[i][j] = the half-edge of cell (i, j) leaving its (i, j) corner in +u direction.
        let mut cell = vec![vec![NONE; size]; size];
        for i in 0..size {
            for j in 0..size {
                let c = if i == 0 && j == 0 {
                    h
                } else if j == 0 {
                    // Right neighbour of cell (i - 1, 0).
                    let left = cell[i - 1][0];
                    if self.face_size(self.he_face(left) as usize) != 4 {
                        return None;
                    }
                    self.he_next(self.he_twin(self.he_next(left))?)
                } else {
                    // Upper neighbour of cell (i, j - 1).
                    let below = cell[i][j - 1];
                    if self.face_size(self.he_face(below) as usize) != 4 {
                        return None;
                    }
                    self.he_twin(self.he_next(self.he_next(below)))?
                };
                if self.face_size(self.he_face(c) as usize) != 4 {
                    return None;
                }
                cell[i][j] = c;
            }
        }
        Some(cell)
    }

    /// Walks a quad grid starting at cell `(0, 0)` whose corner `(0, 0)` is the start of
    /// half-edge `h` and whose `+u` direction is `h`'s direction: returns `grid[i][j]`, the vertex
    /// at chart point `(i, j)` for `0 <= i, j <= size`, or `None` when a needed cell is missing or
    /// not a quad. The chart is oriented like the faces (`+v` is counter-clockwise from `+u`).
    pub fn sector_grid(&self, h: u32, size: usize) -> Option<Vec<Vec<u32>>> {
        let cell = self.sector_cells(h, size)?;
        let mut grid = vec![vec![NONE; size + 1]; size + 1];
        for i in 0..size {
            for j in 0..size {
                let c = cell[i][j];
                let n1 = self.he_next(c);
                let n2 = self.he_next(n1);
                let n3 = self.he_next(n2);
                grid[i][j] = self.he_from(c);
                grid[i + 1][j] = self.he_from(n1);
                grid[i + 1][j + 1] = self.he_from(n2);
                grid[i][j + 1] = self.he_from(n3);
            }
        }
        Some(grid)
    }

    /// The c-net of vertex `v` with `rings` rings of quads, in the canonical order of
    /// [`crate::gallery::cnet`]: `v`, then for each sector `s` (counter-clockwise from
    /// [`PolyMesh::vertex_halfedge`]) the chart points `(i, j)`, `i = 1..=rings`,
    /// `j = 0..=rings`. `None` when `v` is on the boundary or the rings are not regular quads.
    pub fn cnet_indices(&self, v: usize, rings: usize) -> Option<Vec<u32>> {
        if self.is_boundary_vertex(v) {
            return None;
        }
        self.cnet_indices_from(self.vertex_halfedge(v), rings)
    }

    /// Like [`PolyMesh::cnet_indices`] with sector 0 starting at the outgoing half-edge `h` of
    /// an interior vertex.
    pub fn cnet_indices_from(&self, h: u32, rings: usize) -> Option<Vec<u32>> {
        let v = self.he_from(h);
        let mut out = vec![v];
        let mut hs = vec![h];
        loop {
            let t = self.he_twin(self.he_prev(*hs.last().expect("non-empty")))?;
            if t == h {
                break;
            }
            hs.push(t);
        }
        for h in hs {
            let g = self.sector_grid(h, rings)?;
            for row in g.iter().skip(1) {
                out.extend_from_slice(row);
            }
        }
        Some(out)
    }

    /// Centroid of face `f`.
    pub fn face_centroid(&self, f: usize) -> Point {
        crate::geom::centroid(self.face(f).iter().map(|&v| self.positions[v as usize]))
    }

    /// Axis-aligned bounding box of the vertex positions.
    pub fn bounding_box(&self) -> (Point, Point) {
        crate::geom::bounding_box(self.positions.iter().copied())
            .expect("a valid mesh has vertices")
    }
}

impl Topology {
    /// Builds half-edge connectivity and checks manifoldness and orientation (the first problem
    /// in half-edge order, then in vertex order, is reported). `uniform` is the common face size
    /// or 0 (then `face_start` may be empty). Runs in parallel over blocks of half-edges and
    /// vertices.
    fn build(
        nv: usize,
        face_start: &[u32],
        corners: &[u32],
        uniform: u32,
        relaxed: bool,
    ) -> std::result::Result<Topology, MeshError> {
        let nh = corners.len();
        let nf = if uniform != 0 {
            nh / uniform as usize
        } else {
            face_start.len() - 1
        };
        let he_face = if uniform == 0 {
            let mut he_face = vec![0u32; nh];
            for f in 0..nf {
                he_face[face_start[f] as usize..face_start[f + 1] as usize].fill(f as u32);
            }
            he_face
        } else {
            Vec::new()
        };
        let faces = FaceIndex {
            face_start,
            he_face: &he_face,
            uniform,
        };
        // Outgoing half-edges bucketed per vertex (CSR), in increasing half-edge order.
        let mut out_start = vec![0u32; nv + 1];
        for &v in corners {
            out_start[v as usize + 1] += 1;
        }
        for v in 0..nv {
            out_start[v + 1] += out_start[v];
        }
        let mut fill = out_start.clone();
        let mut out_he = vec![0u32; nh];
        for (h, &v) in corners.iter().enumerate() {
            out_he[fill[v as usize] as usize] = h as u32;
            fill[v as usize] += 1;
        }
        drop(fill);
        let outs =
            |v: u32| &out_he[out_start[v as usize] as usize..out_start[v as usize + 1] as usize];
        let to = |h: u32| corners[faces.next(h) as usize];
        let mut twin = vec![NONE; nh];
        let bad_edge = twin
            .par_chunks_mut(CHUNK)
            .enumerate()
            .filter_map(|(c, chunk)| {
                for (k, slot) in chunk.iter_mut().enumerate() {
                    let h = (c * CHUNK + k) as u32;
                    let (a, b) = (corners[h as usize], to(h));
                    // Same-direction duplicates: orientation conflict or a non-manifold edge.
                    let n_same = outs(a).iter().filter(|&&g| to(g) == b).count();
                    let mut n_opp = 0;
                    for &g in outs(b) {
                        if to(g) == a {
                            if n_opp == 0 {
                                *slot = g;
                            }
                            n_opp += 1;
                        }
                    }
                    if n_same + n_opp > 2 {
                        let mut faces: Vec<usize> = outs(a)
                            .iter()
                            .filter(|&&g| to(g) == b)
                            .chain(outs(b).iter().filter(|&&g| to(g) == a))
                            .map(|&g| faces.face(g) as usize)
                            .collect();
                        faces.sort_unstable();
                        let edge = [a.min(b) as usize, a.max(b) as usize];
                        return Some((h, MeshError::NonManifoldEdge { edge, faces }));
                    }
                    if n_same == 2 {
                        let mut faces: Vec<usize> = outs(a)
                            .iter()
                            .filter(|&&g| to(g) == b)
                            .map(|&g| faces.face(g) as usize)
                            .collect();
                        faces.sort_unstable();
                        let e = MeshError::InconsistentOrientation {
                            edge: [a as usize, b as usize],
                            faces: [faces[0], faces[1]],
                        };
                        return Some((h, e));
                    }
                }
                None
            })
            .min_by_key(|(h, _)| *h);
        if let Some((_, e)) = bad_edge {
            return Err(e);
        }
        let (he_edge, edge_he) = number_edges(&twin);
        // Vertex half-edges: the boundary outgoing half-edge, else the first; check single fans.
        let mut vert_he = vec![NONE; nv];
        let bad_vertex = vert_he
            .par_chunks_mut(CHUNK)
            .enumerate()
            .filter_map(|(c, chunk)| {
                for (k, slot) in chunk.iter_mut().enumerate() {
                    let v = c * CHUNK + k;
                    let outs = outs(v as u32);
                    let Some(&first) = outs.first() else {
                        continue; // unreferenced vertex (only in refinement output; never queried)
                    };
                    let mut start = first;
                    let mut boundary_starts = 0;
                    for &h in outs {
                        if twin[h as usize] == NONE {
                            boundary_starts += 1;
                            start = h;
                        }
                    }
                    // Count faces reached by counter-clockwise rotation from `start`.
                    let mut count = 1;
                    let mut h = start;
                    loop {
                        let t = twin[faces.prev(h) as usize];
                        if t == NONE || t == start {
                            break;
                        }
                        h = t;
                        count += 1;
                        if count > outs.len() {
                            break;
                        }
                    }
                    if !relaxed && (count != outs.len() || boundary_starts > 1) {
                        let fans = boundary_starts.max(2);
                        return Some((v, MeshError::NonManifoldVertex { vertex: v, fans }));
                    }
                    *slot = start;
                }
                None
            })
            .min_by_key(|(v, _)| *v);
        if let Some((_, e)) = bad_vertex {
            return Err(e);
        }
        Ok(Topology {
            he_face,
            twin,
            he_edge,
            edge_he,
            vert_he,
        })
    }
}

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
    pub fn outgoing(&self, v: usize) -> OutgoingIter<'a> {
        let start = self.vert_he[v];
        OutgoingIter {
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

/// Iterator of [`MeshView::outgoing`].
pub(crate) struct OutgoingIter<'a> {
    view: MeshView<'a>,
    start: u32,
    next: u32,
}

impl Iterator for OutgoingIter<'_> {
    type Item = u32;

    #[inline]
    fn next(&mut self) -> Option<u32> {
        let h = self.next;
        if h == NONE {
            return None;
        }
        let t = self.view.twin[self.view.faces.prev(h) as usize];
        self.next = if t == self.start { NONE } else { t };
        Some(h)
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

impl FaceIndex<'_> {
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

/// Numbers the edges of a half-edge mesh from its twins, in the order of their first half-edge
/// (`h` with no twin or `h < twin[h]`): returns `(he_edge, edge_he)`. Runs in parallel (a count,
/// a scan and two fill passes).
pub(crate) fn number_edges(twin: &[u32]) -> (Vec<u32>, Vec<u32>) {
    use std::sync::atomic::{AtomicU32, Ordering::Relaxed};
    let nh = twin.len();
    let first = |h: usize| {
        let t = twin[h];
        t == NONE || (h as u32) < t
    };
    let blocks = nh.div_ceil(CHUNK);
    let block = |c: usize| c * CHUNK..((c + 1) * CHUNK).min(nh);
    let counts: Vec<usize> = (0..blocks)
        .into_par_iter()
        .map(|c| block(c).filter(|&h| first(h)).count())
        .collect();
    let ne: usize = counts.iter().sum();
    let he_edge: Vec<AtomicU32> = (0..nh)
        .into_par_iter()
        .map(|_| AtomicU32::new(NONE))
        .collect();
    let mut edge_he = vec![0u32; ne];
    let mut parts = Vec::with_capacity(blocks);
    let mut rest = &mut edge_he[..];
    let mut base = 0;
    for &n in &counts {
        let (part, tail) = rest.split_at_mut(n);
        parts.push((base, part));
        base += n;
        rest = tail;
    }
    parts
        .into_par_iter()
        .enumerate()
        .for_each(|(c, (base, part))| {
            let mut k = 0;
            for h in block(c) {
                if first(h) {
                    he_edge[h].store((base + k) as u32, Relaxed);
                    part[k] = h as u32;
                    k += 1;
                }
            }
        });
    (0..blocks).into_par_iter().for_each(|c| {
        for h in block(c) {
            if !first(h) {
                he_edge[h].store(he_edge[twin[h] as usize].load(Relaxed), Relaxed);
            }
        }
    });
    let he_edge = he_edge.into_iter().map(AtomicU32::into_inner).collect();
    (he_edge, edge_he)
}

/// Asserts that two meshes have the same faces and the same half-edge connectivity, edge
/// numbering and vertex half-edges (for tests of refinement kernels that build the child's
/// connectivity directly).
#[cfg(test)]
pub(crate) fn assert_same_topology(a: &PolyMesh, b: &PolyMesh, what: &str) {
    assert_eq!(a.face_starts(), b.face_starts(), "{what}: face offsets");
    assert_eq!(a.corners(), b.corners(), "{what}: corners");
    assert_eq!(a.num_vertices(), b.num_vertices(), "{what}: vertices");
    assert_eq!(a.num_edges(), b.num_edges(), "{what}: edges");
    for h in 0..a.num_halfedges() as u32 {
        assert_eq!(a.he_twin(h), b.he_twin(h), "{what}: twin of {h}");
        assert_eq!(a.he_edge(h), b.he_edge(h), "{what}: edge of {h}");
        assert_eq!(a.he_face(h), b.he_face(h), "{what}: face of {h}");
        assert_eq!(a.he_next(h), b.he_next(h), "{what}: next of {h}");
        assert_eq!(a.he_prev(h), b.he_prev(h), "{what}: prev of {h}");
    }
    for e in 0..a.num_edges() {
        assert_eq!(a.edge_halfedge(e), b.edge_halfedge(e), "{what}: edge {e}");
    }
    assert_eq!(a.edges(), b.edges(), "{what}: edge end points");
    for v in 0..a.num_vertices() {
        assert_eq!(
            a.vertex_halfedge(v),
            b.vertex_halfedge(v),
            "{what}: vertex {v}"
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;

    #[test]
    fn grid_connectivity() {
        let m = crate::gallery::quad_grid(3, |_, _| 0.0);
        assert_eq!(m.num_vertices(), 16);
        assert_eq!(m.num_faces(), 9);
        assert_eq!(m.num_edges(), 24);
        assert_eq!(m.valence(5), 4);
        assert!(!m.is_boundary_vertex(5));
        assert_eq!(m.valence(0), 2);
        assert_eq!(m.valence(1), 3);
        assert_eq!(m.boundary_loops().len(), 1);
        assert_eq!(m.boundary_loops()[0].len(), 12);
        assert_eq!(m.one_ring(5).len(), 8);
        assert_eq!(m.two_ring(5).len(), 7);
        assert!(m.extraordinary_vertices().is_empty());
        // Counter-clockwise neighbours of interior vertex 5 (at (1,1)).
        let nb = m.vertex_neighbors(5);
        assert_eq!(nb.len(), 4);
        let p5 = m.position(5);
        let ang: Vec<f64> = nb
            .iter()
            .map(|&w| {
                let p = m.position(w as usize);
                (p[1] - p5[1]).atan2(p[0] - p5[0])
            })
            .collect();
        for k in 0..4 {
            let d = (ang[(k + 1) % 4] - ang[k]).rem_euclid(2.0 * std::f64::consts::PI);
            assert!(
                (d - std::f64::consts::FRAC_PI_2).abs() < 1e-12,
                "not counter-clockwise"
            );
        }
        // Boundary vertex neighbours run from one boundary neighbour to the other.
        let nb1 = m.vertex_neighbors(1);
        assert_eq!(nb1.len(), 3);
        assert!(m.is_boundary_vertex(nb1[0] as usize) && m.is_boundary_vertex(nb1[2] as usize));
    }

    #[test]
    fn errors_name_the_element() {
        let p = vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]];
        let e = PolyMesh::new(p.clone(), &[vec![0, 1]]).unwrap_err();
        assert!(matches!(
            e,
            Error::Mesh(MeshError::FaceTooSmall { face: 0, len: 2 })
        ));
        let e = PolyMesh::new(p.clone(), &[vec![0, 1, 7]]).unwrap_err();
        assert!(matches!(
            e,
            Error::Mesh(MeshError::IndexOutOfRange {
                face: 0,
                index: 7,
                ..
            })
        ));
        let e = PolyMesh::new(p.clone(), &[vec![0, 1, 1]]).unwrap_err();
        assert!(matches!(
            e,
            Error::Mesh(MeshError::RepeatedVertex { face: 0, vertex: 1 })
        ));
        let e = PolyMesh::new(p.clone(), &[vec![0, 1, 2], vec![0, 1, 3]]).unwrap_err();
        assert!(matches!(
            e,
            Error::Mesh(MeshError::InconsistentOrientation { .. })
        ));
        let mut q = p.clone();
        q[2][1] = f64::NAN;
        let e = PolyMesh::new(q, &[vec![0, 1, 2]]).unwrap_err();
        assert!(matches!(
            e,
            Error::Mesh(MeshError::NonFiniteCoordinate { vertex: 2 })
        ));
        let e = PolyMesh::new(p.clone(), &Vec::<Vec<usize>>::new()).unwrap_err();
        assert!(matches!(e, Error::Mesh(MeshError::Empty)));
        // Three triangles on edge 0-1.
        let mut r = p.clone();
        r.push([0.0, 0.0, 1.0]);
        let e = PolyMesh::new(r, &[vec![0, 1, 2], vec![1, 0, 3], vec![0, 1, 4]]).unwrap_err();
        assert!(
            matches!(
                e,
                Error::Mesh(MeshError::NonManifoldEdge { edge: [0, 1], .. })
            ),
            "{e}"
        );
        // Bow-tie: two triangles sharing only vertex 0.
        let mut s = p.clone();
        s.push([-1.0, 0.0, 0.0]);
        s.push([0.0, -1.0, 0.0]);
        let e = PolyMesh::new(s, &[vec![0, 1, 2], vec![0, 4, 5]]).unwrap_err();
        assert!(
            matches!(
                e,
                Error::Mesh(MeshError::NonManifoldVertex { vertex: 0, .. })
            ),
            "{e}"
        );
    }

    #[test]
    fn parallel_build_reports_the_first_problem() {
        // A grid with more half-edges than one parallel block, with two flipped faces: the
        // error names the first one in half-edge order, as a sequential scan would.
        let n = 150;
        let m = crate::gallery::quad_grid(n, |_, _| 0.0);
        let mut faces: Vec<Vec<usize>> = m
            .faces()
            .map(|f| f.iter().map(|&v| v as usize).collect())
            .collect();
        let (f1, f2) = (9000, 20000);
        faces[f1].reverse();
        faces[f2].reverse();
        let e = PolyMesh::new(m.positions().to_vec(), &faces).unwrap_err();
        match e {
            Error::Mesh(MeshError::InconsistentOrientation { faces, .. }) => {
                // Every conflicting edge lies between a flipped face and a neighbour.
                assert!(faces.contains(&f1), "{faces:?}");
            }
            other => panic!("{other:?}"),
        }
        // Uniform meshes store no face per half-edge and agree with arithmetic.
        assert_eq!(m.uniform_face_size(), Some(4));
        assert!(m.topology().he_face.is_empty());
        assert_eq!(m.num_edges(), 2 * n * (n + 1));
        let g = gallery_mixed();
        assert_eq!(g.uniform_face_size(), None);
        for h in 0..g.num_halfedges() as u32 {
            let f = g.he_face(h) as usize;
            assert!(g.face_starts()[f] <= h && h < g.face_starts()[f + 1]);
        }
    }

    /// A quad and a triangle sharing an edge.
    fn gallery_mixed() -> PolyMesh {
        let p = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 0.5, 0.0],
        ];
        PolyMesh::new(p, &[vec![0, 1, 2, 3], vec![1, 4, 2]]).unwrap()
    }

    #[test]
    fn unused_vertices_dropped() {
        let p = vec![[0.0; 3], [9.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let m = PolyMesh::new(p, &[vec![0, 2, 3]]).unwrap();
        assert_eq!(m.dropped_vertices(), &[1]);
        assert_eq!(m.num_vertices(), 3);
        assert_eq!(m.face(0), &[0, 1, 2]);
    }
}
