//! The registry rows of EG: ids, aliases, suffixes, catalogue
//! text, beside the family's rules (the registry lists them in catalogue order).

use crate::schemes::entry::{About, DERIVED_SUFFIX, Entry};
use crate::schemes::options::ids::EG;

/// The rows, in catalogue order.
pub static ENTRIES: &[Entry] = &[
    Entry::new(
        EG,
        &[],
        About {
            family: "Evolving Guide subdivision [Karciauskas-Peters]: bi-4 rings joining bi-3 surroundings C^2",
            input: "Catmull-Clark nets (quads; one local Catmull-Clark step where extraordinary vertices touch or n-gons occur)",
            patches: "bi-3 on regular quads; K rings of 3n bi-4 patches per extraordinary vertex; G^1 cap (bi-4/bi-5) C^1 to the last ring",
            smoothness: "C^2 rings and joins, C^1 at the extraordinary point; mu/lambda^2 = 1.00015 (n=3), 1.00016 (n=5); derived rules: Catmull-Clark's lambda, mu/lambda^2 0.997..1.0006",
            valences: "3, 5 printed; 4 = bi-4 refinement; 6..16 fairsub's derived rules (eg-derived; the text lost 6..10; --rules derived or suffix -derived: also at 3, 5); above 16: Catmull-Clark fallback or error",
            status: "available (patches; printed 3, 5; derived 6..16, a reconstruction approximating the printed arrays)",
        },
        &super::DESCRIPTOR,
    )
    .with_suffixes(DERIVED_SUFFIX),
];
