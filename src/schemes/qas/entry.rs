//! The registry rows of the QAS+ schemes: ids, aliases, suffixes, catalogue
//! text, beside the family's rules (the registry lists them in catalogue order).

use crate::schemes::entry::{About, DERIVED_SUFFIX, Entry};
use crate::schemes::options::ids::{QAS_04, QAS_05_04, QAS_PLUS, QAS_PLUS_BI3};

/// The rows, in catalogue order.
pub static ENTRIES: &[Entry] = &[
    Entry::new(
        QAS_PLUS,
        &["qas-plus-chi"],
        About {
            family: "QAS+^4 quadratic-attraction subdivision [Karciauskas-Peters], contraction 1/2",
            input: "Catmull-Clark nets (as eg); initial quadratic expansion by fairsub's qas-fit",
            patches: "bi-3 on regular quads; K rings of 3n bi-4 patches per extraordinary vertex; G^1 cap (bi-4/bi-5) C^1 to the last ring",
            smoothness: "C^2 rings and joins, curvature bounded (rho(M_d) < 0.13621 < 1/4; derived tables 0.1253..0.1297)",
            valences: "5, 6, 7 printed; 8..16 fairsub's derived tables (qas-plus-derived; --rules derived or suffix -derived: also at 5..7); 3 uses eg's rules, 4 bi-4 refinement; above 16: Catmull-Clark fallback or error",
            status: "available (patches; printed 5..7; derived 8..16, a reconstruction approximating the printed tables)",
        },
        &super::DESCRIPTOR,
    )
    .with_suffixes(DERIVED_SUFFIX),
    Entry::new(
        QAS_PLUS_BI3,
        &[],
        About {
            family: "QAS+^3: bi-3 rings (2 x 2 macro-patches) through fairsub's derived bijection T_3^4",
            input: "as qas-plus",
            patches: "bi-3 on regular quads; K rings of 12n bi-3 patches; fairsub's split G^1 cap, 2 x 2 bi-4 pieces per sector",
            smoothness: "C^2 rings and joins, curvature bounded (rho(M_d) = 0.136252 < 0.13626 at n = 5)",
            valences: "as qas-plus",
            status: "available (patches; T_3^4 derived: the earlier paper's formulas are not in the corpus)",
        },
        &super::DESCRIPTOR_BI3,
    )
    .with_suffixes(DERIVED_SUFFIX),
    Entry::new(
        QAS_04,
        &[],
        About {
            family: "QAS+^4 accelerated: lambda = 0.4 in the restriction S (tables unchanged)",
            input: "as qas-plus",
            patches: "as qas-plus",
            smoothness: "curvature bounded (rho(M_d) < 0.16 = lambda^2)",
            valences: "as qas-plus",
            status: "available (patches)",
        },
        &super::DESCRIPTOR_04,
    )
    .with_suffixes(DERIVED_SUFFIX),
    Entry::new(
        QAS_05_04,
        &[],
        About {
            family: "QAS+^4 with the gradual schedule 0.5, 0.5, 0.475, 0.475, 0.45, 0.45, then 0.4",
            input: "as qas-plus",
            patches: "as qas-plus",
            smoothness: "as qas-0.4",
            valences: "as qas-plus",
            status: "available (patches)",
        },
        &super::DESCRIPTOR_05_04,
    )
    .with_suffixes(DERIVED_SUFFIX),
];
