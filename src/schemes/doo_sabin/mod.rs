//! Doo-Sabin subdivision and its Catmull-Clark variant DS^CC, with boundaries, as stencils.
//!
//! Both are dual (vertex-splitting) schemes that generalise uniform bi-2 B-spline refinement to
//! nets of any polygons (D. Doo, M. Sabin, *Behaviour of recursive division surfaces near
//! extraordinary points*, CAD 10(6), 1978). They share one topological step and differ only in
//! the rule for the new point at a face corner, a circulant rule on the face's vertices:
//!
//! - Doo-Sabin ([`DooSabin`]): for corner `i` of an n-gon `v_0 .. v_{n-1}`,
//!   `sum_j w_ij v_j` with `w_ii = 1/4 + 5/(4n)`, `w_ij = (3 + 2 cos(2 pi (i-j)/n)) / (4n)`. Its
//!   n-gon block has the eigenvalues `1, 1/2, 1/2, 1/4, ..., 1/4`.
//! - DS^CC ([`DooSabinCc`]), the rule Catmull and Clark suggested (reported by Doo and Sabin in
//!   1978; the bi-2 paper of this project uses it to pre-process coarse nets): the mean of the
//!   vertex, the face centroid and the midpoints of the two face edges at the vertex,
//!   `(v_i + c + (v_i + v_{i-1})/2 + (v_i + v_{i+1})/2) / 4`. Eigenvalues
//!   `1, 1/2 + cos(2 pi k / n) / 4`.
//!
//! On a quad both give the bi-2 mask `9/16, 3/16, 3/16, 1/16`.
//!
//! # Boundary rules (fairsub's choice)
//!
//! The boundary polygon of the net is refined by Chaikin's corner cutting, so the boundary of the
//! limit surface is the uniform quadratic B-spline curve of the boundary polygon:
//!
//! - each boundary edge `a -> b` (in the direction of its half-edge) gets two child points,
//!   `3/4 a + 1/4 b` and `1/4 a + 3/4 b`;
//! - the E-face of a boundary edge is the quad of the two face-corner points of its face and its
//!   two edge points;
//! - the V-face of a boundary vertex is the polygon of the edge point on its outgoing boundary
//!   edge, its face-corner points counter-clockwise, and the edge point on its incoming boundary
//!   edge;
//! - a corner, a boundary vertex with a single face (valence 2), is also kept as a child point
//!   that stays put and closes its V-face to a quad (edge point, face-corner point, edge point,
//!   corner). The boundary curve is then the quadratic B-spline of the boundary polygon with every
//!   corner doubled: it interpolates the corner with a tangent break, as the Loop and
//!   Catmull-Clark corner rules (OpenSubdiv's `VTX_BOUNDARY_EDGE_AND_CORNER`) do. A boundary
//!   vertex that the net's extras tag as sharp is kept the same way whatever its number of
//!   faces (its V-face gets the kept corner as one more vertex): these are the crease ends and
//!   junctions of a net cut along its creases ([`sharp`], [`sharp::is_kept_corner`]).
//!
//! Why these rules: on a rectangular quad net they are exactly tensor-product bi-2 B-spline
//! refinement of the net whose boundary layer of points is doubled (a phantom copy of every
//! boundary point, four copies of a corner): the phantom face on a boundary edge is degenerate and
//! its Doo-Sabin corner points are the Chaikin points, so the scheme stays a uniform spline up to
//! and including the corners, and every other rule is the plain Doo-Sabin rule. Nasri's boundary
//! rules (A. Nasri, *Polyhedral subdivision methods for free-form surfaces*, ACM TOG 6(1), 1987)
//! have the same aim, a limit boundary that is the quadratic B-spline of the boundary polygon; we
//! did not have Nasri's text to hand, so we do not claim to reproduce his masks, and the rules
//! here are our own documented construction (CGAL's `DooSabin_mask_3` and OpenSubdiv have no
//! Doo-Sabin boundary rules to compare with). Without
//! the kept corner the V-face of a corner would be a triangle that survives at every level, and
//! the bi-2 paper of this project blames exactly such 3-sided faces for Doo-Sabin's worst
//! highlight-line oscillations. Near boundary vertices with other than two faces the V-face is a
//! `(k + 2)`-gon touching the boundary; its smoothness is not analysed here.
//!
//! # Boundary modes (fairsub's translation of OpenSubdiv's, not published)
//!
//! OpenSubdiv's `VtxBoundaryInterpolation` names three modes for the primal schemes; the net's
//! `interpolateboundary` option (or `--boundary`, [`boundary_mode`]) picks their dual
//! counterparts, which are our own:
//!
//! - `edge-and-corner` (the default): the rules above, corners of one face kept.
//! - `edge-only`: OpenSubdiv's boundary vertex with one face follows the boundary crease
//!   instead of staying put. Here: no kept corner at a vertex with one face (vertices the
//!   net's extras tag as sharp are still kept); the boundary polygon is refined by Chaikin's
//!   rule through the corner like everywhere else, so the limit boundary is the quadratic
//!   B-spline of the boundary polygon without doubled corners (it cuts the corner), and the
//!   corner's V-face is a triangle that leaves the boundary after one more step and shrinks to
//!   an interior point (an extraordinary 3-gon of the surface).
//! - `none`: OpenSubdiv makes the faces at the boundary holes, refined for support and not
//!   written, so the surface is what the interior rules alone determine. Here: a point is
//!   *rule-free* when no boundary rule (a Chaikin point, a kept corner, a phantom of a
//!   boundary vertex's patch) enters its computation; what is written is what is made of
//!   rule-free points only. A refinement step makes the corner points only (all rule-free,
//!   the corner rule reads no boundary point rule) and the F-faces, the E-faces of interior
//!   edges and the V-faces of interior vertices: the boundary strip (Chaikin points, kept
//!   corners, E-faces of boundary edges, V-faces of boundary vertices) is not made, and the
//!   next step refines the trimmed net the same way. The surface is the union of the patches
//!   of the input's interior vertices (on a regular region; in general the part of the
//!   edge-and-corner surface with rule-free control points), and the trimmed net at any level
//!   describes the same surface under `none`. Limit points (`--limit`) are refused on a net
//!   with a boundary: a boundary vertex's patch is not part of the surface. The patch output
//!   writes the rule-free patches (`surface`).
//!
//! An interior vertex of valence 2 (two faces sharing two edges) would give a 2-sided V-face:
//! that V-face is omitted and its two neighbouring E-faces share the edge instead.
//!
//! # Layout of one step
//!
//! Child points: `h` for face corner (half-edge) `h`, `0 <= h < H`; then two per boundary edge,
//! `H + 2b` (near `a`) and `H + 2b + 1` (near `b`) for the `b`-th boundary edge in edge order;
//! then the kept corners in vertex order. Child faces: the F-face of parent face `f` (index `f`,
//! its corners are the points `h` of `f` in order), the E-face of every edge in edge order, the
//! V-face of every vertex in vertex order (omitted for interior vertices of valence 2). This is
//! the mesh layer's dual split numbered by kind ([`crate::mesh::dual_split::DualOrder::ByKind`]);
//! this module gives its points their stencils.
//!
//! # Limit points
//!
//! A face-corner rule whose rows and columns sum to one keeps the centroid of every F-face, and
//! F-faces shrink to a point of the limit surface: the limit point of a face is its centroid
//! ([`face_limit_stencils`]). So the limit point of an interior vertex is the centroid of its
//! V-face (for a regular quad net the bi-2 mask `(1, 6, 1) x (1, 6, 1) / 64`); of a boundary vertex
//! with neighbours `u`, `w` on the boundary, the boundary curve's point `(u + 6v + w) / 8`; of a
//! corner, the corner.

pub mod descriptor;
pub mod entry;
pub mod fourier;
pub mod local;
pub mod sharp;
pub mod surface;
pub use descriptor::{DESCRIPTOR, DESCRIPTOR_CC};

use crate::error::{Error, Result};
use crate::mesh::dual_split::{DualFeatures, DualOrder, DualPoint, VFaces, dual_split};
use crate::mesh::tags::{BoundaryInterpolation, SubdOptions};
use crate::mesh::{Extras, NONE, PolyMesh};
use crate::schemes::sdc::crease::INFINITE;
use crate::stencil::{Stencil, StencilTable};

use super::common::{RowBuf, check_child_size, cos_2pi};
use super::{Refinement, Scheme, finish_refinement};

/// Doo-Sabin subdivision (scheme name `doo-sabin`). See the [module](self) documentation for
/// the rules, the boundary treatment and the layout of the child net.
#[derive(Debug, Clone, Copy, Default)]
pub struct DooSabin;

/// DS^CC (scheme name `doo-sabin-cc`): Doo-Sabin's topology with Catmull and Clark's corner
/// rule `(v + c + m_prev + m_next) / 4`. See the [module](self) documentation.
#[derive(Debug, Clone, Copy, Default)]
pub struct DooSabinCc;

impl DooSabin {
    /// The first row of the circulant n-gon block (`n >= 3`): entry `d` is the weight of vertex
    /// `i + d` (mod n) in the new point of corner `i`: `1/4 + 5/(4n)` for `d = 0`, else
    /// `(3 + 2 cos(2 pi d / n)) / (4n)`.
    pub fn weights(n: usize) -> Vec<f64> {
        let nf = n as f64;
        (0..n)
            .map(|d| {
                if d == 0 {
                    0.25 + 1.25 / nf
                } else {
                    (3.0 + 2.0 * cos_2pi(d as i64, n as i64)) / (4.0 * nf)
                }
            })
            .collect()
    }
}

impl DooSabinCc {
    /// The first row of the circulant n-gon block (`n >= 3`): the vertex itself
    /// `1/2 + 1/(4n)`, its two face neighbours `1/8 + 1/(4n)`, every other vertex `1/(4n)`.
    pub fn weights(n: usize) -> Vec<f64> {
        let q = 0.25 / n as f64;
        (0..n)
            .map(|d| match d {
                0 => 0.5 + q,
                _ if d == 1 || d + 1 == n => 0.125 + q,
                _ => q,
            })
            .collect()
    }
}

impl Scheme for DooSabin {
    fn step_size(&self, s: &crate::schemes::growth::NetSize) -> crate::schemes::growth::NetSize {
        crate::schemes::growth::dual(s)
    }

    fn name(&self) -> &'static str {
        crate::schemes::options::ids::DOO_SABIN.name()
    }

    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        refine_dual(mesh, self.name(), Self::weights)
    }

    /// Limit points of the net's vertices: see the [module](self) documentation.
    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        dual_limit_stencils(mesh, self.name(), Self::weights)
    }
}

impl Scheme for DooSabinCc {
    fn step_size(&self, s: &crate::schemes::growth::NetSize) -> crate::schemes::growth::NetSize {
        crate::schemes::growth::dual(s)
    }

    fn name(&self) -> &'static str {
        crate::schemes::options::ids::DOO_SABIN_CC.name()
    }

    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        refine_dual(mesh, self.name(), Self::weights)
    }

    /// Limit points of the net's vertices: see the [module](self) documentation.
    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        dual_limit_stencils(mesh, self.name(), Self::weights)
    }
}

/// Limit points of the faces of a net under [`DooSabin`] or [`DooSabinCc`] (row `f` for face
/// `f`): the face centroids, which both corner rules keep at every level while the face shrinks
/// to a point of the limit surface.
pub fn face_limit_stencils(mesh: &PolyMesh) -> StencilTable {
    let nf = mesh.num_faces();
    let mut table = StencilTable::with_capacity(mesh.num_vertices(), nf, 4);
    let mut row = RowBuf::default();
    for f in 0..nf {
        let w = 1.0 / mesh.face_size(f) as f64;
        for &v in mesh.face(f) {
            row.add(v, w);
        }
        row.flush_into(&mut table);
    }
    table
}

/// Weights `(w_a, w_b)` of the two Chaikin points of a boundary edge `a -> b`: the point near
/// `a` first, then the point near `b` (see the module's boundary rules).
pub const CHAIKIN: [(f64, f64); 2] = [(0.75, 0.25), (0.25, 0.75)];

/// The new point of face corner `h` (a half-edge: the corner at its start vertex in its face)
/// under the circulant corner rule `rule` ([`DooSabin::weights`] or [`DooSabinCc::weights`]),
/// as a stencil over the mesh vertices. The same rule [`Scheme::refine`] applies, for adaptive
/// refinement.
pub fn corner_point_stencil(mesh: &PolyMesh, h: u32, rule: fn(usize) -> Vec<f64>) -> Stencil {
    let mut rules = RuleCache::new(rule);
    let mut row = RowBuf::default();
    add_corner_point(mesh, &mut rules, h, 1.0, &mut row);
    row.take_stencil()
}

/// The Chaikin point of boundary half-edge `h` (`a -> b`) near `a` (`near_to = false`) or near
/// `b` (`near_to = true`), as a stencil: the boundary rule of [`Scheme::refine`].
pub fn boundary_edge_point_stencil(mesh: &PolyMesh, h: u32, near_to: bool) -> Stencil {
    let (wa, wb) = CHAIKIN[near_to as usize];
    let mut s = Stencil::new();
    s.add(mesh.he_from(h) as usize, wa)
        .add(mesh.he_to(h) as usize, wb);
    s.merged()
}

/// The circulant first rows of a corner rule, computed once per face size.
struct RuleCache {
    rule: fn(usize) -> Vec<f64>,
    rows: Vec<Vec<f64>>,
}

impl RuleCache {
    fn new(rule: fn(usize) -> Vec<f64>) -> Self {
        RuleCache {
            rule,
            rows: Vec::new(),
        }
    }

    fn get(&mut self, n: usize) -> &[f64] {
        if self.rows.len() <= n {
            self.rows.resize(n + 1, Vec::new());
        }
        if self.rows[n].is_empty() {
            self.rows[n] = (self.rule)(n);
        }
        &self.rows[n]
    }
}

/// Adds the new point of corner `h` (a half-edge) under the circulant corner rule.
fn add_corner_point(mesh: &PolyMesh, rules: &mut RuleCache, h: u32, scale: f64, row: &mut RowBuf) {
    let f = mesh.he_face(h) as usize;
    let verts = mesh.face(f);
    let n = verts.len();
    let i = (h - mesh.face_halfedge(f)) as usize;
    let w = rules.get(n);
    for (d, &wd) in w.iter().enumerate() {
        row.add(verts[(i + d) % n], scale * wd);
    }
}

/// One step of a dual scheme: Doo-Sabin topology with the given circulant corner rule
/// (`rule(n)` is the first row of the n-gon block). Boundary and corner points follow the
/// module's boundary rules whatever the corner rule.
pub(crate) fn refine_dual(
    mesh: &PolyMesh,
    name: &str,
    rule: fn(usize) -> Vec<f64>,
) -> Result<Refinement> {
    let mut rules = RuleCache::new(rule);
    refine_dual_with(mesh, name, |m, h, row| {
        add_corner_point(m, &mut rules, h, 1.0, row)
    })
}

/// One step of a dual scheme with Doo-Sabin topology whose corner rule is any stencil:
/// `corner_rule(mesh, h, row)` adds the weights of the new point of face corner `h` (a half-edge) to
/// `row`. The rule may reach beyond the face (the point-augmented bi-2 rules read the quads
/// across the facet's edges). Boundary points, kept corners and the child layout are those of
/// [`DooSabin`] (see the module documentation).
pub(crate) fn refine_dual_with(
    mesh: &PolyMesh,
    name: &str,
    mut corner_rule: impl FnMut(&PolyMesh, u32, &mut RowBuf),
) -> Result<Refinement> {
    // (at most a corner point per half-edge, two Chaikin points per edge, a kept point per
    // vertex)
    check_child_size(
        name,
        mesh.num_halfedges() + 2 * mesh.num_edges() + mesh.num_vertices(),
    )?;
    if let Some(c) = sharp::step::Creases::of(mesh, name)? {
        // fairsub's crease construction ([`sharp`]), laid out as documented there
        let mut row = RowBuf::default();
        let mut corner = |m: &PolyMesh, h: u32| {
            corner_rule(m, h, &mut row);
            row.take_stencil()
        };
        return sharp::levels::refine_creased(mesh, &c, &mut corner);
    }
    // Boundary `none`: the boundary strip (its Chaikin points, kept corners, boundary E-faces
    // and V-faces) is not made; see the module's boundary modes.
    let trim = boundary_mode(mesh) == BoundaryInterpolation::None;
    let all: Vec<u32> = (0..mesh.num_faces() as u32).collect();
    let split = dual_split(
        mesh,
        all,
        &mut PlainFeatures { mesh, trim },
        DualOrder::ByKind,
    );

    // Stencils, in child point order.
    let mut table = StencilTable::with_capacity(mesh.num_vertices(), split.points.len(), 4);
    let mut row = RowBuf::default();
    for &p in &split.points {
        match p {
            DualPoint::Corner(h) => corner_rule(mesh, h, &mut row),
            DualPoint::Chaikin { edge, end } => {
                let [a, b] = mesh.edge(edge as usize);
                let (wa, wb) = CHAIKIN[end as usize];
                row.add(a, wa);
                row.add(b, wb);
            }
            DualPoint::Kept(v) => row.add(v, 1.0),
        }
        row.flush_into(&mut table);
    }
    let kept = split.kept;
    let (face_start, corners) = (split.face_start, split.corners);
    let mut r = finish_refinement(mesh, table, face_start, corners)?;
    // The child keeps the boundary mode, and a kept corner's child point stays kept.
    if let Some(ex) = mesh.extras() {
        let kept: Vec<(u32, f32)> = (0..mesh.num_vertices())
            .filter(|&v| kept[v] != NONE && sharp::is_tagged_corner(mesh, v))
            .map(|v| (kept[v], INFINITE))
            .collect();
        if !kept.is_empty() || ex.options.boundary.is_some() {
            let extras = Extras {
                sharp_vertices: kept,
                options: SubdOptions {
                    boundary: ex.options.boundary,
                    ..SubdOptions::default()
                },
                sharpened: true,
                ..Extras::default()
            };
            r.mesh = r.mesh.with_extras(Some(extras));
        }
    }
    Ok(r)
}

/// The features of a whole net's step without creases: Chaikin points on the boundary edges,
/// kept points at the kept corners, a V-face at every vertex (one sector); with the boundary
/// mode `none` (`trim`) no boundary strip.
struct PlainFeatures<'a> {
    mesh: &'a PolyMesh,
    trim: bool,
}

impl DualFeatures for PlainFeatures<'_> {
    fn chaikin(&mut self, e: usize) -> bool {
        !self.trim && self.mesh.is_boundary_edge(e)
    }

    fn kept(&mut self, v: usize) -> bool {
        !self.trim && sharp::is_kept_corner(self.mesh, v)
    }

    fn v_faces(&mut self, v: usize, _: &[u32]) -> VFaces {
        if self.trim && self.mesh.is_boundary_vertex(v) {
            VFaces::None
        } else {
            VFaces::Whole
        }
    }
}

/// The boundary mode a dual scheme refines `mesh` with: the net's `interpolateboundary`
/// option (a command-line `--boundary` is put there by the front end), edge-and-corner when it
/// says nothing. See the module's boundary modes.
pub fn boundary_mode(mesh: &PolyMesh) -> BoundaryInterpolation {
    mesh.extras()
        .map_or(BoundaryInterpolation::EdgeAndCorner, |e| {
            e.options.boundary()
        })
}

/// Refuses limit points under the boundary mode `none` when the net has a boundary: its
/// boundary vertices' patches are not part of the surface, so they have no limit point on it.
///
/// # Errors
/// [`Error::Unsupported`] naming the first boundary vertex.
pub(crate) fn refuse_limit_without_boundary(mesh: &PolyMesh, name: &str) -> Result<()> {
    if boundary_mode(mesh) != BoundaryInterpolation::None {
        return Ok(());
    }
    match (0..mesh.num_vertices()).find(|&v| mesh.is_boundary_vertex(v)) {
        Some(v) => Err(Error::Unsupported(format!(
            "vertex {v} is on the boundary and the boundary mode is none: {name}'s surface \
             leaves out the patches of boundary vertices, so the vertex has no limit point on \
             it (write the refined net without --limit, or choose --boundary edge-only or \
             edge-and-corner)"
        ))),
        None => Ok(()),
    }
}

/// For a corner rule that reads beyond its face (PGS reads the quads across a facet's edges):
/// refuses a step under the boundary mode `none` on a refined level (one whose boundary is
/// where the boundary strip was left out) when a face that is not a quad has a boundary edge.
/// There the full refinement's rule reads the left-out strip, so the face's new corners are not
/// rule-free, and the trimmed net has no faces to read in their place.
///
/// # Errors
/// [`Error::Unsupported`] naming the face.
pub(crate) fn refuse_reaching_rule_at_trimmed_boundary(mesh: &PolyMesh, name: &str) -> Result<()> {
    let refined = mesh.extras().is_some_and(|e| e.sharpened);
    if boundary_mode(mesh) != BoundaryInterpolation::None || !refined {
        return Ok(());
    }
    let at_boundary = |f: usize| {
        let h0 = mesh.face_halfedge(f);
        (h0..h0 + mesh.face_size(f) as u32).any(|h| mesh.he_twin(h).is_none())
    };
    match (0..mesh.num_faces()).find(|&f| mesh.face_size(f) != 4 && at_boundary(f)) {
        Some(f) => Err(Error::Unsupported(format!(
            "face {f} ({} sides) of the refined net lies on the boundary that the boundary \
             mode none left after the strip was dropped; {name}'s rule for it reads the quads \
             across its edges, which none leaves out (not built: refine with one level fewer, \
             use {} or {}, whose rules read the face alone, or --rings, whose patches take \
             none here)",
            mesh.face_size(f),
            crate::schemes::options::ids::DOO_SABIN,
            crate::schemes::options::ids::DOO_SABIN_CC
        ))),
        None => Ok(()),
    }
}

/// Limit points of the vertices of a net under a dual scheme with the given corner rule.
fn dual_limit_stencils(
    mesh: &PolyMesh,
    name: &str,
    rule: fn(usize) -> Vec<f64>,
) -> Result<StencilTable> {
    refuse_limit_without_boundary(mesh, name)?;
    let nv = mesh.num_vertices();
    let mut rules = RuleCache::new(rule);
    let mut table = StencilTable::with_capacity(nv, nv, 9);
    let mut row = RowBuf::default();
    for v in 0..nv {
        let vi = v as u32;
        if !mesh.is_boundary_vertex(v) {
            let k = mesh.outgoing(v).count();
            if k < 3 {
                return Err(Error::Unsupported(format!(
                    "vertex {v} is an interior vertex of valence 2, which has no closed-form \
                     {name} limit point; refine the net once (the refined net has no such vertex)"
                )));
            }
            // Centroid of the V-face: the mean of the new points of v's corners.
            for h in mesh.outgoing(v) {
                add_corner_point(mesh, &mut rules, h, 1.0 / k as f64, &mut row);
            }
        } else if sharp::is_kept_corner(mesh, v) {
            row.add(vi, 1.0);
        } else {
            let (u, w) = mesh.boundary_neighbors(v);
            row.add(vi, 0.75);
            row.add(u, 0.125);
            row.add(w, 0.125);
        }
        row.flush_into(&mut table);
    }
    Ok(table)
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn quad_weights_are_the_bi2_mask() {
        let expect = [9.0 / 16.0, 3.0 / 16.0, 1.0 / 16.0, 3.0 / 16.0];
        assert_eq!(DooSabin::weights(4), expect);
        assert_eq!(DooSabinCc::weights(4), expect);
        for n in 3..12 {
            for w in [DooSabin::weights(n), DooSabinCc::weights(n)] {
                assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-15);
            }
        }
        // DS^CC for a triangle: both other vertices are face neighbours.
        let t = DooSabinCc::weights(3);
        assert_eq!(t[1], t[2]);
        assert!((t[0] - (0.5 + 1.0 / 12.0)).abs() < 1e-16);
    }

    #[crate::unit::test]
    fn interior_valence_two_vertices_lose_their_v_face() {
        // A pillow of two quads glued along all four edges: every vertex is interior of
        // valence 2. One step drops the four 2-sided V-faces and gives a cube.
        let pos = vec![
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [2.0, 0.0, 0.0],
            [1.0, -1.0, 0.0],
        ];
        let m = PolyMesh::new(pos, &[vec![0, 3, 2, 1], vec![0, 1, 2, 3]]).unwrap();
        let r = DooSabin.refine(&m).unwrap();
        let c = &r.mesh;
        assert_eq!((c.num_vertices(), c.num_edges(), c.num_faces()), (8, 12, 6));
        assert!(c.is_all_quads() && c.boundary_loops().is_empty());
        assert!((0..8).all(|v| c.valence(v) == 3));
        let msg = DooSabin.limit_stencils(&m).unwrap_err().to_string();
        assert!(
            msg.contains("vertex 0") && msg.contains("valence 2"),
            "{msg}"
        );
        assert!(DooSabin.limit_stencils(c).is_ok());
    }
}
