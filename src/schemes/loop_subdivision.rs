//! Loop subdivision of triangle nets, with boundaries, written as stencils.
//!
//! Loop's scheme (C. Loop, *Smooth subdivision surfaces based on triangles*, MS thesis, Utah
//! 1987) generalises the quartic three-direction box spline: on a regular net (every interior
//! vertex of valence 6) one step is exactly the box spline's refinement. This module holds the
//! refinement rules, the limit-position masks and the limit-tangent masks, each written once as
//! stencils so that refinement, analysis and patch output share them.
//!
//! # Rules
//!
//! The conventions are OpenSubdiv's Loop scheme (`Sdc::Scheme<SCHEME_LOOP>`) with every boundary
//! edge sharp (a boundary is a crease):
//!
//! | child point | rule |
//! | --- | --- |
//! | interior vertex, valence `n` | `(1 - n beta) v + beta sum p_i`, `beta = (5/8 - (3/8 + cos(2 pi/n)/4)^2) / n` (Loop's own beta) |
//! | boundary vertex | `3/4 v + 1/8 (a + b)`, `a`, `b` its two boundary neighbours (cubic B-spline curve rule) |
//! | corner: boundary vertex with one face (valence 2) | `v`: it stays put |
//! | interior edge `ab` with opposite vertices `c`, `d` | `3/8 (a + b) + 1/8 (c + d)` |
//! | boundary edge `ab` | `(a + b) / 2` |
//!
//! The corner rule is OpenSubdiv's `VTX_BOUNDARY_EDGE_AND_CORNER` behaviour; with
//! `VTX_BOUNDARY_EDGE_ONLY` OpenSubdiv would smooth a valence-2 boundary vertex with the
//! boundary-vertex rule instead. All other rules agree with both options. So the boundary curve
//! is the uniform cubic B-spline of the boundary polygon, which at a corner `c` is continued by the
//! reflected point `2c - p`: the curve interpolates the corner.
//!
//! # Layout of one step
//!
//! Child vertex `v` (for `v < V`) is the child of parent vertex `v`; child vertex `V + e` is the
//! point of parent edge `e`. Parent triangle `f = (a, b, c)` with edge points `ab`, `bc`, `ca`
//! becomes child faces `4f .. 4f + 3` = `(a, ab, ca)`, `(b, bc, ab)`, `(c, ca, bc)`,
//! `(ab, bc, ca)`, oriented like the parent.

use crate::error::{Error, Result};
use crate::geom::{Point, cross, normalize};
use crate::mesh::PolyMesh;
use crate::stencil::{Stencil, StencilTable};

use super::common::{
    Outgoing, RowBuf, boundary_neighbors, check_child_size, cos_2pi, is_corner, sin_2pi,
};
use super::{Refinement, Scheme, finish_refinement};

/// Loop subdivision of triangle nets (scheme name `loop`). See the [module](self) documentation
/// for the rules and the layout of the child net.
#[derive(Debug, Clone, Copy, Default)]
pub struct Loop;

impl Loop {
    /// Loop's weight `beta` of each edge neighbour of an interior vertex of valence `n >= 3`:
    /// `(5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n`; `1/16` for the regular `n = 6`.
    pub fn vertex_beta(n: usize) -> f64 {
        let c = 0.375 + 0.25 * cos_2pi(1, n as i64);
        (0.625 - c * c) / n as f64
    }

    /// Weight `chi` of each edge neighbour in the limit-position mask of an interior vertex of
    /// valence `n`: `chi = 1 / (3 / (8 beta) + n)`, the vertex itself keeping `1 - n chi`;
    /// `1/12` (and `1/2` for the centre) for `n = 6`.
    pub fn limit_chi(n: usize) -> f64 {
        1.0 / (3.0 / (8.0 * Self::vertex_beta(n)) + n as f64)
    }

    /// Stencils of two limit tangents at every vertex, `[t1, t2]` (row `v` for vertex `v`; the
    /// weights of each row sum to 0). The limit normal is `t1 x t2`, pointing to the side from
    /// which the faces are counter-clockwise. Lengths carry no meaning, only directions do.
    ///
    /// Each mask is a left eigenvector of the subdivision matrix of the vertex's one-ring (which
    /// Loop's rules map to itself), so it gives the exact tangent direction of the limit surface:
    ///
    /// - interior vertex of valence `n`, neighbours `p_0 .. p_{n-1}` counter-clockwise:
    ///   `t1 = sum cos(2 pi i / n) p_i`, `t2 = sum sin(2 pi i / n) p_i` (eigenvalue
    ///   `3/8 + cos(2 pi / n) / 4`);
    /// - boundary vertex with `k >= 2` faces, neighbours `p_0 .. p_k` counter-clockwise (`p_0`
    ///   ends the outgoing boundary edge, `p_k` starts the incoming one): along the boundary
    ///   `t1 = p_0 - p_k` (eigenvalue `1/2`); across it, pointing into the surface,
    ///   `t2 = a v + b (p_0 + p_k) + sum_{i=1}^{k-1} sin(i theta) p_i` with `theta = pi / k`,
    ///   eigenvalue `l = 3/8 + cos(theta) / 4`, `b = ((3/4 - l) sin(theta) - 3/8 S) /
    ///   (8 (3/4 - l)(l - 1/2) + 1)`, `S = sum_{i=1}^{k-1} sin(i theta)`,
    ///   `a = 8 (l - 1/2) b - sin(theta)`. For `k = 3` (the regular boundary) this is
    ///   `(sqrt 3 / 4) (2 p_1 + 2 p_2 - 2 v - p_0 - p_3)`, for `k = 2` it is `p_1 - v`, both
    ///   multiples of OpenSubdiv's masks. For `k >= 4` OpenSubdiv uses the general formula of
    ///   Hoppe et al. (SIGGRAPH 1994), which belongs to their modified edge rule and is not an
    ///   eigenvector of the rules used here.
    /// - corner, neighbours `p_0` (outgoing boundary edge) and `p_1`: `t1 = p_0 - v`,
    ///   `t2 = p_1 - v`.
    ///
    /// The one-ring matrix of a boundary vertex has the eigenvalues `1, 1/2, 1/4` of the cubic
    /// B-spline curve and `3/8 + cos(m pi / k) / 4`, `m = 1 .. k-1`. The two tangent eigenvalues
    /// above are the subdominant pair for boundary vertices with up to 5 faces; from 6 faces on
    /// the mode `m = 2` reaches `1/2` (equal at 6, above from 7), a known weakness of these
    /// boundary rules, and the tangent plane there is not guaranteed.
    ///
    /// # Errors
    /// [`Error::Unsupported`] for a face that is not a triangle.
    pub fn limit_tangent_stencils(&self, mesh: &PolyMesh) -> Result<[StencilTable; 2]> {
        check_triangles(mesh)?;
        let nv = mesh.num_vertices();
        let mut t1 = StencilTable::with_capacity(nv, nv, 7);
        let mut t2 = StencilTable::with_capacity(nv, nv, 7);
        let (mut r1, mut r2) = (RowBuf::default(), RowBuf::default());
        for v in 0..nv {
            let vi = v as u32;
            if !mesh.is_boundary_vertex(v) {
                let n = Outgoing::new(mesh, v).count() as i64;
                for (i, h) in Outgoing::new(mesh, v).enumerate() {
                    let p = mesh.he_to(h);
                    r1.add(p, cos_2pi(i as i64, n));
                    r2.add(p, sin_2pi(i as i64, n));
                }
            } else if is_corner(mesh, v) {
                let (p0, p1) = boundary_neighbors(mesh, v);
                r1.add(p0, 1.0);
                r1.add(vi, -1.0);
                r2.add(p1, 1.0);
                r2.add(vi, -1.0);
            } else {
                let (p0, pk) = boundary_neighbors(mesh, v);
                r1.add(p0, 1.0);
                r1.add(pk, -1.0);
                let k = Outgoing::new(mesh, v).count() as i64;
                let sin_t = sin_2pi(1, 2 * k);
                let s: f64 = (1..k).map(|i| sin_2pi(i, 2 * k)).sum();
                let l = 0.375 + 0.25 * cos_2pi(1, 2 * k);
                let b = ((0.75 - l) * sin_t - 0.375 * s) / (8.0 * (0.75 - l) * (l - 0.5) + 1.0);
                let a = 8.0 * (l - 0.5) * b - sin_t;
                r2.add(vi, a);
                r2.add(p0, b);
                r2.add(pk, b);
                // The interior neighbours p_1 .. p_{k-1} end the outgoing half-edges 1 .. k-1.
                for (i, h) in Outgoing::new(mesh, v).enumerate().skip(1) {
                    r2.add(mesh.he_to(h), sin_2pi(i as i64, 2 * k));
                }
            }
            r1.flush_into(&mut t1);
            r2.flush_into(&mut t2);
        }
        Ok([t1, t2])
    }

    /// Unit limit normals at every vertex (`t1 x t2` of [`Loop::limit_tangent_stencils`],
    /// normalised; the zero vector where the net is degenerate).
    ///
    /// # Errors
    /// [`Error::Unsupported`] for a face that is not a triangle.
    pub fn limit_normals(&self, mesh: &PolyMesh) -> Result<Vec<Point>> {
        let [t1, t2] = self.limit_tangent_stencils(mesh)?;
        let (a, b) = (t1.apply(mesh.positions()), t2.apply(mesh.positions()));
        Ok(a.iter()
            .zip(&b)
            .map(|(&x, &y)| normalize(cross(x, y)))
            .collect())
    }
}

/// Loop needs a pure triangle net: the first face that is not a triangle is named.
fn check_triangles(mesh: &PolyMesh) -> Result<()> {
    match (0..mesh.num_faces()).find(|&f| mesh.face_size(f) != 3) {
        None => Ok(()),
        Some(f) => Err(Error::Unsupported(format!(
            "Loop subdivision needs a triangle net, but face {f} has {} corners; triangulate the \
             net or use catmull-clark",
            mesh.face_size(f)
        ))),
    }
}

/// Writes a vertex-centred mask of Loop's shape into `row`: an interior vertex of valence `n`
/// keeps `1 - n w(n)` and gives `w(n)` to each edge neighbour; a boundary vertex keeps
/// `1 - 2 b` and gives `b` to each boundary neighbour; a corner keeps itself. Both the
/// refinement rule and the limit mask have this shape.
fn vertex_mask(mesh: &PolyMesh, v: usize, w: fn(usize) -> f64, b: f64, row: &mut RowBuf) {
    let vi = v as u32;
    if !mesh.is_boundary_vertex(v) {
        let n = Outgoing::new(mesh, v).count();
        let wn = w(n);
        row.add(vi, 1.0 - n as f64 * wn);
        for h in Outgoing::new(mesh, v) {
            row.add(mesh.he_to(h), wn);
        }
    } else if is_corner(mesh, v) {
        row.add(vi, 1.0);
    } else {
        let (p, q) = boundary_neighbors(mesh, v);
        row.add(vi, 1.0 - 2.0 * b);
        row.add(p, b);
        row.add(q, b);
    }
}

/// Writes Loop's edge rule for edge `e` into `row`: `3/8, 3/8` for the end points and `1/8` for
/// each opposite vertex; the midpoint on a boundary edge.
fn edge_mask(mesh: &PolyMesh, e: usize, row: &mut RowBuf) {
    let h = mesh.edge_halfedge(e);
    let (a, b) = (mesh.he_from(h), mesh.he_to(h));
    match mesh.he_twin(h) {
        None => {
            row.add(a, 0.5);
            row.add(b, 0.5);
        }
        Some(t) => {
            row.add(a, 0.375);
            row.add(b, 0.375);
            row.add(mesh.he_from(mesh.he_prev(h)), 0.125);
            row.add(mesh.he_from(mesh.he_prev(t)), 0.125);
        }
    }
}

/// The refined position of vertex `v` under Loop's vertex rule, as a stencil over the mesh
/// vertices (the rule [`Scheme::refine`] applies, for adaptive refinement).
pub fn vertex_point_stencil(mesh: &PolyMesh, v: usize) -> Stencil {
    let mut row = RowBuf::default();
    vertex_mask(mesh, v, Loop::vertex_beta, 0.125, &mut row);
    row.take_stencil()
}

/// The new point of edge `e` under Loop's edge rule, as a stencil over the mesh vertices.
pub fn edge_point_stencil(mesh: &PolyMesh, e: usize) -> Stencil {
    let mut row = RowBuf::default();
    edge_mask(mesh, e, &mut row);
    row.take_stencil()
}

/// The limit position of vertex `v` ([`Scheme::limit_stencils`] for one vertex).
pub fn limit_point_stencil(mesh: &PolyMesh, v: usize) -> Stencil {
    let mut row = RowBuf::default();
    vertex_mask(mesh, v, Loop::limit_chi, 1.0 / 6.0, &mut row);
    row.take_stencil()
}

impl Scheme for Loop {
    fn name(&self) -> &'static str {
        "loop"
    }

    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        check_triangles(mesh)?;
        let (nv, ne, nf) = (mesh.num_vertices(), mesh.num_edges(), mesh.num_faces());
        check_child_size(self.name(), nv + ne)?;
        let mut table = StencilTable::with_capacity(nv, nv + ne, 6);
        let mut row = RowBuf::default();
        for v in 0..nv {
            vertex_mask(mesh, v, Self::vertex_beta, 0.125, &mut row);
            row.flush_into(&mut table);
        }
        for e in 0..ne {
            edge_mask(mesh, e, &mut row);
            row.flush_into(&mut table);
        }
        let nv32 = nv as u32;
        let mut corners = Vec::with_capacity(12 * nf);
        for f in 0..nf {
            let h0 = mesh.face_halfedge(f);
            let tri = mesh.face(f);
            let (a, b, c) = (tri[0], tri[1], tri[2]);
            let ab = nv32 + mesh.he_edge(h0);
            let bc = nv32 + mesh.he_edge(h0 + 1);
            let ca = nv32 + mesh.he_edge(h0 + 2);
            corners.extend_from_slice(&[a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca]);
        }
        let face_start = (0..=4 * nf as u32).map(|i| 3 * i).collect();
        finish_refinement(mesh, table, face_start, corners)
    }

    /// Limit positions: interior `(1 - n chi) v + chi sum p_i` ([`Loop::limit_chi`]), boundary
    /// `2/3 v + 1/6 (a + b)` (the cubic B-spline curve at its knot), corner `v`.
    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        check_triangles(mesh)?;
        let nv = mesh.num_vertices();
        let mut table = StencilTable::with_capacity(nv, nv, 7);
        let mut row = RowBuf::default();
        for v in 0..nv {
            vertex_mask(mesh, v, Self::limit_chi, 1.0 / 6.0, &mut row);
            row.flush_into(&mut table);
        }
        Ok(table)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Regular interior (valence 6) weights, Warren's n = 3 value, and the limit masks.
    #[test]
    fn published_weights() {
        assert_eq!(Loop::vertex_beta(6), 1.0 / 16.0);
        assert_eq!(Loop::vertex_beta(3), 3.0 / 16.0);
        assert_eq!(Loop::vertex_beta(4), (0.625 - 0.375 * 0.375) / 4.0);
        assert!((Loop::limit_chi(6) - 1.0 / 12.0).abs() < 1e-16);
        // n = 5: beta = (5/8 - (3/8 + cos(72 deg)/4)^2)/5 = 0.0790924...
        let c = (2.0 * std::f64::consts::PI / 5.0).cos();
        let beta5 = (0.625 - (0.375 + 0.25 * c).powi(2)) / 5.0;
        assert!((Loop::vertex_beta(5) - beta5).abs() < 1e-16);
        assert!((Loop::vertex_beta(5) - 0.084_093_2).abs() < 1e-7);
    }

    #[test]
    fn quad_face_is_named() {
        let pos = vec![
            [0.0; 3],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0; 3],
        ];
        let m = PolyMesh::new(pos, &[vec![0, 1, 4], vec![0, 4, 2, 3]]).unwrap();
        let msg = Loop.refine(&m).unwrap_err().to_string();
        assert!(msg.contains("face 1 has 4 corners"), "{msg}");
        assert!(
            msg.contains("triangulate the net or use catmull-clark"),
            "{msg}"
        );
        assert!(Loop.limit_stencils(&m).is_err());
        assert!(Loop.limit_tangent_stencils(&m).is_err());
    }
}
