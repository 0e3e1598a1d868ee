//! Subdivision schemes, one module per family, each written once as stencils.
//!
//! A scheme that refines whole control nets implements [`Scheme`]: one refinement step returns
//! the child net together with the [`StencilTable`] that computes every child point from the
//! parent points. Applying a scheme to positions, composing several levels, building the local
//! subdivision matrix for analysis or re-applying the step to moved points all reuse that one
//! table, so every rule exists exactly once.

pub mod bi2;
pub mod catmull_clark;
pub mod doo_sabin;
pub mod eg;
pub mod guided;
pub mod local;
pub mod loop_subdivision;
pub mod nonbox;
pub mod qas;

mod common;

pub use catmull_clark::CatmullClark;
pub use doo_sabin::{DooSabin, DooSabinCc};
pub use loop_subdivision::Loop;
pub use nonbox::{NonBox, NonBox4Dir};

use crate::error::Result;
use crate::mesh::PolyMesh;
use crate::stencil::StencilTable;

/// The result of one refinement step.
#[derive(Debug, Clone)]
pub struct Refinement {
    /// The child net, its positions already computed by `stencils`.
    pub mesh: PolyMesh,
    /// Row `i` computes child vertex `i` from the parent's vertices.
    pub stencils: StencilTable,
}

/// A subdivision scheme acting on whole control nets.
pub trait Scheme: Sync {
    /// The scheme's name as used on the command line (`catmull-clark`, `loop`, ...).
    fn name(&self) -> &'static str;

    /// One refinement step of the whole net. Errors name the element the scheme cannot handle
    /// (for example a non-triangle face for Loop).
    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement>;

    /// `levels` refinement steps for output: the refined net only. Schemes with a direct kernel
    /// override it to skip the stencil tables, drop each parent level as soon as its child
    /// exists and keep the peak memory close to the size of the result; the default repeats
    /// [`Scheme::refine`]. `progress(level)` is called after each step. Schemes whose steps
    /// depend on more than the net (the knot widths of adjustable TPS, the DS^CC pre-processing
    /// steps of PGS) override it too.
    fn refine_uniform(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        progress: &mut dyn FnMut(usize),
    ) -> Result<PolyMesh> {
        let mut m: Option<PolyMesh> = None;
        for l in 0..levels {
            m = Some(self.refine(m.as_ref().unwrap_or(mesh))?.mesh);
            progress(l + 1);
        }
        Ok(m.unwrap_or_else(|| mesh.clone()))
    }

    /// Stencils of the limit positions of the net's vertices (row `v` for vertex `v`), where the
    /// scheme has closed-form limit masks.
    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        let _ = mesh;
        Err(crate::error::Error::Unsupported(format!(
            "scheme {} has no limit-position masks",
            self.name()
        )))
    }
}

/// Applies `levels` refinement steps ([`Scheme::refine_uniform`]), calling `progress(level)`
/// after each.
pub fn refine_levels(
    scheme: &dyn Scheme,
    mesh: &PolyMesh,
    levels: usize,
    mut progress: impl FnMut(usize),
) -> Result<PolyMesh> {
    scheme.refine_uniform(mesh, levels, &mut progress)
}

/// The stencil table from the control points of `mesh` to the points of its `levels`-th uniform
/// refinement (each step's table composed with the previous ones), with that refined net.
///
/// This is the precomputed form for animation: the topology stays, the control points move, and
/// [`StencilTable::apply_into`] maps new control positions (or any per-point data) straight to
/// the refined level, in parallel over rows and without allocating. `levels = 0` gives the
/// identity.
///
/// The steps are repeated [`Scheme::refine`] calls, so for schemes whose
/// [`Scheme::refine_uniform`] carries state from step to step (the knot widths of adjustable
/// TPS, the DS^CC pre-processing of `pgs-dscc`) the table follows the repeated single step,
/// not that override.
///
/// # Errors
/// Whatever [`Scheme::refine`] reports (for example a face the scheme cannot handle).
pub fn level_stencils(
    scheme: &dyn Scheme,
    mesh: &PolyMesh,
    levels: usize,
) -> Result<(PolyMesh, StencilTable)> {
    let mut fine: Option<PolyMesh> = None;
    let mut table: Option<StencilTable> = None;
    for _ in 0..levels {
        let r = scheme.refine(fine.as_ref().unwrap_or(mesh))?;
        table = Some(match table {
            None => r.stencils,
            Some(t) => r.stencils.compose(&t),
        });
        fine = Some(r.mesh);
    }
    Ok(match (fine, table) {
        (Some(m), Some(t)) => (m, t),
        _ => (mesh.clone(), StencilTable::identity(mesh.num_vertices())),
    })
}

/// Builds the child mesh from topology and stencils: positions are the stencils applied to the
/// parent positions.
pub(crate) fn finish_refinement(
    parent: &PolyMesh,
    stencils: StencilTable,
    face_start: Vec<u32>,
    corners: Vec<u32>,
) -> Result<Refinement> {
    let positions = stencils.apply(parent.positions());
    let mesh = PolyMesh::from_refinement(positions, face_start, corners)?;
    Ok(Refinement { mesh, stencils })
}

/// What `fairsub schemes` tells about a scheme.
#[derive(Debug, Clone, serde::Serialize)]
pub struct SchemeInfo {
    /// Command-line name.
    pub name: &'static str,
    /// Family and paper.
    pub family: &'static str,
    /// Input nets it accepts.
    pub input: &'static str,
    /// Patches it outputs (degree and layout), if it has exact patch output.
    pub patches: &'static str,
    /// Smoothness claimed by its paper (or the classical result).
    pub smoothness: &'static str,
    /// Valences / element sizes with rules.
    pub valences: &'static str,
    /// Whether refinement (`--levels`) is available.
    pub refine: bool,
    /// Whether exact patch output (`--rings`) is available.
    pub rings: bool,
    /// Implementation status.
    pub status: &'static str,
}

/// Every scheme fairsub knows, implemented or planned, with its properties.
pub fn catalog() -> Vec<SchemeInfo> {
    vec![
        SchemeInfo {
            name: "catmull-clark",
            family: "classic primal quad scheme [CC78]",
            input: "any polygon mesh (one step makes it all quads); boundaries with edge-only interpolation",
            patches: "bi-3 on regular quads; rings of 3n bi-3 patches per extraordinary vertex; Hermite-Coons fill",
            smoothness: "C^2 on regular parts, C^1 at extraordinary vertices",
            valences: "all",
            refine: true,
            rings: true,
            status: "available",
        },
        SchemeInfo {
            name: "doo-sabin",
            family: "classic dual quad scheme [DS78], weights of the Doo-Sabin paper",
            input: "any polygon mesh; boundaries: Chaikin points on boundary edges (fairsub's rules)",
            patches: "bi-2 per regular vertex (Chaikin boundaries via doubled boundary layer); rings of 3n bi-2 patches per n-gon (from level 2 for an n-valent vertex); centroid fill",
            smoothness: "C^1 (bi-2 on regular parts)",
            valences: "all facet sizes",
            refine: true,
            rings: true,
            status: "available",
        },
        SchemeInfo {
            name: "doo-sabin-cc",
            family: "DS^CC: face-corner point = mean of vertex, face centroid and the two edge midpoints",
            input: "any polygon mesh; boundaries as doo-sabin",
            patches: "as doo-sabin: bi-2 per regular vertex; rings of 3n bi-2 patches per n-gon; centroid fill",
            smoothness: "C^1",
            valences: "all facet sizes",
            refine: true,
            rings: true,
            status: "available",
        },
        SchemeInfo {
            name: "loop",
            family: "classic triangle scheme [Loo87], Loop's original beta",
            input: "triangle meshes; boundaries as OpenSubdiv (corners stay put)",
            patches: "quartic box-spline triangles (as degenerate bi-4 patches), regular boundary triangles included; rings of 3n triangles per extraordinary vertex; Hermite fill",
            smoothness: "C^2 on regular parts, C^1 at extraordinary vertices",
            valences: "all",
            refine: true,
            rings: true,
            status: "available",
        },
        SchemeInfo {
            name: "nonbox",
            family: "non-box subdivision [Huang]: four-directional S_3^1 non-box splines, quad variant with face control vertices (FCVs)",
            input: "any polygon mesh (FCVs: face barycentres, scaled barycentres or an FCV file); boundaries: cubic B-spline V/E rules, ghost-FCV NFCV rule (fairsub's reconstruction)",
            patches: "cubic S_3^1 triangles (4 per regular quad cell, as degenerate bi-3 patches); rings of 12n triangles per extraordinary vertex; Hermite fill",
            smoothness: "C^1 with the convex hull property (all weights non-negative); C^1 at extraordinary vertices (lambda = 1/2 + cos(2 pi / k) / 4)",
            valences: "all",
            refine: true,
            rings: true,
            status: "available",
        },
        SchemeInfo {
            name: "nonbox-4dir",
            family: "non-box subdivision [Huang], four-directional variant: 1-4 split of quasi-four-directional triangle meshes",
            input: "quasi-four-directional triangle meshes (vertex types found from the topology), or any polygon mesh (triangulated around barycentric FCVs)",
            patches: "as nonbox (the same limit surface)",
            smoothness: "as nonbox",
            valences: "all",
            refine: true,
            rings: true,
            status: "available",
        },
        SchemeInfo {
            name: "eg",
            family: "Evolving Guide subdivision [Karciauskas-Peters]: bi-4 rings joining bi-3 surroundings C^2",
            input: "Catmull-Clark nets (quads; one local Catmull-Clark step where extraordinary vertices touch or n-gons occur)",
            patches: "bi-3 on regular quads; K rings of 3n bi-4 patches per extraordinary vertex; bi-4 fill C^1 to the last ring",
            smoothness: "C^2 rings and joins, C^1 at the extraordinary point; mu/lambda^2 = 1.00015 (n=3), 1.00016 (n=5)",
            valences: "3, 5 published (4 = bi-4 refinement); 6..10 lost in the text: Catmull-Clark fallback or error",
            refine: false,
            rings: true,
            status: "available (patches; valences 3 and 5)",
        },
        SchemeInfo {
            name: "qas-plus",
            family: "QAS+^4 quadratic-attraction subdivision [Karciauskas-Peters], contraction 1/2",
            input: "Catmull-Clark nets (as eg); initial quadratic expansion by fairsub's qas-fit",
            patches: "bi-3 on regular quads; K rings of 3n bi-4 patches per extraordinary vertex; bi-4 fill C^1 to the last ring",
            smoothness: "C^2 rings and joins, curvature bounded (rho(M_d) < 0.13621 < 1/4)",
            valences: "5, 6, 7 published; 3 uses eg; others fall back to Catmull-Clark or error",
            refine: false,
            rings: true,
            status: "available (patches; valences 5..7)",
        },
        SchemeInfo {
            name: "qas-plus-bi3",
            family: "QAS+^3: bi-3 rings (2 x 2 macro-patches) through fairsub's derived bijection T_3^4",
            input: "as qas-plus",
            patches: "bi-3 on regular quads; K rings of 12n bi-3 patches; bi-3 fill (C^0, 2 x 2 Coons per sector)",
            smoothness: "C^2 rings and joins, curvature bounded (rho(M_d) = 0.136252 < 0.13626 at n = 5)",
            valences: "as qas-plus",
            refine: false,
            rings: true,
            status: "available (patches; T_3^4 derived: the earlier paper's formulas are not in the corpus)",
        },
        SchemeInfo {
            name: "qas-0.4",
            family: "QAS+^4 accelerated: lambda = 0.4 in the restriction S (tables unchanged)",
            input: "as qas-plus",
            patches: "as qas-plus",
            smoothness: "curvature bounded (rho(M_d) < 0.16 = lambda^2)",
            valences: "as qas-plus",
            refine: false,
            rings: true,
            status: "available (patches)",
        },
        SchemeInfo {
            name: "qas-0.5-0.4",
            family: "QAS+^4 with the gradual schedule 0.5, 0.5, 0.475, 0.475, 0.45, 0.45, then 0.4",
            input: "as qas-plus",
            patches: "as qas-plus",
            smoothness: "as qas-0.4",
            valences: "as qas-plus",
            refine: false,
            rings: true,
            status: "available (patches)",
        },
        SchemeInfo {
            name: "pgs",
            family: "Point-Augmented Bi-2 Subdivision [Karciauskas-Peters]: Doo-Sabin with an added central point p per extraordinary facet",
            input: "any polygon mesh (p is added automatically by (1)); facets without a DS-net get one Doo-Sabin step first; boundaries as doo-sabin",
            patches: "as doo-sabin: bi-2 per regular vertex; rings of 3n bi-2 patches per n-gon; fill centred at the limit point (7)",
            smoothness: "C^1; lambda_sub from (10) (> 1/2 for n > 4)",
            valences: "all facet sizes (n = 4 is uniform bi-2)",
            refine: true,
            rings: true,
            status: "available",
        },
        SchemeInfo {
            name: "pgs-dscc",
            family: "PGS after two steps of DS^CC (the paper's pre-processing of prisms)",
            input: "any polygon mesh",
            patches: "as pgs, on the twice DS^CC-refined net",
            smoothness: "C^1",
            valences: "all facet sizes",
            refine: true,
            rings: true,
            status: "available",
        },
        SchemeInfo {
            name: "polar-bi2",
            family: "Polar Bi-2 Subdivision (PolBS) [Karciauskas-Peters]: radial bi-2 refinement around poles",
            input: "polar layouts (poles with fans of triangles, rings of quads); prism-like n-gon caps become poles at their centroids (or at --pole FACE:X,Y,Z); other elements as bi2-mixed",
            patches: "bi-2 per regular vertex; rings of n bi-2 patches per pole; collapsed bi-2 cap at the limit point (16)",
            smoothness: "C^1; subdominant 1/2, subsubdominant 1/4",
            valences: "all pole valences",
            refine: true,
            rings: true,
            status: "available",
        },
        SchemeInfo {
            name: "tps",
            family: "Primal Bi-2 Subdivision (TPS) [Karciauskas-Peters]: ternary bi-2 on quad nets",
            input: "quad nets (one Catmull-Clark step makes any mesh one); boundaries with a doubled layer (fairsub's rules)",
            patches: "bi-2 per regular vertex; rings of 2n bi-2 patches per extraordinary vertex (ternary); quarter-piece fill at the limit point (21)",
            smoothness: "C^1; lambda = (5 + 2c + 2 sqrt(c^2 + 5c + 4)) / 27",
            valences: "all interior valences >= 3; extraordinary boundary vertices: error",
            refine: true,
            rings: true,
            status: "available",
        },
        SchemeInfo {
            name: "tps-adjustable",
            family: "adjustable TPS, split ratio e = 0.2 or --split-ratio E; alphas of (18) by --alpha-rule (fairsub's reconstruction of the stencils, tps-adjustable-derived: exact e : 1-2e : e knot insertion; reproduces (22))",
            input: "quad nets, as tps",
            patches: "bi-2 with non-uniform knots; rings of 2n patches per extraordinary vertex; fill as tps",
            smoothness: "C^1 (up to per-piece affine reparametrisation across ring sides); lambda from (22)",
            valences: "all interior valences >= 3",
            refine: true,
            rings: true,
            status: "available (reconstruction)",
        },
        SchemeInfo {
            name: "bi2-mixed",
            family: "bi-2 family combined (Fig. 15): regular bi-2, PGS at facets, TPS at extraordinary vertices, PolBS at poles",
            input: "polygon meshes with separated elements; net refinement only when all elements are of one kind",
            patches: "bi-2 per regular vertex; per element its scheme's rings and fill",
            smoothness: "C^1",
            valences: "all",
            refine: true,
            rings: true,
            status: "available",
        },
        SchemeInfo {
            name: "guided-bi5",
            family: "guided subdivision [Karciauskas-Peters]: bi-5 rings sampled from a G^2 bi-5 guide through L^-1 o lambda^l chi (Catmull-Clark's chi and lambda; suffix -half: QAS+'s chi, lambda 1/2; -g4/-g3: bi-4/bi-3 guide)",
            input: "Catmull-Clark nets (as eg); guide target: fairsub's guide-fit F_4 (the paper's [KP15] target is not in the corpus)",
            patches: "bi-3 on regular quads; K rings of 3n bi-5 patches per extraordinary vertex; G^1 bi-6 cap C^1 to the last ring",
            smoothness: "C^2 rings and joins, curvature bounded at the centre; spectrum lambda^s, s = 0..10, multiplicities of table (5)",
            valences: "3, 5..16 (4 is regular); -half: 5..10 (others use Catmull-Clark's chi)",
            refine: false,
            rings: true,
            status: "available (patches)",
        },
        SchemeInfo {
            name: "guided-bi6",
            family: "guided subdivision: bi-6 rings from 4 x 4 corner jets averaged (Fig. 2b), otherwise as guided-bi5",
            input: "as guided-bi5",
            patches: "bi-3 on regular quads; K rings of 3n bi-6 patches; G^1 bi-6 cap C^1 to the last ring",
            smoothness: "C^2 rings and joins (C^2 at the centre in the limit)",
            valences: "as guided-bi5",
            refine: false,
            rings: true,
            status: "available (patches)",
        },
        SchemeInfo {
            name: "guided-bi4-macro",
            family: "guided subdivision, Section 6.2: rings of 2 x 2 bi-4 macro patches (C^3 inner knot), fairsub's derivation (figures lost)",
            input: "as guided-bi5",
            patches: "bi-3 on regular quads; K rings of 12n bi-4 patches; no cap (the hole stays open)",
            smoothness: "C^2 rings and joins, curvature bounded at the centre",
            valences: "as guided-bi5",
            refine: false,
            rings: true,
            status: "reconstruction (rings only)",
        },
        SchemeInfo {
            name: "guided-bi3-macro",
            family: "guided subdivision, Section 6.2: rings of 3 x 3 bi-3 macro patches (C^2 knots), fairsub's derivation (figures lost)",
            input: "as guided-bi5",
            patches: "bi-3 on regular quads; K rings of 27n bi-3 patches; no cap (the hole stays open)",
            smoothness: "C^2 rings and joins, curvature bounded at the centre",
            valences: "as guided-bi5",
            refine: false,
            rings: true,
            status: "reconstruction (rings only)",
        },
    ]
}

/// The refinement scheme of a command-line name; the error lists the available names.
pub fn by_name(name: &str) -> Result<Box<dyn Scheme>> {
    match name {
        "catmull-clark" | "cc" => Ok(Box::new(CatmullClark)),
        "doo-sabin" | "ds" => Ok(Box::new(DooSabin)),
        "doo-sabin-cc" | "ds-cc" => Ok(Box::new(DooSabinCc)),
        "loop" => Ok(Box::new(Loop)),
        "pgs" => Ok(Box::new(bi2::Pgs)),
        "pgs-dscc" => Ok(Box::new(bi2::PgsPreprocessed::default())),
        "polar-bi2" | "polbs" => Ok(Box::new(bi2::PolarBi2::default())),
        "tps" => Ok(Box::new(bi2::Tps)),
        "tps-adjustable" => Ok(Box::new(bi2::AdjustableTps::default())),
        "bi2-mixed" => Ok(Box::new(bi2::Bi2Mixed)),
        "nonbox" | "non-box" => Ok(Box::new(NonBox::default())),
        "nonbox-4dir" | "non-box-4dir" => Ok(Box::new(NonBox4Dir)),
        _ => {
            let names: Vec<&str> = catalog()
                .iter()
                .filter(|s| s.refine)
                .map(|s| s.name)
                .collect();
            Err(crate::error::Error::InvalidArgument(format!(
                "unknown scheme '{name}' (available for refinement: {})",
                names.join(", ")
            )))
        }
    }
}
