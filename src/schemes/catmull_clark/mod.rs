//! Catmull-Clark subdivision with boundaries, limit positions and limit normals.
//!
//! Rules as in OpenSubdiv's Catmark scheme with boundary interpolation of edges and corners
//! (`VTX_BOUNDARY_EDGE_AND_CORNER`; with edge-only interpolation OpenSubdiv would smooth
//! valence-2 corners by the crease rule, fairsub keeps them as the foundation issue asks):
//! face point = centroid; interior edge point = (a + b + F1 + F2) / 4; interior vertex of valence
//! n: (n - 2)/n v + 1/n^2 sum(edge neighbours) + 1/n^2 sum(face points); boundary edges and
//! vertices follow the cubic B-spline curve rules of the boundary polygon ((a + b)/2 and
//! (a + 6 v + b)/8); a boundary vertex with a single incident face (valence 2) is a corner and
//! stays put.
//!
//! Child vertex order: one vertex point per parent vertex, then one edge point per parent edge
//! (edge index order), then one face point per parent face. Child face `h` is the quad of parent
//! corner (half-edge) `h`: (vertex point, edge point of the outgoing edge, face point, edge point
//! of the incoming edge), so child faces inherit the parent orientation.
//!
//! # One source of truth, two ways to apply it
//!
//! The rules are written once (`face_rule`, `edge_rule`, `vertex_rule`) against `CcTerms`:
//! terms on parent vertices and on parent face points. A stencil table
//! ([`CatmullClark::stencils`]) expands each face-point term into the face's corners; the direct
//! kernel ([`CatmullClark::refine_points`]) computes the face points first and reads them back,
//! as OpenSubdiv's primvar refiner does. The child connectivity is derived from the parent's
//! combinatorially ([`CatmullClark::child_mesh`]): no search, every pass parallel. One-shot
//! refinement to several levels ([`CatmullClark::refine_uniform`]) keeps no tables, drops each
//! parent level as soon as its child exists, and does not build the last level's half-edges.

pub mod descriptor;
pub mod local;
pub mod regular;
pub mod surface;
pub use descriptor::DESCRIPTOR;

use super::common::check_child_size;
use super::{Refinement, Scheme};
use crate::error::Result;
use crate::geom::{self, Point};
use crate::mesh::{FaceIndex, MeshParts, MeshView, NONE, PolyMesh, Topology, number_edges};
use crate::stencil::{RowWriter, Stencil, StencilTable, Terms, axpy};
use rayon::prelude::*;
use std::f64::consts::PI;

/// The Catmull-Clark scheme.
#[derive(Debug, Clone, Copy, Default)]
pub struct CatmullClark;

/// Receives the terms of a Catmull-Clark rule: weights on parent vertices and on parent face
/// points (see the module documentation).
pub(crate) trait CcTerms {
    /// Adds `w` times parent vertex `v`.
    fn vertex(&mut self, v: u32, w: f64);
    /// Adds `w` times the face point of parent face `f` ([`face_rule`]).
    fn face_point(&mut self, f: u32, w: f64);
}

/// Face point of face `f`, scaled by `scale`: `scale / k` times each of its `k` corners.
#[inline]
fn face_rule(m: &MeshView<'_>, f: usize, scale: f64, out: &mut impl CcTerms) {
    let face = m.face_corners(f);
    let w = scale / face.len() as f64;
    for &v in face {
        out.vertex(v, w);
    }
}

/// Edge point of edge `e`: `(a + b + F1 + F2) / 4` inside, the midpoint on the boundary.
#[inline]
fn edge_rule(m: &MeshView<'_>, e: usize, out: &mut impl CcTerms) {
    let h = m.edge_he[e];
    let (a, b) = (m.from(h), m.to(h));
    let t = m.twin(h);
    if t == NONE {
        out.vertex(a, 0.5);
        out.vertex(b, 0.5);
    } else {
        out.vertex(a, 0.25);
        out.vertex(b, 0.25);
        out.face_point(m.face(h), 0.25);
        out.face_point(m.face(t), 0.25);
    }
}

/// Vertex point of `v`: `(n - 2)/n v + 1/n^2 sum(edge neighbours) + 1/n^2 sum(face points)`
/// inside; `3/4 v + 1/8 (a + b)` on the boundary; a corner stays put.
#[inline]
fn vertex_rule(m: &MeshView<'_>, v: usize, out: &mut impl CcTerms) {
    if m.is_boundary_vertex(v) {
        if m.is_corner(v) {
            out.vertex(v as u32, 1.0);
        } else {
            let (a, b) = m.boundary_neighbors(v);
            out.vertex(v as u32, 0.75);
            out.vertex(a, 0.125);
            out.vertex(b, 0.125);
        }
        return;
    }
    let n = m.outgoing(v).count() as f64;
    out.vertex(v as u32, (n - 2.0) / n);
    let w = 1.0 / (n * n);
    for h in m.outgoing(v) {
        out.vertex(m.to(h), w);
        out.face_point(m.face(h), w);
    }
}

/// Expands face-point terms into the face's corners: the table form of a rule.
struct Expand<'a, T> {
    m: MeshView<'a>,
    row: &'a mut T,
}

impl<T: Terms> CcTerms for Expand<'_, T> {
    #[inline]
    fn vertex(&mut self, v: u32, w: f64) {
        self.row.add(v, w);
    }

    #[inline]
    fn face_point(&mut self, f: u32, w: f64) {
        let m = self.m;
        face_rule(&m, f as usize, w, self);
    }
}

/// Evaluates a rule on point data, reading face points from the already computed child points.
struct Eval<'a, const D: usize> {
    src: &'a [[f64; D]],
    faces: &'a [[f64; D]],
    acc: [f64; D],
}

impl<'a, const D: usize> Eval<'a, D> {
    #[inline]
    fn new(src: &'a [[f64; D]], faces: &'a [[f64; D]]) -> Self {
        Eval {
            src,
            faces,
            acc: [0.0; D],
        }
    }
}

impl<const D: usize> CcTerms for Eval<'_, D> {
    #[inline]
    fn vertex(&mut self, v: u32, w: f64) {
        axpy(&mut self.acc, w, &self.src[v as usize]);
    }

    #[inline]
    fn face_point(&mut self, f: u32, w: f64) {
        axpy(&mut self.acc, w, &self.faces[f as usize]);
    }
}

/// Stencil of the Catmull-Clark vertex point of `v`.
pub(crate) fn vertex_point_stencil(mesh: &PolyMesh, v: usize) -> Stencil {
    let mut s = Stencil::new();
    let m = mesh.view();
    vertex_rule(&m, v, &mut Expand { m, row: &mut s });
    s.merged()
}

/// Stencil of the Catmull-Clark edge point of edge `e`.
pub(crate) fn edge_point_stencil(mesh: &PolyMesh, e: usize) -> Stencil {
    let mut s = Stencil::new();
    let m = mesh.view();
    edge_rule(&m, e, &mut Expand { m, row: &mut s });
    s.merged()
}

/// Child points (or parent half-edges) per parallel task.
const BLOCK: usize = 4096;

/// Fails when a child net would not fit fairsub's 32-bit indices.
fn check_sizes(mesh: &PolyMesh) -> Result<()> {
    check_child_size(
        crate::schemes::registry::ids::CATMULL_CLARK.name(),
        mesh.num_vertices() + mesh.num_edges() + mesh.num_faces(),
    )?;
    // Child half-edges (4 per parent corner) are indexed by u32 below NONE.
    check_child_size(
        crate::schemes::registry::ids::CATMULL_CLARK.name(),
        4 * mesh.num_halfedges() + 1,
    )
}

/// Child corners of one step from the parent's arrays: child face `h` is
/// `(from(h), edge point of h, face point of h, edge point of prev(h))`.
fn child_corners(
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

/// The limit-position rule of vertex `v` (see [`CatmullClark::limit_stencils`]) when all faces
/// at `v` are quads or `v` is on the boundary; returns `false`, writing nothing, otherwise.
/// Walks the connectivity in place (no allocation per vertex).
fn limit_terms(m: &MeshView<'_>, v: usize, t: &mut impl Terms) -> bool {
    let vv = v as u32;
    if m.is_boundary_vertex(v) {
        if m.is_corner(v) {
            t.add(vv, 1.0);
        } else {
            let (a, b) = m.boundary_neighbors(v);
            t.add(vv, 4.0 / 6.0);
            t.add(a, 1.0 / 6.0);
            t.add(b, 1.0 / 6.0);
        }
        return true;
    }
    if m.outgoing(v)
        .any(|h| m.face_corners(m.face(h) as usize).len() != 4)
    {
        return false;
    }
    let n = m.outgoing(v).count() as f64;
    let d = n * (n + 5.0);
    t.add(vv, n * n / d);
    for h in m.outgoing(v) {
        t.add(m.to(h), 4.0 / d);
        t.add(m.from(m.faces.next(m.faces.next(h))), 1.0 / d);
    }
    true
}

impl CatmullClark {
    /// The refinement stencils of one step (child vertex order as in the module doc), built in
    /// parallel without per-row allocation.
    pub fn stencils(mesh: &PolyMesh) -> StencilTable {
        let (nv, ne, nf) = (mesh.num_vertices(), mesh.num_edges(), mesh.num_faces());
        let m = mesh.view();
        StencilTable::build_par(nv, nv + ne + nf, 9, |rows, t| {
            let mut row = RowWriter::new();
            for r in rows {
                let mut x = Expand { m, row: &mut row };
                if r < nv {
                    vertex_rule(&m, r, &mut x);
                } else if r < nv + ne {
                    edge_rule(&m, r - nv, &mut x);
                } else {
                    face_rule(&m, r - nv - ne, 1.0, &mut x);
                }
                row.push_into(t);
            }
        })
    }

    /// The child points of one step computed directly by the rules (no table): face points
    /// first, then edge and vertex points reading them, in parallel. Works on any per-point
    /// data (`src` has one entry per parent vertex): positions, colours, texture coordinates.
    /// Row `i` of the result equals row `i` of [`CatmullClark::stencils`] applied to `src` up
    /// to rounding.
    ///
    /// # Panics
    /// Panics when `src` has fewer entries than the mesh has vertices.
    pub fn refine_points<const D: usize>(mesh: &PolyMesh, src: &[[f64; D]]) -> Vec<[f64; D]> {
        let (nv, ne, nf) = (mesh.num_vertices(), mesh.num_edges(), mesh.num_faces());
        assert!(src.len() >= nv, "one point per parent vertex is needed");
        let m = mesh.view();
        // Zeroed output (fresh pages, touched once); face points first, in place.
        let mut out = crate::buffers::zeroed(nv + ne + nf, [0.0; D]);
        let (head, faces) = out.split_at_mut(nv + ne);
        faces
            .par_chunks_mut(BLOCK)
            .enumerate()
            .for_each(|(c, chunk)| {
                for (k, o) in chunk.iter_mut().enumerate() {
                    let mut ev = Eval::new(src, &[]);
                    face_rule(&m, c * BLOCK + k, 1.0, &mut ev);
                    *o = ev.acc;
                }
            });
        let faces: &[[f64; D]] = faces;
        head.par_chunks_mut(BLOCK)
            .enumerate()
            .for_each(|(c, chunk)| {
                for (k, o) in chunk.iter_mut().enumerate() {
                    let i = c * BLOCK + k;
                    let mut ev = Eval::new(src, faces);
                    if i < nv {
                        vertex_rule(&m, i, &mut ev);
                    } else {
                        edge_rule(&m, i - nv, &mut ev);
                    }
                    *o = ev.acc;
                }
            });
        out
    }

    /// Child topology of one step: `(face_start, corners)` of the all-quad child net.
    pub fn child_topology(mesh: &PolyMesh) -> (Vec<u32>, Vec<u32>) {
        let face_start = (0..mesh.num_halfedges() + 1)
            .into_par_iter()
            .map(|h| 4 * h as u32)
            .collect();
        (face_start, Self::child_corners(mesh))
    }

    /// The corners of the child faces (four per parent corner).
    fn child_corners(mesh: &PolyMesh) -> Vec<u32> {
        let m = mesh.view();
        child_corners(
            m.faces,
            m.corners,
            m.he_edge,
            mesh.num_vertices(),
            mesh.num_edges(),
        )
    }

    /// The child net of one step with the given child points (from
    /// [`CatmullClark::refine_points`] or [`CatmullClark::stencils`]), its half-edge
    /// connectivity derived from the parent's without any search: the same connectivity, edge
    /// numbering and vertex half-edges as [`PolyMesh::from_refinement`] would build.
    ///
    /// # Panics
    /// Panics when `positions` does not have one point per child vertex.
    pub fn child_mesh(mesh: &PolyMesh, positions: Vec<Point>) -> PolyMesh {
        let (nv, ne, nf) = (mesh.num_vertices(), mesh.num_edges(), mesh.num_faces());
        assert_eq!(positions.len(), nv + ne + nf, "one point per child vertex");
        let topo = Self::child_halfedges(mesh);
        PolyMesh::from_trusted_uniform(positions, 4, Self::child_corners(mesh), Some(topo))
    }

    /// Half-edge topology of the child net from the parent's. Child half-edge `4h + k` is side
    /// `k` of child face `h` (`k = 0`: vertex point to outgoing edge point, `1`: to the face
    /// point, `2`: to the incoming edge point, `3`: back to the vertex point), so twins are
    /// known combinatorially: `4h` and `4 next(twin h) + 3`, `4h + 1` and `4 next(h) + 2`.
    fn child_halfedges(mesh: &PolyMesh) -> Topology {
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
        // Vertex half-edges by the rule of the generic build: the boundary outgoing half-edge,
        // else the smallest outgoing one.
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
        }
    }

    /// `levels` steps of one-shot refinement: the refined net only. Points come from the direct
    /// kernel ([`CatmullClark::refine_points`]), connectivity from the parent's; no stencil
    /// table is built, each parent level is dropped as soon as its child exists, and the last
    /// step frees the parent's points and most of its connectivity before allocating the child
    /// faces and does not build the last level's half-edges (built on first use, if ever). So
    /// the peak memory stays close to the size of the result. `progress(level)` is called after
    /// each step.
    ///
    /// # Errors
    /// When a level would exceed fairsub's 32-bit indices.
    pub fn refine_uniform(
        mesh: &PolyMesh,
        levels: usize,
        mut progress: impl FnMut(usize),
    ) -> Result<PolyMesh> {
        use super::common::{OneShotStep, one_shot_levels};
        one_shot_levels(mesh, levels, &mut progress, check_sizes, |s| {
            Ok(match s {
                OneShotStep::Middle(p) => {
                    Self::child_mesh(p, Self::refine_points(p, p.positions()))
                }
                OneShotStep::OnlyStep(p) => PolyMesh::from_trusted_uniform(
                    Self::refine_points(p, p.positions()),
                    4,
                    Self::child_corners(p),
                    None,
                ),
                OneShotStep::Last(p) => {
                    let positions = Self::refine_points(&p, p.positions());
                    Self::last_child(p, positions)
                }
            })
        })
    }

    /// The last step of [`CatmullClark::refine_uniform`]: consumes the parent, keeping only
    /// what the child faces need (its corners, face offsets and edge numbers).
    fn last_child(parent: PolyMesh, positions: Vec<Point>) -> PolyMesh {
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

    /// Limit-position stencils of every vertex of `mesh` (row `v` for vertex `v`).
    ///
    /// Interior vertex surrounded by quads: `(n^2 v + 4 sum e_j + sum f_j) / (n (n + 5))` with edge
    /// neighbours `e_j` and diagonal neighbours `f_j`; boundary vertex: `(a + 4 v + b) / 6`;
    /// corner: `v`. A vertex next to a non-quad face takes the limit of its child after one
    /// step (composed with that step's stencils), which is the same limit point.
    ///
    /// Rows are built in parallel blocks.
    pub fn limit_stencils(mesh: &PolyMesh) -> StencilTable {
        let nv = mesh.num_vertices();
        // Only a vertex next to a non-quad face needs the child.
        let child = (!mesh.is_all_quads()).then(|| Self::child(mesh));
        let m = mesh.view();
        StencilTable::build_par(nv, nv, 9, |rows, t| {
            let mut row = RowWriter::new();
            for v in rows {
                if limit_terms(&m, v, &mut row) {
                    row.push_into(t);
                } else {
                    let (cm, cs) = child.as_ref().expect("a non-quad face is next to v");
                    t.push(Self::limit_through_child(cm, cs, v));
                }
            }
        })
    }

    /// Limit-position stencil of one vertex (see [`CatmullClark::limit_stencils`]).
    pub fn limit_stencil(mesh: &PolyMesh, v: usize) -> Stencil {
        Self::direct_limit_stencil(mesh, v).unwrap_or_else(|| {
            let (cm, cs) = Self::child(mesh);
            Self::limit_through_child(&cm, &cs, v)
        })
    }

    fn child(mesh: &PolyMesh) -> (PolyMesh, StencilTable) {
        let st = Self::stencils(mesh);
        let m = Self::child_mesh(mesh, st.apply(mesh.positions()));
        (m, st)
    }

    fn limit_through_child(cm: &PolyMesh, cs: &StencilTable, v: usize) -> Stencil {
        let s =
            Self::direct_limit_stencil(cm, v).expect("child of a vertex is surrounded by quads");
        let mut out = Stencil::new();
        for &(i, w) in s.entries() {
            out.add_scaled(&cs.stencil(i as usize), w);
        }
        out.merged()
    }

    /// Limit stencil when all faces at `v` are quads (or `v` is on the boundary).
    fn direct_limit_stencil(mesh: &PolyMesh, v: usize) -> Option<Stencil> {
        let mut s = Stencil::new();
        limit_terms(&mesh.view(), v, &mut s).then(|| s.merged())
    }

    /// Limit tangent stencils `(t1, t2)` at vertex `v` when all faces at `v` are quads: for an
    /// interior vertex the eigenvector masks of Halstead et al. (t1 x t2 is the outward normal);
    /// for a boundary vertex of valence 3 and a corner the exact derivatives of the regular
    /// boundary patch (ghost points mirrored across the boundary). Returns `None` for other
    /// boundary vertices and vertices next to non-quads.
    pub fn tangent_stencils(mesh: &PolyMesh, v: usize) -> Option<(Stencil, Stencil)> {
        let hs = mesh.outgoing_halfedges(v);
        if hs
            .iter()
            .any(|&h| mesh.face_size(mesh.he_face(h) as usize) != 4)
        {
            return None;
        }
        if mesh.is_boundary_vertex(v) {
            let nb = mesh.vertex_neighbors(v);
            let (a, b) = (nb[0] as usize, *nb.last()? as usize);
            let mut along = Stencil::new();
            let mut across = Stencil::new();
            match nb.len() {
                2 => {
                    // Corner: the face is (v, a, d, b); tangents along both boundary edges.
                    along.add(a, 1.0).add(v, -1.0);
                    across.add(b, 1.0).add(v, -1.0);
                }
                3 => {
                    // Regular boundary vertex: nb = [a, c, b] counter-clockwise.
                    along.add(a, 1.0).add(b, -1.0);
                    across = Self::boundary_cross_stencil(mesh, v, &hs, &nb);
                }
                _ => return None,
            }
            return Some((along.merged(), across.merged()));
        }
        Some((
            Self::eigen_tangent(mesh, &hs, 0).merged(),
            Self::eigen_tangent(mesh, &hs, 1).merged(),
        ))
    }

    /// Halstead et al.'s eigenvector tangent mask at an interior vertex of valence `n` with only
    /// quads around it (`hs` its outgoing half-edges), phased to its `j`-th edge:
    /// `sum_i a_n cos(2 pi (i - j) / n) e_i + (cos(2 pi (i - j) / n) + cos(2 pi (i + 1 - j) / n)) f_i`
    /// over the edge neighbours `e_i` and face neighbours `f_i`, `a_n = 1 + c + cos(pi / n)
    /// sqrt(2 (9 + c))`. It points along the limit tangent of edge `j`; divided by `3 n` it is the
    /// derivative along that edge in its unit parameter (exact for `n = 4`).
    pub fn eigen_tangent(mesh: &PolyMesh, hs: &[u32], j: usize) -> Stencil {
        let nf = hs.len() as f64;
        let c = (2.0 * PI / nf).cos();
        let a_n = 1.0 + c + (PI / nf).cos() * (2.0 * (9.0 + c)).sqrt();
        let j = j as isize;
        let cj = |k: isize| (2.0 * PI * (k - j) as f64 / nf).cos();
        let diag = |h: u32| mesh.he_from(mesh.he_next(mesh.he_next(h))) as usize;
        let mut t = Stencil::new();
        for (i, &h) in hs.iter().enumerate() {
            let i = i as isize;
            t.add(mesh.he_to(h) as usize, a_n * cj(i));
            t.add(diag(h), cj(i) + cj(i + 1));
        }
        t
    }

    /// Six times the derivative across the boundary, in the unit edge parameter, at a regular
    /// boundary vertex `v` (two quads; `hs` its outgoing half-edges, `nb = [a, c, b]` its
    /// neighbours counter-clockwise): `d1 + 4 c + d2 - a - 4 v - b`, the exact derivative of the
    /// regular boundary patch with ghost points mirrored across the boundary.
    pub fn boundary_cross_stencil(mesh: &PolyMesh, v: usize, hs: &[u32], nb: &[u32]) -> Stencil {
        let diag = |h: u32| mesh.he_from(mesh.he_next(mesh.he_next(h))) as usize;
        let (a, c, b) = (nb[0] as usize, nb[1] as usize, nb[2] as usize);
        let mut across = Stencil::new();
        across
            .add(diag(hs[0]), 1.0)
            .add(c, 4.0)
            .add(diag(hs[1]), 1.0)
            .add(a, -1.0)
            .add(v, -4.0)
            .add(b, -1.0);
        across
    }

    /// Unit limit normals of every vertex (outward for counter-clockwise faces). Vertices whose
    /// tangents have no closed form here (next to non-quads, irregular boundary vertices) use the
    /// limit normal of their child after one step, found the same way, and after two steps fall
    /// back to the area-weighted normal of the child's limit positions.
    pub fn limit_normals(mesh: &PolyMesh) -> Vec<Point> {
        Self::normals_rec(mesh, 2)
    }

    fn normals_rec(mesh: &PolyMesh, depth: usize) -> Vec<Point> {
        let pos = mesh.positions();
        let mut out = vec![[0.0; 3]; mesh.num_vertices()];
        let mut missing = Vec::new();
        for (v, o) in out.iter_mut().enumerate() {
            match Self::tangent_stencils(mesh, v) {
                Some((t1, t2)) => *o = geom::normalize(geom::cross(t1.apply(pos), t2.apply(pos))),
                None => missing.push(v),
            }
        }
        if missing.is_empty() {
            return out;
        }
        let child = Self::child_mesh(mesh, Self::refine_points(mesh, pos));
        let child_normals = if depth > 0 {
            Self::normals_rec(&child, depth - 1)
        } else {
            let lim = Self::limit_stencils(&child).apply(child.positions());
            (0..child.num_vertices())
                .map(|v| {
                    let mut nrm = [0.0; 3];
                    for h in child.outgoing_halfedges(v) {
                        let a = geom::sub(lim[child.he_to(h) as usize], lim[v]);
                        let p = child.he_prev(h);
                        let b = geom::sub(lim[child.he_from(p) as usize], lim[v]);
                        nrm = geom::add(nrm, geom::cross(a, b));
                    }
                    geom::normalize(nrm)
                })
                .collect()
        };
        for v in missing {
            out[v] = child_normals[v];
        }
        out
    }
}

impl Scheme for CatmullClark {
    fn name(&self) -> &'static str {
        crate::schemes::registry::ids::CATMULL_CLARK.name()
    }

    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        check_sizes(mesh)?;
        let stencils = Self::stencils(mesh);
        let mesh = Self::child_mesh(mesh, stencils.apply(mesh.positions()));
        Ok(Refinement { mesh, stencils })
    }

    fn refine_uniform(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        progress: &mut dyn FnMut(usize),
    ) -> Result<PolyMesh> {
        Self::refine_uniform(mesh, levels, progress)
    }

    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        Ok(Self::limit_stencils(mesh))
    }
}

/// Catmull-Clark's subdominant eigenvalue in closed form,
/// `(c + 5 + sqrt((c + 1)(c + 9))) / 16` with `c = cos(2 pi / n)`.
pub fn catmull_clark_lambda(n: usize) -> f64 {
    let c = (2.0 * PI / n as f64).cos();
    (c + 5.0 + ((c + 1.0) * (c + 9.0)).sqrt()) / 16.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_one_level_by_hand() {
        let m = crate::mesh::nets::unit_cube();
        let r = CatmullClark.refine(&m).unwrap();
        assert_eq!(r.mesh.num_vertices(), 8 + 12 + 6);
        assert_eq!(r.mesh.num_faces(), 24);
        // Vertex (0,0,0), valence 3: Q = mean of face points of the 3 faces at it
        // = ((0.5,0.5,0)+(0.5,0,0.5)+(0,0.5,0.5))/3 = (1/3,1/3,1/3);
        // R = mean of edge midpoints = ((0.5,0,0)+(0,0.5,0)+(0,0,0.5))/3 = (1/6,1/6,1/6);
        // V' = (Q + 2R + (n-3) v)/n = (1/3 + 1/3)/3 = 2/9 per coordinate.
        let p = r.mesh.position(0);
        for c in p {
            assert!((c - 2.0 / 9.0).abs() < 1e-15, "{p:?}");
        }
        // Edge (0,0,0)-(1,0,0): (a + b + F1 + F2)/4 with F1=(0.5,0.5,0), F2=(0.5,0,0.5):
        // (0.5, 0.125, 0.125).
        let e = (0..m.num_edges()).find(|&e| {
            let [a, b] = m.edge(e);
            (a.min(b), a.max(b)) == (0, 1)
        });
        let q = r.mesh.position(8 + e.unwrap());
        assert!(
            (q[0] - 0.5).abs() < 1e-15
                && (q[1] - 0.125).abs() < 1e-15
                && (q[2] - 0.125).abs() < 1e-15
        );
        // Face point of the bottom face.
        assert_eq!(r.mesh.position(20), [0.5, 0.5, 0.0]);
        assert!(r.mesh.is_all_quads());
    }

    #[test]
    fn limit_is_fixed_under_refinement() {
        // Limit of a vertex equals the limit of its child (vertex points keep their index).
        let m = crate::mesh::nets::unit_cube();
        let l0 = CatmullClark::limit_stencils(&m).apply(m.positions());
        let r = CatmullClark.refine(&m).unwrap();
        let l1 = CatmullClark::limit_stencils(&r.mesh).apply(r.mesh.positions());
        for v in 0..8 {
            assert!(geom::dist(l0[v], l1[v]) < 1e-14);
        }
    }

    fn max_dist(a: &[Point], b: &[Point]) -> f64 {
        assert_eq!(a.len(), b.len());
        a.iter()
            .zip(b)
            .map(|(p, q)| geom::dist(*p, *q))
            .fold(0.0, f64::max)
    }

    #[test]
    fn direct_child_equals_generic_build_and_kernel_equals_table() {
        for (name, mesh) in crate::gallery::all() {
            let mut m = mesh;
            for level in 0..2 {
                let what = format!("{name} level {level}");
                let st = CatmullClark::stencils(&m);
                let pts = st.apply(m.positions());
                let direct = CatmullClark::child_mesh(&m, pts.clone());
                let (fs, c) = CatmullClark::child_topology(&m);
                let generic = PolyMesh::from_refinement(pts.clone(), fs, c).unwrap();
                crate::mesh::assert_same_topology(&direct, &generic, &what);
                let fused = CatmullClark::refine_points(&m, m.positions());
                assert!(max_dist(&fused, &pts) < 1e-13, "{what}");
                // Rows built by the rules equal the single-point stencils.
                for v in 0..m.num_vertices() {
                    assert_eq!(st.stencil(v), vertex_point_stencil(&m, v), "{what}");
                }
                for e in 0..m.num_edges() {
                    let r = m.num_vertices() + e;
                    assert_eq!(st.stencil(r), edge_point_stencil(&m, e), "{what}");
                }
                m = direct;
            }
        }
    }

    #[test]
    fn one_shot_levels_equal_repeated_steps() {
        for (name, mesh) in crate::gallery::all() {
            for levels in 0..=3 {
                let what = format!("{name}, {levels} levels");
                let mut calls = Vec::new();
                let fast = CatmullClark::refine_uniform(&mesh, levels, |l| calls.push(l)).unwrap();
                assert_eq!(calls, (1..=levels).collect::<Vec<_>>());
                let mut slow = mesh.clone();
                for _ in 0..levels {
                    slow = CatmullClark.refine(&slow).unwrap().mesh;
                }
                assert!(
                    max_dist(fast.positions(), slow.positions()) < 1e-12,
                    "{what}"
                );
                // The last level's connectivity is built on first use and agrees.
                crate::mesh::assert_same_topology(&fast, &slow, &what);
            }
        }
        // Through the trait, as the CLI calls it; other data widths through the kernel.
        let m = crate::mesh::nets::unit_cube();
        let r = super::super::refine_levels(&CatmullClark, &m, 2, |_| {}).unwrap();
        assert_eq!(r.num_faces(), 96);
        let colours: Vec<[f64; 1]> = (0..8).map(|v| [v as f64]).collect();
        let c1 = CatmullClark::refine_points(&m, &colours);
        let t = CatmullClark::stencils(&m).apply(&colours);
        assert!(c1.iter().zip(&t).all(|(a, b)| (a[0] - b[0]).abs() < 1e-14));
    }
}
