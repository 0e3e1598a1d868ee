//! The limit point and tangent plane at a dart (an interior vertex with exactly one infinitely
//! sharp edge, a crease ending inside the surface) from the dart's 1-ring subdivision matrix,
//! for the schemes whose 1-ring is mapped onto itself by one step (Catmull-Clark's
//! [`crate::schemes::catmull_clark::dart`], Loop's [`crate::schemes::loop_subdivision::dart`]).
//!
//! Under OpenSubdiv's rules a dart's vertex takes the smooth rule and its sharp edge the
//! midpoint rule, so its subdivision matrix is not the smooth one and neither are its limit
//! and tangent masks (OpenSubdiv applies the smooth limit mask at a dart; it is not the dart's
//! limit). The left eigenvector of eigenvalue 1 (scaled to sum 1) is the limit mask; the left
//! eigenvectors of the two subdominant eigenvalues (real, above the rest of the spectrum: the
//! antisymmetric mode about the sharp edge keeps the smooth vertex's value, the symmetric one
//! changes) applied to the points span the limit tangent plane. That plane is where the dart's
//! G^1 cap ([`crate::bezier::g1::Fan::Dart`]) is centred.

use nalgebra::DMatrix;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

/// The largest valence of a dart whose masks are computed (the G^1 caps stop there too).
pub const MAX_DART_VALENCE: usize = crate::bezier::g1::MAX_CAP_VALENCE;

/// The masks of a dart over its scheme's 1-ring (in the order of the scheme's ring matrix).
#[derive(Debug, Clone)]
pub struct DartMasks {
    /// The two subdominant eigenvalues, larger first.
    pub lambda: [f64; 2],
    /// The limit mask (sums to 1).
    pub limit: Vec<f64>,
    /// Two tangent masks spanning the limit tangent plane (each sums to 0, largest weight 1).
    pub tangents: [Vec<f64>; 2],
}

impl DartMasks {
    /// The limit point and the two plane vectors of the masks applied to `ring` (the 1-ring's
    /// points in the masks' order).
    pub fn apply(
        &self,
        ring: &[crate::geom::Point],
    ) -> (crate::geom::Point, [crate::geom::Point; 2]) {
        let apply = |w: &[f64]| {
            w.iter()
                .zip(ring)
                .fold([0.0; 3], |acc, (&wi, &p)| crate::geom::axpy(acc, wi, p))
        };
        (
            apply(&self.limit),
            [apply(&self.tangents[0]), apply(&self.tangents[1])],
        )
    }
}

/// A per-scheme cache of [`DartMasks`] by valence.
pub(crate) type MaskCache = OnceLock<Mutex<HashMap<usize, Arc<DartMasks>>>>;

/// The masks of valence `n` from `cache`, computed from `matrix(n)` on first use (`None` below
/// 3 or above [`MAX_DART_VALENCE`], or if the spectrum is not as the module documentation
/// describes).
pub(crate) fn cached_masks(
    cache: &'static MaskCache,
    n: usize,
    matrix: impl FnOnce(usize) -> DMatrix<f64>,
) -> Option<Arc<DartMasks>> {
    cached_masks_with(cache, n, (3, masks_of), matrix)
}

/// How a dart's masks are read off its 1-ring matrix ([`masks_of`], [`masks_of_positive`]).
pub(crate) type MasksOf = fn(&DMatrix<f64>) -> Option<DartMasks>;

/// [`cached_masks`] from valence `lowest` on, the masks computed by `masks` ([`masks_of`], or
/// [`masks_of_positive`] for a valence-2 dart).
pub(crate) fn cached_masks_with(
    cache: &'static MaskCache,
    n: usize,
    (lowest, masks): (usize, MasksOf),
    matrix: impl FnOnce(usize) -> DMatrix<f64>,
) -> Option<Arc<DartMasks>> {
    if !(lowest..=MAX_DART_VALENCE).contains(&n) {
        return None;
    }
    let cache = cache.get_or_init(|| Mutex::new(HashMap::new()));
    if let Some(w) = cache.lock().ok()?.get(&n) {
        return Some(w.clone());
    }
    let out = Arc::new(masks(&matrix(n))?);
    cache.lock().ok()?.insert(n, out.clone());
    Some(out)
}

/// An orthonormal basis of the left null space of `S - lambda I` of dimension `dim`.
fn left_null(s: &DMatrix<f64>, lambda: f64, dim: usize) -> Option<Vec<Vec<f64>>> {
    let n = s.nrows();
    let a = s.transpose() - DMatrix::identity(n, n) * lambda;
    let svd = a.svd(false, true);
    let vt = svd.v_t?;
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| svd.singular_values[i].total_cmp(&svd.singular_values[j]));
    let small = order
        .iter()
        .take(dim)
        .all(|&i| svd.singular_values[i] < 1e-9);
    small.then(|| {
        order
            .iter()
            .take(dim)
            .map(|&i| vt.row(i).iter().copied().collect())
            .collect()
    })
}

/// The masks of a dart's 1-ring matrix `s` (module documentation), or `None` when its spectrum
/// is not `1`, two real subdominant eigenvalues, then the rest strictly below.
pub(crate) fn masks_of(s: &DMatrix<f64>) -> Option<DartMasks> {
    let mut ev: Vec<f64> = s
        .complex_eigenvalues()
        .iter()
        .filter(|z| z.im.abs() < 1e-9 && z.re < 1.0 - 1e-9)
        .map(|z| z.re)
        .collect();
    ev.sort_by(|a, b| b.total_cmp(a));
    let (la, lb) = (*ev.first()?, *ev.get(1)?);
    // the rest of the spectrum (complex values included) lies strictly below both
    let rest = s
        .complex_eigenvalues()
        .iter()
        .map(|z| z.norm())
        .filter(|&r| r < 1.0 - 1e-9)
        .filter(|&r| (r - la).abs() > 1e-9 && (r - lb).abs() > 1e-9)
        .fold(0.0f64, f64::max);
    if rest >= lb - 1e-9 {
        return None;
    }
    masks_at(s, la, lb)
}

/// The masks of a dart's 1-ring matrix `s` from its two largest positive real eigenvalues
/// below 1, whatever the rest of the spectrum: at a valence-2 dart of Catmull-Clark the
/// spectrum is `1, 0.3878, -0.2811, 0.25, 0.1433`, a negative eigenvalue of larger modulus
/// than the second tangent mode's, so (as at a smooth vertex of valence 2) the limit has no
/// tangent plane and [`masks_of`] declines; the two positive modes still span the plane of the
/// rings' first-order shape, in which the cap is centred.
pub(crate) fn masks_of_positive(s: &DMatrix<f64>) -> Option<DartMasks> {
    let mut ev: Vec<f64> = s
        .complex_eigenvalues()
        .iter()
        .filter(|z| z.im.abs() < 1e-9 && z.re > 1e-9 && z.re < 1.0 - 1e-9)
        .map(|z| z.re)
        .collect();
    ev.sort_by(|a, b| b.total_cmp(a));
    masks_at(s, *ev.first()?, *ev.get(1)?)
}

/// The limit mask and the tangent masks of eigenvalues `la >= lb` of `s`.
pub(crate) fn masks_at(s: &DMatrix<f64>, la: f64, lb: f64) -> Option<DartMasks> {
    let mut limit = left_null(s, 1.0, 1)?.pop()?;
    let sum: f64 = limit.iter().sum();
    limit.iter_mut().for_each(|w| *w /= sum);
    let tangents: Vec<Vec<f64>> = if (la - lb).abs() < 1e-9 {
        left_null(s, la, 2)?
    } else {
        vec![left_null(s, la, 1)?.pop()?, left_null(s, lb, 1)?.pop()?]
    };
    let unit = |mut w: Vec<f64>| {
        let big = w.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        w.iter_mut().for_each(|x| *x /= big);
        w
    };
    let mut it = tangents.into_iter().map(unit);
    Some(DartMasks {
        lambda: [la, lb],
        limit,
        tangents: [it.next()?, it.next()?],
    })
}

/// The tests' check of masks computed from the ring matrix `s`: the limit mask a left
/// eigenvector of 1 summing to 1, each tangent mask a left eigenvector of its eigenvalue
/// summing to 0 (`what` names the case in messages).
#[cfg(feature = "unit-tests")]
pub(crate) fn assert_left_eigenvectors(s: &DMatrix<f64>, m: &DartMasks, what: &str) {
    let lim = nalgebra::DVector::from_vec(m.limit.clone());
    assert!((s.transpose() * &lim - &lim).amax() < 1e-12, "{what}");
    assert!((lim.sum() - 1.0).abs() < 1e-12, "{what}");
    for (k, t) in m.tangents.iter().enumerate() {
        let v = nalgebra::DVector::from_vec(t.clone());
        assert!(
            (s.transpose() * &v - &v * m.lambda[k]).amax() < 1e-9,
            "{what}"
        );
        assert!(v.sum().abs() < 1e-9, "{what}");
    }
}

/// The tests' check of a scheme's rules: the smooth ring matrix `smooth` has the subdominant
/// eigenvalue `want` (double, to 1e-7), and the dart keeps it (its antisymmetric mode has no
/// weight on the sharp edge's end).
#[cfg(feature = "unit-tests")]
pub(crate) fn assert_smooth_pair_kept(smooth: &DMatrix<f64>, m: &DartMasks, want: f64, what: &str) {
    let mut ev: Vec<f64> = smooth
        .complex_eigenvalues()
        .iter()
        .map(|z| z.re)
        .filter(|&r| r < 1.0 - 1e-9)
        .collect();
    ev.sort_by(|a, b| b.total_cmp(a));
    let close = |l: f64| (l - want).abs() < 1e-7;
    assert!(
        close(ev[0]) && close(ev[1]),
        "{what}: {:?} against {want}",
        &ev[..3]
    );
    assert!(
        m.lambda.iter().any(|&l| close(l)),
        "{what}: {:?} against {want}",
        m.lambda
    );
}
