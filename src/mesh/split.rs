//! What the 1-4 split refiners share: the topology of one uniform step (`UniformSplit`,
//! implemented by `quad_split::QuadSplit` and `tri_split::TriSplit`) and the
//! sparse step over selected faces ([`sparse_split`]), both without any weights (OpenSubdiv's
//! `Vtr` refinements, CGAL's hosts: the split is topology, the masks are the scheme's).
//!
//! A uniform step numbers the child points as vertex points (one per parent vertex), edge points
//! (one per parent edge, `nv + e`) and, for splits with face points, face points (`nv + ne + f`);
//! its child half-edges are derived from the parent's without any search, for manifold parents
//! combinatorially and for any parent by the tolerant build fed with the child edges as the
//! parent determines them (the two halves of every parent edge, shared by all its faces, and the
//! edges inside the parent faces), as OpenSubdiv's refinement does.
//!
//! A sparse step refines only the selected faces (the adaptive levels of Catmull-Clark, Loop and
//! non-box): the same child faces per parent face, the child points numbered in the order the
//! selected faces first use them ([`Numbering`]).

use super::{FaceIndex, MeshView, NONE, PolyMesh, Topology};
use std::ops::Range;

/// The topology of one uniform 1-4 split (quads at every corner with face points, or triangles
/// at every corner plus a middle one), numbered as the [module](self) says.
pub(crate) trait UniformSplit {
    /// Corners per child face.
    const ARITY: u32;
    /// The child points of one step of `mesh`.
    fn num_points(mesh: &PolyMesh) -> usize;
    /// The child corners from the parent's arrays (the parent's faces, corners and edge of
    /// every half-edge; `nv`, `ne` its vertex and edge counts), in parallel.
    fn corners(
        faces: FaceIndex<'_>,
        corners: &[u32],
        he_edge: &[u32],
        nv: usize,
        ne: usize,
    ) -> Vec<u32>;
    /// The child's half-edges when the parent is manifold: what [`PolyMesh::from_refinement`]
    /// would build, derived without search.
    fn manifold_halfedges(mesh: &PolyMesh) -> Topology;
    /// The child's half-edges for any parent (non-manifold ones included), by the tolerant
    /// build; for a manifold parent equal to [`UniformSplit::manifold_halfedges`].
    fn general_halfedges(mesh: &PolyMesh, child_corners: &[u32]) -> Topology;
    /// The child half-edge on the half of parent edge(`h`) at the end of `h` (`at_to`) or at
    /// its start, inside the face of `h`.
    fn half_side(m: &MeshView<'_>, h: u32, at_to: bool) -> u32;
    /// The child faces of parent face `f` (consecutive).
    fn face_children(m: &MeshView<'_>, f: u32) -> Range<u32>;

    /// The child corners of one step of `mesh`.
    fn child_corners(mesh: &PolyMesh) -> Vec<u32> {
        let m = mesh.view();
        Self::corners(
            m.faces,
            m.corners,
            m.he_edge,
            mesh.num_vertices(),
            mesh.num_edges(),
        )
    }

    /// The child's half-edges (manifold or tolerant build, as the parent is).
    fn child_halfedges(mesh: &PolyMesh, child_corners: &[u32]) -> Topology {
        if mesh.is_manifold() {
            Self::manifold_halfedges(mesh)
        } else {
            Self::general_halfedges(mesh, child_corners)
        }
    }
}

/// The end (0 or 1) of edge(h) at which the start of half-edge `h` lies.
#[inline]
fn end_at_from(m: &MeshView<'_>, h: u32) -> u32 {
    let first = m.edge_he[m.he_edge[h as usize] as usize];
    u32::from(!(h == first || m.from(h) == m.from(first)))
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
/// their vertex points.
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

/// What a child point of a sparse step is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SplitPoint {
    /// The point of parent vertex `v`.
    Vertex(u32),
    /// The point of parent edge `e`.
    Edge(u32),
    /// The point of parent face `f` (quad split).
    Face(u32),
}

/// The order in which a sparse step numbers the child points of each selected face (in the
/// order of the selected faces, each point where it is first used). The orders are the
/// conventions the adaptive levels have always used, kept so that their outputs stay the same.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Numbering {
    /// The face point, then per corner the vertex point and the points of its outgoing and its
    /// incoming edge (Catmull-Clark's levels).
    FaceFirst,
    /// Per corner the vertex point and the point of its outgoing edge, then the face point, if
    /// the split has one (Loop's and non-box's levels).
    CornersFirst,
}

/// One sparse step: the selected faces of a parent split, their child points numbered
/// compactly ([`Numbering`]).
#[derive(Debug, Clone)]
pub struct SparseSplit {
    /// What each child point is, in child vertex order.
    pub points: Vec<SplitPoint>,
    /// The child vertex of each parent vertex's point ([`NONE`] where none was made).
    pub vertex_point: Vec<u32>,
    /// The child vertex of each parent edge's point ([`NONE`] where none was made).
    pub edge_point: Vec<u32>,
    /// The child vertex of each parent face's point (quad split; [`NONE`] where none was made,
    /// empty for the triangle split).
    pub face_point: Vec<u32>,
    /// Child face offsets.
    pub face_start: Vec<u32>,
    /// Child face corners.
    pub corners: Vec<u32>,
    /// The first child face of each selected parent face ([`NONE`] for the others); its
    /// children are consecutive, in the order of the uniform split's.
    pub first_child: Vec<u32>,
    /// The selected parent faces, in the order given.
    pub faces: Vec<u32>,
}

impl SparseSplit {
    /// The child faces of the selected parent face `f`.
    pub fn children(&self, m: &PolyMesh, f: u32, quads: bool) -> Range<u32> {
        let first = self.first_child[f as usize];
        let k = if quads {
            m.face_size(f as usize) as u32
        } else {
            4
        };
        first..first + k
    }
}

/// The sparse step of `mesh` over the selected faces `faces` (each once): quads at every corner
/// with face points (`quads`, the layout of [`super::quad_split`]) or the triangle 1-4 split
/// (the layout of [`super::tri_split`]; triangles only). Child corners and faces as in the
/// uniform split, child points numbered by `numbering`.
pub fn sparse_split(
    mesh: &PolyMesh,
    faces: Vec<u32>,
    quads: bool,
    numbering: Numbering,
) -> SparseSplit {
    let (nv, ne, nf) = (mesh.num_vertices(), mesh.num_edges(), mesh.num_faces());
    let mut points = Vec::with_capacity(3 * faces.len());
    let mut vid = vec![NONE; nv];
    let mut eid = vec![NONE; ne];
    let mut fid = if quads { vec![NONE; nf] } else { Vec::new() };
    let mut face_start = Vec::with_capacity(4 * faces.len() + 1);
    face_start.push(0u32);
    let mut corners = Vec::with_capacity(if quads { 16 } else { 12 } * faces.len());
    let mut first_child = vec![NONE; nf];
    let face_first = numbering == Numbering::FaceFirst;
    for &f in &faces {
        let fu = f as usize;
        if quads && face_first {
            number(&mut fid[fu], SplitPoint::Face(f), &mut points);
        }
        let h0 = mesh.face_halfedge(fu);
        let k = mesh.face_size(fu) as u32;
        for h in h0..h0 + k {
            let v = mesh.he_from(h);
            number(&mut vid[v as usize], SplitPoint::Vertex(v), &mut points);
            let e = mesh.he_edge(h);
            number(&mut eid[e as usize], SplitPoint::Edge(e), &mut points);
            if face_first {
                let e = mesh.he_edge(mesh.he_prev(h));
                number(&mut eid[e as usize], SplitPoint::Edge(e), &mut points);
            }
        }
        if quads && !face_first {
            number(&mut fid[fu], SplitPoint::Face(f), &mut points);
        }
        first_child[fu] = (face_start.len() - 1) as u32;
        let vp = |h: u32| vid[mesh.he_from(h) as usize];
        let ep = |h: u32| eid[mesh.he_edge(h) as usize];
        if quads {
            let fc = fid[fu];
            for h in h0..h0 + k {
                corners.extend_from_slice(&[vp(h), ep(h), fc, ep(mesh.he_prev(h))]);
                face_start.push(corners.len() as u32);
            }
        } else {
            let (a, b, c) = (vp(h0), vp(h0 + 1), vp(h0 + 2));
            let (ab, bc, ca) = (ep(h0), ep(h0 + 1), ep(h0 + 2));
            for tri in [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]] {
                corners.extend_from_slice(&tri);
                face_start.push(corners.len() as u32);
            }
        }
    }
    SparseSplit {
        points,
        vertex_point: vid,
        edge_point: eid,
        face_point: fid,
        face_start,
        corners,
        first_child,
        faces,
    }
}

/// Gives the point `p` the next child vertex unless `id` already holds one.
#[inline]
fn number(id: &mut u32, p: SplitPoint, points: &mut Vec<SplitPoint>) {
    if *id == NONE {
        *id = points.len() as u32;
        points.push(p);
    }
}
