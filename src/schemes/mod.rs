//! Subdivision schemes, one module per family, each written once as stencils.
//!
//! A scheme that refines whole control nets implements [`Scheme`]: one refinement step returns
//! the child net together with the [`StencilTable`] that computes every child point from the
//! parent points. Applying a scheme to positions, composing several levels, building the local
//! subdivision matrix for analysis or re-applying the step to moved points all reuse that one
//! table, so every rule exists exactly once.

pub mod doo_sabin;
pub mod loop_subdivision;

mod common;

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

/// Applies `levels` refinement steps, calling `progress(level)` after each.
pub fn refine_levels(
    scheme: &dyn Scheme,
    mesh: &PolyMesh,
    levels: usize,
    mut progress: impl FnMut(usize),
) -> Result<PolyMesh> {
    let mut m = mesh.clone();
    for l in 0..levels {
        m = scheme.refine(&m)?.mesh;
        progress(l + 1);
    }
    Ok(m)
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
