//! `qas-plus-derived`: fairsub's derivation of the QAS+ tables `K^n` and `T_n` for any valence,
//! by the guide construction of the QAS+ paper's Appendix D (which follows the earlier QAS
//! paper, not in the corpus), with the choices the text leaves open named.
//!
//! The paper prints `K^5..K^7` and `T_5..T_8`; the natural readings of its lost Fig. 29 do not
//! reproduce them (papers README). This module rebuilds the construction and tabulates it as a
//! [`QasRules`] for the existing [`super::Qas`] step code. It is a reconstruction, never the
//! published rule; [`compare::qas_comparison`] measures it against every printed number.
//!
//! # The construction
//!
//! 1. **Characteristic map.** `chi` of Section 3 for any `n` ([`chi::derived_z`]).
//! 2. **A local guide per sector.** The printed `K` tables show that a special node of sector `s`
//!    depends on the d-net only through the 21 nodes of sector `s`'s L-net (the 5 x 5 window of
//!    Fig. 28 minus the central 2 x 2), and on `q` only through sector `s`'s coefficients
//!    `q^s` ((7)); the ray nodes average that with the mirror image from sector `s + 1` ((6)).
//!    So the guide is built per sector: one bi-5 patch `g^s` over the unit square, mapped by the
//!    shear `L_s` onto the unit-edge parallelogram spanned by the sector's rays `R+` (the chart's
//!    `u` axis) and `R-` (its `v` axis, shared with sector `s - 1`).
//! 3. **Central part from `q`.** `q_1..q_6` are the corner coefficients `b500, b410, b320, b401,
//!    b311, b302` of a total-degree-5 net over the triangle `(O, R-, R+)`, `R+-` the unit ray
//!    points of `chi` (found by fitting: the scales of the linear and quadratic parts of `q` that
//!    best make the printed `K`, `T` reproduce sampled quadratics are 0.400 and 0.0999, the 2/5
//!    and 1/10 of this reading); they fix the total-degree-2 Taylor part of `g^s` at `O`.
//! 4. **Fit (open choice).** The sampled L-net of `g^s o chi^T` at the current level
//!    ([`crate::schemes::eg::derive::sampling`]) equals the input d-net's L-net of sector `s`
//!    (21 conditions); the 9 remaining coefficients minimise `F_4` over the unit square.
//! 5. **Sampling at the next level** with `g^s o (chi^T / 2)`: the own-sector estimates of the
//!    nodes 11, 22, 21, 12 give `K_11 .. K_12`; the ray nodes 31, 32 take the mean of the own
//!    estimate and the mirrored one from sector `s + 1`, which is exactly the form of (6) (half
//!    the own `q^s`, half the neighbour's mirrored `q^(s+1)`), and gives `K_31`, `K_32`.
//! 6. **`T` from `K`** by the reproduction of quadratics ([`quadratic::t_from_k`]): the guide's
//!    own `q` weights ([`LocalMaps::q`]) come within about 1e-3 of it, not exactly, because a
//!    sector's L-net samples of `Q o chi` differ slightly from its neighbours' on the shared
//!    nodes; fixing `T` by reproduction makes the derived rule map every sampled quadratic
//!    exactly (tested).
//!
//! # Valences 3 and 4
//!
//! At n = 4 QAS+ is plain bi-4 refinement, i.e. EG's [`crate::schemes::eg::EgRules::regular`]
//! with the central point `p` in the role of `c0`. That rule is not expressible in QAS+ tables:
//! through the omitted centre node it reaches the diagonal node `(-1/2, -1/2)`, outside the K
//! window. The construction below runs at n = 4 only for comparison. At n = 3 the paper keeps
//! the earlier QAS (not in the corpus); the construction runs at n = 3 as well and its
//! certificate (spectral radius of `M_d` below 1/4, measured 0.2448) is reported, but its margin
//! is thin, so EG stays the recommended rule at n = 3.

pub mod chi;
pub mod compare;
pub mod quadratic;

use super::QasRules;
use crate::error::{Error, Result};
use crate::schemes::eg::SPECIAL;
use crate::schemes::eg::derive::guide::{CENTRAL, centre_taylor, fairness_gram};
use crate::schemes::eg::derive::sampling::{
    composed_jet_matrix, jet_from_block, key_index, lnet_node_weights,
};
use crate::schemes::eg::derive::{MAX_VALENCE, constrained_min};
use nalgebra::DMatrix;
use std::f64::consts::PI;
use std::sync::OnceLock;

/// Contraction of QAS+.
pub const LAMBDA: f64 = 0.5;

/// The local maps of one sector: own-sector estimates (21 rows, in the order of
/// [`crate::schemes::eg::derive::sampling::LNET_KEYS`]) of the new
/// nodes in terms of the 21 window nodes (`nodes`, `21 x 21`) and of `q_1 .. q_6` (`q`,
/// `21 x 6`).
#[derive(Debug, Clone)]
pub struct LocalMaps {
    /// Weights of the window nodes.
    pub nodes: DMatrix<f64>,
    /// Weights of `q_1 .. q_6`.
    pub q: DMatrix<f64>,
}

/// `q_1 .. q_6` -> the total-degree-2 Taylor coefficients (`1, u, v, u^2, uv, v^2`, guide frame,
/// `u` along `R+`) of the quadratic whose degree-5 corner coefficients they are.
fn q_to_central() -> DMatrix<f64> {
    // c = q1; a_v = 5 (q2 - q1); h_vv = 10 (q3 - 2 q2 + q1); a_u = 5 (q4 - q1);
    // h_uv = 20 (q5 - q4 - q2 + q1); h_uu = 10 (q6 - 2 q4 + q1).
    let rows: [[f64; 6]; 6] = [
        [1.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [-5.0, 0.0, 0.0, 5.0, 0.0, 0.0],
        [-5.0, 5.0, 0.0, 0.0, 0.0, 0.0],
        [10.0, 0.0, 0.0, -20.0, 0.0, 10.0],
        [20.0, -20.0, 0.0, -20.0, 20.0, 0.0],
        [10.0, -20.0, 10.0, 0.0, 0.0, 0.0],
    ];
    DMatrix::from_fn(6, 6, |r, c| rows[r][c])
}

/// The local maps of valence `n` with fairness order `k`.
pub fn local_maps(n: usize, k: usize) -> Result<LocalMaps> {
    let (z, _) = chi::derived_z(n)?;
    let p = super::chi::sector_patch(n, &z);
    let alpha = 2.0 * PI / n as f64;
    // Guide frame: u along R+ = e(alpha/2), v along R- = e(-alpha/2) (chi's frame, bisectrix x).
    let (c, s) = ((alpha / 2.0).cos(), (alpha / 2.0).sin());
    // L = [[c, c], [s, -s]]; L^-1 = 1/(-2cs) [[-s, -c], [-s, c]].
    let det = -2.0 * c * s;
    let linv = [[-s / det, -c / det], [-s / det, c / det]];
    let blocks = [
        ([4, 3, 2], [0, 1, 2], false, true),
        ([4, 3, 2], [4, 3, 2], false, false),
        ([0, 1, 2], [4, 3, 2], true, false),
    ];
    let jm = |scale: f64| -> DMatrix<f64> {
        let mut m = DMatrix::zeros(27, 36);
        for (ci, (ia, ib, fu, fv)) in blocks.iter().enumerate() {
            let mut jets = [[[0.0; 3]; 3]; 2];
            for (comp, jet) in jets.iter_mut().enumerate() {
                let mut blk = [[0.0; 3]; 3];
                for x in 0..3 {
                    for y in 0..3 {
                        blk[x][y] = p[ia[x]][ib[y]][comp];
                    }
                }
                *jet = jet_from_block(&blk, *fu, *fv);
            }
            let mut x = [[0.0; 3]; 3];
            let mut y = [[0.0; 3]; 3];
            for a in 0..3 {
                for b in 0..3 {
                    x[a][b] = scale * (linv[0][0] * jets[0][a][b] + linv[0][1] * jets[1][a][b]);
                    y[a][b] = scale * (linv[1][0] * jets[0][a][b] + linv[1][1] * jets[1][a][b]);
                }
            }
            m.rows_mut(9 * ci, 9)
                .copy_from(&composed_jet_matrix(5, &x, &y));
        }
        m
    };
    let w = lnet_node_weights();
    let now = &w * jm(1.0);
    let next = &w * jm(LAMBDA);
    let mut a = DMatrix::zeros(27, 36);
    a.rows_mut(0, 21).copy_from(&now);
    for (r, &(i, j)) in CENTRAL.iter().enumerate() {
        let t = centre_taylor(i, j);
        for (col, x) in t.iter().enumerate() {
            a[(21 + r, col)] = *x;
        }
    }
    let x = constrained_min(&a, &DMatrix::identity(27, 27), &fairness_gram(5, k))?;
    let out = next * x; // 21 x 27
    Ok(LocalMaps {
        nodes: out.columns(0, 21).into_owned(),
        q: out.columns(21, 6) * q_to_central(),
    })
}

/// Converts local maps into QAS+ tables (the layout of [`QasRules`]).
pub fn tables_from_local(n: usize, m: &LocalMaps) -> QasRules {
    let idx = |key: (i32, i32)| key_index(key);
    let row_of = |h: usize, k: usize| idx((6 - 2 * k as i32, 6 - 2 * h as i32)).expect("special");
    let mut k4 = [[[0.0; 5]; 5]; 4];
    for (r, kk) in k4.iter_mut().enumerate() {
        let (h, k) = SPECIAL[r];
        let row = row_of(h, k);
        for (a, ka) in kk.iter_mut().enumerate() {
            for (b, x) in ka.iter_mut().enumerate() {
                if let Some(i) = idx((-2 + 2 * a as i32, 6 - 2 * b as i32)) {
                    *x = m.nodes[(row, i)];
                }
            }
        }
    }
    let mut k3 = [[[0.0; 4]; 5]; 2];
    for (r, kk) in k3.iter_mut().enumerate() {
        let (h, k) = SPECIAL[4 + r];
        let row = row_of(h, k);
        let w = |key: (i32, i32)| idx(key).map(|i| m.nodes[(row, i)]).unwrap_or(0.0);
        for (a, ka) in kk.iter_mut().enumerate() {
            for (b, x) in ka.iter_mut().enumerate() {
                let (u, v) = (-2 + 2 * a as i32, 2 * (3 - b as i32));
                *x = if v == 0 {
                    w((u, 0))
                } else {
                    0.5 * (w((u, v)) + w((u, -v)))
                };
            }
        }
    }
    let mut tau = [[0.0; 5]; 6];
    for (r, t) in tau.iter_mut().enumerate() {
        let (h, k) = SPECIAL[r];
        let row = row_of(h, k);
        for (c, x) in t.iter_mut().enumerate() {
            *x = m.q[(row, c + 1)];
        }
    }
    QasRules { n, tau, k4, k3 }
}

fn check_valence(n: usize) -> Result<()> {
    if !(3..=MAX_VALENCE).contains(&n) {
        return Err(Error::InvalidArgument(format!(
            "valence {n}: the QAS+ derivation covers valences 3..={MAX_VALENCE}"
        )));
    }
    Ok(())
}

/// Derives the QAS+ tables of valence `n` (3..=16) with fairness order `k` (the default
/// derivation uses 4). At n = 4 the scheme is plain bi-4 refinement (see the module docs); the
/// tables derived there are only for comparison.
pub fn derive_tables(n: usize, k: usize) -> Result<QasRules> {
    check_valence(n)?;
    quadratic::t_from_k(&tables_from_local(n, &local_maps(n, k)?))
}

/// The cached default derivation of valence `n` (3 and 5..=16, `F_4`): derived once per
/// process. Valence 4 is an error: there QAS+ is plain bi-4 refinement (module docs).
pub fn derived_rules(n: usize) -> Result<&'static QasRules> {
    check_valence(n)?;
    if n == 4 {
        return Err(Error::Unsupported(
            "QAS+ at valence 4 is plain bi-4 refinement (EG's regular rules with p as c0), which \
             QAS+ tables cannot express; derive_tables(4, k) gives the construction's tables for \
             comparison only"
                .into(),
        ));
    }
    static CACHE: [OnceLock<std::result::Result<QasRules, String>>; MAX_VALENCE + 1] =
        [const { OnceLock::new() }; MAX_VALENCE + 1];
    CACHE[n]
        .get_or_init(|| derive_tables(n, 4).map_err(|e| e.to_string()))
        .as_ref()
        .map_err(|e| Error::Unsupported(e.clone()))
}
