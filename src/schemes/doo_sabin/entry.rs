//! The registry rows of Doo-Sabin and DS^CC: ids, aliases, suffixes, catalogue
//! text, beside the family's rules (the registry lists them in catalogue order).

use crate::schemes::entry::{About, Entry};
use crate::schemes::options::ids::{DOO_SABIN, DOO_SABIN_CC};

/// The rows, in catalogue order.
pub static ENTRIES: &[Entry] = &[
    Entry::new(
        DOO_SABIN,
        &["ds"],
        About {
            family: "classic dual quad scheme [DS78], weights of the Doo-Sabin paper",
            input: "any polygon mesh (--rings: interior vertices of valence 2 get one Doo-Sabin step first, --prepare); boundaries: Chaikin points on boundary edges (fairsub's rules), --boundary edge-and-corner (default: corners of one face kept), edge-only (Chaikin through the corners) or none (what a boundary rule makes is not written; fairsub's dual reading of OpenSubdiv's modes); --rings: infinitely sharp creases by cutting the net",
            patches: "bi-2 per regular vertex (Chaikin boundaries via doubled boundary layer); rings of 3n bi-2 patches per n-gon (from level 2 for an n-valent vertex); G^1 cap (centroid fill where the ring is incomplete)",
            smoothness: "C^1 (bi-2 on regular parts)",
            valences: "all facet sizes",
            status: "available",
        },
        &super::DESCRIPTOR,
    ),
    Entry::new(
        DOO_SABIN_CC,
        &["ds-cc"],
        About {
            family: "DS^CC: face-corner point = mean of vertex, face centroid and the two edge midpoints",
            input: "any polygon mesh (--rings: interior vertices of valence 2 get one DS^CC step first, --prepare); boundaries as doo-sabin",
            patches: "as doo-sabin: bi-2 per regular vertex; rings of 3n bi-2 patches per n-gon; G^1 cap (centroid fill where the ring is incomplete)",
            smoothness: "C^1",
            valences: "all facet sizes",
            status: "available",
        },
        &super::DESCRIPTOR_CC,
    ),
];
