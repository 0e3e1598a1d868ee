//! Doo-Sabin's local analysis: the subdivision matrix of an `n`-gon facet, read off the scheme's
//! own refinement of a prism.

use super::DooSabin;
use crate::error::{Error, Result};
use crate::mesh::nets;
use crate::schemes::Scheme;
use crate::schemes::circulant::SparseLocal;
use crate::schemes::local::{LocalMatrix, check_valence};
use crate::schemes::options::ids;

/// Doo-Sabin's `n x n` block of an `n`-gon facet: the child points of the facet's corners in
/// terms of its corners (the facet of a prism cap).
pub fn local_matrix(n: usize) -> Result<LocalMatrix> {
    Ok(local_sparse(n)?.to_matrix())
}

/// [`local_matrix`]'s rows, sparse (for its Fourier blocks at large valences: one circulant
/// `n x n` block, whose Fourier blocks are `1 x 1`, the eigenvalues of
/// [`super::fourier`]'s closed form).
pub fn local_sparse(n: usize) -> Result<SparseLocal> {
    check_valence(n)?;
    let net = nets::prism(n);
    let f = (0..net.num_faces())
        .find(|&f| net.face_size(f) == n && n != 4 || (n == 4 && f == 0))
        .unwrap_or(0);
    let r = DooSabin.refine(&net)?;
    // Child point h is the point of parent corner (half-edge) h.
    let h0 = net.face_halfedge(f) as usize;
    let rows: Vec<usize> = (h0..h0 + n).collect();
    let cols: Vec<usize> = net.face(f).iter().map(|&v| v as usize).collect();
    let t = r
        .stencils
        .select_rows(&rows)
        .restrict_sources(&cols)
        .ok_or_else(|| Error::Unsupported("Doo-Sabin facet block is not invariant".into()))?;
    Ok(SparseLocal::from_table(
        ids::DOO_SABIN.name(),
        (0, 1, n),
        &t,
    ))
}
