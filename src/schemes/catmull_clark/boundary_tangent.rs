//! Catmull-Clark's limit tangent across the boundary at an extraordinary boundary vertex
//! (`k >= 3` quads, a plain boundary: the crease rule `(e_0 + 6 v + e_k) / 8` at the vertex,
//! `(v + e_i) / 2` on the boundary edges, the smooth rules inside).
//!
//! The 1-ring of such a vertex, `v`, its edge neighbours `e_0 .. e_k` (counter-clockwise from
//! one boundary neighbour to the other) and the far corners `d_0 .. d_(k-1)` of its quads, is
//! mapped onto itself by one step; its `(2 k + 2)^2` subdivision matrix `S` has eigenvalue 1
//! (the limit point), `1/2` (the boundary curve's tangent, left eigenvector `e_0 - e_k`) and
//! `lambda'`, the largest eigenvalue below 1, whose eigenvector is symmetric in the fan
//! (`e_i <-> e_(k-i)`): measured `0.5797, 0.6111, 0.6263, 0.6348, 0.6400, 0.6433` for
//! `k = 3 .. 8`: the subdominant eigenvalue of an interior vertex of valence `2 k`
//! (`(5 + cos(pi / k) + cos(pi / (2 k)) sqrt(18 + 2 cos(pi / k))) / 16`, tested to 1e-12). Its left eigenvector, applied
//! to the points, is the limit derivative across the boundary (up to scale). Together with
//! `e_0 - e_k` it spans the plane the G^1 cap of an open fan is centred in
//! ([`crate::bezier::g1::Layout::OpenQuad`]).
//!
//! For `k >= 5` an antisymmetric interior mode lies above `1/2` (`0.55` at `k = 5`, `0.61` at
//! `k = 8`): its tangent, not the boundary curve's, is the second direction of the limit
//! surface's interior at the vertex, and the two differ on a general net. This is the known
//! defect of the plain boundary rules at high boundary valence (Biermann, Levin and Zorin 2000
//! modify the rules to remove it); the plane taken here contains the boundary curve's tangent,
//! so the surface's boundary stays C^1 through the cap.
//!
//! The weights are computed once per `k` (an eigenvalue and a null vector of a small dense
//! matrix) and cached.

use nalgebra::DMatrix;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

/// The largest number of quads at a boundary vertex for which the tangent is computed (the
/// dense eigen-solve grows like `k^3`; the G^1 caps stop at this valence too).
pub const MAX_BOUNDARY_FACES: usize = crate::bezier::g1::MAX_CAP_VALENCE;

/// The local subdivision matrix of the 1-ring of a boundary vertex with `k` quads, in the
/// order `v, e_0 .. e_k, d_0 .. d_(k-1)`.
fn ring_matrix(k: usize) -> DMatrix<f64> {
    let n = 2 * k + 2;
    let (v, e, d) = (0, |i: usize| 1 + i, |i: usize| k + 2 + i);
    let face = |i: usize| [v, e(i), d(i), e(i + 1)];
    let mut s = DMatrix::zeros(n, n);
    s[(v, v)] = 0.75;
    s[(v, e(0))] += 0.125;
    s[(v, e(k))] += 0.125;
    for i in 0..=k {
        if i == 0 || i == k {
            s[(e(i), v)] += 0.5;
            s[(e(i), e(i))] += 0.5;
        } else {
            s[(e(i), v)] += 0.25;
            s[(e(i), e(i))] += 0.25;
            for f in [i - 1, i] {
                for c in face(f) {
                    s[(e(i), c)] += 0.0625;
                }
            }
        }
    }
    for i in 0..k {
        for c in face(i) {
            s[(d(i), c)] += 0.25;
        }
    }
    s
}

/// The subdominant eigenvalue `lambda'` and the weights of the cross-boundary tangent over
/// `v, e_0 .. e_k, d_0 .. d_(k-1)`, scaled to largest weight 1 and signed to point into the
/// fan (`None` for `k < 3` or above [`MAX_BOUNDARY_FACES`]).
pub fn across_weights(k: usize) -> Option<Arc<(f64, Vec<f64>)>> {
    if !(3..=MAX_BOUNDARY_FACES).contains(&k) {
        return None;
    }
    type Cache = Mutex<HashMap<usize, Arc<(f64, Vec<f64>)>>>;
    static CACHE: OnceLock<Cache> = OnceLock::new();
    let cache = CACHE.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(w) = cache.lock().ok()?.get(&k) {
        return Some(w.clone());
    }
    let s = ring_matrix(k);
    let lambda = s
        .complex_eigenvalues()
        .iter()
        .filter(|z| z.im.abs() < 1e-9 && z.re < 1.0 - 1e-9)
        .map(|z| z.re)
        .fold(f64::NEG_INFINITY, f64::max);
    let n = s.nrows();
    let a = s.transpose() - DMatrix::identity(n, n) * lambda;
    let svd = a.svd(false, true);
    let vt = svd.v_t?;
    let (l, _) = svd
        .singular_values
        .iter()
        .enumerate()
        .min_by(|x, y| x.1.total_cmp(y.1))?;
    let mut w: Vec<f64> = vt.row(l).iter().copied().collect();
    // inward: positive on the far side of a flat half-fan (e_i at angle pi i / k)
    let y = |i: usize| (std::f64::consts::PI * i as f64 / k as f64).sin();
    let inward: f64 = (0..=k).map(|i| w[1 + i] * y(i)).sum::<f64>()
        + (0..k)
            .map(|i| w[k + 2 + i] * (std::f64::consts::PI * (i as f64 + 0.5) / k as f64).sin())
            .sum::<f64>();
    let big = w.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let sign = if inward < 0.0 { -1.0 } else { 1.0 };
    w.iter_mut().for_each(|x| *x *= sign / big);
    let out = Arc::new((lambda, w));
    cache.lock().ok()?.insert(k, out.clone());
    Some(out)
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn subdominant_eigenvalues_and_symmetric_weights() {
        let want = [0.57968, 0.61112, 0.62634, 0.6348, 0.63996, 0.64333];
        for (k, want) in (3..=8).zip(want) {
            let w = across_weights(k).unwrap();
            assert!((w.0 - want).abs() < 1e-5, "k {k}: {}", w.0);
            let (c, h) = (
                (std::f64::consts::PI / k as f64).cos(),
                (std::f64::consts::PI / (2 * k) as f64).cos(),
            );
            let closed = (5.0 + c + h * (18.0 + 2.0 * c).sqrt()) / 16.0;
            assert!(
                (w.0 - closed).abs() < 1e-12,
                "k {k}: {} against {closed}",
                w.0
            );
            // a left eigenvector, symmetric in the fan, summing to zero (a tangent)
            let s = ring_matrix(k);
            let x = nalgebra::DVector::from_vec(w.1.clone());
            assert!((s.transpose() * &x - &x * w.0).amax() < 1e-12, "k {k}");
            for i in 0..=k {
                assert!((w.1[1 + i] - w.1[1 + k - i]).abs() < 1e-12, "k {k} e_{i}");
            }
            assert!(w.1.iter().sum::<f64>().abs() < 1e-12, "k {k}");
        }
        assert!(across_weights(2).is_none());
    }
}
