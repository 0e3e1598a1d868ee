//! Catmull-Clark subdivision as OpenSubdiv's Catmark scheme: boundaries, sharp features,
//! non-manifold nets, limit positions and limit normals.
//!
//! Plain rules (no sharp feature, boundary interpolation edge-and-corner): face point =
//! centroid; interior edge point = (a + b + F1 + F2) / 4; interior vertex of valence n:
//! (n - 2)/n v + 1/n^2 sum(edge neighbours) + 1/n^2 sum(face points); boundary edges and
//! vertices follow the cubic B-spline curve rules of the boundary polygon ((a + b)/2 and
//! (a + 6 v + b)/8); a boundary vertex with a single incident face (valence 2) is a corner and
//! stays put.
//!
//! Sharp features (crease and corner sharpness, semi-sharp values decaying level by level,
//! uniform and Chaikin creasing, the boundary options, holes, non-manifold features) follow
//! OpenSubdiv's rules, written once in `crease` for Catmull-Clark and Loop as plans that
//! combine this scheme's smooth masks with crease and corner masks; the smooth-triangle option
//! changes the smooth edge mask next to triangles. Only the vertices and edges that need them
//! take those rules: the plain rules stay the hot loop.
//!
//! Child vertex order: one vertex point per parent vertex, then one edge point per parent edge
//! (edge index order), then one face point per parent face. Child face `h` is the quad of parent
//! corner (half-edge) `h`: (vertex point, edge point of the outgoing edge, face point, edge point
//! of the incoming edge), so child faces inherit the parent orientation: the mesh layer's quad
//! split ([`crate::mesh::quad_split`]), which gives the child nets (`schemes::split_child`).
//!
//! # One source of truth, two ways to apply it
//!
//! The rules are written once (`face_rule`, the edge and vertex rules of `Rules`) against
//! `CcTerms`: terms on parent vertices and on parent face points. A stencil table
//! ([`CatmullClark::stencils`]) expands each face-point term into the face's corners; the direct
//! kernel ([`CatmullClark::refine_points`]) computes the face points first and reads them back,
//! as OpenSubdiv's primvar refiner does. The child connectivity is derived from the parent's
//! combinatorially ([`CatmullClark::child_mesh`]): no search, every pass parallel. One-shot
//! refinement to several levels ([`CatmullClark::refine_uniform`]) keeps no tables, drops each
//! parent level as soon as its child exists, and does not build the last level's half-edges.

pub mod boundary_tangent;
use crate::schemes::sdc::crease;
pub mod dart;
pub mod descriptor;
pub mod entry;
mod limit;
pub mod local;
pub mod regular;
pub mod surface;
pub use descriptor::DESCRIPTOR;
pub use limit::LimitStencils;

use super::common::check_child_size;
use super::{Refinement, Scheme};
use crate::error::Result;
use crate::geom::Point;
use crate::mesh::quad_split::{QuadSplit, quad_starts};
use crate::mesh::split::UniformSplit;
use crate::mesh::tags::{SubdOptions, TriangleSubdivision};
use crate::mesh::{MeshView, NONE, PolyMesh};
use crate::stencil::{RowWriter, StencilTable, Terms, axpy};
use crease::{CREASE_EDGE, EdgePlan, Emit, Scratch, SharpLevel};
use rayon::prelude::*;
use std::f64::consts::PI;

/// Child points per parallel task.
const BLOCK: usize = 4096;

/// OpenSubdiv's options as the rules take them (see [`crate::mesh::tags`]).
pub type Opts = SubdOptions;

/// The Catmull-Clark scheme with the default options (boundary edge-and-corner, uniform
/// creasing, Catmark triangles); the net's own sharp features apply.
#[derive(Debug, Clone, Copy, Default)]
pub struct CatmullClark;

/// The Catmull-Clark scheme with OpenSubdiv's options (what `--boundary`, `--crease-method`,
/// `--smooth-triangles` and `--fvar` set).
#[derive(Debug, Clone, Copy, Default)]
pub struct Configured {
    /// The options.
    pub options: Opts,
}

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

/// OpenSubdiv's face weight of a triangle in the smooth edge mask under
/// `TriangleSubdivision::Smooth` (`CATMARK_SMOOTH_TRI_EDGE_WEIGHT`).
const SMOOTH_TRI_WEIGHT: f64 = 0.47;

/// The smooth mask of interior edge `e`, scaled: `(a + b + F1 + F2) / 4`; with smooth
/// triangles and a triangle among its two faces, face weights `w = (w1 + w2) / 2` (0.47 for a
/// triangle, 1/4 otherwise) and vertex weights `(1 - 2w) / 2`.
#[inline(always)]
fn smooth_edge(m: &MeshView<'_>, e: usize, tris: bool, scale: f64, out: &mut impl CcTerms) {
    let h = m.edge_he[e];
    let (a, b, t) = (m.from(h), m.to(h), m.twin(h));
    let (f1, f2) = (m.face(h), m.face(t));
    let (mut vw, mut fw) = (0.25, 0.25);
    if tris {
        let w = |f: u32| {
            if m.face_corners(f as usize).len() == 3 {
                SMOOTH_TRI_WEIGHT
            } else {
                0.25
            }
        };
        let (w1, w2) = (w(f1), w(f2));
        if w1 != 0.25 || w2 != 0.25 {
            fw = 0.5 * (w1 + w2);
            vw = 0.5 * (1.0 - 2.0 * fw);
        }
    }
    out.vertex(a, vw * scale);
    out.vertex(b, vw * scale);
    out.face_point(f1, fw * scale);
    out.face_point(f2, fw * scale);
}

/// The smooth mask of interior vertex `v`, scaled:
/// `(n - 2)/n v + 1/n^2 sum(edge neighbours) + 1/n^2 sum(face points)`.
#[inline(always)]
fn smooth_vertex(m: &MeshView<'_>, v: usize, scale: f64, out: &mut impl CcTerms) {
    let n = m.outgoing(v).count() as f64;
    out.vertex(v as u32, scale * (n - 2.0) / n);
    let w = scale / (n * n);
    for h in m.outgoing(v) {
        out.vertex(m.to(h), w);
        out.face_point(m.face(h), w);
    }
}

/// The rules of one step: plain, or with the sharp features of the level.
pub(crate) struct Rules<'a> {
    m: MeshView<'a>,
    sharp: Option<SharpLevel<'a>>,
    tris: bool,
}

impl<'a> Rules<'a> {
    /// The rules for `mesh` under `opts`.
    pub fn new(mesh: &'a PolyMesh, opts: &Opts) -> Rules<'a> {
        let tris =
            opts.triangles() == TriangleSubdivision::Smooth && mesh.uniform_face_size() != Some(4);
        Rules {
            m: mesh.view(),
            sharp: SharpLevel::new(mesh, opts),
            tris,
        }
    }

    /// Edge point of edge `e`: the smooth mask inside, the midpoint on the boundary; with
    /// sharp features the edge's plan.
    #[inline(always)]
    fn edge(&self, e: usize, scratch: &mut Scratch, out: &mut impl CcTerms) {
        self.edge_in::<false>(e, scratch, out)
    }

    /// Whether the level has neither sharp features nor smooth triangles: the plain rules.
    fn plain(&self) -> bool {
        self.sharp.is_none() && !self.tris
    }

    /// [`Rules::edge`]; `PLAIN` (only where [`Rules::plain`] holds) compiles the feature checks
    /// away.
    #[inline(always)]
    fn edge_in<const PLAIN: bool>(&self, e: usize, scratch: &mut Scratch, out: &mut impl CcTerms) {
        let m = &self.m;
        let (sharp, tris) = if PLAIN {
            (None, false)
        } else {
            (self.sharp.as_ref(), self.tris)
        };
        let plan = match sharp {
            Some(sl) => sl.edge_plan(e as u32, scratch),
            None if m.twin(m.edge_he[e]) == NONE => {
                // EdgePlan::Crease's terms, emitted here: passing `out` to the plan's closure
                // kept the kernel's accumulator in memory for every point (+6% instructions of
                // `--levels 3`, callgrind)
                let h = m.edge_he[e];
                out.vertex(m.from(h), CREASE_EDGE);
                out.vertex(m.to(h), CREASE_EDGE);
                return;
            }
            None => EdgePlan::Smooth,
        };
        if plan == EdgePlan::Smooth {
            return smooth_edge(m, e, tris, 1.0, out);
        }
        let h = m.edge_he[e];
        plan.emit(m.from(h), m.to(h), |t| match t {
            Emit::Smooth(s) => smooth_edge(m, e, tris, s, out),
            Emit::Vertex(u, w) => out.vertex(u, w),
        });
    }

    /// Vertex point of `v`: the smooth mask inside; `3/4 v + 1/8 (a + b)` on the boundary; a
    /// corner stays put; with sharp features the vertex's plan.
    #[inline(always)]
    fn vertex(&self, v: usize, scratch: &mut Scratch, out: &mut impl CcTerms) {
        self.vertex_in::<false>(v, scratch, out)
    }

    /// [`Rules::vertex`]; `PLAIN` as in [`Rules::edge_in`].
    #[inline(always)]
    fn vertex_in<const PLAIN: bool>(
        &self,
        v: usize,
        scratch: &mut Scratch,
        out: &mut impl CcTerms,
    ) {
        let m = &self.m;
        let sharp = if PLAIN { None } else { self.sharp.as_ref() };
        match sharp {
            Some(sl) if sl.special[v] => {
                sl.vertex_plan(v as u32, scratch)
                    .emit(v as u32, |t| match t {
                        Emit::Smooth(s) => smooth_vertex(m, v, s, out),
                        Emit::Vertex(u, w) => out.vertex(u, w),
                    })
            }
            None if m.is_boundary_vertex(v) => {
                if m.is_corner(v) {
                    out.vertex(v as u32, 1.0);
                } else {
                    let (a, b) = m.boundary_neighbors(v);
                    out.vertex(v as u32, 0.75);
                    out.vertex(a, 0.125);
                    out.vertex(b, 0.125);
                }
            }
            _ => smooth_vertex(m, v, 1.0, out),
        }
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

impl Rules<'_> {
    /// The stencil of the vertex point of `v` under these rules (the tests' reference for the
    /// rows [`Rules::push_vertex_row`] writes).
    #[cfg(feature = "unit-tests")]
    pub(crate) fn vertex_stencil(&self, v: usize) -> crate::stencil::Stencil {
        let mut s = crate::stencil::Stencil::new();
        let m = self.m;
        self.vertex(v, &mut Scratch::default(), &mut Expand { m, row: &mut s });
        s.merged()
    }

    /// Appends the row of the vertex point of `v` ([`Rules::vertex_stencil`]) to `table`,
    /// through the reusable buffers `scratch` and `row` (no allocation per row).
    pub(crate) fn push_vertex_row(
        &self,
        v: usize,
        scratch: &mut Scratch,
        row: &mut RowWriter,
        table: &mut StencilTable,
    ) {
        let m = self.m;
        self.vertex(v, scratch, &mut Expand { m, row: &mut *row });
        row.push_into(table);
    }

    /// Appends the row of the edge point of `e` ([`Rules::edge_stencil`]) to `table`, as
    /// [`Rules::push_vertex_row`].
    pub(crate) fn push_edge_row(
        &self,
        e: usize,
        scratch: &mut Scratch,
        row: &mut RowWriter,
        table: &mut StencilTable,
    ) {
        let m = self.m;
        self.edge(e, scratch, &mut Expand { m, row: &mut *row });
        row.push_into(table);
    }

    /// The stencil of the edge point of edge `e` under these rules.
    #[cfg(feature = "unit-tests")]
    pub(crate) fn edge_stencil(&self, e: usize) -> crate::stencil::Stencil {
        let mut s = crate::stencil::Stencil::new();
        let m = self.m;
        self.edge(e, &mut Scratch::default(), &mut Expand { m, row: &mut s });
        s.merged()
    }
}

/// Fails when a child net would not fit fairsub's 32-bit indices.
fn check_sizes(mesh: &PolyMesh) -> Result<()> {
    check_child_size(
        crate::schemes::options::ids::CATMULL_CLARK.name(),
        mesh.num_vertices() + mesh.num_edges() + mesh.num_faces(),
    )?;
    // Child half-edges (4 per parent corner) are indexed by u32 below NONE.
    check_child_size(
        crate::schemes::options::ids::CATMULL_CLARK.name(),
        4 * mesh.num_halfedges() + 1,
    )
}

impl CatmullClark {
    /// The refinement stencils of one step with the default options (child vertex order as
    /// in the module doc), built in parallel without per-row allocation.
    pub fn stencils(mesh: &PolyMesh) -> StencilTable {
        Self::stencils_with(mesh, &Opts::default())
    }

    /// [`CatmullClark::stencils`] with OpenSubdiv's options.
    pub fn stencils_with(mesh: &PolyMesh, opts: &Opts) -> StencilTable {
        let (nv, ne, nf) = (mesh.num_vertices(), mesh.num_edges(), mesh.num_faces());
        let rules = Rules::new(mesh, opts);
        let m = mesh.view();
        StencilTable::build_par(nv, nv + ne + nf, 9, |rows, t| {
            let mut row = RowWriter::new();
            let mut scratch = Scratch::default();
            for r in rows {
                let mut x = Expand { m, row: &mut row };
                if r < nv {
                    rules.vertex(r, &mut scratch, &mut x);
                } else if r < nv + ne {
                    rules.edge(r - nv, &mut scratch, &mut x);
                } else {
                    face_rule(&m, r - nv - ne, 1.0, &mut x);
                }
                row.push_into(t);
            }
        })
    }

    /// The child points of one step computed directly by the rules (no table) with the
    /// default options: face points first, then edge and vertex points reading them, in
    /// parallel. Works on any per-point data (`src` has one entry per parent vertex):
    /// positions, colours, texture coordinates. Row `i` of the result equals row `i` of
    /// [`CatmullClark::stencils`] applied to `src` up to rounding.
    ///
    /// # Panics
    /// Panics when `src` has fewer entries than the mesh has vertices.
    pub fn refine_points<const D: usize>(mesh: &PolyMesh, src: &[[f64; D]]) -> Vec<[f64; D]> {
        Self::refine_points_with(mesh, src, &Opts::default())
    }

    /// [`CatmullClark::refine_points`] with OpenSubdiv's options.
    pub fn refine_points_with<const D: usize>(
        mesh: &PolyMesh,
        src: &[[f64; D]],
        opts: &Opts,
    ) -> Vec<[f64; D]> {
        Self::refine_points_by(mesh, src, &Rules::new(mesh, opts))
    }

    fn refine_points_by<const D: usize>(
        mesh: &PolyMesh,
        src: &[[f64; D]],
        rules: &Rules<'_>,
    ) -> Vec<[f64; D]> {
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
        if rules.plain() {
            Self::vertex_edge_points::<D, true>(head, nv, src, faces, rules);
        } else {
            Self::vertex_edge_points::<D, false>(head, nv, src, faces, rules);
        }
        out
    }

    /// The vertex and edge points (`head`, vertices first) of [`CatmullClark::refine_points_by`]
    /// from the parent points and the face points; `PLAIN` as in [`Rules::edge_in`].
    fn vertex_edge_points<const D: usize, const PLAIN: bool>(
        head: &mut [[f64; D]],
        nv: usize,
        src: &[[f64; D]],
        faces: &[[f64; D]],
        rules: &Rules<'_>,
    ) {
        head.par_chunks_mut(BLOCK)
            .enumerate()
            .for_each(|(c, chunk)| {
                let mut scratch = Scratch::default();
                for (k, o) in chunk.iter_mut().enumerate() {
                    let i = c * BLOCK + k;
                    let mut ev = Eval::new(src, faces);
                    if i < nv {
                        rules.vertex_in::<PLAIN>(i, &mut scratch, &mut ev);
                    } else {
                        rules.edge_in::<PLAIN>(i - nv, &mut scratch, &mut ev);
                    }
                    *o = ev.acc;
                }
            });
    }

    /// Child topology of one step: `(face_start, corners)` of the all-quad child net.
    pub fn child_topology(mesh: &PolyMesh) -> (Vec<u32>, Vec<u32>) {
        (
            quad_starts(mesh.num_halfedges()),
            QuadSplit::child_corners(mesh),
        )
    }

    /// The child net of one step with the given child points (from
    /// [`CatmullClark::refine_points`] or [`CatmullClark::stencils`]), its half-edge
    /// connectivity derived from the parent's without any search: for a manifold parent the
    /// same connectivity, edge numbering and vertex half-edges as [`PolyMesh::from_refinement`]
    /// would build. The child carries the parent's sharp features, refined with the default
    /// options.
    ///
    /// # Panics
    /// Panics when `positions` does not have one point per child vertex.
    pub fn child_mesh(mesh: &PolyMesh, positions: Vec<Point>) -> PolyMesh {
        Self::child_mesh_with(mesh, positions, &Opts::default())
    }

    /// [`CatmullClark::child_mesh`] with OpenSubdiv's options.
    pub fn child_mesh_with(mesh: &PolyMesh, positions: Vec<Point>, opts: &Opts) -> PolyMesh {
        Self::child_mesh_by(mesh, positions, &Rules::new(mesh, opts))
    }

    fn child_mesh_by(mesh: &PolyMesh, positions: Vec<Point>, rules: &Rules<'_>) -> PolyMesh {
        super::split_child::child_mesh::<QuadSplit>(mesh, positions, rules.sharp.as_ref())
    }

    /// `levels` steps of one-shot refinement with the default options: the refined net only.
    /// Points come from the direct kernel ([`CatmullClark::refine_points`]), connectivity from
    /// the parent's; no stencil table is built, each parent level is dropped as soon as its
    /// child exists, and the last step frees the parent's points and most of its connectivity
    /// before allocating the child faces and does not build the last level's half-edges (built
    /// on first use, if ever). So the peak memory stays close to the size of the result.
    /// `progress(level)` is called after each step.
    ///
    /// # Errors
    /// When a level would exceed fairsub's 32-bit indices.
    pub fn refine_uniform(
        mesh: &PolyMesh,
        levels: usize,
        progress: impl FnMut(usize),
    ) -> Result<PolyMesh> {
        Self::refine_uniform_with(mesh, levels, progress, &Opts::default())
    }

    /// [`CatmullClark::refine_uniform`] with OpenSubdiv's options.
    pub fn refine_uniform_with(
        mesh: &PolyMesh,
        levels: usize,
        mut progress: impl FnMut(usize),
        opts: &Opts,
    ) -> Result<PolyMesh> {
        super::common::refine_one_shot::<Self>(mesh, levels, &mut progress, check_sizes, opts)
    }
}

impl super::common::OneShot for CatmullClark {
    type Rules<'a> = Rules<'a>;
    type Split = QuadSplit;

    fn rules<'a>(mesh: &'a PolyMesh, opts: &Opts) -> Rules<'a> {
        Rules::new(mesh, opts)
    }

    fn points(mesh: &PolyMesh, rules: &Rules<'_>) -> Vec<Point> {
        Self::refine_points_by(mesh, mesh.positions(), rules)
    }

    fn sharp<'r, 'a: 'r>(rules: &'r Rules<'a>) -> Option<&'r SharpLevel<'a>> {
        rules.sharp.as_ref()
    }
}

impl Scheme for Configured {
    fn name(&self) -> &'static str {
        crate::schemes::options::ids::CATMULL_CLARK.name()
    }

    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        check_sizes(mesh)?;
        let rules = Rules::new(mesh, &self.options);
        let stencils = CatmullClark::stencils_with(mesh, &self.options);
        let mesh = CatmullClark::child_mesh_by(mesh, stencils.apply(mesh.positions()), &rules);
        Ok(Refinement { mesh, stencils })
    }

    fn refine_uniform(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        progress: &mut dyn FnMut(usize),
    ) -> Result<PolyMesh> {
        CatmullClark::refine_uniform_with(mesh, levels, progress, &self.options)
    }

    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        Ok(CatmullClark::limit_stencils_with(mesh, &self.options))
    }

    fn face_varying(&self) -> Option<crate::schemes::sdc::fvar::FvarRules> {
        Some(crate::schemes::sdc::fvar::FvarRules {
            split: crate::schemes::sdc::fvar::Split::Quads,
            options: self.options,
        })
    }
}

impl Scheme for CatmullClark {
    fn name(&self) -> &'static str {
        Configured::default().name()
    }

    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        Configured::default().refine(mesh)
    }

    fn refine_uniform(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        progress: &mut dyn FnMut(usize),
    ) -> Result<PolyMesh> {
        Configured::default().refine_uniform(mesh, levels, progress)
    }

    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        Configured::default().limit_stencils(mesh)
    }

    fn face_varying(&self) -> Option<crate::schemes::sdc::fvar::FvarRules> {
        Configured::default().face_varying()
    }
}

/// Catmull-Clark's subdominant eigenvalue in closed form,
/// `(c + 5 + sqrt((c + 1)(c + 9))) / 16` with `c = cos(2 pi / n)`.
pub fn catmull_clark_lambda(n: usize) -> f64 {
    let c = (2.0 * PI / n as f64).cos();
    (c + 5.0 + ((c + 1.0) * (c + 9.0)).sqrt()) / 16.0
}

#[cfg(feature = "unit-tests")]
mod tests;
