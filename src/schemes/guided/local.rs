//! Guided subdivision's local analysis: the subdivision matrix on the guide's free set, its
//! contraction, the characteristic ring sampled from the planar guide, and table (5).

use crate::error::Result;
use crate::schemes::local::{LocalMatrix, check_valence};

/// The contraction of guided subdivision: Catmull-Clark's lambda, or 1/2.
pub fn lambda(n: usize, chi: crate::schemes::guided::chi::ChiKind) -> f64 {
    match chi {
        crate::schemes::guided::chi::ChiKind::CatmullClark => {
            crate::schemes::catmull_clark::catmull_clark_lambda(n)
        }
        crate::schemes::guided::chi::ChiKind::Half => 0.5,
    }
}

/// Guided subdivision's subdivision matrix `M` on the free set `P` of the guide (Section 5 and
/// Appendix C of the paper): the guide restricted to `[0, lambda]^2` by de Casteljau, in the
/// guide's coordinates. For the bi-5 guide these are the paper's coordinates (6 central ones, one
/// more for n = 3, 6, then 18 per sector); the central quadratic expansion is not
/// rotation-invariant, so the matrix has no discrete Fourier blocks of the sector-periodic form
/// (the Bloch basis of [`super::fourier`] splits it by frequency). Its eigenvalues are
/// `lambda^s`, `s = 0..10`, with the multiplicities of the paper's table (5). The matrix does not
/// depend on the ring degree (bi-5 or bi-6) or on chi, only on `lambda`.
pub fn local_matrix(
    n: usize,
    degree: crate::schemes::guided::guide::GuideDegree,
    lambda: f64,
) -> Result<LocalMatrix> {
    check_valence(n)?;
    let space = crate::schemes::guided::guide::GuideSpace::new(n, degree)?;
    let m = space.step_matrix(lambda);
    let (centre, sector) = if space.centre + 18 * n == space.dim() {
        (space.centre, 18)
    } else {
        (space.dim(), 0)
    };
    Ok(LocalMatrix {
        scheme: format!("guided (bi-{} guide)", space.degree),
        n,
        centre,
        sector,
        matrix: m,
    })
}

/// The matrix the analysis decomposes: [`local_matrix`] within
/// [`crate::linalg::MAX_DENSE_EIGEN_ROWS`] rows (so that outputs there are the dense path's
/// to the bit) or for guides without the paper's coordinates (bi-4, bi-3, valence 4), the
/// Fourier blocks of the bi-5 guide's matrix ([`super::fourier::GuidedBlocks`]) above.
///
/// # Errors
/// As [`local_matrix`] and [`super::fourier::GuidedBlocks::new`].
pub fn operator(
    n: usize,
    degree: crate::schemes::guided::guide::GuideDegree,
    lambda: f64,
) -> Result<Box<dyn crate::schemes::local::LocalOperator>> {
    check_valence(n)?;
    let bloch = degree == crate::schemes::guided::guide::GuideDegree::Bi5 && n != 4;
    let rows = 6 + usize::from(n == 3 || n == 6) + 18 * n;
    if !bloch || rows <= crate::schemes::circulant::dense_rows() {
        return Ok(Box::new(local_matrix(n, degree, lambda)?));
    }
    Ok(Box::new(super::fourier::GuidedBlocks::new(
        "guided (bi-5 guide)",
        n,
        lambda,
    )?))
}

/// The characteristic ring of guided subdivision: the ring sampled from the planar guide `L`
/// (the subdominant eigenfunctions), i.e. chi re-expressed in bi-5 or bi-6 form by the scheme's
/// own ring table, and lambda.
pub fn characteristic_ring(
    n: usize,
    o: crate::schemes::guided::rings::GuidedOptions,
) -> Result<(Vec<crate::bezier::BezierPatch>, f64)> {
    // The ring tables only: neither the guide space nor the fit (O(1) in n).
    let g = crate::schemes::guided::rings::RingTables::new(n, o)?;
    let d = o.ring.degree();
    let dg = o.guide.degree();
    let mg = (dg + 1) * (dg + 1);
    let l = crate::schemes::guided::guide::shear_coeffs(n, dg);
    let lambda = g.chi.lambda;
    let m = (d + 1) * (d + 1);
    let mut out = Vec::with_capacity(3 * n);
    for s in 0..n {
        let ring = &g.ring_table * l.rows(s * mg, mg);
        for x in 0..3 {
            let cps: Vec<[f64; 3]> = (0..m)
                .map(|r| {
                    let r = x * m + r;
                    [ring[(r, 0)] / lambda, ring[(r, 1)] / lambda, 0.0]
                })
                .collect();
            match o.ring.macro_kind() {
                None => out.push(crate::bezier::BezierPatch::new(d, d, cps)),
                // The macro variants: the pieces of the macro patch.
                Some(k) => out.extend(
                    k.pieces_of(&cps)
                        .into_iter()
                        .map(|p| crate::bezier::BezierPatch::new(k.degree(), k.degree(), p)),
                ),
            }
        }
    }
    Ok((out, lambda))
}

/// Table (5) of the guided paper against a computed matrix: for `s = 0..=10`, the published
/// multiplicity of `lambda^s` (1, 2, 3, n*, 2n, 3n, 3n, 3n, 3n, 2n, n) and the number of
/// the eigenvalues `ev` (of the matrix, with repetitions) within `1e-6` (relative) of
/// `lambda^s`.
pub fn table5(n: usize, lambda: f64, ev: &[crate::linalg::C64]) -> Vec<(usize, usize, usize)> {
    let ns = crate::schemes::guided::guide::n_star(n);
    let published = [1, 2, 3, ns, 2 * n, 3 * n, 3 * n, 3 * n, 3 * n, 2 * n, n];
    (0..=10)
        .map(|s| {
            let t = lambda.powi(s as i32);
            let count = ev
                .iter()
                .filter(|z| (z.re - t).abs() < 1e-6 * t.max(1e-4) + 1e-9 && z.im.abs() < 1e-7)
                .count();
            (s, published[s], count)
        })
        .collect()
}
