//! Quadratics sampled through `chi`, and `T` from `K` by their reproduction (QAS+).
//!
//! A quadratic `Q` of the plane defines a d-net `D(Q)` (the L-net samples of `Q o chi` in every
//! sector, joined with [`crate::schemes::eg::derive::Join::RayAverage`], the same sampling the derivation uses) and the
//! coefficients `q^s` of every sector ([`quadratic_q`]). QAS+ must map `(D(Q), q(Q))` to
//! `D_(1/2)(Q)`, the samples of `Q o chi / 2`, on the six special nodes: that fixes `T` given `K`
//! (`T = N_lambda(q) - K D(q)`): five equations per row, one per non-constant quadratic. For
//! the ray nodes 31, 32, whose rule (6) sees `q^s` and the mirrored `q^(s+1)`, a C^2 quadratic
//! only fixes the response to quadratics symmetric across the ray; the response of the
//! own-sector expression to the antisymmetric ones (`s`, `t s` with `t` along the ray) is set to
//! zero, so that the rule computed from sector `s`'s quadratic alone is mirror symmetric too.

use super::chi::derived_z;
use crate::error::{Error, Result};
use crate::schemes::eg::derive::sampling::{
    Jet, LNET_KEYS, jet_from_block, jet_mul, lnet, lnet_nodes,
};
use crate::schemes::eg::{SPECIAL, dnet_index, dnet_node};
use crate::schemes::qas::QasRules;
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;

/// A plane quadratic: coefficients of `1, x, y, x^2, xy, y^2` in the frame of sector 0 (chi's
/// frame: sector 0's bisectrix on the x axis, its chart `u` axis at `+alpha / 2`).
pub type Quadratic = [f64; 6];

/// Jets of sector 0's `chi` (frame coordinates) at the L-net corners, scaled by `scale`.
fn chi_jets(n: usize, scale: f64) -> Result<[[Jet; 2]; 3]> {
    let (z, _) = derived_z(n)?;
    Ok(chi_jets_of(n, &z, scale))
}

fn chi_jets_of(n: usize, z: &[f64; 11], scale: f64) -> [[Jet; 2]; 3] {
    let p = crate::schemes::qas::chi::sector_patch(n, z);
    let blocks = [
        ([4, 3, 2], [0, 1, 2], false, true),
        ([4, 3, 2], [4, 3, 2], false, false),
        ([0, 1, 2], [4, 3, 2], true, false),
    ];
    let mut out = [[[[0.0; 3]; 3]; 2]; 3];
    for (c, (ia, ib, fu, fv)) in blocks.iter().enumerate() {
        for comp in 0..2 {
            let mut blk = [[0.0; 3]; 3];
            for x in 0..3 {
                for y in 0..3 {
                    blk[x][y] = scale * p[ia[x]][ib[y]][comp];
                }
            }
            out[c][comp] = jet_from_block(&blk, *fu, *fv);
        }
    }
    out
}

/// The jet of `Q(x, y)` for jets `x`, `y`.
fn compose(q: &Quadratic, x: &Jet, y: &Jet) -> Jet {
    let mut out = [[0.0; 3]; 3];
    let xx = jet_mul(x, x);
    let xy = jet_mul(x, y);
    let yy = jet_mul(y, y);
    for a in 0..3 {
        for b in 0..3 {
            out[a][b] = q[1] * x[a][b]
                + q[2] * y[a][b]
                + q[3] * xx[a][b]
                + q[4] * xy[a][b]
                + q[5] * yy[a][b];
        }
    }
    out[0][0] += q[0];
    out
}

/// The d-net (`12 n` nodes, paper order) of `Q o (scale chi)`: every sector's L-net samples,
/// joined with [`crate::schemes::eg::derive::Join::RayAverage`].
pub fn sampled_quadratic(n: usize, q: &Quadratic, scale: f64) -> Result<Vec<f64>> {
    sample_with(n, &chi_jets(n, scale)?, q)
}

fn sample_with(n: usize, jets: &[[Jet; 2]; 3], q: &Quadratic) -> Result<Vec<f64>> {
    let alpha = 2.0 * PI / n as f64;
    let mut est: Vec<Vec<(usize, f64)>> = vec![Vec::new(); 12 * n + 1];
    for s in 0..n {
        let (c, sn) = ((s as f64 * alpha).cos(), (s as f64 * alpha).sin());
        let mut fj = [[[0.0; 3]; 3]; 3];
        for (k, j) in jets.iter().enumerate() {
            let mut x = [[0.0; 3]; 3];
            let mut y = [[0.0; 3]; 3];
            for a in 0..3 {
                for b in 0..3 {
                    x[a][b] = c * j[0][a][b] - sn * j[1][a][b];
                    y[a][b] = sn * j[0][a][b] + c * j[1][a][b];
                }
            }
            fj[k] = compose(q, &x, &y);
        }
        let nodes = lnet_nodes(&lnet(&fj));
        for (key, x) in LNET_KEYS.iter().zip(nodes) {
            let src = dnet_node(n, s, key.0, key.1)
                .ok_or_else(|| Error::Unsupported("L-net key outside the d-net".into()))?;
            est[src].push((s, x));
        }
    }
    Ok((1..=12 * n)
        .map(|src| {
            let owner = (src - 1) / 12;
            let e = &est[src];
            let pick: Vec<f64> = if (src - 1) % 4 == 3 {
                e.iter().map(|x| x.1).collect()
            } else {
                e.iter().filter(|x| x.0 == owner).map(|x| x.1).collect()
            };
            pick.iter().sum::<f64>() / pick.len().max(1) as f64
        })
        .collect())
}

/// `q_1 .. q_6` of every sector for the quadratic `Q`: the corner coefficients of its
/// total-degree-5 net over `(O, R-, R+)`, `R+ = e(alpha/2 + s alpha)` (the chart's `u` axis),
/// `R- = e(-alpha/2 + s alpha)`.
pub fn quadratic_q(n: usize, q: &Quadratic) -> Vec<[f64; 6]> {
    let alpha = 2.0 * PI / n as f64;
    let blossom = |a: [f64; 2], b: [f64; 2]| {
        q[0] + (q[1] * (a[0] + b[0]) + q[2] * (a[1] + b[1])) / 5.0
            + (q[3] * a[0] * b[0] + 0.5 * q[4] * (a[0] * b[1] + a[1] * b[0]) + q[5] * a[1] * b[1])
                / 10.0
    };
    (0..n)
        .map(|s| {
            let th = s as f64 * alpha;
            let rp = [(th + alpha / 2.0).cos(), (th + alpha / 2.0).sin()];
            let rm = [(th - alpha / 2.0).cos(), (th - alpha / 2.0).sin()];
            let o = [0.0, 0.0];
            [
                blossom(o, o),
                blossom(o, rm),
                blossom(rm, rm),
                blossom(o, rp),
                blossom(rm, rp),
                blossom(rp, rp),
            ]
        })
        .collect()
}

/// Five non-constant quadratics adapted to sector 0's ray (its chart `u` axis): with `t` along
/// the ray and `s` across it, `t, t^2, s^2` (symmetric across the ray) and `s, t s`
/// (antisymmetric), each with its symmetry.
pub fn ray_basis(n: usize) -> [(Quadratic, bool); 5] {
    let h = PI / n as f64;
    let (c, s) = (h.cos(), h.sin());
    // t = c x + s y along the ray, w = -s x + c y across it.
    [
        ([0.0, c, s, 0.0, 0.0, 0.0], true),
        ([0.0, 0.0, 0.0, c * c, 2.0 * c * s, s * s], true),
        ([0.0, 0.0, 0.0, s * s, -2.0 * s * c, c * c], true),
        ([0.0, -s, c, 0.0, 0.0, 0.0], false),
        ([0.0, 0.0, 0.0, -c * s, c * c - s * s, s * c], false),
    ]
}

/// `T` from `K` by the reproduction of quadratics (module docs); the `tau` of `rules` is
/// ignored and the returned tables carry the new one.
pub fn t_from_k(rules: &QasRules) -> Result<QasRules> {
    let n = rules.n;
    let mut zero = rules.clone();
    zero.tau = [[0.0; 5]; 6];
    let basis = ray_basis(n);
    let (z, _) = derived_z(n)?;
    let (j1, jh) = (chi_jets_of(n, &z, 1.0), chi_jets_of(n, &z, 0.5));
    let mut samples = Vec::with_capacity(5);
    for (q, _) in &basis {
        samples.push((
            sample_with(n, &j1, q)?,
            sample_with(n, &jh, q)?,
            quadratic_q(n, q),
        ));
    }
    let mut tau = [[0.0; 5]; 6];
    for (row, t) in tau.iter_mut().enumerate() {
        let mut a = DMatrix::zeros(5, 5);
        let mut b = DVector::zeros(5);
        let w = zero.d_weights(0, row)?;
        let (h, k) = SPECIAL[row];
        for (i, ((_, sym), (d, next, qs))) in basis.iter().zip(&samples).enumerate() {
            let kd: f64 = w.iter().map(|&(src, x)| x * d[src - 1]).sum();
            for c in 0..5 {
                a[(i, c)] = qs[0][c + 1] - qs[0][0];
            }
            b[i] = if row < 4 || *sym {
                next[dnet_index(0, h, k) - 1] - kd
            } else {
                0.0
            };
        }
        let x = a
            .lu()
            .solve(&b)
            .ok_or_else(|| Error::Unsupported("quadratic reproduction is singular".into()))?;
        for c in 0..5 {
            t[c] = x[c];
        }
    }
    let mut out = rules.clone();
    out.tau = tau;
    Ok(out)
}
