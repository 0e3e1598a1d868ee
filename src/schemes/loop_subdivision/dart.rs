//! Loop's limit point and tangent plane at a dart: an interior vertex of valence `n` with
//! exactly one infinitely sharp edge (OpenSubdiv's rules: the vertex keeps the smooth rule
//! `(1 - n beta) x + beta sum e_i`, [`Loop::vertex_beta`]; the smooth edges
//! `3/8 (x + e_i) + 1/8 (e_(i-1) + e_(i+1))`; the sharp edge its midpoint `(x + e_0) / 2`).
//! The 1-ring `x, e_0 .. e_(n-1)` (counter-clockwise from the sharp edge's end `e_0`) is mapped
//! onto itself; the left eigenvectors of its `(n + 1)^2` matrix are the dart's limit and
//! tangent masks ([`crate::schemes::sdc::dart`]). Spectrum (tested): `1`, then `0.3983` and `1/4`
//! at `n = 3`, `0.4518` and `0.375` at `n = 4`, `1/2` double at `n = 6`, `0.5518` and `0.5268`
//! at `n = 8`; the antisymmetric mode keeps the smooth vertex's subdominant eigenvalue
//! `3/8 + cos(2 pi / n) / 4`.

use super::Loop;
pub use crate::schemes::sdc::dart::{DartMasks, MAX_DART_VALENCE};
use crate::schemes::sdc::dart::{MaskCache, cached_masks};
use nalgebra::DMatrix;
use std::sync::{Arc, OnceLock};

/// The 1-ring subdivision matrix of a dart of valence `n` (module documentation); the smooth
/// one with `dart = false`.
fn ring_matrix(n: usize, dart: bool) -> DMatrix<f64> {
    let e = |i: usize| 1 + i % n;
    let beta = Loop::vertex_beta(n);
    let mut s = DMatrix::zeros(n + 1, n + 1);
    s[(0, 0)] = 1.0 - n as f64 * beta;
    for i in 0..n {
        s[(0, e(i))] = beta;
        if i == 0 && dart {
            s[(e(0), 0)] = 0.5;
            s[(e(0), e(0))] = 0.5;
        } else {
            s[(e(i), 0)] += 0.375;
            s[(e(i), e(i))] += 0.375;
            s[(e(i), e(i + n - 1))] += 0.125;
            s[(e(i), e(i + 1))] += 0.125;
        }
    }
    s
}

/// The masks of a Loop dart of valence `n` over `x, e_0 .. e_(n-1)` (`None` below 3 or above
/// [`MAX_DART_VALENCE`]).
pub fn dart_masks(n: usize) -> Option<Arc<DartMasks>> {
    static CACHE: MaskCache = OnceLock::new();
    cached_masks(&CACHE, n, |n| ring_matrix(n, true))
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    /// The spectrum of the module documentation; left eigenvectors summing to 1 (limit) and 0
    /// (tangents); the antisymmetric mode's eigenvalue is the smooth vertex's, and without the
    /// dart the matrix is Loop's smooth one (subdominant `3/8 + cos(2 pi / n) / 4`, double).
    #[crate::unit::test]
    fn loop_dart_spectra_and_masks() {
        for (n, l) in [
            (3, [0.39827, 0.25]),
            (4, [0.45182, 0.375]),
            (6, [0.5, 0.5]),
            (8, [0.55178, 0.52679]),
        ] {
            let m = dart_masks(n).unwrap();
            assert!((m.lambda[0] - l[0]).abs() < 1e-5, "n {n}: {:?}", m.lambda);
            assert!((m.lambda[1] - l[1]).abs() < 1e-5, "n {n}: {:?}", m.lambda);
        }
        for n in 3..=12 {
            let smooth = 0.375 + 0.25 * (2.0 * std::f64::consts::PI / n as f64).cos();
            let m = dart_masks(n).unwrap();
            let what = format!("n {n}");
            crate::schemes::sdc::dart::assert_smooth_pair_kept(
                &ring_matrix(n, false),
                &m,
                smooth,
                &what,
            );
            crate::schemes::sdc::dart::assert_left_eigenvectors(&ring_matrix(n, true), &m, &what);
        }
    }
}
