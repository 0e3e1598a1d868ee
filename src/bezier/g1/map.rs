//! The cap as one fixed linear map per `(n, layout, segment degrees, cap degree)`: built once
//! ([`CapMap::new`], cached by [`cap_map`]), applied to a hole's data vector
//! ([`CapMap::apply`]), and exposed as a matrix ([`CapMap::matrix`]) so that a stencil table can
//! express every cap coefficient in the ring's coefficients.

use super::centre::centre_unknowns;
pub(super) use super::choose::Key;
use super::choose::hole_size;
use super::compat::compatibility;
use super::conversion::Conversion;
use super::hole::{Degrees, Fan, Hole, Layout};
use super::system::{QuadData, cidx, conditions, dense, patch_energy};
use crate::bezier::BezierPatch;
use crate::error::{Error, Result};
use crate::geom::{add, axpy};
use crate::stencil::StencilTable;
use nalgebra::DMatrix;

/// Relative eigenvalue threshold (of `a^T a`) for ranks, pseudo-inverses and null spaces.
const EIG_TOL: f64 = 1e-9;

/// Order `k` of the fairness functional `F_k` whose sum over the cap patches the free
/// coefficients minimise (see [`super`] for the measured comparison of `F_2`, `F_3`, `F_4`).
pub const FAIRNESS_ORDER: usize = 4;

/// Certificate level below which a map counts as certified (consistent conditions measure
/// about 1e-14, inconsistent ones 1e-2 and more).
pub const CERTIFIED: f64 = 1e-10;

/// What the cap satisfies at the centre besides G^1.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Centre {
    /// [`Centre::QuadraticJet`] where it is certified at the lowest degree certified for
    /// [`Centre::TangentPlane`] (or at the requested degree), else [`Centre::TangentPlane`]: the
    /// lowest degree first, curvature continuity at the centre when it costs no degree.
    #[default]
    Auto,
    /// Only the centre point and the tangent plane (spoke tangents) are prescribed.
    TangentPlane,
    /// In addition, one quadratic expansion for all sectors (curvature continuous at the
    /// centre), its Hessian a free parameter (see [`super`]).
    QuadraticJet,
}

/// A certified G^1 cap map.
#[derive(Debug, Clone)]
pub struct CapMap {
    /// Valence.
    pub n: usize,
    /// Pieces per sector side (`m` of [`Layout::Split`], else 1): `m^2` patches per sector.
    pub pieces: usize,
    /// Layout of the input holes.
    pub layout: Layout,
    /// Degrees of the input segments.
    pub degrees: Degrees,
    /// Bi-degree of the cap patches.
    pub degree: usize,
    /// Spoke-end twist of the G^1 weight.
    pub kappa: f64,
    /// Spoke-end value `w(1)` of the G^1 weight.
    pub w1: f64,
    /// The condition at the centre.
    pub centre: Centre,
    /// The shape of the conditions: closed, open, or an open fan whose boundary spokes are the
    /// Hermite cubics of a crease ([`Fan::Crease`]) or a dart ([`Fan::Dart`]).
    pub fan: Fan,
    /// Consistency certificate: the largest residual of the cap conditions over a basis of all
    /// data that satisfy the ring's compatibility conditions (0 up to rounding when the cap
    /// exists for every compatible ring; see [`super`]).
    pub certificate: f64,
    /// Number of free parameters left after all conditions (fixed by the energy).
    pub free_parameters: usize,
    /// `n m^2 (d + 1)^2 x data` weights: cap coefficient `cidx(p, i, j)` from the hole's data
    /// vector.
    matrix: DMatrix<f64>,
    /// Labels of the compatibility rows (`sparse_compat`) over the hole's data vector.
    compat_labels: Vec<String>,
    /// `matrix` and the compatibility rows as sparse rows (zeros skipped, columns in order):
    /// what [`CapMap::apply`] and [`CapMap::compatibility_defect`] sum, without the strided
    /// reads of a column-major matrix by rows (the hot path of a mesh with thousands of caps).
    sparse: StencilTable,
    sparse_compat: StencilTable,
}

/// The rows of `m` as a stencil table over its columns (zeros skipped).
fn sparse_rows(m: &DMatrix<f64>) -> StencilTable {
    // nalgebra stores by columns: the transpose's storage is `m` by rows
    StencilTable::from_dense(m.nrows(), m.ncols(), m.transpose().as_slice())
}

/// Row `r` of `t` applied to `data` (`sum w * data[c]` in column order).
#[inline]
fn row_point(t: &StencilTable, r: usize, data: &[crate::geom::Point]) -> crate::geom::Point {
    let (cols, weights) = t.row(r);
    cols.iter()
        .zip(weights)
        .fold([0.0; 3], |acc, (&c, &w)| axpy(acc, w, data[c as usize]))
}

/// Pseudo-inverse and null space of `a` (`rows x cols`) from the symmetric eigen-decomposition
/// of `a^T a` by `faer`. (Both SVDs at hand were found wanting on these systems: nalgebra's
/// leaves residuals of 1e-10, faer's reports a spurious singular value `2^-13` for
/// `n = 8, d = 5` where LAPACK finds none; the eigenvalues of `a^T a` agree with LAPACK's
/// squared singular values.) The conditions are well scaled (singular values between about
/// 0.1 and 30), so squaring costs little: a gap of at least 1e-3 separates the zero eigenvalues
/// (below `1e-12` of the largest) from the others, tested.
fn pinv_and_null(a: &DMatrix<f64>) -> Result<(DMatrix<f64>, DMatrix<f64>)> {
    let c = a.ncols();
    let ata = a.transpose() * a;
    let fa = faer::Mat::<f64>::from_fn(c, c, |i, j| ata[(i, j)]);
    drop(ata); // the eigen-decomposition holds two more c x c matrices
    let eig = fa.self_adjoint_eigen(faer::Side::Lower).map_err(|e| {
        Error::Unsupported(format!("eigen-decomposition of the cap conditions: {e:?}"))
    })?;
    let (v, ev) = (eig.U(), eig.S().column_vector());
    let emax = (0..c).map(|l| ev[l].abs()).fold(0.0, f64::max);
    let tol = EIG_TOL * emax.max(1.0);
    let (keep, null): (Vec<usize>, Vec<usize>) = (0..c).partition(|&l| ev[l] > tol);
    let vk = DMatrix::from_fn(c, keep.len(), |i, k| v[(i, keep[k])] / ev[keep[k]]);
    let vk2 = DMatrix::from_fn(c, keep.len(), |i, k| v[(i, keep[k])]);
    let pinv = vk * vk2.transpose() * a.transpose();
    let z = DMatrix::from_fn(c, null.len(), |i, k| v[(i, null[k])]);
    Ok((pinv, z))
}

/// The matrix that raises every canonical curve from degree `from` to degree `to` (`m` pieces
/// per sector side).
fn raise_canonical(n: usize, m: usize, from: usize, to: usize) -> DMatrix<f64> {
    let (qf, qt) = (QuadData { d: from, m }, QuadData { d: to, m });
    let mut mat = DMatrix::zeros(qt.len(n), qf.len(n));
    for k in 0..3 {
        mat[(k, k)] = 1.0;
    }
    // univariate raising from -> to
    let mut r = DMatrix::<f64>::identity(from + 1, from + 1);
    for p in from..to {
        let step = DMatrix::from_fn(p + 2, p + 1, |i, j| {
            let pf = (p + 1) as f64;
            if j == i {
                1.0 - i as f64 / pf
            } else if j + 1 == i {
                i as f64 / pf
            } else {
                0.0
            }
        });
        r = step * r;
    }
    for s in 0..n {
        for k in 0..m {
            for (to_off, from_off) in [
                (qt.a(s, k, 0), qf.a(s, k, 0)),
                (qt.ca(s, k, 0), qf.ca(s, k, 0)),
                (qt.b(s, k, 0), qf.b(s, k, 0)),
                (qt.cb(s, k, 0), qf.cb(s, k, 0)),
            ] {
                mat.view_mut((to_off, from_off), (to + 1, from + 1))
                    .copy_from(&r);
            }
        }
    }
    mat
}

/// The conditions of one cap shape solved for their least-norm solution and null space, with
/// the certificate: everything of [`CapMap::with_fan`] but the fairness energy. The degree
/// search ([`lowest_certified_fan`]) needs only the certificate, so it stops here
/// ([`certificate`]); [`Solved::finish`] adds the energy and the matrix for the map that is
/// used. (On a `3 x 3` split hole of valence 10 the energy and the final products are about a
/// third of a map's time, and the search builds two or three maps it does not use.)
pub(super) struct Solved {
    pub(super) key: Key,
    kappa: f64,
    w1: f64,
    pm: usize,
    nx: usize,
    nu: usize,
    free: Vec<usize>,
    /// Rows of the unknowns set directly by data (`nu x nq`), zero elsewhere.
    a_fixed: DMatrix<f64>,
    /// The least-norm solution of the remaining rows for the free unknowns (`free x nq`).
    y_p: DMatrix<f64>,
    /// Null space of the remaining rows over the free unknowns.
    z: DMatrix<f64>,
    /// Canonical data from the hole's data vector.
    q: DMatrix<f64>,
    /// The compatibility rows over the canonical data, and their labels.
    gm: DMatrix<f64>,
    compat_labels: Vec<String>,
    pub(super) certificate: f64,
}

impl Solved {
    pub(super) fn new((n, layout, degrees, degree, centre, fan): Key) -> Result<Solved> {
        let fan = fan.on(layout);
        if n < layout.min_sectors_of(fan) {
            return Err(Error::InvalidArgument(format!(
                "a G^1 cap needs at least {} sectors, got {n}",
                layout.min_sectors_of(fan)
            )));
        }
        let conv = Conversion::new(n, layout, degrees);
        if degree < conv.degree.max(3) {
            return Err(Error::InvalidArgument(format!(
                "cap degree {degree} is below the degree {} of the hole's quad data (or 3)",
                conv.degree
            )));
        }
        let d = degree;
        let wconv = DMatrix::from_row_slice(conv.rows, conv.cols, &conv.w);
        let pm = layout.pieces();
        let q = raise_canonical(n, pm, conv.degree, d) * wconv;
        let qd = QuadData { d, m: pm };
        let nq = qd.len(n);
        let np = n * pm * pm;
        let nx = np * (d + 1) * (d + 1);
        if centre == Centre::Auto {
            return Err(Error::InvalidArgument(
                "a cap map needs a definite centre condition (Auto is resolved by g1_cap_with)"
                    .into(),
            ));
        }
        let jet = centre == Centre::QuadraticJet;
        let ends = (conv.kappa, conv.w1);
        let nu = nx + centre_unknowns(n, fan, jet);
        let cond = conditions((n, fan), d, pm, ends, jet);
        // Unknowns set directly by a data row (the C^1 layers, the centre, the spoke tangents)
        // are eliminated exactly: their value is the mean of their defining rows (all equal for
        // compatible data), so C^1 to the ring holds to rounding. The other unknowns `y` solve
        // the remaining rows `E_y y = F_r q - E_r x_fixed(q)`.
        let mut def: Vec<Vec<usize>> = vec![Vec::new(); nu];
        let mut rest = Vec::new();
        for (r, row) in cond.e.iter().enumerate() {
            match row.as_slice() {
                [(x, w)] if *w == 1.0 => def[*x].push(r),
                _ => rest.push(r),
            }
        }
        let fixed: Vec<usize> = (0..nu).filter(|&x| !def[x].is_empty()).collect();
        let free: Vec<usize> = (0..nu).filter(|&x| def[x].is_empty()).collect();
        let fdense = dense(&cond.f, nq);
        let mut a_fixed = DMatrix::zeros(nu, nq); // rows of fixed unknowns only
        for &x in &fixed {
            let k = def[x].len() as f64;
            for &r in &def[x] {
                let row = fdense.row(r) / k;
                let add = a_fixed.row(x) + row;
                a_fixed.set_row(x, &add);
            }
        }
        let e_rest = dense(
            &rest.iter().map(|&r| cond.e[r].clone()).collect::<Vec<_>>(),
            nu,
        );
        let f_rest = DMatrix::from_fn(rest.len(), nq, |r, c| fdense[(rest[r], c)]);
        drop(fdense);
        let b = &f_rest - &e_rest * &a_fixed;
        drop(f_rest);
        let e_y = DMatrix::from_fn(rest.len(), free.len(), |r, k| e_rest[(r, free[k])]);
        drop(e_rest);
        let (e_pinv, z) = pinv_and_null(&e_y)?;
        let y_p = &e_pinv * &b; // free x nq
        // Certificate over the data satisfying the ring's compatibility conditions: the part
        // of `b` on them that `E_y` cannot reach, `(I - E_y E_y^+) b A`, evaluated as
        // `b A - E_y (E_y^+ (b A))` (the same value to rounding; the product `E_y E_y^+` was a
        // `rest x rest` matrix and the largest product of the whole map).
        let g = compatibility(n, fan, d, pm, ends);
        let gm = dense(&g.iter().map(|(_, r)| r.clone()).collect::<Vec<_>>(), nq);
        let (_, admissible) = pinv_and_null(&gm)?;
        let ba = &b * admissible;
        let resid = &ba - &e_y * (&e_pinv * &ba);
        let certificate = resid.amax();
        Ok(Solved {
            key: (n, layout, degrees, degree, centre, fan),
            kappa: conv.kappa,
            w1: conv.w1,
            pm,
            nx,
            nu,
            free,
            a_fixed,
            y_p,
            z,
            q,
            gm,
            compat_labels: g.into_iter().map(|(l, _)| l).collect(),
            certificate,
        })
    }

    /// The map: the free unknowns minimise the fairness energy of all patches over the null
    /// space.
    pub(super) fn finish(self) -> Result<CapMap> {
        let (n, layout, degrees, d, centre, fan) = self.key;
        let Solved {
            pm,
            nx,
            nu,
            free,
            a_fixed,
            y_p,
            z,
            ..
        } = self;
        // Fairness energy of every patch: block diagonal, one `(d + 1)^2` block per patch (the
        // centre unknowns have none); only its rows of the free unknowns are needed.
        let hp = patch_energy(d, FAIRNESS_ORDER);
        let m = (d + 1) * (d + 1);
        let h = |a: usize, c: usize| -> f64 {
            if a < nx && c < nx && a / m == c / m {
                hp[(a % m, c % m)]
            } else {
                0.0
            }
        };
        let h_yy = DMatrix::from_fn(free.len(), free.len(), |a, c| h(free[a], free[c]));
        let h_yf = DMatrix::from_fn(free.len(), nu, |a, c| h(free[a], c));
        let free_parameters = z.ncols();
        let y = if free_parameters > 0 {
            let mut zhz = z.transpose() * &h_yy * &z;
            // A tiny ridge keeps the minimiser unique if the energy vanishes on a free direction.
            let ridge = 1e-12 * zhz.diagonal().amax().max(1e-300);
            for k in 0..free_parameters {
                zhz[(k, k)] += ridge;
            }
            let chol = zhz.cholesky().ok_or_else(|| {
                Error::Unsupported(format!(
                    "valence {n}, degree {d}: the cap energy is not positive definite"
                ))
            })?;
            let g = z.transpose() * (&h_yy * &y_p + &h_yf * &a_fixed);
            &y_p - &z * chol.solve(&g)
        } else {
            y_p
        };
        let mut map = a_fixed;
        for (k, &x) in free.iter().enumerate() {
            map.set_row(x, &y.row(k));
        }
        let matrix = map.rows(0, nx) * &self.q;
        let compat = self.gm * self.q;
        Ok(CapMap {
            n,
            pieces: pm,
            layout,
            degrees,
            degree: d,
            kappa: self.kappa,
            w1: self.w1,
            certificate: self.certificate,
            free_parameters,
            centre,
            fan,
            sparse: sparse_rows(&matrix),
            sparse_compat: sparse_rows(&compat),
            matrix,
            compat_labels: self.compat_labels,
        })
    }
}

impl CapMap {
    /// Builds the map for valence `n`, layout, input segment degrees and cap bi-degree `degree`
    /// (at least the degree of the quad data, see [`Hole::to_quad_layout`], and at least 3).
    pub fn new(
        n: usize,
        layout: Layout,
        degrees: Degrees,
        degree: usize,
        centre: Centre,
    ) -> Result<CapMap> {
        CapMap::with_fan(n, layout, degrees, degree, centre, Fan::Closed)
    }

    /// [`CapMap::new`] for the holes of kind `fan` ([`Hole::fan`]; a closed layout is always
    /// [`Fan::Closed`], an open one at least [`Fan::Open`], [`Fan::on`]): a crease's or a
    /// dart's open fan has its boundary spokes the cubic Hermite interpolants of their end
    /// data, a dart's spokes span a full turn.
    pub fn with_fan(
        n: usize,
        layout: Layout,
        degrees: Degrees,
        degree: usize,
        centre: Centre,
        fan: Fan,
    ) -> Result<CapMap> {
        Solved::new((n, layout, degrees, degree, centre, fan))?.finish()
    }

    /// Whether the certificate shows that the cap exists for every compatible ring.
    pub fn is_certified(&self) -> bool {
        self.certificate < CERTIFIED
    }

    /// The weights: row `p (d + 1)^2 + i (d + 1) + j` gives coefficient `b_ij` of cap patch `p`
    /// (the sector `s`, or piece `(a, b)` of a split sector, `p = (s m + a) m + b`)
    /// as a combination of the entries of the hole's data vector ([`Hole::data`]); the same
    /// weights apply to x, y and z.
    pub fn matrix(&self) -> &DMatrix<f64> {
        &self.matrix
    }

    /// The largest violation of the ring's compatibility conditions by `hole`, relative to the
    /// hole's size, and the label of the condition.
    pub fn compatibility_defect(&self, hole: &Hole) -> (f64, String) {
        // the conditions vanish on translations: measured about the centre, to the rounding
        // of the hole's own size
        let data = hole.data_about_centre();
        let size = hole_size(hole);
        let mut worst = (0.0, String::new());
        for (r, label) in self.compat_labels.iter().enumerate() {
            let acc = row_point(&self.sparse_compat, r, &data);
            let v = crate::geom::norm(acc) / size;
            if v > worst.0 {
                worst = (v, label.clone());
            }
        }
        worst
    }

    /// The cap patches of a hole of this map's shape (one bi-`degree` patch per quad sector, or
    /// the `m x m` pieces of each split sector, row-major with `a` along `u`, in the
    /// conventions of [`super::hole`]).
    pub fn apply(&self, hole: &Hole) -> Result<Vec<BezierPatch>> {
        let (layout, degrees) = hole.layout()?;
        if hole.valence() != self.n || layout != self.layout || degrees != self.degrees {
            return Err(Error::InvalidArgument(format!(
                "hole of valence {} ({layout:?}, degrees {degrees:?}) given to the cap map of \
                 valence {} ({:?}, {:?})",
                hole.valence(),
                self.n,
                self.layout,
                self.degrees
            )));
        }
        // applied about the centre ([`Hole::data_about_centre`]: the map's error then scales
        // with the hole, not with its distance from the origin), the centre added back
        let data = hole.data_about_centre();
        let c = hole.centre;
        let d = self.degree;
        let m = (d + 1) * (d + 1);
        Ok((0..self.n * self.pieces * self.pieces)
            .map(|s| {
                let cps = (0..m)
                    .map(|k| add(c, row_point(&self.sparse, cidx(d, s, 0, 0) + k, &data)))
                    .collect();
                BezierPatch::new(d, d, cps)
            })
            .collect())
    }
}
