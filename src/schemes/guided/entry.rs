//! The registry rows of guided subdivision: ids, aliases, suffixes, catalogue
//! text, beside the family's rules (the registry lists them in catalogue order).

use crate::schemes::entry::{About, Entry, Suffix};
use crate::schemes::options::ids::{GUIDED_BI3_MACRO, GUIDED_BI4_MACRO, GUIDED_BI5, GUIDED_BI6};
use crate::schemes::options::{ChiKind, GuideDegree};

/// The guided schemes' suffixes: `-g4` / `-g3` (guide degree), then `-half` (contraction 1/2).
pub const GUIDED_SUFFIXES: &[Suffix] = &[
    Suffix {
        text: "-g4",
        set: |p| p.guide = Some(GuideDegree::Bi4),
    },
    Suffix {
        text: "-g3",
        set: |p| p.guide = Some(GuideDegree::Bi3),
    },
    Suffix {
        text: "-half",
        set: |p| p.chi = Some(ChiKind::Half),
    },
];

/// The rows, in catalogue order.
pub static ENTRIES: &[Entry] = &[
    Entry::new(
        GUIDED_BI5,
        &[],
        About {
            family: "guided subdivision [Karciauskas-Peters]: bi-5 rings sampled from a G^2 bi-5 guide through L^-1 o lambda^l chi (Catmull-Clark's chi and lambda; suffix -half: QAS+'s chi, lambda 1/2; -g4/-g3: bi-4/bi-3 guide)",
            input: "Catmull-Clark nets (as eg); guide target: fairsub's guide-fit F_4 (the paper's [KP15] target is not in the corpus)",
            patches: "bi-3 on regular quads; K rings of 3n bi-5 patches per extraordinary vertex; G^1 bi-6 cap C^1 to the last ring",
            smoothness: "C^2 rings and joins, curvature bounded at the centre; spectrum lambda^s, s = 0..10, multiplicities of table (5)",
            valences: "3, 5..16 (4 is regular); -half: 5..10 (others use Catmull-Clark's chi)",
            status: "available (patches)",
        },
        &super::descriptor::BI5,
    )
    .with_suffixes(GUIDED_SUFFIXES),
    Entry::new(
        GUIDED_BI6,
        &[],
        About {
            family: "guided subdivision: bi-6 rings from 4 x 4 corner jets averaged (Fig. 2b), otherwise as guided-bi5",
            input: "as guided-bi5",
            patches: "bi-3 on regular quads; K rings of 3n bi-6 patches; G^1 bi-6 cap C^1 to the last ring",
            smoothness: "C^2 rings and joins (C^2 at the centre in the limit)",
            valences: "as guided-bi5",
            status: "available (patches)",
        },
        &super::descriptor::BI6,
    )
    .with_suffixes(GUIDED_SUFFIXES),
    Entry::new(
        GUIDED_BI4_MACRO,
        &[],
        About {
            family: "guided subdivision, Section 6.2: rings of 2 x 2 bi-4 macro patches (C^3 inner knot), fairsub's derivation (figures lost)",
            input: "as guided-bi5",
            patches: "bi-3 on regular quads; K rings of 12n bi-4 patches; fairsub's split G^1 cap, 2 x 2 bi-4 pieces per sector",
            smoothness: "C^2 rings and joins, curvature bounded at the centre",
            valences: "as guided-bi5",
            status: "reconstruction (rings only)",
        },
        &super::descriptor::BI4_MACRO,
    )
    .with_suffixes(GUIDED_SUFFIXES),
    Entry::new(
        GUIDED_BI3_MACRO,
        &[],
        About {
            family: "guided subdivision, Section 6.2: rings of 3 x 3 bi-3 macro patches (C^2 knots), fairsub's derivation (figures lost)",
            input: "as guided-bi5",
            patches: "bi-3 on regular quads; K rings of 27n bi-3 patches; fairsub's split G^1 cap, 3 x 3 bi-5 pieces per sector",
            smoothness: "C^2 rings and joins, curvature bounded at the centre",
            valences: "as guided-bi5",
            status: "reconstruction (rings only)",
        },
        &super::descriptor::BI3_MACRO,
    )
    .with_suffixes(GUIDED_SUFFIXES),
];
