//! The G^2 guide `g` of guided subdivision (Section 3.1 and Appendix A of the paper): `n`
//! tensor-product sectors of degree bi-5 (or bi-4, bi-3, Section 6.1) over unit squares, joined
//! G^2 through the shear `L`.
//!
//! # Orientation
//!
//! Sector `k` uses fairsub's mesh chart: `g^k_ij` with `i` along `e_k` and `j` along `e_(k+1)`,
//! `e_k = (cos 2 pi k / n, sin 2 pi k / n)`; `L_k(u, v) = u e_k + v e_(k+1)` maps the unit square
//! onto the sector's parallelogram. At the ray `e_k` the paper's local pair is `f' = g^k` (acute)
//! and `f'' (u, v) = g^(k-1)(v, u)` (grave: the neighbour transposed, so that its `u` runs along
//! the common edge): `p'_ij = g^k_ij`, `p''_ij = g^(k-1)_ji`. With this indexing the paper's
//! rotationally-symmetric `p^k_12` is `g^k_12`.
//!
//! # Constraints (checked against `L` itself)
//!
//! `f'' = f' o rho` with `rho(u, v) = (u + 2 c v, -v)` is the reparametrisation that relates the
//! shear `L` to its reflection, `c = cos(2 pi / n)`. Differentiating once and twice along `v = 0`:
//!
//! * (1) `dv f' + dv f'' - 2 c du f' = 0`,
//! * (2) `dvv f'' - dvv f' + 4 c duv f' - 4 c^2 duu f' = 0`
//!
//! (the accents of (2) are lost in the text; this is the assignment that `L` and its reflection
//! satisfy and that makes (1)-(2) unbiased). They say exactly that `g o L^-1` is C^2 across every
//! ray: the guide is a piecewise polynomial in the plane, C^2 except at the centre.
//!
//! # The free set `P` (bi-5)
//!
//! Coordinates of [`GuideSpace::paper_bi5`], in this order: the six coefficients
//! `g^0_00, g^0_10, g^0_20, g^0_01, g^0_11, g^0_02` of the central quadratic expansion (the
//! paper's red bullets, `g^0_00` the central point), for `n = 3, 6` one more coordinate (the extra
//! free `p_12` direction), then per sector `k` the nine black bullets
//! `g^k_21, 22, 40, 50, 42, 52, 23, 24, 25` and the nine cyan bullets `g^k_ij`, `i, j = 3..5`.
//! That is `17 n + n* + 6` coordinates, the paper's count `17 n + n* + 5` plus the central point.
//! The other coefficients follow from
//!
//! * (3): the central expansion of sector `k` from that of sector `k - 1`,
//! * (4): `p'_12 = p''_12 - 2c p''_21 + 2c p'_21 + c p''_01 + (3c - 4) p''_11 +
//!   4/5 c (4 - 3c) p_20 + (4 - 27/5 c + 4/5 c^2) p_10 + c/5 (8c - 9) p_00` (accents
//!   reconstructed), i.e. the
//!   circulant system `g^(k+1)_12 + 2c g^k_12 = r_k`, singular exactly for `n = 3` (constant
//!   kernel) and `n = 6` (alternating kernel); fairsub takes the minimum-norm solution plus a free
//!   multiple of the unit kernel vector,
//! * Appendix A: `p_30, p'_32, p''_31, p''_41, p''_51` and, swapping the accents, `p'_31, p'_41,
//!   p'_51`, with one erratum ([`APPENDIX_A_ERRATUM`]).
//!
//! Accent reconstruction: every printed relation was tested, for every assignment of accents,
//! against the row space of the 12 local equations (1)-(2) in BB form (a symbolic computation
//! recorded in the module tests as numeric checks): the printed accents of (3) and of Appendix A
//! hold except for one term; (4) holds with the accents above.

use crate::bezier::bern::{bernstein_derivs, subsegment};
use crate::error::{Error, Result};
pub use crate::schemes::options::GuideDegree;
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;

/// The one correction Appendix A needs.
pub const APPENDIX_A_ERRATUM: &str = "Appendix A, p''_41: the last term reads c/(4 d1) (p'_52 - p''_52) \
(printed c/(4 d1) (p''_52 - p'_52)); with the printed accents the relation is not implied by (1)-(2)";

impl GuideDegree {
    /// The polynomial degree.
    pub fn degree(self) -> usize {
        match self {
            GuideDegree::Bi5 => 5,
            GuideDegree::Bi4 => 4,
            GuideDegree::Bi3 => 3,
        }
    }

    /// The paper's count of unconstrained coefficients (eigenfunctions) including the central
    /// point: `17 n + 6 + n*`, `9 n + 6 + n*`, `3 n + 6 + n*`.
    pub fn paper_count(self, n: usize) -> usize {
        let k = match self {
            GuideDegree::Bi5 => 17,
            GuideDegree::Bi4 => 9,
            GuideDegree::Bi3 => 3,
        };
        k * n + 6 + n_star(n)
    }
}

/// `n* = n + 1` for `n = 3, 6`, else `n`.
pub fn n_star(n: usize) -> usize {
    if n == 3 || n == 6 { n + 1 } else { n }
}

/// `c = cos(2 pi / n)`.
pub fn cos_n(n: usize) -> f64 {
    (2.0 * PI / n as f64).cos()
}

/// A linear space of G^2 guides at one valence, with coordinates.
#[derive(Debug, Clone)]
pub struct GuideSpace {
    /// Valence.
    pub n: usize,
    /// Degree of the sectors.
    pub degree: usize,
    /// `n (d + 1)^2 x dim`: column `k` holds the BB coefficients of coordinate `k`'s guide;
    /// coefficient `g^s_ij` is row [`GuideSpace::coeff`]`(s, i, j)`.
    pub basis: DMatrix<f64>,
    /// `dim x n (d + 1)^2`: the coordinates of a guide of the space (a left inverse of `basis`).
    pub extract: DMatrix<f64>,
    /// Number of leading coordinates that are not per-sector (6, or 7 for n = 3, 6 with the
    /// paper's coordinates; all of them for a numeric basis).
    pub centre: usize,
}

impl GuideSpace {
    /// Row of coefficient `g^s_ij`.
    pub fn coeff(&self, s: usize, i: usize, j: usize) -> usize {
        let m = self.degree + 1;
        (s % self.n) * m * m + i * m + j
    }

    /// Dimension of the space.
    pub fn dim(&self) -> usize {
        self.basis.ncols()
    }

    /// Number of BB coefficients of all sectors.
    pub fn num_coeffs(&self) -> usize {
        self.basis.nrows()
    }

    /// The guide space of the given degree: the paper's coordinates for bi-5 (valences other than
    /// 4), an orthonormal basis of the null space of (1)-(2) otherwise.
    pub fn new(n: usize, degree: GuideDegree) -> Result<GuideSpace> {
        if n < 3 {
            return Err(Error::InvalidArgument(format!(
                "valence {n}: a valence is at least 3"
            )));
        }
        match degree {
            GuideDegree::Bi5 if n != 4 => Self::paper_bi5(n),
            _ => Self::numeric(n, degree.degree()),
        }
    }

    /// An orthonormal basis of all guides of degree `d` satisfying (1)-(2) at every ray.
    pub fn numeric(n: usize, d: usize) -> Result<GuideSpace> {
        let a = constraint_matrix(n, d);
        let ns = crate::linalg::null_space(&a, 1e-9);
        if ns.is_empty() {
            return Err(Error::Unsupported(format!(
                "no G^2 guide of degree {d} at valence {n}"
            )));
        }
        let basis = DMatrix::from_columns(&ns);
        let extract = basis.transpose();
        let centre = basis.ncols();
        Ok(GuideSpace {
            n,
            degree: d,
            basis,
            extract,
            centre,
        })
    }

    /// The bi-5 guide space in the paper's coordinates `P` (see the module documentation).
    /// Valence 4 (`c = 0`, where Appendix A divides by `c`) is not covered.
    pub fn paper_bi5(n: usize) -> Result<GuideSpace> {
        if n < 3 || n == 4 {
            return Err(Error::Unsupported(format!(
                "the paper's bi-5 guide coordinates need a valence n >= 3, n != 4 (got {n})"
            )));
        }
        let extra = usize::from(n == 3 || n == 6);
        let centre = 6 + extra;
        let dim = centre + 18 * n;
        let rows = 36 * n;
        let circ = Circulant::new(n);
        let mut basis = DMatrix::zeros(rows, dim);
        for k in 0..dim {
            let mut p = vec![0.0; dim];
            p[k] = 1.0;
            let g = expand_bi5(n, &p, &circ);
            basis.set_column(k, &DVector::from_vec(g));
        }
        let mut extract = DMatrix::zeros(dim, rows);
        let at = |s: usize, i: usize, j: usize| 36 * (s % n) + 6 * i + j;
        for (k, &(i, j)) in CENTRAL.iter().enumerate() {
            extract[(k, at(0, i, j))] = 1.0;
        }
        if let Some(kv) = &circ.kernel {
            for s in 0..n {
                extract[(6, at(s, 1, 2))] = kv[s];
            }
        }
        for s in 0..n {
            for (b, &(i, j)) in FREE_SECTOR.iter().enumerate() {
                extract[(centre + 18 * s + b, at(s, i, j))] = 1.0;
            }
        }
        Ok(GuideSpace {
            n,
            degree: 5,
            basis,
            extract,
            centre,
        })
    }

    /// The guide with coordinates `p` (one column per coordinate of the points: `p` is
    /// `dim x k`), as BB coefficients (`n (d + 1)^2 x k`).
    pub fn guide(&self, p: &DMatrix<f64>) -> DMatrix<f64> {
        &self.basis * p
    }

    /// The subdivision matrix `M` of the guide: `P -> P` of the guide restricted to
    /// `[0, lambda]^2` in every sector (de Casteljau at `u = lambda = v`). The restriction keeps
    /// (1)-(2) because `rho` is linear.
    pub fn step_matrix(&self, lambda: f64) -> DMatrix<f64> {
        let r = restriction(self.n, self.degree, lambda);
        &self.extract * (r * &self.basis)
    }

    /// The coordinates of the shear `L` itself as a planar guide (`x` and `y` columns): sector
    /// `k` is `L_k` raised to degree `d`.
    pub fn shear(&self) -> DMatrix<f64> {
        let g = shear_coeffs(self.n, self.degree);
        &self.extract * g
    }
}

/// BB coefficients of the shear `L` (`n (d+1)^2 x 2`): `g^k_ij = (i/d) e_k + (j/d) e_(k+1)`.
pub fn shear_coeffs(n: usize, d: usize) -> DMatrix<f64> {
    let m = d + 1;
    let mut g = DMatrix::zeros(n * m * m, 2);
    for k in 0..n {
        let a0 = 2.0 * PI * k as f64 / n as f64;
        let a1 = 2.0 * PI * (k + 1) as f64 / n as f64;
        for i in 0..m {
            for j in 0..m {
                let (x, y) = (i as f64 / d as f64, j as f64 / d as f64);
                let r = k * m * m + i * m + j;
                g[(r, 0)] = x * a0.cos() + y * a1.cos();
                g[(r, 1)] = x * a0.sin() + y * a1.sin();
            }
        }
    }
    g
}

/// Block-diagonal restriction of every sector to `[0, lambda]^2` (`n (d+1)^2` square).
pub fn restriction(n: usize, d: usize, lambda: f64) -> DMatrix<f64> {
    let s = subsegment(d, 0.0, lambda);
    let k = crate::bezier::bern::kron(&s, &s);
    let m = (d + 1) * (d + 1);
    let mut r = DMatrix::zeros(n * m, n * m);
    for sec in 0..n {
        r.view_mut((sec * m, sec * m), (m, m)).copy_from(&k);
    }
    r
}

/// The central coefficients of sector 0 in the order of `P`.
pub(crate) const CENTRAL: [(usize, usize); 6] = [(0, 0), (1, 0), (2, 0), (0, 1), (1, 1), (0, 2)];

/// Per-sector free coefficients: nine black, nine cyan.
pub(crate) const FREE_SECTOR: [(usize, usize); 18] = [
    (2, 1),
    (2, 2),
    (4, 0),
    (5, 0),
    (4, 2),
    (5, 2),
    (2, 3),
    (2, 4),
    (2, 5),
    (3, 3),
    (3, 4),
    (3, 5),
    (4, 3),
    (4, 4),
    (4, 5),
    (5, 3),
    (5, 4),
    (5, 5),
];

/// The circulant system `x_(k+1) + 2 c x_k = r_k` of (4) for `x_k = g^k_12`.
struct Circulant {
    /// Minimum-norm solution operator (pseudo-inverse), `n x n`.
    pinv: DMatrix<f64>,
    /// Unit kernel vector for `n = 3, 6`.
    kernel: Option<Vec<f64>>,
}

impl Circulant {
    fn new(n: usize) -> Circulant {
        let c = cos_n(n);
        let mut a = DMatrix::zeros(n, n);
        for k in 0..n {
            a[(k, (k + 1) % n)] += 1.0;
            a[(k, k)] += 2.0 * c;
        }
        let kernel = match n {
            3 => Some(vec![1.0 / 3f64.sqrt(); 3]),
            6 => Some(
                (0..6)
                    .map(|k| if k % 2 == 0 { 1.0 } else { -1.0 } / 6f64.sqrt())
                    .collect(),
            ),
            _ => None,
        };
        let pinv = a.pseudo_inverse(1e-10).expect("SVD of a small matrix");
        Circulant { pinv, kernel }
    }
}

/// A scalar the bi-5 guide's relations are evaluated in: `f64` for the guide of [`expand_bi5`],
/// [`crate::linalg::C64`] for the Bloch guides of [`super::fourier`] (one sector of a guide whose
/// sector `s` is `exp(2 pi i w s / n)` times sector 0).
pub(crate) trait Coef:
    Copy
    + Default
    + std::ops::Add<Output = Self>
    + std::ops::Sub<Output = Self>
    + std::ops::Neg<Output = Self>
    + std::ops::Mul<f64, Output = Self>
{
}
impl Coef for f64 {}
impl Coef for crate::linalg::C64 {}

/// The `6 x 6` BB coefficients of one bi-5 sector.
pub(crate) type Sector<T> = [[T; 6]; 6];

/// (3): the central expansion of a sector (in [`CENTRAL`] order) from that of the sector
/// before it, `prev` (the grave side of their common ray).
pub(crate) fn central_next<T: Coef>(c: f64, prev: &Sector<T>) -> [T; 6] {
    // acute = this sector, grave = the previous one transposed: p''_ij = prev[j][i].
    let gr = |i: usize, j: usize| prev[j][i];
    let (p00, p10, p20) = (gr(0, 0), gr(1, 0), gr(2, 0));
    let (p01, p11, p02) = (gr(0, 1), gr(1, 1), gr(0, 2));
    [
        p00,
        p10,
        p20,
        -p01 + p10 * (2.0 * c) + p00 * (2.0 * (1.0 - c)),
        -p11 + p20 * (1.6 * c) + p10 * (2.0 - 1.2 * c) - p00 * (0.4 * c),
        p02 - p11 * (5.0 * c)
            + p20 * (4.0 * c * c)
            + p01 * (5.0 * c - 4.0)
            + p10 * (c * (9.0 - 8.0 * c))
            + p00 * (4.0 - 9.0 * c + 4.0 * c * c),
    ]
}

/// (4)'s right-hand side `r_s` of `x_(s+1) + 2 c x_s = r_s` (`x_k = g^k_12`) at the ray between
/// sector `s` (`gs`, grave) and sector `s + 1` (`gt`, acute).
pub(crate) fn rhs4<T: Coef>(c: f64, gs: &Sector<T>, gt: &Sector<T>) -> T {
    gs[2][1]
        + gt[2][1] * (2.0 * c)
        + gs[1][0] * c
        + gs[1][1] * (3.0 * c - 4.0)
        + gt[2][0] * (0.8 * c * (4.0 - 3.0 * c))
        + gt[1][0] * (4.0 - 5.4 * c + 0.8 * c * c)
        + gt[0][0] * (c / 5.0 * (8.0 * c - 9.0))
}

/// Appendix A at one ray, between sector `e` (`ac`, acute) and sector `e - 1` (`gv`, grave):
/// `p_30` (shared), `p'_32` of the acute side, `p_31, p_41, p_51` of the grave side (the
/// printed formulas) and of the acute side (accents swapped), with the erratum
/// [`APPENDIX_A_ERRATUM`].
pub(crate) fn appendix_a<T: Coef>(
    c: f64,
    ac: &Sector<T>,
    gv: &Sector<T>,
) -> (T, T, [T; 3], [T; 3]) {
    let d1 = 4.0 + 8.0 * c + 5.0 * c * c;
    let d2 = 4.0 + 5.0 * c;
    let d3 = 36.0 + 45.0 * c + 5.0 * c * c;
    let d4 = 20.0 + 36.0 * c + 9.0 * c * c - 15.0 * c.powi(3);
    let d5 = 32.0 + 48.0 * c + 15.0 * c * c;
    let d6 = 16.0 + 36.0 * c + 36.0 * c * c + 15.0 * c.powi(3);
    let d7 = 32.0 + 64.0 * c + 72.0 * c * c + 48.0 * c.powi(3) + 15.0 * c.powi(4);
    let acu = |i: usize, j: usize| ac[i][j];
    let gr = |i: usize, j: usize| gv[j][i];
    let row = |i: usize| ac[i][0];
    let p30 = row(1) * (2.0 / 3.0)
        + row(2) * ((c - 5.0) / (3.0 * c))
        + (gr(2, 1) + acu(2, 1)) * (5.0 / (6.0 * c));
    let p32a = gr(3, 2) - (gr(1, 1) - acu(1, 1)) * (d6 / (3.0 * d1))
        + (gr(2, 1) - acu(2, 1)) * (d7 / (3.0 * c * d1))
        - (gr(2, 2) - acu(2, 2)) * (d6 / (3.0 * c * d1))
        - (gr(4, 2) - acu(4, 2)) * (c * d2 / (2.0 * d1))
        + (gr(5, 2) - acu(5, 2)) * (c * c / (2.0 * d1));
    // p_31, p_41, p_51 for the side `own` (grave: the printed formulas; acute: swapped).
    let side = |own: &dyn Fn(usize, usize) -> T, oth: &dyn Fn(usize, usize) -> T| {
        let p31 = row(0) * (2.0 * c / 15.0) + row(1) * (8.0 * c / 15.0) + own(1, 1) * (2.0 / 3.0)
            - row(2) * ((25.0 + 16.0 * c * c) / (15.0 * c))
            + own(2, 1) * ((1.0 + 2.0 * c) / (6.0 * c))
            + oth(2, 1) * (3.0 / (2.0 * c))
            + (own(2, 2) - oth(2, 2)) * (1.0 / (3.0 * c))
            + row(4) * (2.0 * c / 5.0);
        let p41 = (row(0) * (c * d2) - row(1) * d3 + own(1, 1) * (5.0 * d2))
            * (2.0 * c / (15.0 * d1))
            + row(2) * (4.0 * d4 / (15.0 * d1))
            - own(2, 1) * (d5 / (6.0 * d1))
            - oth(2, 1) * (c * (16.0 + 25.0 * c) / (6.0 * d1))
            + (own(2, 2) - oth(2, 2)) * (d2 / (3.0 * d1))
            + row(4) * (1.0 + 0.6 * c)
            + (own(4, 2) - oth(4, 2)) * (d2 / (4.0 * d1))
            + row(5) * (c / 5.0)
            // Erratum: printed (own - other).
            + (oth(5, 2) - own(5, 2)) * (c / (4.0 * d1));
        let p51 = (row(0) * c + row(1) * (3.0 * c - 5.0) + own(1, 1) * 5.0)
            * (2.0 * c * c / (3.0 * d1))
            + (row(2) * (-16.0 * c * c)
                + (own(2, 1) - oth(2, 1)) * (5.0 * (c - 4.0))
                + (own(2, 2) - oth(2, 2)) * 10.0)
                * (c / (6.0 * d1))
            - row(4) * c
            + (own(4, 2) - oth(4, 2)) * (5.0 * c / (4.0 * d1))
            + row(5) * (1.0 + c)
            + (own(5, 2) - oth(5, 2)) * ((4.0 + 3.0 * c) / (4.0 * d1));
        [p31, p41, p51]
    };
    let grave = side(&gr, &acu);
    let acute = side(&acu, &gr);
    (p30, p32a, grave, acute)
}

/// All `36 n` BB coefficients of the bi-5 guide with coordinates `p`.
fn expand_bi5(n: usize, p: &[f64], circ: &Circulant) -> Vec<f64> {
    let c = cos_n(n);
    let extra = usize::from(circ.kernel.is_some());
    let centre = 6 + extra;
    let mut g: Vec<Sector<f64>> = vec![[[0.0f64; 6]; 6]; n];
    // Central quadratic expansion of sector 0, then (3) around the vertex.
    for (k, &(i, j)) in CENTRAL.iter().enumerate() {
        g[0][i][j] = p[k];
    }
    for s in 1..n {
        let new = central_next(c, &g[s - 1]);
        for (k, &(i, j)) in CENTRAL.iter().enumerate() {
            g[s][i][j] = new[k];
        }
    }
    for s in 0..n {
        for (b, &(i, j)) in FREE_SECTOR.iter().enumerate() {
            g[s][i][j] = p[centre + 18 * s + b];
        }
    }
    // (4): x_(s+1) + 2c x_s = r_s at the ray e_(s+1) (acute s+1, grave s).
    let r: Vec<f64> = (0..n).map(|s| rhs4(c, &g[s], &g[(s + 1) % n])).collect();
    let x = &circ.pinv * DVector::from_vec(r);
    for s in 0..n {
        g[s][1][2] = x[s] + circ.kernel.as_ref().map_or(0.0, |kv| p[6] * kv[s]);
    }
    // Appendix A at every ray e_e: acute = sector e, grave = sector e-1 transposed.
    for e in 0..n {
        let q = (e + n - 1) % n;
        let (p30, p32a, grave, acute) = appendix_a(c, &g[e], &g[q]);
        g[e][3][0] = p30;
        g[q][0][3] = p30;
        g[e][3][2] = p32a;
        for (k, i) in [3usize, 4, 5].into_iter().enumerate() {
            g[q][1][i] = grave[k];
            g[e][i][1] = acute[k];
        }
        // The shared row j = 0 of sector e is column i = 0 of sector e-1.
        for i in 0..6 {
            let v = g[e][i][0];
            g[q][0][i] = v;
        }
    }
    let mut out = Vec::with_capacity(36 * n);
    for sec in &g {
        for row in sec {
            out.extend_from_slice(row);
        }
    }
    out
}

/// The local G^2 equations (1)-(2) and C^0 at every ray as rows over all `n (d + 1)^2`
/// coefficients, evaluated at `d + 2` points of each ray (a polynomial identity of degree `d`
/// holds when it holds at `d + 1` points).
pub fn constraint_matrix(n: usize, d: usize) -> DMatrix<f64> {
    let c = cos_n(n);
    let m = d + 1;
    let nc = n * m * m;
    let idx = |k: usize, i: usize, j: usize| (k % n) * m * m + i * m + j;
    let mut rows: Vec<Vec<f64>> = Vec::new();
    for e in 0..n {
        let q = e + n - 1;
        for p in 0..d + 2 {
            let u = (p as f64 + 0.5) / (d + 2) as f64;
            // Derivative d^a/du^a d^b/dv^b at (u, 0) of the acute (true) or grave side.
            let deriv = |acute: bool, a: usize, b: usize| -> Vec<f64> {
                let mut r = vec![0.0; nc];
                let bu = bernstein_derivs(d, a, u);
                let bv = bernstein_derivs(d, b, 0.0);
                for i in 0..m {
                    for j in 0..m {
                        let w = bu[i] * bv[j];
                        if acute {
                            r[idx(e, i, j)] += w;
                        } else {
                            r[idx(q, j, i)] += w;
                        }
                    }
                }
                r
            };
            let comb = |terms: &[(f64, Vec<f64>)]| -> Vec<f64> {
                let mut r = vec![0.0; nc];
                for (w, v) in terms {
                    for (x, y) in r.iter_mut().zip(v) {
                        *x += w * y;
                    }
                }
                r
            };
            rows.push(comb(&[
                (1.0, deriv(true, 0, 0)),
                (-1.0, deriv(false, 0, 0)),
            ]));
            rows.push(comb(&[
                (1.0, deriv(true, 0, 1)),
                (1.0, deriv(false, 0, 1)),
                (-2.0 * c, deriv(true, 1, 0)),
            ]));
            rows.push(comb(&[
                (1.0, deriv(false, 0, 2)),
                (-1.0, deriv(true, 0, 2)),
                (4.0 * c, deriv(true, 1, 1)),
                (-4.0 * c * c, deriv(true, 2, 0)),
            ]));
        }
    }
    DMatrix::from_fn(rows.len(), nc, |r, k| rows[r][k])
}

/// The measured G^2 defect of a guide given by its BB coefficients (`n (d+1)^2 x k`, any
/// number `k` of coordinates): the largest residual of C^0, (1) and (2) over 33 points of every
/// ray, relative to the largest coefficient.
pub fn g2_defect(n: usize, d: usize, g: &DMatrix<f64>) -> f64 {
    let c = cos_n(n);
    let m = d + 1;
    let scale = g.amax().max(1e-300);
    let mut worst: f64 = 0.0;
    for col in 0..g.ncols() {
        let coef = |k: usize, i: usize, j: usize| g[((k % n) * m * m + i * m + j, col)];
        for e in 0..n {
            let q = e + n - 1;
            for p in 0..=32 {
                let u = p as f64 / 32.0;
                let dv = |acute: bool, a: usize, b: usize| -> f64 {
                    let bu = bernstein_derivs(d, a, u);
                    let bv = bernstein_derivs(d, b, 0.0);
                    let mut s = 0.0;
                    for i in 0..m {
                        for j in 0..m {
                            let x = if acute { coef(e, i, j) } else { coef(q, j, i) };
                            s += bu[i] * bv[j] * x;
                        }
                    }
                    s
                };
                let r0 = dv(true, 0, 0) - dv(false, 0, 0);
                let r1 = dv(true, 0, 1) + dv(false, 0, 1) - 2.0 * c * dv(true, 1, 0);
                let r2 = dv(false, 0, 2) - dv(true, 0, 2) + 4.0 * c * dv(true, 1, 1)
                    - 4.0 * c * c * dv(true, 2, 0);
                worst = worst.max(r0.abs()).max(r1.abs()).max(r2.abs());
            }
        }
    }
    worst / scale
}
