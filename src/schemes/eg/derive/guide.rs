//! The guide space of the EG derivation (Section 4): `n` bi-5 sectors `g^s` over the unit
//! square, `G^1`-connected through the shear `L`, with a unique quadratic expansion at the common
//! point; and the fairness functionals `F_k` that fix the coefficients the fit leaves free.
//!
//! # Frames
//!
//! Sector `s` of the guide lives on the unit square; `L_s(u, v) = u e(theta_s) + v e(theta_s +
//! alpha)`, `theta_s = -s alpha`, maps it onto the parallelogram of the EG chart's sector `s`
//! (its `u` axis is the ray shared with sector `s + 1`, whose `v` axis it is). Coefficient
//! `g^s_ij` (`i` along u) has index `36 s + 6 i + j`.
//!
//! # Constraints (exactly what `L` satisfies)
//!
//! Along the ray shared by sectors `s` and `t = s + 1`, with `c = cos alpha`:
//!
//! * C^0: `g^s(r, 0) = g^t(0, r)`, i.e. `g^s_i0 = g^t_0i`;
//! * G^1: `d_v g^s(r, 0) + d_u g^t(0, r) = 2 c d_u g^s(r, 0)` (differentiate `g o L^-1` across
//!   the ray: `e(theta + alpha) = -e(theta - alpha) + 2 c e(theta)`); in BB form six equations,
//!   the right side degree-raised from 4 to 5;
//! * unique quadratic expansion: the total-degree-2 Taylor coefficients of every `g^s` at the
//!   centre are those of `Q o L_s` for one quadratic `Q` of the plane.
//!
//! `L` itself, and every `Q o L` with `Q` a polynomial of degree <= 5 of the plane, satisfy all
//! of them: the guide space contains the planar characteristic map (so Catmull-Clark's lambda is
//! reproduced exactly) and all polynomials (so the fit reproduces what its fairness functional
//! annihilates).

use crate::bezier::bern::{bernstein_derivs, binom, gauss_legendre};
use nalgebra::DMatrix;
use std::f64::consts::PI;

/// Index of `g^s_ij`.
pub fn gidx(s: usize, i: usize, j: usize) -> usize {
    36 * s + 6 * i + j
}

/// The columns of `L_s` (plane images of the unit `u` and `v` directions).
pub fn shear(n: usize, s: usize) -> [[f64; 2]; 2] {
    let alpha = 2.0 * PI / n as f64;
    let th = -(s as f64) * alpha;
    [
        [th.cos(), th.sin()],
        [(th + alpha).cos(), (th + alpha).sin()],
    ]
}

/// Taylor coefficient of `u^a v^b` at the centre of a bi-5 patch, as a row over its 36 BB
/// coefficients.
pub fn centre_taylor(a: usize, b: usize) -> [f64; 36] {
    let m = super::sampling::bernstein_to_monomial(5);
    let mut r = [0.0; 36];
    for i in 0..6 {
        for j in 0..6 {
            r[6 * i + j] = m[(a, i)] * m[(b, j)];
        }
    }
    r
}

/// The total-degree-2 monomials `(a, b)` of the central expansion, in the order
/// `1, u, v, u^2, uv, v^2`.
pub const CENTRAL: [(usize, usize); 6] = [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)];

/// `6 x 6` map from a plane quadratic (coefficients of `1, x, y, x^2, xy, y^2`) to the central
/// Taylor coefficients ([`CENTRAL`]) of `Q o L` for the shear with columns `l`.
pub fn quadratic_to_central(l: [[f64; 2]; 2]) -> DMatrix<f64> {
    // x = l[0][0] u + l[1][0] v, y = l[0][1] u + l[1][1] v.
    let (xu, xv, yu, yv) = (l[0][0], l[1][0], l[0][1], l[1][1]);
    let cols: [[f64; 6]; 6] = [
        [1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, xu, xv, 0.0, 0.0, 0.0],
        [0.0, yu, yv, 0.0, 0.0, 0.0],
        [0.0, 0.0, 0.0, xu * xu, 2.0 * xu * xv, xv * xv],
        [0.0, 0.0, 0.0, xu * yu, xu * yv + xv * yu, xv * yv],
        [0.0, 0.0, 0.0, yu * yu, 2.0 * yu * yv, yv * yv],
    ];
    DMatrix::from_fn(6, 6, |r, c| cols[c][r])
}

/// The constraint matrix of the guide space (rows vanish on the space) over `36 n`
/// coefficients.
pub fn constraints(n: usize) -> DMatrix<f64> {
    let c = (2.0 * PI / n as f64).cos();
    let mut rows: Vec<Vec<(usize, f64)>> = Vec::new();
    for s in 0..n {
        let t = (s + 1) % n;
        for i in 0..6 {
            rows.push(vec![(gidx(s, i, 0), 1.0), (gidx(t, 0, i), -1.0)]);
        }
        for i in 0..6 {
            let mut r = vec![
                (gidx(s, i, 1), 5.0),
                (gidx(s, i, 0), -5.0),
                (gidx(t, 1, i), 5.0),
                (gidx(t, 0, i), -5.0),
            ];
            // 2 c d_u g^s(r, 0), degree-raised: e_i = i/5 a_(i-1) + (1 - i/5) a_i,
            // a_k = 5 (g_(k+1, 0) - g_(k, 0)).
            for (k, w) in [
                (i as i64 - 1, i as f64 / 5.0),
                (i as i64, 1.0 - i as f64 / 5.0),
            ] {
                if (0..=4).contains(&k) && w != 0.0 {
                    let k = k as usize;
                    r.push((gidx(s, k + 1, 0), -2.0 * c * 5.0 * w));
                    r.push((gidx(s, k, 0), 2.0 * c * 5.0 * w));
                }
            }
            rows.push(r);
        }
    }
    // Central expansion: jets_s = M_s M_0^-1 jets_0.
    let m0 = quadratic_to_central(shear(n, 0))
        .try_inverse()
        .expect("the shear is invertible");
    let taylor: Vec<[f64; 36]> = CENTRAL.iter().map(|&(a, b)| centre_taylor(a, b)).collect();
    for s in 1..n {
        let t = quadratic_to_central(shear(n, s)) * &m0;
        for (r, tr) in taylor.iter().enumerate() {
            let mut row = Vec::new();
            for (k, x) in tr.iter().enumerate() {
                if *x != 0.0 {
                    row.push((36 * s + k, *x));
                }
            }
            for (q, tq) in taylor.iter().enumerate() {
                let w = t[(r, q)];
                if w.abs() > 1e-15 {
                    for (k, x) in tq.iter().enumerate() {
                        if *x != 0.0 {
                            row.push((k, -w * x));
                        }
                    }
                }
            }
            rows.push(row);
        }
    }
    let mut m = DMatrix::zeros(rows.len(), 36 * n);
    for (r, row) in rows.iter().enumerate() {
        for &(k, w) in row {
            m[(r, k)] += w;
        }
    }
    m
}

/// The Gram matrix of `F_k g = int_[0,1]^2 sum_(i+j=k) k!/(i! j!) (d_u^i d_v^j g)^2` for one
/// bi-`d` patch (`(d + 1)^2` BB coefficients, index `(d + 1) i + j`).
pub fn fairness_gram(d: usize, k: usize) -> DMatrix<f64> {
    let m = (d + 1) * (d + 1);
    let gl = gauss_legendre(d + 2);
    let mut g = DMatrix::zeros(m, m);
    for i in 0..=k.min(d) {
        let j = k - i;
        if j > d {
            continue;
        }
        let w = binom(k, i);
        for &(x, wx) in &gl {
            let bu = bernstein_derivs(d, i, x);
            for &(y, wy) in &gl {
                let bv = bernstein_derivs(d, j, y);
                let v: Vec<f64> = (0..m).map(|r| bu[r / (d + 1)] * bv[r % (d + 1)]).collect();
                let f = w * wx * wy;
                for r in 0..m {
                    if v[r] == 0.0 {
                        continue;
                    }
                    for c in 0..m {
                        g[(r, c)] += f * v[r] * v[c];
                    }
                }
            }
        }
    }
    g
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn the_shear_and_quadratics_lie_in_the_guide_space() {
        for n in [3, 5, 8] {
            let c = constraints(n);
            // g^s = Q o L_s for a cubic Q of the plane, as bi-5 BB coefficients (by blossoming a
            // polynomial of degree <= 5: evaluate at the 36 points and solve).
            let q = |x: f64, y: f64| 0.3 + x - 2.0 * y + 0.5 * x * x - x * y + 0.25 * y * y * y;
            let mut g = nalgebra::DVector::zeros(36 * n);
            let pts: Vec<f64> = (0..6).map(|k| k as f64 / 5.0).collect();
            let vand = DMatrix::from_fn(36, 36, |r, col| {
                let (u, v) = (pts[r / 6], pts[r % 6]);
                let bu = bernstein_derivs(5, 0, u);
                let bv = bernstein_derivs(5, 0, v);
                bu[col / 6] * bv[col % 6]
            });
            let lu = vand.lu();
            for s in 0..n {
                let l = shear(n, s);
                let rhs = nalgebra::DVector::from_fn(36, |r, _| {
                    let (u, v) = (pts[r / 6], pts[r % 6]);
                    q(u * l[0][0] + v * l[1][0], u * l[0][1] + v * l[1][1])
                });
                let b = lu.solve(&rhs).expect("invertible");
                g.rows_mut(36 * s, 36).copy_from(&b);
            }
            let r = &c * &g;
            assert!(r.amax() < 1e-10, "n={n}: {}", r.amax());
        }
    }
}
