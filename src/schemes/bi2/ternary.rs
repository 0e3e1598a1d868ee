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
use crate::schemes::common::{Outgoing, check_child_size};
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
        if n < 3 {
            return Err(Error::InvalidArgument(format!(
                "TPS needs a valence of at least 3 (got {n})"
            )));
        }
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

/// How rule (18)'s `alpha_1, alpha_2` are chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AlphaRule {
    /// TPS's published values.
    Published,
    /// Adjustable TPS as the paper states it: the stationary limit point is TPS's (21) (with
    /// the valence-3 fallback of [`TernaryRules::stationary_alphas`]).
    #[default]
    TpsLimitPoint,
    /// fairsub's alternative for adjustable TPS: the stationary frequency-0 eigenvalues are
    /// `lambda^2, lambda^4` as in the regular case (`mu / lambda^2 = 1` in that block); the
    /// surface's limit point is still TPS's, through the first step's `alpha`s.
    RegularSpectrum,
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
            let (r, nw) = ternary_step(&m, &w, &rules, "tps-adjustable")?;
            m = r.mesh;
            w = nw;
            progress(l + 1);
        }
        Ok((m, w))
    }
}

impl Scheme for Tps {
    fn name(&self) -> &'static str {
        "tps"
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
    fn name(&self) -> &'static str {
        "tps-adjustable"
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

    /// Refused: a refined adjustable net has non-uniform knots that a mesh does not carry, so
    /// its limit positions cannot be read from the mesh alone.
    fn limit_stencils(&self, _mesh: &PolyMesh) -> Result<StencilTable> {
        Err(Error::Unsupported(
            "tps-adjustable nets have non-uniform knots after refinement, which a mesh does not \
             carry, so their limit positions are not available from the mesh; write the exact \
             surface with --rings K instead of --limit"
                .into(),
        ))
    }
}

/// The kind of a vertex for ternary refinement.
#[derive(Debug, Clone, Copy, PartialEq)]
enum VKind {
    /// Interior, valence 4.
    Regular,
    /// Interior, valence `n != 4` (`n >= 3`).
    Extraordinary,
    /// Boundary with two quads.
    Boundary,
    /// Boundary with one quad.
    Corner,
}

fn classify(mesh: &PolyMesh, name: &str) -> Result<Vec<VKind>> {
    for f in 0..mesh.num_faces() {
        if mesh.face_size(f) != 4 {
            return Err(Error::Unsupported(format!(
                "face {f} has {} sides; {name} refines quad nets (q-nets): apply one \
                 Catmull-Clark step first (fairsub subdivide --scheme catmull-clark --levels 1), \
                 or use pgs or bi2-mixed, which take n-gons",
                mesh.face_size(f)
            )));
        }
    }
    (0..mesh.num_vertices())
        .map(|v| {
            let k = Outgoing::new(mesh, v).count();
            if mesh.is_boundary_vertex(v) {
                match k {
                    1 => Ok(VKind::Corner),
                    2 => Ok(VKind::Boundary),
                    _ => Err(Error::Unsupported(format!(
                        "vertex {v} is a boundary vertex with {k} quads; {name} has no rules for \
                         extraordinary boundary vertices (way out: pgs or doo-sabin, whose \
                         boundary rules take them)"
                    ))),
                }
            } else {
                match k {
                    4 => Ok(VKind::Regular),
                    k if k >= 3 => Ok(VKind::Extraordinary),
                    _ => Err(Error::Unsupported(format!(
                        "vertex {v} is an interior vertex of valence {k}; {name} needs valence \
                         at least 3 (refine once with catmull-clark to remove it)"
                    ))),
                }
            }
        })
        .collect()
}

/// Weighted 3x3 tensor rule over a grid of vertex indices: `grid[ku][kv]`.
fn tensor3(grid: &[[u32; 3]; 3], wu: [f64; 3], wv: [f64; 3], out: &mut Stencil) {
    for (ku, col) in grid.iter().enumerate() {
        for (kv, &x) in col.iter().enumerate() {
            let w = wu[ku] * wv[kv];
            if w != 0.0 {
                out.add(x as usize, w);
            }
        }
    }
}

/// The 3x3 grid `grid[ku][kv]` of a regular, boundary or corner vertex with the knot widths
/// of its three pieces along `u` and along `v` (phantoms are copies with mirrored widths). `u`
/// runs along the vertex's first outgoing half-edge (the boundary half-edge on the boundary),
/// `v` counter-clockwise from it.
fn vertex_grid(
    mesh: &PolyMesh,
    w: &Widths,
    v: usize,
    kind: VKind,
) -> ([[u32; 3]; 3], [f64; 3], [f64; 3]) {
    let hs: Vec<u32> = Outgoing::new(mesh, v).collect();
    let to = |h: u32| mesh.he_to(h);
    let diag = |h: u32| mesh.he_to(mesh.he_next(h));
    let vi = v as u32;
    match kind {
        VKind::Regular => {
            let [h0, h1, h2, h3] = [hs[0], hs[1], hs[2], hs[3]];
            let grid = [
                [diag(h2), to(h2), diag(h1)],
                [to(h3), vi, to(h1)],
                [diag(h3), to(h0), diag(h0)],
            ];
            let wu = [w[h2 as usize][1], w[h0 as usize][0], w[h0 as usize][1]];
            let wv = [w[h3 as usize][1], w[h1 as usize][0], w[h1 as usize][1]];
            (grid, wu, wv)
        }
        VKind::Boundary => {
            // u along the boundary (bl, v, br), v inwards (phantom, v, in).
            let (h0, h1) = (hs[0], hs[1]);
            let p1 = mesh.he_prev(h1);
            let bl = mesh.he_from(p1);
            let grid = [
                [bl, bl, diag(h1)],
                [vi, vi, to(h1)],
                [to(h0), to(h0), diag(h0)],
            ];
            let wu = [w[p1 as usize][0], w[h0 as usize][0], w[h0 as usize][1]];
            let wi = w[h1 as usize][0];
            (grid, wu, [wi, wi, w[h1 as usize][1]])
        }
        VKind::Corner => {
            let h0 = hs[0];
            let p0 = mesh.he_prev(h0);
            let (u1, u2, x) = (to(h0), mesh.he_from(p0), diag(h0));
            let grid = [[vi, vi, u2], [vi, vi, u2], [u1, u1, x]];
            let wa = w[h0 as usize][0];
            let wb = w[p0 as usize][1];
            (
                grid,
                [wa, wa, w[h0 as usize][1]],
                [wb, wb, w[p0 as usize][0]],
            )
        }
        VKind::Extraordinary => unreachable!("extraordinary vertices have no grid"),
    }
}

/// The vertex child of a regular, boundary or corner vertex: middle x middle over its grid.
fn vertex_child_regular(mesh: &PolyMesh, w: &Widths, v: usize, kind: VKind, e: f64) -> Stencil {
    let (grid, wu, wv) = vertex_grid(mesh, w, v, kind);
    let mut s = Stencil::new();
    tensor3(
        &grid,
        middle_child_weights(wu[0], wu[1], wu[2], e),
        middle_child_weights(wv[0], wv[1], wv[2], e),
        &mut s,
    );
    s.merged()
}

/// The exact bi-2 patch (nine coefficient stencils, row-major, `u` along the vertex's first
/// outgoing half-edge) of a vertex of a ternary net with knot widths `w`, when the vertex is
/// regular (four quads), a boundary vertex with two quads or a corner; `None` otherwise.
pub fn regular_patch(mesh: &PolyMesh, w: &Widths, v: usize) -> Option<Vec<Stencil>> {
    if mesh
        .vertex_faces(v)
        .iter()
        .any(|&f| mesh.face_size(f as usize) != 4)
    {
        return None;
    }
    let k = Outgoing::new(mesh, v).count();
    let kind = match (mesh.is_boundary_vertex(v), k) {
        (false, 4) => VKind::Regular,
        (true, 2) => VKind::Boundary,
        (true, 1) => VKind::Corner,
        _ => return None,
    };
    let (grid, wu, wv) = vertex_grid(mesh, w, v, kind);
    let net: [[Stencil; 3]; 3] =
        std::array::from_fn(|a| std::array::from_fn(|b| Stencil::point(grid[a][b] as usize)));
    Some(super::bi2_patch_stencils(&net, wu, wv))
}

/// Rule (18) at an extraordinary vertex.
fn vertex_child_extraordinary(
    mesh: &PolyMesh,
    w: &Widths,
    v: usize,
    rules: &TernaryRules,
) -> Result<Stencil> {
    let hs: Vec<u32> = Outgoing::new(mesh, v).collect();
    let n = hs.len();
    let h1 = w[hs[0] as usize][1] / w[hs[0] as usize][0];
    let (a1, a2) = rules.alphas(n, h1)?;
    let mut s = Stencil::new();
    s.add(v, 1.0 - a1 - a2);
    for &h in &hs {
        s.add(mesh.he_to(h) as usize, a1 / n as f64);
        s.add(mesh.he_to(mesh.he_next(h)) as usize, a2 / n as f64);
    }
    Ok(s.merged())
}

/// The edge child of half-edge `h` (`v -> w`) next to `v`: end (along) x middle (across).
fn edge_child(mesh: &PolyMesh, w: &Widths, h: u32, e: f64) -> Stencil {
    let (v, x) = (mesh.he_from(h), mesh.he_to(h));
    let hi = h as usize;
    let t = end_child_weight(w[hi][0], w[hi][1], e);
    // Left face (of h): v's other neighbour yl, x's other neighbour xl.
    let p = mesh.he_prev(h);
    let yl = mesh.he_from(p);
    let xl = mesh.he_to(mesh.he_next(h));
    let wc = w[p as usize][1];
    let wl = w[p as usize][0];
    let (yr, xr, wr) = match mesh.he_twin(h) {
        Some(tw) => {
            let nt = mesh.he_next(tw);
            (
                mesh.he_to(nt),
                mesh.he_from(mesh.he_prev(tw)),
                w[nt as usize][1],
            )
        }
        // Boundary edge: the phantom side copies the edge (mirrored width).
        None => (v, x, wc),
    };
    let m = middle_child_weights(wr, wc, wl, e);
    let mut s = Stencil::new();
    for (k, (a, b)) in [(yr, xr), (v, x), (yl, xl)].into_iter().enumerate() {
        s.add(a as usize, (1.0 - t) * m[k]);
        s.add(b as usize, t * m[k]);
    }
    s.merged()
}

/// The face child of corner `h` (next to `from(h)`) of a quad: end x end.
fn face_child(mesh: &PolyMesh, w: &Widths, h: u32, e: f64) -> Stencil {
    let p = mesh.he_prev(h);
    let t1 = end_child_weight(w[h as usize][0], w[h as usize][1], e);
    let t2 = end_child_weight(w[p as usize][1], w[p as usize][0], e);
    let (v, w1, x, w2) = (
        mesh.he_from(h),
        mesh.he_to(h),
        mesh.he_to(mesh.he_next(h)),
        mesh.he_from(p),
    );
    Stencil::from_pairs([
        (v as usize, (1.0 - t1) * (1.0 - t2)),
        (w1 as usize, t1 * (1.0 - t2)),
        (w2 as usize, (1.0 - t1) * t2),
        (x as usize, t1 * t2),
    ])
}

/// One ternary step of a quad net with knot widths: the child net, its stencils and its
/// widths. Child layout: vertex children `0..V` (child `v` of vertex `v`); edge children
/// `V + 2e + k` (`k = 0` next to the start of the edge's half-edge, `1` next to its end); face
/// children `V + 2E + h` (next to the start of half-edge `h`); then the boundary layer.
///
/// # Errors
/// [`Error::Unsupported`] for non-quad faces, boundary vertices with more than two quads and
/// interior vertices of valence 2, naming the element and the way out.
pub fn ternary_step(
    mesh: &PolyMesh,
    widths: &Widths,
    rules: &TernaryRules,
    name: &str,
) -> Result<(Refinement, Widths)> {
    let kinds = classify(mesh, name)?;
    let (nv, ne, nh) = (mesh.num_vertices(), mesh.num_edges(), mesh.num_halfedges());
    let e = rules.e;
    let sigma = 1.0 - 2.0 * e;
    // Boundary-layer numbering.
    let base = (nv + 2 * ne + nh) as u32;
    let mut next = base;
    // Per boundary vertex: outer child (non-corner), or [out, in, corner-corner] for corners.
    let mut outer = vec![[u32::MAX; 3]; nv];
    for (slot, kind) in outer.iter_mut().zip(&kinds) {
        match kind {
            VKind::Boundary => {
                slot[0] = next;
                next += 1;
            }
            VKind::Corner => {
                *slot = [next, next + 1, next + 2];
                next += 3;
            }
            _ => {}
        }
    }
    let mut outer_edge = vec![u32::MAX; ne];
    for (e_idx, slot) in outer_edge.iter_mut().enumerate() {
        if mesh.is_boundary_edge(e_idx) {
            *slot = next;
            next += 2;
        }
    }
    check_child_size(name, next as usize)?;

    // Stencils.
    let mut rows: Vec<Stencil> = Vec::with_capacity(next as usize);
    for (v, &kind) in kinds.iter().enumerate() {
        rows.push(match kind {
            VKind::Extraordinary => vertex_child_extraordinary(mesh, widths, v, rules)?,
            k => vertex_child_regular(mesh, widths, v, k, e),
        });
    }
    for ei in 0..ne {
        let h = mesh.edge_halfedge(ei);
        rows.push(edge_child(mesh, widths, h, e));
        let back = mesh.he_twin(h);
        rows.push(match back {
            Some(t) => edge_child(mesh, widths, t, e),
            None => edge_child_reversed_boundary(mesh, widths, h, e),
        });
    }
    for h in 0..nh as u32 {
        rows.push(face_child(mesh, widths, h, e));
    }
    for (v, &kind) in kinds.iter().enumerate() {
        match kind {
            VKind::Boundary => {
                let hs: Vec<u32> = Outgoing::new(mesh, v).collect();
                let p1 = mesh.he_prev(hs[1]);
                let (bl, br) = (mesh.he_from(p1), mesh.he_to(hs[0]));
                let m = middle_child_weights(
                    widths[p1 as usize][0],
                    widths[hs[0] as usize][0],
                    widths[hs[0] as usize][1],
                    e,
                );
                rows.push(Stencil::from_pairs([
                    (bl as usize, m[0]),
                    (v, m[1]),
                    (br as usize, m[2]),
                ]));
            }
            VKind::Corner => {
                let h0 = mesh.vertex_halfedge(v);
                let p0 = mesh.he_prev(h0);
                let wa = widths[h0 as usize][0];
                let m = middle_child_weights(wa, wa, widths[h0 as usize][1], e);
                rows.push(Stencil::from_pairs([
                    (v, m[0] + m[1]),
                    (mesh.he_to(h0) as usize, m[2]),
                ]));
                let wb = widths[p0 as usize][1];
                let m = middle_child_weights(wb, wb, widths[p0 as usize][0], e);
                rows.push(Stencil::from_pairs([
                    (v, m[0] + m[1]),
                    (mesh.he_from(p0) as usize, m[2]),
                ]));
                rows.push(Stencil::point(v));
            }
            _ => {}
        }
    }
    for (ei, &oe) in outer_edge.iter().enumerate() {
        if oe == u32::MAX {
            continue;
        }
        let h = mesh.edge_halfedge(ei) as usize;
        let (a, b) = (
            mesh.he_from(h as u32) as usize,
            mesh.he_to(h as u32) as usize,
        );
        let t = end_child_weight(widths[h][0], widths[h][1], e);
        rows.push(Stencil::from_pairs([(a, 1.0 - t), (b, t)]));
        let t = end_child_weight(widths[h][1], widths[h][0], e);
        rows.push(Stencil::from_pairs([(b, 1.0 - t), (a, t)]));
    }
    debug_assert_eq!(rows.len(), next as usize);
    let mut table = StencilTable::with_capacity(nv, rows.len(), 9);
    for s in rows {
        table.push(s);
    }

    // Topology and widths.
    let edge_child_idx = |h: u32, near_from: bool| -> u32 {
        let ei = mesh.he_edge(h);
        let g = mesh.edge_halfedge(ei as usize);
        let k = u32::from(if g == h { !near_from } else { near_from });
        (nv as u32) + 2 * ei + k
    };
    let mut face_start = vec![0u32];
    let mut corners: Vec<u32> = Vec::with_capacity(9 * nh + 16 * ne);
    let mut cw: Widths = Vec::with_capacity(9 * nh + 16 * ne);
    let mut push_face =
        |pts: [u32; 4], wid: [[f64; 2]; 4], corners: &mut Vec<u32>, cw: &mut Widths| {
            corners.extend_from_slice(&pts);
            cw.extend_from_slice(&wid);
            face_start.push(corners.len() as u32);
        };
    // Per face: the 4x4 child grid in the face's chart rotated to start at corner k.
    let chart = |f: usize, k: usize| -> FaceChart {
        let h0f = mesh.face_halfedge(f);
        let hk = |j: usize| h0f + ((k + j) % 4) as u32;
        let (h0, h1, h2, h3) = (hk(0), hk(1), hk(2), hk(3));
        let v: [u32; 4] = [
            mesh.he_from(h0),
            mesh.he_from(h1),
            mesh.he_from(h2),
            mesh.he_from(h3),
        ];
        let wd = |h: u32, i: usize| widths[h as usize][i];
        let wu = [wd(h0, 0), wd(h0, 1), wd(h2, 0), wd(h2, 1)];
        let wv = [wd(h3, 1), wd(h1, 0), wd(h1, 1), wd(h3, 0)];
        let mut g = [[0u32; 4]; 4];
        g[0][0] = v[0];
        g[3][0] = v[1];
        g[3][3] = v[2];
        g[0][3] = v[3];
        g[1][0] = edge_child_idx(h0, true);
        g[2][0] = edge_child_idx(h0, false);
        g[3][1] = edge_child_idx(h1, true);
        g[3][2] = edge_child_idx(h1, false);
        g[2][3] = edge_child_idx(h2, true);
        g[1][3] = edge_child_idx(h2, false);
        g[0][2] = edge_child_idx(h3, true);
        g[0][1] = edge_child_idx(h3, false);
        let fc = |h: u32| (nv + 2 * ne) as u32 + h;
        g[1][1] = fc(h0);
        g[2][1] = fc(h1);
        g[2][2] = fc(h2);
        g[1][2] = fc(h3);
        let mut uw = [[0.0; 4]; 4];
        let mut vw = [[0.0; 4]; 4];
        for i in 0..4 {
            for j in 0..4 {
                let c = match (i >= 2, j >= 2) {
                    (false, false) => 0,
                    (true, false) => 1,
                    (true, true) => 2,
                    (false, true) => 3,
                };
                let fu = if i == 0 || i == 3 { sigma } else { e };
                let fv = if j == 0 || j == 3 { sigma } else { e };
                uw[i][j] = fu * wu[c];
                vw[i][j] = fv * wv[c];
            }
        }
        (g, uw, vw)
    };
    for f in 0..mesh.num_faces() {
        let (g, uw, vw) = chart(f, 0);
        for i in 0..3 {
            for j in 0..3 {
                push_face(
                    [g[i][j], g[i + 1][j], g[i + 1][j + 1], g[i][j + 1]],
                    [
                        [uw[i][j], uw[i + 1][j]],
                        [vw[i + 1][j], vw[i + 1][j + 1]],
                        [uw[i + 1][j + 1], uw[i][j + 1]],
                        [vw[i][j + 1], vw[i][j]],
                    ],
                    &mut corners,
                    &mut cw,
                );
            }
        }
    }
    // Boundary strips (one per boundary edge) and corner cells.
    for (ei, &oe) in outer_edge.iter().enumerate() {
        if oe == u32::MAX {
            continue;
        }
        let h = mesh.edge_halfedge(ei);
        let f = mesh.he_face(h) as usize;
        let k = (h - mesh.face_halfedge(f)) as usize;
        let (g, uw, vw) = chart(f, k);
        let (a, b) = (mesh.he_from(h) as usize, mesh.he_to(h) as usize);
        // Outer points along the strip, with (along, across) widths.
        // A corner's first outer child lies along its outgoing boundary edge, its second
        // along the incoming one.
        let oa = outer[a][0];
        let ob = if kinds[b] == VKind::Corner {
            outer[b][1]
        } else {
            outer[b][0]
        };
        let row = [g[0][0], g[1][0], g[2][0], g[3][0]];
        let out = [oa, oe, oe + 1, ob];
        let along = [uw[0][0], uw[1][0], uw[2][0], uw[3][0]];
        let across_row = [vw[0][0], vw[1][0], vw[2][0], vw[3][0]];
        // The outer children are end pieces across: e times the parent's width across.
        let across_out = [
            vw[0][0] / sigma * e,
            vw[1][0] / sigma * e,
            vw[2][0] / sigma * e,
            vw[3][0] / sigma * e,
        ];
        for q in 0..3 {
            push_face(
                [out[q], out[q + 1], row[q + 1], row[q]],
                [
                    [along[q], along[q + 1]],
                    [across_out[q + 1], across_row[q + 1]],
                    [along[q + 1], along[q]],
                    [across_row[q], across_out[q]],
                ],
                &mut corners,
                &mut cw,
            );
        }
    }
    for (v, &kind) in kinds.iter().enumerate() {
        if kind != VKind::Corner {
            continue;
        }
        let h0 = mesh.vertex_halfedge(v);
        let f = mesh.he_face(h0) as usize;
        let k = (h0 - mesh.face_halfedge(f)) as usize;
        let (_, uw, vw) = chart(f, k);
        let (wu, wv) = (uw[0][0] / sigma, vw[0][0] / sigma);
        let [o_out, o_in, cc] = outer[v];
        push_face(
            [cc, o_out, v as u32, o_in],
            [
                [e * wu, sigma * wu],
                [e * wv, sigma * wv],
                [sigma * wu, e * wu],
                [sigma * wv, e * wv],
            ],
            &mut corners,
            &mut cw,
        );
    }
    let r = finish_refinement(mesh, table, face_start, corners)?;
    Ok((r, cw))
}

/// Index of the edge child of [`ternary_step`] on the edge of half-edge `h`, next to `from(h)`
/// (`near_from`) or to `to(h)`.
pub fn edge_child_index(mesh: &PolyMesh, h: u32, near_from: bool) -> usize {
    let ei = mesh.he_edge(h) as usize;
    let g = mesh.edge_halfedge(ei);
    let k = usize::from(if g == h { !near_from } else { near_from });
    mesh.num_vertices() + 2 * ei + k
}

/// Index of the face child of [`ternary_step`] next to `from(h)` in the face of `h`.
pub fn face_child_index(mesh: &PolyMesh, h: u32) -> usize {
    mesh.num_vertices() + 2 * mesh.num_edges() + h as usize
}

/// The 4x4 child grid of a face in its chart (child indices), with each child's knot width
/// along the chart's `u` and `v`.
type FaceChart = ([[u32; 4]; 4], [[f64; 4]; 4], [[f64; 4]; 4]);

/// The edge child next to the end of boundary half-edge `h` (`a -> b`, no twin): the mirror of
/// [`edge_child`] for the reversed direction, whose phantom side is the edge itself.
fn edge_child_reversed_boundary(mesh: &PolyMesh, w: &Widths, h: u32, e: f64) -> Stencil {
    let hi = h as usize;
    let (a, b) = (mesh.he_from(h), mesh.he_to(h));
    let t = end_child_weight(w[hi][1], w[hi][0], e);
    // Across at b: inside the face the neighbour of b is to(next(h)); of a, from(prev(h)).
    let nx = mesh.he_next(h);
    let p = mesh.he_prev(h);
    let (yb, ya) = (mesh.he_to(nx), mesh.he_from(p));
    let wc = w[nx as usize][0];
    let wi = w[nx as usize][1];
    let m = middle_child_weights(wc, wc, wi, e);
    let mut s = Stencil::new();
    for (k, (x, y)) in [(b, a), (b, a), (yb, ya)].into_iter().enumerate() {
        s.add(x as usize, (1.0 - t) * m[k]);
        s.add(y as usize, t * m[k]);
    }
    s.merged()
}

/// Limit stencils of a uniform ternary net (TPS): (21) at extraordinary vertices, the centre
/// value of the vertex's bi-2 patch elsewhere.
fn ternary_limit_stencils(mesh: &PolyMesh, name: &str) -> Result<StencilTable> {
    let kinds = classify(mesh, name)?;
    let nv = mesh.num_vertices();
    let mut table = StencilTable::with_capacity(nv, nv, 9);
    for (v, &kind) in kinds.iter().enumerate() {
        let s = match kind {
            VKind::Extraordinary => {
                let hs: Vec<u32> = Outgoing::new(mesh, v).collect();
                let n = hs.len();
                let p = TpsParams::new(n)?;
                let mut s = Stencil::new();
                s.add(v, 1.0 - p.tau1 - p.tau2);
                for &h in &hs {
                    s.add(mesh.he_to(h) as usize, p.tau1 / n as f64);
                    s.add(mesh.he_to(mesh.he_next(h)) as usize, p.tau2 / n as f64);
                }
                s.merged()
            }
            k => {
                // The centre value of the bi-2 patch: (1, 6, 1) / 8 in both directions, which
                // is the middle rule with e -> 1/2 (a sub-piece of width 0 at the centre).
                vertex_child_regular(mesh, &uniform_widths(mesh), v, k, 0.5)
            }
        };
        table.push(s);
    }
    Ok(table)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
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

    #[test]
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
