//! The whole-net steps of the preparation: each is one step of a scheme's own refinement
//! (its stencils, its topology), applied to the net before the prepared-for scheme's rules.

use super::map::ParamMap;
use crate::error::Result;
use crate::mesh::PolyMesh;
use crate::schemes::descriptor::Spec;
use crate::schemes::needs::NetStep;
use crate::schemes::{Scheme, catmull_clark, doo_sabin};

impl NetStep {
    /// The step's refinement rules for `spec`'s net `mesh` (Catmull-Clark with the scheme's
    /// OpenSubdiv options, unset ones from the net's tags).
    fn scheme(self, spec: &Spec, mesh: &PolyMesh) -> Box<dyn Scheme> {
        match self {
            NetStep::CatmullClark => {
                let tags = mesh.extras().map(|e| e.options).unwrap_or_default();
                Box::new(catmull_clark::Configured {
                    options: spec.params.subd.or(tags),
                })
            }
            NetStep::DooSabin => Box::new(doo_sabin::DooSabin),
            NetStep::DooSabinCc => Box::new(doo_sabin::DooSabinCc),
            NetStep::Pgs => Box::new(crate::schemes::bi2::Pgs),
        }
    }

    /// The step applied to `mesh` (whose faces lie in the input faces as `map` says; `None`:
    /// `mesh` is the input net): the child net and where its faces lie.
    ///
    /// # Errors
    /// Those of the refinement.
    pub(super) fn apply(
        self,
        spec: &Spec,
        mesh: &PolyMesh,
        map: Option<&ParamMap>,
    ) -> Result<(PolyMesh, ParamMap)> {
        // A dual step's child marks its extras as a refined level (`sharpened`), but only
        // Catmull-Clark's own levels have their boundaries sharpened: the Catmull-Clark step
        // after a dual step sharpens them (boundary edges and kept corners), as for a net read
        let unsharpened;
        let mesh = match mesh.extras() {
            Some(ex)
                if self == NetStep::CatmullClark && ex.sharpened && ex.sharp_edges.is_empty() =>
            {
                let mut ex = ex.clone();
                ex.sharpened = false;
                unsharpened = mesh.clone().with_extras(Some(ex));
                &unsharpened
            }
            _ => mesh,
        };
        let mut child = self.scheme(spec, mesh).refine(mesh)?.mesh;
        // Catmull-Clark's child extras carry the sharp features but not the net's options
        // (boundary mode, ...): the scheme after the step must read the same ones
        if let Some(opts) = mesh.extras().map(|e| e.options).filter(|o| !o.is_empty())
            && self == NetStep::CatmullClark
        {
            let mut ex = child.extras().cloned().unwrap_or_default();
            ex.options = opts.or(ex.options);
            child = child.with_extras(Some(ex));
        }
        let input;
        let map = match map {
            Some(m) => m,
            None => {
                input = ParamMap::input(mesh);
                &input
            }
        };
        let next = if self.is_dual() {
            map.dual_step(mesh, &child)
        } else {
            map.catmull_clark_step(mesh)
        };
        Ok((child, next))
    }
}

/// Steps in words, joined ("one Doo-Sabin step, then one Catmull-Clark step").
pub(super) fn words(steps: &[NetStep]) -> String {
    steps
        .iter()
        .map(|s| s.words())
        .collect::<Vec<_>>()
        .join(", then ")
}
