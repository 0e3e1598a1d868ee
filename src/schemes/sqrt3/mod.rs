//! Kobbelt's sqrt(3) subdivision of triangle nets (L. Kobbelt, *sqrt(3)-Subdivision*,
//! SIGGRAPH 2000), approximating, with Kobbelt's boundary rule: the masks of the child points
//! of the mesh layer's sqrt(3) split ([`crate::mesh::sqrt3_split`]).
//!
//! # Rules
//!
//! | child point | rule |
//! | --- | --- |
//! | face point | the centroid `(a + b + c) / 3` |
//! | interior vertex, valence `n` | `(1 - alpha_n) v + alpha_n / n sum p_i`, `alpha_n = (4 - 2 cos(2 pi / n)) / 9` |
//! | boundary vertex, odd step | `v`: it stays put |
//! | boundary vertex, border step | `(4 r + 19 v + 4 q) / 27`, `r`, `q` its boundary neighbours |
//! | edge point of boundary edge `pq` near `p`, border step | `(r + 16 p + 10 q) / 27`, `r` the other boundary neighbour of `p` |
//!
//! The boundary masks are the univariate ternary subdivision of the uniform cubic B-spline,
//! applied every second step (steps 2, 4, ... are border steps; step 1 leaves the boundary
//! polygon untouched and flips no boundary edge), so that two steps refine the boundary by 3
//! as two steps refine the interior. These are the rules of Kobbelt's paper (Section 4,
//! boundaries) as CGAL implements them (`Sqrt3_mask_3::border_node`, `Sqrt3_1step`), against
//! which `tests/it/peer_sqrt3_butterfly.rs` compares point by point.
//!
//! # Limit positions
//!
//! On the one-ring of an interior vertex, `v` and the ring's mean `s` evolve by the 2x2 matrix
//! `[[1 - alpha, alpha], [1/3, 2/3]]` (the new ring is the face points `(v + p_i + p_i+1) / 3`),
//! whose left eigenvector of 1 gives the limit `(1 - beta) v + beta s` with
//! `beta = 3 alpha / (1 + 3 alpha)`. The boundary curve is the cubic B-spline of the boundary
//! polygon: limit `(r + 4 v + q) / 6`. [`Scheme::limit_stencils`] is the limit of sqrt(3)
//! subdivision *started* from the net given (its next step odd): for closed nets that is the
//! limit of any level, for open nets that of an even level; after an odd number of levels on an
//! open net the near-boundary interior differs, since the next step would be a border step.

pub mod descriptor;
pub mod entry;
pub mod local;
pub use descriptor::DESCRIPTOR;

use super::common::{RowBuf, cos_2pi};
use super::options::ids;
use super::{Refinement, Scheme, finish_refinement, growth};
use crate::error::Result;
use crate::mesh::PolyMesh;
use crate::mesh::sqrt3_split::{Sqrt3Point, sqrt3_split};
use crate::stencil::StencilTable;

/// Kobbelt's sqrt(3) subdivision (scheme name `sqrt3`). [`Scheme::refine`] is an odd step (the
/// boundary untouched); several levels alternate odd and border steps.
#[derive(Debug, Clone, Copy, Default)]
pub struct Sqrt3;

/// Kobbelt's `alpha_n = (4 - 2 cos(2 pi / n)) / 9`.
pub fn alpha(n: usize) -> f64 {
    (4.0 - 2.0 * cos_2pi(1, n as i64)) / 9.0
}

/// The limit weight `beta_n = 3 alpha_n / (1 + 3 alpha_n)` of an interior vertex's ring.
pub fn limit_beta(n: usize) -> f64 {
    let a = alpha(n);
    3.0 * a / (1.0 + 3.0 * a)
}

/// The two boundary neighbours `(r, q)` of boundary vertex `v`.
fn boundary_pair(mesh: &PolyMesh, v: usize) -> (u32, u32) {
    mesh.boundary_neighbors(v)
}

/// `(1 - w) v + w / n sum p_i` over the edge neighbours of interior vertex `v`.
fn ring_mask(mesh: &PolyMesh, v: usize, w: impl Fn(usize) -> f64, row: &mut RowBuf) {
    let n = mesh.valence(v);
    let w = w(n);
    row.add(v as u32, 1.0 - w);
    for h in mesh.outgoing(v) {
        row.add(mesh.he_to(h), w / n as f64);
    }
}

/// The mask of one child point of the split.
fn point_mask(mesh: &PolyMesh, p: Sqrt3Point, border: bool, row: &mut RowBuf) {
    match p {
        Sqrt3Point::Face(f) => {
            for &c in mesh.face(f as usize) {
                row.add(c, 1.0 / 3.0);
            }
        }
        Sqrt3Point::Vertex(v) => {
            let v = v as usize;
            if !mesh.is_boundary_vertex(v) {
                ring_mask(mesh, v, alpha, row);
            } else if border {
                let (r, q) = boundary_pair(mesh, v);
                row.add(r, 4.0 / 27.0);
                row.add(v as u32, 19.0 / 27.0);
                row.add(q, 4.0 / 27.0);
            } else {
                row.add(v as u32, 1.0);
            }
        }
        Sqrt3Point::BoundaryEdge { near, far, .. } => {
            let (a, b) = boundary_pair(mesh, near as usize);
            let r = if a == far { b } else { a };
            row.add(r, 1.0 / 27.0);
            row.add(near, 16.0 / 27.0);
            row.add(far, 10.0 / 27.0);
        }
    }
}

impl Sqrt3 {
    /// One step: `border` makes it a border step (boundary edges trisected, boundary vertices
    /// smoothed), as every second step is.
    pub fn step(&self, mesh: &PolyMesh, border: bool) -> Result<Refinement> {
        let split = sqrt3_split(mesh, border)?;
        let mut table = StencilTable::with_capacity(mesh.num_vertices(), split.points.len(), 7);
        let mut row = RowBuf::default();
        for &p in &split.points {
            point_mask(mesh, p, border, &mut row);
            row.flush_into(&mut table);
        }
        let face_start = split.face_start();
        finish_refinement(mesh, table, face_start, split.corners)
    }
}

impl Scheme for Sqrt3 {
    fn name(&self) -> &'static str {
        ids::SQRT3.name()
    }

    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        self.step(mesh, false)
    }

    /// Kobbelt's boundary rule alternates: the border is kept on even steps (0, 2, ...) and
    /// trisected on odd ones.
    fn refine_at(&self, mesh: &PolyMesh, level: usize) -> Result<Refinement> {
        self.step(mesh, level % 2 == 1)
    }

    fn step_size(&self, s: &growth::NetSize) -> growth::NetSize {
        // Upper bounds over both kinds of step: every triangle becomes three; a face point per
        // triangle, or (border step) two edge points instead of a trisected triangle's one.
        growth::NetSize {
            vertices: s.vertices + s.faces + s.boundary_edges,
            edges: s.edges + 3.0 * s.faces + 2.0 * s.boundary_edges,
            faces: 3.0 * s.faces,
            corners: 9.0 * s.faces,
            boundary_edges: 3.0 * s.boundary_edges,
            non_triangles: 0.0,
            face_squares: 27.0 * s.faces,
            valence_squares: s.valence_squares
                + 4.0 * s.edges
                + 36.0 * s.faces
                + 25.0 * s.boundary_edges,
            stencil: s.vertices + 2.0 * s.edges + 3.0 * s.faces + 6.0 * s.boundary_edges,
        }
    }

    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        let mut table = StencilTable::with_capacity(mesh.num_vertices(), mesh.num_vertices(), 7);
        let mut row = RowBuf::default();
        for v in 0..mesh.num_vertices() {
            if mesh.is_boundary_vertex(v) {
                let (r, q) = boundary_pair(mesh, v);
                row.add(r, 1.0 / 6.0);
                row.add(v as u32, 4.0 / 6.0);
                row.add(q, 1.0 / 6.0);
            } else {
                ring_mask(mesh, v, limit_beta, &mut row);
            }
            row.flush_into(&mut table);
        }
        Ok(table)
    }
}
