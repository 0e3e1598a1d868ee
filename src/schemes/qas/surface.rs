//! QAS+ surfaces of whole meshes: bi-3 patches on regular faces and a QAS+^4 cap of `K` bi-4
//! rings at every extraordinary vertex, on the machinery of EG caps
//! ([`crate::schemes::eg::surface`]: the same d-net, local Catmull-Clark step, fill and fallback).
//!
//! The tables of each valence are chosen by [`super::select`]: printed at 5, 6, 7, fairsub's
//! derived ones at 8..=16 (and at 5..7 with `--rules derived`), named in the notes
//! (`qas-plus (derived rules, n = 8)`). Valence 3 uses EG's rules (QAS keeps the earlier QAS
//! paper's rules there, which are not in the corpus), 4 regular bi-4 refinement; valences above
//! 16 fall back to Catmull-Clark or stop with an error, as the user chooses.
//! The initial quadratic expansion is fairsub's `qas-fit` ([`crate::schemes::qas::fit_stencils`]).

use super::bi3::QasBi3;
use super::select::{self, QasSelected};
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::host::SurfaceOutput;
use crate::mesh::{Element, PolyMesh};
use crate::schemes::descriptor::{RulesChoice, RulesOrigin, SchemeId};
use crate::schemes::eg::derive::MAX_VALENCE;
use crate::schemes::eg::surface::{DnetRules, EgOptions, Used, dnet_complex};
use crate::schemes::eg::{Eg, EgStep};
use crate::schemes::options::ids;
use crate::schemes::qas;
use crate::schemes::qas::QSpec;
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

/// The rules of a QAS+ variant per valence ([`super::select`]).
pub(crate) struct QasRulesProvider {
    /// The variant's name (in notes).
    pub(crate) id: SchemeId,
    /// The contraction schedule.
    pub(crate) contraction: Contraction,
    /// User-given expansions per input vertex.
    pub(crate) overrides: BTreeMap<u32, QSpec>,
    /// QAS+^3 (bi-3 rings) instead of QAS+^4.
    pub(crate) bi3: bool,
    /// Printed or derived tables where both exist.
    pub(crate) choice: RulesChoice,
}

impl QasRulesProvider {
    /// The rules of valence `n` (an error where none exist).
    fn rules(&self, n: usize) -> Result<QasSelected> {
        select::select(n, self.choice)?
            .ok_or_else(|| Error::Unsupported(select::no_rules(self.id, n)))
    }
}

impl DnetRules for QasRulesProvider {
    fn primary(&self) -> &'static str {
        self.id.name()
    }

    fn used(&self, n: usize) -> Result<Option<Used>> {
        let Some(origin) = select::origin(n, self.choice) else {
            return Ok(None);
        };
        Ok(Some(match origin {
            RulesOrigin::Printed => Used::Own,
            RulesOrigin::Derived => Used::Derived {
                label: format!("{} (derived rules, n = {n})", self.id),
                chosen: select::printed_exists(n),
            },
            // EG's rules at 3 (printed or derived), regular bi-4 at 4.
            _ => {
                let sel = self.rules(n)?;
                Used::Borrowed(select::label(self.id, n, &sel))
            }
        }))
    }

    fn init(&self, n: usize) -> Result<StencilTable> {
        match self.rules(n)? {
            QasSelected::Qas { qas, .. } if self.bi3 => qas::bi3::from_cnet_of(&qas),
            QasSelected::Qas { qas, .. } => qas.from_cnet(),
            QasSelected::Eg(_) => crate::schemes::eg::from_cnet(n),
        }
    }

    fn step(&self, n: usize, k: usize) -> Result<EgStep> {
        let lambda = self.contraction.at(k);
        match self.rules(n)? {
            QasSelected::Qas { qas, .. } if self.bi3 => QasBi3::with_qas(qas).step(lambda),
            QasSelected::Qas { qas, .. } => qas.step(lambda),
            QasSelected::Eg(e) => Eg::with_rules(e.rules).step(),
        }
    }

    fn stationary(&self) -> bool {
        !matches!(self.contraction, Contraction::Gradual)
    }

    fn no_rules(&self, n: usize) -> String {
        select::no_rules(self.id, n)
    }

    /// QAS+'s limit tangent plane: the plane of the expansion `q` (see
    /// [`crate::schemes::eg::surface`]'s cap): Fourier mode 1 of `q_2^s - p`, `q_2^s` along the
    /// chart direction `e_s`.
    fn limit_tangents(&self, n: usize, x: &[Point]) -> Result<Option<[Point; 2]>> {
        if !matches!(self.rules(n)?, QasSelected::Qas { .. }) {
            return Ok(None);
        }
        let mut t = [[0.0; 3]; 2];
        for s in 0..n {
            let th = 2.0 * std::f64::consts::PI * s as f64 / n as f64;
            let d = crate::geom::sub(x[qas::q_index(n, s, 2)], x[0]);
            t[0] = crate::geom::axpy(t[0], th.cos(), d);
            t[1] = crate::geom::axpy(t[1], th.sin(), d);
        }
        Ok(Some(t))
    }

    fn adjust(&self, n: usize, element: Element, x: &mut [Point]) -> Result<()> {
        let Element::Vertex(v) = element else {
            return Ok(());
        };
        let Some(spec) = self.overrides.get(&v) else {
            return Ok(());
        };
        if !matches!(self.rules(n)?, QasSelected::Qas { .. }) {
            return Err(spec.error(
                spec.line,
                format!(
                    "the q file gives an expansion for vertex {v}, which has valence {n}: QAS+ \
                     tables (with a quadratic expansion) are used at valences 5..={MAX_VALENCE}; \
                     valence 3 uses EG's rules and 4 regular bi-4 refinement"
                ),
            ));
        }
        if let Some(p) = spec.p {
            x[0] = p;
        }
        for (i, &(s, k, val)) in spec.q.iter().enumerate() {
            if s >= n {
                let line = spec.q_lines.get(i).copied().unwrap_or(spec.line);
                return Err(spec.error(
                    line,
                    format!("the q file names sector {s} of vertex {v}, which has {n} sectors"),
                ));
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
            .map_err(|e| spec.error(spec.line, format!("q file, vertex {v}: {e}")))
    }
}

/// What selects a QAS variant's rules on a whole mesh.
#[derive(Debug, Clone)]
pub struct QasSurface {
    /// The variant (its name appears in the notes).
    pub id: SchemeId,
    /// The contraction schedule.
    pub contraction: Contraction,
    /// QAS+^3 (bi-3 rings and fill) instead of QAS+^4.
    pub bi3: bool,
    /// Printed or derived tables where both exist.
    pub rules: RulesChoice,
    /// User-given expansions per input vertex ([`crate::schemes::qas::parse_q_file`]): given
    /// coefficients replace those of `qas-fit` and the result must be of the declared kind
    /// (C^2, C^1 or C^1-C^0), else an error names the vertex, sector and coefficient. Sectors
    /// are numbered as in [`crate::mesh::PolyMesh::cnet_indices`] at the level where the cap is
    /// made.
    pub overrides: BTreeMap<u32, QSpec>,
}

impl QasSurface {
    /// QAS+^4 (`qas-plus`) with `contraction`, printed tables where they exist.
    pub fn new(contraction: Contraction) -> QasSurface {
        QasSurface {
            id: ids::QAS_PLUS,
            contraction,
            bi3: false,
            rules: RulesChoice::Printed,
            overrides: BTreeMap::new(),
        }
    }
}

/// The surface of a net under a QAS variant, with the elements that fell back and the notes
/// (caps with EG's, regular or derived rules).
pub fn qas_surface(
    mesh: &PolyMesh,
    opts: EgOptions,
    q: &QasSurface,
    progress: impl FnMut(usize),
) -> Result<SurfaceOutput> {
    dnet_complex(
        &QasRulesProvider {
            id: q.id,
            contraction: q.contraction,
            overrides: q.overrides.clone(),
            bi3: q.bi3,
            choice: q.rules,
        },
        mesh,
        opts,
        progress,
    )
}

/// The QAS+ surface of a net (printed tables where they exist, derived ones elsewhere), with
/// the elements that fell back and notes for the user.
pub fn qas_complex(
    mesh: &PolyMesh,
    opts: EgOptions,
    contraction: Contraction,
    progress: impl FnMut(usize),
) -> Result<SurfaceOutput> {
    qas_surface(mesh, opts, &QasSurface::new(contraction), progress)
}

/// QAS+^3: like [`qas_complex`] with the bi-3 rings of [`crate::schemes::qas::bi3`] (12 n bi-3
/// patches per ring) and the bi-3 fill.
pub fn qas_bi3_complex(
    mesh: &PolyMesh,
    opts: EgOptions,
    contraction: Contraction,
    progress: impl FnMut(usize),
) -> Result<SurfaceOutput> {
    let q = QasSurface {
        id: ids::QAS_PLUS_BI3,
        bi3: true,
        ..QasSurface::new(contraction)
    };
    qas_surface(mesh, opts, &q, progress)
}

/// Like [`qas_complex`], with user-given expansions per input vertex
/// ([`QasSurface::overrides`]).
pub fn qas_complex_with(
    mesh: &PolyMesh,
    opts: EgOptions,
    contraction: Contraction,
    overrides: BTreeMap<u32, QSpec>,
    progress: impl FnMut(usize),
) -> Result<SurfaceOutput> {
    let q = QasSurface {
        overrides,
        ..QasSurface::new(contraction)
    };
    qas_surface(mesh, opts, &q, progress)
}
