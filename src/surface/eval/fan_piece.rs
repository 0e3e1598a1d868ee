//! Evaluation inside the G^1 cap of an open fan of triangles (Loop at a boundary vertex,
//! [`crate::bezier::g1::Layout::OpenTriangle`]): cap patch `s` covers fan triangle `s` whole,
//! as the bilinear image of the unit square with corners `C, E_s, M_s, E_(s+1)` (a straight
//! corner at the midpoint `M_s` of the outer edge).
//!
//! # The map
//!
//! In the chart of the fan triangle (`C` at `(0, 0)`, `E_s` at `(1, 0)`, `E_(s+1)` at `(0, 1)`:
//! `(alpha, beta)`, the cap patch's domain chart, [`crate::bezier::domain::Shape::corner_map`]):
//!
//! `alpha = u - u v / 2`, `beta = v - u v / 2`,
//!
//! with Jacobian determinant `1 - (u + v) / 2`, positive on the square but at the corner
//! `(1, 1)` (`M_s`), and twist `(-1/2, -1/2)`. The inverse: with `delta = alpha - beta = u - v`,
//! `v` is the smaller root of `v^2 + (delta - 2) v + 2 beta = 0` (discriminant at least
//! `(1 - 2 beta)^2` on the triangle) and `u = v + delta`.
//!
//! At `M_s` itself the map is singular: the point and the normal are the patch's (its normal by
//! [`crate::bezier::Derivatives::normal_toward`], the cap's corner data being the ring's to
//! third order), the first derivatives in the chart are taken `1e-7` inside along the
//! diagonal (they approximate the ring's to about that) and the second derivatives, and so the
//! curvatures, `1e-3` inside ([`chart_derivatives`]: the one-sided limit to about that; `1e-7`
//! inside, the inverse function rule's rounding gave Gauss curvatures of `1e11`).

use crate::bezier::Derivatives;

/// The patch parameters of chart point `ab = (alpha, beta)` of the fan triangle.
pub(super) fn locate(ab: [f64; 2]) -> [f64; 2] {
    let [a, b] = ab;
    let delta = a - b;
    let bb = 2.0 - delta;
    // smaller root, in the stable form 2 c / (b + sqrt(D)) with c = 2 beta
    let v = 4.0 * b / (bb + (bb * bb - 8.0 * b).max(0.0).sqrt());
    let unit = |x: f64| x.clamp(0.0, 1.0);
    [unit(v + delta), unit(v)]
}

/// Distance from the singular corner `(1, 1)` inside which the point counts as the corner.
const SINGULAR: f64 = 1e-7;

/// Where the chart's second derivatives at the singular corner are taken instead (along the
/// diagonal): the inverse function rule divides by the Jacobian determinant, about this
/// distance there, so rounding stays near `1e-10` relative, while the one-sided limit of the
/// second derivatives is approximated to about this distance.
const SECOND_ORDER: f64 = 1e-3;

/// The patch derivatives of the cap patch `patch` at its parameters `uv` pulled back to the
/// chart ([`to_chart`]); at (within [`SINGULAR`] of) the singular corner `(1, 1)`: the point
/// itself, the first derivatives [`SINGULAR`] and the second derivatives [`SECOND_ORDER`]
/// inside along the diagonal (the cap is C^1 to the ring there, with a one-sided curvature).
pub(super) fn chart_derivatives(patch: &crate::bezier::BezierPatch, uv: [f64; 2]) -> Derivatives {
    if (1.0 - uv[0]).max(1.0 - uv[1]) >= SINGULAR {
        return to_chart(&patch.derivatives(uv[0], uv[1]), uv);
    }
    let at = |e: f64| {
        let q = [1.0 - e, 1.0 - e];
        to_chart(&patch.derivatives(q[0], q[1]), q)
    };
    let (first, second) = (at(SINGULAR), at(SECOND_ORDER));
    Derivatives {
        p: patch.eval(uv[0], uv[1]),
        du: first.du,
        dv: first.dv,
        duu: second.duu,
        duv: second.duv,
        dvv: second.dvv,
    }
}

/// The derivatives with respect to the chart of the cap patch whose derivatives at its
/// parameters `uv` (not the singular corner) are `d`.
pub(super) fn to_chart(d: &Derivatives, uv: [f64; 2]) -> Derivatives {
    let [u, v] = uv;
    let j = [[1.0 - v / 2.0, -u / 2.0], [-v / 2.0, 1.0 - u / 2.0]];
    super::kite::pull_back(d, j, [-0.5, -0.5])
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    fn forward([u, v]: [f64; 2]) -> [f64; 2] {
        [u - u * v / 2.0, v - u * v / 2.0]
    }

    #[crate::unit::test]
    fn locate_inverts_the_map_on_the_triangle() {
        for i in 0..=20 {
            for k in 0..=20 - i {
                let ab = [i as f64 / 20.0, k as f64 / 20.0];
                let uv = locate(ab);
                let back = forward(uv);
                assert!(
                    (back[0] - ab[0]).abs() < 1e-12 && (back[1] - ab[1]).abs() < 1e-12,
                    "{ab:?} -> {uv:?} -> {back:?}"
                );
            }
        }
        assert_eq!(locate([0.0, 0.0]), [0.0, 0.0]);
        assert_eq!(locate([1.0, 0.0]), [1.0, 0.0]);
        assert_eq!(locate([0.0, 1.0]), [0.0, 1.0]);
        let m = locate([0.5, 0.5]);
        assert!((m[0] - 1.0).abs() < 1e-15 && (m[1] - 1.0).abs() < 1e-15);
    }

    /// A quadratic in the chart pulled back through the map has the quadratic's chart
    /// derivatives.
    #[crate::unit::test]
    fn chart_derivatives_by_the_inverse_function_rule() {
        let truth = |a: f64, b: f64| Derivatives {
            p: [a * a + b, a * b, b * b - a],
            du: [2.0 * a, b, -1.0],
            dv: [1.0, a, 2.0 * b],
            duu: [2.0, 0.0, 0.0],
            duv: [0.0, 1.0, 0.0],
            dvv: [0.0, 0.0, 2.0],
        };
        for uv in [[0.3, 0.2], [0.9, 0.6], [0.1, 0.7], [0.0, 0.0], [0.99, 0.98]] {
            let [a, b] = forward(uv);
            let t = truth(a, b);
            let [u, v] = uv;
            let j = [[1.0 - v / 2.0, -u / 2.0], [-v / 2.0, 1.0 - u / 2.0]];
            let p = crate::surface::testing::chain_rule(&t, j, [-0.5, -0.5]);
            let c = to_chart(&p, uv);
            for (x, y) in [(c.du, t.du), (c.dv, t.dv), (c.duu, t.duu), (c.duv, t.duv)] {
                for k in 0..3 {
                    assert!((x[k] - y[k]).abs() < 1e-10, "{uv:?}: {x:?} {y:?}");
                }
            }
        }
    }
}
