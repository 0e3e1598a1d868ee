//! Catmull-Clark's descriptor: mesh rules, exact patches, local analysis.

use crate::bezier::BezierPatch;
use crate::error::Result;
use crate::host::ComplexOptions;
use crate::mesh::PolyMesh;
use crate::schemes::Scheme;
use crate::schemes::circulant::SparseLocal;
use crate::schemes::descriptor::{
    Capabilities, Computed, Descriptor, LocalRules, ParamKind, PatchRules, Published, Spec,
    SurfaceOutput,
};
use crate::schemes::local::LocalMatrix;

/// Catmull-Clark.
#[derive(Debug)]
pub struct CcDescriptor;

/// The registry's Catmull-Clark row.
pub static DESCRIPTOR: CcDescriptor = CcDescriptor;

impl Descriptor for CcDescriptor {
    fn capabilities(&self) -> Capabilities {
        Capabilities {
            eval: true,
            ..Capabilities::REFINE_AND_PATCHES
        }
    }

    fn params(&self) -> &'static [ParamKind] {
        &[ParamKind::SharpFeatures, ParamKind::SmoothTriangles]
    }

    fn mesh_rules(&self, spec: &Spec) -> Result<Option<Box<dyn Scheme>>> {
        Ok(Some(Box::new(super::Configured {
            options: spec.params.subd,
        })))
    }

    /// The adaptive loop with bi-3 patches and the Hermite-Coons fill, honouring the net's
    /// sharp features under OpenSubdiv's options.
    fn patch_rules(&self, spec: &Spec) -> Result<Option<Box<dyn PatchRules>>> {
        Ok(Some(Box::new(CcPatches {
            subd: spec.params.subd,
        })))
    }

    fn patches_take_features(&self) -> bool {
        true
    }

    fn local_rules(&self, _: &Spec) -> Result<Option<Box<dyn LocalRules>>> {
        Ok(Some(Box::new(CcLocal)))
    }
}

/// Catmull-Clark's exact surfaces, with their patch tables tracked beside the points.
struct CcPatches {
    subd: crate::mesh::tags::SubdOptions,
}

impl PatchRules for CcPatches {
    fn build(
        &self,
        mesh: &PolyMesh,
        opts: ComplexOptions,
        progress: &mut dyn FnMut(usize),
    ) -> Result<SurfaceOutput> {
        super::surface::catmull_clark_complex_with(mesh, opts, self.subd, progress)
            .map(SurfaceOutput::plain)
    }

    fn build_tracked(
        &self,
        mesh: &PolyMesh,
        opts: ComplexOptions,
    ) -> Result<Option<(SurfaceOutput, crate::stencil::LayeredTable)>> {
        let (complex, rows) = super::surface::catmull_clark_tracked(mesh, opts, self.subd)?;
        Ok(rows.map(|r| (SurfaceOutput::plain(complex), r)))
    }
}

/// Catmull-Clark's local analysis on the c-net.
struct CcLocal;

impl LocalRules for CcLocal {
    fn matrix(&self, n: usize) -> Result<LocalMatrix> {
        super::local::local_matrix(n)
    }

    fn sparse(&self, n: usize) -> Result<Option<SparseLocal>> {
        super::local::local_sparse(n).map(Some)
    }

    fn characteristic_ring(&self, n: usize) -> Result<(Vec<BezierPatch>, f64)> {
        super::local::characteristic_ring(n)
    }

    fn published(&self, n: usize, c: &Computed<'_>) -> Result<Vec<Published>> {
        let nf = n as f64;
        Ok(vec![
            Published::new(
                "lambda = (c + 5 + sqrt((c+1)(c+9))) / 16",
                super::catmull_clark_lambda(n),
                c.spectrum.lambda,
            ),
            Published::new(
                "limit weight of the centre n / (n + 5)",
                nf / (nf + 5.0),
                c.limit_stencil[0],
            ),
        ])
    }
}
