//! Loop subdivision of triangle nets as OpenSubdiv's Loop scheme: boundaries, sharp features,
//! non-manifold nets, written as stencils.
//!
//! Loop's scheme (C. Loop, *Smooth subdivision surfaces based on triangles*, MS thesis, Utah
//! 1987) generalises the quartic three-direction box spline: on a regular net (every interior
//! vertex of valence 6) one step is exactly the box spline's refinement. This module holds the
//! refinement rules, the limit-position masks and the limit-tangent masks (`limit`), each
//! written once as stencils so that refinement, analysis and patch output share them.
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
//! The corner rule is OpenSubdiv's `VTX_BOUNDARY_EDGE_AND_CORNER` behaviour, the default. So
//! the boundary curve is the uniform cubic B-spline of the boundary polygon, which at a corner
//! `c` is continued by the reflected point `2c - p`: the curve interpolates the corner.
//!
//! Sharp features (creases, corners, semi-sharp decay, uniform and Chaikin creasing, the
//! boundary options `edge-only` and `none`, holes, non-manifold features) are OpenSubdiv's,
//! the same machinery as Catmull-Clark's (`sdc::crease`) with Loop's smooth masks.
//!
//! # Layout of one step
//!
//! Child vertex `v` (for `v < V`) is the child of parent vertex `v`; child vertex `V + e` is the
//! point of parent edge `e`. Parent triangle `f = (a, b, c)` with edge points `ab`, `bc`, `ca`
//! becomes child faces `4f .. 4f + 3` = `(a, ab, ca)`, `(b, bc, ab)`, `(c, ca, bc)`,
//! `(ab, bc, ca)`, oriented like the parent: the mesh layer's triangle 1-4 split
//! ([`crate::mesh::tri_split`]), which gives the child nets (`schemes::split_child`).

pub mod dart;
pub mod descriptor;
pub mod entry;
mod limit;
pub mod local;
pub mod surface;
pub use descriptor::DESCRIPTOR;

use crate::error::Result;
use crate::geom::Point;
use crate::mesh::{MeshView, PolyMesh};
use crate::stencil::{Accumulator, Stencil, StencilTable, Terms};
use rayon::prelude::*;

use super::catmull_clark::Opts;
use super::common::{RowBuf, check_child_size};
use super::{Refinement, Scheme};
use crate::mesh::tri_split::TriSplit;
use crate::schemes::sdc::crease::{EdgeTerms, Emit, Scratch, SharpLevel, edge_terms};

/// Child points per parallel task.
const BLOCK: usize = 4096;

/// Loop subdivision of triangle nets (scheme name `loop`) with the default options. See the
/// [module](self) documentation for the rules and the layout of the child net.
#[derive(Debug, Clone, Copy, Default)]
pub struct Loop;

/// Loop subdivision with OpenSubdiv's options (`--boundary`, `--crease-method`, `--fvar`).
#[derive(Debug, Clone, Copy, Default)]
pub struct Configured {
    /// The options (the triangle option is Catmull-Clark's and is ignored).
    pub options: Opts,
}

/// Loop needs a pure triangle net: the first face that is not a triangle is named.
fn check_triangles(mesh: &PolyMesh) -> Result<()> {
    super::common::require_triangles(mesh, "Loop subdivision needs")
}

/// The smooth vertex-centred mask of Loop's shape at interior vertex `v`, scaled: `v` keeps
/// `1 - n w(n)` and each edge neighbour gets `w(n)`. Both the refinement rule (`w = beta`) and
/// the limit mask (`w = chi`) have this shape.
#[inline(always)]
fn smooth_vertex(
    m: &MeshView<'_>,
    v: usize,
    w: fn(usize) -> f64,
    scale: f64,
    row: &mut impl Terms,
) {
    let n = m.outgoing(v).count();
    let wn = w(n);
    row.add(v as u32, scale * (1.0 - n as f64 * wn));
    for h in m.outgoing(v) {
        row.add(m.to(h), scale * wn);
    }
}

/// Writes a vertex-centred mask of Loop's shape into `row` by the plain rules: the smooth
/// mask inside, a boundary vertex keeps `1 - 2 b` and gives `b` to each boundary neighbour; a
/// corner keeps itself.
#[inline]
fn vertex_mask(m: &MeshView<'_>, v: usize, w: fn(usize) -> f64, b: f64, row: &mut impl Terms) {
    let vi = v as u32;
    if !m.is_boundary_vertex(v) {
        smooth_vertex(m, v, w, 1.0, row);
    } else if m.is_corner(v) {
        row.add(vi, 1.0);
    } else {
        let (p, q) = m.boundary_neighbors(v);
        row.add(vi, 1.0 - 2.0 * b);
        row.add(p, b);
        row.add(q, b);
    }
}

/// Loop's receiver of [`edge_terms`]: the smooth mask of edge `e` ([`smooth_edge`]) and
/// vertex weights into `row`.
struct LoopEdge<'r, 'm, R> {
    m: &'r MeshView<'m>,
    e: usize,
    row: &'r mut R,
}

impl<R: Terms> EdgeTerms for LoopEdge<'_, '_, R> {
    #[inline(always)]
    fn smooth(&mut self, s: f64) {
        smooth_edge(self.m, self.e, s, self.row)
    }

    #[inline(always)]
    fn vertex(&mut self, u: u32, w: f64) {
        self.row.add(u, w)
    }
}

/// Loop's smooth edge mask of interior edge `e`, scaled: `3/8, 3/8` for the end points and
/// `1/8` for each opposite vertex.
#[inline(always)]
fn smooth_edge(m: &MeshView<'_>, e: usize, scale: f64, row: &mut impl Terms) {
    let h = m.edge_he[e];
    let t = m.twin(h);
    row.add(m.from(h), 0.375 * scale);
    row.add(m.to(h), 0.375 * scale);
    row.add(m.from(m.faces.prev(h)), 0.125 * scale);
    row.add(m.from(m.faces.prev(t)), 0.125 * scale);
}

/// The rules of one step: plain, or with the sharp features of the level.
pub(crate) struct Rules<'a> {
    m: MeshView<'a>,
    sharp: Option<SharpLevel<'a>>,
}

impl<'a> Rules<'a> {
    /// The rules for `mesh` under `opts`.
    pub fn new(mesh: &'a PolyMesh, opts: &Opts) -> Rules<'a> {
        Rules {
            m: mesh.view(),
            sharp: SharpLevel::new(mesh, opts),
        }
    }

    /// The plain rules of `mesh` (its features, if any, not read): the smooth masks inside,
    /// the boundary's crease and corner masks.
    pub fn plain(mesh: &'a PolyMesh) -> Rules<'a> {
        Rules {
            m: mesh.view(),
            sharp: None,
        }
    }

    /// The level's sharp features, when its rules have them.
    pub fn sharp(&self) -> Option<&SharpLevel<'a>> {
        self.sharp.as_ref()
    }

    /// The refined position of vertex `v` as a stencil over the mesh vertices.
    pub fn vertex_stencil(&self, v: usize) -> Stencil {
        row_stencil(|s, row| self.vertex(v, s, row))
    }

    /// The point of edge `e` as a stencil over the mesh vertices.
    pub fn edge_stencil(&self, e: usize) -> Stencil {
        row_stencil(|s, row| self.edge(e, s, row))
    }

    /// The limit position of vertex `v` as a stencil over the mesh vertices.
    pub fn limit_stencil(&self, v: usize) -> Stencil {
        row_stencil(|s, row| self.limit(v, s, row))
    }

    /// The point of edge `e`.
    #[inline(always)]
    fn edge(&self, e: usize, scratch: &mut Scratch, row: &mut impl Terms) {
        self.edge_in::<false>(e, scratch, row)
    }

    /// [`Rules::edge`]; `PLAIN` (only where the level has no sharp features) compiles the
    /// feature checks away.
    #[inline(always)]
    fn edge_in<const PLAIN: bool>(&self, e: usize, scratch: &mut Scratch, row: &mut impl Terms) {
        let m = &self.m;
        let sharp = if PLAIN { None } else { self.sharp.as_ref() };
        edge_terms(m, e, sharp, scratch, &mut LoopEdge { m, e, row });
    }

    /// The refined point of vertex `v`.
    #[inline(always)]
    fn vertex(&self, v: usize, scratch: &mut Scratch, row: &mut impl Terms) {
        self.vertex_in::<false>(v, scratch, row)
    }

    /// [`Rules::vertex`]; `PLAIN` as in [`Rules::edge_in`].
    #[inline(always)]
    fn vertex_in<const PLAIN: bool>(&self, v: usize, scratch: &mut Scratch, row: &mut impl Terms) {
        let m = &self.m;
        let sharp = if PLAIN { None } else { self.sharp.as_ref() };
        match sharp {
            Some(sl) if sl.special[v] => {
                sl.vertex_plan(v as u32, scratch)
                    .emit(v as u32, |t| match t {
                        Emit::Smooth(s) => smooth_vertex(m, v, Loop::vertex_beta, s, row),
                        Emit::Vertex(u, w) => row.add(u, w),
                    })
            }
            Some(_) => smooth_vertex(m, v, Loop::vertex_beta, 1.0, row),
            None => vertex_mask(m, v, Loop::vertex_beta, 0.125, row),
        }
    }

    /// The limit position of vertex `v`: `(1 - n chi) v + chi sum p_i` inside, the crease's
    /// cubic B-spline `2/3 v + 1/6 (a + b)`, a corner `v`.
    #[inline]
    fn limit(&self, v: usize, scratch: &mut Scratch, row: &mut impl Terms) {
        let m = &self.m;
        match &self.sharp {
            Some(sl) if sl.special[v] => {
                sl.limit_plan(v as u32, scratch)
                    .emit(v as u32, |t| match t {
                        Emit::Smooth(_) => smooth_vertex(m, v, Loop::limit_chi, 1.0, row),
                        Emit::Vertex(u, w) => row.add(u, w),
                    })
            }
            Some(_) => smooth_vertex(m, v, Loop::limit_chi, 1.0, row),
            None => vertex_mask(m, v, Loop::limit_chi, 1.0 / 6.0, row),
        }
    }
}

/// One rule's row (written into a [`RowBuf`]) as a stencil.
fn row_stencil(rule: impl FnOnce(&mut Scratch, &mut RowBuf)) -> Stencil {
    let mut row = RowBuf::default();
    rule(&mut Scratch::default(), &mut row);
    row.take_stencil()
}

/// The refined position of vertex `v` under Loop's vertex rule, as a stencil over the mesh
/// vertices (the rule [`Scheme::refine`] applies, for adaptive refinement).
pub fn vertex_point_stencil(mesh: &PolyMesh, v: usize) -> Stencil {
    Rules::new(mesh, &Opts::default()).vertex_stencil(v)
}

/// The new point of edge `e` under Loop's edge rule, as a stencil over the mesh vertices.
pub fn edge_point_stencil(mesh: &PolyMesh, e: usize) -> Stencil {
    Rules::new(mesh, &Opts::default()).edge_stencil(e)
}

/// The limit position of vertex `v` ([`Scheme::limit_stencils`] for one vertex).
pub fn limit_point_stencil(mesh: &PolyMesh, v: usize) -> Stencil {
    Rules::new(mesh, &Opts::default()).limit_stencil(v)
}

/// Fails when a child net would need more points than fairsub's 32-bit indices.
fn check_sizes(p: &PolyMesh) -> Result<()> {
    check_child_size(
        crate::schemes::options::ids::LOOP.name(),
        p.num_vertices() + p.num_edges(),
    )?;
    check_child_size(
        crate::schemes::options::ids::LOOP.name(),
        4 * p.num_halfedges() + 1,
    )
}

impl Loop {
    /// The refinement stencils of one step with the default options (child vertex `v < V` from
    /// parent vertex `v`, then one edge point per parent edge), built in parallel without
    /// per-row allocation.
    ///
    /// # Errors
    /// [`Error::Unsupported`] for a face that is not a triangle.
    pub fn stencils(mesh: &PolyMesh) -> Result<StencilTable> {
        Self::stencils_with(mesh, &Opts::default())
    }

    /// [`Loop::stencils`] with OpenSubdiv's options.
    ///
    /// # Errors
    /// [`Error::Unsupported`] for a face that is not a triangle.
    pub fn stencils_with(mesh: &PolyMesh, opts: &Opts) -> Result<StencilTable> {
        check_triangles(mesh)?;
        let (nv, ne) = (mesh.num_vertices(), mesh.num_edges());
        let rules = Rules::new(mesh, opts);
        Ok(StencilTable::build_par(nv, nv + ne, 6, |rows, t| {
            let mut row = RowBuf::default();
            let mut scratch = Scratch::default();
            for r in rows {
                if r < nv {
                    rules.vertex(r, &mut scratch, &mut row);
                } else {
                    rules.edge(r - nv, &mut scratch, &mut row);
                }
                row.flush_into(t);
            }
        }))
    }

    /// The child points of one step computed directly by the rules (no table), in parallel, for
    /// any per-point data (`src` has one entry per parent vertex), with the default options.
    /// Row `i` equals row `i` of [`Loop::stencils`] applied to `src` up to rounding.
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
        Ok(Self::refine_points_by(
            mesh,
            src,
            &Rules::new(mesh, &Opts::default()),
        ))
    }

    /// [`Loop::refine_points`] with OpenSubdiv's options.
    ///
    /// # Errors
    /// [`Error::Unsupported`] for a face that is not a triangle.
    pub fn refine_points_with<const D: usize>(
        mesh: &PolyMesh,
        src: &[[f64; D]],
        opts: &Opts,
    ) -> Result<Vec<[f64; D]>> {
        check_triangles(mesh)?;
        Ok(Self::refine_points_by(mesh, src, &Rules::new(mesh, opts)))
    }

    fn refine_points_by<const D: usize>(
        mesh: &PolyMesh,
        src: &[[f64; D]],
        rules: &Rules<'_>,
    ) -> Vec<[f64; D]> {
        let (nv, ne) = (mesh.num_vertices(), mesh.num_edges());
        assert!(src.len() >= nv, "one point per parent vertex is needed");
        let mut out = crate::buffers::zeroed(nv + ne, [0.0; D]);
        if rules.sharp.is_none() {
            Self::points_in::<D, true>(&mut out, nv, src, rules);
        } else {
            Self::points_in::<D, false>(&mut out, nv, src, rules);
        }
        out
    }

    /// The child points (`out`, vertices first) of [`Loop::refine_points_by`]; `PLAIN` as in
    /// [`Rules::edge_in`].
    fn points_in<const D: usize, const PLAIN: bool>(
        out: &mut [[f64; D]],
        nv: usize,
        src: &[[f64; D]],
        rules: &Rules<'_>,
    ) {
        out.par_chunks_mut(BLOCK)
            .enumerate()
            .for_each(|(c, chunk)| {
                let mut scratch = Scratch::default();
                for (k, o) in chunk.iter_mut().enumerate() {
                    let i = c * BLOCK + k;
                    let mut acc = Accumulator::new(src);
                    if i < nv {
                        rules.vertex_in::<PLAIN>(i, &mut scratch, &mut acc);
                    } else {
                        rules.edge_in::<PLAIN>(i - nv, &mut scratch, &mut acc);
                    }
                    *o = acc.value();
                }
            });
    }

    /// The child net of one step with the given child points (from [`Loop::refine_points`] or
    /// [`Loop::stencils`]); its connectivity is derived from the parent's without search: for
    /// a manifold parent the same connectivity, edge numbering and vertex half-edges as
    /// [`PolyMesh::from_refinement`] would build. The child carries the parent's sharp features
    /// refined with the default options.
    ///
    /// # Errors
    /// [`Error::Unsupported`] for a face that is not a triangle.
    ///
    /// # Panics
    /// Panics when `positions` does not have one point per child vertex.
    pub fn child_mesh(mesh: &PolyMesh, positions: Vec<Point>) -> Result<PolyMesh> {
        check_triangles(mesh)?;
        Ok(Self::child_mesh_by(
            mesh,
            positions,
            &Rules::new(mesh, &Opts::default()),
        ))
    }

    fn child_mesh_by(mesh: &PolyMesh, positions: Vec<Point>, rules: &Rules<'_>) -> PolyMesh {
        super::split_child::child_mesh::<TriSplit>(mesh, positions, rules.sharp.as_ref())
    }

    /// `levels` steps of one-shot refinement with the default options: the refined net only,
    /// points from the direct kernel ([`Loop::refine_points`]), connectivity from the parent's;
    /// no stencil table, each parent dropped as soon as its child exists, and the last level's
    /// half-edges built only on first use (see
    /// [`crate::schemes::CatmullClark::refine_uniform`]).
    ///
    /// # Errors
    /// [`Error::Unsupported`] for a face that is not a triangle; when a level would exceed
    /// fairsub's 32-bit indices.
    pub fn refine_uniform(
        mesh: &PolyMesh,
        levels: usize,
        progress: impl FnMut(usize),
    ) -> Result<PolyMesh> {
        Self::refine_uniform_with(mesh, levels, progress, &Opts::default())
    }

    /// [`Loop::refine_uniform`] with OpenSubdiv's options.
    ///
    /// # Errors
    /// As [`Loop::refine_uniform`].
    pub fn refine_uniform_with(
        mesh: &PolyMesh,
        levels: usize,
        mut progress: impl FnMut(usize),
        opts: &Opts,
    ) -> Result<PolyMesh> {
        check_triangles(mesh)?;
        super::common::refine_one_shot::<Self>(mesh, levels, &mut progress, check_sizes, opts)
    }

    /// Limit-position stencils with OpenSubdiv's options (see [`Scheme::limit_stencils`]).
    ///
    /// # Errors
    /// [`Error::Unsupported`] for a face that is not a triangle.
    pub fn limit_stencils_with(mesh: &PolyMesh, opts: &Opts) -> Result<StencilTable> {
        check_triangles(mesh)?;
        let nv = mesh.num_vertices();
        let rules = Rules::new(mesh, opts);
        Ok(StencilTable::build_par(nv, nv, 7, |rows, t| {
            let mut row = RowBuf::default();
            let mut scratch = Scratch::default();
            for v in rows {
                rules.limit(v, &mut scratch, &mut row);
                row.flush_into(t);
            }
        }))
    }
}

impl super::common::OneShot for Loop {
    type Rules<'a> = Rules<'a>;
    type Split = TriSplit;

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
    fn step_size(&self, s: &crate::schemes::growth::NetSize) -> crate::schemes::growth::NetSize {
        crate::schemes::growth::triangle(s)
    }

    fn name(&self) -> &'static str {
        crate::schemes::options::ids::LOOP.name()
    }

    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        check_triangles(mesh)?;
        check_sizes(mesh)?;
        let rules = Rules::new(mesh, &self.options);
        let stencils = Loop::stencils_with(mesh, &self.options)?;
        let mesh = Loop::child_mesh_by(mesh, stencils.apply(mesh.positions()), &rules);
        Ok(Refinement { mesh, stencils })
    }

    fn refine_uniform(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        progress: &mut dyn FnMut(usize),
    ) -> Result<PolyMesh> {
        Loop::refine_uniform_with(mesh, levels, progress, &self.options)
    }

    /// Limit positions: interior `(1 - n chi) v + chi sum p_i` ([`Loop::limit_chi`]), boundary
    /// and crease `2/3 v + 1/6 (a + b)` (the cubic B-spline curve at its knot), corner `v`.
    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        Loop::limit_stencils_with(mesh, &self.options)
    }

    fn face_varying(&self) -> Option<crate::schemes::sdc::fvar::FvarRules> {
        Some(crate::schemes::sdc::fvar::FvarRules {
            split: crate::schemes::sdc::fvar::Split::Triangles,
            options: self.options,
        })
    }
}

super::common::scheme_by_default!(Loop => Configured);

#[cfg(feature = "unit-tests")]
mod tests;
