//! Hole faces removed before the dual schemes' patches: a bi-2 patch spans the quarters of four
//! faces, so a hole cannot be refined for support and left out as OpenSubdiv leaves it; the
//! faces around a hole end on its boundary curve instead. The removal keeps the net's creases
//! and corner tags (by end points and renumbered vertices), so the cut and the spending steps
//! that follow see them.

use crate::mesh::{PolyMesh, SharpEdges};

/// The faces of `mesh` that are not hole faces, in order: face `k` of [`without_holes`]'s net
/// is face `kept_faces(mesh)[k]` of `mesh`.
pub(crate) fn kept_faces(mesh: &PolyMesh) -> Vec<usize> {
    (0..mesh.num_faces())
        .filter(|&f| !mesh.is_hole(f))
        .collect()
}

/// `mesh` without its `holes` tagged hole faces, with a note when there are any: a bi-2 patch
/// spans the quarters of four faces, so a hole cannot be refined for support and left out.
pub(crate) fn without_holes(
    mesh: &PolyMesh,
    holes: usize,
    name: &str,
    notes: &mut Vec<String>,
) -> PolyMesh {
    if holes == 0 {
        return mesh.clone();
    }
    notes.push(format!(
        "{holes} hole faces removed before the patches ({name}'s patches span four faces, so a \
         hole cannot be refined for support and left out): the surface ends on the hole's \
         boundary curve"
    ));
    // `PolyMesh::without_holes` renumbers the edges and drops the tags by edge index (it makes
    // output nets): the sharp edges are carried by their end points instead, whose indices it
    // keeps, those of edges only hole faces had dropped with them
    let pairs: Vec<([u32; 2], f32)> = match mesh.extras().map(|e| &e.sharp_edges) {
        Some(SharpEdges::ById(v)) => v
            .iter()
            .map(|&(e, s)| {
                let h = mesh.edge_halfedge(e as usize);
                ([mesh.he_from(h), mesh.he_to(h)], s)
            })
            .collect(),
        Some(SharpEdges::ByPair(v)) => v.clone(),
        None => Vec::new(),
    };
    let net = mesh.clone().without_holes();
    let mut ex = net.extras().cloned().unwrap_or_default();
    // the vertices only hole faces had are dropped (the dual hosts take every vertex for one
    // with faces), and the tags follow the renumbering
    let face_start: Vec<u32> = std::iter::once(0)
        .chain(net.faces().scan(0u32, |n, f| {
            *n += f.len() as u32;
            Some(*n)
        }))
        .collect();
    let corners: Vec<u32> = net.faces().flatten().copied().collect();
    let Ok(compact) = PolyMesh::from_flat(net.positions().to_vec(), face_start, corners) else {
        // every face a hole: the scheme refuses the empty net with its own message
        return net;
    };
    let new = |v: u32| compact.input_vertex(v as usize);
    ex.sharp_edges = SharpEdges::ByPair(
        pairs
            .into_iter()
            .filter_map(|([a, b], s)| Some(([new(a)?, new(b)?], s)))
            .filter(|([a, b], _)| compact.find_edge(*a, *b).is_some())
            .collect(),
    );
    ex.sharp_vertices = ex
        .sharp_vertices
        .iter()
        .filter_map(|&(v, s)| Some((new(v)?, s)))
        .collect();
    compact.with_extras(Some(ex))
}
