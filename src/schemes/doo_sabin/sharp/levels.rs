//! One whole-net step of a dual scheme on a net with sharp features (`--levels`): the step of
//! [`crate::schemes::doo_sabin::surface::step`] with every face selected, laid out like the
//! plain step of [`crate::schemes::doo_sabin`].
//!
//! # Layout
//!
//! Child points: `h` for the corner of half-edge `h`; then two per sharp edge (boundary edges
//! and creases, in edge order: near the start of its edge half-edge, near its end); then the
//! kept points in vertex order. Child faces: the F-face of parent face `f` (index `f`), the
//! E-faces in edge order (one half per side of a crease), the V-faces in vertex order (one per
//! sector between sharp edges). This is the mesh layer's dual split numbered by kind
//! ([`crate::mesh::dual_split::DualOrder::ByKind`]). The child's extras carry the sharpness of its crease edges and kept points
//! (and its boundary edges, infinitely sharp), already sharpened, and the parent's boundary
//! mode and crease method.

use super::step::Creases;
use crate::error::Result;
use crate::host::adaptive::Info;
use crate::mesh::PolyMesh;
use crate::mesh::dual_split::DualOrder;
use crate::schemes::Refinement;
use crate::schemes::doo_sabin::surface::step::{StepIn, dual_step};
use crate::stencil::{Stencil, StencilTable};

/// One step of `mesh` with its creases `creases` and the corner rule `corner` (see the
/// [module](self) documentation).
///
/// # Errors
/// Those of building the child net.
pub(crate) fn refine_creased(
    mesh: &PolyMesh,
    creases: &Creases<'_>,
    corner: &mut dyn FnMut(&PolyMesh, u32) -> Stencil,
) -> Result<Refinement> {
    let info = vec![
        Info {
            pos_ok: true,
            fan_ok: true,
            origin: None,
        };
        mesh.num_vertices()
    ];
    let face_origin = vec![None; mesh.num_faces()];
    let inp = StepIn {
        mesh,
        info: &info,
        rule_free: None,
        face_origin: &face_origin,
        face_corners: None,
    };
    let all: Vec<u32> = (0..mesh.num_faces() as u32).collect();
    // the layout: corners by half-edge, Chaikin points by edge, kept points by vertex
    let out = dual_step(&inp, (all, DualOrder::ByKind), corner, Some(creases))?;
    let table = StencilTable::from_rows(mesh.num_vertices(), out.composed_stencils(), 6);
    let positions = table.apply(mesh.positions());
    let child = PolyMesh::from_refinement(positions, out.split.face_start, out.split.corners)?;
    let extras = out.extras;
    Ok(Refinement {
        mesh: child.with_extras(extras),
        stencils: table,
    })
}
