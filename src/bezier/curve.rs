//! Bezier curves: Bernstein values, de Casteljau evaluation, blossoms, hodographs, splitting,
//! sub-segments and degree raising.
//!
//! The patch code ([`super::BezierPatch`]) applies these univariate operations row by row and
//! column by column, and the adjacency and tessellation code compares patch boundaries with them,
//! so every curve rule lives here once. The free functions work on coefficient slices of any
//! fixed width `[f64; D]` (positions, 2D parameters, scalars as `[f64; 1]`); [`BezierCurve`] wraps
//! a `Vec` of 3D points for callers who want an owned curve.
//!
//! Evaluation does not allocate for degrees below [`STACK_DEGREE`]; higher degrees fall back to
//! a heap buffer and stay correct.

use crate::geom::Point;

/// Degrees strictly below this are evaluated in fixed-size stack buffers (no heap allocation).
pub const STACK_DEGREE: usize = 16;

/// `(1 - t) a + t b` for points of any width.
#[inline]
fn lerp_d<const D: usize>(a: [f64; D], b: [f64; D], t: f64) -> [f64; D] {
    let mut r = a;
    for k in 0..D {
        r[k] = a[k] + t * (b[k] - a[k]);
    }
    r
}

/// Runs `f` on a zeroed scratch slice of `n` points, on the stack when `n <= STACK_DEGREE`.
#[inline]
fn with_scratch<const D: usize, R>(n: usize, f: impl FnOnce(&mut [[f64; D]]) -> R) -> R {
    if n <= STACK_DEGREE {
        let mut buf = [[0.0; D]; STACK_DEGREE];
        f(&mut buf[..n])
    } else {
        let mut buf = vec![[0.0; D]; n];
        f(&mut buf)
    }
}

/// Fills `out[0..=d]` with the Bernstein polynomials `B_i^d(t)` (triangular recursion, stable
/// for all `t`, also outside `[0, 1]`).
///
/// # Panics
/// Panics when `out` is shorter than `d + 1`.
pub fn bernstein(d: usize, t: f64, out: &mut [f64]) {
    out[0] = 1.0;
    for k in 0..d {
        elevate_stage(k, t, out);
    }
}

/// Fills `b0`, `b1`, `b2` (each at least `d + 1` long) with the Bernstein polynomials of degree
/// `d` at `t` and their first and second derivatives, so that a curve with coefficients `c_i`
/// has value `sum b0[i] c_i`, derivative `sum b1[i] c_i` and second derivative `sum b2[i] c_i`.
///
/// # Panics
/// Panics when a buffer is shorter than `d + 1`.
pub fn bernstein_derivs(d: usize, t: f64, b0: &mut [f64], b1: &mut [f64], b2: &mut [f64]) {
    bernstein_derivs_inline(d, t, b0, b1, b2);
}

/// [`bernstein_derivs`] inlined into its caller, so that a degree known at compile time
/// unrolls it (the evaluation fast path of [`crate::bezier::BezierPatch::derivatives`]).
#[inline(always)]
pub(crate) fn bernstein_derivs_inline(
    d: usize,
    t: f64,
    b0: &mut [f64],
    b1: &mut [f64],
    b2: &mut [f64],
) {
    let (b0, b1, b2) = (&mut b0[..=d], &mut b1[..=d], &mut b2[..=d]);
    b1.fill(0.0);
    b2.fill(0.0);
    let df = d as f64;
    // values of degree max(d - 2, 0), then scatter the second-derivative weights
    // d (d - 1) (B_{i-2} - 2 B_{i-1} + B_i): each B_k^{d-2} adds to i = k, k + 1, k + 2
    let m = d.saturating_sub(2);
    // `bernstein(m, t, b0)`, inlined
    b0[0] = 1.0;
    for k in 0..m {
        elevate_stage(k, t, b0);
    }
    if d >= 2 {
        let c = df * (df - 1.0);
        for k in 0..=m {
            let w = c * b0[k];
            b2[k] += w;
            b2[k + 1] -= 2.0 * w;
            b2[k + 2] += w;
        }
    }
    // raise to degree d - 1 and scatter the first-derivative weights d (B_{i-1} - B_i)
    if d >= 2 {
        elevate_stage(m, t, b0);
    }
    if d >= 1 {
        for k in 0..d {
            let w = df * b0[k];
            b1[k] -= w;
            b1[k + 1] += w;
        }
        elevate_stage(d - 1, t, b0);
    }
}

/// One step of the Bernstein recursion: `b[0..=k]` of degree `k` to `b[0..=k+1]` of degree
/// `k + 1`.
#[inline(always)]
fn elevate_stage(k: usize, t: f64, b: &mut [f64]) {
    let s = 1.0 - t;
    let mut saved = 0.0;
    for o in b[..=k].iter_mut() {
        let tmp = *o;
        *o = saved + s * tmp;
        saved = t * tmp;
    }
    b[k + 1] = saved;
}

/// Value of the curve with coefficients `cps` at `t` (de Casteljau; the origin for an empty
/// slice).
pub fn eval<const D: usize>(cps: &[[f64; D]], t: f64) -> [f64; D] {
    let n = cps.len();
    if n == 0 {
        return [0.0; D];
    }
    with_scratch(n, |w: &mut [[f64; D]]| {
        w.copy_from_slice(cps);
        for r in 1..n {
            for i in 0..n - r {
                w[i] = lerp_d(w[i], w[i + 1], t);
            }
        }
        w[0]
    })
}

/// Value, first and second derivative of the curve at `t`.
pub fn eval_derivs<const D: usize>(cps: &[[f64; D]], t: f64) -> [[f64; D]; 3] {
    let n = cps.len();
    let mut out = [[0.0; D]; 3];
    if n == 0 {
        return out;
    }
    let d = n - 1;
    let run = |b0: &mut [f64], b1: &mut [f64], b2: &mut [f64], out: &mut [[f64; D]; 3]| {
        bernstein_derivs(d, t, b0, b1, b2);
        for (i, c) in cps.iter().enumerate() {
            for k in 0..D {
                out[0][k] += b0[i] * c[k];
                out[1][k] += b1[i] * c[k];
                out[2][k] += b2[i] * c[k];
            }
        }
    };
    if n <= STACK_DEGREE {
        let (mut b0, mut b1, mut b2) = (
            [0.0; STACK_DEGREE],
            [0.0; STACK_DEGREE],
            [0.0; STACK_DEGREE],
        );
        run(&mut b0, &mut b1, &mut b2, &mut out);
    } else {
        let (mut b0, mut b1, mut b2) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        run(&mut b0, &mut b1, &mut b2, &mut out);
    }
    out
}

/// The blossom (polar form) of the curve at the arguments `ts` (`ts.len()` must equal the
/// degree): de Casteljau with a different parameter at each level. `blossom(c, [t; d])` is the
/// value at `t`; `blossom(c, [t0^(d-k), t1^k])` is coefficient `k` of the sub-segment
/// `[t0, t1]`.
///
/// # Panics
/// Panics when `ts.len() + 1 != cps.len()`.
pub fn blossom<const D: usize>(cps: &[[f64; D]], ts: &[f64]) -> [f64; D] {
    let n = cps.len();
    assert_eq!(ts.len() + 1, n, "blossom needs degree-many arguments");
    with_scratch(n, |w: &mut [[f64; D]]| {
        w.copy_from_slice(cps);
        for (r, &t) in ts.iter().enumerate() {
            for i in 0..n - 1 - r {
                w[i] = lerp_d(w[i], w[i + 1], t);
            }
        }
        w[0]
    })
}

/// Splits the curve at `t` into the coefficients of its pieces over `[0, t]` and `[t, 1]`.
pub fn split<const D: usize>(cps: &[[f64; D]], t: f64) -> (Vec<[f64; D]>, Vec<[f64; D]>) {
    let n = cps.len();
    let mut left = Vec::with_capacity(n);
    let mut right = vec![[0.0; D]; n];
    let mut w = cps.to_vec();
    for r in 0..n {
        left.push(w[0]);
        right[n - 1 - r] = w[n - 1 - r];
        for i in 0..n.saturating_sub(r + 1) {
            w[i] = lerp_d(w[i], w[i + 1], t);
        }
    }
    (left, right)
}

/// Coefficients of the curve restricted to `[t0, t1]` and reparametrised over `[0, 1]` (any
/// `t0`, `t1`, also `t0 > t1`, which reverses, or values outside `[0, 1]`, which extrapolate).
pub fn subsegment<const D: usize>(cps: &[[f64; D]], t0: f64, t1: f64) -> Vec<[f64; D]> {
    let n = cps.len();
    if n == 0 {
        return Vec::new();
    }
    let d = n - 1;
    let mut args = vec![t0; d];
    (0..n)
        .map(|k| {
            // arguments t0^(d-k) t1^k
            for (i, a) in args.iter_mut().enumerate() {
                *a = if i < k { t1 } else { t0 };
            }
            blossom(cps, &args)
        })
        .collect()
}

/// Coefficients of the derivative curve (hodograph) of degree `d - 1`; a single zero
/// coefficient for a constant curve.
pub fn hodograph<const D: usize>(cps: &[[f64; D]]) -> Vec<[f64; D]> {
    if cps.len() <= 1 {
        return vec![[0.0; D]];
    }
    let d = (cps.len() - 1) as f64;
    cps.windows(2)
        .map(|w| {
            let mut r = [0.0; D];
            for k in 0..D {
                r[k] = d * (w[1][k] - w[0][k]);
            }
            r
        })
        .collect()
}

/// Degree raising by one: the same curve with `d + 2` coefficients.
pub fn raise<const D: usize>(cps: &[[f64; D]]) -> Vec<[f64; D]> {
    let n = cps.len();
    if n == 0 {
        return Vec::new();
    }
    let d1 = n as f64; // d + 1
    (0..=n)
        .map(|k| {
            if k == 0 {
                cps[0]
            } else if k == n {
                cps[n - 1]
            } else {
                let a = k as f64 / d1;
                lerp_d(cps[k], cps[k - 1], a)
            }
        })
        .collect()
}

/// Degree raising to degree `d` (the coefficients unchanged when already of degree `d`);
/// `None` when the curve's degree exceeds `d` or there are no coefficients.
pub fn raise_to<const D: usize>(cps: &[[f64; D]], d: usize) -> Option<Vec<[f64; D]>> {
    if cps.is_empty() || cps.len() > d + 1 {
        return None;
    }
    let mut c = cps.to_vec();
    while c.len() < d + 1 {
        c = raise(&c);
    }
    Some(c)
}

/// Largest distance between corresponding coefficients after raising both curves to the larger
/// degree. Because of the convex-hull property this bounds the distance between the curves
/// at equal parameters; it is zero exactly when the two polynomials are equal.
pub fn coefficient_distance(a: &[Point], b: &[Point]) -> f64 {
    let d = a.len().max(b.len()).saturating_sub(1);
    let (Some(a), Some(b)) = (raise_to(a, d), raise_to(b, d)) else {
        return f64::INFINITY;
    };
    a.iter()
        .zip(&b)
        .map(|(p, q)| crate::geom::dist(*p, *q))
        .fold(0.0, f64::max)
}

/// The parameter in `[0, 1]` of the point of the curve closest to `q`, and the distance.
/// Coarse sampling followed by Newton steps on `(c(t) - q) . c'(t) = 0`, clamped to `[0, 1]`.
pub fn closest_param(cps: &[Point], q: Point) -> (f64, f64) {
    use crate::geom::{dist, dot, sub};
    if cps.is_empty() {
        return (0.0, f64::INFINITY);
    }
    let samples = 4 * cps.len().max(2);
    let mut best = (0.0, f64::INFINITY);
    for k in 0..=samples {
        let t = k as f64 / samples as f64;
        let dd = dist(eval(cps, t), q);
        if dd < best.1 {
            best = (t, dd);
        }
    }
    let mut t = best.0;
    for _ in 0..12 {
        let [p, d1, d2] = eval_derivs(cps, t);
        let r = sub(p, q);
        let f = dot(r, d1);
        let fp = dot(d1, d1) + dot(r, d2);
        if fp <= 0.0 || !fp.is_finite() {
            break;
        }
        let nt = (t - f / fp).clamp(0.0, 1.0);
        let done = (nt - t).abs() < 1e-15;
        t = nt;
        if done {
            break;
        }
    }
    let dd = dist(eval(cps, t), q);
    if dd <= best.1 { (t, dd) } else { best }
}

/// A Bezier curve in 3-space of degree `cps.len() - 1`.
#[derive(Debug, Clone, PartialEq)]
pub struct BezierCurve {
    /// Coefficients `b_0, ..., b_d` in increasing parameter order.
    pub cps: Vec<Point>,
}

impl BezierCurve {
    /// A curve from its coefficients.
    ///
    /// # Panics
    /// Panics when `cps` is empty (a curve needs at least one coefficient).
    pub fn new(cps: Vec<Point>) -> Self {
        assert!(
            !cps.is_empty(),
            "a Bezier curve needs at least one coefficient"
        );
        BezierCurve { cps }
    }

    /// The degree.
    pub fn degree(&self) -> usize {
        self.cps.len().saturating_sub(1)
    }

    /// Value at `t`.
    pub fn eval(&self, t: f64) -> Point {
        eval(&self.cps, t)
    }

    /// Value, first and second derivative at `t`.
    pub fn eval_derivs(&self, t: f64) -> [Point; 3] {
        eval_derivs(&self.cps, t)
    }

    /// The derivative curve (hodograph), of degree one less (degree 0 and zero for a constant).
    pub fn derivative(&self) -> BezierCurve {
        BezierCurve {
            cps: hodograph(&self.cps),
        }
    }

    /// The pieces over `[0, t]` and `[t, 1]`.
    pub fn split(&self, t: f64) -> (BezierCurve, BezierCurve) {
        let (a, b) = split(&self.cps, t);
        (BezierCurve { cps: a }, BezierCurve { cps: b })
    }

    /// The piece over `[t0, t1]` reparametrised over `[0, 1]` (see [`subsegment`]).
    pub fn subsegment(&self, t0: f64, t1: f64) -> BezierCurve {
        BezierCurve {
            cps: subsegment(&self.cps, t0, t1),
        }
    }

    /// The same curve with degree one higher.
    pub fn raised(&self) -> BezierCurve {
        BezierCurve {
            cps: raise(&self.cps),
        }
    }

    /// The same curve raised to degree `d`; `None` when its degree exceeds `d`.
    pub fn raised_to(&self, d: usize) -> Option<BezierCurve> {
        raise_to(&self.cps, d).map(|cps| BezierCurve { cps })
    }

    /// The curve traversed backwards (`t -> 1 - t`).
    pub fn reversed(&self) -> BezierCurve {
        let mut cps = self.cps.clone();
        cps.reverse();
        BezierCurve { cps }
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;
    use crate::geom::dist;

    fn cubic() -> Vec<Point> {
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 2.0, 0.5],
            [3.0, 2.5, -1.0],
            [4.0, 0.0, 2.0],
        ]
    }

    /// Power-basis reference: x(t) of the cubic above via binomial expansion.
    fn reference(t: f64) -> Point {
        let c = cubic();
        let s = 1.0 - t;
        let w = [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t];
        let mut p = [0.0; 3];
        for i in 0..4 {
            for k in 0..3 {
                p[k] += w[i] * c[i][k];
            }
        }
        p
    }

    #[crate::unit::test]
    fn eval_matches_bernstein_sum_and_derivatives_match_differences() {
        let c = cubic();
        for k in 0..=20 {
            let t = k as f64 / 20.0 * 1.4 - 0.2;
            assert!(dist(eval(&c, t), reference(t)) < 1e-13);
            let [p, d1, d2] = eval_derivs(&c, t);
            assert!(dist(p, reference(t)) < 1e-13);
            let h = 1e-5;
            let fd1 = crate::geom::scale(
                crate::geom::sub(reference(t + h), reference(t - h)),
                0.5 / h,
            );
            let fd2 = crate::geom::scale(
                crate::geom::add(
                    crate::geom::sub(reference(t + h), crate::geom::scale(reference(t), 2.0)),
                    reference(t - h),
                ),
                1.0 / (h * h),
            );
            assert!(dist(d1, fd1) < 1e-8, "{d1:?} {fd1:?}");
            assert!(dist(d2, fd2) < 1e-4, "{d2:?} {fd2:?}");
            // hodograph evaluation equals the derivative
            assert!(dist(eval(&hodograph(&c), t), d1) < 1e-12);
        }
        // degree 0 and 1
        let [p, d1, d2] = eval_derivs(&[[2.0, 3.0, 4.0]], 0.3);
        assert_eq!((p, d1, d2), ([2.0, 3.0, 4.0], [0.0; 3], [0.0; 3]));
        let [p, d1, d2] = eval_derivs(&[[0.0; 3], [2.0, 0.0, 0.0]], 0.25);
        assert_eq!((p, d1, d2), ([0.5, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0; 3]));
    }

    #[crate::unit::test]
    fn bernstein_is_a_partition_of_unity() {
        let mut b = [0.0; 9];
        bernstein(8, 0.37, &mut b);
        assert!((b.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        // B_3^8(0.37) = 56 * 0.63^5 * 0.37^3
        assert!((b[3] - 56.0 * 0.63f64.powi(5) * 0.37f64.powi(3)).abs() < 1e-15);
    }

    #[crate::unit::test]
    fn split_subsegment_raise() {
        let c = cubic();
        let (l, r) = split(&c, 0.3);
        for k in 0..=10 {
            let s = k as f64 / 10.0;
            assert!(dist(eval(&l, s), reference(0.3 * s)) < 1e-13);
            assert!(dist(eval(&r, s), reference(0.3 + 0.7 * s)) < 1e-13);
            let sub = subsegment(&c, 0.8, 0.2);
            assert!(dist(eval(&sub, s), reference(0.8 - 0.6 * s)) < 1e-13);
            let up = raise_to(&c, 6).map(|u| eval(&u, s));
            assert!(dist(up.unwrap_or([f64::NAN; 3]), reference(s)) < 1e-13);
        }
        assert_eq!(raise_to(&c, 2), None);
        assert_eq!(raise_to::<3>(&[], 2), None);
        assert_eq!(coefficient_distance(&[], &c), f64::INFINITY);
        assert!(subsegment::<3>(&[], 0.0, 1.0).is_empty() && split::<3>(&[], 0.5).0.is_empty());
        assert_eq!(eval::<3>(&[], 0.5), [0.0; 3]);
        assert_eq!(closest_param(&[], [0.0; 3]).1, f64::INFINITY);
        assert_eq!(coefficient_distance(&c, &raise(&raise(&c))), 0.0);
        assert!(coefficient_distance(&subsegment(&c, 0.0, 0.3), &l) < 1e-15);
        let (t, d) = closest_param(&c, reference(0.61));
        assert!((t - 0.61).abs() < 1e-10 && d < 1e-12, "{t} {d}");
    }

    #[crate::unit::test]
    fn curve_wrapper() {
        let c = BezierCurve::new(cubic());
        assert_eq!(c.degree(), 3);
        assert_eq!(c.reversed().eval(0.25), c.eval(0.75));
        assert_eq!(c.derivative().degree(), 2);
        assert_eq!(c.raised().degree(), 4);
        assert!(c.raised_to(2).is_none());
        let (a, b) = c.split(0.5);
        assert!(dist(a.eval(1.0), b.eval(0.0)) < 1e-15);
        assert!(dist(c.subsegment(0.5, 1.0).eval(0.5), c.eval(0.75)) < 1e-15);
    }
}
