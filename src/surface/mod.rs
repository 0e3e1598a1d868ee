//! Patch complexes: the exact piecewise-polynomial surfaces fairsub produces.
//!
//! A [`PatchComplex`] holds the Bezier patches of a whole surface, each tagged with its
//! [`Provenance`] (regular region, ring `k` of an extraordinary element, cap / fill), so writers
//! can group them, the renderer can colour them and analysis can report where a defect sits.

pub(crate) mod adaptive;
pub mod adjacency;
pub mod bi2;
pub mod cc;
pub mod ds;
pub mod eg;
pub mod guided;
pub mod loop_patches;
pub mod nonbox;
pub mod qas;
pub mod regular;
pub mod tessellate;
#[cfg(test)]
pub(crate) mod testing;

use crate::bezier::BezierPatch;
use serde::Serialize;

/// Where a patch comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Provenance {
    /// A patch of a regular region of the input net (`face` numbers the input face it lies in,
    /// when known).
    Regular {
        /// Input face the patch lies in.
        face: u32,
    },
    /// A patch of ring `ring` (1 = outermost) around an extraordinary element.
    Ring {
        /// The extraordinary element (vertex or facet of the input net).
        element: Element,
        /// Ring index, 1-based.
        ring: u32,
        /// Sector of the element the patch lies in.
        sector: u32,
    },
    /// A patch of the cap or fill closing the hole left inside the last ring.
    Cap {
        /// The extraordinary element.
        element: Element,
        /// Sector of the element the patch lies in.
        sector: u32,
    },
    /// A patch of unknown origin (read from a file).
    Unknown,
}

/// An extraordinary element of an input net.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(tag = "type", content = "index", rename_all = "snake_case")]
pub enum Element {
    /// A vertex (extraordinary vertex / node, or a pole).
    Vertex(u32),
    /// A face (extraordinary facet).
    Face(u32),
}

impl Provenance {
    /// A short group name used by writers (`regular`, `ring3`, `cap`, ...).
    pub fn group_name(&self) -> String {
        match self {
            Provenance::Regular { .. } => "regular".to_string(),
            Provenance::Ring { ring, .. } => format!("ring{ring}"),
            Provenance::Cap { .. } => "cap".to_string(),
            Provenance::Unknown => "patches".to_string(),
        }
    }
}

/// The patches of a surface with their provenance.
#[derive(Debug, Clone, Default)]
pub struct PatchComplex {
    /// The patches.
    pub patches: Vec<BezierPatch>,
    /// Provenance of each patch (same length as `patches`).
    pub provenance: Vec<Provenance>,
}

impl PatchComplex {
    /// An empty complex.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a patch.
    pub fn push(&mut self, patch: BezierPatch, provenance: Provenance) {
        self.patches.push(patch);
        self.provenance.push(provenance);
    }

    /// Number of patches.
    pub fn len(&self) -> usize {
        self.patches.len()
    }

    /// Whether the complex has no patches.
    pub fn is_empty(&self) -> bool {
        self.patches.is_empty()
    }

    /// Appends all patches of another complex.
    pub fn extend(&mut self, other: PatchComplex) {
        self.patches.extend(other.patches);
        self.provenance.extend(other.provenance);
    }
}

/// Options for exact patch output of any scheme.
#[derive(Debug, Clone, Copy)]
pub struct ComplexOptions {
    /// Rings per extraordinary element.
    pub rings: usize,
    /// Close the central hole (each scheme documents its fill).
    pub fill: bool,
}

/// What schemes with rules for some valences only (EG, QAS+) do elsewhere.
pub use eg::Fallback;

/// The exact surface of `mesh` under the named scheme as a patch complex. `progress(level)` is
/// called as rings are produced.
pub fn complex(
    scheme: &str,
    mesh: &crate::mesh::PolyMesh,
    opts: ComplexOptions,
    progress: impl FnMut(usize),
) -> crate::error::Result<PatchComplex> {
    complex_with_notes(scheme, mesh, opts, Fallback::default(), progress).map(|(c, _)| c)
}

/// Like [`complex`], with the fallback for valences without rules, and notes for the user (which
/// elements fell back to which rules).
pub fn complex_with_notes(
    scheme: &str,
    mesh: &crate::mesh::PolyMesh,
    opts: ComplexOptions,
    fallback: Fallback,
    progress: impl FnMut(usize),
) -> crate::error::Result<(PatchComplex, Vec<String>)> {
    let plain = |c: crate::error::Result<PatchComplex>| c.map(|c| (c, Vec::new()));
    match scheme {
        "eg" | "qas-plus" | "qas-0.4" | "qas-0.5-0.4" | "qas-plus-bi3" => {
            let eo = eg::EgOptions {
                rings: opts.rings,
                fill: opts.fill,
                fallback,
            };
            let o = match scheme {
                "eg" => eg::dnet_complex(&eg::EgRulesProvider, mesh, eo, progress)?,
                "qas-plus" => qas::qas_complex(mesh, eo, qas::Contraction::Half, progress)?,
                "qas-0.4" => qas::qas_complex(mesh, eo, qas::Contraction::Fixed(0.4), progress)?,
                "qas-plus-bi3" => qas::qas_bi3_complex(mesh, eo, qas::Contraction::Half, progress)?,
                _ => qas::qas_complex(mesh, eo, qas::Contraction::Gradual, progress)?,
            };
            Ok((o.complex, o.notes))
        }
        name if guided::parse_scheme(name).is_some() => {
            let scheme = guided::parse_scheme(name).expect("checked");
            let o = guided::guided_complex(
                mesh,
                guided::GuidedComplexOptions {
                    rings: opts.rings,
                    cap: opts.fill,
                    scheme,
                    fallback,
                },
                progress,
            )?;
            Ok((o.complex, o.notes))
        }
        "catmull-clark" | "cc" => plain(cc::catmull_clark_complex(
            mesh,
            cc::CcComplexOptions {
                rings: opts.rings,
                fill: opts.fill,
            },
            progress,
        )),
        "doo-sabin" | "ds" => plain(ds::doo_sabin_complex(mesh, opts, progress)),
        "doo-sabin-cc" | "ds-cc" => plain(ds::doo_sabin_cc_complex(mesh, opts, progress)),
        "loop" => plain(loop_patches::loop_complex(mesh, opts, progress)),
        "pgs" => plain(bi2::pgs_complex(
            mesh,
            opts,
            crate::schemes::bi2::pgs::PgsOptions::default(),
            progress,
        )),
        "pgs-dscc" => plain(bi2::pgs_complex(
            mesh,
            opts,
            crate::schemes::bi2::pgs::PgsOptions { dscc_steps: 2 },
            progress,
        )),
        "polar-bi2" | "polbs" => bi2::polar_complex(mesh, opts, &[], progress),
        "tps" => bi2::tps_complex(
            mesh,
            opts,
            crate::schemes::bi2::ternary::TernaryRules::TPS,
            progress,
        ),
        "tps-adjustable" => bi2::tps_complex(
            mesh,
            opts,
            crate::schemes::bi2::ternary::TernaryRules::adjustable(
                crate::analysis::bi2::DEFAULT_E,
            )?,
            progress,
        ),
        "bi2-mixed" => plain(bi2::mixed_complex(mesh, opts, progress)),
        "nonbox" | "non-box" => Ok((
            nonbox::nonbox_mesh_complex(mesh, opts, progress)?,
            crate::schemes::nonbox::input_notes(scheme, mesh),
        )),
        "nonbox-4dir" | "non-box-4dir" => Ok((
            nonbox::nonbox_4dir_mesh_complex(mesh, opts, progress)?,
            crate::schemes::nonbox::input_notes(scheme, mesh),
        )),
        other => {
            let names: Vec<&str> = crate::schemes::catalog()
                .iter()
                .filter(|s| s.rings)
                .map(|s| s.name)
                .collect();
            Err(crate::error::Error::InvalidArgument(format!(
                "scheme '{other}' has no exact patch output (available: {})",
                names.join(", ")
            )))
        }
    }
}
