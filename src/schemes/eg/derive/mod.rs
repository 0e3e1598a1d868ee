//! `eg-derived`: fairsub's derivation of the EG special rules for any valence, from the
//! construction of the EG paper's Section 4, with the choices the text leaves open named.
//!
//! The paper tabulates complete rules only for n = 3 and 5; the Appendix lost all but one row
//! per array for n = 6..10 (papers README). Section 4 describes how the rules were obtained; the
//! step that fixes the guide's free coefficients is in \[KP18, Appendix\], outside the corpus. This
//! module rebuilds the whole construction and tabulates the result as an [`EgRules`], so that
//! [`super::Eg::with_rules`] runs it with the scheme's own step and ring code. The derived rules
//! are a reconstruction: they are never presented as the published ones, and
//! [`compare::eg_comparison`] measures them against every printed number.
//!
//! # The construction (Section 4, step by step)
//!
//! 1. **Characteristic map.** `chi` is Catmull-Clark's characteristic map in d-net form,
//!    `chi^T = L^-1 o chi` per sector, normalised so that the ray corner of the hole maps to
//!    `(1, 0)` of the guide's unit square ([`cc_chi`]).
//! 2. **Guide space.** `n` bi-5 sectors, `G^1` through the shear `L`, with a unique quadratic
//!    expansion at the centre ([`guide`]). It contains `L` (hence lambda is Catmull-Clark's
//!    exactly, as the paper observes of its rules) and every polynomial `Q o L`.
//! 3. **Sampling.** A guide is sampled at the current level by the corner jets of `g o chi^T` at
//!    the three corners of every sector's hole cell, assembled into L-nets and converted to
//!    nodes by the inverse of (6) ([`sampling`]); at the next level by the same with
//!    `g o lambda chi^T` (the new d-net at half the spacing).
//! 4. **Fit (open choice, [`Fit`]).** The guide is an affine combination of `d` and `c0`:
//!    `g(0) = c0` and the guide's sampled tensor-borders reproduce the input d-net; the
//!    coefficients this leaves free minimise the fairness functional `F_k` (`k = 4` by default,
//!    the order QAS+ Section 3 found most uniform) summed over the sectors' unit squares.
//! 5. **Conversion (open choice, [`Join`]).** The sampled new nodes: on a sector-separating ray
//!    the mean of the two sectors' samples (the symmetric C^2 join of Fig. 8c), elsewhere the
//!    sector's own sample. The six inner nodes per sector are the special rules; the outer ones
//!    are replaced by regular refinement, as the paper prescribes.
//!
//! Valence 4 is plain bi-4 refinement ([`EgRules::regular`]); the derivation is not used there.
//! Everything is linear, so the derived rules are exact affine combinations; they satisfy the
//! structural symmetries of Section 5 by construction (tested).
//!
//! # Explored and kept
//!
//! Both fits, both joins, fairness orders 2..5 measured in the plane or on the unit square, and a
//! fairness integrated over the image of the cap were tried against the printed n = 3, 5 tables
//! (see the crate's report `examples/derived_rules.rs`); the kept defaults
//! ([`EgDeriveOptions::default`]) come closest. None reproduces the printed weights to
//! truncation: the guide's free coefficients are fixed differently in \[KP18\].

pub mod cc_chi;
pub mod compare;
pub mod guide;
pub mod sampling;

pub use sampling::Join;

use super::{EgRules, SPECIAL, dnet_index, dnet_node};
use crate::error::{Error, Result};
use nalgebra::{DMatrix, DVector};
use sampling::{LNET_KEYS, composed_jet_matrix, lnet_node_weights};
use std::sync::OnceLock;

/// Largest valence the derivation is run and certified for.
pub const MAX_VALENCE: usize = 16;

/// Which sampled data the guide must reproduce (step 4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Fit {
    /// Every sector's sampled L-net equals the input d-net's L-net of that sector: all 21
    /// estimates per sector are interpolated (the "exact corner-jet interpolation of the d-net's
    /// L-net"). The guide's sampled tensor-border is then C^2 by itself.
    #[default]
    AllEstimates,
    /// The joined sample (the same [`Join`] as the output) equals the input d-net: the guide
    /// reproduces the d-net under exactly the map that produces the new d-net.
    JoinedNodes,
}

/// The open choices of the construction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EgDeriveOptions {
    /// What the guide reproduces.
    pub fit: Fit,
    /// How samples of several sectors are joined into nodes.
    pub join: Join,
    /// Order `k` of the fairness functional `F_k`.
    pub fairness: usize,
    /// Measure `F_k` in the plane (derivatives and area through `L`) instead of on each
    /// sector's unit square.
    pub plane: bool,
}

impl Default for EgDeriveOptions {
    fn default() -> Self {
        EgDeriveOptions {
            fit: Fit::AllEstimates,
            join: Join::RayAverage,
            fairness: 4,
            plane: false,
        }
    }
}

fn check_valence(n: usize) -> Result<()> {
    if !(3..=MAX_VALENCE).contains(&n) {
        return Err(Error::InvalidArgument(format!(
            "valence {n}: the EG derivation covers valences 3..={MAX_VALENCE}"
        )));
    }
    Ok(())
}

/// Sampling rows: for every sector and L-net key, the `36 n` row of the sampled node estimate
/// and the `(c0, d-net)` source index of the node it estimates.
fn sampled_rows(
    n: usize,
    jm: &DMatrix<f64>,
    w: &DMatrix<f64>,
) -> Vec<(usize, usize, DVector<f64>)> {
    let per = w * jm; // 21 x 36
    let mut out = Vec::with_capacity(21 * n);
    for s in 0..n {
        for (k, &(u, v)) in LNET_KEYS.iter().enumerate() {
            let src = dnet_node(n, s, u, v).expect("L-net keys are d-net nodes");
            let mut row = DVector::zeros(36 * n);
            row.rows_mut(36 * s, 36).copy_from(&per.row(k).transpose());
            out.push((s, src, row));
        }
    }
    out
}

/// The joined node rows (`12 n` of them, by source index) from the estimates.
fn joined(n: usize, est: &[(usize, usize, DVector<f64>)], join: Join) -> Vec<DVector<f64>> {
    let mut groups: Vec<Vec<(usize, &DVector<f64>)>> = vec![Vec::new(); 12 * n + 1];
    for (s, src, row) in est {
        groups[*src].push((*s, row));
    }
    (1..=12 * n)
        .map(|src| {
            let g = &groups[src];
            let owner = (src - 1) / 12;
            let on_ray = (src - 1) % 4 == 3; // i = 3: the nodes on the line v = 0
            let pick: Vec<&DVector<f64>> = match join {
                Join::MeanOfAll => g.iter().map(|x| x.1).collect(),
                Join::RayAverage if on_ray => g.iter().map(|x| x.1).collect(),
                Join::RayAverage => g.iter().filter(|x| x.0 == owner).map(|x| x.1).collect(),
            };
            let mut r = DVector::zeros(36 * n);
            for p in &pick {
                r += *p;
            }
            r / pick.len().max(1) as f64
        })
        .collect()
}

/// Derives the EG special rules of valence `n` (3..=16; 4 gives [`EgRules::regular`]) with the
/// given choices. Costs a few dense SVDs of size `36 n`; use [`derived_rules`] for the cached
/// default.
pub fn derive_rules(n: usize, opts: &EgDeriveOptions) -> Result<EgRules> {
    check_valence(n)?;
    if n == 4 {
        return Ok(EgRules::regular());
    }
    let (jets, lambda) = cc_chi::cc_chi_jets(n)?;
    let w = lnet_node_weights();
    let jm = |scale: f64| -> DMatrix<f64> {
        let mut m = DMatrix::zeros(27, 36);
        for (c, j) in jets.iter().enumerate() {
            let x = j[0].map(|r| r.map(|v| v * scale));
            let y = j[1].map(|r| r.map(|v| v * scale));
            m.rows_mut(9 * c, 9)
                .copy_from(&composed_jet_matrix(5, &x, &y));
        }
        m
    };
    let now = sampled_rows(n, &jm(1.0), &w);
    let next = joined(n, &sampled_rows(n, &jm(lambda), &w), opts.join);
    // Interpolation conditions: rows over 36 n, selector into the (c0, d) sources.
    let mut cond: Vec<(DVector<f64>, usize)> = match opts.fit {
        Fit::AllEstimates => now.iter().map(|(_, src, r)| (r.clone(), *src)).collect(),
        Fit::JoinedNodes => joined(n, &now, opts.join)
            .into_iter()
            .enumerate()
            .map(|(k, r)| (r, k + 1))
            .collect(),
    };
    let mut centre = DVector::zeros(36 * n);
    centre[0] = 1.0;
    cond.push((centre, 0));
    let nb = null_basis(&guide::constraints(n))?;
    let a = DMatrix::from_fn(cond.len(), 36 * n, |r, c| cond[r].0[c]) * &nb;
    let sel = DMatrix::from_fn(cond.len(), 12 * n + 1, |r, c| {
        if cond[r].1 == c { 1.0 } else { 0.0 }
    });
    let fg = if opts.plane {
        plane_gram(n, opts.fairness)
    } else {
        guide::fairness_gram(5, opts.fairness)
    };
    // H = N^T (I_n (x) F) N, block by block.
    let mut h = DMatrix::zeros(nb.ncols(), nb.ncols());
    for s in 0..n {
        let blk = nb.rows(36 * s, 36);
        h += blk.transpose() * (&fg * blk);
    }
    let x = constrained_min(&a, &sel, &h)?;
    let g = nb * x; // 36 n x (12 n + 1)
    let mut weights: [Vec<[f64; 12]>; 6] = Default::default();
    let mut a0 = [0.0; 6];
    for (k, &(h, kk)) in SPECIAL.iter().enumerate() {
        let row = next[dnet_index(0, h, kk) - 1].transpose() * &g; // 1 x (12 n + 1)
        a0[k] = row[0];
        weights[k] = (0..n)
            .map(|r| std::array::from_fn(|e| row[1 + 12 * r + e]))
            .collect();
    }
    Ok(EgRules { n, weights, a0 })
}

/// `F_k` in the plane: derivatives along the plane's axes of `g o L^-1`, area of the
/// parallelogram (sector 0's shear; the same for every sector up to a rotation, under which
/// `F_k` is invariant).
fn plane_gram(n: usize, k: usize) -> DMatrix<f64> {
    use crate::bezier::bern::{bernstein_derivs, binom, gauss_legendre};
    let l = guide::shear(n, 0);
    // (u, v) = L^-1 (x, y): d/dx = a d/du + b d/dv with [a b] the first column of L^-T.
    let det = l[0][0] * l[1][1] - l[1][0] * l[0][1];
    let inv = [
        [l[1][1] / det, -l[1][0] / det],
        [-l[0][1] / det, l[0][0] / det],
    ];
    let (dxu, dxv, dyu, dyv) = (inv[0][0], inv[1][0], inv[0][1], inv[1][1]);
    let gl = gauss_legendre(7);
    let mut gram = DMatrix::zeros(36, 36);
    for &(x, wx) in &gl {
        for &(y, wy) in &gl {
            let der: Vec<Vec<f64>> = (0..=k)
                .map(|a| {
                    let bu = bernstein_derivs(5, a, x);
                    let bv = bernstein_derivs(5, k - a, y);
                    (0..36).map(|r| bu[r / 6] * bv[r % 6]).collect()
                })
                .collect();
            for i in 0..=k {
                // (dxu du + dxv dv)^i (dyu du + dyv dv)^(k - i) as sum_a coef_a du^a dv^(k-a).
                let mut poly = vec![1.0];
                for _ in 0..i {
                    poly = mul_lin(&poly, dxu, dxv);
                }
                for _ in i..k {
                    poly = mul_lin(&poly, dyu, dyv);
                }
                let v: Vec<f64> = (0..36)
                    .map(|r| (0..=k).map(|a| poly[a] * der[a][r]).sum())
                    .collect();
                let f = binom(k, i) * wx * wy * det.abs();
                for r in 0..36 {
                    for c in 0..36 {
                        gram[(r, c)] += f * v[r] * v[c];
                    }
                }
            }
        }
    }
    gram
}

/// `poly(du, dv) * (p du + q dv)` with `poly[a]` the coefficient of `du^a dv^(deg - a)`.
fn mul_lin(poly: &[f64], p: f64, q: f64) -> Vec<f64> {
    let mut out = vec![0.0; poly.len() + 1];
    for (a, &c) in poly.iter().enumerate() {
        out[a + 1] += c * p;
        out[a] += c * q;
    }
    out
}

/// Full SVD by `faer`: `(U, singular values, V)` with `U` `r x r`, `V` `c x c`.
fn svd_full(a: &DMatrix<f64>) -> Result<(DMatrix<f64>, Vec<f64>, DMatrix<f64>)> {
    let (r, c) = a.shape();
    let f = faer::Mat::<f64>::from_fn(r, c, |i, j| a[(i, j)]);
    let svd = f
        .svd()
        .map_err(|e| Error::Unsupported(format!("SVD did not converge: {e:?}")))?;
    let (u, s, v) = (svd.U(), svd.S().column_vector(), svd.V());
    let um = DMatrix::from_fn(r, r, |i, j| u[(i, j)]);
    let vm = DMatrix::from_fn(c, c, |i, j| v[(i, j)]);
    let sv = (0..r.min(c)).map(|i| s[i]).collect();
    Ok((um, sv, vm))
}

/// Orthonormal basis (columns) of the null space of `a`: singular values below `1e-9` of the
/// largest.
pub(crate) fn null_basis(a: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    let (_, sv, v) = svd_full(a)?;
    let smax = sv.iter().copied().fold(0.0, f64::max).max(1e-300);
    let rank = sv.iter().filter(|&&x| x > 1e-9 * smax).count();
    Ok(v.columns(rank, a.ncols() - rank).into_owned())
}

/// `argmin x^T H x` subject to `A x = S b` (in the least-squares sense when `A` is rank
/// deficient), as the matrix `X` with `x = X b`: the minimum-norm least-squares solution plus the
/// `H`-optimal correction in the null space of `A`.
pub(crate) fn constrained_min(
    a: &DMatrix<f64>,
    sel: &DMatrix<f64>,
    h: &DMatrix<f64>,
) -> Result<DMatrix<f64>> {
    let (u, sv, v) = svd_full(a)?;
    let c = a.ncols();
    let smax = sv.iter().copied().fold(0.0, f64::max).max(1e-300);
    let rank = sv.iter().filter(|&&x| x > 1e-9 * smax).count();
    // x0 = V_r S_r^-1 U_r^T sel.
    let mut coef = u.columns(0, rank).transpose() * sel;
    for (i, mut row) in coef.row_iter_mut().enumerate() {
        row /= sv[i];
    }
    let x0 = v.columns(0, rank) * coef;
    if rank == c {
        return Ok(x0);
    }
    let z = v.columns(rank, c - rank).into_owned();
    let zh = z.transpose() * h;
    let zhz = &zh * &z;
    let rhs = -(zh * &x0);
    let y = zhz
        .clone()
        .cholesky()
        .map(|ch| ch.solve(&rhs))
        .or_else(|| zhz.lu().solve(&rhs))
        .ok_or_else(|| {
            Error::Unsupported(
                "the fairness functional is singular on the free guide coefficients".into(),
            )
        })?;
    Ok(x0 + z * y)
}

/// The cached default derivation of valence `n` (3..=16): derived once per process.
pub fn derived_rules(n: usize) -> Result<&'static EgRules> {
    check_valence(n)?;
    static CACHE: [OnceLock<std::result::Result<EgRules, String>>; MAX_VALENCE + 1] =
        [const { OnceLock::new() }; MAX_VALENCE + 1];
    CACHE[n]
        .get_or_init(|| derive_rules(n, &EgDeriveOptions::default()).map_err(|e| e.to_string()))
        .as_ref()
        .map_err(|e| Error::Unsupported(e.clone()))
}
