//! The registry rows of Kobbelt's sqrt(3) subdivision: ids, aliases, suffixes, catalogue
//! text, beside the family's rules (the registry lists them in catalogue order).

use crate::schemes::entry::{About, Entry};
use crate::schemes::options::ids::SQRT3;

/// The rows, in catalogue order.
pub static ENTRIES: &[Entry] = &[Entry::new(
    SQRT3,
    &["sqrt-3"],
    About {
        family: "Kobbelt's sqrt(3) subdivision [Kob00]: face points, edge flips; approximating",
        input: "triangle meshes; boundaries: Kobbelt's rule (boundary kept on odd steps, trisected by the ternary cubic B-spline rule on even steps)",
        patches: "none (--levels, --limit only; no --rings)",
        smoothness: "C^2 on regular parts, C^1 at extraordinary vertices",
        valences: "all",
        status: "available (refinement, limit positions, analysis)",
    },
    &super::DESCRIPTOR,
)];
