//! QAS+'s local analysis: the subdivision matrices of QAS+^4 and QAS+^3 on `(p, d-net, q)`,
//! the facts of Section 5 (`M_d`, `M_q`) and the characteristic maps, of the printed tables or
//! of any given ones (the derived tables).

use super::Qas;
use super::bi3::QasBi3;
use crate::bezier::BezierPatch;
use crate::error::Result;
use crate::schemes::eg::local::dnet_ring_patches;
use crate::schemes::local::{LocalMatrix, check_valence, dense};
use crate::schemes::options::ids;
use crate::stencil::StencilTable;
use nalgebra::DMatrix;

/// QAS+^4's matrix on the local vector `(p, d-net, q)` reordered sector by sector: centre `p`,
/// then per sector its 12 d-net nodes and its 5 expansion coefficients `q_2 .. q_6` (17 points),
/// so that the Fourier blocks apply. `lambda` is the contraction of `S` (1/2 for QAS+).
pub fn local_matrix(n: usize, lambda: f64) -> Result<LocalMatrix> {
    check_valence(n)?;
    local_matrix_of(&Qas::new(n)?, lambda, ids::QAS_PLUS.name())
}

/// QAS+^4's matrix of given tables, labelled `label`.
pub fn local_matrix_of(qas: &Qas, lambda: f64, label: &str) -> Result<LocalMatrix> {
    qas_from_step(qas.n(), qas.step(lambda)?.step, label)
}

/// QAS+^3's matrix (bi-3 d-net through `T_3^4`), ordered like [`local_matrix`].
pub fn local_matrix_bi3(n: usize, lambda: f64) -> Result<LocalMatrix> {
    check_valence(n)?;
    local_matrix_bi3_of(&Qas::new(n)?, lambda, ids::QAS_PLUS_BI3.name())
}

/// QAS+^3's matrix of given QAS+^4 tables, labelled `label`.
pub fn local_matrix_bi3_of(qas: &Qas, lambda: f64, label: &str) -> Result<LocalMatrix> {
    qas_from_step(
        qas.n(),
        QasBi3::with_qas(qas.clone()).step(lambda)?.step,
        label,
    )
}

fn qas_from_step(n: usize, st: StencilTable, name: &str) -> Result<LocalMatrix> {
    use crate::schemes::qas::{num_sources, q_index};
    let m = num_sources(n);
    let perm: Vec<usize> = std::iter::once(0)
        .chain((0..n).flat_map(|s| {
            (0..12)
                .map(move |e| 1 + 12 * s + e)
                .chain((2..=6).map(move |k| q_index(n, s, k)))
        }))
        .collect();
    let a = dense(&st);
    let b = DMatrix::from_fn(m, m, |i, j| a[(perm[i], perm[j])]);
    Ok(LocalMatrix {
        scheme: name.into(),
        n,
        centre: 1,
        sector: 17,
        matrix: b,
    })
}

/// Facts of QAS+ beyond the spectrum of the whole matrix: the spectral radius of `M_d` (the
/// d-net block, independent of `q`) and the eigenvalues of `M_q` restricted to each kind of
/// quadratic expansion (C^2: 6 coordinates, C^1: `3 + n`, C^1-C^0: `3 + 2n`).
#[derive(Debug, Clone, serde::Serialize)]
pub struct QasFacts {
    /// Largest modulus of the eigenvalues of `M_d`.
    pub m_d_spectral_radius: f64,
    /// Eigenvalues (real parts, sorted decreasing) of `M_q` on C^2 expansions.
    pub m_q_c2: Vec<f64>,
    /// Eigenvalues of `M_q` on C^1 expansions.
    pub m_q_c1: Vec<f64>,
    /// Eigenvalues of `M_q` on C^1-C^0 expansions.
    pub m_q_c1c0: Vec<f64>,
    /// Largest residual of the invariance of each kind's subspace under `M_q` (0 = invariant).
    pub invariance_defect: f64,
}

/// Computes [`QasFacts`] of the printed tables at valence `n` with contraction `lambda`.
pub fn facts(n: usize, lambda: f64) -> Result<QasFacts> {
    facts_of(&Qas::new(n)?, lambda)
}

/// [`QasFacts`] of given tables.
pub fn facts_of(qas: &Qas, lambda: f64) -> Result<QasFacts> {
    qas_facts_of(qas.n(), qas.step(lambda)?.step)
}

/// [`QasFacts`] of QAS+^3 (printed tables).
pub fn facts_bi3(n: usize, lambda: f64) -> Result<QasFacts> {
    facts_bi3_of(&Qas::new(n)?, lambda)
}

/// [`QasFacts`] of QAS+^3 on given QAS+^4 tables.
pub fn facts_bi3_of(qas: &Qas, lambda: f64) -> Result<QasFacts> {
    qas_facts_of(qas.n(), QasBi3::with_qas(qas.clone()).step(lambda)?.step)
}

fn qas_facts_of(n: usize, st: StencilTable) -> Result<QasFacts> {
    use crate::schemes::qas::{num_sources, q_index, quadratic_bb};
    let m = num_sources(n);
    let a = dense(&st);
    let nd = 12 * n;
    let md = a.view((1, 1), (nd, nd)).into_owned();
    let rho = crate::linalg::eigenvalues(&md)
        .iter()
        .map(|z| z.norm())
        .fold(0.0, f64::max);
    // q-space: coordinates p (source 0) and all q_k^s.
    let qsrc: Vec<usize> = std::iter::once(0)
        .chain((0..n).flat_map(|s| (2..=6).map(move |k| q_index(n, s, k))))
        .collect();
    let mq = DMatrix::from_fn(qsrc.len(), qsrc.len(), |i, j| a[(qsrc[i], qsrc[j])]);
    let c = (2.0 * std::f64::consts::PI / n as f64).cos();
    let col = |p: f64, f: &dyn Fn(usize, usize) -> f64| -> Vec<f64> {
        let mut v = vec![p];
        for s in 0..n {
            for k in 2..=6 {
                v.push(f(s, k));
            }
        }
        v
    };
    let poly = |p: f64, lin: [f64; 2], quad: [f64; 3]| {
        col(p, &|s, k| quadratic_bb(n, s, p, lin, quad)[k - 1])
    };
    let mut c2 = vec![
        poly(1.0, [0.0; 2], [0.0; 3]),
        poly(0.0, [1.0, 0.0], [0.0; 3]),
        poly(0.0, [0.0, 1.0], [0.0; 3]),
    ];
    let mut c1 = c2.clone();
    let mut c1c0 = c2.clone();
    for quad in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
        c2.push(poly(0.0, [0.0; 2], quad));
    }
    for t in 0..n {
        // C^1: q_5^t = 1; q_6^s = q_3^(s+1) = (q_5^s + q_5^(s+1)) / (2c).
        c1.push(col(0.0, &|s, k| match k {
            5 if s == t => 1.0,
            6 if s == t || (s + 1) % n == t => 0.5 / c,
            3 if s == t || s == (t + 1) % n => 0.5 / c,
            _ => 0.0,
        }));
        // C^1-C^0: q_3^t free (and q_6^(t-1) = q_3^t), q_5^t free.
        c1c0.push(col(0.0, &|s, k| match k {
            3 if s == t => 1.0,
            6 if (s + 1) % n == t => 1.0,
            _ => 0.0,
        }));
        c1c0.push(col(0.0, &|s, k| if k == 5 && s == t { 1.0 } else { 0.0 }));
    }
    let mut defect: f64 = 0.0;
    let mut restricted = |cols: &[Vec<f64>]| -> Vec<f64> {
        let b = DMatrix::from_fn(qsrc.len(), cols.len(), |i, j| cols[j][i]);
        let mb = &mq * &b;
        let pinv = b.clone().pseudo_inverse(1e-12).expect("pseudo-inverse");
        let r = &pinv * &mb;
        defect = defect.max((&b * &r - &mb).abs().max());
        let mut ev: Vec<f64> = crate::linalg::eigenvalues(&r)
            .iter()
            .map(|z| z.re)
            .collect();
        ev.sort_by(|x, y| y.total_cmp(x));
        ev
    };
    let m_q_c2 = restricted(&c2);
    let m_q_c1 = restricted(&c1);
    let m_q_c1c0 = restricted(&c1c0);
    let _ = m;
    Ok(QasFacts {
        m_d_spectral_radius: rho,
        m_q_c2,
        m_q_c1,
        m_q_c1c0,
        invariance_defect: defect,
    })
}

/// The characteristic map of Section 3 (`chi`, valences 5..10) as a ring of bi-4 patches, with
/// its contraction 1/2.
pub fn characteristic_ring(n: usize) -> Result<(Vec<BezierPatch>, f64)> {
    Ok((super::chi::chi_ring(n)?.0, 0.5))
}

/// The characteristic map of the QAS+^4 rules (eigenvectors of the subdivision matrix) as a
/// ring of bi-4 patches, with its contraction 1/2; compared with [`characteristic_ring`] by the
/// tests.
pub fn rules_characteristic_ring(n: usize) -> Result<(Vec<BezierPatch>, f64)> {
    rules_characteristic_ring_of(&Qas::new(n)?)
}

/// The characteristic map of given QAS+^4 tables as a ring of bi-4 patches, with its
/// contraction 1/2.
pub fn rules_characteristic_ring_of(qas: &Qas) -> Result<(Vec<BezierPatch>, f64)> {
    let [cx, cy] = qas.characteristic_vectors()?;
    let pts: Vec<_> = cx.iter().zip(&cy).map(|(&x, &y)| [x, y, 0.0]).collect();
    let ring = qas.step(0.5)?.ring.apply(&pts);
    Ok((dnet_ring_patches(&ring, qas.n()), 0.5))
}
