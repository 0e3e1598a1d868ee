//! Block-circulant local matrices solved by their discrete Fourier blocks, in time and memory
//! linear in the valence (issue 20: `analyze` / `charmap` at valence 1000).
//!
//! The local matrix of an `n`-fold symmetric scheme on its local net (`centre` points fixed by
//! the rotation, then `n` sectors of `sector` points each) is block-circulant over the sectors:
//! row `(s, x)` is row `(0, x)` with its sector columns shifted by `s`, and every centre row
//! weighs the `n` copies of a sector point alike. So it is determined by its *generating rows*
//! (the centre rows and sector 0's rows, kept sparse here), and the discrete Fourier transform
//! over the sector index splits it into `n` blocks of `sector` rows (frequency 0 also holds the
//! centre): eigenvalues, eigenvectors, the limit stencil and the characteristic map come from
//! the blocks, never from the `(centre + n sector)^2` dense matrix. The blocks are exactly
//! [`LocalMatrix::fourier_blocks`]'s (same definition; tested equal), and the characteristic
//! points are read off the frequency-1 block by the same code as the dense path
//! ([`super::local::points_from_block`]).
//!
//! Schemes build their rows once (from their own stencils) and hand them to [`SparseLocal`],
//! which picks the dense matrix up to [`crate::linalg::MAX_DENSE_EIGEN_ROWS`] rows (so every
//! output within that bound is unchanged to the bit) and the blocks above it.

use super::local::{
    FourierBlock, LocalMatrix, LocalOperator, Spectrum, points_from_block, spectrum_of,
};
use crate::error::{Error, Result};
use crate::linalg::{C64, MAX_DENSE_EIGEN_ROWS, complex_eigenvalues, null_space};
use nalgebra::{DMatrix, DVector};
use std::cell::Cell;
use std::f64::consts::PI;

/// A scheme's local matrix as sparse rows (all `centre + n sector` of them, local-net order),
/// before the choice between the dense matrix and the Fourier blocks.
#[derive(Debug, Clone)]
pub struct SparseLocal {
    /// Scheme name (the label of the report).
    pub scheme: String,
    /// Valence.
    pub n: usize,
    /// Centre points.
    pub centre: usize,
    /// Points per sector.
    pub sector: usize,
    /// Row `r` as `(column, weight)` pairs.
    pub rows: Vec<Vec<(usize, f64)>>,
    /// Whether the scheme's local matrix is these rows' replicated-centre form (the bi-2
    /// family, as its paper writes it).
    pub replicate: bool,
}

impl SparseLocal {
    /// The rows of a square stencil table on the local net.
    pub fn from_table(
        scheme: impl Into<String>,
        (centre, sector, n): (usize, usize, usize),
        t: &crate::stencil::StencilTable,
    ) -> SparseLocal {
        SparseLocal {
            scheme: scheme.into(),
            n,
            centre,
            sector,
            rows: (0..t.num_rows())
                .map(|r| {
                    let (i, w) = t.row(r);
                    i.iter()
                        .map(|&i| i as usize)
                        .zip(w.iter().copied())
                        .collect()
                })
                .collect(),
            replicate: false,
        }
    }

    /// The dense matrix of the rows (duplicates summed in order, like
    /// [`crate::stencil::StencilTable::to_dense`]), without replication.
    pub fn to_matrix(&self) -> LocalMatrix {
        let size = self.size();
        let mut m = DMatrix::zeros(size, size);
        for (r, row) in self.rows.iter().enumerate() {
            for &(c, w) in row {
                m[(r, c)] += w;
            }
        }
        LocalMatrix {
            scheme: self.scheme.clone(),
            n: self.n,
            centre: self.centre,
            sector: self.sector,
            matrix: m,
        }
    }

    /// The local operator of rows whose dense matrix is [`SparseLocal::to_matrix`]:
    /// [`choose`] between it and the Fourier blocks.
    ///
    /// # Errors
    /// As [`choose`].
    pub fn operator(&self) -> Result<Box<dyn LocalOperator>> {
        choose(self, false, || Ok(self.to_matrix()))
    }

    /// Rows (and columns) of the matrix.
    pub fn size(&self) -> usize {
        self.centre + self.n * self.sector
    }

    /// Rows of the scheme's local matrix (of the replicated-centre form where the scheme's
    /// matrix is that form, or where `replicated_centre` asks for it).
    pub fn matrix_size(&self, replicated_centre: bool) -> usize {
        if self.replicate || replicated_centre {
            self.n * (self.centre + self.sector)
        } else {
            self.size()
        }
    }

    /// The block-circulant form of the scheme's local matrix (replicated where the scheme's
    /// matrix is).
    ///
    /// # Errors
    /// When the rows do not have the local net's size.
    pub fn circulant(&self) -> Result<Circulant> {
        let c = Circulant::new(self)?;
        Ok(if self.replicate {
            c.replicated_centre()
        } else {
            c
        })
    }
}

/// A block-circulant local matrix kept as its generating rows.
#[derive(Debug, Clone)]
pub struct Circulant {
    /// Scheme name.
    pub scheme: String,
    /// Valence.
    pub n: usize,
    /// Centre points (fixed by the rotation).
    pub centre: usize,
    /// Points per sector.
    pub sector: usize,
    /// The centre rows, then sector 0's rows, sorted by column with duplicates summed.
    rows: Vec<Vec<(usize, f64)>>,
    /// Largest deviation of the full rows from the rotation of the generating rows.
    defect: f64,
    /// `exp(2 pi i k / n)`, `k = 0..n`.
    zeta: Vec<C64>,
}

/// Sorts by column and sums duplicates (in the order given).
fn merged(mut row: Vec<(usize, f64)>) -> Vec<(usize, f64)> {
    row.sort_by_key(|e| e.0);
    let mut out: Vec<(usize, f64)> = Vec::with_capacity(row.len());
    for (c, w) in row {
        match out.last_mut() {
            Some(last) if last.0 == c => last.1 += w,
            _ => out.push((c, w)),
        }
    }
    out
}

/// Largest `|a - b|` over the union of two sorted sparse rows.
fn row_difference(a: &[(usize, f64)], b: &[(usize, f64)]) -> f64 {
    let (mut i, mut j, mut d) = (0, 0, 0.0f64);
    while i < a.len() || j < b.len() {
        let ca = a.get(i).map_or(usize::MAX, |e| e.0);
        let cb = b.get(j).map_or(usize::MAX, |e| e.0);
        if ca == cb {
            d = d.max((a[i].1 - b[j].1).abs());
            i += 1;
            j += 1;
        } else if ca < cb {
            d = d.max(a[i].1.abs());
            i += 1;
        } else {
            d = d.max(b[j].1.abs());
            j += 1;
        }
    }
    d
}

impl Circulant {
    fn new(s: &SparseLocal) -> Result<Circulant> {
        let (c, m, n) = (s.centre, s.sector, s.n);
        if s.rows.len() != s.size() || n == 0 {
            return Err(Error::Unsupported(format!(
                "{} at valence {n}: {} local rows, expected {} + {n} x {m}",
                s.scheme,
                s.rows.len(),
                c
            )));
        }
        let shift = |col: usize, by: usize| -> usize {
            if col < c {
                col
            } else {
                let (r, y) = ((col - c) / m, (col - c) % m);
                c + ((r + n - by % n) % n) * m + y
            }
        };
        let rows: Vec<Vec<(usize, f64)>> = (0..c + m).map(|r| merged(s.rows[r].clone())).collect();
        let mut defect: f64 = 0.0;
        // Sector rows: row (s, x) shifted back by s is row (0, x).
        for sec in 1..n {
            for x in 0..m {
                let back: Vec<(usize, f64)> = s.rows[c + sec * m + x]
                    .iter()
                    .map(|&(col, w)| (shift(col, sec), w))
                    .collect();
                defect = defect.max(row_difference(&merged(back), &rows[c + x]));
            }
        }
        // Centre rows: the same weight on every copy of a sector point.
        for row in &rows[..c] {
            let mut first = vec![0.0; m];
            let mut dense = vec![0.0; n * m];
            for &(col, w) in row.iter().filter(|e| e.0 >= c) {
                dense[col - c] = w;
                if col - c < m {
                    first[col - c] = w;
                }
            }
            for (k, w) in dense.iter().enumerate() {
                defect = defect.max((w - first[k % m]).abs());
            }
        }
        let zeta = (0..n)
            .map(|k| C64::from_polar(1.0, 2.0 * PI * k as f64 / n as f64))
            .collect();
        Ok(Circulant {
            scheme: s.scheme.clone(),
            n,
            centre: c,
            sector: m,
            rows,
            defect,
            zeta,
        })
    }

    /// The form with the centre points replicated once per sector (see
    /// [`LocalMatrix::replicated_centre`]): sector `s` holds a copy of every centre point
    /// first, a copy's row is the centre's row, and every weight on a centre point is split
    /// evenly over its `n` copies.
    pub fn replicated_centre(&self) -> Circulant {
        let (c, m, n) = (self.centre, self.sector, self.n);
        let k = c + m;
        let rows = self
            .rows
            .iter()
            .map(|row| {
                let mut out = Vec::new();
                for &(col, w) in row {
                    if col < c {
                        out.extend((0..n).map(|t| (t * k + col, w / n as f64)));
                    } else {
                        let (r, y) = ((col - c) / m, (col - c) % m);
                        out.push((r * k + c + y, w));
                    }
                }
                merged(out)
            })
            .collect();
        Circulant {
            scheme: self.scheme.clone(),
            n,
            centre: 0,
            sector: k,
            rows,
            defect: self.defect,
            zeta: self.zeta.clone(),
        }
    }

    /// Entry `(i, j)` of the full matrix.
    pub fn entry(&self, i: usize, j: usize) -> f64 {
        let (c, m, n) = (self.centre, self.sector, self.n);
        let (row, col) = if i < c {
            (&self.rows[i], j)
        } else {
            let (s, x) = ((i - c) / m, (i - c) % m);
            let col = if j < c {
                j
            } else {
                let (r, y) = ((j - c) / m, (j - c) % m);
                c + ((r + n - s) % n) * m + y
            };
            (&self.rows[c + x], col)
        };
        row.binary_search_by_key(&col, |e| e.0)
            .map_or(0.0, |k| row[k].1)
    }

    /// The Fourier block of frequency `w`: `B[x][y] = sum_r exp(2 pi i w r / n) A[(0, x), (r, y)]`
    /// on the sector points, and for `w = 0` the centre rows and columns first (a centre row's
    /// weights summed over the sectors).
    pub fn block(&self, w: usize) -> FourierBlock {
        let (c, m, n) = (self.centre, self.sector, self.n);
        let off = if w == 0 { c } else { 0 };
        let k = off + m;
        let mut b = DMatrix::<C64>::zeros(k, k);
        for x in 0..m {
            for &(col, a) in &self.rows[c + x] {
                if col < c {
                    if w == 0 {
                        b[(c + x, col)] += C64::new(a, 0.0);
                    }
                } else {
                    let (r, y) = ((col - c) / m, (col - c) % m);
                    b[(off + x, off + y)] += self.zeta[(w * r) % n] * a;
                }
            }
        }
        if w == 0 {
            for i in 0..c {
                for &(col, a) in &self.rows[i] {
                    let j = if col < c { col } else { c + (col - c) % m };
                    b[(i, j)] += C64::new(a, 0.0);
                }
            }
        }
        FourierBlock {
            frequency: w,
            matrix: b,
        }
    }

    /// The left eigenvectors of the real eigenvalue `value`, as real vectors on the whole local
    /// net: an orthonormal basis of the union over frequencies of the blocks' left null spaces
    /// of `B - value I` (singular values below `1e-8` of the largest). A block of frequency
    /// `w` (and its conjugate `n - w`) gives the real and imaginary parts of
    /// `l_(s, x) = u_x exp(-2 pi i w s / n)`; frequency 0 gives the centre weights `u_c` and
    /// the sector weights `u_x / n`.
    pub fn left_eigenvectors(&self, value: f64) -> Vec<DVector<f64>> {
        let (c, m, n) = (self.centre, self.sector, self.n);
        let size = c + n * m;
        let lift = |w: usize, u: &DVector<C64>| {
            let off = if w == 0 { c } else { 0 };
            let mut full = DVector::<C64>::zeros(size);
            for i in 0..off {
                full[i] = u[i];
            }
            let scale = if w == 0 { 1.0 / n as f64 } else { 1.0 };
            for s in 0..n {
                let z = self.zeta[(w * s) % n].conj() * scale;
                for x in 0..m {
                    full[c + s * m + x] = u[off + x] * z;
                }
            }
            full
        };
        left_eigenvectors_by_blocks(n, value, |w| self.block(w).matrix, lift)
    }
}

/// The left eigenvectors of the real eigenvalue `value` of a matrix that the discrete Fourier
/// transform over its `n` sectors splits into blocks (`block(w)`, frequency `w`), as real
/// vectors on the whole space: an orthonormal basis of the union over frequencies `0..=n/2` of
/// the blocks' left null spaces of `B - value I` (singular values below `1e-8` of the largest),
/// each null vector `u` of block `w` lifted to the whole space by `lift(w, u)` (the row of the
/// inverse transform: `l^T y = u^T (coordinates of y in block w)`). Blocks `w = 0` and
/// `2 w = n` are real, so their null vectors are real up to a phase, which is removed; a
/// complex block (and its conjugate `n - w`) gives the real and imaginary parts of its lift.
pub(crate) fn left_eigenvectors_by_blocks(
    n: usize,
    value: f64,
    block: impl Fn(usize) -> DMatrix<C64>,
    lift: impl Fn(usize, &DVector<C64>) -> DVector<C64>,
) -> Vec<DVector<f64>> {
    let mut out: Vec<DVector<f64>> = Vec::new();
    for w in 0..=n / 2 {
        let b = block(w);
        let k = b.nrows();
        let shifted = b.transpose() - DMatrix::<C64>::identity(k, k) * C64::new(value, 0.0);
        for u in block_null_space(&shifted, &b) {
            let real = w == 0 || 2 * w == n;
            // A real block's null vector is real up to a phase.
            let u = if real {
                let big = (0..k)
                    .max_by(|&a, &b| u[a].norm().total_cmp(&u[b].norm()))
                    .unwrap_or(0);
                let ph = u[big].conj() / u[big].norm();
                u.map(|z| z * ph)
            } else {
                u
            };
            let full = lift(w, &u);
            out.push(full.map(|z| z.re));
            if !real {
                out.push(full.map(|z| z.im));
            }
        }
    }
    orthonormal(out)
}

/// The null space of `shifted = B^T - value I` for a Fourier block `B`: singular values at
/// most `1e-8` of the larger of the largest one and `B`'s Frobenius norm (the dense path's
/// tolerance is relative to the whole matrix, whose scale a `1 x 1` block with its eigenvalue
/// at the shift would lose).
fn block_null_space(shifted: &DMatrix<C64>, b: &DMatrix<C64>) -> Vec<DVector<C64>> {
    let smax = shifted
        .clone()
        .singular_values()
        .iter()
        .copied()
        .fold(0.0, f64::max);
    let scale = smax.max(b.norm());
    if smax <= 1e-8 * scale {
        let k = shifted.ncols();
        return (0..k)
            .map(|i| DVector::from_fn(k, |j, _| C64::new(f64::from(u8::from(i == j)), 0.0)))
            .collect();
    }
    null_space(shifted, 1e-8 * scale / smax)
}

/// Modified Gram-Schmidt, dropping vectors that are (numerically) in the span of earlier ones.
fn orthonormal(vs: Vec<DVector<f64>>) -> Vec<DVector<f64>> {
    let mut out: Vec<DVector<f64>> = Vec::new();
    for mut v in vs {
        let norm0 = v.norm();
        for b in &out {
            let d = b.dot(&v);
            v -= b * d;
        }
        let norm = v.norm();
        if norm > 1e-8 * norm0.max(f64::MIN_POSITIVE) {
            out.push(v / norm);
        }
    }
    out
}

impl LocalOperator for Circulant {
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
        self.centre + self.n * self.sector
    }

    fn rotation_defect(&self) -> f64 {
        self.defect
    }

    fn entry(&self, i: usize, j: usize) -> f64 {
        Circulant::entry(self, i, j)
    }

    fn eigenvalues(&self) -> Vec<C64> {
        (0..self.n)
            .flat_map(|w| complex_eigenvalues(&self.block(w).matrix))
            .collect()
    }

    fn spectrum(&self) -> Spectrum {
        spectrum_of(&self.eigenvalues())
    }

    fn fourier_blocks(&self) -> Result<Vec<FourierBlock>> {
        symmetric(self)?;
        Ok((0..self.n).map(|w| self.block(w)).collect())
    }

    fn left_eigenvectors(&self, value: f64) -> Vec<DVector<f64>> {
        Circulant::left_eigenvectors(self, value)
    }

    fn characteristic_points(&self) -> Result<(Vec<[f64; 3]>, f64)> {
        symmetric(self)?;
        let lambda = self.spectrum().lambda;
        points_from_block(
            &self.scheme,
            (self.centre, self.sector, self.n),
            lambda,
            &self.block(1 % self.n),
        )
    }
}

/// The error of a matrix that is not rotationally symmetric (its blocks would not be its own).
fn symmetric(c: &Circulant) -> Result<()> {
    if c.defect > 1e-9 {
        return Err(Error::Unsupported(format!(
            "{} at valence {} is not rotationally symmetric (defect {:.3e}); no Fourier blocks",
            c.scheme, c.n, c.defect
        )));
    }
    Ok(())
}

thread_local! {
    /// The most rows [`choose`] decomposes densely on this thread ([`with_dense_rows`]).
    static DENSE_ROWS: Cell<usize> = const { Cell::new(MAX_DENSE_EIGEN_ROWS) };
}

/// Runs `f` with [`choose`] taking the dense path up to `max` rows only on this thread (0: the
/// Fourier blocks for every block-circulant matrix), so that tests can compare both paths on
/// the same valences.
pub fn with_dense_rows<T>(max: usize, f: impl FnOnce() -> T) -> T {
    let old = DENSE_ROWS.with(|c| c.replace(max));
    let out = f();
    DENSE_ROWS.with(|c| c.set(old));
    out
}

/// The most rows [`choose`] decomposes densely on this thread ([`MAX_DENSE_EIGEN_ROWS`], or
/// what [`with_dense_rows`] set), for schemes that choose between their dense matrix and their
/// blocks themselves.
pub fn dense_rows() -> usize {
    DENSE_ROWS.with(Cell::get)
}

/// The local operator of a scheme's sparse rows: the dense matrix `dense()` (the scheme's
/// [`LocalMatrix`]) within [`MAX_DENSE_EIGEN_ROWS`] rows, so that outputs there are the dense
/// path's to the bit, and the Fourier blocks above; with `replicated_centre`, in the
/// replicated-centre form ([`LocalMatrix::replicated_centre`]).
///
/// # Errors
/// As [`SparseLocal::circulant`], or `dense`'s.
pub fn choose(
    rows: &SparseLocal,
    replicated_centre: bool,
    dense: impl FnOnce() -> Result<LocalMatrix>,
) -> Result<Box<dyn LocalOperator>> {
    if rows.matrix_size(replicated_centre) <= dense_rows() {
        let lm = dense()?;
        return Ok(Box::new(if replicated_centre {
            lm.replicated_centre()
        } else {
            lm
        }));
    }
    let c = rows.circulant()?;
    Ok(Box::new(if replicated_centre {
        let mut r = c.replicated_centre();
        r.scheme = format!("{} (replicated centre)", c.scheme);
        r
    } else {
        c
    }))
}
