//! USD: `UsdGeomMesh` control nets in, meshes and control nets out (`.usda`, `.usdc`,
//! `.usdz`), through the `openusd` crate (a pure-Rust implementation of Pixar's formats: the
//! text and crate encodings, usdz packages, and composition, so a mesh that a file references
//! or pulls in by payload, sublayer or variant is read as `usd-core` composes it).
//!
//! # Reading
//!
//! The first `Mesh` prim of the composed stage (in traversal order, inactive prims skipped) is
//! the net; the others are named in a warning. Read, at the default time (or the first time
//! sample, with a warning):
//!
//! | attribute | becomes |
//! | --- | --- |
//! | `points`, `faceVertexCounts`, `faceVertexIndices` | the net (float, double or half points) |
//! | `orientation = "leftHanded"` | faces reversed to counter-clockwise (a note says so) |
//! | `creaseIndices`, `creaseLengths`, `creaseSharpnesses` | crease tags: each chain's edges, one sharpness per chain or per edge |
//! | `cornerIndices`, `cornerSharpnesses` | corner tags |
//! | `holeIndices` | hole tags |
//! | `interpolateBoundary` | boundary option (`none`, `edgeOnly`, `edgeAndCorner`) |
//! | `faceVaryingLinearInterpolation` | fvar option (USD's fallback `cornersPlus1` when unauthored) |
//! | `triangleSubdivisionRule` | Catmull-Clark's triangle option (`catmullClark`, `smooth`) |
//! | `primvars:st` (+ `:indices`) | texture coordinates: `faceVarying`, `vertex` or `varying` interpolation |
//! | `subdivisionScheme` | a note when it is not `catmullClark` (the command's `--scheme` refines) |
//!
//! Errors name the file, the prim and the attribute (and the face or index); the mesh is then
//! validated as every reader's is.
//!
//! # Writing
//!
//! One layer: `defaultPrim` an `Xform` named after the file, holding `Mesh "mesh"`, with
//! `upAxis = "Y"`, `metersPerUnit = 1`. The mesh has `points` (float, as USD's schema types
//! them), `extent`, the face arrays, `subdivisionScheme` (`none` for refined meshes and
//! tessellations: they are drawn as they are), `normals` (vertex interpolation) and, where the
//! mesh has them, `primvars:st` (face-varying, indexed), per-vertex `float[]` primvars
//! (`gaussianCurvature`, `meanCurvature`) and `primvars:displayColor`. A control net gets its
//! scheme (`catmullClark`, `loop`) and its tags: every sharp edge a crease of two vertices,
//! corners, holes, `interpolateBoundary`, `faceVaryingLinearInterpolation` and (Catmull-Clark)
//! `triangleSubdivisionRule`. `.usdz` packages the text layer. `.usdc` (the binary crate
//! encoding) is read but not written: openusd 0.6's crate writer stores the children of prims
//! as a token array where usd-core requires a token vector, and usd-core refuses such files
//! (fixed in openusd 0.8, which needs a newer Rust than fairsub builds with).

mod read;
mod write;

pub use read::read_usd_with;
pub use write::write_usd;

/// The encodings of USD fairsub writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UsdFlavor {
    /// Text (`.usda`, and `.usd`, which USD reads in either encoding).
    Usda,
    /// `.usdz` package (a zip of the text layer, entries aligned to 64 bytes).
    Usdz,
}

/// Why `.usdc` is not written (the reader reads it).
pub const NO_USDC: &str = "fairsub writes USD as text (.usda, .usd) or as a package (.usdz), \
     not as .usdc: the crate writer of openusd 0.6 (the last release that builds on this \
     toolchain) stores prim children in a form usd-core rejects";

#[cfg(feature = "unit-tests")]
mod tests;
