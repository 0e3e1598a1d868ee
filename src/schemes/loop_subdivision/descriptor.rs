//! Loop's descriptor: mesh rules, exact patches, local analysis.

use crate::error::Result;
use crate::mesh::PolyMesh;
use crate::schemes::Scheme;
use crate::schemes::descriptor::{
    Capabilities, Descriptor, LocalRules, ParamKind, PatchRules, Spec, SurfaceOutput,
    matrix_and_rows, patch_fn,
};

/// Loop.
#[derive(Debug)]
pub struct LoopDescriptor;

/// The registry's Loop row.
pub static DESCRIPTOR: LoopDescriptor = LoopDescriptor;

impl Descriptor for LoopDescriptor {
    fn capabilities(&self) -> Capabilities {
        Capabilities {
            eval: true,
            ..Capabilities::REFINE_AND_PATCHES
        }
    }

    fn check_input(&self, mesh: &PolyMesh) -> Result<()> {
        crate::schemes::common::require_triangles(mesh, "Loop subdivision needs")
    }

    fn params(&self) -> &'static [ParamKind] {
        &[ParamKind::SharpFeatures]
    }

    fn mesh_rules(&self, spec: &Spec) -> Result<Option<Box<dyn Scheme>>> {
        Ok(Some(Box::new(super::Configured {
            options: spec.params.subd,
        })))
    }

    /// Quartic box-spline triangles, rings, G^1 caps of kites (open triangle fans at boundary vertices),
    /// honouring the net's sharp features under OpenSubdiv's options.
    fn patch_rules(&self, spec: &Spec) -> Result<Option<Box<dyn PatchRules>>> {
        let subd = spec.params.subd;
        patch_fn(move |mesh, opts, progress| {
            super::surface::loop_complex_with(mesh, opts, subd, progress).map(SurfaceOutput::plain)
        })
    }

    fn patches_take_features(&self) -> bool {
        true
    }

    /// The matrix on the one-ring.
    fn local_rules(&self, _: &Spec) -> Result<Option<Box<dyn LocalRules>>> {
        matrix_and_rows(super::local::local_matrix, super::local::local_sparse)
    }
}
