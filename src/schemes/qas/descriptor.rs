//! The descriptors of QAS+ and its variants: exact patches (caps of bi-4 or bi-3 rings on
//! Catmull-Clark nets) and local analysis, with the printed tables where the paper has them and
//! fairsub's derived ones elsewhere ([`super::select`]). QAS+ has no control net of its own to
//! refine.

use super::Qas;
use super::derive::compare::QasComparison;
use super::local::QasFacts;
use super::select::{self, QasSelected};
use super::surface::{Contraction, QasSurface, qas_surface};
use crate::bezier::BezierPatch;
use crate::error::{Error, Result};
use crate::schemes::descriptor::{
    Capabilities, Computed, Descriptor, ExtraFacts, LocalRules, ParamKind, PatchRules, Published,
    RulesChoice, RulesOrigin, SchemeId, Spec, ValenceRules, patch_fn,
};
use crate::schemes::eg::derive::MAX_VALENCE;
use crate::schemes::eg::select as eg_select;
use crate::schemes::eg::surface::EgOptions;
use crate::schemes::local::LocalMatrix;
use crate::schemes::options::ids;

/// Which QAS+ variant.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum QasVariant {
    /// QAS+^4, contraction 1/2.
    Bi4,
    /// QAS+^3 (bi-3 rings through T_3^4), contraction 1/2.
    Bi3,
    /// QAS+^4 with lambda 0.4.
    Fixed04,
    /// QAS+^4 with the gradual schedule 0.5 .. 0.4.
    Gradual,
}

/// A QAS+ scheme.
#[derive(Debug)]
pub struct QasDescriptor {
    /// The variant.
    pub variant: QasVariant,
}

/// The registry's QAS+ row.
pub static DESCRIPTOR: QasDescriptor = QasDescriptor {
    variant: QasVariant::Bi4,
};
/// The registry's QAS+^3 row.
pub static DESCRIPTOR_BI3: QasDescriptor = QasDescriptor {
    variant: QasVariant::Bi3,
};
/// The registry's QAS_0.4 row.
pub static DESCRIPTOR_04: QasDescriptor = QasDescriptor {
    variant: QasVariant::Fixed04,
};
/// The registry's QAS_{0.5,0.4} row.
pub static DESCRIPTOR_05_04: QasDescriptor = QasDescriptor {
    variant: QasVariant::Gradual,
};

impl Descriptor for QasDescriptor {
    /// Sharp features: as Catmull-Clark's host refines them (its rings and cap next to them).
    fn patches_take_features(&self) -> bool {
        true
    }

    /// Exact patches and evaluation: the caps' rings tile each sector's face dyadically in the
    /// d-net's chart ([`crate::schemes::eg::surface`]'s parameter domain).
    fn capabilities(&self) -> Capabilities {
        Capabilities::PATCHES_AND_EVAL
    }

    fn params(&self) -> &'static [ParamKind] {
        match self.variant {
            QasVariant::Bi3 => &[ParamKind::Fallback, ParamKind::Rules],
            _ => &[ParamKind::Fallback, ParamKind::QFile, ParamKind::Rules],
        }
    }

    /// Catmull-Clark's adaptive loop with QAS+ caps (EG's at valence 3).
    fn patch_rules(&self, spec: &Spec) -> Result<Option<Box<dyn PatchRules>>> {
        let (variant, params) = (self.variant, spec.params.clone());
        patch_fn(move |mesh, opts, progress| {
            let o = EgOptions {
                rings: opts.rings,
                fill: opts.fill,
                fallback: params.fallback,
            };
            let q = QasSurface {
                id: variant.id(),
                contraction: variant.contraction(),
                bi3: variant == QasVariant::Bi3,
                rules: params.rules,
                overrides: params.q_overrides.clone(),
            };
            qas_surface(mesh, o, &q, progress)
        })
    }

    fn local_rules(&self, spec: &Spec) -> Result<Option<Box<dyn LocalRules>>> {
        Ok((self.variant != QasVariant::Gradual).then(|| {
            Box::new(QasLocal {
                variant: self.variant,
                choice: spec.params.rules,
            }) as Box<dyn LocalRules>
        }))
    }

    fn valence_rules(&self, spec: &Spec, n: usize) -> Option<ValenceRules> {
        Some(select::valence_rules(
            self.variant.id(),
            n,
            spec.params.rules,
            spec.params.fallback,
        ))
    }
}

impl QasVariant {
    /// The contraction schedule of the variant.
    pub fn contraction(self) -> Contraction {
        match self {
            QasVariant::Bi4 | QasVariant::Bi3 => Contraction::Half,
            QasVariant::Fixed04 => Contraction::Fixed(0.4),
            QasVariant::Gradual => Contraction::Gradual,
        }
    }

    /// The variant's registry id.
    pub fn id(self) -> SchemeId {
        match self {
            QasVariant::Bi4 => ids::QAS_PLUS,
            QasVariant::Bi3 => ids::QAS_PLUS_BI3,
            QasVariant::Fixed04 => ids::QAS_04,
            QasVariant::Gradual => ids::QAS_05_04,
        }
    }
}

/// QAS+'s local analysis (the gradual schedule has no stationary matrix): the matrix of the
/// rules in use, the Section 5 facts, rho(M_d) beside the printed tables' and the bound (for
/// the printed and the derived tables), and the deviation of the derived tables from the
/// printed ones.
struct QasLocal {
    variant: QasVariant,
    choice: RulesChoice,
}

impl QasLocal {
    fn lambda(&self) -> f64 {
        match self.variant {
            QasVariant::Fixed04 => 0.4,
            _ => 0.5,
        }
    }

    fn selected(&self, n: usize, choice: RulesChoice) -> Result<QasSelected> {
        select::select(n, choice)?.ok_or_else(|| {
            Error::Unsupported(format!(
                "valence {n}: {} has rules for valences 3..={MAX_VALENCE} (EG's at 3, regular bi-4 \
                 at 4, printed tables 5..7, derived elsewhere)",
                self.variant.id()
            ))
        })
    }

    /// The Section 5 facts of given tables.
    fn facts(&self, qas: &Qas) -> Result<QasFacts> {
        match self.variant {
            QasVariant::Bi3 => super::local::facts_bi3_of(qas, self.lambda()),
            _ => super::local::facts_of(qas, self.lambda()),
        }
    }
}

impl LocalRules for QasLocal {
    fn matrix(&self, n: usize) -> Result<LocalMatrix> {
        let id = self.variant.id();
        match self.selected(n, self.choice)? {
            QasSelected::Eg(e) => crate::schemes::eg::local::local_matrix_of(
                &e.rules,
                &format!(
                    "{} (used by {id} at n = {n})",
                    eg_select::label(n, e.origin)
                ),
            ),
            sel @ QasSelected::Qas { .. } => {
                let label = select::label(id, n, &sel);
                let QasSelected::Qas { qas, .. } = sel else {
                    unreachable!("matched above")
                };
                match self.variant {
                    QasVariant::Bi3 => {
                        super::local::local_matrix_bi3_of(&qas, self.lambda(), &label)
                    }
                    _ => super::local::local_matrix_of(&qas, self.lambda(), &label),
                }
            }
        }
    }

    /// QAS+^4's: the paper's chi of Section 3 for the printed tables, the derived rules' own
    /// characteristic map for the derived ones, EG's at valences 3 and 4.
    fn characteristic_ring(&self, n: usize) -> Result<(Vec<BezierPatch>, f64)> {
        match self.selected(n, self.choice)? {
            QasSelected::Eg(e) => crate::schemes::eg::local::characteristic_ring_of(&e.rules),
            _ if self.variant != QasVariant::Bi4 => Err(Error::Unsupported(format!(
                "valence {n}: the characteristic map of Section 3 is QAS+^4's"
            ))),
            QasSelected::Qas {
                origin: RulesOrigin::Printed,
                ..
            } => super::local::characteristic_ring(n),
            QasSelected::Qas { qas, .. } => super::local::rules_characteristic_ring_of(&qas),
        }
    }

    /// rho(M_d) beside the printed tables' (5, 6, 7) and beside the bound of Section 5 (QAS+^4)
    /// or 6 (QAS+^3) for n = 5..10, for the printed and for the derived tables.
    fn published(&self, n: usize, _: &Computed<'_>) -> Result<Vec<Published>> {
        let bound = match self.variant {
            QasVariant::Bi4 => super::facts::RHO_MD_BOUND,
            QasVariant::Bi3 => super::facts::RHO_MD_BOUND_BI3,
            _ => return Ok(Vec::new()),
        };
        let in_use = select::origin(n, self.choice);
        let mut out = Vec::new();
        for choice in [RulesChoice::Printed, RulesChoice::Derived] {
            let Some(QasSelected::Qas { qas, origin }) = select::select(n, choice)? else {
                continue;
            };
            if (choice == RulesChoice::Printed) != (origin == RulesOrigin::Printed) {
                continue; // each kind of table once
            }
            let rho = self.facts(&qas)?.m_d_spectral_radius;
            let tag = format!(
                "{}{}",
                if origin == RulesOrigin::Printed {
                    "printed tables"
                } else {
                    "derived tables"
                },
                if in_use == Some(origin) {
                    " (in use)"
                } else {
                    ""
                }
            );
            let of_printed =
                super::facts::rho_md_of_printed(n).filter(|_| self.variant == QasVariant::Bi4);
            if let Some(p) = of_printed {
                out.push(Published::new(
                    format!(
                        "spectral radius of M_d of the printed tables (computed from Appendix C with \
                         the papers README's K layout; the paper states the bound), {tag}"
                    ),
                    p,
                    rho,
                ));
            }
            if super::facts::BOUND_VALENCES.contains(&n) {
                out.push(Published::new(
                    format!(
                        "bound on the spectral radius of M_d (Section {}, n = 5..10: below {bound}), {tag}",
                        if self.variant == QasVariant::Bi4 { 5 } else { 6 }
                    ),
                    bound,
                    rho,
                ));
            }
        }
        Ok(out)
    }

    fn extras(&self, n: usize) -> Result<Vec<ExtraFacts>> {
        let mut out = Vec::new();
        if let QasSelected::Qas { qas, .. } = self.selected(n, self.choice)? {
            let q = self.facts(&qas)?;
            let lines = vec![format!(
                "QAS+: spectral radius of M_d {:.6}; M_q eigenvalues: C^2 {:?}, C^1 {} values, C^1-C^0 {} values (all 1, 1/2 x2, then 1/4)",
                q.m_d_spectral_radius,
                q.m_q_c2
                    .iter()
                    .map(|x| format!("{x:.4}"))
                    .collect::<Vec<_>>(),
                q.m_q_c1.len(),
                q.m_q_c1c0.len()
            )];
            out.push(ExtraFacts {
                key: "qas",
                value: serde_json::to_value(&q).expect("serialisable"),
                lines,
            });
        }
        if (5..=MAX_VALENCE).contains(&n) {
            let c = super::derive::compare::qas_comparison(n)?;
            out.push(ExtraFacts {
                key: "derivation",
                lines: comparison_lines(&c),
                value: serde_json::to_value(&c).expect("serialisable"),
            });
        }
        Ok(out)
    }
}

/// The text report's lines of a comparison.
fn comparison_lines(c: &QasComparison) -> Vec<String> {
    let mut lines = vec![format!("derived tables: {}", c.construction)];
    if c.tables.is_empty() {
        lines.push(format!(
            "derived vs printed: the paper prints no QAS+ tables for n = {}",
            c.n
        ));
        return lines;
    }
    lines.push(format!(
        "derived vs printed tables (units of 1e-5): K max {:.0}, median {:.1}; T max {:.0}, median {:.1} (the printed tables are approximated, not reproduced)",
        c.k_max_e5, c.k_median_e5, c.t_max_e5, c.t_median_e5
    ));
    for t in &c.tables {
        lines.push(format!(
            "  {}: {} entries, max {:.0}, median {:.1}",
            t.table, t.entries, t.max_e5, t.median_e5
        ));
    }
    lines
}
