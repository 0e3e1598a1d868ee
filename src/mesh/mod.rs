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

mod check;
mod csr;
pub mod dual_split;
mod element;
mod extras;
mod general;
mod halfedge;
pub mod nets;
pub mod quad_split;
pub mod split;
pub mod sqrt3_split;
pub mod tags;
pub mod ternary_split;
mod topology;
pub mod tri_split;
mod view;
mod walk;

pub(crate) use check::{check_face, check_finite};
use check::{face_count, repeated_corner, uniform_size};
pub use element::Element;
pub use extras::{Extras, FaceVarying, ScalarKind, SharpEdges, VertexData};
pub(crate) use general::NonManifold;
pub(crate) use topology::number_edges;
pub use view::Outgoing;
pub(crate) use view::{FaceIndex, MeshView};

use crate::error::{MeshError, Result};
use crate::geom::Point;
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
    /// with the smallest index ([`NONE`] for a vertex no face uses).
    pub(crate) vert_he: Vec<u32>,
    /// The non-manifold edges and vertices of a net built by the tolerant constructor
    /// ([`PolyMesh::from_flat_general`]); `None` for a manifold net.
    pub(crate) nm: Option<Box<NonManifold>>,
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
    /// Sharp features, face-varying and per-vertex data (`None` for a plain net).
    extras: Option<Box<Extras>>,
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
pub(crate) const CHUNK: usize = 1 << 14;

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
        let nf = face_count(&positions, &face_start)?;
        let nv = positions.len();
        // For large faces: the last face that used each vertex (so a repeat is found in time
        // linear in the face size); allocated only when a large face appears.
        let mut last_face: Vec<u32> = Vec::new();
        for f in 0..nf {
            let (a, b) = (face_start[f] as usize, face_start[f + 1] as usize);
            let face = &corners[a..b];
            check_face(face, f, nv)?;
            if let Some(vertex) = repeated_corner(face, f as u32, &mut last_face) {
                return Err(MeshError::RepeatedVertex { face: f, vertex }.into());
            }
        }
        check_finite(&positions)?;
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
        Ok(Self::assemble(
            positions, face_start, corners, uniform, topo, dropped,
        ))
    }

    /// The mesh of checked face arrays and their topology (no extras); `dropped` lists the
    /// input vertices no face used, removed.
    pub(super) fn assemble(
        positions: Vec<Point>,
        face_start: Vec<u32>,
        corners: Vec<u32>,
        uniform: u32,
        topo: Topology,
        dropped: Vec<usize>,
    ) -> PolyMesh {
        PolyMesh {
            positions,
            face_start: OnceLock::from(face_start),
            corners,
            uniform,
            topo: OnceLock::from(topo),
            edges: OnceLock::new(),
            dropped,
            extras: None,
        }
    }

    /// Builds a mesh whose validity is guaranteed by construction (refinement output). Still
    /// builds the topology and fails on a broken input instead of producing a wrong mesh.
    pub fn from_refinement(
        positions: Vec<Point>,
        face_start: Vec<u32>,
        corners: Vec<u32>,
    ) -> Result<PolyMesh> {
        Self::from_refined_faces(positions, face_start, corners, false)
    }

    /// Like [`PolyMesh::from_refinement`], but tolerates non-manifold ("bow-tie") vertices, as
    /// they occur at the cut of a partially refined region. Such a vertex gets one of its fans;
    /// callers must not rely on its one-ring (adaptive refinement marks it incomplete).
    pub fn from_partial_refinement(
        positions: Vec<Point>,
        face_start: Vec<u32>,
        corners: Vec<u32>,
    ) -> Result<PolyMesh> {
        Self::from_refined_faces(positions, face_start, corners, true)
    }

    /// The one builder of [`PolyMesh::from_refinement`] and
    /// [`PolyMesh::from_partial_refinement`]: the topology is built (and checked), bow-tie
    /// vertices tolerated when `bow_ties`.
    fn from_refined_faces(
        positions: Vec<Point>,
        face_start: Vec<u32>,
        corners: Vec<u32>,
        bow_ties: bool,
    ) -> Result<PolyMesh> {
        let uniform = uniform_size(&face_start);
        let topo = Topology::build(positions.len(), &face_start, &corners, uniform, bow_ties)?;
        Ok(Self::assemble(
            positions,
            face_start,
            corners,
            uniform,
            topo,
            Vec::new(),
        ))
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
            extras: None,
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

    /// The half-edge topology (built now if this refined mesh did not have it yet: strictly,
    /// or tolerantly where the net is not manifold or has unused vertices).
    #[inline]
    pub(crate) fn topology(&self) -> &Topology {
        self.topo.get_or_init(|| {
            let nv = self.positions.len();
            Topology::build(
                nv,
                self.stored_offsets(),
                &self.corners,
                self.uniform,
                false,
            )
            .ok()
            .filter(|t| !t.vert_he.contains(&NONE))
            .unwrap_or_else(|| {
                Self::general_topology(nv, self.offsets(), &self.corners, self.uniform)
            })
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

/// Asserts that two meshes have the same faces and the same half-edge connectivity, edge
/// numbering and vertex half-edges (for tests of refinement kernels that build the child's
/// connectivity directly).
#[cfg(feature = "unit-tests")]
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

#[cfg(feature = "unit-tests")]
mod tests;
