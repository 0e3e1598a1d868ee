//! The registry rows of Catmull-Clark: ids, aliases, suffixes, catalogue
//! text, beside the family's rules (the registry lists them in catalogue order).

use crate::schemes::entry::{About, Entry};
use crate::schemes::options::ids::CATMULL_CLARK;

/// The rows, in catalogue order.
pub static ENTRIES: &[Entry] = &[Entry::new(
    CATMULL_CLARK,
    &["cc"],
    About {
        family: "classic primal quad scheme [CC78]",
        input: "any polygon mesh (one step makes it all quads); with --levels OpenSubdiv's boundary options (default edge-and-corner), sharp features and face-varying UVs (--fvar, default all)",
        patches: "bi-3 on regular quads; rings of 3n bi-3 patches per extraordinary vertex; G^1 cap (bi-4/bi-5, C^1 to the last ring; an open fan of bi-4 patches at boundary vertices; Hermite-Coons fill on creases and where the ring is incomplete)",
        smoothness: "C^2 on regular parts, C^1 at extraordinary vertices",
        valences: "all",
        status: "available",
    },
    &super::DESCRIPTOR,
)];
