//! EG's descriptor: exact patches (caps of bi-4 rings on Catmull-Clark nets) and local analysis.
//! EG has no control net of its own to refine.

use super::surface::{EgOptions, EgRulesProvider, dnet_complex};
use crate::bezier::BezierPatch;
use crate::error::Result;
use crate::mesh::PolyMesh;
use crate::schemes::descriptor::{
    Capabilities, ComplexOptions, Computed, Descriptor, Fallback, LocalRules, ParamKind,
    PatchRules, Published, Spec, SurfaceOutput,
};
use crate::schemes::local::LocalMatrix;

/// EG subdivision.
#[derive(Debug)]
pub struct EgDescriptor;

/// The registry's EG row.
pub static DESCRIPTOR: EgDescriptor = EgDescriptor;

impl Descriptor for EgDescriptor {
    fn capabilities(&self) -> Capabilities {
        Capabilities {
            refine: false,
            patches: true,
        }
    }

    fn params(&self) -> &'static [ParamKind] {
        &[ParamKind::Fallback]
    }

    fn patch_rules(&self, spec: &Spec) -> Result<Option<Box<dyn PatchRules>>> {
        Ok(Some(Box::new(EgPatchRules {
            fallback: spec.params.fallback,
        })))
    }

    fn local_rules(&self, _: &Spec) -> Result<Option<Box<dyn LocalRules>>> {
        Ok(Some(Box::new(EgLocal)))
    }
}

/// EG's exact surface: Catmull-Clark's adaptive loop with EG caps.
struct EgPatchRules {
    fallback: Fallback,
}

impl PatchRules for EgPatchRules {
    fn build(
        &self,
        mesh: &PolyMesh,
        opts: ComplexOptions,
        progress: &mut dyn FnMut(usize),
    ) -> Result<SurfaceOutput> {
        let o = EgOptions {
            rings: opts.rings,
            fill: opts.fill,
            fallback: self.fallback,
        };
        dnet_complex(&EgRulesProvider, mesh, o, progress)
    }
}

/// EG's local analysis: the matrix `A_n`, the characteristic ring, and the published ratio
/// mu / lambda^2 where the paper prints the rules.
struct EgLocal;

impl LocalRules for EgLocal {
    fn matrix(&self, n: usize) -> Result<LocalMatrix> {
        super::local::local_matrix(n)
    }

    fn characteristic_ring(&self, n: usize) -> Result<(Vec<BezierPatch>, f64)> {
        super::local::characteristic_ring(n)
    }

    fn published(&self, n: usize, c: &Computed<'_>) -> Result<Vec<Published>> {
        // The printed rules are complete at 3 and 5 only.
        let ratio = super::facts::mu_over_lambda2(n).filter(|_| matches!(n, 3 | 5));
        Ok(ratio
            .map(|p| {
                Published::new(
                    "mu / lambda^2 (printed to 5 decimals)",
                    p,
                    c.spectrum.mu_over_lambda_squared,
                )
            })
            .into_iter()
            .collect())
    }
}
