//! Loop's local analysis: the subdivision matrix on the one-ring of any valence, read off the
//! scheme's own refinement of a triangle fan.

use super::Loop;
use crate::error::{Error, Result};
use crate::mesh::nets;
use crate::schemes::Scheme;
use crate::schemes::circulant::SparseLocal;
use crate::schemes::local::{LocalMatrix, check_valence};
use crate::schemes::registry::ids;

/// Loop on the one-ring of a vertex of valence `n` (`n + 1` points: centre, then its neighbours
/// in counter-clockwise order).
pub fn local_matrix(n: usize) -> Result<LocalMatrix> {
    Ok(local_sparse(n)?.to_matrix())
}

/// [`local_matrix`]'s rows, sparse (for its Fourier blocks at large valences).
pub fn local_sparse(n: usize) -> Result<SparseLocal> {
    check_valence(n)?;
    let net = nets::loop_net(n, 2);
    let r = Loop.refine(&net)?;
    // Child of the centre is vertex 0; its neighbours are the edge points of the centre's edges.
    let nv = net.num_vertices();
    let mut rows = vec![0usize];
    for h in net.outgoing_halfedges(0) {
        rows.push(nv + net.he_edge(h) as usize);
    }
    let mut cols = vec![0usize];
    cols.extend(net.vertex_neighbors(0).iter().map(|&v| v as usize));
    let t = r
        .stencils
        .select_rows(&rows)
        .restrict_sources(&cols)
        .ok_or_else(|| Error::Unsupported("Loop one-ring is not invariant".into()))?;
    Ok(SparseLocal::from_table(ids::LOOP.name(), (1, 1, n), &t))
}
