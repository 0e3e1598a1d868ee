//! Primal ternary bi-2 subdivision: TPS (Section 4 of the bi-2 paper) and adjustable TPS
//! (Section 4.1), on quad nets (q-nets) with extraordinary vertices.
//!
//! # One engine: knot insertion on bi-2 splines with knot widths
//!
//! A quad net is a bi-2 B-spline whose every vertex carries one polynomial piece (its patch,
//! spanning half-way to its neighbours). A ternary step splits every piece in the ratio
//! `e : 1 - 2e : e` in both directions and takes the B-spline coefficients of the sub-pieces
//! (blossoms, [`super::blossom_weights`]): per vertex a vertex child (middle x middle), per edge
//! two edge children (end x middle), per quad four face children (end x end). With `e = 1/3`
//! and uniform knots these are exactly the paper's rules (17):
//! `a^new = (14 q + 7 a_i + 2 (a_(i-1) + a_(i+1)) + b_i + b_(i+1)) / 27` is the edge child next
//! to `q`, `b^new .. e^new` are face children `(4, 2, 2, 1) / 9`, `f^new` the edge child next
//! to `a_i`; only the vertex child of an extraordinary vertex is special, (18):
//! `q^new = (1 - alpha_1 - alpha_2) q + alpha_1 a_mean + alpha_2 b_mean`.
//! (The paper's Fig. 10 labels are lost; `a_i` are the edge neighbours of `q`, `b_i` the
//! diagonal neighbours between `a_(i-1)` and `a_i`, as (17) forces; `c .. f` are the
//! face and edge children of the quad `q, a_i, b_i, a_(i-1)`.)
//!
//! # Adjustable TPS: fairsub's reconstruction `tps-adjustable`
//!
//! The paper gives only the subdominant eigenvalue (22) of adjustable TPS, not its stencils. We
//! derive them as the paper describes, by splitting the bi-2 patches in the ratio
//! `e : 1 - 2e : e` (not `1/3 : 1/3 : 1/3`) and C^1-extending towards the centre, and we do it
//! exactly: the split is knot insertion, so the refined net is a bi-2 spline with non-uniform
//! knots, and the engine tracks the knot width of every vertex's piece in every direction
//! ([`Widths`]). Around an extraordinary vertex the widths settle after one step into the
//! stationary pattern centre `1`, ring `r = e / (1 - 2e)`, outer ring `r^2` (relative), so the
//! rules are stationary from level 1 on. In that pattern the rules are, with `s = 1 - 2e`:
//! `a^new = (1 - s) [(1 - 2y) q + y (a_(i-1) + a_(i+1))] + s [(1 - 2y) a_i + y (b_i + b_(i+1))]`,
//! `y = e s`; `b^new = (1 - s)^2 q + s (1 - s) (a_i + a_(i-1)) + s^2 b_i`; and the `(a, b)`
//! Fourier block has trace `2 s (e^2 (1 + 2c) + (1 - e)^2)` and determinant `s^4`, whose larger
//! root is exactly (22) (tested to 1e-12 for `n = 3..12`). `alpha_1, alpha_2` are then chosen
//! so that the limit point is TPS's (21): in the stationary pattern the left eigenvector of the
//! `(q, a_mean, b_mean)` block must be TPS's `(1 - tau_1 - tau_2, tau_1, tau_2)`, two linear
//! equations; the first step from the (uniform) input net has its own pair, chosen so that the
//! whole sequence converges to TPS's point ([`TernaryRules::alphas`]). `e = 1/3` gives back
//! (17), (18) exactly.
//!
//! One case the paper does not cover: at valence 3 with `e` below about 0.22 (the default 0.2
//! included), TPS's limit point forces a frequency-0 eigenvalue above (22) (0.5326 against
//! 0.5176 at `e = 0.2`), which would break C^1. There fairsub's documented fallback sets the
//! stationary `alpha`s so that the frequency-0 eigenvalues are `lambda^2` and `lambda^4` (as in
//! the regular case) and keeps TPS's limit point through the first step's `alpha`s
//! ([`TernaryRules::stationary_alphas`]).
//!
//! Because the knots are not uniform, a refined adjustable net is only meaningful with its
//! widths: [`AdjustableTps::refine_levels_exact`] (and `Scheme::refine_uniform`, which the CLI's
//! `--levels` uses) carry them from step to step; a single `refine` assumes the input net is
//! uniform (true for every input net).
//!
//! # Boundaries (fairsub's rules)
//!
//! As for Doo-Sabin ([`crate::schemes::doo_sabin`]), the boundary layer of points is doubled
//! (a phantom copy of every boundary point with its mirrored knot width), so the limit boundary
//! is the quadratic B-spline of the boundary polygon and every rule is the interior rule on the
//! net with phantoms. A ternary step then grows the net by a layer along the boundary: the
//! sub-pieces of the boundary pieces towards the phantoms (each a copy of the boundary row
//! refined along the boundary). Corners (one quad) are doubled in both directions. Boundary
//! vertices with more than two quads have no rules (an error naming the vertex).

use super::{end_child_weight, middle_child_weights};
use crate::error::{Error, Result};
use crate::mesh::PolyMesh;
use crate::schemes::common::check_child_size;
pub use crate::schemes::options::AlphaRule;
use crate::schemes::options::ids;
use crate::schemes::{Refinement, Scheme, finish_refinement};
use crate::stencil::{Stencil, StencilTable};

/// Knot widths of a quad net: for half-edge `h`, `[width of from(h)'s piece along h, width of
/// to(h)'s piece along h]`. A uniform net has all widths 1 ([`uniform_widths`]).
pub type Widths = Vec<[f64; 2]>;

/// Uniform knot widths for `mesh`.
pub fn uniform_widths(mesh: &PolyMesh) -> Widths {
    vec![[1.0, 1.0]; mesh.num_halfedges()]
}

/// The parameters of TPS at valence `n` (the paper's values).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct TpsParams {
    /// Valence.
    pub n: usize,
    /// `alpha_1`: `7 n / (2 n + 1)^2` for `n >= 4`, `339 / 896` for `n = 3`.
    pub alpha1: f64,
    /// `alpha_2 = alpha_1 / 7`.
    pub alpha2: f64,
    /// `tau_1` of the limit point (21).
    pub tau1: f64,
    /// `tau_2` of the limit point (21).
    pub tau2: f64,
    /// The closed-form subdominant eigenvalue `(5 + 2c + 2 sqrt(c^2 + 5c + 4)) / 27`.
    pub lambda: f64,
}

impl TpsParams {
    /// The parameters at valence `n >= 3`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for `n < 3`.
    pub fn new(n: usize) -> Result<TpsParams> {
        super::at_least_three(n, "TPS needs a valence of at least 3")?;
        let nf = n as f64;
        let alpha1 = if n == 3 {
            339.0 / 896.0
        } else {
            7.0 * nf / ((2.0 * nf + 1.0) * (2.0 * nf + 1.0))
        };
        let alpha2 = alpha1 / 7.0;
        let den = 39.0 * alpha1 + 42.0 * alpha2 + 20.0;
        let c = super::cos_2pi(1, n as i64);
        Ok(TpsParams {
            n,
            alpha1,
            alpha2,
            tau1: 18.0 * (2.0 * alpha1 + alpha2) / den,
            tau2: 3.0 * (alpha1 + 8.0 * alpha2) / den,
            lambda: tps_root(c),
        })
    }

    /// The paper's subsubdominant formula `(5 + 2 c2 + 2 sqrt(c2^2 + 5 c2 + 4)) / 27` with the
    /// printed `c2 = cos(pi / n)` (suspicious: it exceeds the subdominant eigenvalue).
    pub fn printed_subsubdominant(&self) -> f64 {
        tps_root((std::f64::consts::PI / self.n as f64).cos())
    }

    /// The same formula with `c2 = cos(4 pi / n) = c_2` of (20), the larger root of `D_2`.
    pub fn corrected_subsubdominant(&self) -> f64 {
        tps_root(super::cos_2pi(2, self.n as i64))
    }
}

/// The larger root of (20), `(5 + 2c + 2 sqrt(c^2 + 5c + 4)) / 27`.
pub fn tps_root(c: f64) -> f64 {
    (5.0 + 2.0 * c + 2.0 * (c * c + 5.0 * c + 4.0).max(0.0).sqrt()) / 27.0
}

/// Formula (22): the subdominant eigenvalue of adjustable TPS with split ratio `e` at
/// `c = cos(2 pi / n)`.
pub fn adjustable_lambda(e: f64, c: f64) -> f64 {
    let a = e * e * (1.0 + 2.0 * c) + (1.0 - e) * (1.0 - e);
    let b = (c + 1.0) * (e * e * c + (1.0 - e) * (1.0 - e));
    (1.0 - 2.0 * e) * (a + 2.0 * e * b.max(0.0).sqrt())
}

/// The rules of one ternary scheme: the split ratio and the rule at extraordinary vertices.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TernaryRules {
    /// Split ratio `e` (`1/3` for TPS).
    pub e: f64,
    /// The choice of `alpha_1, alpha_2`.
    pub alphas: AlphaRule,
}

impl TernaryRules {
    /// TPS: `e = 1/3`, the paper's `alpha`s.
    pub const TPS: TernaryRules = TernaryRules {
        e: 1.0 / 3.0,
        alphas: AlphaRule::Published,
    };

    /// Adjustable TPS with split ratio `e` and the paper's choice of `alpha`s.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] unless `0 < e < 1/2`.
    pub fn adjustable(e: f64) -> Result<TernaryRules> {
        Self::adjustable_with(e, AlphaRule::TpsLimitPoint)
    }

    /// Adjustable TPS with split ratio `e` and the given choice of `alpha`s.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] unless `0 < e < 1/2`.
    pub fn adjustable_with(e: f64, alphas: AlphaRule) -> Result<TernaryRules> {
        if !(e > 0.0 && e < 0.5) {
            return Err(Error::InvalidArgument(format!(
                "the split ratio e of adjustable TPS must lie in (0, 1/2) (got {e})"
            )));
        }
        Ok(TernaryRules { e, alphas })
    }

    /// `r = e / (1 - 2e)`: the stationary ring width relative to the centre (1 for TPS).
    pub fn ring_ratio(&self) -> f64 {
        self.e / (1.0 - 2.0 * self.e)
    }

    /// The averaged (Fourier frequency 0) rows of `a^new` and `b^new` over `(q, a_mean,
    /// b_mean)` at an extraordinary vertex whose ring pieces have width `h1` relative to the
    /// centre piece.
    pub fn averaged_rows(&self, h1: f64) -> [[f64; 3]; 2] {
        let t = end_child_weight(1.0, h1, self.e);
        let m = middle_child_weights(h1, 1.0, h1, self.e);
        [
            [
                (1.0 - t) * m[1],
                (1.0 - t) * (m[0] + m[2]) + t * m[1],
                t * (m[0] + m[2]),
            ],
            [(1.0 - t) * (1.0 - t), 2.0 * t * (1.0 - t), t * t],
        ]
    }

    /// The averaged `(q, a_mean, b_mean)` block (Fourier frequency 0 without the outer ring)
    /// at valence `n`, ring width `h1`, with rule (18)'s `alpha_1, alpha_2`.
    pub fn frequency0_block(&self, h1: f64, a1: f64, a2: f64) -> [[f64; 3]; 3] {
        let [ra, rb] = self.averaged_rows(h1);
        [[1.0 - a1 - a2, a1, a2], ra, rb]
    }

    /// `(alpha_1, alpha_2)` with `target = l M` for the frequency-0 block `M` at ring width
    /// `h1`, given the limit functional `l` of the following levels: the choice that gives the
    /// limit point `target` (weights of `q, a_mean, b_mean`).
    fn alphas_for(&self, h1: f64, l: [f64; 3], target: [f64; 3]) -> (f64, f64) {
        let [ra, rb] = self.averaged_rows(h1);
        let a1 = (target[1] - l[1] * ra[1] - l[2] * rb[1]) / l[0];
        let a2 = (target[2] - l[1] * ra[2] - l[2] * rb[2]) / l[0];
        (a1, a2)
    }

    /// TPS's limit point (21) as weights of `(q, a_mean, b_mean)`.
    fn tps_limit(n: usize) -> Result<[f64; 3]> {
        let p = TpsParams::new(n)?;
        Ok([1.0 - p.tau1 - p.tau2, p.tau1, p.tau2])
    }

    /// The stationary `(alpha_1, alpha_2)` at valence `n` (knot pattern `1, r, r^2`), and
    /// whether the fallback was needed. The rule: the limit point is TPS's (21). Where that
    /// would put a frequency-0 eigenvalue at or above the subdominant eigenvalue (22) (valence
    /// 3 for `e` below about 0.22; no C^1 surface), fairsub's documented fallback sets the
    /// frequency-0 eigenvalues to `lambda^2, lambda^4`, as in the regular case; the surface's
    /// limit point is then still TPS's, through the first step ([`TernaryRules::alphas`]).
    pub fn stationary_alphas(&self, n: usize) -> Result<(f64, f64, bool)> {
        if self.alphas == AlphaRule::Published {
            let p = TpsParams::new(n)?;
            return Ok((p.alpha1, p.alpha2, false));
        }
        let r = self.ring_ratio();
        let lambda = adjustable_lambda(self.e, super::cos_2pi(1, n as i64));
        if self.alphas == AlphaRule::TpsLimitPoint {
            let t = Self::tps_limit(n)?;
            let (a1, a2) = self.alphas_for(r, t, t);
            let m = self.frequency0_block(r, a1, a2);
            if second_modulus(&m) < lambda * (1.0 - 1e-9) {
                return Ok((a1, a2, false));
            }
        }
        // Fallback: tr M = 1 + l^2 + l^4 and det M = l^6, linear in the alphas.
        let [ra, rb] = self.averaged_rows(r);
        let (l2, l4) = (lambda * lambda, lambda.powi(4));
        let c11 = ra[1] * rb[2] - ra[2] * rb[1];
        let c12 = -(ra[0] * rb[2] - ra[2] * rb[0]);
        let c13 = ra[0] * rb[1] - ra[1] * rb[0];
        // (1 - a1 - a2) c11 + a1 c12 + a2 c13 = l^6;  a1 + a2 = ra[1] + rb[2] - l^2 - l^4.
        let s = ra[1] + rb[2] - l2 - l4;
        // a1 (c12 - c11) + a2 (c13 - c11) = l^6 - c11, a2 = s - a1.
        let lhs = (c12 - c11) - (c13 - c11);
        let a1 = (l2 * l4 - c11 - s * (c13 - c11)) / lhs;
        Ok((a1, s - a1, self.alphas == AlphaRule::TpsLimitPoint))
    }

    /// `(alpha_1, alpha_2)` of rule (18) at valence `n` for ring width `h1` (relative to the
    /// centre): the published values for TPS; for adjustable TPS the stationary values in the
    /// stationary pattern (`h1 = r`), and at the first step from a uniform net (`h1 = 1`) the
    /// values that make the limit point of the whole sequence TPS's (21).
    pub fn alphas(&self, n: usize, h1: f64) -> Result<(f64, f64)> {
        let (a1, a2, _) = self.stationary_alphas(n)?;
        let r = self.ring_ratio();
        if self.alphas == AlphaRule::Published || (h1 - r).abs() <= 1e-9 * r {
            return Ok((a1, a2));
        }
        let l = left_fixed_vector(&self.frequency0_block(r, a1, a2));
        Ok(self.alphas_for(h1, l, Self::tps_limit(n)?))
    }
}

/// The second largest eigenvalue modulus of a 3x3 matrix with rows summing to 1 (the other two
/// eigenvalues besides 1).
fn second_modulus(m: &[[f64; 3]; 3]) -> f64 {
    let tr = m[0][0] + m[1][1] + m[2][2];
    let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    let (t, d) = (tr - 1.0, det);
    let disc = t * t - 4.0 * d;
    if disc >= 0.0 {
        let s = disc.sqrt();
        ((t + s) / 2.0).abs().max(((t - s) / 2.0).abs())
    } else {
        d.abs().sqrt()
    }
}

/// The left eigenvector of eigenvalue 1 of a 3x3 matrix with rows summing to 1, normalised to
/// sum 1.
fn left_fixed_vector(m: &[[f64; 3]; 3]) -> [f64; 3] {
    // l (M - I) = 0: columns 1 and 2 give two equations; with l0 = 1 solve for l1, l2.
    let a = [[m[1][1] - 1.0, m[2][1]], [m[1][2], m[2][2] - 1.0]];
    let b = [-m[0][1], -m[0][2]];
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    let l1 = (b[0] * a[1][1] - a[0][1] * b[1]) / det;
    let l2 = (a[0][0] * b[1] - b[0] * a[1][0]) / det;
    let s = 1.0 + l1 + l2;
    [1.0 / s, l1 / s, l2 / s]
}

/// TPS (scheme name `tps`): primal ternary bi-2 subdivision. See the [module](self)
/// documentation.
#[derive(Debug, Clone, Copy, Default)]
pub struct Tps;

/// Adjustable TPS (scheme name `tps-adjustable`, fairsub's reconstruction): ternary bi-2
/// subdivision with split ratio `e` (default 0.2). See the [module](self) documentation.
#[derive(Debug, Clone, Copy)]
pub struct AdjustableTps {
    /// The split ratio `e`, `0 < e < 1/2`.
    pub e: f64,
    /// The choice of rule (18)'s `alpha`s.
    pub alphas: AlphaRule,
}

impl Default for AdjustableTps {
    fn default() -> Self {
        AdjustableTps {
            e: 0.2,
            alphas: AlphaRule::TpsLimitPoint,
        }
    }
}

impl AdjustableTps {
    /// Adjustable TPS with split ratio `e` and the paper's choice of `alpha`s.
    pub fn new(e: f64) -> AdjustableTps {
        AdjustableTps {
            e,
            alphas: AlphaRule::TpsLimitPoint,
        }
    }

    /// The scheme's rules.
    ///
    /// # Errors
    /// For `e` outside `(0, 1/2)`.
    pub fn rules(&self) -> Result<TernaryRules> {
        TernaryRules::adjustable_with(self.e, self.alphas)
    }
}

impl AdjustableTps {
    /// `levels` exact steps, carrying the knot widths from step to step; returns the net and
    /// its widths.
    ///
    /// # Errors
    /// As [`Scheme::refine`], and for `e` outside `(0, 1/2)`.
    pub fn refine_levels_exact(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        mut progress: impl FnMut(usize),
    ) -> Result<(PolyMesh, Widths)> {
        let rules = self.rules()?;
        let mut m = mesh.clone();
        let mut w = uniform_widths(mesh);
        for l in 0..levels {
            let (r, nw) = ternary_step(&m, &w, &rules, ids::TPS_ADJUSTABLE.name())?;
            m = r.mesh;
            w = nw;
            progress(l + 1);
        }
        Ok((m, w))
    }
}

impl Scheme for Tps {
    fn step_size(&self, s: &crate::schemes::growth::NetSize) -> crate::schemes::growth::NetSize {
        crate::schemes::growth::ternary(s)
    }

    fn name(&self) -> &'static str {
        crate::schemes::options::ids::TPS.name()
    }

    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        Ok(ternary_step(mesh, &uniform_widths(mesh), &TernaryRules::TPS, self.name())?.0)
    }

    /// Limit points: (21) at extraordinary vertices, the centre of the vertex's bi-2 patch
    /// elsewhere (`(1, 6, 1) x (1, 6, 1) / 64`, with the doubled boundary layer on the
    /// boundary).
    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        ternary_limit_stencils(mesh, self.name())
    }
}

impl Scheme for AdjustableTps {
    fn step_size(&self, s: &crate::schemes::growth::NetSize) -> crate::schemes::growth::NetSize {
        crate::schemes::growth::ternary(s)
    }

    fn name(&self) -> &'static str {
        crate::schemes::options::ids::TPS_ADJUSTABLE.name()
    }

    /// One exact step from a uniform net (every input net is uniform).
    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        let rules = self.rules()?;
        Ok(ternary_step(mesh, &uniform_widths(mesh), &rules, self.name())?.0)
    }

    /// Several exact steps, carrying the knot widths ([`AdjustableTps::refine_levels_exact`]).
    fn refine_uniform(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        progress: &mut dyn FnMut(usize),
    ) -> Result<PolyMesh> {
        Ok(self.refine_levels_exact(mesh, levels, progress)?.0)
    }

    /// The exact steps of [`AdjustableTps::refine_levels_exact`] (the knot widths carried),
    /// each with its stencils.
    fn refine_steps(
        &self,
        mesh: &PolyMesh,
        levels: usize,
        step: &mut dyn FnMut(&PolyMesh, &mut Refinement) -> Result<()>,
    ) -> Result<PolyMesh> {
        let rules = self.rules()?;
        let mut m = mesh.clone();
        let mut w = uniform_widths(mesh);
        for _ in 0..levels {
            let (mut r, nw) = ternary_step(&m, &w, &rules, ids::TPS_ADJUSTABLE.name())?;
            step(&m, &mut r)?;
            m = r.mesh;
            w = nw;
        }
        Ok(m)
    }

    /// Refused: a refined adjustable net has non-uniform knots that a mesh does not carry, so
    /// its limit positions cannot be read from the mesh alone.
    fn limit_stencils(&self, _mesh: &PolyMesh) -> Result<StencilTable> {
        Err(Error::Unsupported(format!(
            "{} nets have non-uniform knots after refinement, which a mesh does not \
             carry, so their limit positions are not available from the mesh; write the exact \
             surface with --rings K instead of --limit",
            ids::TPS_ADJUSTABLE
        )))
    }
}

mod step;

use step::ternary_limit_stencils;
pub use step::{edge_child_index, face_child_index, regular_patch, ternary_step};

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn published_alphas_satisfy_the_limit_equations() {
        // The adjustable solve at e = 1/3, uniform widths, returns TPS's published alphas.
        let adj = TernaryRules {
            e: 1.0 / 3.0,
            alphas: AlphaRule::TpsLimitPoint,
        };
        for n in 3..=12 {
            let p = TpsParams::new(n).unwrap();
            let (a1, a2) = adj.alphas(n, 1.0).unwrap();
            assert!((a1 - p.alpha1).abs() < 1e-14, "n={n}: {a1} vs {}", p.alpha1);
            assert!((a2 - p.alpha2).abs() < 1e-14, "n={n}: {a2} vs {}", p.alpha2);
        }
    }

    #[crate::unit::test]
    fn uniform_rules_are_17() {
        let m = crate::mesh::nets::cnet(5, crate::mesh::nets::CnetShape::Convex, 2);
        let r = Tps.refine(&m).unwrap();
        // The edge child next to the centre along its first edge: (14 q + 7 a + 2 (..) + ..)/27.
        let h = m.vertex_halfedge(0);
        let e = m.he_edge(h) as usize;
        let k = if m.edge_halfedge(e) == h { 0 } else { 1 };
        let row = r.stencils.stencil(m.num_vertices() + 2 * e + k);
        let w: Vec<f64> = row.entries().iter().map(|x| x.1 * 27.0).collect();
        let mut sorted = w.clone();
        sorted.sort_by(|a, b| b.total_cmp(a));
        let expect = [14.0, 7.0, 2.0, 2.0, 1.0, 1.0];
        for (a, b) in sorted.iter().zip(expect) {
            assert!((a - b).abs() < 1e-12, "{sorted:?}");
        }
    }
}
