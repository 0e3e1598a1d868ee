//! Evaluation in a cell covered by four triangles, the cell split by both its diagonals (the
//! criss-cross cells of non-box subdivision's S_3^1 spline, [`crate::schemes::nonbox::bezier`];
//! their patches carry [`crate::bezier::domain::Domain::criss_cross`] domains).
//!
//! # The triangle -> cell map
//!
//! In the cell's coordinates `(x, y)` (`[0, 1]^2`, corner `k` at `(0, 0)`, `(1, 0)`, `(1, 1)`,
//! `(0, 1)` for `k = 0, 1, 2, 3`, the centre at `(1/2, 1/2)`), triangle `k` has corners
//! `P0` = corner `k`, `P1` = corner `k + 1` and `P2` = the centre; its barycentric `(s, t)`
//! (`s` toward `P1`, `t` toward `P2`) is an affine function of `(x, y)`:
//!
//! | `k` | where | `s` | `t` |
//! | --- | --- | --- | --- |
//! | 0 (bottom) | `y <= x`, `x + y <= 1` | `x - y` | `2 y` |
//! | 1 (right) | `y <= x`, `x + y >= 1` | `x + y - 1` | `2 (1 - x)` |
//! | 2 (top) | `y >= x`, `x + y >= 1` | `y - x` | `2 (1 - y)` |
//! | 3 (left) | `y >= x`, `x + y <= 1` | `1 - x - y` | `2 x` |
//!
//! Every map has Jacobian determinant 2 (orientation preserving), and on a diagonal both
//! neighbours give the same point of their common side (`s = 0` of one, `s + t = 1` of the
//! other, at the same `t`), so the evaluation is continuous there (the S_3^1 pieces are C^1
//! across the diagonals). Derivatives with respect to the cell follow by the chain rule of the
//! affine map; the triangles are evaluated in their own barycentric parameters
//! (`super::triangle`), so they stay exact at the collapsed corner `P2` of the stored patch.

use crate::bezier::Derivatives;

/// The triangle of a criss-cross cell holding the cell point `p`, its barycentric `(s, t)`
/// there and `d (s, t) / d (x, y)` as rows (see the [module](self) documentation; points on a
/// diagonal go to the lower-numbered side of the `y <= x` and `x + y <= 1` tests).
pub(super) fn locate(p: [f64; 2]) -> (usize, [f64; 2], [[f64; 2]; 2]) {
    let [x, y] = p;
    let (k, st, jac) = match (y <= x, x + y <= 1.0) {
        (true, true) => (0, [x - y, 2.0 * y], [[1.0, -1.0], [0.0, 2.0]]),
        (true, false) => (1, [x + y - 1.0, 2.0 * (1.0 - x)], [[1.0, 1.0], [-2.0, 0.0]]),
        (false, false) => (2, [y - x, 2.0 * (1.0 - y)], [[-1.0, 1.0], [0.0, -2.0]]),
        (false, true) => (3, [1.0 - x - y, 2.0 * x], [[-1.0, -1.0], [2.0, 0.0]]),
    };
    // rounding may leave a hair outside the triangle
    let s = st[0].max(0.0);
    let t = st[1].clamp(0.0, 1.0 - s);
    (k, [s, t], jac)
}

/// The derivatives with respect to the cell's `(x, y)` of a triangle's derivatives `d` with
/// respect to its barycentric `(s, t)` ([`locate`]'s `jac`).
pub(super) fn to_cell(d: &Derivatives, jac: [[f64; 2]; 2]) -> Derivatives {
    super::chain(d, jac)
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    /// The cell points of triangle `k` at barycentric `(s, t)`.
    fn forward(k: usize, [s, t]: [f64; 2]) -> [f64; 2] {
        let c = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let (p0, p1) = (c[k], c[(k + 1) % 4]);
        let w = 1.0 - s - t;
        [
            w * p0[0] + s * p1[0] + t * 0.5,
            w * p0[1] + s * p1[1] + t * 0.5,
        ]
    }

    #[crate::unit::test]
    fn locate_inverts_the_triangle_maps() {
        for k in 0..4 {
            for i in 0..=16 {
                for j in 0..=16 - i {
                    let st = [f64::from(i) / 16.0, f64::from(j) / 16.0];
                    let p = forward(k, st);
                    let (kk, back, jac) = locate(p);
                    // the point lies in triangle kk, at the same place
                    let q = forward(kk, back);
                    assert!((q[0] - p[0]).abs() < 1e-15 && (q[1] - p[1]).abs() < 1e-15);
                    if kk == k {
                        assert!((back[0] - st[0]).abs() < 1e-15, "{k} {st:?} {back:?}");
                        assert!((back[1] - st[1]).abs() < 1e-15, "{k} {st:?} {back:?}");
                    }
                    // the Jacobian is that of the inverse map: d(s,t)/d(x,y) J_forward = I
                    let h = 1.0 / 64.0;
                    let fx = [
                        (forward(kk, [back[0] + h, back[1]])[0] - q[0]) / h,
                        (forward(kk, [back[0] + h, back[1]])[1] - q[1]) / h,
                    ];
                    let ft = [
                        (forward(kk, [back[0], back[1] + h])[0] - q[0]) / h,
                        (forward(kk, [back[0], back[1] + h])[1] - q[1]) / h,
                    ];
                    for (a, row) in jac.iter().enumerate() {
                        let ds = row[0] * fx[0] + row[1] * fx[1];
                        let dt = row[0] * ft[0] + row[1] * ft[1];
                        let want = if a == 0 { [1.0, 0.0] } else { [0.0, 1.0] };
                        assert!((ds - want[0]).abs() < 1e-12 && (dt - want[1]).abs() < 1e-12);
                    }
                }
            }
        }
        // the centre is the apex; the corners are P0 or P1 of a triangle beside them
        assert_eq!(locate([0.5, 0.5]).1, [0.0, 1.0]);
        assert_eq!(
            locate([0.0, 0.0]),
            (0, [0.0, 0.0], [[1.0, -1.0], [0.0, 2.0]])
        );
        assert_eq!(locate([1.0, 0.0]).1, [1.0, 0.0]);
        assert_eq!(
            locate([1.0, 1.0]),
            (1, [1.0, 0.0], [[1.0, 1.0], [-2.0, 0.0]])
        );
        assert_eq!(
            locate([0.0, 1.0]),
            (3, [0.0, 0.0], [[-1.0, -1.0], [2.0, 0.0]])
        );
    }
}
