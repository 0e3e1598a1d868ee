//! sqrt(3)'s descriptor: mesh rules (refinement, limit positions) and the local analysis; no
//! exact patches (sqrt(3) subdivision has no closed-form patches on its regular parts that
//! fairsub writes), so no `--rings`.

use crate::error::Result;
use crate::mesh::PolyMesh;
use crate::schemes::Scheme;
use crate::schemes::descriptor::{Capabilities, Descriptor, LocalRules, Spec, matrix_only};

/// sqrt(3) subdivision.
#[derive(Debug)]
pub struct Sqrt3Descriptor;

/// The registry's sqrt(3) row.
pub static DESCRIPTOR: Sqrt3Descriptor = Sqrt3Descriptor;

impl Descriptor for Sqrt3Descriptor {
    fn capabilities(&self) -> Capabilities {
        Capabilities::REFINE
    }

    fn check_input(&self, mesh: &PolyMesh) -> Result<()> {
        crate::schemes::common::require_triangles(mesh, "sqrt(3) subdivision needs")
    }

    fn mesh_rules(&self, _: &Spec) -> Result<Option<Box<dyn Scheme>>> {
        Ok(Some(Box::new(super::Sqrt3)))
    }

    /// The two-step matrix on the one-ring.
    fn local_rules(&self, _: &Spec) -> Result<Option<Box<dyn LocalRules>>> {
        matrix_only(super::local::local_matrix)
    }
}
