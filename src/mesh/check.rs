//! The checks of a flat input net (faces of three or more corners in range, finite
//! coordinates, no corner listed twice) and the face-size test, shared by the mesh's
//! constructors ([`super::PolyMesh::from_flat`], [`super::PolyMesh::from_flat_general`]) and
//! the tagged nets ([`super::Extras`]).

use crate::error::{MeshError, Result};
use crate::geom::Point;

/// The first vertex that face `f` (corners `face`, all in range) lists twice. Small faces
/// compare pairs; large faces mark the vertices in `last_face` (face index + 1 per vertex,
/// sized on first use), so the check is linear in the face size.
pub(super) fn repeated_corner(face: &[u32], f: u32, last_face: &mut Vec<u32>) -> Option<usize> {
    if face.len() <= 16 {
        for i in 0..face.len() {
            if face[i + 1..].contains(&face[i]) {
                return Some(face[i] as usize);
            }
        }
        return None;
    }
    let need = face.iter().map(|&v| v as usize + 1).max().unwrap_or(0);
    if last_face.len() < need {
        last_face.resize(need, 0);
    }
    for &v in face {
        if last_face[v as usize] == f + 1 {
            return Some(v as usize);
        }
        last_face[v as usize] = f + 1;
    }
    None
}

/// The common size of the faces given by `face_start`, or 0 when sizes differ.
pub(super) fn uniform_size(face_start: &[u32]) -> u32 {
    if face_start.len() < 2 {
        return 0;
    }
    let k = face_start[1] - face_start[0];
    if face_start.windows(2).all(|w| w[1] - w[0] == k) {
        k
    } else {
        0
    }
}

/// The number of faces of flat face arrays (`face_start` holds one offset more), refusing a net
/// without faces or without points. One source for [`super::PolyMesh::from_flat`] and
/// [`super::PolyMesh::from_flat_general`].
pub(super) fn face_count(positions: &[Point], face_start: &[u32]) -> Result<usize> {
    let nf = face_start.len().saturating_sub(1);
    if nf == 0 || positions.is_empty() {
        return Err(MeshError::Empty.into());
    }
    Ok(nf)
}

/// The checks every face of a flat input passes: at least three corners, each naming one of the
/// `nv` vertices (errors name face `f`). One source for [`PolyMesh::from_flat`] and
/// [`super::PolyMesh::from_flat_general`].
pub(crate) fn check_face(face: &[u32], f: usize, nv: usize) -> Result<()> {
    if face.len() < 3 {
        return Err(MeshError::FaceTooSmall {
            face: f,
            len: face.len(),
        }
        .into());
    }
    match face.iter().find(|&&v| v as usize >= nv) {
        Some(&v) => Err(MeshError::IndexOutOfRange {
            face: f,
            index: v as i64,
            count: nv,
        }
        .into()),
        None => Ok(()),
    }
}

/// The first vertex with a non-finite coordinate, as an error naming it.
pub(crate) fn check_finite(positions: &[Point]) -> Result<()> {
    match positions
        .iter()
        .position(|p| !p.iter().all(|c| c.is_finite()))
    {
        Some(vertex) => Err(MeshError::NonFiniteCoordinate { vertex }.into()),
        None => Ok(()),
    }
}
