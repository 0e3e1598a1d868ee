//! Which rules a QAS+ scheme (and its variants) uses at each valence, in one place for the mesh
//! caps, the analysis and the reports:
//!
//! | valence | `--rules printed` (default) | `--rules derived` |
//! | --- | --- | --- |
//! | 3 | EG's printed rules (the paper keeps the earlier QAS there) | EG's derived rules |
//! | 4 | regular bi-4 refinement (EG's [`crate::schemes::eg::EgRules::regular`]) | the same |
//! | 5, 6, 7 | the printed tables `K^n`, `T_n` (Appendix C) | `qas-plus-derived` |
//! | 8..=16 | `qas-plus-derived` ([`super::derive`]) | the same |
//! | 17 and more | none: the fallback (`--fallback catmull-clark` or `error`) | the same |
//!
//! Valence 3: the derivation runs there too and its certificate holds (rho(M_d) = 0.2448 <
//! 1/4), but with a thin margin against the subsubdominant 1/4 (curvature converges slowly), and
//! under the accelerated variants' `S` (lambda^2 = 0.16) it would not bound the curvature; so
//! EG's rules stay in use at 3 and the derived QAS+ table of valence 3 is offered only through the
//! library ([`super::derive::derived_rules`]). Valence 4 has no QAS+ table form (the derivation
//! module explains why).

use super::derive;
use super::{Qas, QasRules, tables};
use crate::error::Result;
use crate::schemes::descriptor::{Fallback, RulesChoice, RulesOrigin, SchemeId, ValenceRules};
use crate::schemes::eg::derive::MAX_VALENCE;
use crate::schemes::eg::select::{self as eg_select, Selected as EgSelected};

/// The rules of one valence.
// One value per valence and cap, never stored in bulk: boxing the tables would only add an
// indirection to every use.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone)]
pub enum QasSelected {
    /// QAS+ tables, printed or derived.
    Qas {
        /// The scheme with its tables.
        qas: Qas,
        /// Printed or derived.
        origin: RulesOrigin,
    },
    /// EG's rules: printed or derived at valence 3 ([`RulesOrigin::Borrowed`]), regular bi-4 at
    /// valence 4.
    Eg(EgSelected),
}

impl QasSelected {
    /// Where the rules come from ([`RulesOrigin::Borrowed`] for EG's at valence 3).
    pub fn origin(&self) -> RulesOrigin {
        match self {
            QasSelected::Qas { origin, .. } => *origin,
            QasSelected::Eg(e) if e.origin == RulesOrigin::Regular => RulesOrigin::Regular,
            QasSelected::Eg(_) => RulesOrigin::Borrowed,
        }
    }
}

/// Whether the paper prints complete QAS+ tables at valence `n` (5, 6, 7).
pub fn printed_exists(n: usize) -> bool {
    tables::COMPLETE_VALENCES.contains(&n)
}

/// Where the rules of valence `n` come from under `choice` (`None`: no rules, the fallback).
pub fn origin(n: usize, choice: RulesChoice) -> Option<RulesOrigin> {
    match n {
        3 => Some(RulesOrigin::Borrowed),
        4 => Some(RulesOrigin::Regular),
        _ if (5..=MAX_VALENCE).contains(&n) => {
            Some(if printed_exists(n) && choice == RulesChoice::Printed {
                RulesOrigin::Printed
            } else {
                RulesOrigin::Derived
            })
        }
        _ => None,
    }
}

/// The rules of valence `n` under `choice`; `None` where no construction covers `n`.
pub fn select(n: usize, choice: RulesChoice) -> Result<Option<QasSelected>> {
    let Some(o) = origin(n, choice) else {
        return Ok(None);
    };
    Ok(Some(match o {
        RulesOrigin::Borrowed | RulesOrigin::Regular => {
            QasSelected::Eg(eg_select::select(n, choice)?.expect("EG covers 3 and 4"))
        }
        RulesOrigin::Derived => QasSelected::Qas {
            qas: Qas::with_rules(derive::derived_rules(n)?.clone()),
            origin: o,
        },
        _ => QasSelected::Qas {
            qas: Qas::with_rules(QasRules::new(n)?),
            origin: o,
        },
    }))
}

/// The name of the rules of scheme `id` at valence `n` in notes and reports: the scheme's name
/// for printed tables, `qas-plus (derived rules, n = 8)` for derived ones, EG's name (with its
/// own derived label) at valence 3.
pub fn label(id: SchemeId, n: usize, sel: &QasSelected) -> String {
    match sel {
        QasSelected::Qas {
            origin: RulesOrigin::Derived,
            ..
        } => format!("{id} (derived rules, n = {n})"),
        QasSelected::Qas { .. } => id.name().to_string(),
        QasSelected::Eg(e) => eg_select::label(n, e.origin),
    }
}

/// What `fairsub info` and `fairsub schemes` say about valence `n` for scheme `id`.
pub fn valence_rules(
    id: SchemeId,
    n: usize,
    choice: RulesChoice,
    fallback: Fallback,
) -> ValenceRules {
    let (origin, rules) = match origin(n, choice) {
        Some(RulesOrigin::Printed) => (
            RulesOrigin::Printed,
            format!("{id} (printed tables K^{n}, T_{n})"),
        ),
        Some(RulesOrigin::Derived) => (
            RulesOrigin::Derived,
            format!("{id} (derived rules, n = {n})"),
        ),
        Some(RulesOrigin::Regular) => (RulesOrigin::Regular, "regular bi-4 refinement".into()),
        Some(o) => {
            let eg = eg_select::valence_rules(n, choice, fallback);
            (
                o,
                format!("{} ({id} has no rules of its own here)", eg.rules),
            )
        }
        None => (RulesOrigin::Fallback, eg_select::fallback_words(fallback)),
    };
    ValenceRules {
        valence: n,
        origin,
        rules,
    }
}

/// The message of `--fallback error` at an uncovered valence (after "vertex V has").
pub fn no_rules(id: SchemeId, n: usize) -> String {
    format!(
        "valence {n}: {id} has rules for valences 3..={MAX_VALENCE} only (printed tables for 5, 6, 7, \
         EG's rules at 3, regular bi-4 at 4, fairsub's derived tables elsewhere); use --fallback {}",
        crate::schemes::options::ids::CATMULL_CLARK
    )
}
