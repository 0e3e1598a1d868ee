//! Exact surfaces of whole nets: the patch complexes of every scheme (regular patches, rings
//! around extraordinary elements, caps), built by the scheme's rules, and what is computed from
//! them (tessellations, adjacency of patch sides, the validity checks before output, the patch
//! stencil tables that re-apply a complex to moved control points).
//!
//! The complex itself ([`PatchComplex`], [`Provenance`]) lives in [`crate::bezier::complex`] and
//! the extraordinary elements ([`Element`]) in [`crate::mesh`]; both are re-exported here.

pub mod adjacency;
pub mod eval;
pub mod table;
pub mod tessellate;
#[cfg(test)]
pub(crate) mod testing;
pub mod validate;

pub use crate::bezier::complex::{PatchComplex, Provenance};
pub use crate::mesh::Element;

pub use crate::host::{ComplexOptions, Fallback, SurfaceOutput};

use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use crate::schemes::{Spec, registry};

/// The exact surface of `mesh` under a scheme with its parameters: the registry's descriptor
/// builds it. `progress(ring)` is called as rings are produced.
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
    let rules = registry().descriptor(spec.id).patch_rules(spec)?;
    match rules {
        Some(r) => r.build(mesh, opts, progress),
        None => Err(no_patch_output(spec.name())),
    }
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
