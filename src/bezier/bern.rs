//! Univariate Bernstein-Bezier tools as matrices, for the linear maps of guided subdivision and
//! EG's derivation: derivative values, Taylor coefficients at a point, restriction to a sub-interval (also an
//! extrapolating one, by blossoming), degree raising, power-to-Bernstein conversion at a corner,
//! and Gauss-Legendre quadrature. Tensor-product maps are Kronecker products of these.

use nalgebra::DMatrix;

/// `binomial(n, k)` as a float (0 when `k > n`).
pub fn binom(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    let k = k.min(n - k);
    let mut r = 1.0;
    for i in 0..k {
        r = r * (n - i) as f64 / (i + 1) as f64;
    }
    r
}

/// Values of the `m`-th derivatives of the Bernstein polynomials `B_i^d`, `i = 0..=d`, at `t`.
pub fn bernstein_derivs(d: usize, m: usize, t: f64) -> Vec<f64> {
    let mut out = vec![0.0; d + 1];
    if m > d {
        return out;
    }
    // d^m/dt^m B_i^d = d!/(d-m)! sum_l (-1)^(m-l) C(m, l) B_(i-l)^(d-m).
    let e = d - m;
    let base: Vec<f64> = (0..=e)
        .map(|k| binom(e, k) * (1.0 - t).powi((e - k) as i32) * t.powi(k as i32))
        .collect();
    let mut f = 1.0;
    for k in 0..m {
        f *= (d - k) as f64;
    }
    for (i, o) in out.iter_mut().enumerate() {
        let mut s = 0.0;
        for l in 0..=m {
            if l <= i && i - l <= e {
                let sign = if (m - l).is_multiple_of(2) { 1.0 } else { -1.0 };
                s += sign * binom(m, l) * base[i - l];
            }
        }
        *o = f * s;
    }
    out
}

/// Taylor coefficients of the Bernstein polynomials about `t0`: `[i][m]` is the coefficient of
/// `(t - t0)^m` in `B_i^d(t)`, `m < k`.
pub fn bernstein_taylor(d: usize, t0: f64, k: usize) -> Vec<Vec<f64>> {
    let mut out = vec![vec![0.0; k]; d + 1];
    let mut fact = 1.0;
    for m in 0..k {
        if m > 0 {
            fact *= m as f64;
        }
        let dv = bernstein_derivs(d, m, t0);
        for i in 0..=d {
            out[i][m] = dv[i] / fact;
        }
    }
    out
}

/// The `(d + 1) x (d + 1)` matrix taking the Bezier coefficients of a degree-`d` polynomial on
/// `[0, 1]` to those of the same polynomial on `[a, b]` (reparametrised to `[0, 1]`), by
/// blossoming: new `c_j = blossom(a^(d-j), b^j)`. `a, b` may lie outside `[0, 1]`
/// (extrapolation, as in C^k prolongation).
pub fn subsegment(d: usize, a: f64, b: f64) -> DMatrix<f64> {
    let mut m = DMatrix::zeros(d + 1, d + 1);
    for j in 0..=d {
        // de Casteljau on the basis vectors with the arguments a^(d-j) b^j.
        let args: Vec<f64> = std::iter::repeat_n(a, d - j)
            .chain(std::iter::repeat_n(b, j))
            .collect();
        for i in 0..=d {
            let mut c = vec![0.0; d + 1];
            c[i] = 1.0;
            for (r, &t) in args.iter().enumerate() {
                for k in 0..d - r {
                    c[k] = (1.0 - t) * c[k] + t * c[k + 1];
                }
            }
            m[(j, i)] = c[0];
        }
    }
    m
}

/// Degree raising from `d` to `e >= d`: `(e + 1) x (d + 1)`.
pub fn raise(d: usize, e: usize) -> DMatrix<f64> {
    let mut m = DMatrix::identity(d + 1, d + 1);
    for k in d..e {
        let mut r = DMatrix::<f64>::zeros(k + 2, k + 1);
        for i in 0..=k + 1 {
            let a = i as f64 / (k + 1) as f64;
            if i > 0 {
                r[(i, i - 1)] += a;
            }
            if i <= k {
                r[(i, i)] += 1.0 - a;
            }
        }
        m = r * m;
    }
    m
}

/// Power coefficients `t_m` (of `r^m`, `m < k`, `r` the distance from the end point into the
/// interval) to the `k` Bezier coefficients of degree `d` nearest that end point:
/// `b_i = sum_(m <= i) C(i, m) / C(d, m) t_m` (`k x k`).
pub fn power_to_bezier(d: usize, k: usize) -> DMatrix<f64> {
    DMatrix::from_fn(k, k, |i, m| {
        if m <= i {
            binom(i, m) / binom(d, m)
        } else {
            0.0
        }
    })
}

/// Kronecker product `a (x) b`.
pub fn kron(a: &DMatrix<f64>, b: &DMatrix<f64>) -> DMatrix<f64> {
    let (ar, ac) = a.shape();
    let (br, bc) = b.shape();
    DMatrix::from_fn(ar * br, ac * bc, |r, c| {
        a[(r / br, c / bc)] * b[(r % br, c % bc)]
    })
}

/// Gauss-Legendre nodes and weights on `[0, 1]` with `k` points (exact for degree `2k - 1`).
pub fn gauss_legendre(k: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(k);
    for i in 0..k {
        // Newton iteration on P_k from the Chebyshev guess.
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (k as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for j in 2..=k {
                let p2 = ((2 * j - 1) as f64 * x * p1 - (j - 1) as f64 * p0) / j as f64;
                p0 = p1;
                p1 = p2;
            }
            dp = k as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        let w = 2.0 / ((1.0 - x * x) * dp * dp);
        out.push((0.5 * (x + 1.0), 0.5 * w));
    }
    out
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn subsegment_and_raise_agree_with_evaluation() {
        let c = [0.3, -1.0, 2.0, 0.5, 1.5, -0.2];
        let eval = |cs: &[f64], t: f64| -> f64 {
            let b = bernstein_derivs(cs.len() - 1, 0, t);
            cs.iter().zip(&b).map(|(x, y)| x * y).sum()
        };
        let s = subsegment(5, -0.5, 0.25);
        let cv = nalgebra::DVector::from_column_slice(&c);
        let n = &s * &cv;
        for t in [0.0, 0.3, 1.0] {
            let x = -0.5 + 0.75 * t;
            assert!((eval(n.as_slice(), t) - eval(&c, x)).abs() < 1e-12);
        }
        let r = raise(5, 7) * &cv;
        assert!((eval(r.as_slice(), 0.37) - eval(&c, 0.37)).abs() < 1e-12);
        let gl = gauss_legendre(6);
        let integral: f64 = gl.iter().map(|&(x, w)| w * x.powi(11)).sum();
        assert!((integral - 1.0 / 12.0).abs() < 1e-14);
    }
}
