//! The registry rows of the non-box schemes: ids, aliases, suffixes, catalogue
//! text, beside the family's rules (the registry lists them in catalogue order).

use crate::schemes::entry::{About, Entry};
use crate::schemes::options::ids::{NONBOX, NONBOX_4DIR};

/// The rows, in catalogue order.
pub static ENTRIES: &[Entry] = &[
    Entry::new(
        NONBOX,
        &["non-box"],
        About {
            family: "non-box subdivision [Huang]: four-directional S_3^1 non-box splines, quad variant with face control vertices (FCVs)",
            input: "any polygon mesh (FCVs: face barycentres, scaled barycentres or an FCV file); boundaries: cubic B-spline V/E rules, ghost-FCV NFCV rule (fairsub's reconstruction)",
            patches: "cubic S_3^1 triangles (4 per regular quad cell, as degenerate bi-3 patches); rings of 12n triangles per extraordinary vertex; G^1 cap (bi-4/bi-5, C^1 to the ring in the cells' chart; Coons fill where the ring is incomplete); CAD faces (STEP, IGES): one per patch in every --faces mode (triangles form no tensor grid)",
            smoothness: "C^1 with the convex hull property (all weights non-negative); C^1 at extraordinary vertices (lambda = 1/2 + cos(2 pi / k) / 4)",
            valences: "all",
            status: "available",
        },
        &super::DESCRIPTOR,
    ),
    Entry::new(
        NONBOX_4DIR,
        &["non-box-4dir"],
        About {
            family: "non-box subdivision [Huang], four-directional variant: 1-4 split of quasi-four-directional triangle meshes",
            input: "quasi-four-directional triangle meshes (vertex types found from the topology), or any polygon mesh (triangulated around barycentric FCVs)",
            patches: "as nonbox (the same limit surface)",
            smoothness: "as nonbox",
            valences: "all",
            status: "available",
        },
        &super::DESCRIPTOR_4DIR,
    ),
];
