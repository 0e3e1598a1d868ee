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

/// The parts of the fit shared by every sector: the sampled outer coefficients of ring 0 from
/// a guide sector (`nd x (dg + 1)^2`, with the patch and entry of each row) and the square
/// root of the fairness Gram matrix and `sqrt(w)`.
struct FitParts {
    sampled: DMatrix<f64>,
    entries: Vec<(usize, usize)>,
    root: DMatrix<f64>,
    sw: f64,
}

fn fit_parts(dg: usize, chi: &CharRing, fit: GuideFit) -> FitParts {
    let mg = (dg + 1) * (dg + 1);
    // Outer coefficients of ring 0 in bi-5 form: sampled from the guide and prolonged from the
    // surroundings.
    let outer = jet_tables(chi, dg, 5, 3, OUTER);
    let id = DMatrix::identity(mg, mg);
    let blocks = apply_blocks(&outer, &id);
    // Per patch, the sampled outer entries (by corner blocks).
    let mut rows: Vec<nalgebra::RowDVector<f64>> = Vec::new();
    let mut entries = Vec::new();
    for x in 0..3 {
        for (c, blk) in &blocks[x] {
            for i in 0..3 {
                for j in 0..3 {
                    entries.push((x, block_entry(5, *c, i, j)));
                    rows.push(blk.row(i * 3 + j).into_owned());
                }
            }
        }
    }
    let gram = fairness_gram(dg, fit.order);
    let eig = gram.symmetric_eigen();
    let sw = fit.weight.sqrt();
    let root = DMatrix::from_fn(mg, mg, |i, j| {
        eig.eigenvalues[i].max(0.0).sqrt() * eig.eigenvectors[(j, i)]
    });
    FitParts {
        sampled: DMatrix::from_rows(&rows),
        entries,
        root,
        sw,
    }
}

/// The prolonged outer coefficients of ring 0 of sector `s` from the c-net (`nd x (6 n + 1)`).
fn prolonged(n: usize, s: usize, entries: &[(usize, usize)]) -> DMatrix<f64> {
    let pa = surrounding_patch(n, s, 1, 0);
    let pc = surrounding_patch(n, s, 0, 1);
    let empty: Blocks = Default::default();
    // Outer entries of the prolongation (inner entries stay zero, unused).
    let pro = assemble_outer_only(&empty, &pa, &pc);
    let mut cm = DMatrix::zeros(entries.len(), 6 * n + 1);
    for (r, (x, e)) in entries.iter().enumerate() {
        cm.set_row(r, &pro[*x].row(*e));
    }
    cm
}

/// Solves the stacked least-squares problem by SVD, refusing a singular one.
fn solve(n: usize, stacked: DMatrix<f64>, rhs: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    let svd = stacked.svd(true, true);
    let smax = svd.singular_values.max();
    if svd.singular_values.min() <= 1e-13 * smax {
        return Err(Error::Unsupported(format!(
            "valence {n}: the guide fit is singular"
        )));
    }
    svd.solve(rhs, 1e-14 * smax)
        .map_err(|e| Error::Unsupported(format!("valence {n}: the guide fit: {e}")))
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
    let parts = fit_parts(dg, chi, fit);
    let nd = parts.sampled.nrows();
    let dim = space.dim();
    // Minimise |D p - rhs|^2 + w sum_s |R B_s p|^2 with G = R^T R (the F_k Gram matrix of one
    // sector) as one stacked least-squares problem solved by SVD: the normal equations square
    // the condition number (~1e7 with w = 1e-6) and cost affine invariance at 1e-7.
    let mut stacked = DMatrix::zeros(nd * n + mg * n, dim);
    let mut rhs_all = DMatrix::zeros(nd * n + mg * n, 6 * n + 1);
    for s in 0..n {
        let bs = space.basis.rows(s * mg, mg);
        stacked
            .view_mut((s * nd, 0), (nd, dim))
            .copy_from(&(&parts.sampled * bs));
        rhs_all
            .view_mut((s * nd, 0), (nd, 6 * n + 1))
            .copy_from(&prolonged(n, s, &parts.entries));
    }
    for s in 0..n {
        let bs = space.basis.rows(s * mg, mg);
        stacked
            .view_mut((nd * n + mg * s, 0), (mg, dim))
            .copy_from(&(&parts.root * bs * parts.sw));
    }
    solve(n, stacked, &rhs_all)
}

/// The limit point's stencil on the c-net (centre, then sector by sector): [`fit_matrix`]'s
/// first row (the central point `g^0_00`) from the frequency-0 part of the fit alone, in time
/// linear in `n` (bi-5 guide in the paper's coordinates, `n != 4`).
///
/// The fit's objective is a sum over sectors of the same terms, rotated; the rotation's
/// frequencies are orthogonal, so the fit maps the frequency-`w` part of the c-net to the
/// frequency-`w` part of `P` by the same problem restricted to Bloch vectors
/// ([`crate::schemes::guided::fourier`]), whose objective is `n` times sector 0's. The central
/// point has frequency 0, so its row solves sector 0's problem over the real frequency-0
/// guides for the c-net's rotation average (centre, and each of a sector's six points
/// averaged over the sectors): the weight of sector point `(s, b)` is `1 / n` of the
/// average's.
pub(super) fn limit_row(n: usize, chi: &CharRing, fit: GuideFit) -> Result<Vec<f64>> {
    let (g0, point) = crate::schemes::guided::fourier::frequency_zero_guides(n)?;
    let parts = fit_parts(5, chi, fit);
    let nd = parts.sampled.nrows();
    let k = g0.ncols();
    let mut stacked = DMatrix::zeros(nd + 36, k);
    stacked
        .view_mut((0, 0), (nd, k))
        .copy_from(&(&parts.sampled * &g0));
    stacked
        .view_mut((nd, 0), (36, k))
        .copy_from(&(&parts.root * &g0 * parts.sw));
    // The prolongation of a c-net whose sectors all equal one sector's 6 points.
    let full = prolonged(n, 0, &parts.entries);
    let mut rhs = DMatrix::zeros(nd + 36, 7);
    for r in 0..nd {
        for col in 0..6 * n + 1 {
            let to = if col == 0 { 0 } else { 1 + (col - 1) % 6 };
            rhs[(r, to)] += full[(r, col)];
        }
    }
    let f0 = solve(n, stacked, &rhs)?;
    let row: Vec<f64> = (0..7)
        .map(|col| (0..k).map(|r| point[r] * f0[(r, col)]).sum())
        .collect();
    let mut out = Vec::with_capacity(6 * n + 1);
    out.push(row[0]);
    for _ in 0..n {
        out.extend(row[1..].iter().map(|w| w / n as f64));
    }
    Ok(out)
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
