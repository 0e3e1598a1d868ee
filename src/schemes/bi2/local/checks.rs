//! The published numbers of the bi-2 paper beside the computed ones, per scheme: the checks
//! of [`super::published_rules`] (characteristic polynomials, eigenvalues, limit points).

use crate::error::Result;
use crate::schemes::bi2::cos_2pi;
use crate::schemes::bi2::local_scheme::LocalScheme;
use crate::schemes::bi2::pgs::PgsParams;
use crate::schemes::bi2::polar::PolarParams;
use crate::schemes::bi2::ternary::{AlphaRule, TernaryRules, TpsParams, adjustable_lambda};
use crate::schemes::local::{FourierBlock, Spectrum};

use super::PublishedCheck;

fn check(quantity: impl Into<String>, published: f64, computed: f64) -> PublishedCheck {
    PublishedCheck::new(quantity, published, computed)
}

/// Coefficients (highest first) of `prod (x - r)` for real roots.
fn poly(roots: &[f64]) -> Vec<f64> {
    let mut c = vec![1.0];
    for &r in roots {
        let mut next = vec![0.0; c.len() + 1];
        for (i, &a) in c.iter().enumerate() {
            next[i] += a;
            next[i + 1] -= a * r;
        }
        c = next;
    }
    c
}

/// Product of two polynomials (highest first).
fn poly_mul(a: &[f64], b: &[f64]) -> Vec<f64> {
    let mut c = vec![0.0; a.len() + b.len() - 1];
    for (i, &x) in a.iter().enumerate() {
        for (j, &y) in b.iter().enumerate() {
            c[i + j] += x * y;
        }
    }
    c
}

/// Largest coefficient difference between a block's characteristic polynomial and `expect`.
fn poly_difference(block: &FourierBlock, expect: &[f64]) -> f64 {
    let got = block.characteristic_polynomial();
    if got.len() != expect.len() {
        return f64::INFINITY;
    }
    got.iter()
        .zip(expect)
        .map(|(g, e)| (g - nalgebra::Complex::new(*e, 0.0)).norm())
        .fold(0.0, f64::max)
}

/// What the analysis computed at valence `n`, for the checks against the published numbers.
pub(super) struct Computed {
    pub(super) n: usize,
    pub(super) spec: Spectrum,
    pub(super) blocks: Vec<FourierBlock>,
    /// The limit stencil over the local net.
    pub(super) limit: Vec<f64>,
    /// Points per sector of the local net.
    pub(super) k: usize,
    /// The weight of the centre (the sum of its copies) in the limit stencil.
    pub(super) centre_weight: f64,
}

impl Computed {
    /// The check of the characteristic polynomials of `equations`: the largest coefficient
    /// difference between the Fourier blocks' polynomials and `expect` of each frequency.
    fn polynomials(
        &self,
        equations: &str,
        expect: impl Fn(&FourierBlock) -> Vec<f64>,
    ) -> PublishedCheck {
        let mut worst: f64 = 0.0;
        for b in &self.blocks {
            worst = worst.max(poly_difference(b, &expect(b)));
        }
        check(
            format!("characteristic polynomials {equations}: largest coefficient difference"),
            0.0,
            worst,
        )
    }
}

/// PGS: the characteristic polynomials (5), (6), lambda_sub (10), nu_n and the limit point (7).
pub(super) fn pgs_checks(c: &Computed) -> Result<Vec<PublishedCheck>> {
    let n = c.n;
    let p = PgsParams::new(n)?;
    let d = poly(&[0.25, 0.125, 0.0625, 0.0, 0.0, 0.0, 0.0, 0.0]);
    let polynomials = c.polynomials("(5), (6)", |b| {
        if b.frequency == 0 {
            poly_mul(&poly(&[1.0, p.w1 + 2.0 * p.w2 - p.alpha]), &d)
        } else {
            let ck = cos_2pi(b.frequency as i64, n as i64);
            poly_mul(&poly(&[0.0, p.w1 + 2.0 * p.w2 * ck]), &d)
        }
    });
    Ok(vec![
        polynomials,
        check(
            "subdominant eigenvalue lambda_sub (10)",
            p.lambda,
            c.spec.lambda,
        ),
        check(
            "subsubdominant eigenvalue nu_n as stated in Section 2",
            p.published_subsubdominant(),
            c.spec.mu,
        ),
        check(
            "limit point (7): weight of p, 1 - tau",
            1.0 - p.tau,
            c.centre_weight,
        ),
        check(
            "limit point (7): weight of each a_i, tau / n",
            p.tau / n as f64,
            c.limit[1],
        ),
    ])
}

/// PolBS: the characteristic polynomials (13), (14), the eigenvalues 1/2 and 1/4 and the limit
/// point (16).
pub(super) fn polar_checks(c: &Computed) -> Result<Vec<PublishedCheck>> {
    let n = c.n;
    let p = PolarParams::new(n)?;
    let polynomials = c.polynomials("(13), (14)", |b| {
        if b.frequency == 0 {
            poly(&[1.0, 0.25, 0.0, p.beta - p.alpha])
        } else {
            let gk: f64 = (0..n)
                .map(|j| p.gamma[j] * cos_2pi((b.frequency * j) as i64, n as i64))
                .sum();
            poly(&[0.25, 0.0, 0.0, gk])
        }
    });
    Ok(vec![
        polynomials,
        check("subdominant eigenvalue 1/2", 0.5, c.spec.lambda),
        check("subsubdominant eigenvalue 1/4", 0.25, c.spec.mu),
        check("limit point (16): weight of p", 2.0 / 3.0, c.centre_weight),
        check(
            "limit point (16): weight of each a_i",
            1.0 / (3.0 * n as f64),
            c.limit[1],
        ),
    ])
}

/// TPS: the characteristic polynomials (19), (20), the subdominant eigenvalue, the
/// subsubdominant one (printed and corrected) and the limit point (21).
pub(super) fn tps_checks(c: &Computed) -> Result<Vec<PublishedCheck>> {
    let n = c.n;
    let t = TpsParams::new(n)?;
    let polynomials = c.polynomials("(19), (20)", |b| {
        if b.frequency == 0 {
            let q = [
                1.0,
                t.alpha1 + t.alpha2 - 14.0 / 27.0,
                (1.0 - 3.0 * t.alpha1 + 3.0 * t.alpha2) / 81.0,
            ];
            poly_mul(&poly(&[1.0, 0.0, 0.0, 0.0, 0.0]), &q)
        } else {
            let ck = cos_2pi(b.frequency as i64, n as i64);
            let q = [1.0, -2.0 / 27.0 * (5.0 + 2.0 * ck), 1.0 / 81.0];
            poly_mul(&poly(&[0.0; 5]), &q)
        }
    });
    let mut out = vec![
        polynomials,
        check(
            "subdominant eigenvalue (5 + 2c + 2 sqrt(c^2 + 5c + 4)) / 27",
            t.lambda,
            c.spec.lambda,
        ),
    ];
    if n == 3 {
        out.push(check(
            "subsubdominant nu_3 = .082 (printed)",
            0.082,
            c.spec.mu,
        ));
    } else {
        out.push(check(
            "subsubdominant with the printed c_2 = cos(pi / n)",
            t.printed_subsubdominant(),
            c.spec.mu,
        ));
        out.push(check(
            "subsubdominant with c_2 = cos(4 pi / n) (root of D_2 in (20))",
            t.corrected_subsubdominant(),
            c.spec.mu,
        ));
    }
    limit_point_21(c, &t, &mut out);
    Ok(out)
}

/// Adjustable TPS with `rules`: the subdominant eigenvalue (22) and its multiplicity, the limit
/// point from an input net and, where the stationary limit functional is (21), that one.
pub(super) fn adjustable_checks(c: &Computed, rules: TernaryRules) -> Result<Vec<PublishedCheck>> {
    let (n, k, limit) = (c.n, c.k, &c.limit);
    let e = rules.e;
    let t = TpsParams::new(n)?;
    let mut out = vec![
        check(
            format!("subdominant eigenvalue (22), e = {e}"),
            adjustable_lambda(e, cos_2pi(1, n as i64)),
            c.spec.lambda,
        ),
        check(
            "multiplicity of the subdominant eigenvalue (frequencies 1, n - 1)",
            2.0,
            c.spec.lambda_multiplicity as f64,
        ),
    ];
    // The limit point of a surface from an input net: the stationary limit
    // functional after the first step (uniform knots), over the input q-net.
    let ls = LocalScheme::ternary(n, rules)?;
    let size = ls.size;
    let mut lnon = vec![0.0; size];
    for s in 0..n {
        lnon[0] += limit[s * k];
        for x in 0..6 {
            lnon[1 + 6 * s + x] = limit[s * k + 1 + x];
        }
    }
    let mut w = vec![0.0; size];
    for (r, &lr) in lnon.iter().enumerate() {
        let st = ls.first.stencil(r);
        for &(c, wc) in st.entries() {
            w[c as usize] += lr * wc;
        }
    }
    let qa: f64 = (0..n).map(|s| w[1 + 6 * s]).sum();
    let qb: f64 = (0..n).map(|s| w[2 + 6 * s]).sum();
    out.push(check(
        "limit point from an input net (first step, then stationary): weight of q",
        1.0 - t.tau1 - t.tau2,
        w[0],
    ));
    out.push(check(
        "limit point from an input net: weight of the a_i together, tau_1",
        t.tau1,
        qa,
    ));
    out.push(check(
        "limit point from an input net: weight of the b_i together, tau_2",
        t.tau2,
        qb,
    ));
    let (_, _, fallback) = rules.stationary_alphas(n)?;
    if fallback || n == 4 || rules.alphas == AlphaRule::RegularSpectrum {
        // The stationary net has non-uniform knots; its own limit functional is
        // not (21) (n = 4: the exact spline value; fallback: lambda^2, lambda^4).
        return Ok(out);
    }
    limit_point_21(c, &t, &mut out);
    Ok(out)
}

/// The checks of the limit point (21): the weights of `q`, of each `a_i` and of each `b_i`.
fn limit_point_21(c: &Computed, t: &TpsParams, out: &mut Vec<PublishedCheck>) {
    let n = c.n;
    out.push(check(
        "limit point (21): weight of q, 1 - tau_1 - tau_2",
        1.0 - t.tau1 - t.tau2,
        c.centre_weight,
    ));
    out.push(check(
        "limit point (21): weight of each a_i, tau_1 / n",
        t.tau1 / n as f64,
        c.limit[1],
    ));
    out.push(check(
        "limit point (21): weight of each b_i, tau_2 / n",
        t.tau2 / n as f64,
        c.limit[2],
    ));
}
