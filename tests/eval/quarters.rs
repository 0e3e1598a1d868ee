//! Which face points the schemes whose patches are centred at vertices (Doo-Sabin, DS^CC,
//! PGS, TPS) evaluate: the quarters of faces at interior vertices (`tests/eval_dual.rs`,
//! `tests/eval_ternary.rs`).

use fairsub::mesh::PolyMesh;

/// Whether a face point lies in a quarter at an interior vertex (those at boundary vertices
/// are not tracked by the schemes whose patches are centred at vertices: Doo-Sabin, DS^CC,
/// PGS, TPS): the quarter at corner `floor(u)` of an n-gon, at the nearest corner of a quad.
pub fn at_interior_vertex(mesh: &PolyMesh, (f, u, v): (u32, f64, f64)) -> bool {
    let face = mesh.face(f as usize);
    let k = if face.len() == 4 {
        match (u >= 0.5, v >= 0.5) {
            (false, false) => 0,
            (true, false) => 1,
            (true, true) => 2,
            (false, true) => 3,
        }
    } else {
        (u.floor() as usize).min(face.len() - 1)
    };
    !mesh.is_boundary_vertex(face[k] as usize)
}
