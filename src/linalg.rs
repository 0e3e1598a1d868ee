//! Dense linear algebra shared by every layer: eigenvalues (by `faer`, whose Schur iteration
//! stays robust on the highly defective matrices of subdivision), numerical null spaces (one
//! function, by SVD, for real and complex matrices) and polynomials from their roots.

use nalgebra::{Complex, ComplexField, DMatrix, DVector};

/// Makes `faer` work on the calling thread from now on (for the whole process): its default
/// splits a decomposition by the number of threads, and the rounding of that split changed
/// the last bits of results between one thread and several (a cap's coefficients under
/// `RAYON_NUM_THREADS=1`, on a one-core machine or container), so the same job wrote
/// different files on different machines. The dense problems here are small enough that one
/// thread costs little. The command line and the Python package call this on start, and
/// [`crate::surface::build`] before it builds a surface.
pub fn deterministic() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| faer::set_global_parallelism(faer::Par::Seq));
}

/// Complex numbers of the eigen computations.
pub type C64 = Complex<f64>;

/// All eigenvalues of a real square matrix (computed by `faer`, whose Schur iteration is robust
/// on the highly defective matrices of subdivision; nalgebra's stalls on the regular ones).
pub fn eigenvalues(m: &DMatrix<f64>) -> Vec<C64> {
    let f = faer::Mat::<f64>::from_fn(m.nrows(), m.ncols(), |i, j| m[(i, j)]);
    f.eigenvalues()
        .map(|v| v.into_iter().map(|z| C64::new(z.re, z.im)).collect())
        .unwrap_or_default()
}

/// All eigenvalues of a complex square matrix.
pub fn complex_eigenvalues(m: &DMatrix<C64>) -> Vec<C64> {
    let f = faer::Mat::<faer::c64>::from_fn(m.nrows(), m.ncols(), |i, j| {
        let z = m[(i, j)];
        faer::c64::new(z.re, z.im)
    });
    f.eigenvalues()
        .map(|v| v.into_iter().map(|z| C64::new(z.re, z.im)).collect())
        .unwrap_or_default()
}

/// Coefficients (highest degree first, monic) of the polynomial with the given roots.
pub fn poly_from_roots(roots: &[C64]) -> Vec<C64> {
    let mut c = vec![C64::new(1.0, 0.0)];
    for &r in roots {
        let mut next = vec![C64::new(0.0, 0.0); c.len() + 1];
        for (i, &a) in c.iter().enumerate() {
            next[i] += a;
            next[i + 1] -= a * r;
        }
        c = next;
    }
    c
}

/// Orthonormal basis of the numerical null space of `a` (real or complex): the right singular
/// vectors whose singular values are at most `rel_tol` times the largest, in the order of the
/// SVD. A wide matrix is padded with zero rows first, so that every right singular vector is
/// computed.
pub fn null_space<T: ComplexField<RealField = f64>>(
    a: &DMatrix<T>,
    rel_tol: f64,
) -> Vec<DVector<T>> {
    let (r, c) = a.shape();
    let padded;
    let a = if r < c {
        let mut p = DMatrix::<T>::zeros(c, c);
        p.view_mut((0, 0), (r, c)).copy_from(a);
        padded = p;
        &padded
    } else {
        a
    };
    let svd = a.clone().svd(false, true);
    let v_t = svd.v_t.expect("requested");
    let smax = svd.singular_values.iter().copied().fold(0.0, f64::max);
    (0..svd.singular_values.len())
        .filter(|&i| svd.singular_values[i] <= rel_tol * smax)
        .map(|i| v_t.row(i).adjoint())
        .collect()
}

/// Most rows of a dense matrix that fairsub decomposes for its eigenvalues (`analyze`,
/// `charmap`, the tangent masks of the bi-2 G^1 caps). Measured in release on one core of a
/// shared 2-core machine: the slowest scheme per row, guided-bi5, takes about 2 s at 384 rows
/// (valence 21) and the cost grows with the cube of the rows, so 450 rows keep every accepted
/// case within about 3 s (catmull-clark: 3 s at 721 rows).
pub const MAX_DENSE_EIGEN_ROWS: usize = 450;

/// The subdominant eigenvalue `lambda` of a local subdivision matrix `m` (the largest modulus
/// below the dominant eigenvalue 1) and a basis of its left eigenspace, when that eigenvalue is
/// real, positive and of geometric multiplicity two (the tangent pair of a scheme at an
/// extraordinary element): applied to the local vector, the two left eigenvectors give two
/// vectors spanning the limit tangent plane. `None` otherwise (complex or simple subdominant
/// eigenvalue, or a Jordan block).
pub fn subdominant_left_pair(m: &DMatrix<f64>) -> Option<(f64, [DVector<f64>; 2])> {
    let n = m.nrows();
    let mut ev = eigenvalues(m);
    ev.sort_by(|a, b| b.norm().total_cmp(&a.norm()));
    // skip the eigenvalue 1 (affine invariance; possibly repeated for a block-triangular m)
    let sub = *ev
        .iter()
        .find(|z| (**z - C64::new(1.0, 0.0)).norm() > 1e-8)?;
    if sub.im.abs() > 1e-8 * sub.norm() || sub.re <= 0.0 {
        return None;
    }
    let lambda = sub.re;
    let shifted = m.transpose() - DMatrix::<f64>::identity(n, n) * lambda;
    let null = null_space(&shifted, 1e-8);
    match null.as_slice() {
        [a, b] => Some((lambda, [a.clone(), b.clone()])),
        _ => None,
    }
}
