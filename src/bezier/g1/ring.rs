//! Reading a [`Hole`] off the last ring of a scheme: segments from the sides of ring patches
//! (or of patches that continue the ring C^1 into the hole), and the spoke tangents `T0, T1`
//! from the ring's chart in a given limit tangent plane. Every scheme's provider uses these, so
//! the conventions of [`super::hole`] are implemented once.
//!
//! # Tangent scale ([`chart_tangents`])
//!
//! The cap's centre conditions prescribe the spoke derivatives `t_s` per unit of the cap's
//! parameter, so their length shapes the cap. Near the centre a subdivision surface is, to first
//! order, `c + chi_1 T'_0 + chi_2 T'_1` with the scheme's characteristic map `chi` (its
//! subdominant eigenvector components) and the limit tangent vectors `T'` (the left
//! eigenvectors / tangent masks applied to the control points): the last ring, projected into
//! the limit tangent plane, *is* the characteristic map of that ring up to terms that vanish
//! like `mu^k / lambda^k`. The provider's plane gives the projection; in it, spoke `s` of the
//! hole runs from the centre (chart origin) to the spoke end `e_s` (the projected `E_s - C`),
//! where the ring's derivative along the spoke is `f_s` (the projected `-cross_a(0)` of
//! segment `a` of sector `s`, per unit of the cap's parameter). The spoke of the cap in the
//! chart is taken to be the quadratic with these three values, `q(0) = 0`, `q(1) = e_s`,
//! `q'(1) = f_s`, so its derivative at the centre is `q'(0) = 2 e_s - f_s`; `T0, T1` are the
//! Fourier mode 1 of these `n` vectors (least squares):
//! `T0 = (2/n) sum cos(2 pi s / n) (2 e_s - f_s)`, `T1 = (2/n) sum sin(2 pi s / n) (2 e_s - f_s)`.
//! For a power-law spoke `|x|^a` of the characteristic map (`a = log lambda / log (1/2)` for a
//! binary scheme) this is `(2 - a)` times the chord; for a regular ring (`a = 1`) it is the
//! exact derivative.
//!
//! Triangle holes (Loop's kites) take the cubic spoke with a vanishing second derivative at the
//! centre instead, `q(0) = 0`, `q''(0) = 0`, `q(1) = e_s`, `q'(1) = f_s`, whose derivative at
//! the centre is `(3 e_s - f_s) / 2`: `(3 - a) / 2` times the chord for a power-law spoke.
//! Loop's subdominant eigenvalue is `1/4` at valence 3 (`a = 2`), where the quadratic's
//! derivative `(2 - a) e_s` vanishes and the cap degenerates at its centre (measured: Gauss
//! curvature up to `2.3e6` on a cap whose last ring stays within `[-14, 20]`; with the cubic
//! `115`). At valences 4 to 8 the two fits give caps of similar fairness (the comparison is in
//! `schemes::loop_subdivision::surface::g1`). Quad holes keep the quadratic fit their caps were
//! measured with (Catmull-Clark's largest exponent, at valence 3, is `a = 1.29`).

use super::choose::{Cap, CapOptions, g1_cap_with};
use super::hole::{Fan, Hole, Layout, Segment};
use crate::bezier::complex::CapStep;
use crate::bezier::{BezierPatch, Side, curve};
use crate::error::{Error, Result};
use crate::geom::{Point, axpy, cross, dot, norm, normalize, scale, sub};

/// The side `side` of `p` as Bezier coefficients in the side's parameter, and the derivative off
/// that side pointing out of `p` (`-du` on `U0`, `du` on `U1`, `-dv` on `V0`, `dv` on `V1`).
fn side_and_outward(p: &BezierPatch, side: Side) -> (Vec<Point>, Vec<Point>) {
    let b = p.boundary(side);
    let (du, dv) = (p.deg_u, p.deg_v);
    let cross: Vec<Point> = match side {
        Side::U0 => (0..=dv)
            .map(|j| scale(sub(p.cp(0, j), p.cp(1, j)), du as f64))
            .collect(),
        Side::U1 => (0..=dv)
            .map(|j| scale(sub(p.cp(du, j), p.cp(du - 1, j)), du as f64))
            .collect(),
        Side::V0 => (0..=du)
            .map(|i| scale(sub(p.cp(i, 0), p.cp(i, 1)), dv as f64))
            .collect(),
        Side::V1 => (0..=du)
            .map(|i| scale(sub(p.cp(i, dv), p.cp(i, dv - 1)), dv as f64))
            .collect(),
    };
    (b, cross)
}

/// The hole's segment along side `side` of a ring patch `p` that borders the hole: the side
/// restricted to the side parameters `range[0] -> range[1]` (`[1, 0]` reverses it, `[0.5, 1]`
/// takes half of it) and the derivative out of `p` (into the hole) times the ratio of
/// the cap's transversal parameter length to `p`'s (1 when the hole sector and the ring patch
/// have the same parameter size).
///
/// `factor` is that ratio.
pub fn segment_from_ring(p: &BezierPatch, side: Side, range: [f64; 2], factor: f64) -> Segment {
    let (b, c) = side_and_outward(p, side);
    Segment {
        boundary: curve::subsegment(&b, range[0], range[1]),
        cross: curve::subsegment(&c, range[0], range[1])
            .into_iter()
            .map(|x| scale(x, factor))
            .collect(),
    }
}

/// The hole's segment along side `side` of a patch `p` that lies *inside* the hole and joins the
/// ring C^1 across that side (a scheme's C^1-to-the-ring fill, whose outer layers are the
/// ring's): the side over `range` and the derivative from the ring into the hole, which is `p`'s
/// derivative pointing away from the side, times `factor`.
pub fn segment_from_inside(p: &BezierPatch, side: Side, range: [f64; 2], factor: f64) -> Segment {
    segment_from_ring(p, side, range, -factor)
}

/// Projection of `x` onto the plane through the origin with unit normal `nrm`.
fn project_onto_plane(x: Point, nrm: Point) -> Point {
    axpy(x, -dot(x, nrm), nrm)
}

/// The spoke tangents `[T0, T1]` of a hole in the plane through its centre with normal
/// `normal` (the scheme's limit tangent plane), scaled by the ring's chart (see the
/// [module](self) documentation). The hole's own `tangents` are not read.
///
/// # Errors
/// When the fitted tangents are degenerate (parallel or vanishing), naming the hole's valence.
pub fn chart_tangents(hole: &Hole, normal: Point) -> Result<[Point; 2]> {
    let nrm = normalize(normal);
    if !nrm.iter().all(|x| x.is_finite()) || norm(normal) == 0.0 {
        return Err(Error::InvalidArgument(
            "the limit normal of the hole is not defined".into(),
        ));
    }
    let (t, n, size) = fit_tangents(hole, |x| project_onto_plane(x, nrm))?;
    let area = norm(cross(t[0], t[1]));
    if area.is_nan() || area <= 1e-6 * size * size {
        return Err(Error::Unsupported(format!(
            "the spoke tangents of the hole of valence {n} are degenerate in its tangent plane \
             (|T0 x T1| = {area:.3e} for spoke ends at distance {size:.3e})"
        )));
    }
    Ok(t)
}

/// The Fourier mode 1 `[T0, T1]` of the spoke derivatives `2 e_s - f_s` (quad layouts) or
/// `(3 e_s - f_s) / 2` (triangle layouts) mapped by `proj` (see the [module](self)
/// documentation), the valence and the largest `|proj(e_s)|`.
fn fit_tangents(hole: &Hole, proj: impl Fn(Point) -> Point) -> Result<([Point; 2], usize, f64)> {
    let (spokes, n, size) = spoke_derivatives(hole, &proj)?;
    let mut t = [[0.0; 3]; 2];
    if super::centre::is_half_plane(n, hole.fan()) {
        // two sectors: the spokes are opposite, `t_1 = -T0`, and say nothing across them.
        // Both vectors are fitted to chords of the half-plane chart
        // (`centre::half_plane_rows`): its spoke ends `phi_0(1, 0) = -phi_1(1, 0) =
        // (1 + w'(0) / 4) T0` and its corners `phi_0(1, 1) = -phi_1(1, 1) = k T1`. Not to the
        // spoke derivatives `2 e_s - f_s` of the other holes: at valence 2 Catmull-Clark's and
        // non-box's rings contract by 1/4 per step, their spokes are quadratic at the centre
        // (`|x|^2`, `f_s = 2 e_s`) and that fit vanishes (measured 1e-8 of the hole's size:
        // a cusp whose corner normals were rounding, 3.14 rad apart at 8 rings)
        let q = hole.to_quad_layout()?;
        let m = hole.layout()?.0.pieces();
        let corner = |s: usize| {
            *q.hole.sectors[s][m - 1]
                .boundary
                .last()
                .unwrap_or(&hole.centre)
        };
        let end = |s: usize| {
            *q.hole.sectors[s][0]
                .boundary
                .first()
                .unwrap_or(&hole.centre)
        };
        let w = super::system::weight(2, Fan::Closed, q.kappa, q.w1);
        let reach = 1.0 + (w[1] - w[0]) / 2.0;
        t[0] = scale(proj(sub(end(0), end(1))), 0.5 / reach);
        let across = proj(scale(sub(corner(0), corner(1)), 0.5));
        t[1] = scale(across, 1.0 / super::centre::HALF_PLANE_TWIST);
    } else if hole.is_open() {
        // least squares over the n + 1 spokes of the half-turn (cos and sin are not
        // orthogonal there; a dart's full turn counts its sharp spoke twice): the 2 x 2
        // normal equations
        let step = super::system::turn(n, hole.fan()) / n as f64;
        let (mut cc, mut cs, mut ss) = (0.0, 0.0, 0.0);
        let mut r = [[0.0; 3]; 2];
        for (s, ts) in spokes.iter().enumerate() {
            let (c, si) = ((step * s as f64).cos(), (step * s as f64).sin());
            (cc, cs, ss) = (cc + c * c, cs + c * si, ss + si * si);
            r[0] = axpy(r[0], c, *ts);
            r[1] = axpy(r[1], si, *ts);
        }
        let det = cc * ss - cs * cs;
        t[0] = scale(axpy(scale(r[0], ss), -cs, r[1]), 1.0 / det);
        t[1] = scale(axpy(scale(r[1], cc), -cs, r[0]), 1.0 / det);
    } else {
        for (s, ts) in spokes.iter().enumerate() {
            let th = 2.0 * std::f64::consts::PI * s as f64 / n as f64;
            t[0] = axpy(t[0], 2.0 * th.cos() / n as f64, *ts);
            t[1] = axpy(t[1], 2.0 * th.sin() / n as f64, *ts);
        }
    }
    Ok((t, n, size))
}

/// The spoke tangents of a crease's fan ([`Fan::Crease`]): `T0 = t0`, the crease's exact
/// derivative at the centre along spoke `0` as the provider gives it, and `T1` the least
/// squares fit of the other spokes' chart derivatives (mapped by `proj`) given `T0`:
/// `T1 = sum sin(th_s) (f_s - cos(th_s) T0) / sum sin(th_s)^2` over the `n + 1` spokes of the
/// half-turn. Both sides of a crease thus leave the centre along it with the same derivative.
/// A side of one face has `T1 = -T0` (its two spokes are the crease's halves).
fn crease_fit(hole: &Hole, t0: Point, proj: impl Fn(Point) -> Point) -> Result<[Point; 2]> {
    if hole.valence() == 1 {
        // one face between the crease's two halves: its spokes (a quarter-turn apart in the
        // chart) leave the centre along the crease, `t_1 = T1 = -T0`
        return Ok([t0, scale(t0, -1.0)]);
    }
    let (spokes, n, _) = spoke_derivatives(hole, &proj)?;
    let step = super::system::turn(n, hole.fan()) / n as f64;
    let (mut ss, mut r) = (0.0, [0.0; 3]);
    for (s, ts) in spokes.iter().enumerate() {
        let (c, si) = ((step * s as f64).cos(), (step * s as f64).sin());
        ss += si * si;
        r = axpy(r, si, axpy(*ts, -c, t0));
    }
    Ok([t0, scale(r, 1.0 / ss)])
}

/// [`chart_tangents`] of a crease's fan: `T0 = plane[0]` (the crease's exact derivative),
/// `T1` fitted in the plane (`crease_fit`).
///
/// # Errors
/// As [`chart_tangents`].
pub fn crease_tangents(hole: &Hole, plane: [Point; 2]) -> Result<[Point; 2]> {
    let nrm = normalize(cross(plane[0], plane[1]));
    if !nrm.iter().all(|x| x.is_finite()) {
        return Err(Error::InvalidArgument(
            "the limit normal of the crease's fan is not defined".into(),
        ));
    }
    crease_fit(hole, plane[0], |x| project_onto_plane(x, nrm))
}

/// The chart derivatives of the spokes (`2 e_s - f_s` or `(3 e_s - f_s) / 2`, see the
/// [module](self) documentation) mapped by `proj`, the valence and the largest `|proj(e_s)|`.
fn spoke_derivatives(
    hole: &Hole,
    proj: &impl Fn(Point) -> Point,
) -> Result<(Vec<Point>, usize, f64)> {
    let (layout, _) = hole.layout()?;
    let q = hole.to_quad_layout()?;
    let n = q.hole.valence();
    // spoke s ends at segment a of sector s; the last spoke of an open fan at segment b of
    // its last sector (`cross_b(0) = -dP/dv(0, 1)`, the derivative along that spoke)
    let mut ends: Vec<&Segment> = q.hole.sectors.iter().map(|sec| &sec[0]).collect();
    if hole.is_open() {
        ends.push(&q.hole.sectors[n - 1][1]);
    }
    let mut size: f64 = 0.0;
    let spokes: Vec<Point> = ends
        .iter()
        .map(|a| {
            let e = proj(sub(a.boundary[0], hole.centre));
            // per unit of the sector's parameter (a split sector's segments are per piece)
            let f = proj(scale(a.cross[0], -(layout.pieces() as f64)));
            size = size.max(norm(e));
            match layout {
                Layout::Quad | Layout::OpenQuad | Layout::Split(_) => axpy(scale(e, 2.0), -1.0, f),
                Layout::Triangle | Layout::OpenTriangle => scale(axpy(scale(e, 3.0), -1.0, f), 0.5),
            }
        })
        .collect();
    Ok((spokes, n, size))
}

/// The spoke tangents of a hole whose data are not positions (colours, texture coordinates:
/// per-point data through a patch table, three components at a time): the fit of
/// [`chart_tangents`] without the projection onto a tangent plane, which only positions have,
/// and without its degeneracy check (constant data have zero tangents). Linear in the data.
pub fn data_tangents(hole: &Hole) -> Result<[Point; 2]> {
    fit_tangents(hole, |x| x).map(|(t, _, _)| t)
}

/// [`data_tangents`] of a crease's fan: `T0` the data's first plane vector (the crease's
/// derivative tabulated like the positions'), `T1` fitted given it (`crease_fit`).
pub fn crease_data_tangents(hole: &Hole, plane: [Point; 2]) -> Result<[Point; 2]> {
    crease_fit(hole, plane[0], |x| x)
}

/// The spoke tangents of a hole of per-point data (not positions) from its provider's `plane`
/// vectors (tabulated like the positions'): a corner's both ([`Fan::Corner`]; a cone's, zero,
/// [`Fan::is_cone`]), a crease's fan
/// `T0` with `T1` fitted ([`crease_data_tangents`]), else both fitted ([`data_tangents`]).
pub fn hole_data_tangents(hole: &Hole, plane: [Point; 2]) -> Result<[Point; 2]> {
    if hole.kind.pins_plane() {
        Ok(plane)
    } else if hole.kind == Fan::Crease {
        crease_data_tangents(hole, plane)
    } else {
        data_tangents(hole)
    }
}

/// The G^1 cap of `hole` from its provider's `plane` vectors: [`cap_in_plane`] with the
/// plane's normal; for a corner's sector ([`Fan::Corner`]) with `[T0, T1] = plane` (the two
/// sharp edges' derivatives), for a crease's fan ([`Fan::Crease`]) with `T0 = plane[0]`
/// ([`crease_tangents`]); around a cone point ([`Fan::is_cone`]) with `[T0, T1] = plane` too,
/// which its provider gives as zero and its cap map does not read (every spoke tangent zero).
pub fn cap_from_plane(mut hole: Hole, plane: [Point; 2], opts: CapOptions) -> Result<Cap> {
    if hole.kind.pins_plane() {
        super::choose::check_cap_valence(hole.valence())?;
        hole.tangents = plane;
        g1_cap_with(&hole, opts)
    } else if hole.kind == Fan::Crease {
        super::choose::check_cap_valence(hole.valence())?;
        hole.tangents = crease_tangents(&hole, plane)?;
        g1_cap_with(&hole, opts)
    } else {
        cap_in_plane(hole, cross(plane[0], plane[1]), opts)
    }
}

/// The G^1 cap of `hole` (its centre set by the provider) in the tangent plane with normal
/// `normal`: the tangents from [`chart_tangents`], then [`g1_cap_with`] with `opts`.
pub fn cap_in_plane(mut hole: Hole, normal: Point, opts: CapOptions) -> Result<Cap> {
    super::choose::check_cap_valence(hole.valence())?;
    hole.tangents = chart_tangents(&hole, normal)?;
    g1_cap_with(&hole, opts)
}

/// The G^1 cap of `hole` in the plane spanned by `plane` (normal `plane[0] x plane[1]`) with
/// `opts`, and the [`CapStep`] that records it for a patch stencil table (its `first` patch
/// set to `first`): every caller that closes a hole with [`cap_in_plane`] from data linear in
/// the control points goes through here, so the table can repeat the one non-linear step.
pub fn cap_step(
    hole: Hole,
    plane: [Point; 2],
    opts: CapOptions,
    first: usize,
) -> Result<(Vec<BezierPatch>, CapStep)> {
    let cap = cap_from_plane(hole.clone(), plane, opts)?;
    let step = CapStep {
        first: first as u32,
        count: cap.patches.len() as u32,
        kept: None,
        hole,
        plane,
        options: opts,
    };
    Ok((cap.patches, step))
}

/// The side of a quad patch whose corners `0, 1, 2, 3` of its face sit at `(u, v) = (0, 0),
/// (1, 0), (1, 1), (0, 1)` that runs along the face's edge from corner `k` to corner `k + 1`, and
/// the side-parameter range of that edge from corner `k` to `k + 1` (`forward`) or back.
pub fn quad_edge_side(k: usize, forward: bool) -> (Side, [f64; 2]) {
    let (side, range) = match k % 4 {
        0 => (Side::V0, [0.0, 1.0]),
        1 => (Side::U1, [0.0, 1.0]),
        2 => (Side::V1, [1.0, 0.0]),
        _ => (Side::U0, [1.0, 0.0]),
    };
    if forward {
        (side, range)
    } else {
        (side, [range[1], range[0]])
    }
}

/// The hole's sectors read off a C^1-to-the-ring fill in the cap's conventions (one patch per
/// sector, `(0, 0)` at the centre, spoke `s` its side `v = 0`, `P_s(u, 0) = P_(s-1)(0, u)`):
/// segment `a` is the fill's side `u = 1`, segment `b` its side `v = 1`, each with the
/// derivative from the ring into the hole ([`segment_from_inside`]). Exact ring data when the
/// fill's two outer layers along those sides are the ring's C^1 continuation.
pub fn sectors_from_fill(fill: &[BezierPatch]) -> Vec<Vec<Segment>> {
    fill.iter()
        .map(|p| {
            vec![
                segment_from_inside(p, Side::U1, [0.0, 1.0], 1.0),
                segment_from_inside(p, Side::V1, [0.0, 1.0], 1.0),
            ]
        })
        .collect()
}

/// The `2 m` segments of a split sector ([`super::Layout::Split`]) read off the last ring's
/// pieces that border it: `a_side[b]` the ring piece beside the hole's side `u = 1` at its
/// piece `b` (its side `u = 0` on the hole, `v` running from the spoke end to the corner), and
/// `b_side[a]` the ring piece beside the side `v = 1` at piece `a` (its side `v = 0` on the hole,
/// `u` from spoke `s + 1` to the corner). Ring pieces of the cap pieces' size (the macro-patch
/// rings: a hole sector has the size of one ring patch), so each cross derivative is the piece's
/// own ([`segment_from_ring`], factor 1).
pub fn split_sector(a_side: &[BezierPatch], b_side: &[BezierPatch]) -> Vec<Segment> {
    a_side
        .iter()
        .map(|p| segment_from_ring(p, Side::U0, [0.0, 1.0], 1.0))
        .chain(
            b_side
                .iter()
                .map(|p| segment_from_ring(p, Side::V0, [0.0, 1.0], 1.0)),
        )
        .collect()
}
