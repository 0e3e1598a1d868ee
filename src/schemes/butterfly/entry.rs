//! The registry rows of the modified butterfly scheme: ids, aliases, suffixes, catalogue
//! text, beside the family's rules (the registry lists them in catalogue order).

use crate::schemes::entry::{About, Entry};
use crate::schemes::options::ids::BUTTERFLY;

/// The rows, in catalogue order.
pub static ENTRIES: &[Entry] = &[Entry::new(
    BUTTERFLY,
    &["modified-butterfly"],
    About {
        family: "modified butterfly [ZSS96]: interpolating triangle scheme, 8-point regular stencil (tension w = 0), extraordinary rules for valence 3, 4, >= 5",
        input: "triangle meshes; boundaries: 4-point rule on boundary edges, ghost points by reflection near the boundary (OpenMesh's rules)",
        patches: "none (--levels only; the vertices are their own limit points, --limit keeps them; no --rings)",
        smoothness: "C^1 (interpolating)",
        valences: "all",
        status: "available (refinement, analysis on the one-ring)",
    },
    &super::DESCRIPTOR,
)];
