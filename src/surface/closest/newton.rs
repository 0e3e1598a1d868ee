//! The local search of [`super::ProjectionIndex::closest`]: a projected Newton iteration for
//! `min |S(x) - q|^2 / 2` over a chart's local coordinates `x` (the face's domain, a square or
//! a triangle), evaluated through `Surface::derivatives_local`.
//!
//! With `r = S - q`, the gradient is `g = (r . S_u, r . S_v)` and the Hessian
//! `H = [[S_u . S_u + r . S_uu, S_u . S_v + r . S_uv], [.., S_v . S_v + r . S_vv]]`. Where `H`
//! is not positive definite (far from the surface, beyond a focal point) the step falls back
//! to Gauss-Newton's first fundamental form, which is. A coordinate at its bound whose gradient
//! pushes outward is held there (the active set of the box; the triangle's diagonal is handled
//! by projection). Every accepted step decreases the distance (halving the step otherwise), so
//! the result is never farther than the sample it started from.

use super::super::eval::Surface;
use super::super::eval::charts::{Chart, Local};
use crate::geom::{Point, dot, norm, sub};

/// Iterations at most.
const MAX_STEPS: usize = 60;

/// What the search found.
#[derive(Debug, Clone, Copy)]
pub(super) struct Found {
    /// The chart searched.
    pub chart: usize,
    /// Local coordinates.
    pub local: [f64; 2],
    /// The point.
    pub point: Point,
    /// Whether it is held on the domain's boundary by the constraint.
    pub on_boundary: bool,
}

/// `p` projected onto the local domain.
pub(super) fn project(local: Local, p: [f64; 2]) -> [f64; 2] {
    let [x, y] = [p[0].clamp(0.0, 1.0), p[1].clamp(0.0, 1.0)];
    match local {
        Local::Square => [x, y],
        Local::Triangle if x + y <= 1.0 => [x, y],
        Local::Triangle => {
            let t = (x + y - 1.0) / 2.0;
            let (x, y) = (x - t, y - t);
            if x < 0.0 {
                [0.0, 1.0]
            } else if y < 0.0 {
                [1.0, 0.0]
            } else {
                [x, y]
            }
        }
    }
}

/// The coordinates held at a bound: `[held x, held y, held on the diagonal]`.
fn active(local: Local, p: [f64; 2], g: [f64; 2], tol: [f64; 2]) -> [bool; 3] {
    let held = |k: usize| (p[k] <= 0.0 && g[k] > tol[k]) || (p[k] >= 1.0 && g[k] < -tol[k]);
    let diag = local == Local::Triangle && p[0] + p[1] >= 1.0 && g[0] + g[1] < -(tol[0] + tol[1]);
    [held(0), held(1), diag]
}

/// Solves the 2 x 2 system `h d = -g` with the coordinates in `fixed` held (`d = 0`).
fn step(h: [[f64; 2]; 2], g: [f64; 2], fixed: [bool; 2]) -> [f64; 2] {
    match fixed {
        [true, true] => [0.0, 0.0],
        [true, false] => [0.0, -g[1] / h[1][1]],
        [false, true] => [-g[0] / h[0][0], 0.0],
        [false, false] => {
            let det = h[0][0] * h[1][1] - h[0][1] * h[1][0];
            [
                -(h[1][1] * g[0] - h[0][1] * g[1]) / det,
                -(h[0][0] * g[1] - h[1][0] * g[0]) / det,
            ]
        }
    }
}

/// The local minimum of the distance to `q` reached from `start` in `chart` (number `index`).
pub(super) fn minimise(
    s: &Surface,
    index: usize,
    chart: &Chart,
    start: [f64; 2],
    q: Point,
) -> Option<Found> {
    let eval = |p: [f64; 2]| s.derivatives_local(chart.face, chart.sub, p).ok();
    // start a hair inside the cell (a sample at a cell corner may be a point where the
    // face's parameters are singular: an extraordinary vertex)
    let centre = chart.cell.apply(match chart.shape {
        crate::bezier::domain::Shape::Quad => [0.5, 0.5],
        crate::bezier::domain::Shape::Triangle => [1.0 / 3.0, 1.0 / 3.0],
    });
    let inside = [
        start[0] + 1e-3 * (centre[0] - start[0]),
        start[1] + 1e-3 * (centre[1] - start[1]),
    ];
    let mut p = project(chart.local, inside);
    let mut e = eval(p)?;
    let mut f = norm(sub(e.p, q));
    // distances equal to rounding: a step that changes the distance by less still counts
    // (the tangential residual is resolved past what the distance itself shows)
    let slack = 4.0 * f64::EPSILON * (norm(q) + norm(e.p));
    let mut on_boundary = false;
    for _ in 0..MAX_STEPS {
        let r = sub(e.p, q);
        let g = [dot(r, e.du), dot(r, e.dv)];
        let (ee, ff, gg) = (dot(e.du, e.du), dot(e.du, e.dv), dot(e.dv, e.dv));
        let tol = [1e-13 * norm(r) * ee.sqrt(), 1e-13 * norm(r) * gg.sqrt()];
        let hold = active(chart.local, p, g, tol);
        on_boundary = hold.iter().any(|h| *h);
        let free_small = (0..2).all(|k| hold[k] || g[k].abs() <= 0.01 * tol[k]);
        if free_small && !hold[2] {
            break;
        }
        let newton = [
            [ee + dot(r, e.duu), ff + dot(r, e.duv)],
            [ff + dot(r, e.duv), gg + dot(r, e.dvv)],
        ];
        let pos_def =
            newton[0][0] > 0.0 && newton[0][0] * newton[1][1] - newton[0][1] * newton[1][0] > 0.0;
        let h = if pos_def {
            newton
        } else {
            [[ee, ff], [ff, gg]]
        };
        let mut d = step(h, g, [hold[0], hold[1]]);
        if !d.iter().all(|x| x.is_finite()) {
            // a degenerate point: a small step toward the cell's centre instead
            d = [1e-3 * (centre[0] - p[0]), 1e-3 * (centre[1] - p[1])];
        }
        let mut t = 1.0;
        let mut accepted = None;
        for _ in 0..40 {
            let cand = project(chart.local, [p[0] + t * d[0], p[1] + t * d[1]]);
            if cand == p {
                break;
            }
            if let Some(ec) = eval(cand) {
                let fc = norm(sub(ec.p, q));
                if fc <= f + slack {
                    accepted = Some((cand, ec, fc));
                    break;
                }
            }
            t *= 0.5;
        }
        let Some((cand, ec, fc)) = accepted else {
            break;
        };
        let moved = (cand[0] - p[0]).abs().max((cand[1] - p[1]).abs());
        p = cand;
        e = ec;
        f = fc.min(f);
        if moved < 1e-16 {
            break;
        }
    }
    Some(Found {
        chart: index,
        local: p,
        point: e.p,
        on_boundary,
    })
}
