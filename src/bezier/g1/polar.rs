//! The G^1 cap of a polar ring: `n` patches, each with its side `u = 0` collapsed to the
//! centre, closing the hole inside a ring whose inner boundary is one closed, C^1 periodic
//! spline in the circular parameter `v` (polar bi-2 subdivision: one ring patch per sector,
//! its side `u = 0` on the hole). The quad-layout cap of [`super`] does not fit such a ring: its
//! spoke ends are interior points of smooth boundary curves (flat corners), see [`super`].
//!
//! # Conditions
//!
//! Sector `s` is a patch `P_s(u, v)` of degree 3 in `u` (radial, `u = 0` at the centre) and the
//! ring's degree `m` in `v` (circular), `P_s(u, 1) = P_(s+1)(u, 0)`. Row `i` holds its
//! coefficients `b_i0 .. b_im`; `E^s_j` and `G^s_j` are the coefficients of the ring's inner
//! boundary and of its radial derivative there (pointing away from the centre, per unit of the
//! cap's `u`), both C^1 periodic splines in `v` over the sectors.
//!
//! * **C^1 to the ring**: `b_3j = E_j`, `b_2j = E_j - G_j / 3` (value and radial derivative,
//!   the ring's parameter speed);
//! * **centre**: `b_0j = C` (the side `u = 0` collapsed to the limit point);
//! * **tangent plane**: `b_1j = C + D_j / 3` with `D_j = Pi(2 (E_j - C) - G_j)`, `Pi` the
//!   orthogonal projection onto the limit tangent plane: the radial derivative at the centre of
//!   the quadratic spoke from `C` to `E_j` with end derivative `G_j` (the same scale as
//!   [`super::ring::chart_tangents`]), flattened into the plane. Every `d/du P_s(0, v)` lies in
//!   the plane, so the normal at the centre is the plane's from every direction (the limit of
//!   `d_u P x d_uv P` as `u -> 0`), with one orientation when `D(v)` winds once around `C`
//!   (checked: [`polar_cap`] refuses a cap whose `D x D'` changes sign).
//! * **across spokes**: every row is the same linear combination of `E`, `G` and `C` (and the
//!   projection is linear), so each row is again a C^1 periodic spline in `v`: the cap is C^1
//!   across every spoke in the polar parametrisation (hence G^1 away from the centre), and C^1
//!   to the ring's spoke ends.
//!
//! # Free parameters and degree
//!
//! None: the four rows are fixed by the conditions. Degree 3 radially is the lowest: a
//! quadratic would need its middle row to be both the ring's C^1 layer and in the tangent
//! plane. The circular degree is the ring's.

use super::ring::project_onto_plane;
use crate::bezier::BezierPatch;
use crate::error::{Error, Result};
use crate::geom::{Point, axpy, cross, dot, normalize, scale, sub};

/// The polar G^1 cap (see the [module](self) documentation): `boundary[s]` and `radial[s]` the
/// `m + 1` coefficients of sector `s`'s ring boundary `E` and outward radial derivative `G`,
/// `centre` the limit point, `normal` the limit normal. Returns `n` patches of bi-degree
/// `(3, m)`, `u` radial.
///
/// # Errors
/// When the sectors' degrees differ or `D(v)` does not wind once around the centre (the cap
/// would fold), naming the sector.
pub fn polar_cap(
    boundary: &[Vec<Point>],
    radial: &[Vec<Point>],
    centre: Point,
    normal: Point,
) -> Result<Vec<BezierPatch>> {
    let nrm = normalize(normal);
    if boundary.is_empty() || boundary.len() != radial.len() {
        return Err(Error::InvalidArgument(
            "a polar cap needs one boundary and one radial derivative per sector".into(),
        ));
    }
    let m = boundary[0].len().saturating_sub(1);
    let mut out = Vec::with_capacity(boundary.len());
    let mut sign = 0.0;
    for (s, (e, g)) in boundary.iter().zip(radial).enumerate() {
        if e.len() != m + 1 || g.len() != m + 1 || m == 0 {
            return Err(Error::InvalidArgument(format!(
                "sector {s} of the polar hole has degrees ({}, {}), sector 0 has {m}",
                e.len().saturating_sub(1),
                g.len().saturating_sub(1)
            )));
        }
        let d: Vec<Point> = (0..=m)
            .map(|j| project_onto_plane(axpy(scale(sub(e[j], centre), 2.0), -1.0, g[j]), nrm))
            .collect();
        // D x D' at the coefficients' spans: one sign around the centre.
        for j in 0..m {
            let w = dot(cross(d[j], sub(d[j + 1], d[j])), nrm);
            if sign == 0.0 {
                sign = w.signum();
            }
            if w * sign <= 0.0 {
                return Err(Error::Unsupported(format!(
                    "the polar cap folds at the centre in sector {s} (its radial tangents do \
                     not wind around the limit point)"
                )));
            }
        }
        out.push(BezierPatch::from_fn(3, m, |i, j| match i {
            0 => centre,
            1 => axpy(centre, 1.0 / 3.0, d[j]),
            2 => axpy(e[j], -1.0 / 3.0, g[j]),
            _ => e[j],
        }));
    }
    Ok(out)
}
