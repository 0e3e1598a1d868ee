//! Tensor-product Bezier patches and Bezier curves.
//!
//! Every surface fairsub outputs is a set of polynomial pieces in Bernstein-Bezier form. A
//! [`BezierPatch`] of bi-degree `(du, dv)` stores its coefficients `b[i][j]` row-major with `i`
//! along `u` (`cps[i * (dv + 1) + j]`), the convention of the papers and of BezierView.
//!
//! This module holds the patch mathematics every consumer shares: evaluation and exact first and
//! second derivatives (allocation-free for degrees below [`curve::STACK_DEGREE`], since the
//! renderer calls them per pixel), unit normals that stay defined at collapsed corners,
//! Gauss / mean / principal curvatures, de Casteljau splitting, sub-patches, degree raising and
//! boundary extraction. A patch may be rational (BezierView's type 8): then it carries a weight
//! per coefficient and every operation here works on its homogeneous form (`rational`).
//! [`curve`] holds the univariate rules these are built from and
//! [`convert`] the B-spline to Bezier conversions, as matrices that also yield stencils.
//!
//! # Conventions
//! - The normal is `du x dv` normalised ([`BezierPatch::normal`]).
//! - Curvatures are signed with respect to that normal: a normal curvature is `x'' . n` over the
//!   first fundamental form, so a surface bending *away* from its normal has negative curvature.
//!   On a sphere with outward normal `k1 = k2 = H = -1/r`, `K = 1/r^2`
//!   ([`Derivatives::curvature`]).
//! - A [`Side`] is traversed in increasing parameter order: `U0`/`U1` (the sides `u = 0` / `u =
//!   1`) are parametrised by `v`, `V0`/`V1` by `u` ([`BezierPatch::boundary`]).

pub mod bern;
pub mod complex;
pub mod convert;
mod coons;
pub mod curve;
mod derivatives;
pub mod domain;
pub mod g1;
mod rational;

pub use derivatives::WELL_CONDITIONED;

pub use curve::BezierCurve;

use crate::geom::{Point, cross, norm, scale};
use curve::STACK_DEGREE;

/// A tensor-product Bezier patch of bi-degree `(deg_u, deg_v)`.
#[derive(Debug, Clone, PartialEq)]
pub struct BezierPatch {
    /// Degree in `u` (the first coefficient index).
    pub deg_u: usize,
    /// Degree in `v` (the second coefficient index).
    pub deg_v: usize,
    /// Coefficients, `b[i][j]` at `i * (deg_v + 1) + j`.
    pub cps: Vec<Point>,
    /// The weights of a rational patch, one per coefficient (positive; `cps` then holds the
    /// Euclidean control points, the homogeneous coefficients divided by their weights);
    /// `None` for a polynomial patch, which every surface fairsub builds is.
    pub weights: Option<Vec<f64>>,
}

/// A side of the unit square domain of a patch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Side {
    /// The side `u = 0`, parametrised by `v`.
    U0,
    /// The side `u = 1`, parametrised by `v`.
    U1,
    /// The side `v = 0`, parametrised by `u`.
    V0,
    /// The side `v = 1`, parametrised by `u`.
    V1,
}

impl Side {
    /// All four sides in the order `U0, U1, V0, V1` (the order of [`Side::index`]).
    pub const ALL: [Side; 4] = [Side::U0, Side::U1, Side::V0, Side::V1];

    /// Position of the side in [`Side::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }

    /// The domain point `(u, v)` at side parameter `t` (`U0 -> (0, t)`, `V1 -> (t, 1)`, ...).
    pub fn domain_point(self, t: f64) -> [f64; 2] {
        match self {
            Side::U0 => [0.0, t],
            Side::U1 => [1.0, t],
            Side::V0 => [t, 0.0],
            Side::V1 => [t, 1.0],
        }
    }

    /// The opposite side (`U0 <-> U1`, `V0 <-> V1`).
    pub fn opposite(self) -> Side {
        match self {
            Side::U0 => Side::U1,
            Side::U1 => Side::U0,
            Side::V0 => Side::V1,
            Side::V1 => Side::V0,
        }
    }
}

/// Position and exact partial derivatives up to second order at one domain point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Derivatives {
    /// The point.
    pub p: Point,
    /// `d/du`.
    pub du: Point,
    /// `d/dv`.
    pub dv: Point,
    /// `d^2/du^2`.
    pub duu: Point,
    /// `d^2/du dv`.
    pub duv: Point,
    /// `d^2/dv^2`.
    pub dvv: Point,
}

/// Curvatures at a surface point, signed with respect to the unit normal `du x dv / |du x dv|`
/// (see the module conventions: negative where the surface bends away from its normal).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Curvature {
    /// Gaussian curvature `K = k1 k2`.
    pub gauss: f64,
    /// Mean curvature `H = (k1 + k2) / 2`.
    pub mean: f64,
    /// Larger principal curvature.
    pub k1: f64,
    /// Smaller principal curvature.
    pub k2: f64,
}

impl Curvature {
    /// All fields NaN: curvature undefined (no tangent plane).
    pub const UNDEFINED: Curvature = Curvature {
        gauss: f64::NAN,
        mean: f64::NAN,
        k1: f64::NAN,
        k2: f64::NAN,
    };
}

/// Runs `f` on a zeroed scratch slice of `n` values, on the stack for `n <= STACK_DEGREE`.
#[inline]
fn with_values<R>(n: usize, f: impl FnOnce(&mut [f64]) -> R) -> R {
    if n <= STACK_DEGREE {
        let mut buf = [0.0; STACK_DEGREE];
        f(&mut buf[..n])
    } else {
        let mut buf = vec![0.0; n];
        f(&mut buf)
    }
}

/// Runs `f` on six zeroed scratch slices of `n` values each (the Bernstein values and
/// derivatives in `u`, then in `v`, each `n` long), on the stack for `n <= STACK_DEGREE`.
#[inline]
fn with_values6<R>(n: usize, f: impl FnOnce(&mut [f64]) -> R) -> R {
    if n <= STACK_DEGREE {
        let mut buf = [0.0; 6 * STACK_DEGREE];
        f(&mut buf[..6 * n])
    } else {
        let mut buf = vec![0.0; 6 * n];
        f(&mut buf)
    }
}

impl BezierPatch {
    /// A patch from its coefficients (`(deg_u + 1) * (deg_v + 1)` of them, row-major, `i` along u).
    ///
    /// # Panics
    /// Panics when the number of coefficients does not match the degrees.
    pub fn new(deg_u: usize, deg_v: usize, cps: Vec<Point>) -> Self {
        assert_eq!(
            cps.len(),
            (deg_u + 1) * (deg_v + 1),
            "coefficient count does not match degrees"
        );
        BezierPatch {
            deg_u,
            deg_v,
            cps,
            weights: None,
        }
    }

    /// A patch whose coefficient `b[i][j]` is `f(i, j)`.
    pub fn from_fn(deg_u: usize, deg_v: usize, mut f: impl FnMut(usize, usize) -> Point) -> Self {
        let mut cps = Vec::with_capacity((deg_u + 1) * (deg_v + 1));
        for i in 0..=deg_u {
            for j in 0..=deg_v {
                cps.push(f(i, j));
            }
        }
        BezierPatch {
            deg_u,
            deg_v,
            cps,
            weights: None,
        }
    }

    /// Coefficient `b[i][j]`.
    #[inline]
    pub fn cp(&self, i: usize, j: usize) -> Point {
        self.cps[i * (self.deg_v + 1) + j]
    }

    /// Mutable coefficient `b[i][j]`.
    #[inline]
    pub fn cp_mut(&mut self, i: usize, j: usize) -> &mut Point {
        &mut self.cps[i * (self.deg_v + 1) + j]
    }

    /// Column `j`: the `u`-curve coefficients `b[0][j], ..., b[du][j]`.
    fn column(&self, j: usize) -> Vec<Point> {
        (0..=self.deg_u).map(|i| self.cp(i, j)).collect()
    }

    /// Row `i`: the `v`-curve coefficients `b[i][0], ..., b[i][dv]`.
    fn row(&self, i: usize) -> &[Point] {
        let n = self.deg_v + 1;
        &self.cps[i * n..(i + 1) * n]
    }

    /// Builds a patch from new columns (`u`-curves, all of equal length).
    fn from_columns(cols: &[Vec<Point>]) -> BezierPatch {
        let nu = cols.first().map_or(1, Vec::len);
        let dv = cols.len().saturating_sub(1);
        BezierPatch::from_fn(nu - 1, dv, |i, j| cols[j][i])
    }

    /// Builds a patch from new rows (`v`-curves, all of equal length).
    fn from_rows(rows: &[Vec<Point>]) -> BezierPatch {
        let nv = rows.first().map_or(1, Vec::len);
        let du = rows.len().saturating_sub(1);
        BezierPatch::from_fn(du, nv - 1, |i, j| rows[i][j])
    }

    /// Applies a curve operation to every `u`-curve (column); to a rational patch's
    /// homogeneous form.
    fn map_u_curves(&self, f: impl Fn(&[Point]) -> Vec<Point>) -> BezierPatch {
        let f: &dyn Fn(&[Point]) -> Vec<Point> = &f;
        let poly = |p: &BezierPatch| {
            let cols: Vec<Vec<Point>> = (0..=p.deg_v).map(|j| f(&p.column(j))).collect();
            BezierPatch::from_columns(&cols)
        };
        match self.weights {
            Some(_) => rational::map(self, poly),
            None => poly(self),
        }
    }

    /// Applies a curve operation to every `v`-curve (row); to a rational patch's homogeneous
    /// form.
    fn map_v_curves(&self, f: impl Fn(&[Point]) -> Vec<Point>) -> BezierPatch {
        let f: &dyn Fn(&[Point]) -> Vec<Point> = &f;
        let poly = |p: &BezierPatch| {
            let rows: Vec<Vec<Point>> = (0..=p.deg_u).map(|i| f(p.row(i))).collect();
            BezierPatch::from_rows(&rows)
        };
        match self.weights {
            Some(_) => rational::map(self, poly),
            None => poly(self),
        }
    }

    /// The point at `(u, v)` (tensor-product Bernstein sum; no allocation for degrees below
    /// [`curve::STACK_DEGREE`]).
    pub fn eval(&self, u: f64, v: f64) -> Point {
        if let Some(w) = &self.weights {
            return rational::eval(self, w, u, v);
        }
        let (nu, nv) = (self.deg_u + 1, self.deg_v + 1);
        with_values(nu, |bu| {
            with_values(nv, |bv| {
                curve::bernstein(self.deg_u, u, bu);
                curve::bernstein(self.deg_v, v, bv);
                let mut p = [0.0; 3];
                for (i, &wu) in bu.iter().enumerate() {
                    let row = &self.cps[i * nv..(i + 1) * nv];
                    let mut q = [0.0; 3];
                    for (c, &wv) in row.iter().zip(bv.iter()) {
                        q[0] += wv * c[0];
                        q[1] += wv * c[1];
                        q[2] += wv * c[2];
                    }
                    p[0] += wu * q[0];
                    p[1] += wu * q[1];
                    p[2] += wu * q[2];
                }
                p
            })
        })
    }

    /// Position and exact first and second partial derivatives at `(u, v)`, from the Bernstein
    /// values and their derivatives (the derivative-net formulas), contracting `v` first. No
    /// allocation for degrees below [`curve::STACK_DEGREE`].
    pub fn derivatives(&self, u: f64, v: f64) -> Derivatives {
        if let Some(w) = &self.weights {
            return rational::derivatives(self, w, u, v);
        }
        // the common degrees with their sizes known at compile time (the same operations in
        // the same order, so the same bits, unrolled)
        match (self.deg_u, self.deg_v) {
            (3, 3) => return self.derivatives_fixed::<4, 4>(u, v),
            (2, 2) => return self.derivatives_fixed::<3, 3>(u, v),
            _ => {}
        }
        let (nu, nv) = (self.deg_u + 1, self.deg_v + 1);
        let n = nu.max(nv);
        with_values6(n, |buf| {
            let (bu, bv) = buf.split_at_mut(3 * n);
            let (bu0, rest) = bu.split_at_mut(n);
            let (bu1, bu2) = rest.split_at_mut(n);
            let (bv0, rest) = bv.split_at_mut(n);
            let (bv1, bv2) = rest.split_at_mut(n);
            curve::bernstein_derivs(self.deg_u, u, bu0, bu1, bu2);
            curve::bernstein_derivs(self.deg_v, v, bv0, bv1, bv2);
            combine_derivatives(&self.cps, nv, [&*bu0, &*bu1, &*bu2], [&*bv0, &*bv1, &*bv2])
        })
    }

    /// [`BezierPatch::derivatives`] for bi-degree `(NU - 1, NV - 1)` (which the caller checked),
    /// with the loop bounds known at compile time: the same sums in the same order.
    #[inline]
    fn derivatives_fixed<const NU: usize, const NV: usize>(&self, u: f64, v: f64) -> Derivatives {
        let (mut bu0, mut bu1, mut bu2) = ([0.0; NU], [0.0; NU], [0.0; NU]);
        let (mut bv0, mut bv1, mut bv2) = ([0.0; NV], [0.0; NV], [0.0; NV]);
        curve::bernstein_derivs_inline(NU - 1, u, &mut bu0, &mut bu1, &mut bu2);
        curve::bernstein_derivs_inline(NV - 1, v, &mut bv0, &mut bv1, &mut bv2);
        let cps: &[Point] = &self.cps[..NU * NV];
        combine_derivatives(cps, NV, [&bu0, &bu1, &bu2], [&bv0, &bv1, &bv2])
    }

    /// The domain direction from `(u, v)` toward the centre `(1/2, 1/2)` (`(1, 1)` at the
    /// centre itself): the direction along which [`BezierPatch::normal`] takes limits.
    pub fn inward(u: f64, v: f64) -> [f64; 2] {
        let (hu, hv) = (0.5 - u, 0.5 - v);
        let l = (hu * hu + hv * hv).sqrt();
        if l > 0.0 {
            [hu / l, hv / l]
        } else {
            [1.0, 1.0]
        }
    }

    /// The unit normal `du x dv / |du x dv|` at `(u, v)`.
    ///
    /// At a degenerate point (a collapsed edge such as the pole of a polar patch, a corner where
    /// both partials vanish or are parallel) it returns the limit of the normal approached from
    /// the interior along [`BezierPatch::inward`], computed exactly from the second derivatives
    /// ([`Derivatives::normal_toward`]). If that is undetermined too, it returns the normal at
    /// the first regular point of `(u, v) + s * inward` for `s = 1e-6, 1e-4, 1e-2`, and finally
    /// the zero vector (a patch collapsed to a curve or a point has no normal).
    pub fn normal(&self, u: f64, v: f64) -> Point {
        let d = self.derivatives(u, v);
        self.normal_from(u, v, &d)
    }

    /// [`BezierPatch::normal`] reusing derivatives already computed at `(u, v)`.
    pub fn normal_from(&self, u: f64, v: f64, d: &Derivatives) -> Point {
        let h = Self::inward(u, v);
        if let Some(n) = d.normal_toward(h) {
            return n;
        }
        for s in [1e-6, 1e-4, 1e-2] {
            let e = self.derivatives(u + s * h[0], v + s * h[1]);
            if e.is_regular() {
                let n = cross(e.du, e.dv);
                return scale(n, 1.0 / norm(n));
            }
        }
        [0.0; 3]
    }

    /// Gauss, mean and principal curvatures at `(u, v)` ([`Derivatives::curvature`]; signs
    /// relative to the normal `du x dv`, negative on a sphere with outward normal).
    ///
    /// At a degenerate point (collapsed edge) the curvature is taken at the first point of
    /// `(u, v) + s * inward`, `s = 1e-6, 1e-5, ..., 1e-2`, where the partials are regular and
    /// at least [`WELL_CONDITIONED`] apart in angle (sine) — an approximation of the limit,
    /// which exists where the surface has bounded curvature. Beside a collapsed edge the
    /// partials are far from parallel at once (`s = 1e-6`); at a straight corner (the open
    /// triangle fans of [`g1`], where `du` and `dv` are opposite) they are only `~s` apart,
    /// and `1e-6` away the curvature formula's rounding is `1e3` and more.
    /// [`Curvature::UNDEFINED`] (all NaN) when there is no such point nearby.
    pub fn curvatures(&self, u: f64, v: f64) -> Curvature {
        if let Some(c) = self.derivatives(u, v).curvature() {
            return c;
        }
        let h = Self::inward(u, v);
        for s in [1e-6, 1e-5, 1e-4, 1e-3, 1e-2] {
            let d = self.derivatives(u + s * h[0], v + s * h[1]);
            let (a, b) = (norm(d.du), norm(d.dv));
            if norm(cross(d.du, d.dv)) < WELL_CONDITIONED * a * b {
                continue;
            }
            if let Some(c) = d.curvature() {
                return c;
            }
        }
        Curvature::UNDEFINED
    }

    /// De Casteljau split at `u = t`: the patches over `[0, t] x [0, 1]` and `[t, 1] x [0, 1]`,
    /// each reparametrised over the unit square.
    pub fn split_u(&self, t: f64) -> (BezierPatch, BezierPatch) {
        if self.weights.is_some() {
            return rational::map2(self, |p| p.split_u(t));
        }
        let (l, r): (Vec<_>, Vec<_>) = (0..=self.deg_v)
            .map(|j| curve::split(&self.column(j), t))
            .unzip();
        (BezierPatch::from_columns(&l), BezierPatch::from_columns(&r))
    }

    /// De Casteljau split at `v = t`: the patches over `[0, 1] x [0, t]` and `[0, 1] x [t, 1]`.
    pub fn split_v(&self, t: f64) -> (BezierPatch, BezierPatch) {
        if self.weights.is_some() {
            return rational::map2(self, |p| p.split_v(t));
        }
        let (l, r): (Vec<_>, Vec<_>) = (0..=self.deg_u)
            .map(|i| curve::split(self.row(i), t))
            .unzip();
        (BezierPatch::from_rows(&l), BezierPatch::from_rows(&r))
    }

    /// The patch restricted to `[u0, u1] x [v0, v1]` and reparametrised over the unit square
    /// (by blossoming, so reversed intervals and extrapolation work too).
    pub fn subpatch(&self, u0: f64, u1: f64, v0: f64, v1: f64) -> BezierPatch {
        self.map_u_curves(|c| curve::subsegment(c, u0, u1))
            .map_v_curves(|c| curve::subsegment(c, v0, v1))
    }

    /// The same surface with `u`-degree one higher.
    pub fn raise_u(&self) -> BezierPatch {
        self.map_u_curves(curve::raise)
    }

    /// The same surface with `v`-degree one higher.
    pub fn raise_v(&self) -> BezierPatch {
        self.map_v_curves(curve::raise)
    }

    /// The same surface with bi-degree `(du, dv)`; `None` when a target degree is lower than
    /// the current one.
    pub fn raised_to(&self, du: usize, dv: usize) -> Option<BezierPatch> {
        if du < self.deg_u || dv < self.deg_v {
            return None;
        }
        let mut p = self.clone();
        while p.deg_u < du {
            p = p.raise_u();
        }
        while p.deg_v < dv {
            p = p.raise_v();
        }
        Some(p)
    }

    /// The patch with `u` and `v` swapped (`b'[j][i] = b[i][j]`). Flips the normal.
    pub fn transposed(&self) -> BezierPatch {
        if self.weights.is_some() {
            return rational::map(self, |p| p.transposed());
        }
        BezierPatch::from_fn(self.deg_v, self.deg_u, |i, j| self.cp(j, i))
    }

    /// The patch with `u` reversed (`b'[i][j] = b[du - i][j]`). Flips the normal.
    pub fn reversed_u(&self) -> BezierPatch {
        if self.weights.is_some() {
            return rational::map(self, |p| p.reversed_u());
        }
        BezierPatch::from_fn(self.deg_u, self.deg_v, |i, j| self.cp(self.deg_u - i, j))
    }

    /// The patch with `v` reversed (`b'[i][j] = b[i][dv - j]`). Flips the normal.
    pub fn reversed_v(&self) -> BezierPatch {
        if self.weights.is_some() {
            return rational::map(self, |p| p.reversed_v());
        }
        BezierPatch::from_fn(self.deg_u, self.deg_v, |i, j| self.cp(i, self.deg_v - j))
    }

    /// The coefficients of a boundary curve in increasing parameter order: `U0` is
    /// `b[0][0..=dv]`, `U1` is `b[du][0..=dv]` (parameter `v`), `V0` is `b[0..=du][0]`, `V1` is
    /// `b[0..=du][dv]` (parameter `u`).
    pub fn boundary(&self, side: Side) -> Vec<Point> {
        match side {
            Side::U0 => self.row(0).to_vec(),
            Side::U1 => self.row(self.deg_u).to_vec(),
            Side::V0 => self.column(0),
            Side::V1 => self.column(self.deg_v),
        }
    }

    /// The corner coefficient (= corner point) at `u = 0` or `1` and `v = 0` or `1`.
    pub fn corner(&self, at_u1: bool, at_v1: bool) -> Point {
        let i = if at_u1 { self.deg_u } else { 0 };
        let j = if at_v1 { self.deg_v } else { 0 };
        self.cp(i, j)
    }

    /// Axis-aligned bounding box `(min, max)` of the coefficients, which contains the patch
    /// (convex-hull property).
    pub fn control_bbox(&self) -> (Point, Point) {
        crate::geom::bounding_box(self.cps.iter().copied()).unwrap_or(([0.0; 3], [0.0; 3]))
    }

    /// The patch with every coefficient mapped by `f` (exact image for affine `f`; a rational
    /// patch keeps its weights).
    pub fn map_points(&self, f: impl FnMut(Point) -> Point) -> BezierPatch {
        BezierPatch {
            deg_u: self.deg_u,
            deg_v: self.deg_v,
            cps: self.cps.iter().copied().map(f).collect(),
            weights: self.weights.clone(),
        }
    }

    /// Whether the boundary curve on `side` is collapsed to a point: all its coefficients lie
    /// within `tol` of the first one.
    pub fn is_collapsed(&self, side: Side, tol: f64) -> bool {
        let b = self.boundary(side);
        b.iter().all(|p| crate::geom::dist(*p, b[0]) <= tol)
    }
}

#[cfg(feature = "unit-tests")]
mod tests;

/// Position and first and second derivatives of the tensor-product patch `cps` (rows of `nv`
/// points along `v`) from the Bernstein values and derivatives `bu = [B, B', B'']` in `u` and
/// `bv` in `v`, contracting `v` first; inlined so that fixed-size callers get unrolled loops
/// with the same sums in the same order (the same bits) as the general one.
#[inline(always)]
fn combine_derivatives(cps: &[Point], nv: usize, bu: [&[f64]; 3], bv: [&[f64]; 3]) -> Derivatives {
    let mut d = Derivatives {
        p: [0.0; 3],
        du: [0.0; 3],
        dv: [0.0; 3],
        duu: [0.0; 3],
        duv: [0.0; 3],
        dvv: [0.0; 3],
    };
    for (row, ((&w0, &w1), &w2)) in cps
        .chunks_exact(nv)
        .zip(bu[0].iter().zip(bu[1].iter()).zip(bu[2].iter()))
    {
        let (mut q0, mut q1, mut q2) = ([0.0; 3], [0.0; 3], [0.0; 3]);
        for (c, ((&v0, &v1), &v2)) in row
            .iter()
            .zip(bv[0].iter().zip(bv[1].iter()).zip(bv[2].iter()))
        {
            for k in 0..3 {
                q0[k] += v0 * c[k];
                q1[k] += v1 * c[k];
                q2[k] += v2 * c[k];
            }
        }
        for k in 0..3 {
            d.p[k] += w0 * q0[k];
            d.du[k] += w1 * q0[k];
            d.duu[k] += w2 * q0[k];
            d.dv[k] += w0 * q1[k];
            d.duv[k] += w1 * q1[k];
            d.dvv[k] += w0 * q2[k];
        }
    }
    d
}
