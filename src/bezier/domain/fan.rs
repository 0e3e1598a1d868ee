//! Input faces that are fan triangles of the faces the patches were built on: a polygon with
//! a centre (non-box-4dir's quasi-four-directional triangle meshes, whose triangles `(V_i,
//! V_(i+1), FCV)` fan the polygons of the net with face control vertices the complex is built
//! from).
//!
//! # The domain of a fan triangle
//!
//! The input face keeps the barycentric domain of a triangle: `(u, v)`, `u, v >= 0`,
//! `u + v <= 1`, `u` toward its corner 1, `v` toward its corner 2. With `rot` its corner that
//! is corner `i` of the host polygon (so corner `rot + 1` is the host's corner `i + 1` and
//! corner `rot + 2` the centre), its barycentric `(s, t)` toward host corners `i + 1` and the
//! centre are a cyclic permutation of `(1 - u - v, u, v)`, and the host face's parameters
//! ([`crate::bezier::domain`]) are an affine function of `(s, t)`:
//!
//! * **quad host**: triangle `i` of the cell's criss-cross (the cell split by both diagonals):
//!   `p = c_i + s (c_(i+1) - c_i) + t ((1/2, 1/2) - c_i)` with `c_k` the corners of `[0, 1]^2`;
//!   these are exactly the S_3^1 triangles of non-box's regular cells;
//! * **n-gon host** (`n != 4`): the triangle lies across two quad sub-faces, split by the
//!   segment from the midpoint `M` of edge `i -> i+1` to the centre: the half `2 s + t <= 1` at
//!   corner `i` is the half `y <= x` of sub-face `i`, `(x, y) = (2 s + t, t)`; the half at corner
//!   `i + 1` is the half `x <= y` of sub-face `i + 1`, `(x, y) = (t, 2 - 2 s - t)` (corner
//!   `i + 1` at `(0, 0)`, `M` at `(0, 1)`, the centre at `(1, 1)`). Both maps agree on the
//!   segment, so the evaluation is continuous; its derivatives with respect to `(u, v)` jump
//!   there (the parametrisation, not the surface, has a kink).
//!
//! Every map has a positive Jacobian determinant, so normals and curvatures keep their sign.

/// An input face that is the fan triangle `(corner edge, corner edge + 1, centre)` of a host
/// face (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FanTriangle {
    /// The host face (of the net the patches were built on).
    pub host: u32,
    /// Its number of corners.
    pub sides: u32,
    /// The host edge the triangle stands on: from corner `edge` to corner `edge + 1`.
    pub edge: u32,
    /// The triangle's own corner (0, 1 or 2) that is host corner `edge`.
    pub rot: u8,
}

/// Quad cell corners, counter-clockwise from corner 0.
const QUAD: [[f64; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];

impl FanTriangle {
    /// The host's sub-face (0 for a quad), the point in its cell coordinates and
    /// `jac[a][b]` = d (sub-face coordinate `a`) / d (`b` of `(u, v)`) at the triangle's `(u, v)`.
    pub fn to_host(&self, u: f64, v: f64) -> (u32, [f64; 2], [[f64; 2]; 2]) {
        let r = usize::from(self.rot % 3);
        let l = [1.0 - u - v, u, v];
        // d l_j / d (u, v)
        let dl = [[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]];
        let (s, t) = (l[(r + 1) % 3], l[(r + 2) % 3]);
        let dst = [dl[(r + 1) % 3], dl[(r + 2) % 3]];
        let i = (self.edge % self.sides) as usize;
        let (sub, p, a) = if self.sides == 4 {
            let (c, d) = (QUAD[i], QUAD[(i + 1) % 4]);
            let e0 = [d[0] - c[0], d[1] - c[1]];
            let e1 = [0.5 - c[0], 0.5 - c[1]];
            let p = [c[0] + s * e0[0] + t * e1[0], c[1] + s * e0[1] + t * e1[1]];
            (0, p, [[e0[0], e1[0]], [e0[1], e1[1]]])
        } else if 2.0 * s + t < 1.0 {
            (i as u32, [2.0 * s + t, t], [[2.0, 1.0], [0.0, 1.0]])
        } else {
            let next = ((i + 1) % self.sides as usize) as u32;
            (next, [t, 2.0 - 2.0 * s - t], [[0.0, 1.0], [-2.0, -1.0]])
        };
        let p = [p[0].clamp(0.0, 1.0), p[1].clamp(0.0, 1.0)];
        let jac = std::array::from_fn(|x| {
            std::array::from_fn(|b| a[x][0] * dst[0][b] + a[x][1] * dst[1][b])
        });
        (sub, p, jac)
    }

    /// Whether the host point `p` of sub-face `sub` (cell coordinates, as
    /// [`FanTriangle::to_host`] gives them; `sub` is 0 on a quad host) lies in this triangle,
    /// its sides widened by `eps`: the inverse test of `to_host`'s maps. On a quad host the
    /// triangle is the criss-cross triangle on side `edge` (`y <= x` and `x + y <= 1` for
    /// side 0, turning counter-clockwise); on an n-gon host it is the half `y <= x` of sub-face
    /// `edge` and the half `x <= y` of sub-face `edge + 1`.
    pub fn holds(&self, sub: u32, [x, y]: [f64; 2], eps: f64) -> bool {
        let i = self.edge % self.sides.max(1);
        if self.sides == 4 {
            // below the diagonal y = x; below the anti-diagonal x + y = 1
            let (below, below_anti) = (y - x <= eps, x + y - 1.0 <= eps);
            let (above, above_anti) = (x - y <= eps, 1.0 - x - y <= eps);
            sub == 0
                && match i {
                    0 => below && below_anti,
                    1 => below && above_anti,
                    2 => above && above_anti,
                    _ => above && below_anti,
                }
        } else if sub == i {
            y <= x + eps
        } else if sub == (i + 1) % self.sides {
            x <= y + eps
        } else {
            false
        }
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    /// The host point of a fan triangle's corner `k` (0, 1, 2) as (sub-face, cell point).
    fn corner(f: &FanTriangle, k: u8) -> (u32, [f64; 2]) {
        let uv = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]][usize::from(k)];
        let (sub, p, _) = f.to_host(uv[0], uv[1]);
        (sub, p)
    }

    #[crate::unit::test]
    fn corners_land_on_the_host_corners_and_centre() {
        for rot in 0..3u8 {
            // quad: host corners i, i + 1, the centre
            let q = FanTriangle {
                host: 0,
                sides: 4,
                edge: 2,
                rot,
            };
            assert_eq!(corner(&q, rot), (0, [1.0, 1.0]));
            assert_eq!(corner(&q, (rot + 1) % 3), (0, [0.0, 1.0]));
            assert_eq!(corner(&q, (rot + 2) % 3), (0, [0.5, 0.5]));
            // pentagon: corner i at (0, 0) of sub-face i, corner i + 1 at (0, 0) of sub-face
            // i + 1, the centre at (1, 1) of sub-face i + 1 (either sub-face's (1, 1))
            let p = FanTriangle {
                host: 0,
                sides: 5,
                edge: 4,
                rot,
            };
            assert_eq!(corner(&p, rot), (4, [0.0, 0.0]));
            assert_eq!(corner(&p, (rot + 1) % 3), (0, [0.0, 0.0]));
            assert_eq!(corner(&p, (rot + 2) % 3), (0, [1.0, 1.0]));
        }
    }

    #[crate::unit::test]
    fn the_two_halves_meet_on_the_median_and_jacobians_are_positive() {
        let p = FanTriangle {
            host: 0,
            sides: 3,
            edge: 1,
            rot: 0,
        };
        for k in 0..=8 {
            // the segment 2 s + t = 1 from the edge midpoint to the centre, from both sides
            let t = f64::from(k) / 8.0;
            let s = (1.0 - t) / 2.0;
            let (a, pa, _) = p.to_host(s - 1e-13, t);
            let (b, pb, _) = p.to_host(s + 1e-13, t);
            assert_eq!((a, b), (1, 2));
            // sub-face 1's edge x = 1 (M_1 to the centre) is sub-face 2's edge y = 1
            assert!((pa[0] - 1.0).abs() < 1e-12 && (pb[1] - 1.0).abs() < 1e-12);
            assert!((pa[1] - t).abs() < 1e-12 && (pb[0] - t).abs() < 1e-12);
        }
        for sides in [3, 4, 6] {
            for rot in 0..3 {
                let f = FanTriangle {
                    host: 0,
                    sides,
                    edge: 1,
                    rot,
                };
                for (u, v) in [(0.1, 0.2), (0.6, 0.3), (0.2, 0.7)] {
                    let (_, _, j) = f.to_host(u, v);
                    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
                    // the triangle is half (n-gon: two halves of sub-faces) or a quarter (quad)
                    // of the host's cell
                    let area = if sides == 4 { 0.5 } else { 2.0 };
                    assert_eq!(det, area, "sides {sides} rot {rot} at ({u}, {v})");
                }
            }
        }
    }

    #[crate::unit::test]
    fn holds_inverts_to_host() {
        // points of every fan triangle of a triangle, a quad and a hexagon host: held by their
        // own triangle, by no other (inside, away from the sides) and only with `eps` on a side
        for sides in [3u32, 4, 6] {
            let fans: Vec<FanTriangle> = (0..sides)
                .map(|edge| FanTriangle {
                    host: 0,
                    sides,
                    edge,
                    rot: (edge % 3) as u8,
                })
                .collect();
            for f in &fans {
                for (u, v) in [(0.1, 0.2), (0.6, 0.3), (0.2, 0.7), (0.3, 0.3), (0.05, 0.9)] {
                    let (sub, p, _) = f.to_host(u, v);
                    for g in &fans {
                        assert_eq!(
                            g.holds(sub, p, 1e-12),
                            g.edge == f.edge,
                            "sides {sides}: ({u}, {v}) of edge {} tested on edge {}",
                            f.edge,
                            g.edge
                        );
                    }
                }
                // a point on the side toward the centre shared with the next triangle
                let next = &fans[((f.edge + 1) % sides) as usize];
                let r = usize::from(f.rot);
                // barycentric (s, t) = (1, 0) is host corner edge + 1; (s, t) = (1/2, 1/2) the
                // middle of the side from it to the centre
                let mut l = [0.0; 3];
                l[(r + 1) % 3] = 0.5;
                l[(r + 2) % 3] = 0.5;
                let (sub, p, _) = f.to_host(l[1], l[2]);
                assert!(f.holds(sub, p, 1e-12) && next.holds(sub, p, 1e-12));
            }
        }
    }
}
