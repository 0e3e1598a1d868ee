//! fairsub's initial quadratic expansion `qas-fit` and the eigenvectors it rests on, for any
//! QAS+ tables (printed or derived): the expansion eigenvectors of a rule, its characteristic
//! vectors, the fit stencils and the local vector from a c-net.

use super::{Qas, num_sources, q_index, quadratic_bb};
use crate::error::{Error, Result};
use crate::schemes::eg;
use crate::stencil::{Stencil, StencilTable};

/// The eigenvectors of QAS+ (C^2 `q`, `lambda = 1/2`) of the printed tables at valence `n`
/// ([`Qas::expansion_eigenvectors`]).
pub fn expansion_eigenvectors(n: usize) -> Result<Vec<Vec<f64>>> {
    Qas::new(n)?.expansion_eigenvectors()
}

/// The characteristic map's local vectors of the printed tables
/// ([`Qas::characteristic_vectors`]).
pub fn characteristic_vectors(n: usize) -> Result<[Vec<f64>; 2]> {
    Qas::new(n)?.characteristic_vectors()
}

/// `qas-fit` of the printed tables at valence `n` ([`Qas::fit_stencils`]).
pub fn fit_stencils(n: usize) -> Result<Vec<Stencil>> {
    Qas::new(n)?.fit_stencils()
}

/// The local vector from the c-net with the printed tables at valence `n` ([`Qas::from_cnet`]).
pub fn from_cnet(n: usize) -> Result<StencilTable> {
    Qas::new(n)?.from_cnet()
}

impl Qas {
    /// The eigenvectors of QAS+ (C^2 `q`, `lambda = 1/2`) whose expansion parts are the
    /// monomials `x, y` (eigenvalue 1/2) and `x^2, x y, y^2` (eigenvalue 1/4) of the plane of
    /// the sector charts, with `p = 0`: their d-net parts solve `(M_dd - mu I) d = -M_dq q`. The
    /// first two are the characteristic map's d-nets. Returns the full local vectors in the
    /// order `x, y, x^2, xy, y^2`.
    pub fn expansion_eigenvectors(&self) -> Result<Vec<Vec<f64>>> {
        let n = self.n();
        let st = self.step(0.5)?.step;
        let m = num_sources(n);
        let a = nalgebra::DMatrix::from_row_slice(m, m, &st.to_dense());
        let nd = 12 * n;
        let bases: [([f64; 2], [f64; 3], f64); 5] = [
            ([1.0, 0.0], [0.0; 3], 0.5),
            ([0.0, 1.0], [0.0; 3], 0.5),
            ([0.0; 2], [1.0, 0.0, 0.0], 0.25),
            ([0.0; 2], [0.0, 1.0, 0.0], 0.25),
            ([0.0; 2], [0.0, 0.0, 1.0], 0.25),
        ];
        let mut out = Vec::with_capacity(5);
        for (lin, quad, mu) in bases {
            let mut v = vec![0.0; m];
            for s in 0..n {
                let bb = quadratic_bb(n, s, 0.0, lin, quad);
                for k in 2..=6 {
                    v[q_index(n, s, k)] = bb[k - 1];
                }
            }
            let mdd = a.view((1, 1), (nd, nd)).into_owned()
                - nalgebra::DMatrix::<f64>::identity(nd, nd) * mu;
            let mut rhs = nalgebra::DVector::<f64>::zeros(nd);
            for r in 0..nd {
                let mut acc = 0.0;
                for j in 1 + nd..m {
                    acc += a[(1 + r, j)] * v[j];
                }
                rhs[r] = -acc;
            }
            let d = mdd
                .lu()
                .solve(&rhs)
                .ok_or_else(|| Error::Unsupported(format!("{mu} is an eigenvalue of M_d")))?;
            for r in 0..nd {
                v[1 + r] = d[r];
            }
            out.push(v);
        }
        Ok(out)
    }

    /// The characteristic map's local vectors (`x` and `y` of
    /// [`Qas::expansion_eigenvectors`]).
    pub fn characteristic_vectors(&self) -> Result<[Vec<f64>; 2]> {
        let mut e = self.expansion_eigenvectors()?;
        e.truncate(2);
        let y = e.pop().expect("two");
        let x = e.pop().expect("two");
        Ok([x, y])
    }

    /// fairsub's initial expansion `qas-fit` (the earlier QAS paper's steps S1-S3 are not in
    /// the corpus): with `p` fixed, the C^2 quadratic `Q = p + sum_b c_b b` over the monomials
    /// `b = x, y, x^2, xy, y^2` whose coefficients make `p + sum_b c_b D_b` the least-squares
    /// best approximation of the input d-net, `D_b` the d-net part of these rules' own
    /// eigenvector for `b` ([`Qas::expansion_eigenvectors`]). A d-net that the rules would
    /// produce from a quadratic expansion is reproduced exactly; control nodes are compared with
    /// control nodes, so the fit has no bias from nodes lying off the surface. Returns the
    /// stencils of `q_k^s` over the sources `(p, d-net)` (rows `5 s + k - 2`): the fit is
    /// linear in the data.
    pub fn fit_stencils(&self) -> Result<Vec<Stencil>> {
        let n = self.n();
        let eig = self.expansion_eigenvectors()?;
        let nd = 12 * n;
        let mut b = nalgebra::DMatrix::<f64>::zeros(nd, 5);
        for r in 0..nd {
            for (c, v) in eig.iter().enumerate() {
                b[(r, c)] = v[1 + r];
            }
        }
        let btb = b.transpose() * &b;
        let inv = btb
            .try_inverse()
            .ok_or_else(|| Error::Unsupported("the expansion eigenvectors are dependent".into()))?;
        let g = inv * b.transpose(); // 5 x nd
        // coef_c = sum_r g[c][r] (d_r - p).
        let coef: Vec<Stencil> = (0..5)
            .map(|c| {
                let mut st = Stencil::new();
                for r in 0..nd {
                    st.add(1 + r, g[(c, r)]);
                    st.add(0, -g[(c, r)]);
                }
                st.merged()
            })
            .collect();
        let mut out = Vec::with_capacity(5 * n);
        for s in 0..n {
            for k in 2..=6 {
                let mut st = Stencil::point(0);
                for (c, v) in eig.iter().enumerate() {
                    st.add_scaled(&coef[c], v[q_index(n, s, k)]);
                }
                out.push(st.merged());
            }
        }
        Ok(out)
    }

    /// Stencils of the local vector `(p, d-net, q)` from the c-net of the valence (layout of
    /// [`crate::schemes::eg::from_cnet`]): `p` by the EG limit-point rule (3), `d = R c`, and
    /// `q` by [`Qas::fit_stencils`].
    pub fn from_cnet(&self) -> Result<StencilTable> {
        let n = self.n();
        let egt = eg::from_cnet(n)?;
        let fit = self.fit_stencils()?;
        let mut t = StencilTable::with_capacity(egt.num_sources(), num_sources(n), 40);
        t.extend_rows(&egt);
        for st in fit {
            let mut out = Stencil::new();
            for &(i, w) in st.entries() {
                out.add_scaled(&egt.stencil(i as usize), w);
            }
            t.push(out);
        }
        Ok(t)
    }
}
