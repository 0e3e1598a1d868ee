//! Loop's local analysis: the subdivision matrix on the one-ring of any valence, read off the
//! scheme's own refinement of a triangle fan.

use super::Loop;
use crate::error::{Error, Result};
use crate::mesh::nets;
use crate::mesh::tri_split::one_ring_rows;
use crate::schemes::Scheme;
use crate::schemes::circulant::SparseLocal;
use crate::schemes::local::{LocalMatrix, check_valence};
use crate::schemes::options::ids;

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
    // Child of the centre is vertex 0; its neighbours are the edge points of the centre's edges
    // (Loop's child layout is the 1-4 split's).
    let (rows, cols) = one_ring_rows(&net, 0);
    let t = r
        .stencils
        .select_rows(&rows)
        .restrict_sources(&cols)
        .ok_or_else(|| Error::Unsupported("Loop one-ring is not invariant".into()))?;
    Ok(SparseLocal::from_table(ids::LOOP.name(), (1, 1, n), &t))
}
