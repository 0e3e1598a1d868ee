//! The bi-4 (2 x 2) and bi-3 (3 x 3) macro-patch variants of guided subdivision (Section 6.2 of
//! the paper), as fairsub derives them: the figures (17, 18) are lost and the text says only
//! that "2 x 2 macro patches for degree bi-4 and 3 x 3 macro patches for degree bi-3 ... enforce
//! the C^2 prolongation between rings" and that the surfaces are curvature bounded at the centre.
//!
//! # Derivation (`guided-bi4-macro`, `guided-bi3-macro`)
//!
//! A bi-5 ring patch is fixed by its four corner 2-jets (3 x 3 BB coefficients at each corner).
//! Per variable, the spaces
//!
//! * `S_3`: C^2 cubic splines on `[0, 1]` with knots `1/3, 2/3` (3 pieces), and
//! * `S_4`: C^3 quartic splines with the knot `1/2` (2 pieces; fairsub's choice: C^2 alone leaves
//!   one coefficient per variable free, C^3 fixes it),
//!
//! have dimension 6, and a spline of either is fixed by its 2-jets at `0` and `1`, exactly like a
//! quintic. So the map [`MacroKind::from_quintic`] `T` (quintic -> spline with the same end
//! 2-jets) is a bijection, block-diagonal in the three coefficients at each end, and a macro
//! patch is `(T x T) V` of a *virtual* bi-5 patch `V` whose inner corner blocks are the corner
//! jets of the guide (as for bi-5). The outer layers of `V` are the C^2 prolongation of the
//! previous ring's *macro* patch: `V`'s 2-jets at the new patch's outer corners are those of the
//! previous spline restricted (or extended) to the new patch's box. Both knot sequences are
//! compatible with the binary split of the rings (the previous knots `1/3` or `2/3` land on a new
//! knot, `1/2` on the patch boundary) and the extension of the first piece is one polynomial, so
//! the restricted previous spline lies in the new patch's space: the new macro patch reproduces
//! it exactly to second order across the ring boundary (C^2). Across sector rays and between the
//! patches `A`, `B`, `C` of a ring, both sides apply the same `T` along the edge to the same
//! corner data (C^2). The first ring prolongs the bi-3 surroundings, which are polynomials in
//! every space, so ring 0 is the bi-5 ring 0 in macro form.
//!
//! Converting the bi-5 rings patch by patch would not do: `T` of a restricted quintic is not the
//! restriction of `T` of the quintic, so consecutive rings would in general meet only at the
//! patch corners (with matching 2-jets there) and leave gaps along the ring boundaries.
//!
//! Not the paper's: the variants' caps (the paper's G^1 bi-3 cap is "formally only
//! C^0-connected" to the last ring; its construction is in the lost Fig. 17). fairsub closes the
//! hole with its own split-sector G^1 cap of [`crate::bezier::g1`] (`m x m` pieces per sector,
//! C^1 to the last ring, see [`super::surface`]), a reconstruction, not the paper's cap.

use crate::bezier::bern::{bernstein_derivs, kron};
use nalgebra::DMatrix;

/// The macro-patch variants.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MacroKind {
    /// 2 x 2 bi-4 pieces, C^3 at the inner knot.
    Bi4,
    /// 3 x 3 bi-3 pieces, C^2 at the inner knots.
    Bi3,
}

impl MacroKind {
    /// Degree of the pieces.
    pub fn degree(self) -> usize {
        match self {
            MacroKind::Bi4 => 4,
            MacroKind::Bi3 => 3,
        }
    }

    /// Pieces per variable.
    pub fn pieces(self) -> usize {
        match self {
            MacroKind::Bi4 => 2,
            MacroKind::Bi3 => 3,
        }
    }

    /// Smoothness at the inner knots.
    pub fn smoothness(self) -> usize {
        match self {
            MacroKind::Bi4 => 3,
            MacroKind::Bi3 => 2,
        }
    }

    /// `T`: quintic BB coefficients (6) -> piecewise Bezier coefficients of the spline with the
    /// same 2-jets at both ends (`pieces * (degree + 1)` rows, piece by piece).
    pub fn from_quintic(self) -> DMatrix<f64> {
        let (e, m, r) = (self.degree(), self.pieces(), self.smoothness());
        let nu = m * (e + 1);
        let mf = m as f64;
        let mut a = DMatrix::zeros(nu, nu);
        let mut b = DMatrix::zeros(nu, 6);
        let mut row = 0;
        for (end, piece, t) in [(0.0, 0, 0.0), (1.0, m - 1, 1.0)] {
            for k in 0..3 {
                let w = bernstein_derivs(e, k, t);
                for i in 0..=e {
                    a[(row, piece * (e + 1) + i)] = w[i] * mf.powi(k as i32);
                }
                let q = bernstein_derivs(5, k, end);
                for i in 0..6 {
                    b[(row, i)] = q[i];
                }
                row += 1;
            }
        }
        for p in 0..m - 1 {
            for k in 0..=r {
                let wl = bernstein_derivs(e, k, 1.0);
                let wr = bernstein_derivs(e, k, 0.0);
                for i in 0..=e {
                    a[(row, p * (e + 1) + i)] += wl[i];
                    a[(row, (p + 1) * (e + 1) + i)] -= wr[i];
                }
                row += 1;
            }
        }
        debug_assert_eq!(row, nu);
        a.lu()
            .solve(&b)
            .expect("the spline space is fixed by its end 2-jets")
    }

    /// 2-jet (value, first, second derivative) at `x` of the spline `T v` as rows over `v`
    /// (any real `x`; outside `[0, 1]` the end piece is extended).
    fn jet_at(self, t: &DMatrix<f64>, x: f64) -> DMatrix<f64> {
        let (e, m) = (self.degree(), self.pieces());
        let mf = m as f64;
        let p = ((x * mf).floor().max(0.0) as usize).min(m - 1);
        let local = x * mf - p as f64;
        let mut out = DMatrix::zeros(3, 6);
        for k in 0..3 {
            let w = bernstein_derivs(e, k, local);
            for i in 0..=e {
                for c in 0..6 {
                    out[(k, c)] += w[i] * mf.powi(k as i32) * t[(p * (e + 1) + i, c)];
                }
            }
        }
        out
    }

    /// Univariate C^2 prolongation: the virtual quintic of the new patch whose parameter `[0, 1]`
    /// is `[a, b]` of the previous patch, from the previous patch's virtual quintic (`6 x 6`).
    pub fn prolong_1d(self, a: f64, b: f64) -> DMatrix<f64> {
        let t = self.from_quintic();
        let h = b - a;
        let mut jets = DMatrix::zeros(6, 6);
        let ja = self.jet_at(&t, a);
        let jb = self.jet_at(&t, b);
        for k in 0..3 {
            let s = h.powi(k as i32);
            jets.set_row(k, &(ja.row(k) * s));
            jets.set_row(3 + k, &(jb.row(k) * s));
        }
        // Quintic from its end 2-jets.
        let mut j5 = DMatrix::zeros(6, 6);
        for k in 0..3 {
            let q0 = bernstein_derivs(5, k, 0.0);
            let q1 = bernstein_derivs(5, k, 1.0);
            for i in 0..6 {
                j5[(k, i)] = q0[i];
                j5[(3 + k, i)] = q1[i];
            }
        }
        j5.lu()
            .solve(&jets)
            .expect("quintic end jets are unisolvent")
    }

    /// Tensor-product prolongation over the box `[s0, s1] x [t0, t1]` (`36 x 36`).
    pub fn prolong(self, b: [f64; 4]) -> DMatrix<f64> {
        kron(&self.prolong_1d(b[0], b[1]), &self.prolong_1d(b[2], b[3]))
    }

    /// The pieces of the macro patch of a virtual bi-5 patch (36 coefficients, row-major):
    /// `pieces^2` Bezier patches of degree `degree`, row-major over the pieces (`(p, q)`, `p`
    /// along the first parameter), each as `(degree + 1)^2` coefficients.
    pub fn pieces_of(self, v: &[[f64; 3]]) -> Vec<Vec<[f64; 3]>> {
        let (e, m) = (self.degree(), self.pieces());
        let t = self.from_quintic();
        let nu = m * (e + 1);
        let mut x = vec![[0.0; 3]; nu * nu];
        for a in 0..nu {
            for b in 0..nu {
                let mut s = [0.0; 3];
                for i in 0..6 {
                    for j in 0..6 {
                        let w = t[(a, i)] * t[(b, j)];
                        if w != 0.0 {
                            for c in 0..3 {
                                s[c] += w * v[6 * i + j][c];
                            }
                        }
                    }
                }
                x[a * nu + b] = s;
            }
        }
        let mut out = Vec::with_capacity(m * m);
        for p in 0..m {
            for q in 0..m {
                let mut piece = Vec::with_capacity((e + 1) * (e + 1));
                for i in 0..=e {
                    for j in 0..=e {
                        piece.push(x[(p * (e + 1) + i) * nu + q * (e + 1) + j]);
                    }
                }
                out.push(piece);
            }
        }
        out
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn t_keeps_end_jets_and_prolongation_is_exact_on_splines() {
        for kind in [MacroKind::Bi4, MacroKind::Bi3] {
            let t = kind.from_quintic();
            // Polynomials of the spline's degree are reproduced: T of a raised cubic is the cubic.
            let id = kind.prolong_1d(0.0, 1.0);
            assert!((id - DMatrix::identity(6, 6)).amax() < 1e-12);
            // Prolonging over [0, 1/2] then [1/2, 1] of the half equals prolonging over [1/4,
            // 1/2] directly (restrictions compose, since the spaces nest under halving).
            let ab = kind.prolong_1d(0.5, 1.0) * kind.prolong_1d(0.0, 0.5);
            let direct = kind.prolong_1d(0.25, 0.5);
            assert!((ab - direct).amax() < 1e-10, "{kind:?}");
            assert_eq!(t.nrows(), kind.pieces() * (kind.degree() + 1));
        }
    }
}
