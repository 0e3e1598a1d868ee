//! The refusals of the bi-2 schemes whose boundary rules keep only corners of one face (TPS,
//! adjustable TPS, polar bi-2, the mixed scheme) on a net cut along its creases, and the
//! preparation's test that a dual step removes (`crate::schemes::prepare`).

use super::is_kept_corner;
use crate::error::{Error, Result};
use crate::mesh::tags::{BoundaryInterpolation, Named};
use crate::mesh::{NONE, PolyMesh};

/// For the bi-2 schemes whose boundary rules keep only single-face corners (TPS, adjustable
/// TPS, polar bi-2, the mixed scheme): refuses a cut net with a kept corner that has more than
/// one face, which those rules would not interpolate (the sides of the crease would part).
///
/// # Errors
/// [`Error::Unsupported`] naming the vertex and the way out.
pub fn refuse_kept_corners_with_faces(mesh: &PolyMesh, name: &str) -> Result<()> {
    let Some(ex) = mesh.extras() else {
        return Ok(());
    };
    for &(v, _) in &ex.sharp_vertices {
        let v = v as usize;
        if mesh.is_boundary_vertex(v) && !mesh.is_corner(v) {
            return Err(Error::Unsupported(format!(
                "vertex {v} of the net cut along its creases is a crease end or junction with \
                 {} faces on one side; {name}'s boundary rules keep only corners with one \
                 face, so the crease would open there (way out: {} or {}, which keep it)",
                mesh.outgoing(v).count(),
                crate::schemes::options::ids::PGS,
                crate::schemes::options::ids::DOO_SABIN
            )));
        }
    }
    Ok(())
}

/// The kept corners with more than one face ([`refuse_kept_corners_with_faces`]), as the
/// preparation's test (`crate::schemes::prepare::Need::Scheme`): one dual step makes each a
/// corner of one face (its V-face).
pub fn kept_corners_with_faces(
    mesh: &PolyMesh,
    _: &crate::schemes::descriptor::Spec,
) -> Vec<crate::mesh::Element> {
    let Some(ex) = mesh.extras() else {
        return Vec::new();
    };
    let in_a_face = |v: usize| v < mesh.num_vertices() && mesh.vertex_halfedge(v) != NONE;
    ex.sharp_vertices
        .iter()
        .map(|&(v, _)| v)
        .filter(|&v| {
            let v = v as usize;
            in_a_face(v) && mesh.is_boundary_vertex(v) && !mesh.is_corner(v)
        })
        .map(crate::mesh::Element::Vertex)
        .collect()
}

/// For the bi-2 schemes whose boundary rules keep single-face corners and have no others (TPS,
/// adjustable TPS, polar bi-2, the mixed scheme): refuses the boundary mode `none` on a net with
/// a boundary, and `edge-only` where a boundary vertex has a single face (its V-face would be a
/// triangle at the boundary, for which they have no rule).
///
/// # Errors
/// [`Error::Unsupported`] naming the vertex and the way out.
pub fn refuse_boundary_modes(mesh: &PolyMesh, name: &str) -> Result<()> {
    let mode = super::super::boundary_mode(mesh);
    if mode == BoundaryInterpolation::EdgeAndCorner {
        return Ok(());
    }
    let bad = |v: usize| {
        mesh.is_boundary_vertex(v)
            && (mode == BoundaryInterpolation::None
                || (mesh.is_corner(v) && !is_kept_corner(mesh, v)))
    };
    match (0..mesh.num_vertices()).find(|&v| bad(v)) {
        Some(v) => Err(Error::Unsupported(format!(
            "boundary vertex {v} under the boundary mode {}: {name}'s boundary rules keep \
             every corner with one face and have no rule for the boundary modes none and \
             edge-only there (way out: {}, {} or {}, which take them, or --boundary \
             edge-and-corner)",
            mode.name(),
            crate::schemes::options::ids::PGS,
            crate::schemes::options::ids::DOO_SABIN,
            crate::schemes::options::ids::DOO_SABIN_CC
        ))),
        None => Ok(()),
    }
}
