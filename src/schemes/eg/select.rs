//! Which EG rules a valence gets, in one place for the mesh caps, the analysis and the reports:
//!
//! | valence | `--rules printed` (default) | `--rules derived` |
//! | --- | --- | --- |
//! | 3, 5 | the paper's printed arrays ([`EgRules::new`]) | `eg-derived` ([`super::derive`]) |
//! | 4 | regular bi-4 refinement ([`EgRules::regular`]) | the same |
//! | 6..=16 | `eg-derived` (the text lost these arrays) | the same |
//! | 17 and more | none: the fallback (`--fallback catmull-clark` or `error`) | the same |
//!
//! The derived rules carry their own name in every note and report
//! (`eg (derived rules, n = 7)`), so they are never mistaken for the published ones.

use super::derive::{self, MAX_VALENCE};
use super::{EgRules, tables};
use crate::error::Result;
use crate::schemes::descriptor::{Fallback, RulesChoice, RulesOrigin, ValenceRules};
use crate::schemes::options::ids;

/// The rules of one valence with their origin.
#[derive(Debug, Clone)]
pub struct Selected {
    /// The rules.
    pub rules: EgRules,
    /// Printed, regular or derived.
    pub origin: RulesOrigin,
}

/// Whether the paper prints complete rules at valence `n` (3 and 5).
pub fn printed_exists(n: usize) -> bool {
    tables::COMPLETE_VALENCES.contains(&n)
}

/// Whether some construction gives EG rules at valence `n` (3..=16).
pub fn covered(n: usize) -> bool {
    (3..=MAX_VALENCE).contains(&n)
}

/// Where the rules of valence `n` come from under `choice` (`None`: no rules, the fallback).
pub fn origin(n: usize, choice: RulesChoice) -> Option<RulesOrigin> {
    if n == 4 {
        return Some(RulesOrigin::Regular);
    }
    if !covered(n) {
        return None;
    }
    Some(if printed_exists(n) && choice == RulesChoice::Printed {
        RulesOrigin::Printed
    } else {
        RulesOrigin::Derived
    })
}

/// The rules of valence `n` under `choice`; `None` where no construction covers `n`. The
/// derived rules come from the per-process cache ([`derive::derived_rules`]).
pub fn select(n: usize, choice: RulesChoice) -> Result<Option<Selected>> {
    let Some(origin) = origin(n, choice) else {
        return Ok(None);
    };
    let rules = match origin {
        RulesOrigin::Derived => derive::derived_rules(n)?.clone(),
        _ => EgRules::new(n)?,
    };
    Ok(Some(Selected { rules, origin }))
}

/// The name of the rules in notes and reports: `eg` for the printed and the regular rules,
/// `eg (derived rules, n = 7)` for the derived ones.
pub fn label(n: usize, origin: RulesOrigin) -> String {
    match origin {
        RulesOrigin::Derived => format!("{} (derived rules, n = {n})", ids::EG),
        _ => ids::EG.name().to_string(),
    }
}

/// What `fairsub info` and `fairsub schemes` say about valence `n`.
pub fn valence_rules(n: usize, choice: RulesChoice, fallback: Fallback) -> ValenceRules {
    let (origin, rules) = match origin(n, choice) {
        Some(RulesOrigin::Printed) => (
            RulesOrigin::Printed,
            format!("{} (printed rules, n = {n})", ids::EG),
        ),
        Some(RulesOrigin::Regular) => (RulesOrigin::Regular, "regular bi-4 refinement".into()),
        Some(o) => (o, label(n, o)),
        None => (RulesOrigin::Fallback, fallback_words(fallback)),
    };
    ValenceRules {
        valence: n,
        origin,
        rules,
    }
}

/// The fallback in words.
pub fn fallback_words(fallback: Fallback) -> String {
    match fallback {
        Fallback::CatmullClark => {
            format!(
                "Catmull-Clark rings and fill (--fallback {})",
                ids::CATMULL_CLARK
            )
        }
        Fallback::Error => "an error (--fallback error)".into(),
    }
}

/// The message of `--fallback error` at an uncovered valence (after "vertex V has").
pub fn no_rules(n: usize) -> String {
    format!(
        "valence {n}: EG has rules for valences 3..={MAX_VALENCE} only (printed for 3 and 5, \
         regular bi-4 refinement at 4, fairsub's derived rules elsewhere); use --fallback {}",
        ids::CATMULL_CLARK
    )
}
