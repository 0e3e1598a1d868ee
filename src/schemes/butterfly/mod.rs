//! The modified butterfly scheme (D. Zorin, P. Schröder, W. Sweldens, *Interpolating
//! Subdivision for Meshes with Arbitrary Topology*, SIGGRAPH 1996): an interpolating scheme on
//! the triangle 1-4 split ([`crate::mesh::tri_split`]); this module supplies the masks.
//!
//! # Rules
//!
//! Old vertices stay (the scheme interpolates). The point of edge `a0 a1`:
//!
//! | edge | rule |
//! | --- | --- |
//! | boundary edge, boundary neighbours `r0` (of `a0`), `r1` (of `a1`) | `9/16 (a0 + a1) - 1/16 (r0 + r1)`: the 4-point rule |
//! | interior, both ends of valence 6, or one end on the boundary and the other of valence 6, or both on the boundary | the butterfly: `1/2 (a0 + a1) + 1/8 (b0 + b1) - 1/16 (c0 + c1 + c2 + c3)` |
//! | interior, an end `a` interior of valence `K != 6` | `3/4 a + sum s_j p_j` over `a`'s neighbours from `p_0` = the other end; averaged when both ends are such |
//!
//! `b0`, `b1` are the vertices opposite the edge, `c0 .. c3` those across the other four edges
//! of its two triangles. ZSS's regular stencil has ten points, `1/2 - w`, `1/8 + 2 w`,
//! `-1/16 - w` and `w` on the two points beyond, with the tension `w = 0` chosen for the
//! modified scheme: the eight points above. The extraordinary weights:
//! `K = 3`: `s = (5/12, -1/12, -1/12)`; `K = 4`: `s = (3/8, 0, -1/8, 0)`; `K >= 5`:
//! `s_j = (1/4 + cos(2 pi j / K) + 1/2 cos(4 pi j / K)) / K`.
//!
//! Boundaries: ZSS's paper gives the 4-point rule for boundary edges; the interior edges near
//! the boundary use the butterfly with a `c` point that lies across a boundary edge replaced by
//! its ghost, the reflection `p + q - o` of the triangle's third corner `o` through the edge
//! `pq`. That near-boundary rule is OpenMesh's (`ModifiedButterflyT`), which
//! `tests/it/peer_sqrt3_butterfly.rs` compares point by point; it is fairsub's choice, not the
//! paper's own boundary stencils.

pub mod descriptor;
pub mod entry;
pub mod local;
pub use descriptor::DESCRIPTOR;

use super::common::{RowBuf, cos_2pi};
use super::options::ids;
use super::{Refinement, Scheme, growth, split_child};
use crate::error::Result;
use crate::mesh::PolyMesh;
use crate::mesh::tri_split::{self, TriSplit};
use crate::stencil::StencilTable;

/// The modified butterfly scheme (scheme name `butterfly`).
#[derive(Debug, Clone, Copy, Default)]
pub struct Butterfly;

/// ZSS's weight `s_j` of neighbour `j` (counted from the edge's other end) of an interior
/// vertex of valence `k != 6`.
pub fn extraordinary_weight(k: usize, j: usize) -> f64 {
    match k {
        3 => [5.0 / 12.0, -1.0 / 12.0, -1.0 / 12.0][j],
        4 => [3.0 / 8.0, 0.0, -1.0 / 8.0, 0.0][j],
        _ => {
            let (j, k) = (j as i64, k as i64);
            (0.25 + cos_2pi(j, k) + 0.5 * cos_2pi(2 * j, k)) / k as f64
        }
    }
}

/// The point across the edge of half-edge `k` from its triangle: the third corner of the
/// triangle on the other side, or, across a boundary edge, the ghost `p + q - o`.
fn across(mesh: &PolyMesh, k: u32, w: f64, row: &mut RowBuf) {
    match mesh.he_twin(k) {
        Some(t) => row.add(mesh.he_from(mesh.he_prev(t)), w),
        None => {
            row.add(mesh.he_from(k), w);
            row.add(mesh.he_to(k), w);
            row.add(mesh.he_from(mesh.he_prev(k)), -w);
        }
    }
}

/// The extraordinary rule of interior vertex `from(h)` for the edge of its outgoing `h`,
/// scaled by `scale`.
fn extraordinary(mesh: &PolyMesh, h: u32, k: usize, scale: f64, row: &mut RowBuf) {
    row.add(mesh.he_from(h), 0.75 * scale);
    for (j, g) in mesh.view().outgoing_from(h).enumerate() {
        row.add(mesh.he_to(g), extraordinary_weight(k, j) * scale);
    }
}

/// The mask of the point of edge `e`.
fn edge_mask(mesh: &PolyMesh, e: usize, row: &mut RowBuf) {
    let h = mesh.edge_halfedge(e);
    let (a0, a1) = (mesh.he_from(h), mesh.he_to(h));
    let Some(t) = mesh.he_twin(h) else {
        let r0 = mesh.boundary_neighbors(a0 as usize).1;
        let r1 = mesh.boundary_neighbors(a1 as usize).0;
        row.add(a0, 9.0 / 16.0);
        row.add(a1, 9.0 / 16.0);
        row.add(r0, -1.0 / 16.0);
        row.add(r1, -1.0 / 16.0);
        return;
    };
    let (k0, k1) = (mesh.valence(a0 as usize), mesh.valence(a1 as usize));
    let (bd0, bd1) = (
        mesh.is_boundary_vertex(a0 as usize),
        mesh.is_boundary_vertex(a1 as usize),
    );
    let plain0 = bd0 || k0 == 6;
    let plain1 = bd1 || k1 == 6;
    if plain0 && plain1 {
        row.add(a0, 0.5);
        row.add(a1, 0.5);
        for s in [h, t] {
            row.add(mesh.he_from(mesh.he_prev(s)), 0.125);
            across(mesh, mesh.he_next(s), -1.0 / 16.0, row);
            across(mesh, mesh.he_prev(s), -1.0 / 16.0, row);
        }
        return;
    }
    let ends = [(!plain0, h, k0), (!plain1, t, k1)];
    let count = ends.iter().filter(|e| e.0).count() as f64;
    for (special, g, k) in ends {
        if special {
            extraordinary(mesh, g, k, 1.0 / count, row);
        }
    }
}

impl Scheme for Butterfly {
    fn name(&self) -> &'static str {
        ids::BUTTERFLY.name()
    }

    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        tri_split::check(mesh)?;
        let nv = mesh.num_vertices();
        let mut table = StencilTable::with_capacity(nv, nv + mesh.num_edges(), 8);
        table.push_points(0..nv as u32);
        let mut row = RowBuf::default();
        for e in 0..mesh.num_edges() {
            edge_mask(mesh, e, &mut row);
            row.flush_into(&mut table);
        }
        // the child's half-edges from the parent's, as Loop's (the butterfly has no sharp
        // features)
        let positions = table.apply(mesh.positions());
        let mesh = split_child::child_mesh::<TriSplit>(mesh, positions, None);
        Ok(Refinement {
            mesh,
            stencils: table,
        })
    }

    fn step_size(&self, s: &growth::NetSize) -> growth::NetSize {
        let mut c = growth::triangle(s);
        // An edge point takes at most 14 points (the butterfly with ghosts) or the rings of
        // its two ends (`k0 + k1 + 2`, summing over the edges to the squared valences).
        c.stencil = s.vertices + s.valence_squares + 16.0 * s.edges;
        c
    }

    /// The scheme interpolates: every vertex is its own limit point.
    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        Ok(StencilTable::identity(mesh.num_vertices()))
    }
}
