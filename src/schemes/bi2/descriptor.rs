//! The descriptors of the bi-2 family: PGS (plain and after DS^CC steps), PolBS, TPS,
//! adjustable TPS and the mixed net, with their mesh rules, exact patches and local analysis.

use super::pgs::PgsOptions;
use super::ternary::TernaryRules;
use super::{AdjustableTps, Bi2Mixed, Pgs, PgsPreprocessed, PolarBi2, Tps};
use crate::bezier::BezierPatch;
use crate::error::Result;
use crate::schemes::Scheme;
use crate::schemes::circulant::SparseLocal;
use crate::schemes::descriptor::{
    Capabilities, Computed, Descriptor, LocalRules, ParamKind, PatchRules, Published, Spec,
    SurfaceOutput, patch_fn,
};
use crate::schemes::local::LocalMatrix;
use crate::schemes::needs::{Need, NetStep, Purpose, Requirement, Step};

/// The default split ratio of adjustable TPS (the paper's figures use 0.2).
pub const DEFAULT_E: f64 = 0.2;

/// Which member of the family.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bi2Kind {
    /// PGS.
    Pgs,
    /// PGS after two DS^CC steps.
    PgsDscc,
    /// Polar bi-2.
    Polar,
    /// Ternary TPS.
    Tps,
    /// Adjustable TPS.
    TpsAdjustable,
    /// The mixed net.
    Mixed,
}

/// A bi-2 scheme.
#[derive(Debug)]
pub struct Bi2Descriptor {
    /// The member of the family.
    pub kind: Bi2Kind,
}

/// The registry's PGS row.
pub static PGS: Bi2Descriptor = Bi2Descriptor { kind: Bi2Kind::Pgs };
/// The registry's PGS-after-DS^CC row.
pub static PGS_DSCC: Bi2Descriptor = Bi2Descriptor {
    kind: Bi2Kind::PgsDscc,
};
/// The registry's PolBS row.
pub static POLAR: Bi2Descriptor = Bi2Descriptor {
    kind: Bi2Kind::Polar,
};
/// The registry's TPS row.
pub static TPS: Bi2Descriptor = Bi2Descriptor { kind: Bi2Kind::Tps };
/// The registry's adjustable-TPS row.
pub static TPS_ADJUSTABLE: Bi2Descriptor = Bi2Descriptor {
    kind: Bi2Kind::TpsAdjustable,
};
/// The registry's mixed-net row.
pub static MIXED: Bi2Descriptor = Bi2Descriptor {
    kind: Bi2Kind::Mixed,
};

impl Bi2Descriptor {
    /// Adjustable TPS's rules from the parameters (`--split-ratio`, `--alpha-rule`).
    pub fn ternary_rules(spec: &Spec) -> Result<TernaryRules> {
        TernaryRules::adjustable_with(
            spec.params.split_ratio.unwrap_or(DEFAULT_E),
            spec.params.alpha_rule.unwrap_or_default(),
        )
    }
}

impl Descriptor for Bi2Descriptor {
    /// Refinement and exact patches; evaluation for PGS, laid out like Doo-Sabin, for PGS
    /// after DS^CC steps, whose refined net's vertices carry the input faces' cells
    /// ([`crate::schemes::doo_sabin::surface::step_cells`]), for the mixed net at its regular
    /// vertices, PGS facets (`bi2::surface::cells`) and poles (`bi2::surface::poles`; its TPS
    /// vertices are not evaluated), and for TPS, whose rings record cells in thirds
    /// (`bi2::surface::thirds`), and for adjustable TPS on its input net's faces, whose rings
    /// record cells split at `1 - 2e` in knot coordinates (same module). PolBS evaluates
    /// like the mixed net: its radial rings lie in halves of the fan triangles (collapsed
    /// quads, [`crate::bezier::domain`]), the caps turned into poles are strips of them.
    fn capabilities(&self) -> Capabilities {
        Capabilities {
            eval: matches!(
                self.kind,
                Bi2Kind::Pgs
                    | Bi2Kind::PgsDscc
                    | Bi2Kind::Mixed
                    | Bi2Kind::Polar
                    | Bi2Kind::Tps
                    | Bi2Kind::TpsAdjustable
            ),
            ..Capabilities::REFINE_AND_PATCHES
        }
    }

    fn joins_up_to_scaling(&self) -> bool {
        true
    }

    fn params(&self) -> &'static [ParamKind] {
        match self.kind {
            Bi2Kind::Polar => &[ParamKind::Poles],
            Bi2Kind::TpsAdjustable => &[ParamKind::SplitRatio, ParamKind::AlphaRule],
            // the dual host's boundary modes (crate::schemes::doo_sabin)
            Bi2Kind::Pgs | Bi2Kind::PgsDscc => &[ParamKind::BoundaryMode, ParamKind::Creases],
            _ => &[],
        }
    }

    fn mesh_rules(&self, spec: &Spec) -> Result<Option<Box<dyn Scheme>>> {
        Ok(Some(match self.kind {
            Bi2Kind::Pgs => Box::new(Pgs),
            Bi2Kind::PgsDscc => Box::new(PgsPreprocessed {
                opts: PgsOptions { dscc_steps: 2 },
            }),
            Bi2Kind::Polar => Box::new(PolarBi2 {
                poles: spec.params.poles.clone(),
            }),
            Bi2Kind::Tps => Box::new(Tps),
            Bi2Kind::TpsAdjustable => {
                let r = Self::ternary_rules(spec)?;
                Box::new(AdjustableTps {
                    e: r.e,
                    alphas: r.alphas,
                })
            }
            Bi2Kind::Mixed => Box::new(Bi2Mixed),
        }))
    }

    /// Infinitely sharp creases and corners: the net is cut along them
    /// ([`crate::schemes::doo_sabin::sharp`]). Semi-sharp features: the dual crease
    /// construction (Doo-Sabin, DS^CC, PGS), PGS's (the mixed and polar nets) and Doo-Sabin's
    /// beside TPS's elements (TPS, adjustable TPS), under `--prepare auto`.
    fn patches_take_features(&self) -> bool {
        true
    }

    /// Regular bi-2 patches, the member's rings and fill per element (`rules`: adjustable
    /// TPS's, ignored by the others); on a net with sharp features, of the net cut along its
    /// creases.
    fn patch_rules(&self, spec: &Spec) -> Result<Option<Box<dyn PatchRules>>> {
        let (kind, rules) = (self.kind, Self::ternary_rules(spec)?);
        let poles = spec.params.poles.clone();
        let (name, mode) = (spec.name(), spec.params.prepare);
        patch_fn(move |mesh, opts, progress| {
            use crate::schemes::doo_sabin::sharp;
            // semi-sharp features under the mixed and polar nets: PGS's construction, the
            // surface their spending steps give (`super::surface::spent_by_pgs`)
            let by_pgs = matches!(kind, Bi2Kind::Mixed | Bi2Kind::Polar)
                && mode == crate::schemes::options::PrepareMode::Auto
                && sharp::has_semi_sharp(mesh);
            // semi-sharp features under TPS and adjustable TPS: Doo-Sabin's crease
            // construction near the features, TPS's elements clear of them
            // (`super::surface::tps_spent_locally`)
            let local = matches!(kind, Bi2Kind::Tps | Bi2Kind::TpsAdjustable)
                && mode == crate::schemes::options::PrepareMode::Auto
                && sharp::has_semi_sharp(mesh);
            let semi = matches!(kind, Bi2Kind::Pgs | Bi2Kind::PgsDscc) || by_pgs || local;
            sharp::on_cut_net(mesh, name, semi, |mesh| {
                use super::surface as s;
                if local {
                    let rules = if kind == Bi2Kind::Tps {
                        TernaryRules::TPS
                    } else {
                        rules
                    };
                    let (complex, notes) = s::tps_spent_locally(mesh, opts, rules, name, progress)?;
                    return Ok(SurfaceOutput {
                        complex,
                        fell_back: Vec::new(),
                        notes,
                    });
                }
                if by_pgs {
                    let (complex, note) = s::spent_by_pgs(mesh, opts, name, progress)?;
                    return Ok(SurfaceOutput {
                        complex,
                        fell_back: Vec::new(),
                        notes: vec![note],
                    });
                }
                if !matches!(kind, Bi2Kind::Pgs | Bi2Kind::PgsDscc) {
                    sharp::refuse_kept_corners_with_faces(mesh, name)?;
                    // the mixed and polar nets give such boundaries to PGS's construction
                    // (super::surface's elements) when preparing
                    let separates = matches!(kind, Bi2Kind::Mixed | Bi2Kind::Polar)
                        && mode == crate::schemes::options::PrepareMode::Auto;
                    if !separates {
                        sharp::refuse_boundary_modes(mesh, name)?;
                    }
                }
                let with_notes = |(complex, notes)| SurfaceOutput {
                    complex,
                    fell_back: Vec::new(),
                    notes,
                };
                Ok(match kind {
                    Bi2Kind::Pgs => SurfaceOutput::plain(s::pgs_complex(
                        mesh,
                        opts,
                        PgsOptions::default(),
                        progress,
                    )?),
                    Bi2Kind::PgsDscc => SurfaceOutput::plain(s::pgs_complex(
                        mesh,
                        opts,
                        PgsOptions { dscc_steps: 2 },
                        progress,
                    )?),
                    Bi2Kind::Polar => {
                        with_notes(s::polar_complex(mesh, opts, &poles, mode, progress)?)
                    }
                    Bi2Kind::Tps => {
                        with_notes(s::tps_complex(mesh, opts, TernaryRules::TPS, progress)?)
                    }
                    Bi2Kind::TpsAdjustable => {
                        with_notes(s::tps_complex(mesh, opts, rules, progress)?)
                    }
                    Bi2Kind::Mixed => with_notes(s::mixed_complex(mesh, opts, mode, progress)?),
                })
            })
        })
    }

    /// TPS and adjustable TPS take quad nets without interior vertices of valence 2 and with
    /// regular boundary vertices: one Doo-Sabin step then one Catmull-Clark step where the
    /// net has the first two, one Catmull-Clark step where it has only faces that are not
    /// quads. PGS's patches (and the mixed and polar nets, whose elements become PGS facets)
    /// take no interior vertex of valence 2: one PGS step. The mixed and polar nets separate
    /// their elements by the family's own constructions (`super::surface`'s elements); the
    /// mixed net's refinement takes one kind of element: one PGS step makes every element a
    /// facet.
    fn preparation(&self, _: &Spec, purpose: Purpose) -> Vec<Requirement> {
        const DUAL_THEN_QUADS: &[NetStep] = &[NetStep::DooSabin, NetStep::CatmullClark];
        let net = |need, steps| Requirement {
            need,
            step: Step::Net(steps),
        };
        let no_valence_2 = net(Need::NoInteriorValence2, &[NetStep::Pgs]);
        match (self.kind, purpose) {
            (Bi2Kind::Tps | Bi2Kind::TpsAdjustable, Purpose::Refine) => vec![
                net(Need::NoInteriorValence2, DUAL_THEN_QUADS),
                net(Need::RegularBoundary, DUAL_THEN_QUADS),
                net(Need::Quads, &[NetStep::CatmullClark]),
            ],
            (Bi2Kind::Tps | Bi2Kind::TpsAdjustable, Purpose::Patches) => {
                // with semi-sharp features the surface is Doo-Sabin's construction beside
                // TPS's elements (`super::surface::tps_spent_locally`), which takes any
                // boundary and face but no interior vertex of valence 2: the dual step alone
                // (it carries the creases); without them, TPS's own needs
                let without =
                    |need: &'static Need, steps| net(Need::IfSemiSharp(false, need), steps);
                vec![
                    Requirement {
                        need: Need::InfinitelySharpOnly,
                        step: Step::Own(
                            "the family's dual step spends the sharpness (fairsub's crease \
                             construction): Doo-Sabin's construction refines near the \
                             semi-sharp features only, and extraordinary vertices clear of \
                             them keep TPS's rings and cap",
                        ),
                    },
                    net(
                        Need::IfSemiSharp(true, &Need::NoInteriorValence2),
                        &[NetStep::DooSabin],
                    ),
                    without(&Need::NoInteriorValence2, DUAL_THEN_QUADS),
                    without(&Need::RegularBoundary, DUAL_THEN_QUADS),
                    without(&Need::Quads, &[NetStep::CatmullClark]),
                ]
            }
            (Bi2Kind::Pgs, Purpose::Patches) => vec![no_valence_2],
            (Bi2Kind::Mixed | Bi2Kind::Polar, Purpose::Patches) => vec![
                Requirement {
                    need: Need::InfinitelySharpOnly,
                    step: Step::Own(
                        "the family's dual step spends the sharpness (fairsub's crease \
                         construction), and after one PGS step every element is a facet: the \
                         surface is PGS's, built by PGS's construction, which refines only near \
                         the semi-sharp features",
                    ),
                },
                no_valence_2,
                net(
                    Need::Scheme {
                        what: "keeps only corners of one face (a crease end of the net cut \
                               along its creases with more faces on one side would open)",
                        test: crate::schemes::doo_sabin::sharp::kept_corners_with_faces,
                    },
                    &[NetStep::Pgs],
                ),
                Requirement {
                    need: Need::Scheme {
                        what: "needs its extraordinary elements separated by regular \
                               vertices, facets with a DS-net and regular boundary vertices",
                        test: if self.kind == Bi2Kind::Mixed {
                            super::surface::unseparated
                        } else {
                            super::surface::unseparated_polar
                        },
                    },
                    step: Step::Own(
                        "the family's own separating construction: TPS's whole-net steps on \
                         a net of extraordinary vertices, else the PGS step, which makes every \
                         element a facet (PGS's construction)",
                    ),
                },
            ],
            (Bi2Kind::Mixed, Purpose::Refine) => vec![net(
                Need::Scheme {
                    what: "refines nets whose elements are of one kind",
                    test: super::mixed::mixed_kinds,
                },
                &[NetStep::Pgs],
            )],
            _ => Vec::new(),
        }
    }

    fn local_rules(&self, spec: &Spec) -> Result<Option<Box<dyn LocalRules>>> {
        if matches!(self.kind, Bi2Kind::PgsDscc | Bi2Kind::Mixed) {
            return Ok(None);
        }
        Ok(Some(Box::new(Bi2Local {
            kind: self.kind,
            rules: Self::ternary_rules(spec)?,
        })))
    }
}

/// The local analysis of a member of the bi-2 family (`rules`: adjustable TPS's, ignored by
/// the others).
struct Bi2Local {
    kind: Bi2Kind,
    rules: TernaryRules,
}

impl LocalRules for Bi2Local {
    fn matrix(&self, n: usize) -> Result<LocalMatrix> {
        super::local::local_matrix_rules(self.kind, n, self.rules)
    }

    fn sparse(&self, n: usize) -> Result<Option<SparseLocal>> {
        super::local::sparse_rules(self.kind, n, self.rules).map(Some)
    }

    fn characteristic_ring(&self, n: usize) -> Result<(Vec<BezierPatch>, f64)> {
        super::local::characteristic_ring_rules(self.kind, n, self.rules)
    }

    /// The bi-2 paper's polynomials, eigenvalues and limit points (its own matrix layout).
    fn published(&self, n: usize, _: &Computed<'_>) -> Result<Vec<Published>> {
        super::local::published_rules(self.kind, n, self.rules)
    }
}
