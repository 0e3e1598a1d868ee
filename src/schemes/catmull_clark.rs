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

use super::{Refinement, Scheme, finish_refinement};
use crate::error::Result;
use crate::geom::{self, Point};
use crate::mesh::PolyMesh;
use crate::stencil::{Stencil, StencilTable};
use std::f64::consts::PI;

/// The Catmull-Clark scheme.
#[derive(Debug, Clone, Copy, Default)]
pub struct CatmullClark;

/// Appends the face-point stencil of face `f` scaled by `s`.
fn add_face_point(mesh: &PolyMesh, f: usize, s: f64, out: &mut Stencil) {
    let face = mesh.face(f);
    let w = s / face.len() as f64;
    for &v in face {
        out.add(v as usize, w);
    }
}

/// Stencil of the Catmull-Clark vertex point of `v`.
pub(crate) fn vertex_point_stencil(mesh: &PolyMesh, v: usize) -> Stencil {
    let mut s = Stencil::new();
    if mesh.is_boundary_vertex(v) {
        let nb = mesh.vertex_neighbors(v);
        if nb.len() == 2 {
            // Corner: stays put.
            s.add(v, 1.0);
        } else {
            s.add(v, 0.75);
            s.add(nb[0] as usize, 0.125);
            s.add(
                *nb.last().expect("boundary vertex has neighbours") as usize,
                0.125,
            );
        }
        return s.merged();
    }
    let hs = mesh.outgoing_halfedges(v);
    let n = hs.len() as f64;
    s.add(v, (n - 2.0) / n);
    let w = 1.0 / (n * n);
    for &h in &hs {
        s.add(mesh.he_to(h) as usize, w);
        add_face_point(mesh, mesh.he_face(h) as usize, w, &mut s);
    }
    s.merged()
}

/// Stencil of the Catmull-Clark edge point of edge `e`.
pub(crate) fn edge_point_stencil(mesh: &PolyMesh, e: usize) -> Stencil {
    let [a, b] = mesh.edge(e);
    let mut s = Stencil::new();
    let h = mesh.edge_halfedge(e);
    match mesh.he_twin(h) {
        None => {
            s.add(a as usize, 0.5);
            s.add(b as usize, 0.5);
        }
        Some(t) => {
            s.add(a as usize, 0.25);
            s.add(b as usize, 0.25);
            add_face_point(mesh, mesh.he_face(h) as usize, 0.25, &mut s);
            add_face_point(mesh, mesh.he_face(t) as usize, 0.25, &mut s);
        }
    }
    s.merged()
}

impl CatmullClark {
    /// The refinement stencils of one step (child vertex order as in the module doc).
    pub fn stencils(mesh: &PolyMesh) -> StencilTable {
        let (nv, ne, nf) = (mesh.num_vertices(), mesh.num_edges(), mesh.num_faces());
        let mut t = StencilTable::with_capacity(nv, nv + ne + nf, 9);
        for v in 0..nv {
            t.push(vertex_point_stencil(mesh, v));
        }
        for e in 0..ne {
            t.push(edge_point_stencil(mesh, e));
        }
        for f in 0..nf {
            let mut s = Stencil::new();
            add_face_point(mesh, f, 1.0, &mut s);
            t.push(s);
        }
        t
    }

    /// Child topology of one step: `(face_start, corners)` of the all-quad child net.
    pub fn child_topology(mesh: &PolyMesh) -> (Vec<u32>, Vec<u32>) {
        let (nv, ne) = (mesh.num_vertices() as u32, mesh.num_edges() as u32);
        let nh = mesh.num_halfedges();
        let face_start: Vec<u32> = (0..=nh as u32).map(|h| 4 * h).collect();
        let mut corners = Vec::with_capacity(4 * nh);
        for h in 0..nh as u32 {
            let v = mesh.he_from(h);
            let e_out = nv + mesh.he_edge(h);
            let e_in = nv + mesh.he_edge(mesh.he_prev(h));
            let f = nv + ne + mesh.he_face(h);
            corners.extend_from_slice(&[v, e_out, f, e_in]);
        }
        (face_start, corners)
    }

    /// Limit-position stencils of every vertex of `mesh` (row `v` for vertex `v`).
    ///
    /// Interior vertex surrounded by quads: `(n^2 v + 4 sum e_j + sum f_j) / (n (n + 5))` with edge
    /// neighbours `e_j` and diagonal neighbours `f_j`; boundary vertex: `(a + 4 v + b) / 6`;
    /// corner: `v`. A vertex next to a non-quad face takes the limit of its child after one
    /// step (composed with that step's stencils), which is the same limit point.
    pub fn limit_stencils(mesh: &PolyMesh) -> StencilTable {
        let nv = mesh.num_vertices();
        let mut t = StencilTable::with_capacity(nv, nv, 9);
        let mut child: Option<(PolyMesh, StencilTable)> = None;
        for v in 0..nv {
            match Self::direct_limit_stencil(mesh, v) {
                Some(s) => t.push(s),
                None => {
                    let (cm, cs) = child.get_or_insert_with(|| Self::child(mesh));
                    t.push(Self::limit_through_child(cm, cs, v));
                }
            }
        }
        t
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
        let (fs, cn) = Self::child_topology(mesh);
        let m = PolyMesh::from_refinement(st.apply(mesh.positions()), fs, cn)
            .expect("Catmull-Clark child of a valid mesh is valid");
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
        if mesh.is_boundary_vertex(v) {
            let nb = mesh.vertex_neighbors(v);
            if nb.len() == 2 {
                s.add(v, 1.0);
            } else {
                s.add(v, 4.0 / 6.0);
                s.add(nb[0] as usize, 1.0 / 6.0);
                s.add(*nb.last()? as usize, 1.0 / 6.0);
            }
            return Some(s.merged());
        }
        let hs = mesh.outgoing_halfedges(v);
        if hs
            .iter()
            .any(|&h| mesh.face_size(mesh.he_face(h) as usize) != 4)
        {
            return None;
        }
        let n = hs.len() as f64;
        let d = n * (n + 5.0);
        s.add(v, n * n / d);
        for &h in &hs {
            s.add(mesh.he_to(h) as usize, 4.0 / d);
            s.add(
                mesh.he_from(mesh.he_next(mesh.he_next(h))) as usize,
                1.0 / d,
            );
        }
        Some(s.merged())
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
        let diag = |h: u32| mesh.he_from(mesh.he_next(mesh.he_next(h))) as usize;
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
                    let c = nb[1] as usize;
                    let d1 = diag(hs[0]);
                    let d2 = diag(hs[1]);
                    along.add(a, 1.0).add(b, -1.0);
                    across
                        .add(d1, 1.0)
                        .add(c, 4.0)
                        .add(d2, 1.0)
                        .add(a, -1.0)
                        .add(v, -4.0)
                        .add(b, -1.0);
                }
                _ => return None,
            }
            return Some((along.merged(), across.merged()));
        }
        let n = hs.len();
        let nf = n as f64;
        let c = (2.0 * PI / nf).cos();
        let a_n = 1.0 + c + (PI / nf).cos() * (2.0 * (9.0 + c)).sqrt();
        let mut t1 = Stencil::new();
        let mut t2 = Stencil::new();
        for (j, &h) in hs.iter().enumerate() {
            let cj = |k: isize| (2.0 * PI * k as f64 / nf).cos();
            let (e, f) = (mesh.he_to(h) as usize, diag(h));
            let j = j as isize;
            t1.add(e, a_n * cj(j));
            t1.add(f, cj(j) + cj(j + 1));
            t2.add(e, a_n * cj(j - 1));
            t2.add(f, cj(j - 1) + cj(j));
        }
        Some((t1.merged(), t2.merged()))
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
        let st = Self::stencils(mesh);
        let (fs, cn) = Self::child_topology(mesh);
        let child = PolyMesh::from_refinement(st.apply(pos), fs, cn).expect("valid child");
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
        "catmull-clark"
    }

    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        let st = Self::stencils(mesh);
        let (fs, cn) = Self::child_topology(mesh);
        finish_refinement(mesh, st, fs, cn)
    }

    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        Ok(Self::limit_stencils(mesh))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_one_level_by_hand() {
        let m = crate::gallery::unit_cube();
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
        let m = crate::gallery::unit_cube();
        let l0 = CatmullClark::limit_stencils(&m).apply(m.positions());
        let r = CatmullClark.refine(&m).unwrap();
        let l1 = CatmullClark::limit_stencils(&r.mesh).apply(r.mesh.positions());
        for v in 0..8 {
            assert!(geom::dist(l0[v], l1[v]) < 1e-14);
        }
    }
}
