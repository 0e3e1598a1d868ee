//! The characteristic map of Catmull-Clark subdivision in EG's d-net form, for the EG
//! derivation: its corner jets at chart radius 1 in the guide frame of a sector (`chi^T =
//! L^-1 o chi`, Section 4).
//!
//! The map is the planar subdominant eigenvector of Catmull-Clark's step on the 2-ring c-net,
//! degree-raised to a d-net by `R` (the c-net's bi-3 spline as a bi-4 spline with double knots,
//! as [`crate::schemes::eg::from_cnet`]); both are written here directly in the EG chart (c-net
//! point `(a, b)`, `a = 1, 2`, `b = 0..2`, of sector `s`). The eigenvector is normalised so that
//! sector `s` maps into the plane sector between `e(-s alpha)` (the chart's `u` axis, shared with
//! sector `s + 1`) and `e(-s alpha + alpha)`, with the ray corner `(1, 0)` at distance 1: then
//! `chi^T = L^-1 o chi` maps that corner to `(1, 0)` of the guide's unit square.

use super::sampling::{CORNERS, Jet, NODES_TO_BB, jet_from_block};
use crate::error::{Error, Result};
use crate::schemes::eg::normalize;
use nalgebra::DMatrix;
use std::f64::consts::PI;

/// Catmull-Clark's subdominant eigenvalue `(c + 5 + sqrt((c + 1)(c + 9))) / 16`.
pub fn cc_lambda(n: usize) -> f64 {
    let c = (2.0 * PI / n as f64).cos();
    (c + 5.0 + ((c + 1.0) * (c + 9.0)).sqrt()) / 16.0
}

/// Index of the c-net point at EG chart `(a, b)` (integers) of sector `s` (0 = centre).
fn cidx(n: usize, s: usize, a: i32, b: i32) -> Result<usize> {
    let Some((s, a, b)) = normalize(n, s, 4 * a, 4 * b) else {
        return Ok(0);
    };
    let (a, b) = (a / 4, b / 4);
    if !(1..=2).contains(&a) || !(0..=2).contains(&b) {
        return Err(Error::Unsupported(format!(
            "c-net point ({a}, {b}) outside the 2-ring"
        )));
    }
    Ok(1 + 6 * s + 3 * (a as usize - 1) + b as usize)
}

/// Catmull-Clark's step on the 2-ring c-net (EG chart layout, `6 n + 1` points).
fn cc_step(n: usize) -> Result<DMatrix<f64>> {
    let m = 6 * n + 1;
    let nf = n as f64;
    let mut a = DMatrix::zeros(m, m);
    a[(0, 0)] = (nf - 1.75) / nf;
    for s in 0..n {
        a[(0, cidx(n, s, 1, 0)?)] += 1.5 / (nf * nf);
        a[(0, cidx(n, s, 1, 1)?)] += 0.25 / (nf * nf);
    }
    // Regular masks by parity (half units): vertex (1, 6, 1)/8, edge (1, 1)/2, tensored.
    let reg = |x: i32| -> Vec<(i32, f64)> {
        if x % 2 == 0 {
            vec![(x / 2 - 1, 0.125), (x / 2, 0.75), (x / 2 + 1, 0.125)]
        } else {
            vec![((x - 1) / 2, 0.5), ((x + 1) / 2, 0.5)]
        }
    };
    for s in 0..n {
        for ha in 1..=2 {
            for hb in 0..=2 {
                let row = 1 + 6 * s + 3 * (ha as usize - 1) + hb as usize;
                for (pa, wa) in reg(ha) {
                    for (pb, wb) in reg(hb) {
                        a[(row, cidx(n, s, pa, pb)?)] += wa * wb;
                    }
                }
            }
        }
    }
    Ok(a)
}

/// `R`: the d-net (`12 n` nodes, paper order `1 + 12 s + 4 j + i` minus one) from the c-net.
fn degree_raise(n: usize) -> Result<DMatrix<f64>> {
    let raise = |x: i32| -> Vec<(i32, f64)> {
        if x % 2 == 0 {
            vec![
                (x / 2 - 1, 1.0 / 12.0),
                (x / 2, 10.0 / 12.0),
                (x / 2 + 1, 1.0 / 12.0),
            ]
        } else {
            vec![((x - 1) / 2, 0.5), ((x + 1) / 2, 0.5)]
        }
    };
    let mut r = DMatrix::zeros(12 * n, 6 * n + 1);
    for s in 0..n {
        for j in 0..3 {
            for i in 0..4 {
                let (hu, hv) = (3 - j as i32, 3 - i as i32);
                for (a, wa) in raise(hu) {
                    for (b, wb) in raise(hv) {
                        r[(12 * s + 4 * j + i, cidx(n, s, a, b)?)] += wa * wb;
                    }
                }
            }
        }
    }
    Ok(r)
}

/// The normalised characteristic map of Catmull-Clark as a planar d-net: `12 n` nodes (paper
/// order) and lambda.
pub fn cc_char_dnet(n: usize) -> Result<(Vec<[f64; 2]>, f64)> {
    let lambda = cc_lambda(n);
    let a = cc_step(n)? - DMatrix::identity(6 * n + 1, 6 * n + 1) * lambda;
    let ns = crate::schemes::guided::guide::null_space(&a);
    if ns.len() != 2 {
        return Err(Error::Unsupported(format!(
            "Catmull-Clark's subdominant eigenspace at valence {n} has dimension {}",
            ns.len()
        )));
    }
    let r = degree_raise(n)?;
    let d0 = &r * &ns[0];
    let d1 = &r * &ns[1];
    // Value at the ray corner (1, 0) of sectors 0 and 1: the corner BB coefficient b00 of the
    // cell [1, 2] x [0, 1] from the nodes around it.
    let corner = |d: &nalgebra::DVector<f64>, s: usize| -> Result<f64> {
        let mut v = 0.0;
        for (x, wu) in [(2, 0.25), (4, 0.5), (6, 0.25)] {
            for (y, wv) in [(-2, 0.25), (0, 0.5), (2, 0.25)] {
                v += wu * wv * d[node(n, s, x, y)? - 1];
            }
        }
        Ok(v)
    };
    // Linear map A on the eigen-coordinates with A (corner_0) = e(0), A (corner_1) = e(-alpha).
    let alpha = 2.0 * PI / n as f64;
    let src = nalgebra::Matrix2::new(
        corner(&d0, 0)?,
        corner(&d1, 0)?,
        corner(&d0, 1)?,
        corner(&d1, 1)?,
    )
    .transpose();
    let tgt = nalgebra::Matrix2::new(1.0, alpha.cos(), 0.0, -alpha.sin());
    let inv = src
        .try_inverse()
        .ok_or_else(|| Error::Unsupported("degenerate Catmull-Clark eigenvectors".into()))?;
    let map = tgt * inv;
    let pts = (0..12 * n)
        .map(|k| {
            let p = map * nalgebra::Vector2::new(d0[k], d1[k]);
            [p[0], p[1]]
        })
        .collect();
    Ok((pts, lambda))
}

/// Source index (1-based, `(c0, d-net)` layout) of the d-net node at quarter coordinates.
fn node(n: usize, s: usize, u: i32, v: i32) -> Result<usize> {
    crate::schemes::eg::dnet_node(n, s, u, v)
        .ok_or_else(|| Error::Unsupported(format!("no d-net node at ({u}, {v})/4")))
}

/// The jets of `chi^T = L^-1 o chi` of sector 0 at the chart corners `(1, 0)`, `(1, 1)`,
/// `(0, 1)` (in the guide frame: `x` along the chart's `u` axis image, `y` along `v`), and
/// lambda.
pub fn cc_chi_jets(n: usize) -> Result<([[Jet; 2]; 3], f64)> {
    let (d, lambda) = cc_char_dnet(n)?;
    let alpha = 2.0 * PI / n as f64;
    // L0 = [e(0) e(alpha)]; its inverse.
    let (c, s) = (alpha.cos(), alpha.sin());
    let linv = [[1.0, -c / s], [0.0, 1.0 / s]];
    let mut out = [[[[0.0; 3]; 3]; 2]; 3];
    for (k, &(cu, cv)) in CORNERS.iter().enumerate() {
        // Nodes (cu - 1/2, cu, cu + 1/2) x (cv - 1/2, cv, cv + 1/2), cell forward in both.
        let mut block = [[[0.0; 3]; 3]; 2];
        for x in 0..3 {
            for y in 0..3 {
                for comp in 0..2 {
                    let mut b = 0.0;
                    for (p, wp) in NODES_TO_BB[x].iter().enumerate() {
                        for (q, wq) in NODES_TO_BB[y].iter().enumerate() {
                            if *wp == 0.0 || *wq == 0.0 {
                                continue;
                            }
                            let idx =
                                node(n, 0, 4 * cu - 2 + 2 * p as i32, 4 * cv - 2 + 2 * q as i32)?;
                            b += wp * wq * d[idx - 1][comp];
                        }
                    }
                    block[comp][x][y] = b;
                }
            }
        }
        let jx = jet_from_block(&block[0], true, true);
        let jy = jet_from_block(&block[1], true, true);
        for a in 0..3 {
            for b in 0..3 {
                out[k][0][a][b] = linv[0][0] * jx[a][b] + linv[0][1] * jy[a][b];
                out[k][1][a][b] = linv[1][0] * jx[a][b] + linv[1][1] * jy[a][b];
            }
        }
    }
    Ok((out, lambda))
}
