//! The one table of scheme names: every scheme fairsub knows, with its canonical name, its
//! aliases, the name suffixes that set typed parameters, and its [`Descriptor`].
//!
//! This is the only place where scheme names are spelled. Everything else refers to a scheme
//! by a [`SchemeId`] constant of [`ids`] or looks a name up here ([`Registry::lookup`]); the
//! catalogue (`fairsub schemes`) lists the rows in order.
//!
//! Adding a scheme: one folder under `src/schemes/` with a [`Descriptor`], and one row in
//! [`Registry::builtin`] (or, outside the crate, [`register`]).

use super::SchemeInfo;
use super::descriptor::{
    About, Capabilities, ChiKind, Descriptor, GuideDegree, ParamKind, Params, RulesChoice,
    SchemeId, Spec,
};
use super::{
    bi2, butterfly, catmull_clark, doo_sabin, eg, guided, loop_subdivision, nonbox, qas, sqrt3,
};
use crate::error::{Error, Result};
use std::sync::{LazyLock, RwLock};

mod entry;
pub use entry::{Entry, Suffix};

/// The ids of the built-in schemes.
pub mod ids {
    use super::SchemeId;

    /// Catmull-Clark.
    pub const CATMULL_CLARK: SchemeId = SchemeId::new("catmull-clark");
    /// Doo-Sabin.
    pub const DOO_SABIN: SchemeId = SchemeId::new("doo-sabin");
    /// DS^CC.
    pub const DOO_SABIN_CC: SchemeId = SchemeId::new("doo-sabin-cc");
    /// Loop.
    pub const LOOP: SchemeId = SchemeId::new("loop");
    /// Non-box subdivision, quad variant with FCVs.
    pub const NONBOX: SchemeId = SchemeId::new("nonbox");
    /// Non-box subdivision, four-directional triangle variant.
    pub const NONBOX_4DIR: SchemeId = SchemeId::new("nonbox-4dir");
    /// Evolving Guide subdivision.
    pub const EG: SchemeId = SchemeId::new("eg");
    /// QAS+ of degree bi-4.
    pub const QAS_PLUS: SchemeId = SchemeId::new("qas-plus");
    /// QAS+ of degree bi-3.
    pub const QAS_PLUS_BI3: SchemeId = SchemeId::new("qas-plus-bi3");
    /// QAS+^4 with lambda 0.4.
    pub const QAS_04: SchemeId = SchemeId::new("qas-0.4");
    /// QAS+^4 with the gradual schedule 0.5 .. 0.4.
    pub const QAS_05_04: SchemeId = SchemeId::new("qas-0.5-0.4");
    /// Point-augmented bi-2 subdivision.
    pub const PGS: SchemeId = SchemeId::new("pgs");
    /// PGS after two DS^CC steps.
    pub const PGS_DSCC: SchemeId = SchemeId::new("pgs-dscc");
    /// Polar bi-2 subdivision.
    pub const POLAR_BI2: SchemeId = SchemeId::new("polar-bi2");
    /// Primal ternary bi-2 subdivision.
    pub const TPS: SchemeId = SchemeId::new("tps");
    /// Adjustable TPS.
    pub const TPS_ADJUSTABLE: SchemeId = SchemeId::new("tps-adjustable");
    /// The bi-2 family in one mesh.
    pub const BI2_MIXED: SchemeId = SchemeId::new("bi2-mixed");
    /// Guided subdivision, bi-5 rings.
    pub const GUIDED_BI5: SchemeId = SchemeId::new("guided-bi5");
    /// Guided subdivision, bi-6 rings.
    pub const GUIDED_BI6: SchemeId = SchemeId::new("guided-bi6");
    /// Guided subdivision, bi-4 macro-patch rings.
    pub const GUIDED_BI4_MACRO: SchemeId = SchemeId::new("guided-bi4-macro");
    /// Guided subdivision, bi-3 macro-patch rings.
    pub const GUIDED_BI3_MACRO: SchemeId = SchemeId::new("guided-bi3-macro");
    /// Kobbelt's sqrt(3) subdivision.
    pub const SQRT3: SchemeId = SchemeId::new("sqrt3");
    /// The modified butterfly scheme.
    pub const BUTTERFLY: SchemeId = SchemeId::new("butterfly");
}

/// The guided schemes' suffixes: `-g4` / `-g3` (guide degree), then `-half` (contraction 1/2).
const GUIDED_SUFFIXES: &[Suffix] = &[
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

/// The `-derived` suffix of EG and the QAS+ schemes (`eg-derived`, `qas-plus-derived`): fairsub's
/// derived rules also where the paper prints rules, as `--rules derived`.
const DERIVED_SUFFIX: &[Suffix] = &[Suffix {
    text: "-derived",
    set: |p| p.rules = RulesChoice::Derived,
}];

/// The schemes, in catalogue order.
#[derive(Debug, Clone)]
pub struct Registry {
    entries: Vec<Entry>,
}

/// The registry in use: the built-in schemes and those added by [`register`]. Each version is
/// leaked, so a caller may keep the `&'static` it got while a scheme is added.
static CURRENT: LazyLock<RwLock<&'static Registry>> =
    LazyLock::new(|| RwLock::new(Box::leak(Box::new(Registry::builtin()))));

/// The registry: the built-in schemes and those added with [`register`]. Every front end
/// (command line, demo, surface builder, analysis) looks schemes up here.
pub fn registry() -> &'static Registry {
    *CURRENT.read().unwrap_or_else(|e| e.into_inner())
}

/// Adds a scheme defined outside the crate (its [`Descriptor`] and catalogue row) to the
/// registry, so that every front end offers it. Errors when its name or an alias is taken.
pub fn register(entry: Entry) -> Result<()> {
    let mut current = CURRENT.write().unwrap_or_else(|e| e.into_inner());
    let taken = current.entries.iter().any(|e| {
        let names = || std::iter::once(e.name).chain(e.aliases.iter().copied());
        std::iter::once(entry.name)
            .chain(entry.aliases.iter().copied())
            .any(|n| names().any(|m| m == n))
    });
    if taken {
        return Err(Error::InvalidArgument(format!(
            "a scheme named '{}' (or one of its aliases) is already registered",
            entry.name
        )));
    }
    *current = Box::leak(Box::new((*current).clone().with(entry)));
    Ok(())
}

impl Registry {
    /// Every built-in scheme, in catalogue order.
    pub fn builtin() -> Registry {
        use ids::*;
        Registry {
            entries: vec![
                Entry::new(
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
                    &catmull_clark::DESCRIPTOR,
                ),
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
                    &doo_sabin::DESCRIPTOR,
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
                    &doo_sabin::DESCRIPTOR_CC,
                ),
                Entry::new(
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
                    &loop_subdivision::DESCRIPTOR,
                ),
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
                    &nonbox::DESCRIPTOR,
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
                    &nonbox::DESCRIPTOR_4DIR,
                ),
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
                    &eg::DESCRIPTOR,
                )
                .with_suffixes(DERIVED_SUFFIX),
                Entry::new(
                    QAS_PLUS,
                    &["qas-plus-chi"],
                    About {
                        family: "QAS+^4 quadratic-attraction subdivision [Karciauskas-Peters], contraction 1/2",
                        input: "Catmull-Clark nets (as eg); initial quadratic expansion by fairsub's qas-fit",
                        patches: "bi-3 on regular quads; K rings of 3n bi-4 patches per extraordinary vertex; G^1 cap (bi-4/bi-5) C^1 to the last ring",
                        smoothness: "C^2 rings and joins, curvature bounded (rho(M_d) < 0.13621 < 1/4; derived tables 0.1253..0.1297)",
                        valences: "5, 6, 7 printed; 8..16 fairsub's derived tables (qas-plus-derived; --rules derived or suffix -derived: also at 5..7); 3 uses eg's rules, 4 bi-4 refinement; above 16: Catmull-Clark fallback or error",
                        status: "available (patches; printed 5..7; derived 8..16, a reconstruction approximating the printed tables)",
                    },
                    &qas::DESCRIPTOR,
                )
                .with_suffixes(DERIVED_SUFFIX),
                Entry::new(
                    QAS_PLUS_BI3,
                    &[],
                    About {
                        family: "QAS+^3: bi-3 rings (2 x 2 macro-patches) through fairsub's derived bijection T_3^4",
                        input: "as qas-plus",
                        patches: "bi-3 on regular quads; K rings of 12n bi-3 patches; bi-3 fill (C^0, 2 x 2 Coons per sector)",
                        smoothness: "C^2 rings and joins, curvature bounded (rho(M_d) = 0.136252 < 0.13626 at n = 5)",
                        valences: "as qas-plus",
                        status: "available (patches; T_3^4 derived: the earlier paper's formulas are not in the corpus)",
                    },
                    &qas::DESCRIPTOR_BI3,
                )
                .with_suffixes(DERIVED_SUFFIX),
                Entry::new(
                    QAS_04,
                    &[],
                    About {
                        family: "QAS+^4 accelerated: lambda = 0.4 in the restriction S (tables unchanged)",
                        input: "as qas-plus",
                        patches: "as qas-plus",
                        smoothness: "curvature bounded (rho(M_d) < 0.16 = lambda^2)",
                        valences: "as qas-plus",
                        status: "available (patches)",
                    },
                    &qas::DESCRIPTOR_04,
                )
                .with_suffixes(DERIVED_SUFFIX),
                Entry::new(
                    QAS_05_04,
                    &[],
                    About {
                        family: "QAS+^4 with the gradual schedule 0.5, 0.5, 0.475, 0.475, 0.45, 0.45, then 0.4",
                        input: "as qas-plus",
                        patches: "as qas-plus",
                        smoothness: "as qas-0.4",
                        valences: "as qas-plus",
                        status: "available (patches)",
                    },
                    &qas::DESCRIPTOR_05_04,
                )
                .with_suffixes(DERIVED_SUFFIX),
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
                    &bi2::descriptor::PGS,
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
                    &bi2::descriptor::PGS_DSCC,
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
                    &bi2::descriptor::POLAR,
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
                    &bi2::descriptor::TPS,
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
                    &bi2::descriptor::TPS_ADJUSTABLE,
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
                    &bi2::descriptor::MIXED,
                ),
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
                    &guided::descriptor::BI5,
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
                    &guided::descriptor::BI6,
                )
                .with_suffixes(GUIDED_SUFFIXES),
                Entry::new(
                    GUIDED_BI4_MACRO,
                    &[],
                    About {
                        family: "guided subdivision, Section 6.2: rings of 2 x 2 bi-4 macro patches (C^3 inner knot), fairsub's derivation (figures lost)",
                        input: "as guided-bi5",
                        patches: "bi-3 on regular quads; K rings of 12n bi-4 patches; no cap (the hole stays open)",
                        smoothness: "C^2 rings and joins, curvature bounded at the centre",
                        valences: "as guided-bi5",
                        status: "reconstruction (rings only)",
                    },
                    &guided::descriptor::BI4_MACRO,
                )
                .with_suffixes(GUIDED_SUFFIXES),
                Entry::new(
                    GUIDED_BI3_MACRO,
                    &[],
                    About {
                        family: "guided subdivision, Section 6.2: rings of 3 x 3 bi-3 macro patches (C^2 knots), fairsub's derivation (figures lost)",
                        input: "as guided-bi5",
                        patches: "bi-3 on regular quads; K rings of 27n bi-3 patches; no cap (the hole stays open)",
                        smoothness: "C^2 rings and joins, curvature bounded at the centre",
                        valences: "as guided-bi5",
                        status: "reconstruction (rings only)",
                    },
                    &guided::descriptor::BI3_MACRO,
                )
                .with_suffixes(GUIDED_SUFFIXES),
                Entry::new(
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
                    &sqrt3::DESCRIPTOR,
                ),
                Entry::new(
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
                    &butterfly::DESCRIPTOR,
                ),
            ],
        }
    }

    /// This registry with one more row (a scheme defined outside the crate).
    pub fn with(mut self, entry: Entry) -> Registry {
        self.entries.push(entry);
        self
    }

    /// The rows, in catalogue order.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    /// The row of a scheme.
    ///
    /// # Panics
    /// If the id has no row (ids come from this registry).
    pub fn entry(&self, id: SchemeId) -> &Entry {
        self.entries
            .iter()
            .find(|e| e.id == id)
            .unwrap_or_else(|| panic!("scheme {id} is not in the registry"))
    }

    /// The descriptor of a scheme.
    pub fn descriptor(&self, id: SchemeId) -> &'static dyn Descriptor {
        self.entry(id).descriptor
    }

    /// The scheme a command-line name means, with the parameters its suffixes set: the
    /// canonical name, an alias, or a name followed by suffixes of its row. Unknown names get
    /// [`Error::UnknownScheme`] listing the names.
    pub fn lookup(&self, name: &str) -> Result<Spec> {
        for e in &self.entries {
            for base in std::iter::once(e.name).chain(e.aliases.iter().copied()) {
                let Some(mut rest) = name.strip_prefix(base) else {
                    continue;
                };
                let mut params = Params::default();
                for s in e.suffixes {
                    if let Some(r) = rest.strip_prefix(s.text) {
                        (s.set)(&mut params);
                        rest = r;
                    }
                }
                if rest.is_empty() {
                    return Ok(Spec { id: e.id, params });
                }
            }
        }
        Err(Error::UnknownScheme {
            name: name.to_string(),
            purpose: "",
            available: self.entries.iter().map(|e| e.name).collect(),
        })
    }

    /// [`Registry::lookup`] for a purpose: a name that is unknown, or whose scheme lacks the
    /// capability `pick`, gets [`Error::UnknownScheme`] listing the names that have it
    /// (`purpose` as `" for refinement"`).
    pub fn lookup_for(
        &self,
        name: &str,
        purpose: &'static str,
        pick: impl Fn(Capabilities) -> bool,
    ) -> Result<Spec> {
        match self.lookup(name) {
            Ok(s) if pick(self.entry(s.id).capabilities()) => Ok(s),
            _ => Err(Error::UnknownScheme {
                name: name.to_string(),
                purpose,
                available: self.names_with(pick),
            }),
        }
    }

    /// The catalogue: one row per scheme, in order.
    pub fn catalog(&self) -> Vec<SchemeInfo> {
        self.entries
            .iter()
            .map(|e| {
                let c = e.capabilities();
                SchemeInfo {
                    name: e.name,
                    family: e.about.family,
                    input: e.about.input,
                    patches: e.about.patches,
                    smoothness: e.about.smoothness,
                    valences: e.about.valences,
                    refine: c.refine,
                    rings: c.patches,
                    status: e.about.status,
                }
            })
            .collect()
    }

    /// The names of the schemes with the given capability, in catalogue order.
    pub fn names_with(&self, pick: impl Fn(Capabilities) -> bool) -> Vec<&'static str> {
        self.entries
            .iter()
            .filter(|e| pick(e.capabilities()))
            .map(|e| e.name)
            .collect()
    }

    /// The names of the schemes whose options include `kind`, in catalogue order.
    pub fn names_taking(&self, kind: ParamKind) -> Vec<&'static str> {
        self.entries
            .iter()
            .filter(|e| e.descriptor.params().contains(&kind))
            .map(|e| e.name)
            .collect()
    }
}
