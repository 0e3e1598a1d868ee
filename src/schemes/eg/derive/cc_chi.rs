//! The characteristic map of Catmull-Clark subdivision in EG's d-net form, for the EG
//! derivation: its corner jets at chart radius 1 in the guide frame of a sector (`chi^T =
//! L^-1 o chi`, Section 4).
//!
//! The map is the planar subdominant eigenvector of Catmull-Clark's step on the 2-ring c-net
//! (Catmull-Clark's own local matrix), degree-raised to a d-net by `R` (the c-net's bi-3 spline
//! as a bi-4 spline with double knots, [`crate::schemes::eg::from_cnet`]). The eigenvector is normalised so that
//! sector `s` maps into the plane sector between `e(-s alpha)` (the chart's `u` axis, shared with
//! sector `s + 1`) and `e(-s alpha + alpha)`, with the ray corner `(1, 0)` at distance 1: then
//! `chi^T = L^-1 o chi` maps that corner to `(1, 0)` of the guide's unit square.

use super::sampling::{CORNERS, Jet, NODES_TO_BB, jet_from_block};
use crate::error::{Error, Result};
use crate::schemes::catmull_clark::catmull_clark_lambda;
use crate::schemes::eg::from_cnet;
use crate::schemes::local::dense;
use nalgebra::DMatrix;
use std::f64::consts::PI;

/// The normalised characteristic map of Catmull-Clark as a planar d-net: `12 n` nodes (paper
/// order) and lambda.
pub fn cc_char_dnet(n: usize) -> Result<(Vec<[f64; 2]>, f64)> {
    // Catmull-Clark's own step on its c-net, and EG's R from that c-net to the d-net.
    let lambda = catmull_clark_lambda(n);
    let a = crate::schemes::catmull_clark::local::local_matrix(n)?.matrix
        - DMatrix::identity(6 * n + 1, 6 * n + 1) * lambda;
    let ns = crate::linalg::null_space(&a, 1e-9);
    if ns.len() != 2 {
        return Err(Error::Unsupported(format!(
            "Catmull-Clark's subdominant eigenspace at valence {n} has dimension {}",
            ns.len()
        )));
    }
    let r = dense(&from_cnet(n)?).rows(1, 12 * n).into_owned();
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
