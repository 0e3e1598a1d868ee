//! The Coons patch of four boundary curves (the fills of the schemes' holes).

use super::BezierPatch;
use crate::geom::Point;

impl BezierPatch {
    /// The bilinearly blended Coons patch of four boundary curves of degree `d` (`d + 1`
    /// coefficients each, in increasing parameter order: `v0` along `v = 0`, `u1` along `u = 1`,
    /// `v1` along `v = 1`, `u0` along `u = 0`). Its coefficients are
    /// `b_ij = (1-s) b_0j + s b_dj + (1-t) b_i0 + t b_id - bilinear(corners)` with
    /// `s = i/d`, `t = j/d`, which is the Coons patch in Bezier form; the boundary is reproduced
    /// exactly. The corners are taken from `v0` and `v1`.
    ///
    /// # Panics
    /// Panics when a curve does not have `d + 1` coefficients.
    pub fn coons(d: usize, v0: &[Point], u1: &[Point], v1: &[Point], u0: &[Point]) -> BezierPatch {
        for c in [v0, u1, v1, u0] {
            assert_eq!(c.len(), d + 1, "Coons boundary curve of the wrong degree");
        }
        let mut b = vec![[0.0; 3]; (d + 1) * (d + 1)];
        let at = |i: usize, j: usize| i * (d + 1) + j;
        for i in 0..=d {
            b[at(i, 0)] = v0[i];
            b[at(i, d)] = v1[i];
        }
        for j in 1..d {
            b[at(0, j)] = u0[j];
            b[at(d, j)] = u1[j];
        }
        let df = d as f64;
        for i in 1..d {
            for j in 1..d {
                let (s, t) = (i as f64 / df, j as f64 / df);
                let mut p = [0.0; 3];
                for k in 0..3 {
                    p[k] = (1.0 - s) * b[at(0, j)][k]
                        + s * b[at(d, j)][k]
                        + (1.0 - t) * b[at(i, 0)][k]
                        + t * b[at(i, d)][k]
                        - ((1.0 - s) * (1.0 - t) * b[at(0, 0)][k]
                            + s * (1.0 - t) * b[at(d, 0)][k]
                            + (1.0 - s) * t * b[at(0, d)][k]
                            + s * t * b[at(d, d)][k]);
                }
                b[at(i, j)] = p;
            }
        }
        BezierPatch::new(d, d, b)
    }
}
