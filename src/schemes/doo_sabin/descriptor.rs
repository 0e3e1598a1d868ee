//! The descriptors of Doo-Sabin and DS^CC: mesh rules, exact patches, local analysis.

use super::{DooSabin, DooSabinCc};
use crate::error::Result;
use crate::schemes::Scheme;
use crate::schemes::descriptor::{
    Capabilities, Descriptor, LocalRules, ParamKind, PatchRules, Spec, SurfaceOutput,
    matrix_and_rows, patch_fn,
};
use crate::schemes::needs::{Need, NetStep, Purpose, Requirement, Step};

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
    /// Refinement, exact patches and evaluation: an input vertex's patch covers the quarters
    /// of its faces, every later patch one cell of a face ([`crate::bezier::domain`]).
    fn capabilities(&self) -> Capabilities {
        Capabilities {
            eval: true,
            ..Capabilities::REFINE_AND_PATCHES
        }
    }

    /// The boundary modes (`--boundary`, the net's `interpolateboundary` tag): see
    /// [`super`]; the net's creases and corners with fairsub's crease construction
    /// ([`super::sharp`]).
    fn params(&self) -> &'static [ParamKind] {
        &[ParamKind::BoundaryMode, ParamKind::Creases]
    }

    fn mesh_rules(&self, _: &Spec) -> Result<Option<Box<dyn Scheme>>> {
        Ok(Some(if self.cc {
            Box::new(DooSabinCc)
        } else {
            Box::new(DooSabin)
        }))
    }

    /// Creases and corners: the net is cut along infinitely sharp ones; semi-sharp ones are
    /// refined until spent ([`super::sharp`]).
    fn patches_take_features(&self) -> bool {
        true
    }

    /// Bi-2 patches of regular vertices, rings, centroid fill; on a net with sharp features,
    /// of the net cut along its creases ([`super::sharp`]).
    fn patch_rules(&self, spec: &Spec) -> Result<Option<Box<dyn PatchRules>>> {
        let (cc, name) = (self.cc, spec.name());
        patch_fn(move |mesh, opts, progress| {
            super::sharp::on_cut_net(mesh, name, true, |mesh| {
                let c = if cc {
                    super::surface::doo_sabin_cc_complex(mesh, opts, progress)
                } else {
                    super::surface::doo_sabin_complex(mesh, opts, progress)
                };
                c.map(SurfaceOutput::plain)
            })
        })
    }

    /// The patches take no interior vertex of valence 2: one step of the scheme itself removes
    /// them ([`crate::schemes::prepare`]; the refinement leaves out their 2-sided V-faces).
    fn preparation(&self, _: &Spec, purpose: Purpose) -> Vec<Requirement> {
        if purpose == Purpose::Refine {
            return Vec::new();
        }
        let step: &'static [NetStep] = if self.cc {
            &[NetStep::DooSabinCc]
        } else {
            &[NetStep::DooSabin]
        };
        vec![Requirement {
            need: Need::NoInteriorValence2,
            step: Step::Net(step),
        }]
    }

    /// Doo-Sabin's local analysis: the block of an `n`-gon facet (none for DS^CC).
    fn local_rules(&self, _: &Spec) -> Result<Option<Box<dyn LocalRules>>> {
        if self.cc {
            return Ok(None);
        }
        matrix_and_rows(super::local::local_matrix, super::local::local_sparse)
    }
}
