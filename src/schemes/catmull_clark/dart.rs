//! Catmull-Clark's limit point and tangent plane at a dart: an interior vertex of valence `n`
//! with exactly one infinitely sharp edge (a crease that ends inside the surface).
//!
//! OpenSubdiv's rules at a dart: the vertex takes the smooth rule, the faces and the smooth
//! edges their smooth rules, and the sharp edge its midpoint `(x + e_0) / 2`. The 1-ring, `x`,
//! its edge neighbours `e_0 .. e_(n-1)` counter-clockwise from the sharp edge's end `e_0` and
//! the far corners `f_0 .. f_(n-1)` of its quads (`f_i` between `e_i` and `e_(i+1)`), is mapped
//! onto itself by one step: its `(2 n + 1)^2` subdivision matrix `S` is the smooth one with the
//! row of `e_0` replaced by the midpoint. So the smooth limit and tangent masks, which
//! OpenSubdiv also applies at a dart (its limit mask of a dart is the smooth one), are not the
//! dart's limit: the left eigenvectors of this `S` are. Its spectrum (computed here; tested):
//! `1`, then two real subdominant eigenvalues above the rest: the antisymmetric mode's (no
//! weight on `e_0`), which is the smooth vertex's subdominant eigenvalue, and the symmetric
//! mode's, which the midpoint rule changes: `0.4621` (symmetric) and `0.4101` at `n = 3`,
//! `1/2` double at `n = 4`, `0.5500` and `0.5264` at `n = 5`, `0.6111` and `0.5819` at
//! `n = 8`. The left
//! eigenvector of `1` (scaled to sum 1) is the limit mask; the two subdominant left
//! eigenvectors applied to the points span the limit tangent plane (the surface near the dart
//! is `c + lambda_a^k a + lambda_b^k b` to first order in the ring's chart, with both modes'
//! characteristic directions independent), which is the plane the dart's G^1 cap is centred in
//! ([`crate::bezier::g1::Fan::Dart`]).
//!
//! At valence 2 the spectrum is `1, 0.3878, -0.2811, 0.25, 0.1433`: the negative eigenvalue
//! outweighs the second tangent mode, so, as at a smooth vertex of valence 2, the limit has no
//! tangent plane; the cap is centred in the plane of the two positive modes
//! (`schemes::sdc::dart::masks_of_positive`).
//!
//! The masks are computed once per valence ([`crate::schemes::sdc::dart`]: null vectors of a small
//! dense matrix) and cached.

pub use crate::schemes::sdc::dart::{DartMasks, MAX_DART_VALENCE};
use crate::schemes::sdc::dart::{MaskCache, cached_masks, cached_masks_with, masks_of_positive};
use nalgebra::DMatrix;
use std::sync::{Arc, OnceLock};

/// The 1-ring subdivision matrix of a dart of valence `n` (module documentation); with
/// `dart = false` the smooth one (the tests' check of the rules against Catmull-Clark's known
/// subdominant eigenvalue). The smooth vertex rule over the old points: `(4 n - 7) / (4 n)` on
/// `x`, `3 / (2 n^2)` on each `e_i`, `1 / (4 n^2)` on each `f_i`.
fn ring_matrix(n: usize, dart: bool) -> DMatrix<f64> {
    let (x, e, f) = (0, |i: usize| 1 + i % n, |i: usize| 1 + n + i % n);
    let face = |i: usize| [x, e(i), f(i), e(i + 1)];
    let nf = n as f64;
    let mut s = DMatrix::zeros(2 * n + 1, 2 * n + 1);
    s[(x, x)] = (4.0 * nf - 7.0) / (4.0 * nf);
    for i in 0..n {
        s[(x, e(i))] += 1.5 / (nf * nf);
        s[(x, f(i))] += 0.25 / (nf * nf);
        if i == 0 && dart {
            s[(e(0), x)] = 0.5;
            s[(e(0), e(0))] = 0.5;
        } else {
            s[(e(i), x)] += 0.25;
            s[(e(i), e(i))] += 0.25;
            for g in [(i + n - 1) % n, i] {
                for c in face(g) {
                    s[(e(i), c)] += 0.0625;
                }
            }
        }
        for c in face(i) {
            s[(f(i), c)] += 0.25;
        }
    }
    s
}

/// The masks of a Catmull-Clark dart of valence `n` over `x, e_0 .. e_(n-1), f_0 .. f_(n-1)`
/// (`None` below 2 or above [`MAX_DART_VALENCE`]; at 2 from its positive modes, module documentation).
pub fn dart_masks(n: usize) -> Option<Arc<DartMasks>> {
    static CACHE: MaskCache = OnceLock::new();
    if n == 2 {
        // the negative eigenvalue -0.2811 outweighs the second tangent mode's 1/4 (module
        // documentation): the two positive modes span the cap's plane
        return cached_masks_with(&CACHE, n, (2, masks_of_positive), |n| ring_matrix(n, true));
    }
    cached_masks(&CACHE, n, |n| ring_matrix(n, true))
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    /// The spectrum of the module documentation, and left eigenvectors: the limit mask sums
    /// to 1, the tangent masks to 0, each a left eigenvector of the dart's matrix.
    #[crate::unit::test]
    fn dart_spectra_and_masks() {
        let want = [
            (3, [0.46206, 0.41010]),
            (4, [0.5, 0.5]),
            (5, [0.54999, 0.52642]),
            (8, [0.61112, 0.58191]),
        ];
        for (n, l) in want {
            let m = dart_masks(n).unwrap();
            assert!((m.lambda[0] - l[0]).abs() < 1e-4, "n {n}: {:?}", m.lambda);
            assert!((m.lambda[1] - l[1]).abs() < 1e-4, "n {n}: {:?}", m.lambda);
        }
        for n in 3..=12 {
            let m = dart_masks(n).unwrap();
            let what = format!("n {n}");
            crate::schemes::sdc::dart::assert_left_eigenvectors(&ring_matrix(n, true), &m, &what);
            // not the smooth limit mask: the sharp edge's end weighs differently
            let (e0, e1) = (m.limit[1], m.limit[2]);
            assert!((e0 - e1).abs() > 1e-3, "n {n}: {e0} {e1}");
        }
        // valence 2: the two positive subdominant modes, past a negative eigenvalue of larger
        // modulus (no tangent plane in the limit; module documentation)
        let m = dart_masks(2).unwrap();
        assert!((m.lambda[0] - 0.38785).abs() < 1e-4, "{:?}", m.lambda);
        assert!((m.lambda[1] - 0.25).abs() < 1e-12, "{:?}", m.lambda);
        crate::schemes::sdc::dart::assert_left_eigenvectors(&ring_matrix(2, true), &m, "n 2");
    }

    /// Without the dart the matrix is Catmull-Clark's smooth one: its subdominant eigenvalue is
    /// the closed form `(5 + c + cos(pi / n) sqrt(18 + 2 c)) / 16`, `c = cos(2 pi / n)`
    /// (double); the dart keeps the antisymmetric one (its mode has no weight on `e_0`).
    #[crate::unit::test]
    fn without_the_dart_the_rules_are_the_smooth_ones() {
        for n in 3..=12 {
            let pi = std::f64::consts::PI;
            let c = (2.0 * pi / n as f64).cos();
            let want = (5.0 + c + (pi / n as f64).cos() * (18.0 + 2.0 * c).sqrt()) / 16.0;
            let what = format!("n {n}");
            let m = dart_masks(n).unwrap();
            crate::schemes::sdc::dart::assert_smooth_pair_kept(
                &ring_matrix(n, false),
                &m,
                want,
                &what,
            );
        }
    }
}
