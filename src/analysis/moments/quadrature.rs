//! Gauss-Legendre rules on `[0, 1]`, their tensor products on rectangles of a patch's domain
//! and their collapsed (Duffy) products on the triangle below a square's diagonal, and the
//! integrals of a Bezier patch's moment integrands over them.
//!
//! The `q`-point Gauss-Legendre rule integrates polynomials of degree `2q - 1` exactly, so its
//! tensor product integrates a polynomial of bi-degree `(a, b)` exactly when `2 q_u - 1 >= a`
//! and `2 q_v - 1 >= b`. On the triangle `{0 <= v <= u <= 1}` the map `(x, y) -> (x, x y)`
//! (Jacobian `x`) turns a polynomial of bi-degree `(a, b)` in `(u, v)` into one of bi-degree
//! `(a + b + 1, b)` in `(x, y)`: the conical product rule (Stroud), exact for that degree.
//!
//! The nodes are the roots of the Legendre polynomial `P_q`, found by Newton's iteration from
//! Tricomi's approximation (`cos(pi (i - 1/4) / (q + 1/2))`) with the three-term recurrence,
//! to full double precision; the weights are `2 / ((1 - x^2) P_q'(x)^2)`. Written here rather
//! than taken from a crate: twenty lines, tested for exactness on monomials up to degree
//! `2q - 1` for every `q` used.

use crate::bezier::{BezierPatch, curve};
use crate::geom::{Point, cross};
use std::sync::OnceLock;

/// Most points per direction a rule has (bi-degree 6's fifth moments need 15; the area's
/// checks go a little beyond).
pub const MAX_POINTS: usize = 48;

/// The `q`-point Gauss-Legendre rule on `[0, 1]`: nodes ascending, weights summing to 1.
pub fn gauss_legendre(q: usize) -> &'static [(f64, f64)] {
    static RULES: OnceLock<Vec<Vec<(f64, f64)>>> = OnceLock::new();
    let rules = RULES.get_or_init(|| (0..=MAX_POINTS).map(compute).collect());
    &rules[q.clamp(1, MAX_POINTS)]
}

/// The `q`-point rule on `[0, 1]` (see the module documentation).
fn compute(q: usize) -> Vec<(f64, f64)> {
    if q == 0 {
        return Vec::new();
    }
    let n = q as f64;
    let mut out = Vec::with_capacity(q);
    for i in 1..=q {
        let mut x = (std::f64::consts::PI * (i as f64 - 0.25) / (n + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            // P_q(x) and P_q'(x) by the recurrence
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=q {
                let k = k as f64;
                let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            let p = if q == 1 { x } else { p1 };
            let pm = if q == 1 { 1.0 } else { p0 };
            dp = n * (x * p - pm) / (x * x - 1.0);
            let dx = p / dp;
            x -= dx;
            if dx.abs() <= 1e-16 {
                break;
            }
        }
        let w = 2.0 / ((1.0 - x * x) * dp * dp);
        out.push(((1.0 - x) / 2.0, w / 2.0));
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out
}

/// Points of a domain rule, grouped by their `u`: for each `u` node its `(v, weight)` pairs
/// (the weights include the region's Jacobian).
pub type Columns = Vec<(f64, Vec<(f64, f64)>)>;

/// The tensor rule with `qu x qv` points on the rectangle `[lo, hi]` of a patch's domain.
pub fn rectangle(lo: [f64; 2], hi: [f64; 2], qu: usize, qv: usize) -> Columns {
    let (du, dv) = (hi[0] - lo[0], hi[1] - lo[1]);
    let gv = gauss_legendre(qv);
    gauss_legendre(qu)
        .iter()
        .map(|&(x, wx)| {
            let col = gv
                .iter()
                .map(|&(y, wy)| (lo[1] + dv * y, wx * wy * du * dv));
            (lo[0] + du * x, col.collect())
        })
        .collect()
}

/// The conical product rule on the triangle `{0 <= v <= u <= 1}` (half of the unit square
/// below its diagonal), `qx` points along `u` and `qy` along `v / u`.
pub fn lower_triangle(qx: usize, qy: usize) -> Columns {
    let gy = gauss_legendre(qy);
    gauss_legendre(qx)
        .iter()
        .map(|&(x, wx)| (x, gy.iter().map(|&(y, wy)| (x * y, wx * wy * x)).collect()))
        .collect()
}

/// What a point of a patch contributes: the point, and `du x dv` (the area element's
/// vector).
#[derive(Debug, Clone, Copy)]
pub struct Sample {
    /// The point.
    pub p: Point,
    /// `X_u x X_v`.
    pub n: Point,
}

/// Calls `f(sample, weight)` at every point of `rule` on `patch` (`u` contracted first per
/// column, then `v` per point; a rational patch through [`BezierPatch::derivatives`]).
pub fn for_each_sample(patch: &BezierPatch, rule: &Columns, mut f: impl FnMut(Sample, f64)) {
    if patch.weights.is_some() {
        // a rational patch: the quotient rule's derivatives, point by point
        for (u, col) in rule {
            for &(v, w) in col {
                let d = patch.derivatives(*u, v);
                f(
                    Sample {
                        p: d.p,
                        n: cross(d.du, d.dv),
                    },
                    w,
                );
            }
        }
        return;
    }
    let (du, dv) = (patch.deg_u, patch.deg_v);
    let (nu, nv) = (du + 1, dv + 1);
    let n = nu.max(nv);
    let mut b = vec![0.0; 6 * n];
    let (bu0, rest) = b.split_at_mut(n);
    let (bu1, rest) = rest.split_at_mut(n);
    let (bv0, rest) = rest.split_at_mut(n);
    let (bv1, scratch) = rest.split_at_mut(n);
    let (s1, s2) = scratch.split_at_mut(n);
    // the column sums C_j = sum_i B_i(u) b_ij, D_j = sum_i B_i'(u) b_ij
    let mut c = vec![[0.0; 3]; nv];
    let mut d = vec![[0.0; 3]; nv];
    for (u, col) in rule {
        curve::bernstein_derivs(du, *u, bu0, bu1, s1);
        for j in 0..nv {
            let (mut cj, mut dj) = ([0.0; 3], [0.0; 3]);
            for i in 0..nu {
                let p = patch.cps[i * nv + j];
                for k in 0..3 {
                    cj[k] += bu0[i] * p[k];
                    dj[k] += bu1[i] * p[k];
                }
            }
            c[j] = cj;
            d[j] = dj;
        }
        for &(v, w) in col {
            curve::bernstein_derivs(dv, v, bv0, bv1, s2);
            let (mut p, mut xu, mut xv) = ([0.0; 3], [0.0; 3], [0.0; 3]);
            for j in 0..nv {
                for k in 0..3 {
                    p[k] += bv0[j] * c[j][k];
                    xu[k] += bv0[j] * d[j][k];
                    xv[k] += bv1[j] * c[j][k];
                }
            }
            f(
                Sample {
                    p,
                    n: cross(xu, xv),
                },
                w,
            );
        }
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn rules_integrate_monomials_exactly_up_to_degree_2q_minus_1() {
        for q in 1..=MAX_POINTS {
            let r = gauss_legendre(q);
            assert_eq!(r.len(), q);
            for deg in 0..2 * q {
                let s: f64 = r.iter().map(|&(x, w)| w * x.powi(deg as i32)).sum();
                let exact = 1.0 / (deg as f64 + 1.0);
                // rounding of q terms (and of the nodes' Newton iteration): a few ulps each
                let tol = 4e-15f64.max(1e-15 * q as f64);
                assert!(
                    (s - exact).abs() <= tol * exact.max(1e-3) + 1e-16,
                    "q {q} degree {deg}: {s} vs {exact}"
                );
            }
            // and not one degree more (the rule's degree is exactly 2q - 1; its error on
            // x^(2q) drops below rounding for q > 8)
            let deg = 2 * q;
            let s: f64 = r.iter().map(|&(x, w)| w * x.powi(deg as i32)).sum();
            assert!(
                q > 8 || (s - 1.0 / (deg as f64 + 1.0)).abs() > 1e-15,
                "q {q}"
            );
        }
    }

    #[crate::unit::test]
    fn the_conical_rule_integrates_over_the_lower_triangle() {
        // int_{v <= u} u^a v^b = 1 / ((b + 1) (a + b + 2))
        for a in 0..6usize {
            for b in 0..6usize {
                let rule = lower_triangle((a + b + 3).div_ceil(2), (b + 1).div_ceil(2) + 1);
                let s: f64 = rule
                    .iter()
                    .flat_map(|(u, col)| col.iter().map(move |&(v, w)| (*u, v, w)))
                    .map(|(u, v, w)| w * u.powi(a as i32) * v.powi(b as i32))
                    .sum();
                let exact = 1.0 / ((b + 1) as f64 * (a + b + 2) as f64);
                assert!((s - exact).abs() < 1e-15, "u^{a} v^{b}: {s} vs {exact}");
            }
        }
    }
}
