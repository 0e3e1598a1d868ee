//! Loop's descriptor: mesh rules, exact patches, local analysis.

use crate::error::Result;
use crate::mesh::PolyMesh;
use crate::schemes::Scheme;
use crate::schemes::descriptor::{
    Capabilities, ComplexOptions, Descriptor, LocalRules, ParamKind, PatchRules, Spec,
    SurfaceOutput,
};
use crate::schemes::local::LocalMatrix;

/// Loop.
#[derive(Debug)]
pub struct LoopDescriptor;

/// The registry's Loop row.
pub static DESCRIPTOR: LoopDescriptor = LoopDescriptor;

impl Descriptor for LoopDescriptor {
    fn capabilities(&self) -> Capabilities {
        Capabilities {
            refine: true,
            patches: true,
            eval: true,
        }
    }

    fn check_input(&self, mesh: &PolyMesh) -> Result<()> {
        super::require_triangles(mesh, "Loop subdivision needs")
    }

    fn params(&self) -> &'static [ParamKind] {
        &[ParamKind::SharpFeatures]
    }

    fn mesh_rules(&self, spec: &Spec) -> Result<Option<Box<dyn Scheme>>> {
        Ok(Some(Box::new(super::Configured {
            options: spec.params.subd,
        })))
    }

    fn patch_rules(&self, _: &Spec) -> Result<Option<Box<dyn PatchRules>>> {
        Ok(Some(Box::new(LoopPatchRules)))
    }

    fn local_rules(&self, _: &Spec) -> Result<Option<Box<dyn LocalRules>>> {
        Ok(Some(Box::new(LoopLocal)))
    }
}

/// Loop's exact surface: quartic box-spline triangles, rings, Hermite fill.
struct LoopPatchRules;

impl PatchRules for LoopPatchRules {
    fn build(
        &self,
        mesh: &PolyMesh,
        opts: ComplexOptions,
        progress: &mut dyn FnMut(usize),
    ) -> Result<SurfaceOutput> {
        super::surface::loop_complex(mesh, opts, progress).map(SurfaceOutput::plain)
    }
}

/// Loop's local analysis on the one-ring.
struct LoopLocal;

impl LocalRules for LoopLocal {
    fn matrix(&self, n: usize) -> Result<LocalMatrix> {
        super::local::local_matrix(n)
    }
}
