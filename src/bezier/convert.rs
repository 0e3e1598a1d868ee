//! B-spline to Bezier conversions, written once as univariate matrices and tensored.
//!
//! A univariate conversion is a matrix `M` (rows: Bezier coefficients of one segment, columns:
//! the B-spline control points that influence it). A tensor-product patch from a net `d[k][l]`
//! (`k` along `u`) has coefficients `b[i][j] = sum_kl Mu[i][k] Mv[j][l] d[k][l]`. The same
//! matrices give both point conversions ([`tensor_apply`], [`curve_apply`]) and stencils over
//! node indices ([`tensor_stencils`], [`curve_stencils`]), so a scheme that expresses its patch
//! coefficients as stencils of its local net uses exactly the weights that convert points: one
//! source of truth per rule. The weights are stored once, as the constant tables below.
//!
//! Conversions:
//! - uniform cubic B-spline, segment from `d0..d3` ([`CUBIC_BSPLINE`]);
//! - uniform quadratic B-spline, segment from `d0..d2` ([`QUADRATIC_BSPLINE`]);
//! - C^2 quartic spline with double knots, the d-net of Evolving Guide subdivision (EG paper,
//!   formula (5)), segment from `d0..d4` where `d2` is the segment's middle coefficient
//!   ([`QUARTIC_C2`]). Tensored it gives formula (6) of the paper; see
//!   [`biquartic_c2_to_bezier`] for the index convention.
//!
//! Besides: a triangular Bezier patch of degree `n` as the equivalent degenerate tensor-product
//! patch `X(u, v) = T(u (1 - v), v)` ([`triangle_to_tensor`]).

use super::BezierPatch;
use crate::geom::Point;
use crate::stencil::Stencil;
use std::sync::LazyLock;

/// A dense conversion matrix (rows: Bezier coefficients, columns: B-spline control points).
pub type Matrix = nalgebra::DMatrix<f64>;

/// Uniform cubic B-spline to Bezier: row `k` gives `b_k` over `d_0..d_3`:
/// `b0 = (d0 + 4 d1 + d2)/6`, `b1 = (2 d1 + d2)/3`, `b2 = (d1 + 2 d2)/3`,
/// `b3 = (d1 + 4 d2 + d3)/6`.
pub const CUBIC_BSPLINE: [[f64; 4]; 4] = [
    [1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0, 0.0],
    [0.0, 2.0 / 3.0, 1.0 / 3.0, 0.0],
    [0.0, 1.0 / 3.0, 2.0 / 3.0, 0.0],
    [0.0, 1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0],
];

/// Uniform quadratic B-spline to Bezier: `b0 = (d0 + d1)/2`, `b1 = d1`, `b2 = (d1 + d2)/2`.
pub const QUADRATIC_BSPLINE: [[f64; 3]; 3] = [[0.5, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.5, 0.5]];

/// C^2 quartic spline with double knots (EG paper, formula (5), with `d_{2s-2+k}` written
/// `d_k`): `b0 = (d0 + 2 d1 + d2)/4`, `b1 = (d1 + d2)/2`, `b2 = d2`, `b3 = (d2 + d3)/2`,
/// `b4 = (d2 + 2 d3 + d4)/4`. `d1`, `d3` are the nodes the paper associates with double knots,
/// `d0`, `d2`, `d4` those with single knots.
pub const QUARTIC_C2: [[f64; 5]; 5] = [
    [0.25, 0.5, 0.25, 0.0, 0.0],
    [0.0, 0.5, 0.5, 0.0, 0.0],
    [0.0, 0.0, 1.0, 0.0, 0.0],
    [0.0, 0.0, 0.5, 0.5, 0.0],
    [0.0, 0.0, 0.25, 0.5, 0.25],
];

/// A [`Matrix`] from a constant table of rows.
pub fn matrix<const R: usize, const C: usize>(rows: &[[f64; C]; R]) -> Matrix {
    Matrix::from_fn(R, C, |r, c| rows[r][c])
}

static CUBIC_M: LazyLock<Matrix> = LazyLock::new(|| matrix(&CUBIC_BSPLINE));
static QUADRATIC_M: LazyLock<Matrix> = LazyLock::new(|| matrix(&QUADRATIC_BSPLINE));
static QUARTIC_M: LazyLock<Matrix> = LazyLock::new(|| matrix(&QUARTIC_C2));

/// [`CUBIC_BSPLINE`] as a matrix.
pub fn cubic_bspline_matrix() -> &'static Matrix {
    &CUBIC_M
}

/// [`QUADRATIC_BSPLINE`] as a matrix.
pub fn quadratic_bspline_matrix() -> &'static Matrix {
    &QUADRATIC_M
}

/// [`QUARTIC_C2`] (EG formula (5)) as a matrix.
pub fn quartic_c2_matrix() -> &'static Matrix {
    &QUARTIC_M
}

/// Applies a univariate conversion to points: `b_k = sum_l m[k][l] d_l`.
///
/// # Panics
/// Panics when `d.len() != m.ncols()`.
pub fn curve_apply(m: &Matrix, d: &[Point]) -> Vec<Point> {
    assert_eq!(
        d.len(),
        m.ncols(),
        "control point count does not match matrix"
    );
    (0..m.nrows())
        .map(|k| {
            let mut p = [0.0; 3];
            for (l, q) in d.iter().enumerate() {
                let w = m[(k, l)];
                if w != 0.0 {
                    for c in 0..3 {
                        p[c] += w * q[c];
                    }
                }
            }
            p
        })
        .collect()
}

/// A univariate conversion as stencils: stencil `k` is `sum_l m[k][l] * node[l]`, over the node
/// indices `nodes` (zero weights are skipped, repeated nodes merged).
///
/// # Panics
/// Panics when `nodes.len() != m.ncols()`.
pub fn curve_stencils(m: &Matrix, nodes: &[usize]) -> Vec<Stencil> {
    assert_eq!(nodes.len(), m.ncols(), "node count does not match matrix");
    (0..m.nrows())
        .map(|k| {
            Stencil::from_pairs(
                nodes
                    .iter()
                    .enumerate()
                    .map(|(l, &n)| (n, m[(k, l)]))
                    .filter(|e| e.1 != 0.0),
            )
        })
        .collect()
}

/// The tensor-product conversion as stencils over node indices: `net` lists the node index of
/// `d[k][l]` at `k * mv.ncols() + l` (`k` along `u`), and stencil `i * mv.nrows() + j` gives
/// `b[i][j] = sum_kl mu[i][k] mv[j][l] d[k][l]` (the row-major patch order of
/// [`BezierPatch::cps`]).
///
/// # Panics
/// Panics when `net.len() != mu.ncols() * mv.ncols()`.
pub fn tensor_stencils(mu: &Matrix, mv: &Matrix, net: &[usize]) -> Vec<Stencil> {
    assert_eq!(
        net.len(),
        mu.ncols() * mv.ncols(),
        "net size does not match matrices"
    );
    let mut rows: Vec<Vec<(usize, f64)>> = Vec::with_capacity(mu.nrows() * mv.nrows());
    tensor_weights(mu, mv, |first, node, w| {
        if first {
            rows.push(Vec::new());
        }
        if let (Some(w), Some(row)) = (w, rows.last_mut()) {
            row.push((net[node], w));
        }
    });
    rows.into_iter().map(Stencil::from_pairs).collect()
}

/// Visits the weights of the tensor-product conversion in patch order: for every coefficient
/// `(i, j)` (row-major) first a call `(true, 0, None)`, then `(false, k * mv.ncols() + l, Some(w))`
/// for every non-zero `w = mu[i][k] mv[j][l]`, `k` then `l` increasing. The one definition of
/// the weights behind [`tensor_stencils`] and [`tensor_apply`].
fn tensor_weights(mu: &Matrix, mv: &Matrix, mut f: impl FnMut(bool, usize, Option<f64>)) {
    let nl = mv.ncols();
    for i in 0..mu.nrows() {
        for j in 0..mv.nrows() {
            f(true, 0, None);
            for k in 0..mu.ncols() {
                let a = mu[(i, k)];
                if a == 0.0 {
                    continue;
                }
                for l in 0..nl {
                    let b = mv[(j, l)];
                    if b != 0.0 {
                        f(false, k * nl + l, Some(a * b));
                    }
                }
            }
        }
    }
}

/// The tensor-product conversion applied to points: `net[k * mv.ncols() + l]` is `d[k][l]`
/// (`k` along `u`); returns the patch of bi-degree `(mu.nrows() - 1, mv.nrows() - 1)`.
/// The weights are those of [`tensor_stencils`] (the same products, summed in the same order).
///
/// # Panics
/// Panics when `net.len() != mu.ncols() * mv.ncols()` or a matrix has no rows.
pub fn tensor_apply(mu: &Matrix, mv: &Matrix, net: &[Point]) -> BezierPatch {
    assert_eq!(
        net.len(),
        mu.ncols() * mv.ncols(),
        "net size does not match matrices"
    );
    // Applied directly, without building stencils: this is the hot path of every regular patch.
    let mut cps: Vec<Point> = Vec::with_capacity(mu.nrows() * mv.nrows());
    tensor_weights(mu, mv, |first, node, w| {
        if first {
            cps.push([0.0; 3]);
        }
        if let (Some(w), Some(acc)) = (w, cps.last_mut()) {
            let p = &net[node];
            for d in 0..3 {
                acc[d] += w * p[d];
            }
        }
    });
    BezierPatch::new(mu.nrows() - 1, mv.nrows() - 1, cps)
}

fn flatten<const N: usize, T: Copy>(net: &[[T; N]; N]) -> Vec<T> {
    net.iter().flat_map(|r| r.iter().copied()).collect()
}

/// One uniform cubic B-spline segment in Bezier form (4 coefficients) from `d0..d3`.
pub fn cubic_bspline_to_bezier(d: &[Point; 4]) -> [Point; 4] {
    let b = curve_apply(cubic_bspline_matrix(), d);
    [b[0], b[1], b[2], b[3]]
}

/// One uniform quadratic B-spline segment in Bezier form from `d0..d2`.
pub fn quadratic_bspline_to_bezier(d: &[Point; 3]) -> [Point; 3] {
    let b = curve_apply(quadratic_bspline_matrix(), d);
    [b[0], b[1], b[2]]
}

/// One C^2 quartic double-knot segment (EG formula (5)) in Bezier form from `d0..d4`.
pub fn quartic_c2_to_bezier(d: &[Point; 5]) -> [Point; 5] {
    let b = curve_apply(quartic_c2_matrix(), d);
    [b[0], b[1], b[2], b[3], b[4]]
}

/// The bi-3 patch of a uniform bicubic B-spline surface over the middle face of a 4x4 net
/// `net[k][l]` (`k` along `u`).
pub fn bicubic_bspline_to_bezier(net: &[[Point; 4]; 4]) -> BezierPatch {
    let m = cubic_bspline_matrix();
    tensor_apply(m, m, &flatten(net))
}

/// [`bicubic_bspline_to_bezier`] as stencils over the node indices `net[k][l]`.
pub fn bicubic_bspline_stencils(net: &[[usize; 4]; 4]) -> Vec<Stencil> {
    let m = cubic_bspline_matrix();
    tensor_stencils(m, m, &flatten(net))
}

/// The bi-2 patch of a uniform biquadratic B-spline surface over the middle node of a 3x3 net
/// `net[k][l]` (`k` along `u`).
pub fn biquadratic_bspline_to_bezier(net: &[[Point; 3]; 3]) -> BezierPatch {
    let m = quadratic_bspline_matrix();
    tensor_apply(m, m, &flatten(net))
}

/// [`biquadratic_bspline_to_bezier`] as stencils over the node indices `net[k][l]`.
pub fn biquadratic_bspline_stencils(net: &[[usize; 3]; 3]) -> Vec<Stencil> {
    let m = quadratic_bspline_matrix();
    tensor_stencils(m, m, &flatten(net))
}

/// The bi-4 patch of a C^2 quartic double-knot spline surface (the EG d-net) from a 5x5 net
/// `net[k][l]`, by tensoring formula (5).
///
/// Index convention: the first index of both `b[i][j]` and `d[k][l]` runs along `u`, so
/// `b[i][j] = sum_kl M[i][k] M[j][l] d[k][l]`, `d[2][2]` is the patch's central node
/// (`b[2][2] = d[2][2]`) and `d[1][1]` the node of corner `b[0][0]`. With this convention the
/// tensor form reproduces the EG paper's formula (6) for `b00`, `b10`, `b20`, `b11`, `b22`
/// exactly. The paper prints `b21 := (d12 + d22)/2`, which under that same convention is
/// `b12`; the tensor form gives `b21 = (d21 + d22)/2`, the only value consistent with the
/// paper's `b10` and `b20` (and with its symmetry rules). The test
/// `eg_formula_6_matches_tensor_form` records this.
pub fn biquartic_c2_to_bezier(net: &[[Point; 5]; 5]) -> BezierPatch {
    let m = quartic_c2_matrix();
    tensor_apply(m, m, &flatten(net))
}

/// [`biquartic_c2_to_bezier`] as stencils over the node indices `net[k][l]`.
pub fn biquartic_c2_stencils(net: &[[usize; 5]; 5]) -> Vec<Stencil> {
    let m = quartic_c2_matrix();
    tensor_stencils(m, m, &flatten(net))
}

/// The triangular Bezier patch of degree `n` with coefficients `tri` as the equivalent
/// degenerate tensor-product patch of bi-degree `(n, n)`, `X(u, v) = T(u (1 - v), v)` (side
/// `v = 1` collapsed to the corner `P2`). `tri` lists `b_ijk`, `i + j + k = n`, in rows of
/// decreasing `i`, within a row decreasing `j`. Column `j` (`v`-index) of the result is the
/// degree-`n - j` curve `b_(n-j-r, r, j)`, degree-raised to `n`.
pub fn triangle_to_tensor(n: usize, tri: &[Point]) -> BezierPatch {
    debug_assert_eq!(tri.len(), (n + 1) * (n + 2) / 2);
    let index = |i: usize, j: usize| -> usize {
        let before: usize = (i + 1..=n).map(|a| n + 1 - a).sum();
        before + (n - i - j)
    };
    let binom = |n: usize, k: usize| -> f64 {
        if k > n {
            0.0
        } else {
            (0..k).fold(1.0, |acc, r| acc * (n - r) as f64 / (r + 1) as f64)
        }
    };
    BezierPatch::from_fn(n, n, |i, j| {
        let d = n - j;
        let mut p = [0.0; 3];
        for r in 0..=d.min(i) {
            if i - r > n - d {
                continue;
            }
            let w = binom(d, r) * binom(n - d, i - r) / binom(n, i);
            p = crate::geom::axpy(p, w, tri[index(d - r, r)]);
        }
        p
    })
}

#[cfg(feature = "unit-tests")]
mod tests;
