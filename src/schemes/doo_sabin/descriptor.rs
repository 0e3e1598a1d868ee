//! The descriptors of Doo-Sabin and DS^CC: mesh rules, exact patches, local analysis.

use super::{DooSabin, DooSabinCc};
use crate::error::Result;
use crate::mesh::PolyMesh;
use crate::schemes::Scheme;
use crate::schemes::descriptor::{
    Capabilities, ComplexOptions, Descriptor, LocalRules, PatchRules, Spec, SurfaceOutput,
};
use crate::schemes::local::LocalMatrix;

/// Doo-Sabin (`cc = false`) or DS^CC (`cc = true`).
#[derive(Debug)]
pub struct DsDescriptor {
    /// DS^CC's face-corner rule instead of Doo-Sabin's weights.
    pub cc: bool,
}

/// The registry's Doo-Sabin row.
pub static DESCRIPTOR: DsDescriptor = DsDescriptor { cc: false };
/// The registry's DS^CC row.
pub static DESCRIPTOR_CC: DsDescriptor = DsDescriptor { cc: true };

impl Descriptor for DsDescriptor {
    fn capabilities(&self) -> Capabilities {
        Capabilities {
            refine: true,
            patches: true,
            eval: false,
        }
    }

    fn mesh_rules(&self, _: &Spec) -> Result<Option<Box<dyn Scheme>>> {
        Ok(Some(if self.cc {
            Box::new(DooSabinCc)
        } else {
            Box::new(DooSabin)
        }))
    }

    fn patch_rules(&self, _: &Spec) -> Result<Option<Box<dyn PatchRules>>> {
        Ok(Some(Box::new(DsPatchRules { cc: self.cc })))
    }

    fn local_rules(&self, _: &Spec) -> Result<Option<Box<dyn LocalRules>>> {
        Ok((!self.cc).then(|| Box::new(DsLocal) as Box<dyn LocalRules>))
    }
}

/// The exact surface of Doo-Sabin or DS^CC: bi-2 patches of regular vertices, rings, centroid
/// fill.
struct DsPatchRules {
    cc: bool,
}

impl PatchRules for DsPatchRules {
    fn build(
        &self,
        mesh: &PolyMesh,
        opts: ComplexOptions,
        progress: &mut dyn FnMut(usize),
    ) -> Result<SurfaceOutput> {
        let c = if self.cc {
            super::surface::doo_sabin_cc_complex(mesh, opts, progress)
        } else {
            super::surface::doo_sabin_complex(mesh, opts, progress)
        };
        c.map(SurfaceOutput::plain)
    }
}

/// Doo-Sabin's local analysis: the block of an `n`-gon facet.
struct DsLocal;

impl LocalRules for DsLocal {
    fn matrix(&self, n: usize) -> Result<LocalMatrix> {
        super::local::local_matrix(n)
    }
}
