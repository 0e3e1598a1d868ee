//! Triangular patches stored as collapsed tensor-product patches (Loop's box-spline triangles
//! and fill, see [`crate::schemes::loop_subdivision::surface`]): the triangle `T(s, t)` is
//! recovered from `X(u, v) = T(u (1 - v), v)` and differentiated in its own barycentric
//! parameters, so derivatives stay exact at the collapsed corner `t = 1` as well.
//!
//! Column `j` (`v`-index) of `X`'s coefficients is the degree `n - j` curve of the triangle's
//! coefficients `b_{n-j-r, r, j}`, `r = 0 ..= n - j`, degree-raised to `n`; undoing the raising
//! (exact for a raised curve) gives the triangle's coefficients back.

use crate::bezier::{BezierPatch, Derivatives};
use crate::error::{Error, Result};
use crate::geom::{Point, axpy, scale, sub};

/// Undoes one degree raising: the degree `d - 1` curve whose raising is `c` (degree `d`).
fn unraise(c: &[Point]) -> Vec<Point> {
    let d = c.len() - 1;
    let mut out: Vec<Point> = Vec::with_capacity(d);
    for r in 0..d {
        // c_r = (r / d) b_{r-1} + (1 - r / d) b_r
        let prev = if r == 0 {
            [0.0; 3]
        } else {
            scale(out[r - 1], r as f64 / d as f64)
        };
        out.push(scale(sub(c[r], prev), d as f64 / (d - r) as f64));
    }
    out
}

/// `x^e` and its first two derivatives, zero for negative exponents.
fn powers(x: f64, e: usize) -> [f64; 3] {
    let p = |k: i64| if k < 0 { 0.0 } else { x.powi(k as i32) };
    let e = e as i64;
    [p(e), e as f64 * p(e - 1), (e * (e - 1)) as f64 * p(e - 2)]
}

fn factorial(n: usize) -> f64 {
    (1..=n).map(|k| k as f64).product()
}

/// The stored patch's `(u, v)` at barycentric `(s, t)` of its triangle (`X(u, v) = T(u (1 - v),
/// v)`; the collapsed corner `t = 1` as `(0, 1)`).
pub fn stored_uv(st: [f64; 2]) -> [f64; 2] {
    if st[1] < 1.0 {
        [st[0] / (1.0 - st[1]), st[1]]
    } else {
        [0.0, 1.0]
    }
}

/// Position and derivatives of the triangle stored in `patch` at barycentric `(s, t)`
/// (`s` toward corner 1, `t` toward corner 2).
///
/// # Errors
/// [`Error::InvalidArgument`] if the patch is not of equal degrees (not a stored triangle).
pub fn derivatives(patch: &BezierPatch, st: [f64; 2]) -> Result<Derivatives> {
    let n = patch.deg_u;
    if patch.deg_v != n {
        return Err(Error::InvalidArgument(format!(
            "a triangle patch has equal degrees, this one ({}, {})",
            patch.deg_u, patch.deg_v
        )));
    }
    let [s, t] = st;
    let l = [1.0 - s - t, s, t];
    let mut acc = [[0.0; 3]; 6]; // p, d0, d1, d2 in barycentric partials ... see below
    // partials with respect to the barycentrics: f, f_0, f_1, f_2, f_00, f_01, f_02, f_11,
    // f_12, f_22
    let mut part = [[0.0; 3]; 10];
    for j in 0..=n {
        let mut col: Vec<Point> = (0..=n).map(|i| patch.cp(i, j)).collect();
        for _ in 0..j {
            col = unraise(&col);
        }
        for (r, b) in col.iter().enumerate() {
            let i = n - j - r;
            let w = factorial(n) / (factorial(i) * factorial(r) * factorial(j));
            let (a, bb, c) = (powers(l[0], i), powers(l[1], r), powers(l[2], j));
            let terms = [
                a[0] * bb[0] * c[0],
                a[1] * bb[0] * c[0],
                a[0] * bb[1] * c[0],
                a[0] * bb[0] * c[1],
                a[2] * bb[0] * c[0],
                a[1] * bb[1] * c[0],
                a[1] * bb[0] * c[1],
                a[0] * bb[2] * c[0],
                a[0] * bb[1] * c[1],
                a[0] * bb[0] * c[2],
            ];
            for (pk, tk) in part.iter_mut().zip(terms) {
                *pk = axpy(*pk, w * tk, *b);
            }
        }
    }
    let [f, f0, f1, f2, f00, f01, f02, f11, f12, f22] = part;
    // d/ds = d/dl1 - d/dl0, d/dt = d/dl2 - d/dl0
    let comb = |terms: &[(f64, Point)]| terms.iter().fold([0.0; 3], |r, &(w, p)| axpy(r, w, p));
    acc[0] = f;
    acc[1] = comb(&[(1.0, f1), (-1.0, f0)]);
    acc[2] = comb(&[(1.0, f2), (-1.0, f0)]);
    acc[3] = comb(&[(1.0, f11), (-2.0, f01), (1.0, f00)]);
    acc[4] = comb(&[(1.0, f12), (-1.0, f01), (-1.0, f02), (1.0, f00)]);
    acc[5] = comb(&[(1.0, f22), (-2.0, f02), (1.0, f00)]);
    Ok(Derivatives {
        p: acc[0],
        du: acc[1],
        dv: acc[2],
        duu: acc[3],
        duv: acc[4],
        dvv: acc[5],
    })
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn stored_triangle_matches_its_tensor_patch() {
        // a random quartic triangle, stored as the loop surface stores it
        let mut tri = [[0.0; 3]; 15];
        let mut x = 0.3_f64;
        for p in tri.iter_mut() {
            for c in p.iter_mut() {
                x = (x * 7.31 + 0.17).fract();
                *c = x;
            }
        }
        let patch = crate::schemes::loop_subdivision::surface::triangle_to_tensor(&tri);
        for &(s, t) in &[(0.2, 0.3), (0.0, 0.0), (0.5, 0.5), (0.1, 0.7)] {
            let d = derivatives(&patch, [s, t]).expect("equal degrees");
            let u = s / (1.0 - t);
            let x = patch.eval(u, t);
            assert!(crate::geom::dist(d.p, x) < 1e-13, "{:?} vs {:?}", d.p, x);
            // T_s = X_u / (1 - t), and a finite difference for T_t and T_tt
            let dx = patch.derivatives(u, t);
            let ts = scale(dx.du, 1.0 / (1.0 - t));
            assert!(crate::geom::dist(d.du, ts) < 1e-11);
            let h = 1e-5;
            let fd = |s: f64, t: f64| derivatives(&patch, [s, t]).expect("ok");
            let tt = scale(sub(fd(s, t + h).dv, fd(s, t - h).dv), 0.5 / h);
            assert!(crate::geom::dist(d.dvv, tt) < 1e-6);
            let st = scale(sub(fd(s + h, t).dv, fd(s - h, t).dv), 0.5 / h);
            assert!(crate::geom::dist(d.duv, st) < 1e-6);
        }
    }
}
