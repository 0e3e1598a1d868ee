//! QAS+^3: the bi-3 flavour of QAS+, from QAS+^4 through the bijection `T_3^4` between bi-4 and
//! bi-3 tensor-borders (fairsub's derivation `qas-plus-bi3`; the formulas of the earlier QAS paper
//! are not in the corpus).
//!
//! # The bijection `T_3^4` (derived)
//!
//! The bi-4 d-net is a C^2 quartic spline with double knots at the integers of its level (nodes
//! at integers and half-integers); the bi-3 d-net is a C^2 cubic spline with simple knots at the
//! half-integers (nodes at the same places). Univariately, `T` keeps the half-integer nodes and
//! maps an integer node `d_k` to `(d_(k-1/2) + 6 d_k + d_(k+1/2)) / 8`; its inverse maps `c_k` to
//! `(8 c_k - c_(k-1/2) - c_(k+1/2)) / 6`. At every integer knot the two splines then have the
//! same value, first and second derivative (the quartic's jet there, `b0, b1, b2` of (5), depends
//! on `d_(k-1/2), d_k, d_(k+1/2)` exactly as the cubic's does on `c_(k-1/2), c_k, c_(k+1/2)`), so
//! the tensor product keeps the surface's second-order data across and along every knot line at
//! the knots; and on their common subspace (cubic splines with integer knots, e.g. a c-net's
//! surface) `T` maps the degree-raised net to the knot-inserted one, i.e. it is the identity on
//! the represented surface. `T` and its inverse are local (3 x 3 tensor stencils).
//!
//! # One step
//!
//! The 24 n outer nodes come from uniform bi-3 knot insertion of the bi-3 d-net; the 6 n inner
//! nodes are `T` (at the new level) of the QAS+^4 refinement of `T^(-1)` of the bi-3 d-net. The
//! ring is 12 n bi-3 patches (a 2 x 2 macro-patch per QAS+^4 patch) by uniform bi-3 B-to-BB
//! conversion. The quadratic expansion is that of QAS+^4.

use super::{Qas, num_sources, q_index};
use crate::error::{Error, Result};
use crate::schemes::eg::{self, EgStep, SPECIAL};
use crate::stencil::{Stencil, StencilTable};

/// Univariate `T` weights at a node `x` of a level whose integers are multiples of `unit`
/// quarters: `(position offset, weight)` pairs over the bi-4 nodes.
fn t_forward(x: i32, half: i32) -> Vec<(i32, f64)> {
    if x.rem_euclid(2 * half) == 0 {
        vec![(-half, 0.125), (0, 0.75), (half, 0.125)]
    } else {
        vec![(0, 1.0)]
    }
}

/// Univariate `T^(-1)` weights over the bi-3 nodes.
fn t_inverse(x: i32, half: i32) -> Vec<(i32, f64)> {
    if x.rem_euclid(2 * half) == 0 {
        vec![(-half, -1.0 / 6.0), (0, 8.0 / 6.0), (half, -1.0 / 6.0)]
    } else {
        vec![(0, 1.0)]
    }
}

/// Tensor product of univariate position rules at `(u, v)`: a stencil over the nodes returned
/// by `node(u', v')`.
fn tensor(
    rule: fn(i32, i32) -> Vec<(i32, f64)>,
    half: i32,
    u: i32,
    v: i32,
    node: &dyn Fn(i32, i32) -> Result<Stencil>,
) -> Result<Stencil> {
    let mut st = Stencil::new();
    for (du, wu) in rule(u, half) {
        for (dv, wv) in rule(v, half) {
            st.add_scaled(&node(u + du, v + dv)?, wu * wv);
        }
    }
    Ok(st.merged())
}

/// The old bi-3 d-net node at `(u, v)` (quarters of the old level, even) of sector `s`.
fn bi3_old(n: usize, s: usize, u: i32, v: i32) -> Result<Stencil> {
    eg::dnet_node(n, s, u, v)
        .map(Stencil::point)
        .ok_or_else(|| {
            Error::Unsupported(format!(
                "QAS+^3 rule reaches ({u}, {v})/4 outside the d-net"
            ))
        })
}

/// Uniform bi-3 knot insertion: univariate weights of a new node at `x` (quarters, old nodes at
/// even quarters).
fn cubic_insertion(x: i32) -> Vec<(i32, f64)> {
    if x.rem_euclid(2) == 0 {
        vec![(-2, 0.125), (0, 0.75), (2, 0.125)]
    } else {
        vec![(-1, 0.5), (1, 0.5)]
    }
}

/// The QAS+^3 scheme at one valence.
#[derive(Debug, Clone)]
pub struct QasBi3 {
    qas: Qas,
}

impl QasBi3 {
    /// The scheme at valence `n` (5, 6, 7).
    pub fn new(n: usize) -> Result<QasBi3> {
        Ok(QasBi3 { qas: Qas::new(n)? })
    }

    /// QAS+^3 on given QAS+^4 tables (e.g. the derived ones).
    pub fn with_qas(qas: Qas) -> QasBi3 {
        QasBi3 { qas }
    }

    /// Valence.
    pub fn n(&self) -> usize {
        self.qas.n()
    }

    /// The old bi-4 node `T^(-1)` at `(u, v)` (old quarters) as a stencil over the bi-3 sources.
    fn bi4_old(&self, s: usize, u: i32, v: i32) -> Result<Stencil> {
        let n = self.n();
        tensor(t_inverse, 2, u, v, &|a, b| bi3_old(n, s, a, b))
    }

    /// A new bi-4 node at `(u, v)` (old quarters) over the bi-3 sources: QAS+^4's special rule or
    /// regular bi-4 refinement, applied to `T^(-1)` of the bi-3 d-net.
    fn bi4_new(&self, s: usize, u: i32, v: i32) -> Result<Stencil> {
        let n = self.n();
        let bi4 = eg::new_node(n, &|s, row| self.qas.rules().special_node(s, row), s, u, v)?;
        // Substitute every bi-4 d-net source by its T^(-1) stencil; other sources stay.
        let mut out = Stencil::new();
        for &(src, w) in bi4.entries() {
            let src = src as usize;
            if (1..=12 * n).contains(&src) {
                let (ss, e) = ((src - 1) / 12, (src - 1) % 12);
                let (i, j) = (e % 4, e / 4);
                let (nu, nv) = (6 - 2 * j as i32, 6 - 2 * i as i32);
                out.add_scaled(&self.bi4_old(ss, nu, nv)?, w);
            } else {
                out.add(src, w);
            }
        }
        Ok(out.merged())
    }

    /// A new bi-3 node at `(u, v)` (old quarters) of sector `s`.
    pub fn new_node(&self, s: usize, u: i32, v: i32) -> Result<Stencil> {
        let n = self.n();
        let (so, uo, vo) = eg::normalize(n, s, u, v)
            .ok_or_else(|| Error::Unsupported("no node at the centre".into()))?;
        if SPECIAL
            .iter()
            .any(|&(h, k)| (3 - k as i32, 3 - h as i32) == (uo, vo))
        {
            // T at the new level (integers = even quarters, half-step 1 quarter).
            return tensor(t_forward, 1, uo, vo, &|a, b| self.bi4_new(so, a, b));
        }
        let mut st = Stencil::new();
        for (du, wu) in cubic_insertion(uo) {
            for (dv, wv) in cubic_insertion(vo) {
                st.add_scaled(&bi3_old(n, so, uo + du, vo + dv)?, wu * wv);
            }
        }
        Ok(st.merged())
    }

    /// Step and ring tables: the ring holds 12 bi-3 patches per sector (16 coefficients each):
    /// for each QAS+^4 patch A, B, C its 2 x 2 sub-patches in the order (0,0), (1,0), (0,1), (1,1)
    /// of the EG chart.
    pub fn step(&self, lambda: f64) -> Result<EgStep> {
        let n = self.n();
        let q4 = self.qas.step(lambda)?;
        let m = num_sources(n);
        let mut step = StencilTable::with_capacity(m, m, 60);
        for r in 0..m {
            if (1..=12 * n).contains(&r) {
                let (s, e) = ((r - 1) / 12, (r - 1) % 12);
                let (i, j) = (e % 4, e / 4);
                step.push(self.new_node(s, 3 - j as i32, 3 - i as i32)?);
            } else {
                // p and q rows as QAS+^4 (they use no d-net sources).
                step.push(q4.step.stencil(r));
            }
        }
        let m3 = crate::bezier::convert::cubic_bspline_matrix();
        let mut ring = StencilTable::with_capacity(m, 192 * n, 40);
        for s in 0..n {
            for (cu, cv) in [(2, 0), (2, 2), (0, 2)] {
                for (su, sv) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    let (bu, bv) = (cu + su, cv + sv);
                    let mut net = Vec::with_capacity(16);
                    for a in 0..4 {
                        for b in 0..4 {
                            net.push(self.new_node(s, bu - 1 + a, bv - 1 + b)?);
                        }
                    }
                    for k in 0..4 {
                        for l in 0..4 {
                            let mut st = Stencil::new();
                            for a in 0..4 {
                                for b in 0..4 {
                                    let w = m3[(k, a)] * m3[(l, b)];
                                    if w != 0.0 {
                                        st.add_scaled(&net[4 * a + b], w);
                                    }
                                }
                            }
                            ring.push(st);
                        }
                    }
                }
            }
        }
        let _ = q_index;
        Ok(EgStep { step, ring })
    }
}

/// Stencils of the QAS+^3 local vector `(p, bi-3 d-net, q)` from the c-net: the QAS+^4 vector
/// with the d-net mapped by `T` (which equals uniform bi-3 knot insertion of the c-net).
pub fn from_cnet(n: usize) -> Result<StencilTable> {
    from_cnet_of(&Qas::new(n)?)
}

/// Like [`from_cnet`], with the QAS+^4 vector (and its `qas-fit`) of given tables.
pub fn from_cnet_of(qas: &Qas) -> Result<StencilTable> {
    let n = qas.n();
    let four = qas.from_cnet()?;
    let mut t = StencilTable::with_capacity(four.num_sources(), four.num_rows(), 40);
    for r in 0..four.num_rows() {
        if (1..=12 * n).contains(&r) {
            let (s, e) = ((r - 1) / 12, (r - 1) % 12);
            let (i, j) = (e % 4, e / 4);
            let (u, v) = (6 - 2 * j as i32, 6 - 2 * i as i32);
            let st = tensor(t_forward, 2, u, v, &|a, b| {
                let src = eg::dnet_node(n, s, a, b).ok_or_else(|| {
                    Error::Unsupported(format!("T reaches ({a}, {b})/4 outside the d-net"))
                })?;
                Ok(four.stencil(src))
            })?;
            t.push(st);
        } else {
            t.push(four.stencil(r));
        }
    }
    Ok(t)
}
