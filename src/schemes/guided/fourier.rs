//! Guided subdivision's local matrix by discrete Fourier blocks, in time and memory linear in
//! the valence (issue 20: `analyze` / `charmap` of the guided schemes up to valence 1000).
//!
//! # Derivation
//!
//! The subdivision matrix `M = E R B` of [`super::guide::GuideSpace::step_matrix`] acts on the
//! paper's free set `P`: the six central coefficients `g^0_00, 10, 20, 01, 11, 02` (for
//! `n = 3, 6` a seventh, the kernel direction of (4)), then 18 free coefficients per sector.
//! `B` expands `P` to a guide, `R` restricts every sector to `[0, lambda]^2`, `E` reads `P` back.
//! The rotation by one sector, `(rot g)^s = g^(s-1)`, maps G^2 guides to G^2 guides (the
//! relations are the same at every ray) and commutes with `R`, so `M` commutes with the
//! rotation's action on `P`. That action shifts the sector coordinates, but it does not fix
//! the central ones: they are the 2-jet at the centre of sector 0, and the guide's 2-jet there
//! is the 2-jet of one quadratic `q(x, y)` of the plane (`g o L^-1` is C^2 across every ray), so
//! the central coordinates of `q o L_0` span the rotation's representation on quadratics.
//! With `z = x + i y` it splits into the characters `q in {1, z, zbar, z zbar, z^2, zbar^2}`:
//! `q o rot_s = zeta^(s f) q` with `zeta = exp(2 pi i / n)` and frequency
//! `f = 0, 1, -1, 0, 2, -2` (mod `n`). The kernel coordinate of (4) is the constant
//! (`n = 3`, frequency 0) or alternating (`n = 6`, frequency 3) sequence of `g^s_12`.
//!
//! So `P` has the basis of *Bloch vectors*: `C_q` (central coordinates of `q o L_0`, the BB
//! form of its 2-jet: `b_00 = f`, `b_10 = f + f_u / 5`, `b_20 = f + 2 f_u / 5 + f_uu / 20`,
//! `b_11 = f + (f_u + f_v) / 5 + f_uv / 25`, and `u <-> v`, with `L_0 (u, v) = u + zeta v` as a
//! complex number), the kernel coordinate `X`, and `F_(w, b)` (sector coordinate `b` of sector
//! `s` equal to `zeta^(w s)`). Each is an eigenvector of the rotation, so its guide is a Bloch
//! guide, `g^s = zeta^(w s) g^0`, and so is `M` of it: `M` maps the span of the frequency-`w`
//! vectors into itself, and in this basis it is block diagonal with one block per frequency
//! `w = 0..n`: 18 sector coordinates plus the central ones of frequency `w` (at most 3).
//!
//! A Bloch guide is determined by its sector 0, and each relation of the guide space reads
//! only neighbouring sectors, `g^(+-1) = zeta^(+-w) g^0`. So block `w` costs O(1): for each
//! basis vector, sector 0 of its guide (`bloch_sector`: the central and free coefficients,
//! (4) as `(zeta^w + 2 c) g^0_12 = r_0` (the minimum-norm solution, 0, at the singular
//! frequency, like the pseudo-inverse of the dense path), Appendix A at ray 0 for the acute
//! side of sector 0 and at ray 1, `zeta^w` times ray 0's values, for its grave side, all by
//! the same rule functions as [`super::guide`]'s expansion), restricted by `R`; its
//! coordinates are the free coefficients (the `F_(w, b)` coordinates), `V^-1` of the central
//! coefficients (`V` the matrix of the `C_q`; components at other frequencies are the
//! *leakage*, measured) and `n |kv_0| g^0_12` for `X`.
//!
//! The eigenvalues of `M` are those of the blocks; a left eigenvector `u` of block `w` is the
//! left eigenvector `l^T = u^T Q^-1` of `M` (`Q` the Bloch basis): `l_(s, b) = u_b
//! zeta^(-w s) / n`, the central part `sum_q u_q (V^-1)_(q, .)`, `l_X = u_X`.

use super::guide::{CENTRAL, FREE_SECTOR, Sector, appendix_a, central_next, cos_n, rhs4};
use crate::error::{Error, Result};
use crate::linalg::{C64, complex_eigenvalues};
use crate::schemes::circulant::left_eigenvectors_by_blocks;
use crate::schemes::local::{FourierBlock, LocalOperator, Spectrum, spectrum_of};
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;

/// `exp(2 pi i w / n)`.
fn zeta(n: usize, w: usize) -> C64 {
    C64::from_polar(1.0, 2.0 * PI * (w % n) as f64 / n as f64)
}

/// The valences of the paper's bi-5 coordinates: `n >= 3`, `n != 4` (Appendix A divides by
/// `cos(2 pi / n)`).
fn paper_valence(n: usize) -> Result<()> {
    if n < 3 || n == 4 {
        return Err(Error::Unsupported(format!(
            "the paper's bi-5 guide coordinates need a valence n >= 3, n != 4 (got {n})"
        )));
    }
    Ok(())
}

/// The central Bloch vectors of valence `n`: frequencies and the matrix `V` whose column `q`
/// holds the central BB coefficients (in [`CENTRAL`] order) of `q o L_0`, `q` in
/// `1, z, zbar, z zbar, z^2, zbar^2`.
pub(crate) fn central_basis(n: usize) -> ([usize; 6], DMatrix<C64>) {
    let z = zeta(n, 1);
    let c = C64::new(cos_n(n), 0.0);
    let one = C64::new(1.0, 0.0);
    let zero = C64::new(0.0, 0.0);
    // (f, f_u, f_v, f_uu, f_uv, f_vv) at the origin.
    let jets = [
        [one, zero, zero, zero, zero, zero],
        [zero, one, z, zero, zero, zero],
        [zero, one, z.conj(), zero, zero, zero],
        [zero, zero, zero, one * 2.0, c * 2.0, one * 2.0],
        [zero, zero, zero, one * 2.0, z * 2.0, z * z * 2.0],
        [
            zero,
            zero,
            zero,
            one * 2.0,
            z.conj() * 2.0,
            (z * z).conj() * 2.0,
        ],
    ];
    let mut v = DMatrix::zeros(6, 6);
    for (q, [f, fu, fv, fuu, fuv, fvv]) in jets.into_iter().enumerate() {
        let b = [
            f,
            f + fu / 5.0,
            f + fu * 0.4 + fuu / 20.0,
            f + fv / 5.0,
            f + (fu + fv) / 5.0 + fuv / 25.0,
            f + fv * 0.4 + fvv / 20.0,
        ];
        for (k, x) in b.into_iter().enumerate() {
            v[(k, q)] = x;
        }
    }
    let freq = [0, 1 % n, n - 1, 0, 2 % n, (n - 2) % n];
    (freq, v)
}

/// Sector 0 of the Bloch guide of frequency `w` with central coefficients `cc`, free
/// coefficients `free` and kernel amplitude `kernel` of `g^0_12`, and the deviation of
/// (3) from `cc` (zero when `cc` is a central vector of frequency `w`).
fn bloch_sector(
    n: usize,
    w: usize,
    cc: &[C64; 6],
    free: &[C64; 18],
    kernel: C64,
) -> (Sector<C64>, f64) {
    let c = cos_n(n);
    let z = zeta(n, w);
    let zero = C64::default();
    let mut g: Sector<C64> = [[zero; 6]; 6];
    for (k, &(i, j)) in CENTRAL.iter().enumerate() {
        g[i][j] = cc[k];
    }
    for (b, &(i, j)) in FREE_SECTOR.iter().enumerate() {
        g[i][j] = free[b];
    }
    let scaled = |g: &Sector<C64>, f: C64| g.map(|row| row.map(|x| x * f));
    // (3) from sector -1 must give sector 0 back.
    let back = central_next(c, &scaled(&g, z.conj()));
    let defect = CENTRAL
        .iter()
        .zip(back)
        .map(|(&(i, j), x)| (x - g[i][j]).norm())
        .fold(0.0, f64::max);
    // (4): (zeta^w + 2 c) x_0 = r_0; the pseudo-inverse's zero at the singular frequency.
    let r = rhs4(c, &g, &scaled(&g, z));
    let mu = z + 2.0 * c;
    g[1][2] = if mu.norm() <= 1e-10 { zero } else { r / mu } + kernel;
    // Appendix A: ray 0 (sector 0 acute), ray 1 (sector 0 grave) = zeta^w ray 0.
    let (p30, p32a, grave, acute) = appendix_a(c, &g, &scaled(&g, z.conj()));
    g[3][0] = p30;
    g[3][2] = p32a;
    for (k, i) in [3usize, 4, 5].into_iter().enumerate() {
        g[i][1] = acute[k];
        g[1][i] = grave[k] * z;
    }
    for i in 3..6 {
        g[0][i] = g[i][0] * z;
    }
    (g, defect)
}

/// Guided subdivision's local matrix (bi-5 guide in the paper's coordinates, valence `n != 4`)
/// held as its Fourier blocks in the Bloch basis (see the module documentation).
#[derive(Debug, Clone)]
pub struct GuidedBlocks {
    scheme: String,
    n: usize,
    /// Central coordinates of `P` (6, or 7 with the kernel coordinate).
    centre: usize,
    /// `V`, and its inverse.
    v: DMatrix<C64>,
    vinv: DMatrix<C64>,
    /// Per frequency, the central Bloch vectors of the block (in order).
    members: Vec<Vec<usize>>,
    /// The blocks: central Bloch coordinates of the frequency first, then 18 sector ones.
    blocks: Vec<DMatrix<C64>>,
    /// Largest leakage (central components at other frequencies, or (3) not closing).
    leakage: f64,
}

impl GuidedBlocks {
    /// The blocks of the bi-5 guide's matrix at valence `n` and contraction `lambda`.
    ///
    /// # Errors
    /// Valences below 3 and 4 (the paper's coordinates divide by `cos(2 pi / n)`).
    pub fn new(scheme: impl Into<String>, n: usize, lambda: f64) -> Result<GuidedBlocks> {
        paper_valence(n)?;
        let (f6, v) = central_basis(n);
        let vinv = v
            .clone()
            .try_inverse()
            .ok_or_else(|| Error::Unsupported(format!("valence {n}: no central Bloch basis")))?;
        let mut freq = f6.to_vec();
        // The kernel coordinate: kv_s = amp zeta^(w s).
        let kernel = match n {
            3 => Some((0, 1.0 / 3f64.sqrt())),
            6 => Some((3, 1.0 / 6f64.sqrt())),
            _ => None,
        };
        if let Some((w, _)) = kernel {
            freq.push(w);
        }
        let centre = freq.len();
        let mut members = vec![Vec::new(); n];
        for (j, &w) in freq.iter().enumerate() {
            members[w].push(j);
        }
        let restrict = {
            let s = crate::bezier::bern::subsegment(5, 0.0, lambda);
            crate::bezier::bern::kron(&s, &s)
        };
        let zero = C64::default();
        let mut leakage: f64 = 0.0;
        let mut blocks = Vec::with_capacity(n);
        for (w, mem) in members.iter().enumerate() {
            let k = mem.len() + 18;
            let mut b = DMatrix::<C64>::zeros(k, k);
            for col in 0..k {
                let (mut cc, mut free, mut kern) = ([zero; 6], [zero; 18], zero);
                match mem.get(col) {
                    Some(&j) if j < 6 => cc = std::array::from_fn(|r| v[(r, j)]),
                    Some(_) => kern = C64::new(kernel.map_or(0.0, |k| k.1), 0.0),
                    None => free[col - mem.len()] = C64::new(1.0, 0.0),
                }
                let (g, defect) = bloch_sector(n, w, &cc, &free, kern);
                leakage = leakage.max(defect);
                let flat = DVector::from_iterator(36, g.iter().flatten().copied());
                let h = restrict.map(|x| C64::new(x, 0.0)) * flat;
                let central = DVector::from_iterator(6, CENTRAL.iter().map(|&(i, j)| h[6 * i + j]));
                let a = &vinv * central;
                for q in 0..6 {
                    match mem.iter().position(|&j| j == q) {
                        Some(row) => b[(row, col)] = a[q],
                        None => leakage = leakage.max(a[q].norm()),
                    }
                }
                if let (Some(row), Some((_, amp))) = (mem.iter().position(|&j| j == 6), kernel) {
                    b[(row, col)] = h[6 + 2] * (n as f64 * amp);
                }
                for (x, &(i, j)) in FREE_SECTOR.iter().enumerate() {
                    b[(mem.len() + x, col)] = h[6 * i + j];
                }
            }
            blocks.push(b);
        }
        Ok(GuidedBlocks {
            scheme: scheme.into(),
            n,
            centre,
            v,
            vinv,
            members,
            blocks,
            leakage,
        })
    }

    /// The block of frequency `w` (central Bloch coordinates of that frequency first).
    pub fn block(&self, w: usize) -> &DMatrix<C64> {
        &self.blocks[w % self.n]
    }

    /// Largest leakage of the Bloch basis (central components outside a block's frequency,
    /// (3) not closing around the vertex): rounding error when the derivation holds.
    pub fn leakage(&self) -> f64 {
        self.leakage
    }

    /// Component of `P` coordinate `i` along row `r` of block `w`'s basis.
    fn component(&self, i: usize, w: usize, r: usize) -> C64 {
        let (c, mem) = (self.centre, &self.members[w]);
        if i >= c {
            let (s, x) = ((i - c) / 18, (i - c) % 18);
            return if r == mem.len() + x {
                zeta(self.n, w * s)
            } else {
                C64::default()
            };
        }
        match mem.get(r) {
            Some(&j) if j < 6 && i < 6 => self.v[(i, j)],
            Some(&6) if i == 6 => C64::new(1.0, 0.0),
            _ => C64::default(),
        }
    }

    /// Coordinate along column `col` of block `w` of the unit vector of `P` coordinate `j`.
    fn coordinate(&self, j: usize, w: usize, col: usize) -> C64 {
        let (c, mem) = (self.centre, &self.members[w]);
        if j >= c {
            let (t, y) = ((j - c) / 18, (j - c) % 18);
            return if col == mem.len() + y {
                zeta(self.n, w * t).conj() / self.n as f64
            } else {
                C64::default()
            };
        }
        match mem.get(col) {
            Some(&q) if q < 6 && j < 6 => self.vinv[(q, j)],
            Some(&6) if j == 6 => C64::new(1.0, 0.0),
            _ => C64::default(),
        }
    }
}

impl LocalOperator for GuidedBlocks {
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
        18
    }

    fn size(&self) -> usize {
        self.centre + 18 * self.n
    }

    /// The dense path's measure ([`crate::schemes::local::LocalMatrix::rotation_defect`]) in
    /// the paper's coordinates, whose central coordinates are not fixed by the rotation: the
    /// sector-to-sector part is circulant by construction, the central rows and columns are
    /// read off the blocks of the frequencies that have central vectors.
    fn rotation_defect(&self) -> f64 {
        let (c, n) = (self.centre, self.n);
        let mut d: f64 = 0.0;
        for k in 0..c {
            for x in 0..18 {
                let (col0, row0) = (self.entry(c + x, k), self.entry(k, c + x));
                for s in 1..n {
                    let i = c + 18 * s + x;
                    d = d.max((self.entry(i, k) - col0).abs());
                    d = d.max((self.entry(k, i) - row0).abs());
                }
            }
        }
        d
    }

    /// `sum_w sum_(r, col) component(i) B_w[r, col] coordinate(j)`, over the frequencies
    /// with central vectors when `i` or `j` is central.
    fn entry(&self, i: usize, j: usize) -> f64 {
        let c = self.centre;
        let all: Vec<usize> = if i < c || j < c {
            (0..self.n)
                .filter(|&w| !self.members[w].is_empty())
                .collect()
        } else {
            (0..self.n).collect()
        };
        let mut z = C64::default();
        for w in all {
            let b = &self.blocks[w];
            for col in 0..b.ncols() {
                let a = self.coordinate(j, w, col);
                if a == C64::default() {
                    continue;
                }
                for r in 0..b.nrows() {
                    let p = self.component(i, w, r);
                    if p != C64::default() {
                        z += p * b[(r, col)] * a;
                    }
                }
            }
        }
        z.re
    }

    fn eigenvalues(&self) -> Vec<C64> {
        self.blocks.iter().flat_map(complex_eigenvalues).collect()
    }

    fn spectrum(&self) -> Spectrum {
        spectrum_of(&self.eigenvalues())
    }

    /// None, like the dense matrix in the paper's coordinates: the report's blocks are those
    /// of a matrix whose central points the rotation fixes (see the module documentation for
    /// the blocks of this one, [`GuidedBlocks::block`]).
    fn fourier_blocks(&self) -> Result<Vec<FourierBlock>> {
        Err(Error::Unsupported(format!(
            "{} at valence {}: the central coordinates are not fixed by the rotation; no \
             Fourier blocks of the sector-periodic form",
            self.scheme, self.n
        )))
    }

    fn left_eigenvectors(&self, value: f64) -> Vec<DVector<f64>> {
        let (c, n) = (self.centre, self.n);
        let lift = |w: usize, u: &DVector<C64>| {
            let mut full = DVector::<C64>::zeros(c + 18 * n);
            let mem = &self.members[w];
            for (r, &q) in mem.iter().enumerate() {
                if q < 6 {
                    for k in 0..6 {
                        full[k] += u[r] * self.vinv[(q, k)];
                    }
                } else {
                    full[6] += u[r];
                }
            }
            for s in 0..n {
                let z = zeta(n, w * s).conj() / n as f64;
                for x in 0..18 {
                    full[c + 18 * s + x] = u[mem.len() + x] * z;
                }
            }
            full
        };
        left_eigenvectors_by_blocks(n, value, |w| self.blocks[w].clone(), lift)
    }

    fn characteristic_points(&self) -> Result<(Vec<[f64; 3]>, f64)> {
        Err(Error::Unsupported(format!(
            "{} at valence {}: the characteristic ring is sampled from the planar guide",
            self.scheme, self.n
        )))
    }
}

/// The frequency-0 Bloch guides (sector 0) of the central vectors of frequency 0 and of the
/// sector coordinates, as columns (`36 x k`), with `V`'s first row on those central vectors
/// (the weights of the central point `g^0_00`): the frequency-0 part of the guide space, for
/// the limit point's fit ([`super::rings`]).
pub(crate) fn frequency_zero_guides(n: usize) -> Result<(DMatrix<f64>, Vec<f64>)> {
    paper_valence(n)?;
    let (freq, v) = central_basis(n);
    // The central vectors of frequency 0, and the kernel coordinate of (4) at n = 3.
    let mut mem: Vec<usize> = (0..6).filter(|&j| freq[j] == 0).collect();
    if n == 3 {
        mem.push(6);
    }
    let zero = C64::default();
    let k = mem.len() + 18;
    let mut g = DMatrix::zeros(36, k);
    let mut point = vec![0.0; k];
    for col in 0..k {
        let (mut cc, mut free, mut kern) = ([zero; 6], [zero; 18], zero);
        match mem.get(col) {
            Some(&j) if j < 6 => {
                cc = std::array::from_fn(|r| v[(r, j)]);
                point[col] = v[(0, j)].re;
            }
            Some(_) => kern = C64::new(1.0 / 3f64.sqrt(), 0.0),
            None => free[col - mem.len()] = C64::new(1.0, 0.0),
        }
        let (s, _) = bloch_sector(n, 0, &cc, &free, kern);
        for (r, x) in s.iter().flatten().enumerate() {
            g[(r, col)] = x.re;
        }
    }
    Ok((g, point))
}
