//! The fit of the guide to the c-net: the guide's target (fairsub's guide-fit with a fairness
//! order and weight) and the stacked least-squares matrix from the c-net to the guide's free set.

use super::*;

/// fairsub's guide target (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GuideFit {
    /// The order `k` of the fairness functional `F_k`.
    pub order: usize,
    /// Its weight `w`.
    pub weight: f64,
}

impl GuideFit {
    /// The default weight of `F_4`.
    pub const DEFAULT_WEIGHT: f64 = 1e-6;
}

impl Default for GuideFit {
    fn default() -> Self {
        GuideFit {
            order: 4,
            weight: Self::DEFAULT_WEIGHT,
        }
    }
}

/// The least-squares fit of `P` (see the module documentation): `dim x (6 n + 1)`.
pub(super) fn fit_matrix(
    n: usize,
    space: &GuideSpace,
    chi: &CharRing,
    fit: GuideFit,
) -> Result<DMatrix<f64>> {
    let dg = space.degree;
    let mg = (dg + 1) * (dg + 1);
    // Outer coefficients of ring 0 in bi-5 form: sampled from the guide and prolonged from the
    // surroundings.
    let outer = jet_tables(chi, dg, 5, 3, OUTER);
    let id = DMatrix::identity(mg, mg);
    let mut rows_g: Vec<DMatrix<f64>> = Vec::new(); // per sector: data x mg (same for all)
    let mut rows_c: Vec<DMatrix<f64>> = Vec::new(); // per sector: data x (6n+1)
    let blocks = apply_blocks(&outer, &id);
    // Per patch, the sampled outer entries (by corner blocks).
    let mut sampled: Vec<(usize, usize, nalgebra::RowDVector<f64>)> = Vec::new(); // (patch, entry, row)
    for x in 0..3 {
        for (c, blk) in &blocks[x] {
            for i in 0..3 {
                for j in 0..3 {
                    sampled.push((x, block_entry(5, *c, i, j), blk.row(i * 3 + j).into_owned()));
                }
            }
        }
    }
    for s in 0..n {
        let pa = surrounding_patch(n, s, 1, 0);
        let pc = surrounding_patch(n, s, 0, 1);
        let empty: Blocks = Default::default();
        // Outer entries of the prolongation (inner entries stay zero, unused).
        let pro = assemble_outer_only(&empty, &pa, &pc);
        let mut g = DMatrix::zeros(sampled.len(), mg);
        let mut cm = DMatrix::zeros(sampled.len(), 6 * n + 1);
        for (r, (x, e, row)) in sampled.iter().enumerate() {
            g.set_row(r, row);
            cm.set_row(r, &pro[*x].row(*e));
        }
        rows_g.push(g);
        rows_c.push(cm);
    }
    let nd = rows_g[0].nrows();
    let dim = space.dim();
    let mut dmat = DMatrix::zeros(nd * n, dim);
    let mut rhs = DMatrix::zeros(nd * n, 6 * n + 1);
    for s in 0..n {
        let bs = space.basis.rows(s * mg, mg);
        dmat.view_mut((s * nd, 0), (nd, dim))
            .copy_from(&(&rows_g[s] * bs));
        rhs.view_mut((s * nd, 0), (nd, 6 * n + 1))
            .copy_from(&rows_c[s]);
    }
    // Minimise |D p - rhs|^2 + w sum_s |R B_s p|^2 with G = R^T R (the F_k Gram matrix of one
    // sector) as one stacked least-squares problem solved by SVD: the normal equations square
    // the condition number (~1e7 with w = 1e-6) and cost affine invariance at 1e-7.
    let gram = fairness_gram(dg, fit.order);
    let eig = gram.symmetric_eigen();
    let root = DMatrix::from_fn(mg, mg, |i, j| {
        eig.eigenvalues[i].max(0.0).sqrt() * eig.eigenvectors[(j, i)]
    });
    let mut stacked = DMatrix::zeros(nd * n + mg * n, dim);
    let mut rhs_all = DMatrix::zeros(nd * n + mg * n, 6 * n + 1);
    stacked.view_mut((0, 0), (nd * n, dim)).copy_from(&dmat);
    rhs_all
        .view_mut((0, 0), (nd * n, 6 * n + 1))
        .copy_from(&rhs);
    let sw = fit.weight.sqrt();
    for s in 0..n {
        let bs = space.basis.rows(s * mg, mg);
        stacked
            .view_mut((nd * n + mg * s, 0), (mg, dim))
            .copy_from(&(&root * bs * sw));
    }
    let svd = stacked.svd(true, true);
    let smax = svd.singular_values.max();
    if svd.singular_values.min() <= 1e-13 * smax {
        return Err(Error::Unsupported(format!(
            "valence {n}: the guide fit is singular"
        )));
    }
    svd.solve(&rhs_all, 1e-14 * smax)
        .map_err(|e| Error::Unsupported(format!("valence {n}: the guide fit: {e}")))
}

/// The prolongation of the surroundings into ring 0 (bi-5), outer entries only.
fn assemble_outer_only(
    _inner: &Blocks,
    prev_a: &DMatrix<f64>,
    prev_c: &DMatrix<f64>,
) -> [DMatrix<f64>; 3] {
    let d = 5;
    let src = prev_a.ncols();
    let m = 36;
    let mut out = [
        DMatrix::zeros(m, src),
        DMatrix::zeros(m, src),
        DMatrix::zeros(m, src),
    ];
    for x in 0..3 {
        let pa = prolong(3, d, prolongation_box(x, true)) * prev_a;
        let pc = prolong(3, d, prolongation_box(x, false)) * prev_c;
        for i in 0..=d {
            for j in 0..=d {
                let r = i * (d + 1) + j;
                match source(x, d, i, j) {
                    Source::OuterA => out[x].set_row(r, &pa.row(r)),
                    Source::OuterC => out[x].set_row(r, &pc.row(r)),
                    Source::Inner => {}
                }
            }
        }
    }
    out
}
