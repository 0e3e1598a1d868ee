//! Sampling a map's corner jets into d-net nodes: the tensor-border conversion of EG Section 4
//! (and QAS+ Appendix D), shared by both derivations.
//!
//! # The L-net of a sector (reading of the lost Figs. 7 / 8c)
//!
//! A d-net is a C^2 bi-4 spline with double knots at the integers of its level; its 12 n nodes
//! are exactly the second-order Hermite data along the boundary of the hole (the square of chart
//! radius 1 at level 0). In sector `s` the hole is the cell `H = [0, 1]^2` of the chart. Think of
//! `H` as a bi-4 patch (it is one, for the regular valence): its *L-net* is the set of its BB
//! coefficients `H[a][b]` with `a >= 2` or `b >= 2` (the tensor-borders along `u = 1` and
//! `v = 1`, 21 coefficients), and by (5)/(6) it is in one-to-one correspondence with the 21
//! d-net nodes at quarter coordinates `(u, v)`, `u, v in {-2, 0, 2, 4, 6}`, not both `<= 0`
//! (sector `s`'s 12 nodes, three of sector `s + 1`, six of sector `s - 1`).
//!
//! Sampling a map `f` (a guide composed with the characteristic map) means:
//!
//! 1. its *corner jets* at the chart points `(1, 0)`, `(1, 1)`, `(0, 1)`: the derivatives
//!    `d_u^i d_v^j f`, `i, j <= 2`, written as the 3 x 3 BB corner block of a bi-4 patch over
//!    `H` (Fig. 7; the "coordinate-wise order 3 Taylor expansion" of QAS+ Fig. 4);
//! 2. the L-net: each corner block fills its 3 x 3 corner of `H`; coefficients two blocks share
//!    (`H[a][2]`, `H[2][b]`) are averaged, `H[2][2]`, in all three blocks, is their mean;
//! 3. the inverse of (6): the 21 node values of that L-net ([`lnet_node_weights`]).
//!
//! A node that lies in the L-nets of two or three sectors gets one estimate from each; the
//! derivations say how estimates are joined (see [`Join`]). For any map that is a C^2 bi-4
//! spline on the chart (the characteristic map of Catmull-Clark in bi-4 form, the regular
//! valence) the jets are consistent and every estimate is the spline's node: sampling is exact.
//!
//! Chart positions are in quarters of the level's c-net spacing, as in [`crate::schemes::eg`].

use nalgebra::DMatrix;

/// A tensor jet of order 2 in each variable at a point: `t[i][j]` is the coefficient of
/// `du^i dv^j` (`i, j <= 2`).
pub type Jet = [[f64; 3]; 3];

/// How the estimates of a node from several sectors' L-nets are joined into one node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Join {
    /// Nodes on a sector-separating ray are the mean of the two sectors' estimates (the
    /// symmetric C^2 join across the ray); every other node is its own sector's estimate. This
    /// is the form of QAS+'s (6)/(7): ray nodes average a sector's rule and its mirror image.
    #[default]
    RayAverage,
    /// Every node is the mean of all estimates of it.
    MeanOfAll,
}

/// `(t0, t1, t2) -> (b0, b1, b2)` at the start of a unit interval (degree 4): `b0 = t0`,
/// `b1 = t0 + t1 / 4`, `b2 = t0 + t1 / 2 + t2 / 6`.
pub const FWD: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [1.0, 0.25, 0.0], [1.0, 0.5, 1.0 / 6.0]];

/// `(t0, t1, t2) -> (b4, b3, b2)` at the end of a unit interval (degree 4, `t1` the derivative
/// in the increasing direction).
pub const BWD: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [1.0, -0.25, 0.0], [1.0, -0.5, 1.0 / 6.0]];

/// Inverse of (5) on the high end of a cell: `(b2, b3, b4) -> d(1/2), d(1), d(3/2)`.
const INV_HI: [[f64; 3]; 3] = [[1.0, 0.0, 0.0], [-1.0, 2.0, 0.0], [1.0, -4.0, 4.0]];

/// Inverse of (5) on the low end of a cell: `(b0, b1, b2) -> d(-1/2), d(0), d(1/2)`.
const INV_LO: [[f64; 3]; 3] = [[4.0, -4.0, 1.0], [0.0, 2.0, -1.0], [0.0, 0.0, 1.0]];

/// (5) at a double-knot corner `x`: nodes `d(x - 1/2), d(x), d(x + 1/2)` -> `b0, b1, b2` of the
/// cell starting at `x`.
pub const NODES_TO_BB: [[f64; 3]; 3] = [[0.25, 0.5, 0.25], [0.0, 0.5, 0.5], [0.0, 0.0, 1.0]];

/// The 21 node positions of a sector's L-net (quarter units), in a fixed order.
pub const LNET_KEYS: [(i32, i32); 21] = [
    (-2, 2),
    (-2, 4),
    (-2, 6),
    (0, 2),
    (0, 4),
    (0, 6),
    (2, -2),
    (2, 0),
    (2, 2),
    (2, 4),
    (2, 6),
    (4, -2),
    (4, 0),
    (4, 2),
    (4, 4),
    (4, 6),
    (6, -2),
    (6, 0),
    (6, 2),
    (6, 4),
    (6, 6),
];

/// Position of `key` in [`LNET_KEYS`].
pub fn key_index(key: (i32, i32)) -> Option<usize> {
    LNET_KEYS.iter().position(|&k| k == key)
}

/// The corners of the jets, in the order the L-net takes them.
pub const CORNERS: [(i32, i32); 3] = [(1, 0), (1, 1), (0, 1)];

/// `m a n^T` for 3 x 3 matrices.
fn sandwich(m: &[[f64; 3]; 3], a: &Jet, nt: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut out = [[0.0; 3]; 3];
    for (i, row) in out.iter_mut().enumerate() {
        for (j, o) in row.iter_mut().enumerate() {
            let mut s = 0.0;
            for k in 0..3 {
                for l in 0..3 {
                    s += m[i][k] * a[k][l] * nt[j][l];
                }
            }
            *o = s;
        }
    }
    out
}

/// The L-net `H[a][b]` (NaN outside it) from the jets at `(1, 0)`, `(1, 1)`, `(0, 1)`.
pub fn lnet(jets: &[Jet; 3]) -> [[f64; 5]; 5] {
    let blocks = [
        (sandwich(&BWD, &jets[0], &FWD), [4, 3, 2], [0, 1, 2]),
        (sandwich(&BWD, &jets[1], &BWD), [4, 3, 2], [4, 3, 2]),
        (sandwich(&FWD, &jets[2], &BWD), [0, 1, 2], [4, 3, 2]),
    ];
    let mut sum = [[0.0; 5]; 5];
    let mut count = [[0u32; 5]; 5];
    for (b, ia, ib) in &blocks {
        for (x, &a) in ia.iter().enumerate() {
            for (y, &c) in ib.iter().enumerate() {
                sum[a][c] += b[x][y];
                count[a][c] += 1;
            }
        }
    }
    let mut h = [[f64::NAN; 5]; 5];
    for a in 0..5 {
        for b in 0..5 {
            if count[a][b] > 0 {
                h[a][b] = sum[a][b] / count[a][b] as f64;
            }
        }
    }
    h
}

/// The 21 node values of an L-net, in [`LNET_KEYS`] order (the inverse of (6) restricted to the
/// L-net, univariately `INV_HI` on indices 2..4 and `INV_LO` on 0..2).
pub fn lnet_nodes(h: &[[f64; 5]; 5]) -> [f64; 21] {
    let mut out = [0.0; 21];
    // Rows a = 2..4 (all b): u nodes 1/2, 1, 3/2.
    let mut u = [[0.0; 5]; 3];
    for (r, ur) in u.iter_mut().enumerate() {
        for (b, x) in ur.iter_mut().enumerate() {
            *x = (0..3).map(|k| INV_HI[r][k] * h[2 + k][b]).sum();
        }
    }
    for (iu, uq) in [2, 4, 6].into_iter().enumerate() {
        for (iv, vq) in [-2, 0, 2].into_iter().enumerate() {
            let x: f64 = (0..3).map(|k| INV_LO[iv][k] * u[iu][k]).sum();
            out[key_index((uq, vq)).expect("key")] = x;
        }
        for (iv, vq) in [2, 4, 6].into_iter().enumerate() {
            let x: f64 = (0..3).map(|k| INV_HI[iv][k] * u[iu][2 + k]).sum();
            out[key_index((uq, vq)).expect("key")] = x;
        }
    }
    // Columns b = 2..4, rows a = 0..2: u nodes -1/2, 0.
    let mut v = [[0.0; 3]; 5];
    for (a, vr) in v.iter_mut().enumerate() {
        for (c, x) in vr.iter_mut().enumerate() {
            *x = (0..3).map(|k| INV_HI[c][k] * h[a][2 + k]).sum();
        }
    }
    for (iu, uq) in [-2, 0].into_iter().enumerate() {
        for (iv, vq) in [2, 4, 6].into_iter().enumerate() {
            let x: f64 = (0..3).map(|k| INV_LO[iu][k] * v[k][iv]).sum();
            out[key_index((uq, vq)).expect("key")] = x;
        }
    }
    out
}

/// The linear map from the three jets (27 numbers, jet `c` entry `[i][j]` at `9 c + 3 i + j`) to
/// the 21 node estimates of the L-net: a `21 x 27` matrix.
pub fn lnet_node_weights() -> DMatrix<f64> {
    let mut w = DMatrix::zeros(21, 27);
    for k in 0..27 {
        let mut jets = [[[0.0; 3]; 3]; 3];
        jets[k / 9][(k % 9) / 3][k % 3] = 1.0;
        let nodes = lnet_nodes(&lnet(&jets));
        for (r, x) in nodes.iter().enumerate() {
            w[(r, k)] = *x;
        }
    }
    w
}

/// Product of two jets, truncated to `i, j <= 2`.
pub fn jet_mul(a: &Jet, b: &Jet) -> Jet {
    let mut out = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            if a[i][j] == 0.0 {
                continue;
            }
            for k in 0..3 - i {
                for l in 0..3 - j {
                    out[i + k][j + l] += a[i][j] * b[k][l];
                }
            }
        }
    }
    out
}

/// The Taylor jet at the start corner of a unit cell from its 3 x 3 corner BB block
/// (`block[a][b]`, `a` along u): the inverse of [`FWD`] in both variables.
pub fn jet_from_block(block: &[[f64; 3]; 3], u_forward: bool, v_forward: bool) -> Jet {
    let inv = |fwd: bool| -> [[f64; 3]; 3] {
        // FWD^-1 = [[1,0,0],[-4,4,0],[6,-12,6]]; BWD^-1 = [[1,0,0],[4,-4,0],[6,-12,6]].
        if fwd {
            [[1.0, 0.0, 0.0], [-4.0, 4.0, 0.0], [6.0, -12.0, 6.0]]
        } else {
            [[1.0, 0.0, 0.0], [4.0, -4.0, 0.0], [6.0, -12.0, 6.0]]
        }
    };
    sandwich(&inv(u_forward), block, &inv(v_forward))
}

/// Bernstein (degree `d`) to monomial coefficients: `m[p][k]` is the coefficient of `t^p` in
/// `B_k^d(t)`.
pub fn bernstein_to_monomial(d: usize) -> DMatrix<f64> {
    use crate::bezier::bern::binom;
    DMatrix::from_fn(d + 1, d + 1, |p, k| {
        if p < k {
            0.0
        } else {
            let sign = if (p - k) % 2 == 0 { 1.0 } else { -1.0 };
            binom(d, k) * binom(d - k, p - k) * sign
        }
    })
}

/// The `9 x (d + 1)^2` map from the BB coefficients of a bi-`d` polynomial `g` (index
/// `(d + 1) i + j`, `i` along u) to the jet of `g(x(s, t), y(s, t))`, where `x`, `y` are given by
/// their jets at the sampled point (constant term = the point in `g`'s domain).
pub fn composed_jet_matrix(d: usize, x: &Jet, y: &Jet) -> DMatrix<f64> {
    let m = bernstein_to_monomial(d);
    let mut one = [[0.0; 3]; 3];
    one[0][0] = 1.0;
    let mut xp = vec![one];
    let mut yp = vec![one];
    for k in 0..d {
        xp.push(jet_mul(&xp[k], x));
        yp.push(jet_mul(&yp[k], y));
    }
    // Monomial u^p v^q -> jet.
    let mut mono = DMatrix::zeros(9, (d + 1) * (d + 1));
    for p in 0..=d {
        for q in 0..=d {
            let j = jet_mul(&xp[p], &yp[q]);
            for a in 0..3 {
                for b in 0..3 {
                    mono[(3 * a + b, (d + 1) * p + q)] = j[a][b];
                }
            }
        }
    }
    // BB (i, j) -> monomial (p, q): m[p][i] m[q][j].
    let conv = DMatrix::from_fn((d + 1) * (d + 1), (d + 1) * (d + 1), |r, c| {
        m[(r / (d + 1), c / (d + 1))] * m[(r % (d + 1), c % (d + 1))]
    });
    mono * conv
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn bi4_patches_are_sampled_exactly() {
        // The jets of a bi-4 polynomial give back its L-net; its nodes reproduce the patch.
        let p = |a: usize, b: usize| (a * 7 + b * 3) as f64 * 0.1 + ((a * b) as f64).sin();
        let mut jets = [[[0.0; 3]; 3]; 3];
        let blocks = [
            ([4, 3, 2], [0, 1, 2], false, true),
            ([4, 3, 2], [4, 3, 2], false, false),
            ([0, 1, 2], [4, 3, 2], true, false),
        ];
        for (c, (ia, ib, fu, fv)) in blocks.iter().enumerate() {
            let mut blk = [[0.0; 3]; 3];
            for x in 0..3 {
                for y in 0..3 {
                    blk[x][y] = p(ia[x], ib[y]);
                }
            }
            jets[c] = jet_from_block(&blk, *fu, *fv);
        }
        let h = lnet(&jets);
        for a in 0..5 {
            for b in 0..5 {
                if a >= 2 || b >= 2 {
                    assert!((h[a][b] - p(a, b)).abs() < 1e-12, "{a} {b}");
                }
            }
        }
        let w = lnet_node_weights();
        assert_eq!(w.shape(), (21, 27));
    }
}
