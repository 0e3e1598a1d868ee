//! Guided rings (the Subdivision Algorithm of Section 3.2) as tabulated linear maps, the
//! guide's target ([`GuideFit`], fairsub's own), and the per-valence scheme [`Guided`].
//!
//! # Ring layout
//!
//! Ring `l` of sector `k` has three patches of degree bi-`d` (`d` = 5 or 6) over the L-shaped
//! domain of [`super::chi`]: `A`, `B`, `C`, local `(s, t)` increasing with the chart's `(u, v)`;
//! ring `l` lives at scale `2^-l` of the c-net chart. Inner corners (on the edge to ring `l + 1`)
//! are `A (0,0), A (0,1), B (0,0), C (0,0), C (1,0)`; the other corners are outer.
//!
//! * **Inner data** (the paper's bullets of Fig. 7a): at each inner corner the `k x k` corner jet
//!   (`k = 3` for bi-5, `k = 4` for bi-6) of `g^k o L^-1 o lambda^l chi`, which equals
//!   `(g^k o S_(lambda^l)) o (L^-1 o chi)`: the guide restricted to `[0, lambda^l]^2` (de Casteljau,
//!   the same restriction as the subdivision matrix) sampled through one fixed table per valence.
//!   For bi-6 the overlapping coefficients of neighbouring inner jets are averaged (Fig. 2b).
//! * **Outer layers** (gray in Fig. 7c): the three layers along the outer edges are the C^2
//!   prolongation of the previous ring: `A`'s and `B`'s rows near `s = 1` continue the previous
//!   ring's `A` (its local `(s', t') = ((s - 1)/2, t/2)` resp. `((s - 1)/2, (t + 1)/2)`), `B`'s and
//!   `C`'s columns near `t = 1` continue the previous `C` (`((s + 1)/2, (t - 1)/2)`,
//!   `(s/2, (t - 1)/2)`). Both agree on `B`'s outer corner block since the previous ring is C^2
//!   there. For the first ring the surrounding bi-3 surface plays the previous ring: its patches on
//!   the c-net faces `(1,0)` and `(0,1)` of each sector (whose 2-jets at the cap boundary need only
//!   the c-net's two rings).
//! * For bi-6, the fourth layer (index 3) comes from the inner jets only: the previous ring's
//!   third derivative is not C^2 data, and the surrounding c-net does not determine it.
//!
//! Every coefficient that two patches share to second order across an edge is built from the
//! same data, so rings are C^2 to each other, across sector rays (`g o L^-1` is C^2 there and so
//! is `chi`) and to the bi-3 surroundings; only the central point is special.
//!
//! # The guide's target: `guide-fit F_4` (fairsub's reconstruction)
//!
//! The paper fits the free set `P` to the bi-5 surface of \[KP15\], which is not in the corpus.
//! fairsub's target: `P` minimises
//!
//! `sum over sectors and outer coefficients of ring 0 of |sampled - prolonged|^2 + w F_4(g)`,
//!
//! where *sampled* are the outer coefficients of the first ring as the rings sample the guide
//! (3 x 3 corner jets of `g o L^-1 o chi` at the outer corners, bi-5 form: 63 per sector) and
//! *prolonged* the same coefficients of the C^2 prolongation of the surrounding bi-3 surface,
//! i.e. the guide reproduces the second-order data of the surroundings along the cap boundary as
//! well as a G^2 guide can; `F_4(g^k) = int_[0,1]^2 sum_(i+j=4) 4!/(i! j!) (d_u^i d_v^j g^k)^2`
//! is the paper's fairness functional (Appendix B uses `F_5` for the cap's reparametrisation)
//! with weight `w` = [`GuideFit::DEFAULT_WEIGHT`] (`1e-6`; data in c-net units, `F_4` over the
//! guide's unit square). The data alone leave a few directions of `P` nearly free (the fit is
//! ill-conditioned without `F_4`); a small weight fixes them without pulling the guide off the
//! surroundings: weights of `1e-4` and more make the guide miss the boundary data and show as a
//! ripple in the first ring on the raised-node nets, `1e-9 .. 1e-6` give the same pictures.
//! The centre point is free (fitted too). `P` is linear in the c-net, so the whole cap is
//! ([`Guided::ring_stencils`]). The fit is solved as one stacked least-squares problem (data rows
//! over `sqrt(w) R B_s` with `R^T R` the Gram matrix of `F_4`) by SVD, which keeps the stencils
//! affine to 1e-11 (the normal equations lose about 1e-7 at `w = 1e-6`).
//!
//! The macro-patch variants ([`RingDegree::Bi4Macro`], [`RingDegree::Bi3Macro`]) use the same
//! tables in their virtual bi-5 form; only the prolongation of the previous ring differs
//! ([`super::macro_patch`]).

use super::chi::{CharRing, ChiKind};
use super::guide::{GuideDegree, GuideSpace};
use super::jets::{block_entry, corner_block, patch_series};
use super::macro_patch::MacroKind;
use crate::bezier::bern::{bernstein_derivs, binom, gauss_legendre, kron, raise, subsegment};
use crate::error::{Error, Result};
use nalgebra::DMatrix;

/// The patches of one ring: `3 n` coefficient vectors (patch `x` of sector `s` at `3 s + x`).
pub type RingPatches = Vec<Vec<[f64; 3]>>;

/// Degree of the ring patches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RingDegree {
    /// Bi-5 from 3 x 3 corner jets: C^2 rings, curvature bounded at the centre.
    #[default]
    Bi5,
    /// Bi-6 from 4 x 4 corner jets averaged (Fig. 2b): C^2 rings.
    Bi6,
    /// 2 x 2 bi-4 macro patches (Section 6.2, derived in [`super::macro_patch`]).
    Bi4Macro,
    /// 3 x 3 bi-3 macro patches (Section 6.2, derived in [`super::macro_patch`]).
    Bi3Macro,
}

impl RingDegree {
    /// Polynomial degree of the ring tables: 5 or 6; the macro variants are tabulated as their
    /// virtual bi-5 patches ([`super::macro_patch`]).
    pub fn degree(self) -> usize {
        match self {
            RingDegree::Bi6 => 6,
            _ => 5,
        }
    }

    /// Jet size per variable.
    pub fn jet(self) -> usize {
        match self {
            RingDegree::Bi6 => 4,
            _ => 3,
        }
    }

    /// The macro-patch variant, if any.
    pub fn macro_kind(self) -> Option<MacroKind> {
        match self {
            RingDegree::Bi4Macro => Some(MacroKind::Bi4),
            RingDegree::Bi3Macro => Some(MacroKind::Bi3),
            _ => None,
        }
    }
}

/// Inner corners of the patches A, B, C.
const INNER: [&[(usize, usize)]; 3] = [&[(0, 0), (0, 1)], &[(0, 0)], &[(0, 0), (1, 0)]];
/// Outer corners of the patches A, B, C.
const OUTER: [&[(usize, usize)]; 3] = [
    &[(1, 0), (1, 1)],
    &[(1, 0), (1, 1), (0, 1)],
    &[(0, 1), (1, 1)],
];

/// Corner blocks of one ring patch: `(corner, k^2 x (dg + 1)^2)` for each patch A, B, C.
type Blocks = [Vec<((usize, usize), DMatrix<f64>)>; 3];

/// The corner-jet tables of one valence: for each patch the blocks at the given corners.
fn jet_tables(
    chi: &CharRing,
    dg: usize,
    d: usize,
    k: usize,
    corners: [&[(usize, usize)]; 3],
) -> Blocks {
    let phi = chi.in_guide_domain();
    let mut out: Blocks = Default::default();
    for (x, cs) in corners.iter().enumerate() {
        for &c in cs.iter() {
            let ser = patch_series(&phi[x], c.0 as f64, c.1 as f64, k);
            out[x].push((c, corner_block(&ser, c, dg, d)));
        }
    }
    out
}

/// Where each coefficient of a ring patch comes from.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Source {
    /// The prolongation of the previous A.
    OuterA,
    /// The prolongation of the previous C.
    OuterC,
    /// Average of the inner blocks covering it.
    Inner,
}

fn source(x: usize, d: usize, i: usize, j: usize) -> Source {
    let outer_row = i + 2 >= d;
    let outer_col = j + 2 >= d;
    match x {
        0 if outer_row => Source::OuterA,
        1 if outer_row => Source::OuterA,
        1 if outer_col => Source::OuterC,
        2 if outer_col => Source::OuterC,
        _ => Source::Inner,
    }
}

/// Parameter boxes of patch `x` in the previous ring's `A` (for [`Source::OuterA`]) and `C`.
fn prolongation_box(x: usize, from_a: bool) -> [f64; 4] {
    match (x, from_a) {
        (0, true) => [-0.5, 0.0, 0.0, 0.5],
        (1, true) => [-0.5, 0.0, 0.5, 1.0],
        (1, false) => [0.5, 1.0, -0.5, 0.0],
        _ => [0.0, 0.5, -0.5, 0.0],
    }
}

/// The prolongation map of a degree-`e` patch to the box, raised to degree `d`.
fn prolong(e: usize, d: usize, b: [f64; 4]) -> DMatrix<f64> {
    let r = raise(e, d);
    kron(
        &(&r * subsegment(e, b[0], b[1])),
        &(&r * subsegment(e, b[2], b[3])),
    )
}

/// Assembles the three patches of a ring sector: inner blocks (`k^2 x src` each, already
/// applied to the guide data) and the previous ring's `A` and `C` (degree `e`, `(e+1)^2 x src`;
/// only their three layers at the inner edge matter).
fn assemble(
    d: usize,
    k: usize,
    inner: &Blocks,
    prev_a: &DMatrix<f64>,
    prev_c: &DMatrix<f64>,
    e: usize,
    mk: Option<MacroKind>,
) -> [DMatrix<f64>; 3] {
    let src = prev_a.ncols();
    let m = (d + 1) * (d + 1);
    let mut out = [
        DMatrix::zeros(m, src),
        DMatrix::zeros(m, src),
        DMatrix::zeros(m, src),
    ];
    // The previous ring is a macro spline (virtual bi-5) or a polynomial (bi-3 surroundings,
    // bi-5/6 rings).
    let pro = |b: [f64; 4]| match mk {
        Some(k) if e == 5 => k.prolong(b),
        _ => prolong(e, d, b),
    };
    for x in 0..3 {
        let pa = pro(prolongation_box(x, true)) * prev_a;
        let pc = pro(prolongation_box(x, false)) * prev_c;
        let mut count = vec![0usize; m];
        let mut acc = DMatrix::<f64>::zeros(m, src);
        for (c, blk) in &inner[x] {
            for i in 0..k {
                for j in 0..k {
                    let r = block_entry(d, *c, i, j);
                    let add = acc.row(r) + blk.row(i * k + j);
                    acc.set_row(r, &add);
                    count[r] += 1;
                }
            }
        }
        for i in 0..=d {
            for j in 0..=d {
                let r = i * (d + 1) + j;
                let row = match source(x, d, i, j) {
                    Source::OuterA => pa.row(r).into_owned(),
                    Source::OuterC => pc.row(r).into_owned(),
                    Source::Inner => {
                        debug_assert!(count[r] > 0);
                        acc.row(r) / count[r].max(1) as f64
                    }
                };
                out[x].set_row(r, &row);
            }
        }
    }
    out
}

/// Applies each block to a matrix of guide data (`(dg + 1)^2 x src`).
fn apply_blocks(b: &Blocks, g: &DMatrix<f64>) -> Blocks {
    let mut out: Blocks = Default::default();
    for x in 0..3 {
        out[x] = b[x].iter().map(|(c, m)| (*c, m * g)).collect();
    }
    out
}

/// The c-net (layout of [`crate::mesh::PolyMesh::cnet_indices`], two rings) index of chart
/// point `(i, j)` of sector `s` (any integers within two rings of the centre).
pub fn cnet_index(n: usize, s: usize, i: i32, j: i32) -> Option<usize> {
    let (mut s, mut i, mut j) = (s % n, i, j);
    for _ in 0..4 {
        if i == 0 && j == 0 {
            return Some(0);
        }
        if i >= 1 && j >= 0 {
            break;
        }
        if j < 0 {
            (s, i, j) = ((s + n - 1) % n, -j, i);
        } else if i == 0 {
            (s, i, j) = ((s + 1) % n, j, 0);
        } else {
            (s, i, j) = ((s + 1) % n, j, -i);
        }
    }
    if !(1..=2).contains(&i) || !(0..=2).contains(&j) {
        return None;
    }
    Some(1 + 6 * s + 3 * (i as usize - 1) + j as usize)
}

/// The bi-3 patch of the c-net face with lower-left chart corner `(ci, cj)` of sector `s`, as
/// rows over the c-net; net points outside the two rings are left out (zero): only the three
/// layers at the face's edge to the cap are exact, which is all the prolongation uses.
fn surrounding_patch(n: usize, s: usize, ci: i32, cj: i32) -> DMatrix<f64> {
    let b = crate::bezier::convert::CUBIC_BSPLINE;
    let mut m = DMatrix::zeros(16, 6 * n + 1);
    for x in 0..4 {
        for y in 0..4 {
            for p in 0..4 {
                for q in 0..4 {
                    let w = b[x][p] * b[y][q];
                    if w == 0.0 {
                        continue;
                    }
                    if let Some(c) = cnet_index(n, s, ci - 1 + p as i32, cj - 1 + q as i32) {
                        m[(4 * x + y, c)] += w;
                    }
                }
            }
        }
    }
    m
}

/// Gram matrix of `F_k` on one bi-`d` sector over the unit square.
pub fn fairness_gram(d: usize, k: usize) -> DMatrix<f64> {
    let m = (d + 1) * (d + 1);
    let mut g = DMatrix::zeros(m, m);
    let gl = gauss_legendre(d + 1);
    for &(x, wx) in &gl {
        for &(y, wy) in &gl {
            for i in 0..=k {
                let j = k - i;
                let bu = bernstein_derivs(d, i, x);
                let bv = bernstein_derivs(d, j, y);
                let v = nalgebra::DVector::from_fn(m, |r, _| bu[r / (d + 1)] * bv[r % (d + 1)]);
                g += (wx * wy * binom(k, i)) * &v * v.transpose();
            }
        }
    }
    g
}

/// Options of guided subdivision.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GuidedOptions {
    /// Degree of the rings.
    pub ring: RingDegree,
    /// Degree of the guide.
    pub guide: GuideDegree,
    /// The characteristic map (and so lambda).
    pub chi: ChiKind,
    /// The guide's target.
    pub fit: GuideFit,
}

/// Guided subdivision at one valence: the guide space, the sampling tables and the fit.
#[derive(Debug, Clone)]
pub struct Guided {
    /// Valence.
    pub n: usize,
    /// Options.
    pub opts: GuidedOptions,
    /// The guide space.
    pub space: GuideSpace,
    /// The characteristic ring.
    pub chi: CharRing,
    /// `P_0` from the c-net (`dim x (6 n + 1)`).
    pub fit: DMatrix<f64>,
    /// Restriction of a guide sector to `[0, lambda]^2` (`(dg+1)^2` square).
    pub restrict: DMatrix<f64>,
    /// Ring `l >= 1` of a sector from the guide sector of level `l - 1`
    /// (`3 (d+1)^2 x (dg+1)^2`, patches A, B, C).
    pub ring_table: DMatrix<f64>,
    /// Sector `s`'s ring 0 from the c-net: `3 (d+1)^2 x (6 n + 1)` per sector.
    pub ring0: Vec<DMatrix<f64>>,
}

/// The valence guided subdivision caps (at least 3, not the regular 4).
fn check_valence(n: usize) -> Result<usize> {
    if n < 3 {
        return Err(Error::InvalidArgument(format!(
            "valence {n}: a valence is at least 3"
        )));
    }
    if n == 4 {
        return Err(Error::Unsupported(
            "valence 4 is regular: guided subdivision caps extraordinary vertices only".into(),
        ));
    }
    Ok(n)
}

/// The per-valence tables of [`Guided`] that need neither the guide space nor the fit (so
/// that the characteristic ring costs O(1) in the valence): `chi`, the restriction, the inner
/// jet tables and the ring table.
pub struct RingTables {
    /// The characteristic ring.
    pub chi: CharRing,
    /// Restriction of a guide sector to `[0, lambda]^2`.
    pub restrict: DMatrix<f64>,
    inner: Blocks,
    /// Ring `l >= 1` of a sector from the guide sector of level `l - 1` ([`Guided::ring_table`]).
    pub ring_table: DMatrix<f64>,
}

impl RingTables {
    /// The tables at valence `n`.
    ///
    /// # Errors
    /// Valences below 3 or 4, or a characteristic map that does not exist at `n`.
    pub fn new(n: usize, opts: GuidedOptions) -> Result<RingTables> {
        let chi = CharRing::new(check_valence(n)?, opts.chi)?;
        let dg = opts.guide.degree();
        let mg = (dg + 1) * (dg + 1);
        let d = opts.ring.degree();
        let k = opts.ring.jet();
        let restrict = {
            let s = subsegment(dg, 0.0, chi.lambda);
            kron(&s, &s)
        };
        let inner = jet_tables(&chi, dg, d, k, INNER);
        // Ring l >= 1 from the guide sector g of level l - 1: inner jets of R g, outer layers
        // from the previous ring's inner layers (jets of g).
        let ring_table = {
            let id = DMatrix::identity(mg, mg);
            let prev = assemble(
                d,
                k,
                &apply_blocks(&inner, &id),
                &DMatrix::zeros((d + 1) * (d + 1), mg),
                &DMatrix::zeros((d + 1) * (d + 1), mg),
                d,
                None,
            );
            let cur = assemble(
                d,
                k,
                &apply_blocks(&inner, &restrict),
                &prev[0],
                &prev[2],
                d,
                opts.ring.macro_kind(),
            );
            let m = (d + 1) * (d + 1);
            let mut t = DMatrix::zeros(3 * m, mg);
            for x in 0..3 {
                t.view_mut((x * m, 0), (m, mg)).copy_from(&cur[x]);
            }
            t
        };
        Ok(RingTables {
            chi,
            restrict,
            inner,
            ring_table,
        })
    }
}

/// The limit point's stencil on the c-net at valence `n` (the first row of [`Guided::fit`]),
/// in time linear in `n` from the fit's frequency-0 part (`fit::limit_row`) for the bi-5
/// guide in the paper's coordinates.
///
/// # Errors
/// As [`RingTables::new`]; other guide degrees (their guide space has no Bloch basis here).
pub fn limit_stencil(n: usize, opts: GuidedOptions) -> Result<Vec<f64>> {
    if opts.guide != GuideDegree::Bi5 {
        return Err(Error::Unsupported(format!(
            "valence {n}: the frequency-0 fit needs the bi-5 guide"
        )));
    }
    let chi = CharRing::new(check_valence(n)?, opts.chi)?;
    fit::limit_row(n, &chi, opts.fit)
}

impl Guided {
    /// The scheme at valence `n` with the given options.
    pub fn new(n: usize, opts: GuidedOptions) -> Result<Guided> {
        let space = GuideSpace::new(check_valence(n)?, opts.guide)?;
        let dg = space.degree;
        let mg = (dg + 1) * (dg + 1);
        let d = opts.ring.degree();
        let k = opts.ring.jet();
        let RingTables {
            chi,
            restrict,
            inner,
            ring_table,
        } = RingTables::new(n, opts)?;
        let fit = fit_matrix(n, &space, &chi, opts.fit)?;
        let guide0 = &space.basis * &fit;
        let mut ring0 = Vec::with_capacity(n);
        for s in 0..n {
            let gs = guide0.rows(s * mg, mg).into_owned();
            let pa = surrounding_patch(n, s, 1, 0);
            let pc = surrounding_patch(n, s, 0, 1);
            let cur = assemble(d, k, &apply_blocks(&inner, &gs), &pa, &pc, 3, None);
            let m = (d + 1) * (d + 1);
            let mut t = DMatrix::zeros(3 * m, 6 * n + 1);
            for x in 0..3 {
                t.view_mut((x * m, 0), (m, 6 * n + 1)).copy_from(&cur[x]);
            }
            ring0.push(t);
        }
        Ok(Guided {
            n,
            opts,
            space,
            chi,
            fit,
            restrict,
            ring_table,
            ring0,
        })
    }

    /// Degree of the ring patches.
    pub fn degree(&self) -> usize {
        self.opts.ring.degree()
    }

    /// Ring `l` as stencils on the c-net: per sector `s`, the `3 (d + 1)^2 x (6 n + 1)` matrix
    /// whose rows are the weights of the c-net points in the coefficients of the patches `A`,
    /// `B`, `C` (virtual bi-5 for the macro variants). Ring 0 is [`Guided::ring0`]; ring
    /// `l >= 1` is the per-valence table [`Guided::ring_table`] (the paper's "efficient
    /// implementation", `3 (6^2 x 6^2)` for bi-5, `3 (7^2 x 6^2)` for bi-6) applied to the guide
    /// restricted `l - 1` times by the tabulated de Casteljau map [`Guided::restrict`].
    pub fn ring_stencils(&self, l: usize) -> Vec<DMatrix<f64>> {
        if l == 0 {
            return self.ring0.clone();
        }
        let mg = self.restrict.nrows();
        let mut r = DMatrix::identity(mg, mg);
        for _ in 1..l {
            r = &self.restrict * r;
        }
        let t = &self.ring_table * r;
        (0..self.n)
            .map(|s| &t * (self.space.basis.rows(s * mg, mg) * &self.fit))
            .collect()
    }

    /// The subdivision matrix on `P` (the map `P_l -> P_(l+1)` of the paper's Section 5).
    pub fn step_matrix(&self) -> DMatrix<f64> {
        self.space.step_matrix(self.chi.lambda)
    }

    /// Rings `0..count` of the cap of a c-net (positions in the layout of
    /// [`crate::mesh::PolyMesh::cnet_indices`]): `rings[l][3 s + x]` is patch `x` (A, B, C) of
    /// sector `s` as `(d + 1)^2` coefficients, row-major, in the mesh chart. Also returns the
    /// guide of the last level (`n (dg+1)^2` coefficients) for the cap.
    pub fn rings(
        &self,
        cnet: &[[f64; 3]],
        count: usize,
    ) -> Result<(Vec<RingPatches>, DMatrix<f64>)> {
        let n = self.n;
        if cnet.len() != 6 * n + 1 {
            return Err(Error::InvalidArgument(format!(
                "a c-net of valence {n} has {} points, got {}",
                6 * n + 1,
                cnet.len()
            )));
        }
        let c = DMatrix::from_fn(6 * n + 1, 3, |r, k| cnet[r][k]);
        let d = self.degree();
        let m = (d + 1) * (d + 1);
        let mg = self.restrict.nrows();
        let to_patches = |t: &DMatrix<f64>| -> Vec<Vec<[f64; 3]>> {
            (0..3)
                .map(|x| {
                    (0..m)
                        .map(|r| [t[(x * m + r, 0)], t[(x * m + r, 1)], t[(x * m + r, 2)]])
                        .collect()
                })
                .collect()
        };
        let mut out = Vec::with_capacity(count);
        let mut g = &self.space.basis * (&self.fit * &c);
        if count > 0 {
            let mut ring = Vec::with_capacity(3 * n);
            for s in 0..n {
                ring.extend(to_patches(&(&self.ring0[s] * &c)));
            }
            out.push(ring);
        }
        for _ in 1..count {
            let mut ring = Vec::with_capacity(3 * n);
            let mut next = g.clone();
            for s in 0..n {
                let gs = g.rows(s * mg, mg).into_owned();
                ring.extend(to_patches(&(&self.ring_table * &gs)));
                next.rows_mut(s * mg, mg).copy_from(&(&self.restrict * gs));
            }
            out.push(ring);
            g = next;
        }
        // Guide at the level of the last ring.
        Ok((out, g))
    }
}

mod fit;

pub use fit::GuideFit;
use fit::fit_matrix;
