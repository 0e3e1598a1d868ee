//! The corner jet constructor `[f]^d_(k x k)` of the paper, for compositions
//! `f = g o phi` of a guide sector `g` (a tensor polynomial of degree `dg` in `(u, v)`) with a
//! polynomial map `phi` (a planar Bezier patch, here `L^-1 o chi`), computed exactly by
//! truncated Taylor series: the ring `R[s, t] / (s^k, t^k)` is closed under products, so the
//! `k x k` tensor jet of the composition needs only the `k x k` jets of `phi`'s components.
//!
//! Everything is linear in the coefficients of `g`: [`corner_block`] returns the matrix taking
//! the `(dg + 1)^2` coefficients of a guide sector to the `k x k` BB coefficients of degree `d` at
//! one corner of the sampled patch (the paper's tabulation).

use crate::bezier::BezierPatch;
use crate::bezier::bern::{bernstein_taylor, power_to_bezier};
use nalgebra::DMatrix;

/// A bivariate Taylor series truncated to degree `< k` in each variable.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Truncation order per variable.
    pub k: usize,
    /// Coefficient of `s^a t^b` at `a k + b`.
    pub c: Vec<f64>,
}

impl Series {
    /// The zero series.
    pub fn zero(k: usize) -> Series {
        Series {
            k,
            c: vec![0.0; k * k],
        }
    }

    /// A constant.
    pub fn constant(k: usize, x: f64) -> Series {
        let mut s = Series::zero(k);
        s.c[0] = x;
        s
    }

    /// The truncated product.
    pub fn mul(&self, o: &Series) -> Series {
        let k = self.k;
        let mut r = Series::zero(k);
        for a in 0..k {
            for b in 0..k {
                let x = self.c[a * k + b];
                if x == 0.0 {
                    continue;
                }
                for c in 0..k - a {
                    for d in 0..k - b {
                        r.c[(a + c) * k + b + d] += x * o.c[c * k + d];
                    }
                }
            }
        }
        r
    }

    /// `self + w o`.
    pub fn axpy(&self, w: f64, o: &Series) -> Series {
        Series {
            k: self.k,
            c: self.c.iter().zip(&o.c).map(|(x, y)| x + w * y).collect(),
        }
    }
}

/// Taylor series of the `x` and `y` components of a patch about the corner `(s0, t0)`
/// (`s0, t0` in `{0, 1}`), in the offsets `(s - s0, t - t0)`.
pub fn patch_series(p: &BezierPatch, s0: f64, t0: f64, k: usize) -> [Series; 2] {
    let tu = bernstein_taylor(p.deg_u, s0, k);
    let tv = bernstein_taylor(p.deg_v, t0, k);
    let mut out = [Series::zero(k), Series::zero(k)];
    for i in 0..=p.deg_u {
        for j in 0..=p.deg_v {
            let q = p.cp(i, j);
            for a in 0..k {
                for b in 0..k {
                    let w = tu[i][a] * tv[j][b];
                    out[0].c[a * k + b] += w * q[0];
                    out[1].c[a * k + b] += w * q[1];
                }
            }
        }
    }
    out
}

/// Series of `B_i^d(x(s, t))`, `i = 0..=d`, for a series `x`.
fn bernstein_of(d: usize, x: &Series) -> Vec<Series> {
    let k = x.k;
    let x0 = x.c[0];
    let mut delta = x.clone();
    delta.c[0] = 0.0;
    // Powers of delta (zero beyond total degree 2k - 2).
    let mut pw = vec![Series::constant(k, 1.0)];
    for m in 1..=d {
        let next = pw[m - 1].mul(&delta);
        pw.push(next);
    }
    let t = bernstein_taylor(d, x0, d + 1);
    (0..=d)
        .map(|i| {
            let mut s = Series::zero(k);
            for (m, p) in pw.iter().enumerate() {
                if t[i][m] != 0.0 {
                    s = s.axpy(t[i][m], p);
                }
            }
            s
        })
        .collect()
}

/// The matrix (`k^2 x (dg + 1)^2`) taking a guide sector's BB coefficients (degree `dg`,
/// row-major `a (dg + 1) + b`) to the `k x k` BB coefficients of degree `d` of
/// `[g o phi]^d_(k x k)` at the corner `corner = (s0, t0)` of the unit square, where `phi` is
/// given by the series `phi` of its two components about that corner. Row `i k + j` is the
/// coefficient `i` steps from the corner in `s` and `j` steps in `t`.
pub fn corner_block(
    phi: &[Series; 2],
    corner: (usize, usize),
    dg: usize,
    d: usize,
) -> DMatrix<f64> {
    let k = phi[0].k;
    let bu = bernstein_of(dg, &phi[0]);
    let bv = bernstein_of(dg, &phi[1]);
    let p = power_to_bezier(d, k);
    let sign = |m: usize, flip: usize| if flip == 1 && m % 2 == 1 { -1.0 } else { 1.0 };
    let mg = (dg + 1) * (dg + 1);
    let mut out = DMatrix::zeros(k * k, mg);
    for a in 0..=dg {
        for b in 0..=dg {
            let s = bu[a].mul(&bv[b]);
            // Power coefficients in the distances into the patch.
            let t = DMatrix::from_fn(k, k, |x, y| {
                s.c[x * k + y] * sign(x, corner.0) * sign(y, corner.1)
            });
            let blk = &p * t * p.transpose();
            for i in 0..k {
                for j in 0..k {
                    out[(i * k + j, a * (dg + 1) + b)] = blk[(i, j)];
                }
            }
        }
    }
    out
}

/// Row index in a bi-`d` patch of block entry `(i, j)` at `corner`.
pub fn block_entry(d: usize, corner: (usize, usize), i: usize, j: usize) -> usize {
    let r = if corner.0 == 0 { i } else { d - i };
    let c = if corner.1 == 0 { j } else { d - j };
    r * (d + 1) + c
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn jets_reproduce_a_polynomial_composition() {
        // phi = identity scaled into [0.2, 0.6]^2: the bi-5 jets of g o phi at the four corners
        // assemble the exact restriction of g (degree 5 in each variable).
        let phi = BezierPatch::from_fn(1, 1, |i, j| {
            [0.2 + 0.4 * i as f64, 0.2 + 0.4 * j as f64, 0.0]
        });
        let g: Vec<f64> = (0..36).map(|x| ((x * 7919) % 13) as f64 - 6.0).collect();
        let gm = nalgebra::DVector::from_vec(g.clone());
        let mut assembled = vec![0.0; 36];
        for corner in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            let ser = patch_series(&phi, corner.0 as f64, corner.1 as f64, 3);
            let b = corner_block(&ser, corner, 5, 5) * &gm;
            for i in 0..3 {
                for j in 0..3 {
                    assembled[block_entry(5, corner, i, j)] = b[i * 3 + j];
                }
            }
        }
        let s = crate::bezier::bern::subsegment(5, 0.2, 0.6);
        let exact = crate::bezier::bern::kron(&s, &s) * gm;
        for (a, e) in assembled.iter().zip(exact.iter()) {
            assert!((a - e).abs() < 1e-11, "{a} vs {e}");
        }
    }
}
