//! The trait of net refinement ([`Scheme`]: one step as a child net with its stencil table)
//! and what front ends do with it: [`refine_levels`] (several steps, per-vertex and
//! face-varying data carried along) and [`level_stencils`] (the composed table of several
//! steps). Every rule exists once, in a scheme's step; everything here reuses the step's table.

use super::{growth, sdc};
use crate::error::Result;
use crate::mesh::PolyMesh;
use crate::stencil::StencilTable;

/// The result of one refinement step.
#[derive(Debug, Clone)]
pub struct Refinement {
    /// The child net, its positions already computed by `stencils`.
    pub mesh: PolyMesh,
    /// Row `i` computes child vertex `i` from the parent's vertices.
    pub stencils: StencilTable,
}

/// A subdivision scheme acting on whole control nets.
pub trait Scheme: Sync {
    /// The scheme's name as used on the command line (`catmull-clark`, `loop`, ...).
    fn name(&self) -> &'static str;

    /// One refinement step of the whole net. Errors name the element the scheme cannot handle
    /// (for example a non-triangle face for Loop).
    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement>;

    /// Step `level` (0 for the first) of a sequence of steps from an input net, the step the
    /// default [`Scheme::refine_uniform`] and [`Scheme::refine_steps`] take at that level. The
    /// default is [`Scheme::refine`] at every level; schemes whose step depends on the level
    /// only (sqrt(3)'s boundary rule on odd steps, the DS^CC pre-processing steps of
    /// `pgs-dscc`) override this and keep the default loops.
    fn refine_at(&self, parent: &PolyMesh, level: usize) -> Result<Refinement> {
        let _ = level;
        self.refine(parent)
    }

    /// `levels` refinement steps for output: the refined net only. Schemes with a direct kernel
    /// override it to skip the stencil tables, drop each parent level as soon as its child
    /// exists and keep the peak memory close to the size of the result; the default repeats
    /// [`Scheme::refine_at`]. `progress(level)` is called after each step. Schemes whose steps
    /// carry state other than the level (the knot widths of adjustable TPS, the pole conversion
    /// of polar nets) override it too.
    fn refine_uniform(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        progress: &mut dyn FnMut(usize),
    ) -> Result<PolyMesh> {
        let mut m: Option<PolyMesh> = None;
        for l in 0..levels {
            m = Some(self.refine_at(m.as_ref().unwrap_or(mesh), l)?.mesh);
            progress(l + 1);
        }
        Ok(m.unwrap_or_else(|| mesh.clone()))
    }

    /// `levels` steps as [`Scheme::refine_uniform`] takes them, each with its stencil table:
    /// `step(parent, refinement)` sees every step (row `i` of its table gives child vertex `i`
    /// from the parent's) and may attach data to the child, as the per-vertex and face-varying
    /// data are attached ([`refine_levels`]). The default repeats [`Scheme::refine_at`];
    /// schemes whose `refine_uniform` carries state from step to step override it with the same
    /// state.
    fn refine_steps(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        step: &mut dyn FnMut(&PolyMesh, &mut Refinement) -> Result<()>,
    ) -> Result<PolyMesh> {
        let mut m: Option<PolyMesh> = None;
        for l in 0..levels {
            let parent = m.as_ref().unwrap_or(mesh);
            let mut r = self.refine_at(parent, l)?;
            step(parent, &mut r)?;
            m = Some(r.mesh);
        }
        Ok(m.unwrap_or_else(|| mesh.clone()))
    }

    /// The size of the child of a net of size `s` after one step, with the entries of the
    /// step's stencil table: what a front end checks against its memory budget before
    /// refining (see [`growth`]). The default is Catmull-Clark's primal quad split
    /// ([`growth::primal_quad`]); schemes of other topologies override it.
    fn step_size(&self, s: &growth::NetSize) -> growth::NetSize {
        growth::primal_quad(s)
    }

    /// How the scheme's nets carry face control vertices (the non-box schemes): their input is
    /// read, and their refined nets and limit meshes are written, with the FCVs.
    fn fcv_layout(&self) -> FcvLayout {
        FcvLayout::None
    }

    /// Notes for the user on how the scheme reads `mesh` (where FCVs come from, reconstructed
    /// boundary rules, ...).
    fn input_notes(&self, mesh: &PolyMesh) -> Vec<String> {
        let _ = mesh;
        Vec::new()
    }

    /// The limit surface after `levels` steps as a mesh with exact normals per vertex, for
    /// schemes whose limit is not the refined net's own layout (non-box: the refined quads
    /// split into triangles around their FCVs); `None` where the limit positions of the refined
    /// net are the limit mesh.
    fn limit_mesh_with_normals(
        &self,
        mesh: &PolyMesh,
        levels: usize,
    ) -> Option<Result<(PolyMesh, Vec<crate::geom::Point>)>> {
        let _ = (mesh, levels);
        None
    }

    /// How the scheme refines face-varying data (texture coordinates), if it does: Catmull-Clark
    /// and Loop with OpenSubdiv's face-varying rules ([`sdc::fvar`]); `None` drops the data.
    fn face_varying(&self) -> Option<sdc::fvar::FvarRules> {
        None
    }

    /// Stencils of the limit positions of the net's vertices (row `v` for vertex `v`), where the
    /// scheme has closed-form limit masks.
    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        let _ = mesh;
        Err(crate::error::Error::Unsupported(format!(
            "scheme {} has no limit-position masks",
            self.name()
        )))
    }
}

/// How a scheme's nets carry face control vertices (FCVs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FcvLayout {
    /// No FCVs.
    None,
    /// Quad nets with one FCV per face, stored after the vertices (non-box).
    Quads,
    /// Triangle nets whose type-2 vertices are the FCVs (four-directional non-box).
    Triangles,
}

/// Applies `levels` refinement steps ([`Scheme::refine_uniform`]), calling `progress(level)`
/// after each. A net with per-vertex data ([`crate::mesh::VertexData`]) or face-varying data
/// that the scheme refines is refined step by step ([`Scheme::refine_steps`]): each step's
/// stencil table, the one that made the child's positions, is applied to the per-vertex data
/// ([`crate::mesh::VertexData::through`]) and drives the face-varying rules ([`sdc::fvar::refine`]).
/// Plain nets keep the scheme's direct kernel.
pub fn refine_levels(
    scheme: &dyn Scheme,
    mesh: &PolyMesh,
    levels: usize,
    mut progress: impl FnMut(usize),
) -> Result<PolyMesh> {
    let ex = mesh.extras();
    let fv_rules = scheme.face_varying();
    let uv = ex.is_some_and(|e| e.uv.is_some()) && fv_rules.is_some();
    let data = ex.is_some_and(|e| e.vertex_data.is_some());
    if !uv && !data {
        return scheme.refine_uniform(mesh, levels, &mut progress);
    }
    let mut level = 0;
    scheme.refine_steps(mesh, levels, &mut |parent, r| {
        let pex = parent.extras();
        let refined_uv = match (pex.and_then(|e| e.uv.as_ref()), &fv_rules) {
            (Some(uv), Some(rules)) => Some(sdc::fvar::refine(
                parent,
                uv,
                level == 0,
                &r.mesh,
                &r.stencils,
                rules,
            )),
            _ => None,
        };
        let refined_data = pex
            .and_then(|e| e.vertex_data.as_ref())
            .map(|d| d.through(&r.stencils));
        if refined_uv.is_some() || refined_data.is_some() {
            let mut cex = r.mesh.take_extras().unwrap_or_default();
            cex.uv = refined_uv;
            cex.vertex_data = refined_data;
            r.mesh.set_extras(Some(cex));
        }
        level += 1;
        progress(level);
        Ok(())
    })
}

/// The stencil table from the control points of `mesh` to the points of its `levels`-th uniform
/// refinement (each step's table composed with the previous ones), with that refined net.
///
/// This is the precomputed form for animation: the topology stays, the control points move, and
/// [`StencilTable::apply_into`] maps new control positions (or any per-point data) straight to
/// the refined level, in parallel over rows and without allocating. `levels = 0` gives the
/// identity.
///
/// The steps are those of [`Scheme::refine_steps`], so for schemes whose
/// [`Scheme::refine_uniform`] carries state from step to step (the knot widths of adjustable
/// TPS, the DS^CC pre-processing of `pgs-dscc`, the pole conversion of polar nets) the table
/// follows that state, as refinement does.
///
/// # Errors
/// Whatever [`Scheme::refine`] reports (for example a face the scheme cannot handle).
pub fn level_stencils(
    scheme: &dyn Scheme,
    mesh: &PolyMesh,
    levels: usize,
) -> Result<(PolyMesh, StencilTable)> {
    let mut table: Option<StencilTable> = None;
    let fine = scheme.refine_steps(mesh, levels, &mut |_, r| {
        let step = std::mem::replace(&mut r.stencils, StencilTable::new(0));
        table = Some(match table.take() {
            None => step,
            Some(t) => step.compose(&t),
        });
        Ok(())
    })?;
    let table = table.unwrap_or_else(|| StencilTable::identity(mesh.num_vertices()));
    Ok((fine, table))
}

/// Builds the child mesh from topology and stencils: positions are the stencils applied to the
/// parent positions.
pub(crate) fn finish_refinement(
    parent: &PolyMesh,
    stencils: StencilTable,
    face_start: Vec<u32>,
    corners: Vec<u32>,
) -> Result<Refinement> {
    let positions = stencils.apply(parent.positions());
    let mesh = PolyMesh::from_refinement(positions, face_start, corners)?;
    Ok(Refinement { mesh, stencils })
}
