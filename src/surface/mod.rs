//! Exact surfaces of whole nets: the patch complexes of every scheme (regular patches, rings
//! around extraordinary elements, caps), built by the scheme's rules, and what is computed from
//! them (tessellations, adjacency of patch sides, the validity checks before output, the patch
//! stencil tables that re-apply a complex to moved control points).
//!
//! The complex itself ([`PatchComplex`], [`Provenance`]) lives in [`crate::bezier::complex`] and
//! the extraordinary elements ([`Element`]) in [`crate::mesh`]; both are re-exported here.

pub mod adjacency;
pub mod cad;
pub mod closest;
pub mod eval;
pub mod table;
pub mod tessellate;
#[cfg(feature = "unit-tests")]
pub(crate) mod testing;
pub mod validate;

pub use crate::bezier::complex::{PatchComplex, Provenance};
pub use crate::mesh::Element;

pub use crate::host::{ComplexOptions, Fallback, SurfaceOutput};

use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use crate::schemes::prepare::{Prepared, Purpose};
use crate::schemes::{Spec, registry};

/// The exact surface of `mesh` under a scheme with its parameters: the registry's descriptor
/// builds it on the net [`prepare`] makes ready for it (with `spec.params.prepare`), and the
/// patches' domains are moved back into `mesh`'s faces. `progress(ring)` is called as rings are
/// produced.
///
/// # Errors
/// [`Error::InvalidArgument`] for a scheme without patch output (listing those with one);
/// whatever the scheme reports for the net.
pub fn build(
    spec: &Spec,
    mesh: &PolyMesh,
    opts: ComplexOptions,
    progress: &mut dyn FnMut(usize),
) -> Result<SurfaceOutput> {
    let prepared = prepare(spec, mesh)?;
    build_prepared(spec, &prepared, opts, progress)
}

/// The net the scheme's patch rules take: `mesh` prepared by the smallest documented step its
/// descriptor declares ([`crate::schemes::prepare`]), or `mesh` itself.
///
/// # Errors
/// Those of a preparation step.
pub fn prepare(spec: &Spec, mesh: &PolyMesh) -> Result<Prepared> {
    let desc = registry().descriptor(spec.id);
    crate::schemes::prepare::prepare(desc, spec, mesh, Purpose::Patches)
}

/// [`build`] on a net [`prepare`] made ready: the complex's domains refer to the input net's
/// faces, and the notes start with the preparation's.
///
/// # Errors
/// As [`build`].
pub fn build_prepared(
    spec: &Spec,
    prepared: &Prepared,
    opts: ComplexOptions,
    progress: &mut dyn FnMut(usize),
) -> Result<SurfaceOutput> {
    // the caps' decompositions round alike on every machine
    crate::linalg::deterministic();
    let rules = registry().descriptor(spec.id).patch_rules(spec)?;
    let mut out = match rules {
        Some(r) => r.build(&prepared.mesh, opts, progress)?,
        None => return Err(no_patch_output(spec.name())),
    };
    prepared.lift(&mut out.complex);
    let mut notes = prepared.notes(spec.name());
    notes.append(&mut out.notes);
    out.notes = notes;
    out.notes.extend(uncapped_notes(&out.complex, opts.fill));
    Ok(out)
}

/// The notes on the complex's holes that no G^1 cap closes
/// ([`PatchComplex::uncapped`](crate::bezier::complex::PatchComplex::uncapped)): one per
/// reason, naming the first few elements (a user reading `check`'s `cap|cap` defects of a C^0
/// fill learns why).
fn uncapped_notes(complex: &PatchComplex, fill: bool) -> Vec<String> {
    use crate::mesh::Element;
    use std::collections::{BTreeMap, HashMap, HashSet};
    let mut by_reason: BTreeMap<String, Vec<Element>> = BTreeMap::new();
    for (e, why) in &complex.uncapped {
        let elements = by_reason.entry(why.clone()).or_default();
        if !elements.contains(e) {
            elements.push(*e);
        }
    }
    // holes of fewer than 3 sectors that no provider builds a hole for (the quad-layout
    // providers close two sectors with the half-plane cap): found here, by their fill's
    // patches
    let capped: HashSet<Element> = complex
        .caps
        .iter()
        .filter_map(|c| match complex.provenance.get(c.first as usize) {
            Some(Provenance::Cap { element, .. }) => Some(*element),
            _ => None,
        })
        .collect();
    let mut order: Vec<Element> = Vec::new();
    let mut sectors: HashMap<Element, HashSet<u32>> = HashMap::new();
    for p in &complex.provenance {
        if let Provenance::Cap { element, sector } = p
            && !capped.contains(element)
        {
            sectors
                .entry(*element)
                .or_insert_with(|| {
                    order.push(*element);
                    HashSet::new()
                })
                .insert(*sector);
        }
    }
    // an element whose cap failed is named with its own reason above
    let failed: HashSet<Element> = complex.uncapped.iter().map(|(e, _)| *e).collect();
    for e in order {
        let k = sectors[&e].len();
        if k < 3 && !failed.contains(&e) {
            by_reason
                .entry(format!(
                    "a hole of {k} sectors, which this scheme's G^1 caps do not take"
                ))
                .or_default()
                .push(e);
        }
    }
    const NAMED: usize = 4;
    by_reason
        .into_iter()
        .map(|(why, elements)| {
            let mut named: Vec<String> = elements
                .iter()
                .take(NAMED)
                .map(|&e| crate::host::caps::describe(e))
                .collect();
            if elements.len() > NAMED {
                named.push(format!("{} more", elements.len() - NAMED));
            }
            let closed = if fill {
                "the scheme's C^0 fill closes the hole (not G^1 there)"
            } else {
                "left open (--no-fill)"
            };
            format!("no G^1 cap at {}: {why}; {closed}", named.join(", "))
        })
        .collect()
}

/// The error for a scheme name without patch output, listing the schemes that have it.
pub fn no_patch_output(name: &str) -> Error {
    Error::InvalidArgument(format!(
        "scheme '{name}' has no exact patch output (available: {})",
        registry().names_with(|c| c.patches).join(", ")
    ))
}

/// The exact surface of `mesh` under the named scheme as a patch complex. `progress(level)` is
/// called as rings are produced.
pub fn complex(
    scheme: &str,
    mesh: &PolyMesh,
    opts: ComplexOptions,
    progress: impl FnMut(usize),
) -> Result<PatchComplex> {
    complex_with_notes(scheme, mesh, opts, Fallback::default(), progress).map(|(c, _)| c)
}

/// Like [`complex`], with the fallback for valences without rules, and notes for the user (which
/// elements fell back to which rules).
pub fn complex_with_notes(
    scheme: &str,
    mesh: &PolyMesh,
    opts: ComplexOptions,
    fallback: Fallback,
    mut progress: impl FnMut(usize),
) -> Result<(PatchComplex, Vec<String>)> {
    let mut spec = registry()
        .lookup(scheme)
        .map_err(|_| no_patch_output(scheme))?;
    spec.params.fallback = fallback;
    let o = build(&spec, mesh, opts, &mut progress)?;
    Ok((o.complex, o.notes))
}
