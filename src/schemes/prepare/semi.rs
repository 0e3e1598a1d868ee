//! The semi-sharp features of a net: the elements [`Need::InfinitelySharpOnly`] names for the
//! schemes whose rules take infinitely sharp features only (the bi-2 family's element rings,
//! which spend semi-sharp ones by their own constructions, `crate::schemes::bi2::surface`).

use crate::mesh::{PolyMesh, SharpEdges};
use crate::schemes::sdc::crease::INFINITE;

#[cfg(doc)]
use crate::schemes::needs::Need;

/// Whether `s` is a finite positive sharpness.
fn semi(s: f32) -> bool {
    s > 0.0 && s < INFINITE
}

/// The semi-sharp edges of `mesh` by their end points, with their sharpness.
fn semi_sharp_edges(mesh: &PolyMesh) -> Vec<([u32; 2], f32)> {
    match mesh.extras().map(|ex| &ex.sharp_edges) {
        None => Vec::new(),
        Some(SharpEdges::ById(v)) => v
            .iter()
            .filter(|p| semi(p.1))
            .map(|&(e, s)| {
                let h = mesh.edge_halfedge(e as usize);
                ([mesh.he_from(h), mesh.he_to(h)], s)
            })
            .collect(),
        Some(SharpEdges::ByPair(v)) => v.iter().filter(|p| semi(p.1)).copied().collect(),
    }
}

/// The semi-sharp vertex tags of `mesh`, with their sharpness.
fn semi_sharp_tags(mesh: &PolyMesh) -> impl Iterator<Item = (u32, f32)> + '_ {
    mesh.extras()
        .into_iter()
        .flat_map(|ex| ex.sharp_vertices.iter().copied().filter(|p| semi(p.1)))
}

/// The vertices at semi-sharp features of `mesh` (the ends of its semi-sharp edges, its
/// semi-sharp vertices), sorted.
pub(super) fn semi_sharp_vertices(mesh: &PolyMesh) -> Vec<u32> {
    let mut out: Vec<u32> = semi_sharp_edges(mesh)
        .into_iter()
        .flat_map(|(ends, _)| ends)
        .chain(semi_sharp_tags(mesh).map(|(v, _)| v))
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}
