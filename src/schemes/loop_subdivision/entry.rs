//! The registry rows of Loop: ids, aliases, suffixes, catalogue
//! text, beside the family's rules (the registry lists them in catalogue order).

use crate::schemes::entry::{About, Entry};
use crate::schemes::options::ids::LOOP;

/// The rows, in catalogue order.
pub static ENTRIES: &[Entry] = &[Entry::new(
    LOOP,
    &[],
    About {
        family: "classic triangle scheme [Loo87], Loop's original beta",
        input: "triangle meshes; with --levels OpenSubdiv's boundary options (default edge-and-corner: corners stay put), sharp features and face-varying UVs (--fvar, default all)",
        patches: "quartic box-spline triangles (as degenerate bi-4 patches), regular boundary triangles included; rings of 3n triangles per extraordinary vertex; G^1 cap of n kites (bi-4/bi-5, C^1 to the last ring; open triangle fans at boundary vertices); CAD faces (STEP, IGES): one per patch in every --faces mode (triangles form no tensor grid)",
        smoothness: "C^2 on regular parts, C^1 at extraordinary vertices",
        valences: "all",
        status: "available",
    },
    &super::DESCRIPTOR,
)];
