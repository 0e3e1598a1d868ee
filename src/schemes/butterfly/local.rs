//! The modified butterfly's local analysis: the subdivision matrix on the one-ring of an
//! interior vertex of valence `n != 6`, read off the scheme's own refinement of a triangle fan.
//!
//! At such a vertex every edge point of its edges uses the extraordinary rule (its neighbours
//! are regular), which reads the one-ring only, so the one-ring is invariant; its matrix is the
//! vertex row `(1, 0, ..)` over the rows of the rule, whose eigenvalues are 1 and the discrete
//! Fourier transform of `s_j`: `1/2` (twice) and `1/4` (twice) for `n >= 5`, as ZSS designed
//! the weights. At valence 6 the regular stencil reaches the two-ring and beyond, so there is
//! no one-ring matrix (an error says so).

use super::Butterfly;
use crate::error::{Error, Result};
use crate::mesh::nets;
use crate::mesh::tri_split::one_ring_rows;
use crate::schemes::Scheme;
use crate::schemes::circulant::SparseLocal;
use crate::schemes::local::{LocalMatrix, check_valence};
use crate::schemes::options::ids;

/// The matrix on the one-ring of valence `n` (`n + 1` points: centre, then its neighbours
/// counter-clockwise).
pub fn local_matrix(n: usize) -> Result<LocalMatrix> {
    Ok(local_sparse(n)?.to_matrix())
}

/// [`local_matrix`]'s rows, sparse (for its Fourier blocks at large valences).
pub fn local_sparse(n: usize) -> Result<SparseLocal> {
    check_valence(n)?;
    if n == 6 {
        return Err(Error::Unsupported(format!(
            "valence 6: the regular stencil of {} reaches beyond the one-ring, which is then \
             not invariant; the one-ring matrix exists at valences other than 6",
            ids::BUTTERFLY
        )));
    }
    let net = nets::loop_net(n, 2);
    let r = Butterfly.refine(&net)?;
    let (rows, cols) = one_ring_rows(&net, 0);
    let t = r
        .stencils
        .select_rows(&rows)
        .restrict_sources(&cols)
        .ok_or_else(|| {
            Error::Unsupported(format!("the {} one-ring is not invariant", ids::BUTTERFLY))
        })?;
    Ok(SparseLocal::from_table(
        ids::BUTTERFLY.name(),
        (1, 1, n),
        &t,
    ))
}
