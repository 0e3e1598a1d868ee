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
//! The rules are written once (`rules.rs`: `face_rule`, the edge and vertex rules of `Rules`)
//! against `CcTerms`: terms on parent vertices and on parent face points. A stencil table
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
mod rules;
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
use crate::mesh::{MeshView, PolyMesh};
use crate::stencil::{RowWriter, StencilTable, Terms, axpy};
use crease::{EdgeTerms, Emit, Scratch, SharpLevel, edge_terms};
use rayon::prelude::*;
use std::f64::consts::PI;

pub(crate) use rules::Rules;
use rules::{Eval, Expand, face_rule};

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

super::common::scheme_by_default!(CatmullClark => Configured);

/// Catmull-Clark's subdominant eigenvalue in closed form,
/// `(c + 5 + sqrt((c + 1)(c + 9))) / 16` with `c = cos(2 pi / n)`.
pub fn catmull_clark_lambda(n: usize) -> f64 {
    let c = (2.0 * PI / n as f64).cos();
    (c + 5.0 + ((c + 1.0) * (c + 9.0)).sqrt()) / 16.0
}

#[cfg(feature = "unit-tests")]
mod tests;
