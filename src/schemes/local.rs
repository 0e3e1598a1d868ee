//! The local subdivision matrix of a scheme at one valence, on its local net (centre points,
//! then sector after sector), with what is read off it: the spectrum, the discrete Fourier
//! blocks, eigenvectors, the limit-point stencil and the control points of the characteristic
//! map. Schemes use it where their rules are defined through a characteristic map (guided
//! subdivision samples through Catmull-Clark's); [`crate::analysis`] reports it.

use crate::error::{Error, Result};
use crate::linalg::{C64, complex_eigenvalues, eigenvalues, null_space, poly_from_roots};
use crate::stencil::StencilTable;
use nalgebra::{DMatrix, DVector};
use serde::Serialize;
use std::f64::consts::PI;

/// A scheme's subdivision matrix at one valence, on its local net.
#[derive(Debug, Clone)]
pub struct LocalMatrix {
    /// Scheme name.
    pub scheme: String,
    /// Valence (or facet size).
    pub n: usize,
    /// Number of central points (ordered first).
    pub centre: usize,
    /// Points per sector (sectors follow the centre, in rotation order).
    pub sector: usize,
    /// The square matrix: row `r` gives refined local-net point `r` in terms of the old ones.
    pub matrix: DMatrix<f64>,
}

/// An eigenvalue with its multiplicity.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Eigenvalue {
    /// Real part.
    pub re: f64,
    /// Imaginary part.
    pub im: f64,
    /// Modulus.
    pub modulus: f64,
    /// Algebraic multiplicity (eigenvalues grouped within a relative 1e-6).
    pub multiplicity: usize,
}

/// The spectrum of a subdivision matrix.
#[derive(Debug, Clone, Serialize)]
pub struct Spectrum {
    /// Distinct eigenvalues by decreasing modulus, with multiplicities.
    pub eigenvalues: Vec<Eigenvalue>,
    /// The dominant eigenvalue (1 for an affine scheme).
    pub dominant: f64,
    /// Subdominant eigenvalue lambda (largest modulus below the dominant one).
    pub lambda: f64,
    /// Multiplicity of lambda.
    pub lambda_multiplicity: usize,
    /// Subsubdominant eigenvalue mu (next modulus after lambda).
    pub mu: f64,
    /// mu / lambda^2 (1 for curvature-bounded schemes).
    pub mu_over_lambda_squared: f64,
}

/// Groups sorted eigenvalues into distinct values with multiplicities.
pub fn group_eigenvalues(values: &[C64], rel_tol: f64) -> Vec<Eigenvalue> {
    let mut v: Vec<C64> = values.to_vec();
    v.sort_by(|a, b| {
        b.norm()
            .total_cmp(&a.norm())
            .then(b.re.total_cmp(&a.re))
            .then(b.im.total_cmp(&a.im))
    });
    let mut out: Vec<(C64, usize)> = Vec::new();
    'outer: for z in v {
        for (w, k) in out.iter_mut() {
            if (*w - z).norm() <= rel_tol * w.norm().max(1e-3) {
                // Running mean keeps clusters of a defective eigenvalue together.
                *w = (*w * (*k as f64) + z) / ((*k + 1) as f64);
                *k += 1;
                continue 'outer;
            }
        }
        out.push((z, 1));
    }
    out.into_iter()
        .map(|(z, k)| Eigenvalue {
            re: z.re,
            im: if z.im.abs() < 1e-12 { 0.0 } else { z.im },
            modulus: z.norm(),
            multiplicity: k,
        })
        .collect()
}

/// The spectrum of a subdivision matrix: grouped eigenvalues, lambda, mu and mu / lambda^2.
pub fn spectrum(m: &DMatrix<f64>) -> Spectrum {
    spectrum_of(&eigenvalues(m))
}

/// The spectrum of a matrix with the given eigenvalues (all of them, with repetitions).
pub fn spectrum_of(values: &[C64]) -> Spectrum {
    let ev = group_eigenvalues(values, 1e-6);
    let dominant = ev.first().map(|e| e.re).unwrap_or(0.0);
    let below: Vec<&Eigenvalue> = ev
        .iter()
        .filter(|e| e.modulus < dominant.abs() - 1e-9)
        .collect();
    // Distinct moduli below the dominant one.
    let mut moduli: Vec<(f64, usize)> = Vec::new();
    for e in &below {
        match moduli.last_mut() {
            Some((m, k)) if (*m - e.modulus).abs() <= 1e-6 * m.max(1e-3) => *k += e.multiplicity,
            _ => moduli.push((e.modulus, e.multiplicity)),
        }
    }
    let (lambda, lambda_multiplicity) = moduli.first().copied().unwrap_or((0.0, 0));
    let mu = moduli.get(1).map(|m| m.0).unwrap_or(0.0);
    Spectrum {
        eigenvalues: ev,
        dominant,
        lambda,
        lambda_multiplicity,
        mu,
        mu_over_lambda_squared: if lambda > 0.0 {
            mu / (lambda * lambda)
        } else {
            f64::NAN
        },
    }
}

/// A discrete Fourier block of a rotationally symmetric subdivision matrix.
#[derive(Debug, Clone)]
pub struct FourierBlock {
    /// Frequency `w` (the block acts on vectors `x_(s, b) = v_b exp(2 pi i w s / n)`).
    pub frequency: usize,
    /// The block (`(centre + sector)` square for `w = 0`, `sector` square otherwise).
    pub matrix: DMatrix<C64>,
}

impl FourierBlock {
    /// Eigenvalues of the block.
    pub fn eigenvalues(&self) -> Vec<C64> {
        complex_eigenvalues(&self.matrix)
    }

    /// Coefficients of the characteristic polynomial `det(x I - B)`, highest degree first.
    pub fn characteristic_polynomial(&self) -> Vec<C64> {
        poly_from_roots(&self.eigenvalues())
    }
}

impl LocalMatrix {
    /// Largest deviation from rotational symmetry: `|A[(s,a),(s+r,b)] - A[(0,a),(r,b)]|`, and the
    /// same for the centre rows and columns.
    pub fn rotation_defect(&self) -> f64 {
        let (c, m, n) = (self.centre, self.sector, self.n);
        let idx = |s: usize, a: usize| c + (s % n) * m + a;
        let a = &self.matrix;
        let mut d: f64 = 0.0;
        for s in 0..n {
            for r in 0..n {
                for x in 0..m {
                    for y in 0..m {
                        d = d
                            .max((a[(idx(s, x), idx(s + r, y))] - a[(idx(0, x), idx(r, y))]).abs());
                    }
                }
            }
            for k in 0..c {
                for x in 0..m {
                    d = d.max((a[(idx(s, x), k)] - a[(idx(0, x), k)]).abs());
                    d = d.max((a[(k, idx(s, x))] - a[(k, idx(0, x))]).abs());
                }
            }
        }
        d
    }

    /// The discrete Fourier blocks, frequencies `0..n`. Errors when the matrix is not
    /// rotationally symmetric (defect above 1e-9).
    pub fn fourier_blocks(&self) -> Result<Vec<FourierBlock>> {
        let defect = self.rotation_defect();
        if defect > 1e-9 {
            return Err(Error::Unsupported(format!(
                "{} at valence {} is not rotationally symmetric (defect {defect:.3e}); no Fourier blocks",
                self.scheme, self.n
            )));
        }
        let (c, m, n) = (self.centre, self.sector, self.n);
        let a = &self.matrix;
        let idx = |s: usize, x: usize| c + (s % n) * m + x;
        let mut blocks = Vec::new();
        for w in 0..n {
            let zeta = |r: usize| C64::from_polar(1.0, 2.0 * PI * (w * r % n) as f64 / n as f64);
            let off = if w == 0 { c } else { 0 };
            let k = off + m;
            let mut b = DMatrix::<C64>::zeros(k, k);
            for x in 0..m {
                for y in 0..m {
                    let mut z = C64::new(0.0, 0.0);
                    for r in 0..n {
                        z += zeta(r) * a[(idx(0, x), idx(r, y))];
                    }
                    b[(off + x, off + y)] = z;
                }
            }
            if w == 0 {
                for i in 0..c {
                    for j in 0..c {
                        b[(i, j)] = C64::new(a[(i, j)], 0.0);
                    }
                    for y in 0..m {
                        // Centre row: the sum over sectors of its weights.
                        let mut z = 0.0;
                        for r in 0..n {
                            z += a[(i, idx(r, y))];
                        }
                        b[(i, c + y)] = C64::new(z, 0.0);
                        b[(c + y, i)] = C64::new(a[(idx(0, y), i)], 0.0);
                    }
                }
            }
            blocks.push(FourierBlock {
                frequency: w,
                matrix: b,
            });
        }
        Ok(blocks)
    }

    /// The form with the central points replicated once per sector, as the bi-2 paper writes its
    /// matrices (PGS, PolBS, TPS): sector `s` gets its own copy of every central point, a copy's
    /// row is the central row, and each central column is split equally among the `n` copies.
    /// The non-zero spectrum is unchanged (the copies add `(n - 1) * centre` zeros); the Fourier
    /// blocks all have size `centre + sector` and match the paper's.
    pub fn replicated_centre(&self) -> LocalMatrix {
        let (c, m, n) = (self.centre, self.sector, self.n);
        let k = c + m;
        let old = |s: usize, x: usize| if x < c { x } else { c + s * m + (x - c) };
        let mut a = DMatrix::<f64>::zeros(n * k, n * k);
        for s in 0..n {
            for x in 0..k {
                for t in 0..n {
                    for y in 0..k {
                        let w = self.matrix[(old(s, x), old(t, y))];
                        a[(s * k + x, t * k + y)] = if y < c { w / n as f64 } else { w };
                    }
                }
            }
        }
        LocalMatrix {
            scheme: format!("{} (replicated centre)", self.scheme),
            n,
            centre: 0,
            sector: k,
            matrix: a,
        }
    }

    /// Left eigenvectors (as rows) for the real eigenvalue `value`: an orthonormal basis of the
    /// null space of `A^T - value I` (singular values below `1e-8`).
    pub fn left_eigenvectors(&self, value: f64) -> Vec<DVector<f64>> {
        null_space(
            &(self.matrix.transpose()
                - DMatrix::identity(self.matrix.nrows(), self.matrix.ncols()) * value),
            1e-8,
        )
    }

    /// Right eigenvectors for the real eigenvalue `value`.
    pub fn right_eigenvectors(&self, value: f64) -> Vec<DVector<f64>> {
        null_space(
            &(self.matrix.clone()
                - DMatrix::identity(self.matrix.nrows(), self.matrix.ncols()) * value),
            1e-8,
        )
    }

    /// The limit-point stencil: the left eigenvector of eigenvalue 1, scaled to sum 1
    /// ([`LocalOperator::limit_stencil`]).
    pub fn limit_stencil(&self) -> Result<Vec<f64>> {
        LocalOperator::limit_stencil(self)
    }

    /// The characteristic map's control points on the local net: the real and imaginary parts
    /// of the frequency-1 eigenvector of the subdominant eigenvalue, as `(x, y, 0)` points,
    /// oriented so that the map preserves orientation. Returns the points and lambda.
    pub fn characteristic_points(&self) -> Result<(Vec<[f64; 3]>, f64)> {
        let lambda = spectrum(&self.matrix).lambda;
        let blocks = self.fourier_blocks()?;
        points_from_block(
            &self.scheme,
            (self.centre, self.sector, self.n),
            lambda,
            &blocks[1 % self.n],
        )
    }
}

/// The characteristic map's control points from the frequency-1 Fourier block `b1` of a matrix
/// with `(centre, sector, n)` points and subdominant eigenvalue `lambda`: the real and
/// imaginary parts of the block's eigenvector of `lambda`, rotated from sector to sector, as
/// `(x, y, 0)` points (centre points at the origin), its phase normalised so that the largest
/// entry is real and positive. Returns the points and lambda.
pub fn points_from_block(
    scheme: &str,
    (c, m, n): (usize, usize, usize),
    lambda: f64,
    b1: &FourierBlock,
) -> Result<(Vec<[f64; 3]>, f64)> {
    let k = b1.matrix.nrows();
    let v = null_space(
        &(b1.matrix.clone() - DMatrix::<C64>::identity(k, k) * C64::new(lambda, 0.0)),
        1e-7,
    );
    let Some(v) = v.into_iter().next() else {
        return Err(Error::Unsupported(format!(
            "{scheme} at valence {n}: the subdominant eigenvalue {lambda} is not in the frequency-1 block"
        )));
    };
    let off = if n == 1 { c } else { 0 };
    // Normalise the phase so that the largest entry is real and positive.
    let big = (0..m)
        .max_by(|&a, &b| v[off + a].norm().total_cmp(&v[off + b].norm()))
        .unwrap_or(0);
    let phase = v[off + big].conj() / v[off + big].norm();
    let mut pts = vec![[0.0; 3]; c + n * m];
    for s in 0..n {
        let z = C64::from_polar(1.0, 2.0 * PI * s as f64 / n as f64);
        for x in 0..m {
            let p = v[off + x] * phase * z;
            pts[c + s * m + x] = [p.re, p.im, 0.0];
        }
    }
    Ok((pts, lambda))
}

/// What the analysis reads off a local matrix, whether it is held dense ([`LocalMatrix`]) or
/// as its Fourier blocks ([`super::circulant::Circulant`], for valences whose dense matrix
/// would be too large to decompose).
pub trait LocalOperator: std::fmt::Debug + Sync + Send {
    /// Scheme name (the report's label).
    fn scheme(&self) -> &str;
    /// Valence.
    fn n(&self) -> usize;
    /// Centre points.
    fn centre(&self) -> usize;
    /// Points per sector.
    fn sector(&self) -> usize;
    /// Rows of the matrix.
    fn size(&self) -> usize;
    /// Largest deviation from rotational symmetry.
    fn rotation_defect(&self) -> f64;
    /// Entry `(i, j)`.
    fn entry(&self, i: usize, j: usize) -> f64;
    /// All eigenvalues, with repetitions.
    fn eigenvalues(&self) -> Vec<C64>;
    /// The spectrum.
    fn spectrum(&self) -> Spectrum;
    /// The discrete Fourier blocks, frequencies `0..n`.
    fn fourier_blocks(&self) -> Result<Vec<FourierBlock>>;
    /// An orthonormal basis of the left eigenvectors of the real eigenvalue `value`.
    fn left_eigenvectors(&self, value: f64) -> Vec<DVector<f64>>;
    /// The characteristic map's control points on the local net, and lambda.
    fn characteristic_points(&self) -> Result<(Vec<[f64; 3]>, f64)>;

    /// The limit-point stencil: the left eigenvector of eigenvalue 1, scaled to sum 1.
    fn limit_stencil(&self) -> Result<Vec<f64>> {
        let v = self.left_eigenvectors(1.0);
        if v.len() != 1 {
            return Err(Error::Unsupported(format!(
                "{} at valence {}: eigenvalue 1 has {} left eigenvectors, expected 1",
                self.scheme(),
                self.n(),
                v.len()
            )));
        }
        let s: f64 = v[0].iter().sum();
        Ok(v[0].iter().map(|x| x / s).collect())
    }
}

impl LocalOperator for LocalMatrix {
    fn scheme(&self) -> &str {
        &self.scheme
    }

    fn n(&self) -> usize {
        self.n
    }

    fn centre(&self) -> usize {
        self.centre
    }

    fn sector(&self) -> usize {
        self.sector
    }

    fn size(&self) -> usize {
        self.matrix.nrows()
    }

    fn rotation_defect(&self) -> f64 {
        LocalMatrix::rotation_defect(self)
    }

    fn entry(&self, i: usize, j: usize) -> f64 {
        self.matrix[(i, j)]
    }

    fn eigenvalues(&self) -> Vec<C64> {
        eigenvalues(&self.matrix)
    }

    fn spectrum(&self) -> Spectrum {
        spectrum(&self.matrix)
    }

    fn fourier_blocks(&self) -> Result<Vec<FourierBlock>> {
        LocalMatrix::fourier_blocks(self)
    }

    fn left_eigenvectors(&self, value: f64) -> Vec<DVector<f64>> {
        LocalMatrix::left_eigenvectors(self, value)
    }

    fn characteristic_points(&self) -> Result<(Vec<[f64; 3]>, f64)> {
        LocalMatrix::characteristic_points(self)
    }
}

/// A stencil table as a dense matrix (rows = its rows, columns = its sources).
pub fn dense(t: &StencilTable) -> DMatrix<f64> {
    DMatrix::from_row_slice(t.num_rows(), t.num_sources(), &t.to_dense())
}

/// The error for a valence below 3.
pub fn check_valence(n: usize) -> Result<()> {
    if n < 3 {
        return Err(Error::InvalidArgument(format!(
            "valence {n}: a valence is at least 3"
        )));
    }
    Ok(())
}
