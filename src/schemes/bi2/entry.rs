//! The registry rows of the bi-2 family: ids, aliases, suffixes, catalogue
//! text, beside the family's rules (the registry lists them in catalogue order).

use crate::schemes::entry::{About, Entry};
use crate::schemes::options::ids::{BI2_MIXED, PGS, PGS_DSCC, POLAR_BI2, TPS, TPS_ADJUSTABLE};

/// The rows, in catalogue order.
pub static ENTRIES: &[Entry] = &[
    Entry::new(
        PGS,
        &[],
        About {
            family: "Point-Augmented Bi-2 Subdivision [Karciauskas-Peters]: Doo-Sabin with an added central point p per extraordinary facet",
            input: "any polygon mesh (p is added automatically by (1)); facets without a DS-net get one Doo-Sabin step first; --rings: interior vertices of valence 2 get one PGS step first (--prepare); boundaries as doo-sabin",
            patches: "as doo-sabin: bi-2 per regular vertex; rings of 3n bi-2 patches per n-gon; G^1 cap at the limit point (7)",
            smoothness: "C^1; lambda_sub from (10) (> 1/2 for n > 4)",
            valences: "all facet sizes (n = 4 is uniform bi-2)",
            status: "available",
        },
        &super::descriptor::PGS,
    ),
    Entry::new(
        PGS_DSCC,
        &[],
        About {
            family: "PGS after two steps of DS^CC (the paper's pre-processing of prisms)",
            input: "any polygon mesh",
            patches: "as pgs, on the twice DS^CC-refined net",
            smoothness: "C^1",
            valences: "all facet sizes",
            status: "available",
        },
        &super::descriptor::PGS_DSCC,
    ),
    Entry::new(
        POLAR_BI2,
        &["polbs"],
        About {
            family: "Polar Bi-2 Subdivision (PolBS) [Karciauskas-Peters]: radial bi-2 refinement around poles",
            input: "polar layouts (poles with fans of triangles, rings of quads); prism-like n-gon caps become poles at their centroids (or at --pole FACE:X,Y,Z); other elements, and poles and elements that are not separated, as bi2-mixed",
            patches: "bi-2 per regular vertex; rings of n bi-2 patches per pole; collapsed bi-2 cap at the limit point (16), G^1",
            smoothness: "C^1; subdominant 1/2, subsubdominant 1/4",
            valences: "all pole valences",
            status: "available",
        },
        &super::descriptor::POLAR,
    ),
    Entry::new(
        TPS,
        &[],
        About {
            family: "Primal Bi-2 Subdivision (TPS) [Karciauskas-Peters]: ternary bi-2 on quad nets",
            input: "quad nets; other nets are prepared (--prepare): one Catmull-Clark step where faces are not quads, one Doo-Sabin step then one Catmull-Clark step at interior vertices of valence 2 and extraordinary boundary vertices; boundaries with a doubled layer (fairsub's rules)",
            patches: "bi-2 per regular vertex; rings of 2n bi-2 patches per extraordinary vertex (ternary); G^1 cap (bi-4/bi-5) at the limit point (21)",
            smoothness: "C^1; lambda = (5 + 2c + 2 sqrt(c^2 + 5c + 4)) / 27",
            valences: "all interior valences >= 3 (valence 2 and extraordinary boundary vertices: prepared as above)",
            status: "available",
        },
        &super::descriptor::TPS,
    ),
    Entry::new(
        TPS_ADJUSTABLE,
        &[],
        About {
            family: "adjustable TPS, split ratio e = 0.2 or --split-ratio E; alphas of (18) by --alpha-rule (fairsub's reconstruction of the stencils, tps-adjustable-derived: exact e : 1-2e : e knot insertion; reproduces (22))",
            input: "quad nets, prepared as tps",
            patches: "bi-2 with non-uniform knots; rings of 2n patches per extraordinary vertex; cap as tps",
            smoothness: "C^1 (up to per-piece affine reparametrisation across ring sides); lambda from (22)",
            valences: "all interior valences >= 3",
            status: "available (reconstruction)",
        },
        &super::descriptor::TPS_ADJUSTABLE,
    ),
    Entry::new(
        BI2_MIXED,
        &[],
        About {
            family: "bi-2 family combined (Fig. 15): regular bi-2, PGS at facets, TPS at extraordinary vertices, PolBS at poles",
            input: "any polygon mesh: separated elements get their member's rings; elements that are not separated get the family's own separating step (--prepare): TPS's whole-net steps on a net of extraordinary vertices, else the PGS step (the surface is then PGS's); net refinement when all elements are of one kind (else one PGS step first)",
            patches: "bi-2 per regular vertex; per element its scheme's rings and G^1 cap",
            smoothness: "C^1",
            valences: "all",
            status: "available",
        },
        &super::descriptor::MIXED,
    ),
];
