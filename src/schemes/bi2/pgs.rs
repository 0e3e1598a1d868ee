//! Point-Augmented Bi-2 Subdivision (PGS), Section 2 of the bi-2 paper: Doo-Sabin refinement
//! whose extraordinary facets get an added central point `p` and enriched rules.
//!
//! # The DS-net and its labels
//!
//! Around an `n`-gon facet (`n != 4`) with corners `a_0 .. a_(n-1)` (counter-clockwise), the
//! DS-net holds per sector `i`: `a_i`; `b_i`, the neighbour of `a_i` across the quad on the
//! edge `a_(i-1) a_i`; `d_i`, the neighbour of `a_i` across the quad on the edge `a_i a_(i+1)`;
//! `c_i`, the corner of the quad diagonal to the facet at `a_i`; and five points of the next
//! layer. (The paper's Fig. 4 with labels 1..9 is lost; this labelling is the one its formulas
//! force: `b_i^new` and `d_i^new` are the bi-2 masks 9/16, 3/16, 3/16, 1/16 of exactly these
//! quads.) In the chart of sector `i` the points sit at `(x, y)`, `x, y in {1/2, 3/2, 5/2}`:
//! `a = (1/2, 1/2)`, `b = (3/2, 1/2)`, `c = (3/2, 3/2)`, `d = (1/2, 3/2)`; the facet covers the
//! cell around the origin ([`ds_net`] builds this net).
//!
//! # Rules (the paper's numbering)
//!
//! - (1) `p = mu_n a_mean + (1 - mu_n) (b_mean + d_mean) / 2`, `mu_3 = 3/5`,
//!   `mu_n = 2 (n - 2) / n` for `n >= 4`;
//! - (3) `p^new = (1 - alpha) p + alpha a_mean`;
//! - (4) `a_i^new = (1 - w1 - 2 w2) p + w1 a_i + w2 (a_(i-1) + a_(i+1))`;
//! - `b`, `c`, `d` and every other new point: the bi-2 (Doo-Sabin quad) mask;
//! - (8) `alpha = 3/4 + mu_n (w1 + 2 w2 - 1)`;
//! - (9) `w2 = w1 / 4`, `w1 = 2 lambda / (2 + c)`, `c = cos(2 pi / n)`;
//! - (10) `lambda = sum_i b_i C(3, i) (1 - c)^(3 - i) c^i` with
//!   `b = (1/2, 0.5519, 0.5985, 0.64367)`;
//! - (7) limit point `(1 - tau) p + tau a_mean`, `tau = alpha / (1 + alpha - w1 - 2 w2)`.
//!
//! `n = 4` gives `mu = 1`, `w1 = 1/2`, `w2 = 1/8`, `alpha = 1/2`: rule (4) is then the bi-2
//! mask, so PGS is uniform bi-2 refinement on quads (tested).
//!
//! # `p` is not stored
//!
//! With `alpha` from (8) the rules are stationary (the paper's appendix): `p^new` from (3)
//! equals (1) applied to the refined DS-net. So a whole-mesh step computes `p` from (1) on the
//! current net, applies (4), and stores no extra point: the input and output of
//! [`Pgs::refine`] are plain polygon meshes, and one PGS step has Doo-Sabin's topology. The
//! analysis keeps `p` as an independent point ([`Pgs::corner_stencil_with_centre`],
//! [`Pgs::centre_update`]) so that the subdivision matrix is the paper's `10n x 10n` one, and a
//! test checks the stationarity identity.
//!
//! # Where PGS applies (fairsub's documented fallback)
//!
//! Rule (4) needs the facet's DS-net: every corner an interior vertex of valence 4 and every
//! face across an edge of the facet a quad ([`Pgs::has_ds_net`]). A facet without one (on the
//! boundary, next to another facet or to a triangle, or with corners of valence 3 as on a
//! prism's cap) is refined by Doo-Sabin's rule for that step. One step gives every facet a
//! DS-net (its F-face is surrounded by E-face quads and every vertex has valence 4), so from
//! level 1 on PGS applies at every facet, including the facets that extraordinary vertices
//! become. This is the paper's own procedure for prisms (DS steps, then PGS); the DS^CC
//! pre-processing of its prism experiment is [`PgsOptions::dscc_steps`].
//!
//! Boundaries are those of [`crate::schemes::doo_sabin`] (Chaikin points on boundary edges,
//! kept corners).

use crate::error::{Error, Result};
use crate::geom::axpy;
use crate::mesh::PolyMesh;
use crate::schemes::common::RowBuf;
use crate::schemes::doo_sabin::fourier::{self, FaceCorners};
use crate::schemes::doo_sabin::{DooSabin, refine_dual_with};
use crate::schemes::options::ids;
use crate::schemes::{Refinement, Scheme};
use crate::stencil::{Stencil, StencilTable};

pub use super::pgs_dscc::{PgsOptions, PgsPreprocessed};

/// The control points `b_0 .. b_3` of formula (10), as printed.
pub const LAMBDA_BERNSTEIN: [f64; 4] = [0.5, 0.5519, 0.5985, 0.64367];

/// The parameters of PGS at facet size `n` (formulas (1), (8), (9), (10), (7)).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct PgsParams {
    /// Facet size.
    pub n: usize,
    /// `mu_n` of (1).
    pub mu: f64,
    /// The subdominant eigenvalue `lambda_sub` of (10).
    pub lambda: f64,
    /// `w1` of (9).
    pub w1: f64,
    /// `w2 = w1 / 4` of (9).
    pub w2: f64,
    /// `alpha` of (8).
    pub alpha: f64,
    /// `tau` of the limit point (7).
    pub tau: f64,
}

impl PgsParams {
    /// The parameters for an `n`-gon facet, `n >= 3`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for `n < 3`.
    pub fn new(n: usize) -> Result<PgsParams> {
        super::at_least_three(n, "PGS needs a facet of at least 3 sides")?;
        let c = super::cos_2pi(1, n as i64);
        let mu = if n == 3 {
            0.6
        } else {
            2.0 * (n as f64 - 2.0) / n as f64
        };
        let lambda = lambda_sub(c);
        let w1 = 2.0 * lambda / (2.0 + c);
        let w2 = w1 / 4.0;
        let alpha = 0.75 + mu * (w1 + 2.0 * w2 - 1.0);
        let tau = alpha / (1.0 + alpha - w1 - 2.0 * w2);
        Ok(PgsParams {
            n,
            mu,
            lambda,
            w1,
            w2,
            alpha,
            tau,
        })
    }

    /// Formula (1), the centre `p` of the facet with DS-net `net`, over the net's point indices.
    pub fn centre(&self, net: &FacetNet) -> Stencil {
        let n = self.n as f64;
        let wa = self.mu / n;
        let wbd = (1.0 - self.mu) / (2.0 * n);
        let mut s = Stencil::new();
        for i in 0..net.a.len() {
            s.add(net.a[i] as usize, wa);
            s.add(net.b[i] as usize, wbd);
            s.add(net.d[i] as usize, wbd);
        }
        s.merged()
    }

    /// Formula (7), the limit point `(1 - tau) p + tau a_mean` of the facet with centre `p` and
    /// corners `a`.
    pub fn limit_point(&self, p: &Stencil, a: &[u32]) -> Stencil {
        blend_with_mean(p, self.tau, a)
    }

    /// The subsubdominant eigenvalue as the paper states it: `1/4` for `n = 3`,
    /// `w1 + 2 w2 - alpha` (a root of (5)) for `n = 5, 6`, `w1 + 2 w2 c_2` (a root of (6) for
    /// `k = 2`) for `n > 6`; `1/4` for `n = 4` (uniform bi-2).
    pub fn published_subsubdominant(&self) -> f64 {
        match self.n {
            3 | 4 => 0.25,
            5 | 6 => self.w1 + 2.0 * self.w2 - self.alpha,
            n => self.w1 + 2.0 * self.w2 * super::cos_2pi(2, n as i64),
        }
    }
}

/// `(1 - t) p + t a_mean` over the corners `a`: the shape of formulas (3) (`t = alpha`) and (7)
/// (`t = tau`).
fn blend_with_mean(p: &Stencil, t: f64, a: &[u32]) -> Stencil {
    let mut s = Stencil::new();
    s.add_scaled(p, 1.0 - t);
    for &v in a {
        s.add(v as usize, t / a.len() as f64);
    }
    s.merged()
}

/// Formula (10): `lambda_sub` as a cubic Bernstein polynomial in `c = cos(2 pi / n)`.
pub fn lambda_sub(c: f64) -> f64 {
    let b = LAMBDA_BERNSTEIN;
    let d = 1.0 - c;
    b[0] * d * d * d + 3.0 * b[1] * d * d * c + 3.0 * b[2] * d * c * c + b[3] * c * c * c
}

/// PGS as a whole-mesh scheme (name `pgs`). See the [module](self) documentation.
#[derive(Debug, Clone, Copy, Default)]
pub struct Pgs;

/// The labelled DS-net one-ring of an extraordinary facet.
#[derive(Debug, Clone)]
pub struct FacetNet {
    /// Corners `a_i` (counter-clockwise).
    pub a: Vec<u32>,
    /// `b_i`: neighbour of `a_i` across the quad on edge `a_(i-1) a_i`.
    pub b: Vec<u32>,
    /// `d_i`: neighbour of `a_i` across the quad on edge `a_i a_(i+1)`.
    pub d: Vec<u32>,
}

impl Pgs {
    /// The labelled DS-net one-ring of facet `f` when PGS applies there: `f` is not a quad,
    /// every corner is an interior vertex of valence 4 and every face across an edge of `f` is
    /// a quad. `None` otherwise (the facet is then refined by Doo-Sabin's rule).
    pub fn facet_net(mesh: &PolyMesh, f: usize) -> Option<FacetNet> {
        let n = mesh.face_size(f);
        if n == 4 || n < 3 {
            return None;
        }
        let h0 = mesh.face_halfedge(f);
        let mut a = Vec::with_capacity(n);
        let mut b = vec![0u32; n];
        let mut d = vec![0u32; n];
        for i in 0..n {
            let h = h0 + i as u32;
            let v = mesh.he_from(h) as usize;
            if mesh.is_boundary_vertex(v) || mesh.valence(v) != 4 {
                return None;
            }
            a.push(v as u32);
            // The quad across edge a_i a_(i+1): (a_(i+1), a_i, d_i, b_(i+1)).
            let t = mesh.he_twin(h)?;
            if mesh.face_size(mesh.he_face(t) as usize) != 4 {
                return None;
            }
            let x = mesh.he_next(t);
            d[i] = mesh.he_to(x);
            b[(i + 1) % n] = mesh.he_to(mesh.he_next(x));
        }
        Some(FacetNet { a, b, d })
    }

    /// Whether PGS applies at facet `f` (see [`Pgs::facet_net`]).
    pub fn has_ds_net(mesh: &PolyMesh, f: usize) -> bool {
        Self::facet_net(mesh, f).is_some()
    }

    /// Formula (1): the added point `p` of facet `f` as a stencil over the mesh, when PGS
    /// applies there.
    pub fn centre_stencil(mesh: &PolyMesh, f: usize) -> Option<Stencil> {
        let net = Self::facet_net(mesh, f)?;
        Some(PgsParams::new(net.a.len()).ok()?.centre(&net))
    }

    /// Formula (4): the new point of corner `h` of a facet with a DS-net, for the centre `p`
    /// given as a stencil (formula (1) for mesh refinement, an independent point for the
    /// analysis). The caller guarantees that the facet of `h` has a DS-net.
    pub fn corner_stencil_with_centre(mesh: &PolyMesh, h: u32, p: &Stencil) -> Stencil {
        let f = mesh.he_face(h) as usize;
        let n = mesh.face_size(f);
        let prm = PgsParams::new(n).expect("a face has at least 3 sides");
        let verts = mesh.face(f);
        let i = (h - mesh.face_halfedge(f)) as usize;
        let mut s = Stencil::new();
        s.add_scaled(p, 1.0 - prm.w1 - 2.0 * prm.w2);
        s.add(verts[i] as usize, prm.w1);
        s.add(verts[(i + 1) % n] as usize, prm.w2);
        s.add(verts[(i + n - 1) % n] as usize, prm.w2);
        s.merged()
    }

    /// Formula (3): `p^new = (1 - alpha) p + alpha a_mean` of facet `f` (the analysis's row of
    /// the independent point).
    pub fn centre_update(mesh: &PolyMesh, f: usize, p: &Stencil) -> Stencil {
        let verts = mesh.face(f);
        let prm = PgsParams::new(verts.len()).expect("a face has at least 3 sides");
        blend_with_mean(p, prm.alpha, verts)
    }

    /// The new point of face corner `h` under PGS: (4) with `p` from (1) at a facet with a
    /// DS-net; the bi-2 mask on a quad; Doo-Sabin's rule at a facet without a DS-net (the
    /// documented fallback).
    pub fn corner_stencil(mesh: &PolyMesh, h: u32) -> Stencil {
        let mut row = RowBuf::default();
        add_corner(mesh, h, &mut row);
        row.take_stencil()
    }

    /// All new corners of facet `f` at once, as positions in time linear in its size (for the
    /// adaptive host's large faces): (4) with the centre `p` of (1) evaluated once, where
    /// [`Pgs::corner_stencil`] would carry `p`'s `O(n)` stencil in every corner; Doo-Sabin's rule
    /// ([`crate::schemes::doo_sabin::fourier::doo_sabin`]) at a facet without a DS-net and at a
    /// quad (where it is the bi-2 mask), as [`Pgs::corner_stencil`].
    pub fn face_corners(mesh: &PolyMesh, f: usize) -> FaceCorners {
        let n = mesh.face_size(f);
        let centre = if n == 4 {
            None
        } else {
            Self::centre_stencil(mesh, f)
        };
        let Some(p) = centre else {
            return fourier::doo_sabin(mesh, f);
        };
        let prm = PgsParams::new(n).expect("a face has at least 3 sides");
        let pos = mesh.positions();
        let verts = mesh.face(f);
        let pp = p.apply(pos);
        let at = |i: usize| pos[verts[i % n] as usize];
        let points = (0..n)
            .map(|i| {
                let mut q = axpy([0.0; 3], 1.0 - prm.w1 - 2.0 * prm.w2, pp);
                q = axpy(q, prm.w1, at(i));
                q = axpy(q, prm.w2, at(i + 1));
                axpy(q, prm.w2, at(i + n - 1))
            })
            .collect();
        let mut reads: Vec<u32> = p.entries().iter().map(|&(x, _)| x).collect();
        reads.extend_from_slice(verts);
        FaceCorners { points, reads }
    }

    /// The limit point (7) of facet `f` with `p` from (1), when PGS applies there; otherwise
    /// the limit point of the facet's child after one (Doo-Sabin) step is not a closed form of
    /// `f` alone, and the centroid is returned (exact for quads, the documented centre of the
    /// fill for the rare facets without a DS-net at the last level).
    pub fn facet_limit_stencil(mesh: &PolyMesh, f: usize) -> Stencil {
        match Self::centre_stencil(mesh, f) {
            Some(p) => {
                let verts = mesh.face(f);
                let prm = PgsParams::new(verts.len()).expect("a face has at least 3 sides");
                prm.limit_point(&p, verts)
            }
            None => crate::schemes::doo_sabin::surface::centroid_stencil(mesh, f),
        }
    }

    /// `levels` steps of PGS, the first `opts.dscc_steps` of them DS^CC steps (the paper's
    /// pre-processing of coarse nets such as prisms).
    ///
    /// # Errors
    /// As [`Scheme::refine`].
    pub fn refine_levels_with(
        mesh: &PolyMesh,
        levels: usize,
        opts: PgsOptions,
    ) -> Result<PolyMesh> {
        let mut m = mesh.clone();
        for l in 0..levels {
            // Only the nets are kept: large faces take their corners in linear time.
            m = if l < opts.dscc_steps {
                fourier::refine_cc_net(&m)?
            } else {
                crate::schemes::doo_sabin::refuse_reaching_rule_at_trimmed_boundary(
                    &m,
                    Pgs.name(),
                )?;
                fourier::refine_net_with(&m, Pgs.name(), add_corner, Pgs::face_corners)?
            };
        }
        Ok(m)
    }
}

/// Adds the PGS rule of corner `h` to `row` (see [`Pgs::corner_stencil`]).
fn add_corner(mesh: &PolyMesh, h: u32, row: &mut RowBuf) {
    let f = mesh.he_face(h) as usize;
    let n = mesh.face_size(f);
    let verts = mesh.face(f);
    let i = (h - mesh.face_halfedge(f)) as usize;
    if n == 4 {
        for (k, w) in [(0, 9.0), (1, 3.0), (2, 1.0), (3, 3.0)] {
            row.add(verts[(i + k) % 4], w / 16.0);
        }
        return;
    }
    match Pgs::centre_stencil(mesh, f) {
        Some(p) => {
            for &(x, w) in Pgs::corner_stencil_with_centre(mesh, h, &p).entries() {
                row.add(x, w);
            }
        }
        None => {
            let w = DooSabin::weights(n);
            for (d, &wd) in w.iter().enumerate() {
                row.add(verts[(i + d) % n], wd);
            }
        }
    }
}

impl Scheme for Pgs {
    fn step_size(&self, s: &crate::schemes::growth::NetSize) -> crate::schemes::growth::NetSize {
        crate::schemes::growth::dual(s)
    }

    fn name(&self) -> &'static str {
        crate::schemes::options::ids::PGS.name()
    }

    /// One PGS step: Doo-Sabin topology and boundary rules, rule (4) at every facet with a
    /// DS-net (see the [module](self) documentation).
    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        crate::schemes::doo_sabin::refuse_reaching_rule_at_trimmed_boundary(mesh, self.name())?;
        refine_dual_with(mesh, self.name(), add_corner)
    }

    /// Limit points of the net's vertices: an interior vertex's limit is the limit of its
    /// V-face after one step (the centroid for valence 4, formula (7) on the refined net
    /// otherwise); boundary vertices lie on the Chaikin limit curve `(u + 6 v + w) / 8`;
    /// corners are kept.
    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        crate::schemes::doo_sabin::refuse_limit_without_boundary(mesh, self.name())?;
        let nv = mesh.num_vertices();
        let mut table = StencilTable::with_capacity(nv, nv, 16);
        let mut row = RowBuf::default();
        for v in 0..nv {
            let vi = v as u32;
            if mesh.is_boundary_vertex(v) {
                if crate::schemes::doo_sabin::sharp::is_kept_corner(mesh, v) {
                    row.add(vi, 1.0);
                } else {
                    let (u, w) = mesh.boundary_neighbors(v);
                    row.add(vi, 0.75);
                    row.add(u, 0.125);
                    row.add(w, 0.125);
                }
                row.flush_into(&mut table);
                continue;
            }
            let hs: Vec<u32> = mesh.outgoing(v).collect();
            let k = hs.len();
            if k < 3 {
                return Err(Error::Unsupported(format!(
                    "vertex {v} is an interior vertex of valence 2, which has no closed-form {} \
                     limit point; refine the net once (the refined net has no such vertex)",
                    ids::PGS
                )));
            }
            let corner = |h: u32| Pgs::corner_stencil(mesh, h);
            let a: Vec<Stencil> = hs.iter().map(|&h| corner(h)).collect();
            let s = if k == 4 {
                let mut s = Stencil::new();
                for x in &a {
                    s.add_scaled(x, 0.25);
                }
                s
            } else {
                // The V-face at level 1 is a k-gon with corners a_j; across its edge between
                // a_j and a_(j+1) lies the E-face of the edge v - w, w = to(h_(j+1)), whose far
                // points are the corners of w in the faces of h_j and h_(j+1).
                let prm = PgsParams::new(k)?;
                let mut far = Stencil::new();
                for j in 0..k {
                    let hn = hs[(j + 1) % k];
                    far.add_scaled(&corner(mesh.he_prev(hs[j])), 1.0);
                    far.add_scaled(&corner(mesh.he_next(hn)), 1.0);
                }
                let mut amean = Stencil::new();
                for x in &a {
                    amean.add_scaled(x, 1.0 / k as f64);
                }
                let mut p = amean.clone().scaled(prm.mu);
                p.add_scaled(&far, (1.0 - prm.mu) / (2.0 * k as f64));
                let mut s = p.scaled(1.0 - prm.tau);
                s.add_scaled(&amean, prm.tau);
                s
            };
            for &(x, w) in s.merged().entries() {
                row.add(x, w);
            }
            row.flush_into(&mut table);
        }
        Ok(table)
    }
}

/// Index of chart point `(i, j)` (`x = i + 1/2`, `y = j + 1/2`, `i, j in 0..3`) of sector `s`
/// in the DS-net of [`ds_net`].
pub fn ds_net_index(s: usize, i: usize, j: usize) -> usize {
    9 * s + 3 * i + j
}

/// The point of the DS-net of valence `n` at chart point `(x, y)` of sector `s` (half-integer
/// coordinates, doubled: `x2 = 2x`, odd), reached through the neighbouring sectors' charts
/// (sector `s + 1`'s `(x, y)` lies at `(-y, x)` in sector `s`'s chart). `None` for the facet's
/// interior (both coordinates negative) or beyond the net.
pub fn ds_net_chart(n: usize, s: usize, x2: i64, y2: i64) -> Option<usize> {
    let (mut s, mut x, mut y) = (s as i64, x2, y2);
    for _ in 0..3 {
        if x > 0 && y > 0 {
            break;
        }
        if x < 0 && y > 0 {
            (x, y) = (y, -x);
            s += 1;
        } else if x > 0 && y < 0 {
            (x, y) = (-y, x);
            s -= 1;
        } else {
            return None;
        }
    }
    if x <= 0 || y <= 0 || x > 5 || y > 5 {
        return None;
    }
    let s = s.rem_euclid(n as i64) as usize;
    Some(ds_net_index(
        s,
        ((x - 1) / 2) as usize,
        ((y - 1) / 2) as usize,
    ))
}

/// The DS-net of an `n`-gon facet: the facet and two rings of quads, `9 n` points. Sector `s`
/// holds the chart points `(x, y) = (i + 1/2, j + 1/2)`, `i, j in 0..3`, at vertex
/// [`ds_net_index`]`(s, i, j)`, placed at `x e_s + y e_(s+1)` (`e_s` the unit vector at angle
/// `2 pi s / n`) with height `height(x, y)`. Face 0 is the facet; then per sector its four
/// quads `(i, j)`, `i, j in 0..2`, then its two quads shared with sector `s + 1`.
pub fn ds_net(n: usize, height: impl Fn(f64, f64) -> f64) -> Result<PolyMesh> {
    super::at_least_three(n, "a DS-net needs a facet of at least 3 sides")?;
    let e = |s: usize| {
        let c = super::cos_2pi(s as i64, n as i64);
        let sn = super::cos_2pi(4 * s as i64 - n as i64, 4 * n as i64);
        [c, sn]
    };
    let mut pos = vec![[0.0; 3]; 9 * n];
    for s in 0..n {
        let (es, et) = (e(s), e(s + 1));
        for i in 0..3 {
            for j in 0..3 {
                let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
                let px = x * es[0] + y * et[0];
                let py = x * es[1] + y * et[1];
                pos[ds_net_index(s, i, j)] = [px, py, height(px, py)];
            }
        }
    }
    let mut faces: Vec<Vec<usize>> = vec![(0..n).map(|s| ds_net_index(s, 0, 0)).collect()];
    for s in 0..n {
        let t = (s + 1) % n;
        for i in 0..2 {
            for j in 0..2 {
                faces.push(vec![
                    ds_net_index(s, i, j),
                    ds_net_index(s, i + 1, j),
                    ds_net_index(s, i + 1, j + 1),
                    ds_net_index(s, i, j + 1),
                ]);
            }
        }
        for j in 0..2 {
            faces.push(vec![
                ds_net_index(t, j, 0),
                ds_net_index(s, 0, j),
                ds_net_index(s, 0, j + 1),
                ds_net_index(t, j + 1, 0),
            ]);
        }
    }
    PolyMesh::new(pos, &faces)
}

#[cfg(feature = "unit-tests")]
mod tests;
