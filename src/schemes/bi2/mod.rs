//! The bi-2 family of Karciauskas and Peters (*Point-augmented biquadratic C^1 subdivision
//! surfaces*): point-augmented PGS, polar PolBS, primal ternary TPS and adjustable TPS, and
//! their combination in one mesh.
//!
//! All four schemes generalise uniform biquadratic (bi-2) B-splines, whose control point `d`
//! of a regular quad net carries exactly one polynomial piece, the patch of the vertex (its
//! 3x3 net). They differ in where the net is not regular and in how they refine:
//!
//! | module | scheme | extraordinary element | refinement |
//! | --- | --- | --- | --- |
//! | [`pgs`] | PGS, `pgs` | n-gon facet of a DS-net, plus an added point `p` | binary, dual (Doo-Sabin topology) |
//! | [`polar`] | PolBS, `polar-bi2` | pole `p` of a polar net (fan of triangles) | binary, radial only |
//! | [`ternary`] | TPS, `tps`; adjustable TPS, `tps-adjustable` | vertex of valence `n` in a quad net (q-net) | ternary, primal |
//! | [`mixed`] | `bi2-mixed` | all of the above in one mesh | nested rings per element |
//!
//! This module holds what they share: the univariate quadratic B-spline rules on non-uniform
//! knots ([`blossom_weights`], [`end_child_weight`], [`middle_child_weights`]), which give both
//! the uniform masks (Doo-Sabin's 3/4, 1/4; ternary 2/3, 1/3 and 1/9, 7/9, 1/9) and the
//! non-uniform ones of adjustable TPS, and the B-spline to Bezier conversion of a bi-2 piece
//! with non-uniform knots ([`quadratic_bezier_rows`], [`bi2_patch_stencils`]); and the refusal
//! of valences and facet sizes below 3 that their parameters and canonical nets share.
//!
//! Conventions: a control point is the B-spline coefficient of one knot interval (its
//! *piece*); a piece of width `w` is the interval `[-w/2, w/2]` around its own point; its
//! neighbours' pieces have widths `wl` (left) and `wr` (right).

pub mod descriptor;
pub mod entry;
pub mod local;
pub mod local_scheme;
pub mod mixed;
pub mod pgs;
mod pgs_dscc;
pub mod polar;
pub mod surface;
pub mod ternary;

pub use mixed::Bi2Mixed;
pub use pgs::{Pgs, PgsOptions, PgsParams, PgsPreprocessed};
pub use polar::{PolarBi2, PolarParams};
pub use ternary::{AdjustableTps, AlphaRule, Tps, TpsParams};

use crate::stencil::Stencil;

/// `cos(2 pi k / n)`, exact where the value is rational.
pub fn cos_2pi(k: i64, n: i64) -> f64 {
    super::common::cos_2pi(k, n)
}

/// `Ok` for `n >= 3`, else [`crate::error::Error::InvalidArgument`] saying `needs` and the
/// `n` given (the family's valences, facet sizes and canonical nets start at 3).
pub(crate) fn at_least_three(n: usize, needs: &str) -> crate::error::Result<()> {
    if n < 3 {
        return Err(crate::error::Error::InvalidArgument(format!(
            "{needs} (got {n})"
        )));
    }
    Ok(())
}

/// Weights `(wl, w, wr)` of the three B-spline coefficients `(d_l, d, d_r)` in the blossom
/// `F(s, t)` of the quadratic piece `[-w/2, w/2]` of `d`, whose neighbours' pieces have widths
/// `wl` and `wr`. `F(s, t)` is the B-spline coefficient of the sub-interval `[s, t]` after knot
/// insertion, so every refinement rule of the bi-2 family is a blossom.
///
/// Widths must be positive; the weights always sum to 1.
pub fn blossom_weights(wl: f64, w: f64, wr: f64, s: f64, t: f64) -> [f64; 3] {
    // F(x, y) = A + B (x + y) / 2 + C x y. Rows: the polar form at the three coefficients'
    // knot pairs, d_l = F(-w/2 - wl, -w/2), d = F(-w/2, w/2), d_r = F(w/2, w/2 + wr).
    let h = w / 2.0;
    let rows = [
        [1.0, (-2.0 * h - wl) / 2.0, (h + wl) * h],
        [1.0, 0.0, -h * h],
        [1.0, (2.0 * h + wr) / 2.0, h * (h + wr)],
    ];
    // Solve M^T x = [1, (s + t) / 2, s t]: the weights x with sum_k x_k rows[k] = target.
    let target = [1.0, (s + t) / 2.0, s * t];
    let m = |r: usize, c: usize| rows[c][r];
    let det = |a: [[f64; 3]; 3]| {
        a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
    };
    let full = [
        [m(0, 0), m(0, 1), m(0, 2)],
        [m(1, 0), m(1, 1), m(1, 2)],
        [m(2, 0), m(2, 1), m(2, 2)],
    ];
    let d = det(full);
    let mut out = [0.0; 3];
    for (k, o) in out.iter_mut().enumerate() {
        let mut a = full;
        for (r, row) in a.iter_mut().enumerate() {
            row[k] = target[r];
        }
        *o = det(a) / d;
    }
    out
}

/// Weight of `d_w` in the child at the end of `d_v`'s piece next to `d_w`'s piece, after the
/// piece of `d_v` (width `wv`) is split in the ratio `e : 1 - 2e : e`: the coefficient of
/// `[w/2 - e w, w/2]`, which is `d_v + t (d_w - d_v)` with `t = (1 - e) wv / (wv + ww)`. It
/// reads only the two coefficients that share the knot (`ww` is the width of `d_w`'s piece).
/// Uniform binary refinement (`e = 1/2`) gives Doo-Sabin's `1/4`, ternary (`e = 1/3`) `1/3`.
pub fn end_child_weight(wv: f64, ww: f64, e: f64) -> f64 {
    (1.0 - e) * wv / (wv + ww)
}

/// Weights of `(d_l, d, d_r)` in the middle child `[-w/2 + e w, w/2 - e w]` of `d`'s piece
/// after the split `e : 1 - 2e : e`. Uniform ternary refinement gives `(1, 7, 1) / 9`.
pub fn middle_child_weights(wl: f64, w: f64, wr: f64, e: f64) -> [f64; 3] {
    let h = w / 2.0;
    blossom_weights(wl, w, wr, -h + e * w, h - e * w)
}

/// The Bezier form of the quadratic piece of `d` (width `w`) with neighbours of widths `wl`,
/// `wr`: row `k` gives the weights of `(d_l, d, d_r)` in Bezier coefficient `b_k`:
/// `b0 = (w d_l + wl d) / (wl + w)`, `b1 = d`, `b2 = (wr d + w d_r) / (w + wr)`. Uniform knots
/// give [`crate::bezier::convert::QUADRATIC_BSPLINE`].
pub fn quadratic_bezier_rows(wl: f64, w: f64, wr: f64) -> [[f64; 3]; 3] {
    [
        [w / (wl + w), wl / (wl + w), 0.0],
        [0.0, 1.0, 0.0],
        [0.0, wr / (w + wr), w / (w + wr)],
    ]
}

/// The nine Bezier coefficients (row-major, `b[i][j]` at `3 i + j`, `i` along `u`) of the bi-2
/// piece of the middle point of a 3x3 net `net[k][l]` (`k` along `u`) of stencils, with knot
/// widths `wu` (the three pieces along `u`) and `wv` (along `v`).
pub fn bi2_patch_stencils(net: &[[Stencil; 3]; 3], wu: [f64; 3], wv: [f64; 3]) -> Vec<Stencil> {
    let mu = quadratic_bezier_rows(wu[0], wu[1], wu[2]);
    let mv = quadratic_bezier_rows(wv[0], wv[1], wv[2]);
    let mut out = Vec::with_capacity(9);
    for mi in &mu {
        for mj in &mv {
            let mut s = Stencil::new();
            for (k, &a) in mi.iter().enumerate() {
                for (l, &b) in mj.iter().enumerate() {
                    if a * b != 0.0 {
                        s.add_scaled(&net[k][l], a * b);
                    }
                }
            }
            out.push(s.merged());
        }
    }
    out
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn uniform_rules() {
        // Binary (Chaikin / Doo-Sabin): end child 3/4, 1/4.
        assert!((end_child_weight(1.0, 1.0, 0.5) - 0.25).abs() < 1e-15);
        // Ternary: 2/3, 1/3 and (1, 7, 1) / 9.
        assert!((end_child_weight(1.0, 1.0, 1.0 / 3.0) - 1.0 / 3.0).abs() < 1e-15);
        let m = middle_child_weights(1.0, 1.0, 1.0, 1.0 / 3.0);
        for (a, b) in m.iter().zip([1.0 / 9.0, 7.0 / 9.0, 1.0 / 9.0]) {
            assert!((a - b).abs() < 1e-15, "{m:?}");
        }
        // The Bezier form of a uniform piece.
        let r = quadratic_bezier_rows(1.0, 1.0, 1.0);
        assert_eq!(r, [[0.5, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.5, 0.5]]);
    }

    #[crate::unit::test]
    fn blossom_reproduces_quadratics() {
        // Coefficients of f(x) = x^2 on the knots: d = F(a, b) = a b.
        let (wl, w, wr) = (0.3, 1.0, 0.7);
        let h = w / 2.0;
        let d = [(-h - wl) * -h, -h * h, h * (h + wr)];
        for (s, t) in [(0.1, 0.2), (-0.5, 0.5), (0.4, 0.5), (-0.2, 0.3)] {
            let wts = blossom_weights(wl, w, wr, s, t);
            let v: f64 = wts.iter().zip(&d).map(|(a, b)| a * b).sum();
            assert!((v - s * t).abs() < 1e-14, "({s}, {t}): {v}");
            assert!((wts.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        }
        // The end child reads only its two coefficients and matches the blossom.
        let e = 0.2;
        let b = blossom_weights(wl, w, wr, h - e * w, h);
        assert!(b[0].abs() < 1e-14);
        assert!((b[2] - end_child_weight(w, wr, e)).abs() < 1e-14);
    }
}
