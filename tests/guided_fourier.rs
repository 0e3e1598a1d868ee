//! Guided subdivision's local matrix by Fourier blocks in the Bloch basis
//! (`fairsub::schemes::guided::fourier`, issue 20: linear in the valence) against the dense
//! matrix in the paper's coordinates: the whole `analyze` report computed twice (dense, and
//! with the blocks at every valence, [`circulant::with_dense_rows`]`(0, ..)`) agrees to 1e-10;
//! the blocks' eigenvalues are the dense matrix's; table (5) holds above the dense bound.

use fairsub::analysis::report::{self, AnalyzeReport};
use fairsub::schemes::circulant;
use fairsub::schemes::guided::fourier::GuidedBlocks;
use fairsub::schemes::guided::guide::GuideDegree;
use fairsub::schemes::guided::local;
use fairsub::schemes::local::LocalOperator;
use fairsub::schemes::registry;
use nalgebra::DMatrix;

fn analyze(scheme: &str, n: usize, blocks: bool) -> AnalyzeReport {
    let spec = registry().lookup(scheme).unwrap();
    let run = || report::analyze(&spec, n, false).unwrap();
    if blocks {
        circulant::with_dense_rows(0, run)
    } else {
        run()
    }
}

fn moduli(r: &AnalyzeReport) -> Vec<f64> {
    let mut v: Vec<f64> = r
        .spectrum
        .eigenvalues
        .iter()
        .flat_map(|e| std::iter::repeat_n(e.modulus, e.multiplicity))
        .collect();
    v.sort_by(|a, b| b.total_cmp(a));
    v
}

fn projector(vs: &[Vec<f64>]) -> DMatrix<f64> {
    let k = vs.first().map_or(0, Vec::len);
    let mut p = DMatrix::zeros(k, k);
    for v in vs {
        for i in 0..k {
            for j in 0..k {
                p[(i, j)] += v[i] * v[j];
            }
        }
    }
    p
}

fn close(a: f64, b: f64, what: &str) {
    assert!(
        (a - b).abs() <= 1e-10 * a.abs().max(1.0),
        "{what}: dense {a} vs blocks {b}"
    );
}

#[test]
fn blocks_reproduce_the_dense_reports() {
    for scheme in ["guided-bi5", "guided-bi6", "guided-bi3-macro"] {
        for n in [3, 5, 6, 7, 12, 20] {
            let what = |x: &str| format!("{scheme} n={n} {x}");
            let d = analyze(scheme, n, false);
            let f = analyze(scheme, n, true);
            assert_eq!(d.scheme, f.scheme);
            assert_eq!(d.matrix_size, f.matrix_size, "{}", what("size"));
            assert_eq!(
                (d.centre_points, d.points_per_sector),
                (f.centre_points, f.points_per_sector)
            );
            close(d.rotation_defect, f.rotation_defect, &what("defect"));
            let (md, mf) = (moduli(&d), moduli(&f));
            assert_eq!(md.len(), mf.len(), "{}", what("eigenvalue count"));
            for (k, (a, b)) in md.iter().zip(&mf).enumerate() {
                close(*a, *b, &what(&format!("modulus {k}")));
            }
            assert_eq!(d.spectrum.eigenvalues.len(), f.spectrum.eigenvalues.len());
            for (a, b) in d.spectrum.eigenvalues.iter().zip(&f.spectrum.eigenvalues) {
                assert_eq!(a.multiplicity, b.multiplicity, "{}", what("multiplicity"));
                close(a.re, b.re, &what("eigenvalue"));
                close(a.im, b.im, &what("eigenvalue"));
            }
            close(d.spectrum.lambda, f.spectrum.lambda, &what("lambda"));
            close(d.spectrum.mu, f.spectrum.mu, &what("mu"));
            assert_eq!(
                d.spectrum.lambda_multiplicity,
                f.spectrum.lambda_multiplicity
            );
            // The dense fit is one least-squares problem over all sectors (condition about
            // 1e7, growing with n); its row is rotation-invariant up to its own rounding, which
            // bounds the agreement with the frequency-0 fit from above.
            assert_eq!(d.limit_stencil.len(), f.limit_stencil.len());
            let spread = (1..d.limit_stencil.len())
                .map(|i| (d.limit_stencil[i] - d.limit_stencil[1 + (i - 1) % 6]).abs())
                .fold(0.0, f64::max);
            let diff = d
                .limit_stencil
                .iter()
                .zip(&f.limit_stencil)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            println!(
                "{scheme} n={n}: limit stencil difference {diff:.2e}, dense spread {spread:.2e}"
            );
            assert!(
                diff <= 1e-10f64.max(10.0 * spread),
                "{}: {diff} (dense spread {spread})",
                what("limit stencil")
            );
            let sum: f64 = f.limit_stencil.iter().sum();
            close(sum, 1.0, &what("limit stencil sum"));
            assert_eq!(d.tangent_stencils.len(), 2, "{}", what("tangents"));
            assert_eq!(d.tangent_stencils.len(), f.tangent_stencils.len());
            let dp = projector(&d.tangent_stencils) - projector(&f.tangent_stencils);
            assert!(dp.amax() < 1e-10, "{}: {}", what("tangent span"), dp.amax());
            assert_eq!(d.fourier_blocks.len(), f.fourier_blocks.len());
            let (a, b) = (
                d.characteristic_map.as_ref().unwrap(),
                f.characteristic_map.as_ref().unwrap(),
            );
            assert_eq!(a.injective, b.injective);
            assert_eq!((a.patches, a.pieces), (b.patches, b.pieces));
            assert_eq!(a.windings, b.windings);
            close(
                a.jacobian_min_coefficient,
                b.jacobian_min_coefficient,
                &what("Jacobian"),
            );
            assert_eq!(d.published.len(), f.published.len());
            for (a, b) in d.published.iter().zip(&f.published) {
                assert_eq!(a.quantity, b.quantity);
                close(a.computed, b.computed, &what(&a.quantity));
            }
            assert_eq!(
                serde_json::to_value(&d.extra).unwrap(),
                serde_json::to_value(&f.extra).unwrap()
            );
        }
    }
}

/// Every entry of the matrix read off the blocks is the dense entry, and the Bloch basis
/// leaks nothing outside a block's frequency.
#[test]
fn block_entries_equal_the_dense_matrix() {
    for n in [3, 5, 6, 9] {
        let lambda = local::lambda(n, Default::default());
        let lm = local::local_matrix(n, GuideDegree::Bi5, lambda).unwrap();
        let b = GuidedBlocks::new("guided", n, lambda).unwrap();
        assert!(b.leakage() < 1e-12, "n={n} leakage {}", b.leakage());
        let mut worst: f64 = 0.0;
        for i in 0..lm.matrix.nrows() {
            for j in 0..lm.matrix.ncols() {
                worst = worst.max((lm.matrix[(i, j)] - b.entry(i, j)).abs());
            }
        }
        assert!(worst < 1e-12, "n={n}: {worst}");
    }
}

/// Table (5) of the paper above the dense bound: `lambda^s` with multiplicities
/// 1, 2, 3, n, 2n, 3n, 3n, 3n, 3n, 2n, n, and nothing else.
#[test]
fn table5_above_the_dense_bound() {
    for n in [40, 101] {
        let lambda = local::lambda(n, Default::default());
        let op = local::operator(n, GuideDegree::Bi5, lambda).unwrap();
        assert!(op.size() > fairsub::linalg::MAX_DENSE_EIGEN_ROWS);
        let ev = op.eigenvalues();
        assert_eq!(ev.len(), 6 + 18 * n);
        let rows = local::table5(n, lambda, &ev);
        let mut total = 0;
        for (s, published, computed) in rows {
            assert_eq!(published, computed, "n={n} lambda^{s}");
            total += computed;
        }
        assert_eq!(total, ev.len(), "n={n}: eigenvalues other than lambda^s");
        let r = analyze("guided-bi5", n, false);
        assert!(r.characteristic_map.as_ref().unwrap().injective);
        close(r.spectrum.lambda, lambda, "lambda");
        let sum: f64 = r.limit_stencil.iter().sum();
        close(sum, 1.0, "limit stencil sum");
    }
}
