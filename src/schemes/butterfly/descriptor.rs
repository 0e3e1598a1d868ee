//! The modified butterfly's descriptor: mesh rules (refinement; the vertices are their own
//! limit points) and the local analysis; no exact patches (an interpolating scheme without
//! polynomial pieces), so no `--rings`.

use crate::error::Result;
use crate::mesh::PolyMesh;
use crate::schemes::Scheme;
use crate::schemes::descriptor::{Capabilities, Descriptor, LocalRules, Spec, matrix_and_rows};

/// The modified butterfly scheme.
#[derive(Debug)]
pub struct ButterflyDescriptor;

/// The registry's butterfly row.
pub static DESCRIPTOR: ButterflyDescriptor = ButterflyDescriptor;

impl Descriptor for ButterflyDescriptor {
    fn capabilities(&self) -> Capabilities {
        Capabilities::REFINE
    }

    fn check_input(&self, mesh: &PolyMesh) -> Result<()> {
        crate::schemes::common::require_triangles(
            mesh,
            &format!("{} needs", crate::schemes::options::ids::BUTTERFLY),
        )
    }

    fn mesh_rules(&self, _: &Spec) -> Result<Option<Box<dyn Scheme>>> {
        Ok(Some(Box::new(super::Butterfly)))
    }

    /// The matrix on the one-ring (valences other than 6).
    fn local_rules(&self, _: &Spec) -> Result<Option<Box<dyn LocalRules>>> {
        matrix_and_rows(super::local::local_matrix, super::local::local_sparse)
    }
}
