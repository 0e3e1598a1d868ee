//! EG's descriptor: exact patches (caps of bi-4 rings on Catmull-Clark nets) and local analysis,
//! with the printed rules where the paper has them and fairsub's derived rules elsewhere
//! ([`super::select`]). EG has no control net of its own to refine.

use super::derive::compare::{self, EgComparison};
use super::select::{self, Selected};
use super::surface::{EgOptions, EgRulesProvider, dnet_complex};
use crate::bezier::BezierPatch;
use crate::error::{Error, Result};
use crate::schemes::descriptor::{
    Capabilities, Computed, Descriptor, ExtraFacts, LocalRules, ParamKind, PatchRules, Published,
    RulesChoice, RulesOrigin, Spec, ValenceRules, patch_fn,
};
use crate::schemes::local::{LocalMatrix, spectrum};

/// EG subdivision.
#[derive(Debug)]
pub struct EgDescriptor;

/// The registry's EG row.
pub static DESCRIPTOR: EgDescriptor = EgDescriptor;

impl Descriptor for EgDescriptor {
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
        &[ParamKind::Fallback, ParamKind::Rules]
    }

    /// Catmull-Clark's adaptive loop with EG caps.
    fn patch_rules(&self, spec: &Spec) -> Result<Option<Box<dyn PatchRules>>> {
        let (fallback, choice) = (spec.params.fallback, spec.params.rules);
        patch_fn(move |mesh, opts, progress| {
            let o = EgOptions {
                rings: opts.rings,
                fill: opts.fill,
                fallback,
            };
            dnet_complex(&EgRulesProvider { choice }, mesh, o, progress)
        })
    }

    fn local_rules(&self, spec: &Spec) -> Result<Option<Box<dyn LocalRules>>> {
        Ok(Some(Box::new(EgLocal {
            choice: spec.params.rules,
        })))
    }

    fn valence_rules(&self, spec: &Spec, n: usize) -> Option<ValenceRules> {
        Some(select::valence_rules(
            n,
            spec.params.rules,
            spec.params.fallback,
        ))
    }
}

/// EG's local analysis: the matrix `A_n` of the rules in use, the characteristic ring, the
/// published numbers beside the computed ones (for the printed and the derived rules) and the
/// deviation of the derived rules from the printed arrays.
pub(crate) struct EgLocal {
    /// Printed or derived rules where both exist.
    pub(crate) choice: RulesChoice,
}

impl EgLocal {
    /// The rules in use at valence `n` (an error where none exist).
    pub(crate) fn selected(&self, n: usize) -> Result<Selected> {
        select::select(n, self.choice)?.ok_or_else(|| {
            Error::Unsupported(format!(
                "valence {n}: EG has rules for valences 3..={} (printed 3 and 5, regular 4, derived \
                 elsewhere)",
                super::derive::MAX_VALENCE
            ))
        })
    }
}

/// `mu / lambda^2` of given rules.
fn mu_over_lambda2(sel: &Selected, n: usize) -> Result<f64> {
    let lm = super::local::local_matrix_of(&sel.rules, &select::label(n, sel.origin))?;
    Ok(spectrum(&lm.matrix).mu_over_lambda_squared)
}

impl LocalRules for EgLocal {
    fn matrix(&self, n: usize) -> Result<LocalMatrix> {
        let sel = self.selected(n)?;
        super::local::local_matrix_of(&sel.rules, &select::label(n, sel.origin))
    }

    fn characteristic_ring(&self, n: usize) -> Result<(Vec<BezierPatch>, f64)> {
        super::local::characteristic_ring_of(&self.selected(n)?.rules)
    }

    /// Section 6's claims beside the computed numbers: lambda against Catmull-Clark's, and the
    /// published `mu / lambda^2` (n = 3, 5..10) for the printed rules (3, 5) and for the
    /// derived rules (3, 5..10), whichever is in use.
    fn published(&self, n: usize, c: &Computed<'_>) -> Result<Vec<Published>> {
        let in_use = self.selected(n)?.origin;
        let mut out = vec![Published::new(
            format!(
                "lambda: Catmull-Clark's (Section 6: EG's differs from it by less than {:.0e}), {} in use",
                super::facts::LAMBDA_VS_CATMULL_CLARK,
                origin_words(in_use)
            ),
            crate::schemes::catmull_clark::catmull_clark_lambda(n),
            c.spectrum.lambda,
        )];
        let Some(p) = super::facts::mu_over_lambda2(n) else {
            return Ok(out);
        };
        for choice in [RulesChoice::Printed, RulesChoice::Derived] {
            let Some(sel) = select::select(n, choice)? else {
                continue;
            };
            if choice == RulesChoice::Derived && sel.origin != RulesOrigin::Derived {
                continue; // printed rules only with --rules printed
            }
            if choice == RulesChoice::Printed && sel.origin != RulesOrigin::Printed {
                continue; // 6..10: no printed rules, the derived ones follow
            }
            let computed = if sel.origin == in_use {
                c.spectrum.mu_over_lambda_squared
            } else {
                mu_over_lambda2(&sel, n)?
            };
            out.push(Published::new(
                format!(
                    "mu / lambda^2 (Section 6 table, printed to 5 decimals), {}{}",
                    origin_words(sel.origin),
                    if sel.origin == in_use {
                        " (in use)"
                    } else {
                        ""
                    }
                ),
                p,
                computed,
            ));
        }
        Ok(out)
    }

    /// The deviation of the derived rules from every printed array at this valence (key
    /// `derivation`), in units of 1e-5.
    fn extra(&self, n: usize) -> Result<Option<ExtraFacts>> {
        if n == 4 || !select::covered(n) {
            return Ok(None);
        }
        let c = compare::eg_comparison(n)?;
        Ok(Some(ExtraFacts {
            key: "derivation",
            lines: comparison_lines(&c),
            value: serde_json::to_value(&c).expect("serialisable"),
        }))
    }
}

/// The rules' origin in words.
pub(crate) fn origin_words(o: RulesOrigin) -> &'static str {
    match o {
        RulesOrigin::Printed => "printed rules",
        RulesOrigin::Derived => "derived rules",
        RulesOrigin::Regular => "regular rules",
        RulesOrigin::Borrowed => "another scheme's rules",
        RulesOrigin::Fallback => "the fallback",
    }
}

/// The text report's lines of a comparison.
fn comparison_lines(c: &EgComparison) -> Vec<String> {
    let mut lines = vec![format!("derived rules: {}", c.construction)];
    if c.tables.is_empty() {
        lines.push(format!(
            "derived vs printed: the paper prints no EG arrays for n = {}",
            c.n
        ));
        return lines;
    }
    lines.push(format!(
        "derived vs printed arrays (units of 1e-5): max {:.0}, median {:.1} (the printed arrays are approximated, not reproduced)",
        c.max_e5, c.median_e5
    ));
    for t in &c.tables {
        lines.push(format!(
            "  {}: {} entries, max {:.0}, median {:.1}{}",
            t.table,
            t.entries,
            t.max_e5,
            t.median_e5,
            t.note
                .as_ref()
                .map(|s| format!(" [{s}]"))
                .unwrap_or_default()
        ));
    }
    lines
}
