//! Evaluation inside Loop's G^1 cap: the cap of a triangle hole is made of kites
//! ([`crate::bezier::g1::Hole::to_quad_layout`]), kite `s` covering the half of fan triangle
//! `s` beside spoke end `E_(s+1)` and the half of fan triangle `s + 1` beside it, so a fan
//! triangle's cell holds halves of two cap patches.
//!
//! # The map
//!
//! In the chart of fan triangle `s` with the centre `C` at `(0, 0)`, `E_s` at `(1, 0)` and
//! `E_(s+1)` at `(0, 1)` (`(alpha, beta)`, the cap patch's domain chart,
//! [`crate::bezier::domain::Shape::corner_map`]), the neighbouring fan triangles are unfolded as
//! on a three-direction lattice (`E_(s+2) = E_(s+1) - E_s`, `E_(s-1) = E_s - E_(s+1)`), the
//! chart in which the cap's data are given ([`crate::bezier::g1::hole`]). Kite `s` is the
//! bilinear image of the unit square with corners `C, M_s, E_(s+1), M_(s+1)`:
//!
//! `alpha = (u - v) / 2`, `beta = u / 2 + v - u v / 2`,
//!
//! whose half `u >= v` is the part `beta >= alpha` of fan triangle `s` (between the median
//! `C M_s`, its side `v = 0`, and the edge `C E_(s+1)`, its diagonal). Kite `s - 1` is the mirror
//! image, `alpha = u + v / 2 - u v / 2`, `beta = (v - u) / 2`, its half `v >= u` the part
//! `alpha >= beta`. Both maps agree on the median (`alpha = beta = u / 2` and `= v / 2`), so the
//! evaluation is continuous there; on the outer edge `alpha + beta = 1` they give the segment
//! parameters `(1 + v) / 2` and `(1 - u) / 2` of the cap's data, so it is continuous with the
//! ring; on the fan edges the two unfoldings of kite `s` agree (its diagonal `beta = 3 u / 2 -
//! u^2 / 2` from both sides). The inverse is a quadratic: for kite `s`, `u` is the smaller root
//! of `u^2 - (3 + 2 alpha) u + 2 (beta + 2 alpha) = 0` and `v = u - 2 alpha` (its discriminant is
//! at least `(1 + 2 alpha)^2` on the triangle, so the root is smooth); kite `s - 1` likewise with
//! `alpha`, `beta` and `u`, `v` exchanged. The Jacobian determinant of kite `s`'s map is
//! `3/4 - (u + v) / 4 >= 1/4`: the map is regular on the whole square.
//!
//! Derivatives with respect to the chart come from the patch's by the inverse function rule;
//! the map is bilinear, so its one second derivative, the twist `(0, -1/2)` (kite `s`) or
//! `(-1/2, 0)` (kite `s - 1`), adds a first-derivative term to the second derivatives.

use crate::bezier::Derivatives;
use crate::geom::{Point, axpy};

/// Which of the two kites over a fan triangle holds the chart point `ab = (alpha, beta)`
/// (`true`: kite `s - 1`, the neighbour) and the point's parameters in that kite.
pub(super) fn locate(ab: [f64; 2]) -> (bool, [f64; 2]) {
    let [a, b] = ab;
    // smaller root of x^2 - (3 + 2 p) x + 2 (q + 2 p), in the stable form 2c / (b + sqrt(D))
    let root = |p: f64, q: f64| {
        let bb = 3.0 + 2.0 * p;
        let c = 2.0 * (q + 2.0 * p);
        2.0 * c / (bb + (bb * bb - 4.0 * c).max(0.0).sqrt())
    };
    let unit = |x: f64| x.clamp(0.0, 1.0);
    if b >= a {
        let u = root(a, b);
        (false, [unit(u), unit(u - 2.0 * a)])
    } else {
        let v = root(b, a);
        (true, [unit(v - 2.0 * b), unit(v)])
    }
}

/// The derivatives with respect to the chart `(alpha, beta)` of the kite patch whose
/// derivatives at its parameters `uv` are `d` (`neighbour`: kite `s - 1`, see [`locate`]).
pub(super) fn to_chart(d: &Derivatives, uv: [f64; 2], neighbour: bool) -> Derivatives {
    let [u, v] = uv;
    // j[a][b] = d chart_a / d q_b, twist = d^2 chart / du dv
    let (j, twist) = if neighbour {
        ([[1.0 - v / 2.0, 0.5 - u / 2.0], [-0.5, 0.5]], [-0.5, 0.0])
    } else {
        ([[0.5, -0.5], [0.5 - v / 2.0, 1.0 - u / 2.0]], [0.0, -0.5])
    };
    pull_back(d, j, twist)
}

/// The derivatives with respect to a chart of a patch whose derivatives are `d`, the patch's
/// parameters mapped to the chart by a bilinear map with Jacobian `j` (`j[a][b] = d chart_a /
/// d q_b`) and twist `twist` (`d^2 chart / du dv`) at that point: the inverse function rule.
pub(super) fn pull_back(d: &Derivatives, j: [[f64; 2]; 2], twist: [f64; 2]) -> Derivatives {
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    // inv[a][b] = d q_a / d chart_b
    let inv = [
        [j[1][1] / det, -j[0][1] / det],
        [-j[1][0] / det, j[0][0] / det],
    ];
    // the affine part by the chain rule, then the twist's term:
    // d^2 q / d chart_b d chart_c = -inv . twist . (inv[0][b] inv[1][c] + inv[1][b] inv[0][c])
    let mut out = super::chain(d, inv);
    let inv_twist = [
        inv[0][0] * twist[0] + inv[0][1] * twist[1],
        inv[1][0] * twist[0] + inv[1][1] * twist[1],
    ];
    let term = |b: usize, c: usize, r: Point| -> Point {
        let w = inv[0][b] * inv[1][c] + inv[1][b] * inv[0][c];
        let r = axpy(r, -inv_twist[0] * w, d.du);
        axpy(r, -inv_twist[1] * w, d.dv)
    };
    out.duu = term(0, 0, out.duu);
    out.duv = term(0, 1, out.duv);
    out.dvv = term(1, 1, out.dvv);
    out
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    /// The forward maps of the module documentation.
    fn forward(neighbour: bool, [u, v]: [f64; 2]) -> [f64; 2] {
        if neighbour {
            [u + v / 2.0 - u * v / 2.0, (v - u) / 2.0]
        } else {
            [(u - v) / 2.0, u / 2.0 + v - u * v / 2.0]
        }
    }

    #[crate::unit::test]
    fn locate_inverts_the_kite_maps_on_the_triangle() {
        for i in 0..=20 {
            for k in 0..=20 - i {
                let ab = [i as f64 / 20.0, k as f64 / 20.0];
                let (nb, uv) = locate(ab);
                assert_eq!(nb, ab[0] > ab[1]);
                let back = forward(nb, uv);
                assert!(
                    (back[0] - ab[0]).abs() < 1e-15 && (back[1] - ab[1]).abs() < 1e-15,
                    "{ab:?} -> {uv:?} -> {back:?}"
                );
                // the half of the kite inside this triangle
                assert!(if nb { uv[1] >= uv[0] } else { uv[0] >= uv[1] });
            }
        }
        // corners and midpoints: C, E_s, E_(s+1), M_s
        assert_eq!(locate([0.0, 0.0]), (false, [0.0, 0.0]));
        assert_eq!(locate([0.0, 1.0]), (false, [1.0, 1.0]));
        assert_eq!(locate([1.0, 0.0]), (true, [1.0, 1.0]));
        assert_eq!(locate([0.5, 0.5]), (false, [1.0, 0.0]));
    }

    /// The chart derivatives of a polynomial in the chart, pulled back through a kite, are the
    /// polynomial's own.
    #[crate::unit::test]
    fn chart_derivatives_by_the_inverse_function_rule() {
        // f(a, b) = (a^2 + 3ab - b^2 + a, 2 b^2 - ab, a b^2) at the kite parameters
        let f = |a: f64, b: f64| {
            [
                a * a + 3.0 * a * b - b * b + a,
                2.0 * b * b - a * b,
                a * b * b,
            ]
        };
        let truth = |a: f64, b: f64| Derivatives {
            p: f(a, b),
            du: [2.0 * a + 3.0 * b + 1.0, -b, b * b],
            dv: [3.0 * a - 2.0 * b, 4.0 * b - a, 2.0 * a * b],
            duu: [2.0, 0.0, 0.0],
            duv: [3.0, -1.0, 2.0 * b],
            dvv: [-2.0, 4.0, 2.0 * a],
        };
        for nb in [false, true] {
            for uv in [[0.3, 0.2], [0.9, 0.6], [0.1, 0.7], [1.0, 1.0], [0.0, 0.0]] {
                // the patch P(u, v) = f(K(u, v)) and its derivatives by the chain rule
                let [a, b] = forward(nb, uv);
                let t = truth(a, b);
                let (j, tw) = if nb {
                    (
                        [[1.0 - uv[1] / 2.0, 0.5 - uv[0] / 2.0], [-0.5, 0.5]],
                        [-0.5, 0.0],
                    )
                } else {
                    (
                        [[0.5, -0.5], [0.5 - uv[1] / 2.0, 1.0 - uv[0] / 2.0]],
                        [0.0, -0.5],
                    )
                };
                let p = crate::surface::testing::chain_rule(&t, j, tw);
                let c = to_chart(&p, uv, nb);
                for (x, y) in [
                    (c.du, t.du),
                    (c.dv, t.dv),
                    (c.duu, t.duu),
                    (c.duv, t.duv),
                    (c.dvv, t.dvv),
                ] {
                    for k in 0..3 {
                        assert!((x[k] - y[k]).abs() < 1e-12, "{nb} {uv:?}: {x:?} {y:?}");
                    }
                }
            }
        }
    }
}
