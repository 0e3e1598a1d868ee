//! Local analysis of the bi-2 family: local subdivision matrices in the paper's
//! replicated-centre form, characteristic rings, and the paper's published numbers beside the
//! computed ones. (The C^1-up-to-scaling certificate of their rings is in
//! [`crate::analysis::scaled`].)
//!
//! # Local matrices
//!
//! Each matrix is read off the scheme's own stencils on its canonical local net (the same
//! tables the rings of [`super::surface`] use): PGS on the DS-net with the added point
//! `p` kept independent (rules (3), (4) with `p` an extra point; otherwise the whole-mesh rules),
//! PolBS on the polar net, TPS and adjustable TPS on the q-net (the latter with the stationary
//! knot pattern). The paper analyses the `10n x 10n`, `4n x 4n` and `7n x 7n` circulant
//! matrices "where `p/n` is replicated `n` times": [`replicate_centre`] builds that form (each
//! sector holds a copy of the centre point, every rule's weight on the centre split evenly over
//! the copies), whose Fourier blocks have exactly the printed characteristic polynomials
//! (5), (6), (13), (14), (19), (20). Its limit stencil is affine over the replicated net, so the
//! centre's weight is the sum of its copies' weights.

use super::Pgs;
use super::descriptor::{Bi2Kind, DEFAULT_E};
use super::local_scheme::{LocalScheme, pgs_rows};
use super::pgs::{PgsParams, ds_net};
use super::polar::PolarParams;
use super::surface::ring_patches;
#[cfg(doc)]
use super::ternary::AlphaRule;
use super::ternary::{TernaryRules, TpsParams};
use crate::bezier::BezierPatch;
use crate::error::{Error, Result};
use crate::schemes::Scheme;
use crate::schemes::circulant::{SparseLocal, choose};
use crate::schemes::local::{LocalMatrix, LocalOperator};
use crate::schemes::options::ids;
use crate::stencil::Stencil;
use nalgebra::DMatrix;

mod checks;

/// The replicated-centre form of a local matrix with one centre point: `n (1 + sector)`
/// points, sector `s` holding a copy of the centre first, then its own points; every copy's row
/// is the centre's row and every weight on the centre is split evenly over the `n` copies.
/// Same spectrum plus `n - 1` zeros; its Fourier blocks all have size `1 + sector`.
///
/// # Errors
/// [`Error::InvalidArgument`] when `lm.centre != 1`.
pub fn replicate_centre(lm: &LocalMatrix) -> Result<LocalMatrix> {
    if lm.centre != 1 {
        return Err(Error::InvalidArgument(format!(
            "replicate_centre needs exactly one centre point (got {})",
            lm.centre
        )));
    }
    let (n, m) = (lm.n, lm.sector);
    let k = 1 + m;
    let old = |s: usize, x: usize| if x == 0 { 0 } else { 1 + s * m + x - 1 };
    let a = &lm.matrix;
    let big = DMatrix::from_fn(n * k, n * k, |i, j| {
        let (s, x) = (i / k, i % k);
        let (r, y) = (j / k, j % k);
        let w = a[(old(s, x), old(r, y))];
        if y == 0 { w / n as f64 } else { w }
    });
    Ok(LocalMatrix {
        scheme: lm.scheme.clone(),
        n,
        centre: 0,
        sector: k,
        matrix: big,
    })
}

fn dense(rows: &[Stencil], size: usize) -> DMatrix<f64> {
    let mut m = DMatrix::zeros(rows.len(), size);
    for (r, s) in rows.iter().enumerate() {
        for &(c, w) in s.entries() {
            m[(r, c as usize)] += w;
        }
    }
    m
}

/// PGS's rows at an `n`-gon facet on `(p, DS-net)`, `p` kept as an independent point.
fn pgs_stencils(n: usize) -> Result<Vec<Stencil>> {
    let _ = PgsParams::new(n)?;
    let net = ds_net(n, |_, _| 0.0)?;
    let r = Pgs.refine(&net)?;
    let rows = pgs_rows(&net, n);
    let p = Stencil::point(9 * n);
    // Local order: p first, then the DS-net (index + 1).
    let shift = |s: &Stencil| {
        Stencil::from_pairs(s.entries().iter().map(|&(i, w)| {
            let i = i as usize;
            (if i == 9 * n { 0 } else { i + 1 }, w)
        }))
    };
    let mut out = vec![shift(&Pgs::centre_update(&net, 0, &p))];
    let h0 = net.face_halfedge(0) as usize;
    for &row in &rows {
        let st = if (h0..h0 + n).contains(&row) {
            Pgs::corner_stencil_with_centre(&net, row as u32, &p)
        } else {
            r.stencils.stencil(row)
        };
        out.push(shift(&st));
    }
    Ok(out)
}

/// PGS at an `n`-gon facet: the `10n x 10n` replicated matrix on `(p, a, b, c, d, 5 .. 9)` per
/// sector, `p` kept as an independent point.
pub fn pgs(n: usize) -> Result<LocalMatrix> {
    let out = pgs_stencils(n)?;
    let lm = LocalMatrix {
        scheme: ids::PGS.name().into(),
        n,
        centre: 1,
        sector: 9,
        matrix: dense(&out, 1 + 9 * n),
    };
    replicate_centre(&lm)
}

fn local_stencils(ls: &LocalScheme) -> Vec<Stencil> {
    let t = ls.step(1);
    (0..t.num_rows()).map(|r| t.stencil(r)).collect()
}

fn from_local(name: &str, ls: &LocalScheme, sector: usize) -> Result<LocalMatrix> {
    let rows = local_stencils(ls);
    let lm = LocalMatrix {
        scheme: name.into(),
        n: ls.n,
        centre: 1,
        sector,
        matrix: dense(&rows, ls.size),
    };
    replicate_centre(&lm)
}

/// The sparse rows of a member of the family at valence `n` (before the centre's
/// replication, which they ask for), for its Fourier blocks at large valences.
pub fn sparse_rules(scheme: Bi2Kind, n: usize, adj: TernaryRules) -> Result<SparseLocal> {
    let (rows, sector) = if scheme == Bi2Kind::Pgs {
        (pgs_stencils(n)?, 9)
    } else {
        let (ls, sector) = local_scheme(scheme, n, adj)?;
        (local_stencils(&ls), sector)
    };
    Ok(SparseLocal {
        scheme: match scheme {
            Bi2Kind::Pgs => ids::PGS,
            Bi2Kind::Polar => ids::POLAR_BI2,
            Bi2Kind::Tps => ids::TPS,
            _ => ids::TPS_ADJUSTABLE,
        }
        .name()
        .into(),
        n,
        centre: 1,
        sector,
        rows: rows
            .iter()
            .map(|s| s.entries().iter().map(|&(i, w)| (i as usize, w)).collect())
            .collect(),
        replicate: true,
    })
}

/// The local matrix of a member of the family as the analysis decomposes it: dense within
/// [`crate::linalg::MAX_DENSE_EIGEN_ROWS`] rows, its Fourier blocks above.
pub fn operator_rules(
    scheme: Bi2Kind,
    n: usize,
    adj: TernaryRules,
) -> Result<Box<dyn LocalOperator>> {
    choose(&sparse_rules(scheme, n, adj)?, false, || {
        local_matrix_rules(scheme, n, adj)
    })
}

/// PolBS at a pole of valence `n`: the `4n x 4n` replicated matrix on `(p, a, b, c)`.
pub fn polar(n: usize) -> Result<LocalMatrix> {
    let _ = PolarParams::new(n)?;
    from_local(ids::POLAR_BI2.name(), &LocalScheme::polar(n)?, 3)
}

/// TPS at a vertex of valence `n`: the `7n x 7n` replicated matrix on `(q, a, .., f)`.
pub fn tps(n: usize) -> Result<LocalMatrix> {
    let _ = TpsParams::new(n)?;
    from_local(
        ids::TPS.name(),
        &LocalScheme::ternary(n, TernaryRules::TPS)?,
        6,
    )
}

/// Adjustable TPS with split ratio `e` at valence `n`: the stationary `7n x 7n` replicated
/// matrix (knot pattern `1, r, r^2`).
pub fn tps_adjustable(n: usize, e: f64) -> Result<LocalMatrix> {
    tps_adjustable_rules(n, TernaryRules::adjustable(e)?)
}

/// [`tps_adjustable`] with the given rules (split ratio and [`AlphaRule`]).
pub fn tps_adjustable_rules(n: usize, rules: TernaryRules) -> Result<LocalMatrix> {
    let _ = TpsParams::new(n)?;
    from_local(
        ids::TPS_ADJUSTABLE.name(),
        &LocalScheme::ternary(n, rules)?,
        6,
    )
}

/// The rules of adjustable TPS for a split ratio (the paper's [`AlphaRule`]); TPS's for the
/// other schemes, which ignore them.
fn rules_for(scheme: Bi2Kind, e: f64) -> Result<TernaryRules> {
    if scheme == Bi2Kind::TpsAdjustable {
        TernaryRules::adjustable(e)
    } else {
        Ok(TernaryRules::TPS)
    }
}

/// The local scheme and local-net size of a member of the family (`adj`: the rules of
/// adjustable TPS).
fn local_scheme(scheme: Bi2Kind, n: usize, adj: TernaryRules) -> Result<(LocalScheme, usize)> {
    match scheme {
        Bi2Kind::Pgs => Ok((LocalScheme::pgs(n)?, 9)),
        Bi2Kind::Polar => Ok((LocalScheme::polar(n)?, 3)),
        Bi2Kind::Tps => Ok((LocalScheme::ternary(n, TernaryRules::TPS)?, 6)),
        Bi2Kind::TpsAdjustable => Ok((LocalScheme::ternary(n, adj)?, 6)),
        other => Err(no_analysis(other)),
    }
}

/// The error for a member without local analysis (the preprocessed and mixed schemes).
fn no_analysis(kind: Bi2Kind) -> Error {
    Error::InvalidArgument(format!("no bi-2 analysis for {kind:?}"))
}

/// The local matrix of a bi-2 scheme (adjustable TPS with `e = 0.2`).
pub fn local_matrix(scheme: Bi2Kind, n: usize) -> Result<LocalMatrix> {
    local_matrix_with(scheme, n, DEFAULT_E)
}

/// [`local_matrix`] with the split ratio `e` of adjustable TPS (ignored by the others).
pub fn local_matrix_with(scheme: Bi2Kind, n: usize, e: f64) -> Result<LocalMatrix> {
    local_matrix_rules(scheme, n, rules_for(scheme, e)?)
}

/// [`local_matrix`] with the rules `adj` of adjustable TPS (ignored by the others).
pub fn local_matrix_rules(scheme: Bi2Kind, n: usize, adj: TernaryRules) -> Result<LocalMatrix> {
    match scheme {
        Bi2Kind::Pgs => pgs(n),
        Bi2Kind::Polar => polar(n),
        Bi2Kind::Tps => tps(n),
        Bi2Kind::TpsAdjustable => tps_adjustable_rules(n, adj),
        other => Err(no_analysis(other)),
    }
}

/// The characteristic ring of a bi-2 scheme: the ring patches of its local net (PGS: the `3n`
/// patches of `b, c, d`; TPS: the `2n` of `a, b`, adjustable TPS in its stationary knot
/// pattern; PolBS: the `n` of `b`) built from the characteristic map's control points, and
/// lambda.
pub fn characteristic_ring(scheme: Bi2Kind, n: usize) -> Result<(Vec<BezierPatch>, f64)> {
    characteristic_ring_with(scheme, n, DEFAULT_E)
}

/// [`characteristic_ring`] with the split ratio `e` of adjustable TPS.
pub fn characteristic_ring_with(
    scheme: Bi2Kind,
    n: usize,
    e: f64,
) -> Result<(Vec<BezierPatch>, f64)> {
    characteristic_ring_rules(scheme, n, rules_for(scheme, e)?)
}

/// [`characteristic_ring`] with the rules `adj` of adjustable TPS.
pub fn characteristic_ring_rules(
    scheme: Bi2Kind,
    n: usize,
    adj: TernaryRules,
) -> Result<(Vec<BezierPatch>, f64)> {
    let lm = operator_rules(scheme, n, adj)?;
    let (ls, per) = local_scheme(scheme, n, adj)?;
    let (pts, lambda) = lm.characteristic_points()?;
    // Replicated layout (s, 0) copy, (s, 1 + x) point x of sector s; the local nets have the
    // centre first (TPS, PolBS) or no centre (PGS).
    let centre = usize::from(scheme != Bi2Kind::Pgs);
    let mut local = vec![[0.0; 3]; ls.size];
    for s in 0..n {
        for x in 0..per {
            local[centre + s * per + x] = pts[s * (per + 1) + 1 + x];
        }
    }
    let level = if scheme == Bi2Kind::TpsAdjustable {
        2
    } else {
        0
    };
    Ok((ring_patches(&ls, level, &local), lambda))
}

/// A published number beside the computed one (the paper's value is 0 for polynomial
/// identities, whose difference is reported).
pub use crate::schemes::descriptor::Published as PublishedCheck;

/// The paper's numbers for a bi-2 scheme at valence `n` beside the ones computed from its
/// stencils: characteristic polynomials (as the largest coefficient difference over the
/// Fourier blocks), subdominant and subsubdominant eigenvalues, limit-point weights.
///
/// # Errors
/// For a scheme name that is not of the bi-2 family, or an invalid valence.
pub fn published(scheme: Bi2Kind, n: usize) -> Result<Vec<PublishedCheck>> {
    published_with(scheme, n, DEFAULT_E)
}

/// [`published`] with the split ratio `e` of adjustable TPS.
pub fn published_with(scheme: Bi2Kind, n: usize, e: f64) -> Result<Vec<PublishedCheck>> {
    published_rules(scheme, n, rules_for(scheme, e)?)
}

/// [`published`] with the rules `adj` of adjustable TPS. With
/// [`AlphaRule::RegularSpectrum`] the stationary limit functional is not (21) (only the limit
/// point from an input net is), so those checks are left out.
pub fn published_rules(
    scheme: Bi2Kind,
    n: usize,
    adj: TernaryRules,
) -> Result<Vec<PublishedCheck>> {
    let lm = operator_rules(scheme, n, adj)?;
    let spec = lm.spectrum();
    let blocks = lm.fourier_blocks()?;
    let limit = lm.limit_stencil()?;
    let k = lm.sector();
    // Affine weights of the centre (sum of its copies) and of one first-ring point.
    let centre_weight: f64 = (0..n).map(|s| limit[s * k]).sum();
    let found = checks::Computed {
        n,
        spec,
        blocks,
        limit,
        k,
        centre_weight,
    };
    match scheme {
        Bi2Kind::Pgs => checks::pgs_checks(&found),
        Bi2Kind::Polar => checks::polar_checks(&found),
        Bi2Kind::Tps => checks::tps_checks(&found),
        Bi2Kind::TpsAdjustable => checks::adjustable_checks(&found, adj),
        other => Err(no_analysis(other)),
    }
}
