//! Polynomial tensor-product B-spline surfaces and B-spline curves, the geometry of CAD faces
//! and edges.
//!
//! Knot vectors are clamped (the first and last knot repeated `degree + 1` times) and stored
//! in full. Everything that builds a new spline from an old one (a sub-curve, the Bezier
//! pieces, the merge of patches into one face) goes through the blossom (polar form): the
//! control point `i` of a spline of degree `p` with knots `t` is the blossom of its polynomial
//! piece on any knot span inside `[t_i, t_{i+p+1}]`, evaluated at `t_{i+1}, ..., t_{i+p}`.
//! This is exact (in exact arithmetic) whenever the new knot vector's spline space contains
//! the old piecewise polynomial, and it needs no knot insertion or removal loops.

use crate::bezier::{BezierPatch, Side, curve};
use crate::geom::Point;

/// A polynomial B-spline curve with a clamped knot vector.
#[derive(Debug, Clone, PartialEq)]
pub struct SplineCurve {
    /// Degree.
    pub deg: usize,
    /// The full knot vector (`cps.len() + deg + 1` knots).
    pub knots: Vec<f64>,
    /// Control points.
    pub cps: Vec<Point>,
}

/// A polynomial tensor-product B-spline surface with clamped knot vectors.
#[derive(Debug, Clone, PartialEq)]
pub struct SplineSurface {
    /// Degrees in `u` and `v`.
    pub deg: [usize; 2],
    /// The full knot vectors in `u` and `v`.
    pub knots: [Vec<f64>; 2],
    /// Control points, `P[i][j]` (`i` along `u`) at `i * nv + j`.
    pub cps: Vec<Point>,
}

/// The index `a` of the span `[t_a, t_{a+1})` (non-empty) that holds `x`, clamped to the
/// valid spans of a clamped knot vector of degree `p`.
pub fn find_span(knots: &[f64], p: usize, x: f64) -> usize {
    let n = knots.len() - p - 1; // number of control points
    if x >= knots[n] {
        // the last non-empty span
        let mut a = n - 1;
        while a > p && knots[a] >= knots[a + 1] {
            a -= 1;
        }
        return a;
    }
    let hi = knots[p + 1..=n].partition_point(|&k| k <= x) + p;
    hi.max(p)
}

/// The blossom of the piece of the spline `(p, knots, cps)` on span `a` at `args` (`p` values):
/// de Boor's algorithm with a different argument per level.
pub fn spline_blossom<const D: usize>(
    p: usize,
    knots: &[f64],
    cps: &[[f64; D]],
    a: usize,
    args: &[f64],
) -> [f64; D] {
    debug_assert_eq!(args.len(), p);
    let mut d: Vec<[f64; D]> = cps[a - p..=a].to_vec();
    for (r, &x) in (1..=p).zip(args) {
        for k in (r..=p).rev() {
            let i = a - p + k;
            let (lo, hi) = (knots[i], knots[i + p + 1 - r]);
            let al = if hi > lo { (x - lo) / (hi - lo) } else { 0.0 };
            for c in 0..D {
                d[k][c] = (1.0 - al) * d[k - 1][c] + al * d[k][c];
            }
        }
    }
    d[p]
}

/// The spans `[lo, hi]` of the distinct knots of a clamped knot vector, in order.
pub fn distinct(knots: &[f64]) -> (Vec<f64>, Vec<usize>) {
    let mut vals: Vec<f64> = Vec::new();
    let mut mult: Vec<usize> = Vec::new();
    for &k in knots {
        match vals.last() {
            Some(&l) if l == k => *mult.last_mut().expect("one per value") += 1,
            _ => {
                vals.push(k);
                mult.push(1);
            }
        }
    }
    (vals, mult)
}

/// For a target knot vector `target` of degree `p`, the index `i` of each control point and
/// the span of `target` (the widest non-empty one inside its support) to blossom it on.
pub(crate) fn support_spans(target: &[f64], p: usize) -> Vec<usize> {
    let n = target.len() - p - 1;
    (0..n)
        .map(|i| {
            let mut best = i.max(p).min(n - 1);
            let mut w = -1.0;
            for a in i..=i + p {
                if a < p || a >= n {
                    continue;
                }
                let width = target[a + 1] - target[a];
                if width > w {
                    w = width;
                    best = a;
                }
            }
            best
        })
        .collect()
}

impl SplineCurve {
    /// A Bezier curve as a one-span B-spline on `[0, 1]`.
    pub fn from_bezier(cps: Vec<Point>) -> SplineCurve {
        let deg = cps.len() - 1;
        let mut knots = vec![0.0; deg + 1];
        knots.extend(std::iter::repeat_n(1.0, deg + 1));
        SplineCurve { deg, knots, cps }
    }

    /// The parameter interval.
    pub fn range(&self) -> [f64; 2] {
        [self.knots[self.deg], self.knots[self.cps.len()]]
    }

    /// The point at `t`.
    pub fn eval(&self, t: f64) -> Point {
        let a = find_span(&self.knots, self.deg, t);
        spline_blossom(self.deg, &self.knots, &self.cps, a, &vec![t; self.deg])
    }

    /// The Bezier pieces with their parameter intervals.
    pub fn bezier_pieces(&self) -> Vec<([f64; 2], Vec<Point>)> {
        let p = self.deg;
        let n = self.cps.len();
        (p..n)
            .filter(|&a| self.knots[a + 1] > self.knots[a])
            .map(|a| {
                let (lo, hi) = (self.knots[a], self.knots[a + 1]);
                let cps = (0..=p)
                    .map(|k| {
                        let mut args = vec![lo; p - k];
                        args.extend(std::iter::repeat_n(hi, k));
                        spline_blossom(p, &self.knots, &self.cps, a, &args)
                    })
                    .collect();
                ([lo, hi], cps)
            })
            .collect()
    }

    /// The curve restricted to `[t0, t1]` (inside its range, `t0 < t1`), with the knots of the
    /// curve inside that interval (exact: blossoming).
    pub fn restricted(&self, t0: f64, t1: f64) -> SplineCurve {
        let p = self.deg;
        let mut knots = vec![t0; p + 1];
        knots.extend(self.knots.iter().copied().filter(|&k| k > t0 && k < t1));
        knots.extend(std::iter::repeat_n(t1, p + 1));
        let cps = support_spans(&knots, p)
            .into_iter()
            .enumerate()
            .map(|(i, a)| {
                let mid = 0.5 * (knots[a] + knots[a + 1]);
                let sa = find_span(&self.knots, p, mid);
                spline_blossom(p, &self.knots, &self.cps, sa, &knots[i + 1..=i + p])
            })
            .collect();
        SplineCurve { deg: p, knots, cps }
    }

    /// The parameter of the point of the curve nearest `q`, and the distance.
    pub fn closest(&self, q: Point) -> (f64, f64) {
        let mut best = (self.range()[0], f64::INFINITY);
        for ([lo, hi], cps) in self.bezier_pieces() {
            let (t, d) = curve::closest_param(&cps, q);
            if d < best.1 {
                best = (lo + t * (hi - lo), d);
            }
        }
        best
    }
}

impl SplineSurface {
    /// A Bezier patch as a one-span B-spline surface on `[0, 1]^2` (degree 0 directions
    /// raised to 1, exactly: CAD systems want degree >= 1).
    pub fn from_bezier(p: &BezierPatch) -> SplineSurface {
        let p = p
            .raised_to(p.deg_u.max(1), p.deg_v.max(1))
            .expect("raising never lowers");
        let knots = |d: usize| {
            let mut k = vec![0.0; d + 1];
            k.extend(std::iter::repeat_n(1.0, d + 1));
            k
        };
        SplineSurface {
            deg: [p.deg_u, p.deg_v],
            knots: [knots(p.deg_u), knots(p.deg_v)],
            cps: p.cps,
        }
    }

    /// Number of control points in `u` and `v`.
    pub fn counts(&self) -> [usize; 2] {
        [
            self.knots[0].len() - self.deg[0] - 1,
            self.knots[1].len() - self.deg[1] - 1,
        ]
    }

    /// Control point `P[i][j]`.
    pub fn cp(&self, i: usize, j: usize) -> Point {
        self.cps[i * self.counts()[1] + j]
    }

    /// The parameter rectangle `[[u0, u1], [v0, v1]]`.
    pub fn range(&self) -> [[f64; 2]; 2] {
        let [nu, nv] = self.counts();
        [
            [self.knots[0][self.deg[0]], self.knots[0][nu]],
            [self.knots[1][self.deg[1]], self.knots[1][nv]],
        ]
    }

    /// The point at `(u, v)`.
    pub fn eval(&self, u: f64, v: f64) -> Point {
        let [p, q] = self.deg;
        let nv = self.counts()[1];
        let a = find_span(&self.knots[0], p, u);
        let b = find_span(&self.knots[1], q, v);
        let column: Vec<Point> = (a - p..=a)
            .map(|i| {
                let row = &self.cps[i * nv..(i + 1) * nv];
                spline_blossom(q, &self.knots[1], row, b, &vec![v; q])
            })
            .collect();
        // the column holds the points of rows a - p ..= a: blossom them as span p of a
        // knot vector shifted to start at a - p
        let shifted = &self.knots[0][a - p..];
        spline_blossom(p, shifted, &column, p, &vec![u; p])
    }

    /// The boundary curve on `side`, in increasing parameter order (`U0`, `U1` along `v`;
    /// `V0`, `V1` along `u`).
    pub fn side(&self, side: Side) -> SplineCurve {
        let [nu, nv] = self.counts();
        let (deg, knots, cps): (usize, &Vec<f64>, Vec<Point>) = match side {
            Side::U0 => (
                self.deg[1],
                &self.knots[1],
                (0..nv).map(|j| self.cp(0, j)).collect(),
            ),
            Side::U1 => (
                self.deg[1],
                &self.knots[1],
                (0..nv).map(|j| self.cp(nu - 1, j)).collect(),
            ),
            Side::V0 => (
                self.deg[0],
                &self.knots[0],
                (0..nu).map(|i| self.cp(i, 0)).collect(),
            ),
            Side::V1 => (
                self.deg[0],
                &self.knots[0],
                (0..nu).map(|i| self.cp(i, nv - 1)).collect(),
            ),
        };
        SplineCurve {
            deg,
            knots: knots.clone(),
            cps,
        }
    }

    /// The surface with `u` and `v` swapped (the normal flips).
    pub fn transposed(&self) -> SplineSurface {
        let [nu, nv] = self.counts();
        let mut cps = Vec::with_capacity(self.cps.len());
        for j in 0..nv {
            for i in 0..nu {
                cps.push(self.cp(i, j));
            }
        }
        SplineSurface {
            deg: [self.deg[1], self.deg[0]],
            knots: [self.knots[1].clone(), self.knots[0].clone()],
            cps,
        }
    }

    /// The Bezier pieces of the surface with their rectangles `[[u0, u1], [v0, v1]]`.
    pub fn bezier_pieces(&self) -> Vec<([[f64; 2]; 2], BezierPatch)> {
        let [p, q] = self.deg;
        let [nu, nv] = self.counts();
        let spans = |k: &Vec<f64>, d: usize, n: usize| -> Vec<usize> {
            (d..n).filter(|&a| k[a + 1] > k[a]).collect()
        };
        let mut out = Vec::new();
        for a in spans(&self.knots[0], p, nu) {
            for b in spans(&self.knots[1], q, nv) {
                let (u0, u1) = (self.knots[0][a], self.knots[0][a + 1]);
                let (v0, v1) = (self.knots[1][b], self.knots[1][b + 1]);
                // v first: the Bezier rows of every control row i in a - p ..= a
                let rows: Vec<Vec<Point>> = (a - p..=a)
                    .map(|i| {
                        let row = &self.cps[i * nv..(i + 1) * nv];
                        (0..=q)
                            .map(|l| {
                                let mut args = vec![v0; q - l];
                                args.extend(std::iter::repeat_n(v1, l));
                                spline_blossom(q, &self.knots[1], row, b, &args)
                            })
                            .collect()
                    })
                    .collect();
                let shifted = &self.knots[0][a - p..];
                let patch = BezierPatch::from_fn(p, q, |k, l| {
                    let col: Vec<Point> = rows.iter().map(|r| r[l]).collect();
                    let mut args = vec![u0; p - k];
                    args.extend(std::iter::repeat_n(u1, k));
                    spline_blossom(p, shifted, &col, p, &args)
                });
                out.push(([[u0, u1], [v0, v1]], patch));
            }
        }
        out
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    fn patch() -> BezierPatch {
        BezierPatch::from_fn(3, 2, |i, j| {
            let (x, y) = (i as f64, j as f64);
            [x, y, (x * y + 0.3 * x * x - y).sin()]
        })
    }

    #[crate::unit::test]
    fn one_span_surfaces_evaluate_as_their_patch() {
        let b = patch();
        let s = SplineSurface::from_bezier(&b);
        for &(u, v) in &[(0.0, 0.0), (0.3, 0.7), (1.0, 1.0), (0.5, 0.0)] {
            let (x, y) = (s.eval(u, v), b.eval(u, v));
            assert!(crate::geom::dist(x, y) < 1e-14, "{x:?} {y:?}");
        }
        let pieces = s.bezier_pieces();
        assert_eq!(pieces.len(), 1);
        assert!(curve::coefficient_distance(&pieces[0].1.cps, &b.cps) < 1e-14);
    }

    #[crate::unit::test]
    fn restriction_keeps_the_curve() {
        let c = SplineCurve::from_bezier(vec![
            [0.0, 0.0, 0.0],
            [1.0, 2.0, 0.0],
            [2.0, -1.0, 1.0],
            [3.0, 0.0, 0.5],
        ]);
        let r = c.restricted(0.25, 0.75);
        for k in 0..=8 {
            let t = 0.25 + 0.5 * f64::from(k) / 8.0;
            assert!(crate::geom::dist(r.eval(t), c.eval(t)) < 1e-14);
        }
        let (t, d) = c.closest(c.eval(0.4));
        assert!((t - 0.4).abs() < 1e-9 && d < 1e-12);
    }
}
