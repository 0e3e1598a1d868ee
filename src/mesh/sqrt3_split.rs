//! The sqrt(3) split of a triangle net (Kobbelt 2000): the topology of one step, without any
//! weights. A scheme supplies the masks of the child points ([`Sqrt3Point`]).
//!
//! One step inserts a point in every triangle, connects it to the triangle's corners and flips
//! every old interior edge, so that each old edge is replaced by the edge between the points of
//! its two triangles. Old boundary edges are not flipped. On a *border step* (Kobbelt's
//! boundary rule: every second step) each triangle with a boundary edge gets no face point;
//! its boundary edge is trisected by two edge points instead and the triangle becomes a fan of
//! three around its opposite corner, whose two old interior edges are then flipped as usual.
//! A border step needs at most one boundary edge per triangle, which holds after any
//! non-border step.
//!
//! Layout of the child: vertex `v < V` is parent vertex `v`; then, face by face in order, the
//! face point, or on a border step the two edge points of a triangle's boundary edge (the one
//! near the edge's start first). The faces are the triangles of the face points' boundary
//! edges, the middle triangles of the trisected faces and the two triangles of each flipped
//! edge, all oriented like the parent.

use super::PolyMesh;
use crate::error::{Error, Result};

/// What a child point of the sqrt(3) split is, for the scheme to give its mask.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sqrt3Point {
    /// The child of parent vertex `v`.
    Vertex(u32),
    /// The point of parent face `f`.
    Face(u32),
    /// The edge point nearer to the start `from` of the boundary half-edge `h` (its face is
    /// the triangle trisected); `to` is the half-edge's end.
    BoundaryEdge {
        /// The boundary half-edge (its twin is missing).
        h: u32,
        /// The end point it lies nearer to.
        near: u32,
        /// The other end point.
        far: u32,
    },
}

/// One sqrt(3) step's topology: the child points (in child vertex order) and the child faces.
#[derive(Debug, Clone)]
pub struct Sqrt3Split {
    /// What each child vertex is.
    pub points: Vec<Sqrt3Point>,
    /// Child triangles, three corners each.
    pub corners: Vec<u32>,
}

impl Sqrt3Split {
    /// Face offsets of the child (all triangles).
    pub fn face_start(&self) -> Vec<u32> {
        super::tri_split::triangle_starts(&self.corners)
    }
}

/// The sqrt(3) split of the triangle net `mesh`; `border` makes it a border step (boundary
/// edges trisected). Errors name a face that is not a triangle, or, on a border step, a
/// triangle with more than one boundary edge.
pub fn sqrt3_split(mesh: &PolyMesh, border: bool) -> Result<Sqrt3Split> {
    let nv = mesh.num_vertices();
    let nf = mesh.num_faces();
    let mut points: Vec<Sqrt3Point> = (0..nv as u32).map(Sqrt3Point::Vertex).collect();
    // Per half-edge: the child vertex opposite it in its face's fan (the face point, or the
    // edge point of a trisected face next to that half-edge).
    let mut apex = vec![u32::MAX; mesh.num_halfedges()];
    let mut corners = Vec::with_capacity(9 * nf);
    for f in 0..nf {
        super::tri_split::require_triangle(mesh, f, "the sqrt(3) split needs", "")?;
        let h0 = mesh.face_halfedge(f);
        let hs = [h0, mesh.he_next(h0), mesh.he_prev(h0)];
        let open: Vec<u32> = hs
            .iter()
            .copied()
            .filter(|&h| mesh.he_twin(h).is_none())
            .collect();
        if border && !open.is_empty() {
            if open.len() > 1 {
                return Err(Error::UnsupportedFace {
                    face: f,
                    msg: format!(
                        "a sqrt(3) border step needs at most one boundary edge per triangle, \
                         but face {f} has {}",
                        open.len()
                    ),
                });
            }
            let hb = open[0];
            let (a, b) = (mesh.he_from(hb), mesh.he_to(hb));
            let c = mesh.he_from(mesh.he_prev(hb));
            let e1 = points.len() as u32;
            points.push(Sqrt3Point::BoundaryEdge {
                h: hb,
                near: a,
                far: b,
            });
            points.push(Sqrt3Point::BoundaryEdge {
                h: hb,
                near: b,
                far: a,
            });
            let e2 = e1 + 1;
            // Fan (a, e1, c), (e1, e2, c), (e2, b, c): the middle one stays, the other two
            // are halves of flips.
            corners.extend_from_slice(&[e1, e2, c]);
            apex[mesh.he_next(hb) as usize] = e2;
            apex[mesh.he_prev(hb) as usize] = e1;
        } else {
            let m = points.len() as u32;
            points.push(Sqrt3Point::Face(f as u32));
            for &h in &hs {
                apex[h as usize] = m;
                if mesh.he_twin(h).is_none() {
                    corners.extend_from_slice(&[mesh.he_from(h), mesh.he_to(h), m]);
                }
            }
        }
    }
    // The flips: old interior edge u -> v (apex x) against v -> u (apex y) gives (u, y, x) and
    // (v, x, y).
    for h in 0..mesh.num_halfedges() as u32 {
        if let Some(t) = mesh.he_twin(h)
            && h < t
        {
            let (u, v) = (mesh.he_from(h), mesh.he_to(h));
            let (x, y) = (apex[h as usize], apex[t as usize]);
            corners.extend_from_slice(&[u, y, x, v, x, y]);
        }
    }
    if points.len() > u32::MAX as usize {
        return Err(Error::Unsupported(
            "one sqrt(3) step would create more points than 32-bit indices allow".into(),
        ));
    }
    Ok(Sqrt3Split { points, corners })
}
