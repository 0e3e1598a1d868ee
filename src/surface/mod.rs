//! Exact surfaces of whole nets: the patch complexes of every scheme (regular patches, rings
//! around extraordinary elements, caps), built by the scheme's rules, and what is computed from
//! them (tessellations, adjacency of patch sides).
//!
//! The complex itself ([`PatchComplex`], [`Provenance`]) lives in [`crate::bezier::complex`] and
//! the extraordinary elements ([`Element`]) in [`crate::mesh`]; both are re-exported here.

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

pub use crate::bezier::complex::{PatchComplex, Provenance};
pub use crate::mesh::Element;

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
