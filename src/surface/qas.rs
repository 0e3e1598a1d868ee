//! QAS+ surfaces of whole meshes: bi-3 patches on regular faces and a QAS+^4 cap of `K` bi-4
//! rings at every extraordinary vertex of valence 5, 6 or 7, on the machinery of EG caps
//! ([`super::eg`]: the same d-net, local Catmull-Clark step, fill and fallback).
//!
//! Valence 3 uses EG's rules (QAS keeps the earlier QAS paper's rules there, which are not in the
//! corpus); other valences fall back to Catmull-Clark or stop with an error, as the user chooses.
//! The initial quadratic expansion is fairsub's `qas-fit` ([`crate::schemes::qas::fit_stencils`]).

use super::eg::{CapOutput, DnetRules, EgOptions, EgRulesProvider, dnet_complex};
use crate::error::Result;
use crate::mesh::PolyMesh;
use crate::schemes::eg::{Eg, EgStep};
use crate::schemes::qas::{self, Qas};
use crate::stencil::StencilTable;

/// The contraction used by a QAS variant at ring `k` (0-based).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Contraction {
    /// QAS+: 1/2 at every step.
    Half,
    /// A fixed `lambda` in `S` (QAS_0.4 with 0.4).
    Fixed(f64),
    /// QAS_{0.5,0.4}: 0.5, 0.5, 0.475, 0.475, 0.45, 0.45, then 0.4.
    Gradual,
}

impl Contraction {
    /// `lambda` at ring `k` (0-based).
    pub fn at(self, k: usize) -> f64 {
        match self {
            Contraction::Half => 0.5,
            Contraction::Fixed(l) => l,
            Contraction::Gradual => [0.5, 0.5, 0.475, 0.475, 0.45, 0.45]
                .get(k)
                .copied()
                .unwrap_or(0.4),
        }
    }
}

struct QasRulesProvider {
    contraction: Contraction,
}

impl DnetRules for QasRulesProvider {
    fn primary(&self) -> &'static str {
        "qas-plus"
    }

    fn rules_name(&self, n: usize) -> Option<&'static str> {
        if qas::tables::COMPLETE_VALENCES.contains(&n) {
            Some("qas-plus")
        } else {
            EgRulesProvider.rules_name(n)
        }
    }

    fn init(&self, n: usize) -> Result<StencilTable> {
        if qas::tables::COMPLETE_VALENCES.contains(&n) {
            qas::from_cnet(n)
        } else {
            EgRulesProvider.init(n)
        }
    }

    fn step(&self, n: usize, k: usize) -> Result<EgStep> {
        if qas::tables::COMPLETE_VALENCES.contains(&n) {
            Qas::new(n)?.step(self.contraction.at(k))
        } else {
            Eg::new(n)?.step()
        }
    }

    fn no_rules(&self, n: usize) -> String {
        format!(
            "valence {n}: QAS+ has published rules for valences 5, 6, 7 (and EG's for 3); use --fallback catmull-clark"
        )
    }
}

/// The QAS+ surface of a net, with the elements that fell back and notes for the user.
pub fn qas_complex(
    mesh: &PolyMesh,
    opts: EgOptions,
    contraction: Contraction,
    progress: impl FnMut(usize),
) -> Result<CapOutput> {
    dnet_complex(&QasRulesProvider { contraction }, mesh, opts, progress)
}
