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

pub mod descriptor;
pub mod local;
pub mod surface;
pub use descriptor::DESCRIPTOR;

use crate::error::{Error, Result};
use crate::geom::{Point, cross, normalize};
use crate::mesh::{MeshParts, MeshView, NONE, PolyMesh, Topology, number_edges};
use crate::stencil::{Accumulator, Stencil, StencilTable, Terms};
use rayon::prelude::*;

use super::common::{
    Outgoing, RowBuf, boundary_neighbors, check_child_size, cos_2pi, is_corner, sin_2pi,
};
use super::{Refinement, Scheme};

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
    require_triangles(mesh, "Loop subdivision needs")
}

/// The error naming the first face of `mesh` that is not a triangle (`what` says who needs
/// triangles: "Loop subdivision needs", "Loop patches need").
pub(crate) fn require_triangles(mesh: &PolyMesh, what: &str) -> Result<()> {
    match (0..mesh.num_faces()).find(|&f| mesh.face_size(f) != 3) {
        None => Ok(()),
        Some(f) => Err(Error::UnsupportedFace {
            face: f,
            msg: format!(
                "{what} a triangle net, but face {f} has {} corners; triangulate the net or use {}",
                mesh.face_size(f),
                crate::schemes::registry::ids::CATMULL_CLARK
            ),
        }),
    }
}

/// Writes a vertex-centred mask of Loop's shape into `row`: an interior vertex of valence `n`
/// keeps `1 - n w(n)` and gives `w(n)` to each edge neighbour; a boundary vertex keeps
/// `1 - 2 b` and gives `b` to each boundary neighbour; a corner keeps itself. Both the
/// refinement rule and the limit mask have this shape.
#[inline]
fn vertex_mask(m: &MeshView<'_>, v: usize, w: fn(usize) -> f64, b: f64, row: &mut impl Terms) {
    let vi = v as u32;
    if !m.is_boundary_vertex(v) {
        let n = m.outgoing(v).count();
        let wn = w(n);
        row.add(vi, 1.0 - n as f64 * wn);
        for h in m.outgoing(v) {
            row.add(m.to(h), wn);
        }
    } else if m.is_corner(v) {
        row.add(vi, 1.0);
    } else {
        let (p, q) = m.boundary_neighbors(v);
        row.add(vi, 1.0 - 2.0 * b);
        row.add(p, b);
        row.add(q, b);
    }
}

/// Writes Loop's edge rule for edge `e` into `row`: `3/8, 3/8` for the end points and `1/8` for
/// each opposite vertex; the midpoint on a boundary edge.
#[inline]
fn edge_mask(m: &MeshView<'_>, e: usize, row: &mut impl Terms) {
    let h = m.edge_he[e];
    let (a, b) = (m.from(h), m.to(h));
    match m.twin(h) {
        NONE => {
            row.add(a, 0.5);
            row.add(b, 0.5);
        }
        t => {
            row.add(a, 0.375);
            row.add(b, 0.375);
            row.add(m.from(m.faces.prev(h)), 0.125);
            row.add(m.from(m.faces.prev(t)), 0.125);
        }
    }
}

/// The refined position of vertex `v` under Loop's vertex rule, as a stencil over the mesh
/// vertices (the rule [`Scheme::refine`] applies, for adaptive refinement).
pub fn vertex_point_stencil(mesh: &PolyMesh, v: usize) -> Stencil {
    let mut row = RowBuf::default();
    vertex_mask(&mesh.view(), v, Loop::vertex_beta, 0.125, &mut row);
    row.take_stencil()
}

/// The new point of edge `e` under Loop's edge rule, as a stencil over the mesh vertices.
pub fn edge_point_stencil(mesh: &PolyMesh, e: usize) -> Stencil {
    let mut row = RowBuf::default();
    edge_mask(&mesh.view(), e, &mut row);
    row.take_stencil()
}

/// The limit position of vertex `v` ([`Scheme::limit_stencils`] for one vertex).
pub fn limit_point_stencil(mesh: &PolyMesh, v: usize) -> Stencil {
    let mut row = RowBuf::default();
    vertex_mask(&mesh.view(), v, Loop::limit_chi, 1.0 / 6.0, &mut row);
    row.take_stencil()
}

/// Child points (or parent half-edges) per parallel task.
const BLOCK: usize = 4096;

/// Child face of the corner where parent half-edge `h` starts: `4f + i` for `h = 3f + i`.
#[inline]
fn corner_face(h: u32) -> u32 {
    h + h / 3
}

/// Child corners of one step from the parent's arrays: parent triangle `f = (a, b, c)` becomes
/// `(a, ab, ca)`, `(b, bc, ab)`, `(c, ca, bc)`, `(ab, bc, ca)`.
fn child_corners(corners: &[u32], he_edge: &[u32], nv: usize) -> Vec<u32> {
    let nf = corners.len() / 3;
    let nv = nv as u32;
    let mut child = crate::buffers::zeroed(12 * nf, 0u32);
    child
        .par_chunks_mut(12 * BLOCK)
        .enumerate()
        .for_each(|(c, chunk)| {
            for (k, out) in chunk.chunks_exact_mut(12).enumerate() {
                let h0 = 3 * (c * BLOCK + k);
                let [a, b, cc] = [corners[h0], corners[h0 + 1], corners[h0 + 2]];
                let ab = nv + he_edge[h0];
                let bc = nv + he_edge[h0 + 1];
                let ca = nv + he_edge[h0 + 2];
                out.copy_from_slice(&[a, ab, ca, b, bc, ab, cc, ca, bc, ab, bc, ca]);
            }
        });
    child
}

impl Loop {
    /// The refinement stencils of one step (child vertex `v < V` from parent vertex `v`, then
    /// one edge point per parent edge), built in parallel without per-row allocation.
    ///
    /// # Errors
    /// [`Error::Unsupported`] for a face that is not a triangle.
    pub fn stencils(mesh: &PolyMesh) -> Result<StencilTable> {
        check_triangles(mesh)?;
        let (nv, ne) = (mesh.num_vertices(), mesh.num_edges());
        let m = mesh.view();
        Ok(StencilTable::build_par(nv, nv + ne, 6, |rows, t| {
            let mut row = RowBuf::default();
            for r in rows {
                if r < nv {
                    vertex_mask(&m, r, Self::vertex_beta, 0.125, &mut row);
                } else {
                    edge_mask(&m, r - nv, &mut row);
                }
                row.flush_into(t);
            }
        }))
    }

    /// The child points of one step computed directly by the rules (no table), in parallel, for
    /// any per-point data (`src` has one entry per parent vertex). Row `i` equals row `i` of
    /// [`Loop::stencils`] applied to `src` up to rounding.
    ///
    /// # Errors
    /// [`Error::Unsupported`] for a face that is not a triangle.
    ///
    /// # Panics
    /// Panics when `src` has fewer entries than the mesh has vertices.
    pub fn refine_points<const D: usize>(
        mesh: &PolyMesh,
        src: &[[f64; D]],
    ) -> Result<Vec<[f64; D]>> {
        check_triangles(mesh)?;
        let (nv, ne) = (mesh.num_vertices(), mesh.num_edges());
        assert!(src.len() >= nv, "one point per parent vertex is needed");
        let m = mesh.view();
        let mut out = crate::buffers::zeroed(nv + ne, [0.0; D]);
        out.par_chunks_mut(BLOCK)
            .enumerate()
            .for_each(|(c, chunk)| {
                for (k, o) in chunk.iter_mut().enumerate() {
                    let i = c * BLOCK + k;
                    let mut acc = Accumulator::new(src);
                    if i < nv {
                        vertex_mask(&m, i, Self::vertex_beta, 0.125, &mut acc);
                    } else {
                        edge_mask(&m, i - nv, &mut acc);
                    }
                    *o = acc.value();
                }
            });
        Ok(out)
    }

    /// The child net of one step with the given child points (from [`Loop::refine_points`] or
    /// [`Loop::stencils`]); its connectivity is derived from the parent's without search: the
    /// same connectivity, edge numbering and vertex half-edges as [`PolyMesh::from_refinement`]
    /// would build.
    ///
    /// # Errors
    /// [`Error::Unsupported`] for a face that is not a triangle.
    ///
    /// # Panics
    /// Panics when `positions` does not have one point per child vertex.
    pub fn child_mesh(mesh: &PolyMesh, positions: Vec<Point>) -> Result<PolyMesh> {
        check_triangles(mesh)?;
        let (nv, ne) = (mesh.num_vertices(), mesh.num_edges());
        assert_eq!(positions.len(), nv + ne, "one point per child vertex");
        let topo = Self::child_halfedges(mesh);
        let m = mesh.view();
        let corners = child_corners(m.corners, m.he_edge, nv);
        Ok(PolyMesh::from_trusted_uniform(
            positions,
            3,
            corners,
            Some(topo),
        ))
    }

    /// Half-edge topology of the child net. Child face `4f + i` (`i < 3`) is the corner
    /// triangle at the start of parent half-edge `h = 3f + i`; its sides are `3(4f + i) + k`:
    /// `k = 0` from the vertex along `h`, `1` across the parent face, `2` back along `prev(h)`.
    /// The middle face `4f + 3` has side `k` from the point of edge `3f + k` to the next. Twins
    /// follow: side 0 of `h` pairs with side 2 at `next(twin h)`, side 1 with a side of the
    /// middle face.
    fn child_halfedges(mesh: &PolyMesh) -> Topology {
        let m = mesh.view();
        let (nv, ne, nf) = (mesh.num_vertices(), mesh.num_edges(), mesh.num_faces());
        let twin: Vec<u32> = (0..12 * nf)
            .into_par_iter()
            .with_min_len(12 * BLOCK)
            .map(|c| {
                let f = (c / 12) as u32;
                let r = (c % 12) as u32;
                if r >= 9 {
                    // Middle face side k: pairs with side 1 of corner face k + 1.
                    let k = r - 9;
                    return 12 * f + 3 * ((k + 1) % 3) + 1;
                }
                let (i, side) = (r / 3, r % 3);
                let h = 3 * f + i;
                match side {
                    0 => match m.twin(h) {
                        NONE => NONE,
                        t => 3 * corner_face(m.faces.next(t)) + 2,
                    },
                    1 => 12 * f + 9 + (i + 2) % 3,
                    _ => match m.twin(m.faces.prev(h)) {
                        NONE => NONE,
                        t => 3 * corner_face(t),
                    },
                }
            })
            .collect();
        let (he_edge, edge_he) = number_edges(&twin);
        // Vertex half-edges by the rule of the generic build: the boundary outgoing half-edge,
        // else the smallest outgoing one.
        let vert_he = (0..nv + ne)
            .into_par_iter()
            .with_min_len(BLOCK)
            .map(|i| {
                if i < nv {
                    return 3 * corner_face(m.vert_he[i]);
                }
                let h = m.edge_he[i - nv];
                let side = |h: u32| {
                    let f = h / 3;
                    (3 * corner_face(h) + 1)
                        .min(12 * f + 9 + h % 3)
                        .min(3 * corner_face(m.faces.next(h)) + 2)
                };
                let last = 3 * corner_face(m.faces.next(h)) + 2;
                match m.twin(h) {
                    NONE => last,
                    t => side(h).min(side(t)),
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

    /// `levels` steps of one-shot refinement: the refined net only, points from the direct
    /// kernel ([`Loop::refine_points`]), connectivity from the parent's; no stencil table, each
    /// parent dropped as soon as its child exists, and the last level's half-edges built only
    /// on first use (see [`crate::schemes::CatmullClark::refine_uniform`]).
    ///
    /// # Errors
    /// [`Error::Unsupported`] for a face that is not a triangle; when a level would exceed
    /// fairsub's 32-bit indices.
    pub fn refine_uniform(
        mesh: &PolyMesh,
        levels: usize,
        mut progress: impl FnMut(usize),
    ) -> Result<PolyMesh> {
        check_triangles(mesh)?;
        use super::common::{OneShotStep, one_shot_levels};
        let check = |p: &PolyMesh| {
            check_child_size(
                crate::schemes::registry::ids::LOOP.name(),
                p.num_vertices() + p.num_edges(),
            )?;
            check_child_size(
                crate::schemes::registry::ids::LOOP.name(),
                4 * p.num_halfedges() + 1,
            )
        };
        one_shot_levels(mesh, levels, &mut progress, check, |s| match s {
            OneShotStep::Middle(p) => Self::child_mesh(p, Self::refine_points(p, p.positions())?),
            OneShotStep::OnlyStep(p) => {
                let positions = Self::refine_points(p, p.positions())?;
                let m = p.view();
                let corners = child_corners(m.corners, m.he_edge, p.num_vertices());
                Ok(PolyMesh::from_trusted_uniform(positions, 3, corners, None))
            }
            OneShotStep::Last(p) => {
                // Keep only what the child faces need from the parent.
                let positions = Self::refine_points(&p, p.positions())?;
                let nv = p.num_vertices();
                let MeshParts { corners, topo, .. } = p.into_parts();
                let Topology { he_edge, .. } =
                    topo.expect("an intermediate level has its topology");
                let child = child_corners(&corners, &he_edge, nv);
                drop((corners, he_edge));
                Ok(PolyMesh::from_trusted_uniform(positions, 3, child, None))
            }
        })
    }
}

impl Scheme for Loop {
    fn step_size(&self, s: &crate::schemes::growth::NetSize) -> crate::schemes::growth::NetSize {
        crate::schemes::growth::triangle(s)
    }

    fn name(&self) -> &'static str {
        crate::schemes::registry::ids::LOOP.name()
    }

    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        let (nv, ne) = (mesh.num_vertices(), mesh.num_edges());
        check_child_size(self.name(), nv + ne)?;
        let stencils = Self::stencils(mesh)?;
        let mesh = Self::child_mesh(mesh, stencils.apply(mesh.positions()))?;
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

    /// Limit positions: interior `(1 - n chi) v + chi sum p_i` ([`Loop::limit_chi`]), boundary
    /// `2/3 v + 1/6 (a + b)` (the cubic B-spline curve at its knot), corner `v`.
    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        check_triangles(mesh)?;
        let nv = mesh.num_vertices();
        let m = mesh.view();
        Ok(StencilTable::build_par(nv, nv, 7, |rows, t| {
            let mut row = RowBuf::default();
            for v in rows {
                vertex_mask(&m, v, Self::limit_chi, 1.0 / 6.0, &mut row);
                row.flush_into(t);
            }
        }))
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

    #[test]
    fn direct_child_and_one_shot_levels_equal_the_generic_path() {
        let dist = |a: &[Point], b: &[Point]| {
            a.iter()
                .zip(b)
                .map(|(p, q)| crate::geom::dist(*p, *q))
                .fold(0.0, f64::max)
        };
        let nets: Vec<(String, PolyMesh)> = crate::gallery::all()
            .into_iter()
            .filter(|(_, m)| m.is_all_triangles())
            .collect();
        assert!(nets.len() >= 4);
        for (name, mesh) in nets {
            let mut m = mesh.clone();
            for level in 0..2 {
                let what = format!("{name} level {level}");
                let st = Loop::stencils(&m).unwrap();
                let pts = st.apply(m.positions());
                let direct = Loop::child_mesh(&m, pts.clone()).unwrap();
                let (fs, c) = (direct.face_starts().to_vec(), direct.corners().to_vec());
                let generic = PolyMesh::from_refinement(pts.clone(), fs, c).unwrap();
                crate::mesh::assert_same_topology(&direct, &generic, &what);
                let fused = Loop::refine_points(&m, m.positions()).unwrap();
                assert!(dist(&fused, &pts) < 1e-13, "{what}");
                m = direct;
            }
            for levels in 0..=3 {
                let what = format!("{name}, {levels} levels");
                let fast = Loop::refine_uniform(&mesh, levels, |_| {}).unwrap();
                let mut slow = mesh.clone();
                for _ in 0..levels {
                    slow = Loop.refine(&slow).unwrap().mesh;
                }
                assert!(dist(fast.positions(), slow.positions()) < 1e-12, "{what}");
                crate::mesh::assert_same_topology(&fast, &slow, &what);
            }
        }
    }
}
