//! QAS+ surfaces of whole meshes: bi-3 patches on regular faces and a QAS+^4 cap of `K` bi-4
//! rings at every extraordinary vertex of valence 5, 6 or 7, on the machinery of EG caps
//! ([`crate::schemes::eg::surface`]: the same d-net, local Catmull-Clark step, fill and fallback).
//!
//! Valence 3 uses EG's rules (QAS keeps the earlier QAS paper's rules there, which are not in the
//! corpus); other valences fall back to Catmull-Clark or stop with an error, as the user chooses.
//! The initial quadratic expansion is fairsub's `qas-fit` ([`crate::schemes::qas::fit_stencils`]).

use crate::error::{Error, Result};
use crate::geom::Point;
use crate::host::SurfaceOutput;
use crate::mesh::{Element, PolyMesh};
use crate::schemes::eg::surface::{DnetRules, EgOptions, EgRulesProvider, dnet_complex};
use crate::schemes::eg::{Eg, EgStep};
use crate::schemes::qas::QSpec;
use crate::schemes::qas::{self, Qas};
use crate::schemes::registry::ids;
use crate::stencil::StencilTable;
use std::collections::BTreeMap;

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
    overrides: BTreeMap<u32, QSpec>,
    bi3: bool,
}

impl DnetRules for QasRulesProvider {
    fn primary(&self) -> &'static str {
        ids::QAS_PLUS.name()
    }

    fn rules_name(&self, n: usize) -> Option<&'static str> {
        if qas::tables::COMPLETE_VALENCES.contains(&n) {
            Some(ids::QAS_PLUS.name())
        } else {
            EgRulesProvider.rules_name(n)
        }
    }

    fn init(&self, n: usize) -> Result<StencilTable> {
        if qas::tables::COMPLETE_VALENCES.contains(&n) && self.bi3 {
            qas::bi3::from_cnet(n)
        } else if qas::tables::COMPLETE_VALENCES.contains(&n) {
            qas::from_cnet(n)
        } else {
            EgRulesProvider.init(n)
        }
    }

    fn step(&self, n: usize, k: usize) -> Result<EgStep> {
        if qas::tables::COMPLETE_VALENCES.contains(&n) && self.bi3 {
            qas::bi3::QasBi3::new(n)?.step(self.contraction.at(k))
        } else if qas::tables::COMPLETE_VALENCES.contains(&n) {
            Qas::new(n)?.step(self.contraction.at(k))
        } else {
            Eg::new(n)?.step()
        }
    }

    fn stationary(&self) -> bool {
        !matches!(self.contraction, Contraction::Gradual)
    }

    fn no_rules(&self, n: usize) -> String {
        format!(
            "valence {n}: QAS+ has published rules for valences 5, 6, 7 (and EG's for 3); use --fallback {}",
            ids::CATMULL_CLARK
        )
    }

    fn adjust(&self, n: usize, element: Element, x: &mut [Point]) -> Result<()> {
        let Element::Vertex(v) = element else {
            return Ok(());
        };
        let Some(spec) = self.overrides.get(&v) else {
            return Ok(());
        };
        if !qas::tables::COMPLETE_VALENCES.contains(&n) {
            return Err(Error::InvalidArgument(format!(
                "the q file gives an expansion for vertex {v}, which has valence {n}: QAS+ rules exist for 5, 6, 7"
            )));
        }
        if let Some(p) = spec.p {
            x[0] = p;
        }
        for &(s, k, val) in &spec.q {
            if s >= n {
                return Err(Error::InvalidArgument(format!(
                    "the q file names sector {s} of vertex {v}, which has {n} sectors"
                )));
            }
            x[qas::q_index(n, s, k)] = val;
        }
        let full: Vec<[[f64; 3]; 6]> = (0..n)
            .map(|s| {
                let mut q = [x[0]; 6];
                for k in 2..=6 {
                    q[k - 1] = x[qas::q_index(n, s, k)];
                }
                q
            })
            .collect();
        let scale = x
            .iter()
            .flat_map(|p| p.iter())
            .fold(1.0f64, |m, c| m.max(c.abs()));
        qas::check_kind(n, &full, spec.kind, 1e-9 * scale)
            .map_err(|e| Error::InvalidArgument(format!("q file, vertex {v}: {e}")))
    }
}

/// The QAS+ surface of a net, with the elements that fell back and notes for the user.
pub fn qas_complex(
    mesh: &PolyMesh,
    opts: EgOptions,
    contraction: Contraction,
    progress: impl FnMut(usize),
) -> Result<SurfaceOutput> {
    qas_complex_with(mesh, opts, contraction, BTreeMap::new(), progress)
}

/// QAS+^3: like [`qas_complex`] with the bi-3 rings of [`crate::schemes::qas::bi3`] (12 n bi-3
/// patches per ring) and the bi-3 fill.
pub fn qas_bi3_complex(
    mesh: &PolyMesh,
    opts: EgOptions,
    contraction: Contraction,
    progress: impl FnMut(usize),
) -> Result<SurfaceOutput> {
    dnet_complex(
        &QasRulesProvider {
            contraction,
            overrides: BTreeMap::new(),
            bi3: true,
        },
        mesh,
        opts,
        progress,
    )
}

/// Like [`qas_complex`], with user-given expansions per input vertex
/// ([`crate::schemes::qas::parse_q_file`]): given coefficients replace those of `qas-fit` and the
/// result must be of the declared kind (C^2, C^1 or C^1-C^0), else an error names the vertex,
/// sector and coefficient. Sectors are numbered as in [`crate::mesh::PolyMesh::cnet_indices`] at the level where
/// the cap is made.
pub fn qas_complex_with(
    mesh: &PolyMesh,
    opts: EgOptions,
    contraction: Contraction,
    overrides: BTreeMap<u32, QSpec>,
    progress: impl FnMut(usize),
) -> Result<SurfaceOutput> {
    dnet_complex(
        &QasRulesProvider {
            contraction,
            overrides,
            bi3: false,
        },
        mesh,
        opts,
        progress,
    )
}
