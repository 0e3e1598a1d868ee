//! PGS after DS^CC pre-processing (`pgs-dscc`, the paper's prism experiment): the first steps
//! are DS^CC steps, the rest PGS ([`super::pgs`]); the step depends on the level only, so the
//! scheme overrides [`Scheme::refine_at`] and keeps the trait's level loops.

use super::pgs::Pgs;
use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use crate::schemes::doo_sabin::DooSabinCc;
use crate::schemes::options::ids;
use crate::schemes::{Refinement, Scheme};
use crate::stencil::StencilTable;

/// Options of PGS beyond the paper's rules.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PgsOptions {
    /// Steps of DS^CC applied before PGS (the paper's prism experiment uses 2; `0` applies PGS
    /// from the start).
    pub dscc_steps: usize,
}

/// PGS after DS^CC pre-processing (scheme name `pgs-dscc`, two steps by default): the first
/// `opts.dscc_steps` levels are DS^CC steps, the rest PGS, as in the paper's prism experiment.
#[derive(Debug, Clone, Copy)]
pub struct PgsPreprocessed {
    /// The pre-processing.
    pub opts: PgsOptions,
}

impl Default for PgsPreprocessed {
    fn default() -> Self {
        PgsPreprocessed {
            opts: PgsOptions { dscc_steps: 2 },
        }
    }
}

impl Scheme for PgsPreprocessed {
    fn step_size(&self, s: &crate::schemes::growth::NetSize) -> crate::schemes::growth::NetSize {
        crate::schemes::growth::dual(s)
    }

    fn name(&self) -> &'static str {
        crate::schemes::options::ids::PGS_DSCC.name()
    }

    /// The first step of the sequence: DS^CC (PGS when no pre-processing is asked for).
    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        self.refine_at(mesh, 0)
    }

    /// The pre-processing steps first (DS^CC), then PGS.
    fn refine_at(&self, mesh: &PolyMesh, level: usize) -> Result<Refinement> {
        if level < self.opts.dscc_steps {
            DooSabinCc.refine(mesh)
        } else {
            Pgs.refine(mesh)
        }
    }

    /// Refused: the limit of a net depends on how many pre-processing steps remain, which the
    /// net does not record.
    fn limit_stencils(&self, _mesh: &PolyMesh) -> Result<StencilTable> {
        Err(Error::Unsupported(format!(
            "{} limit positions depend on how many DS^CC steps remain; refine with \
             --levels 2 or more and take the limit of the result with --scheme {}",
            ids::PGS_DSCC,
            ids::PGS
        )))
    }
}
