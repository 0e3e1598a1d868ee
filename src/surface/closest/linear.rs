//! The piecewise-linear surrogate of a chart that prunes [`super::ProjectionIndex::closest`]'s
//! candidates and starts its Newton searches: the chart's sample grid cut into triangles, and
//! how far the surface strays from them.
//!
//! A point `S(x)` of the chart lies within `deviation` of the point at the same local
//! coordinates `x` of the linear interpolant over the triangle holding `x`, so the distance
//! from `q` to the chart's surface is at least the distance from `q` to the triangles less
//! `deviation` (far tighter than the sample grid's own bound, the nearest sample's distance
//! less the grid's spacing, once the query is a few grid cells away). The deviation is
//! measured when the index is built, at each triangle's centroid and edge midpoints, where
//! the interpolation error of a smooth surface peaks (it is of second order in the grid's
//! size), and taken twice over: a measured bound, not a proven one, like the grid's spacing.
//! The closest point on the nearest triangle, mapped back to local coordinates through its
//! barycentric coordinates, is where Newton's iteration starts.

use crate::bezier::domain::Shape;
use crate::geom::{Point, add, cross, dot, scale, sub};

/// The triangles of a sample grid with `n` samples per side, as indices into the grid's
/// samples in `super::grid`'s order (row `i`, column `j`; a triangle grid's rows shorten).
pub(super) fn triangles(shape: Shape, n: usize) -> Vec<[usize; 3]> {
    // the index of sample (i, j) in grid order
    let index = |i: usize, j: usize| match shape {
        Shape::Quad => i * n + j,
        // rows of n, n - 1, ... samples
        Shape::Triangle => (0..i).map(|r| n - r).sum::<usize>() + j,
    };
    let mut out = Vec::new();
    for i in 0..n - 1 {
        for j in 0..n - 1 {
            let quad = shape == Shape::Quad;
            if quad || i + j + 1 < n {
                out.push([index(i, j), index(i + 1, j), index(i, j + 1)]);
            }
            if quad || i + j + 2 < n {
                out.push([index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)]);
            }
        }
    }
    out
}

/// The closest point to `p` of the triangle `t`, as barycentric weights of its corners
/// (Ericson, *Real-Time Collision Detection*, 5.1.5; a degenerate triangle through its
/// edges).
pub(super) fn closest_on_triangle(p: Point, t: [Point; 3]) -> [f64; 3] {
    let [a, b, c] = t;
    let (ab, ac, ap) = (sub(b, a), sub(c, a), sub(p, a));
    let n = cross(ab, ac);
    if dot(n, n) <= 1e-28 * dot(ab, ab).max(dot(ac, ac)).powi(2) {
        return degenerate(p, t);
    }
    let (d1, d2) = (dot(ab, ap), dot(ac, ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return [1.0, 0.0, 0.0];
    }
    let bp = sub(p, b);
    let (d3, d4) = (dot(ab, bp), dot(ac, bp));
    if d3 >= 0.0 && d4 <= d3 {
        return [0.0, 1.0, 0.0];
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return [1.0 - v, v, 0.0];
    }
    let cp = sub(p, c);
    let (d5, d6) = (dot(ab, cp), dot(ac, cp));
    if d6 >= 0.0 && d5 <= d6 {
        return [0.0, 0.0, 1.0];
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return [1.0 - w, 0.0, w];
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return [0.0, 1.0 - w, w];
    }
    let denom = 1.0 / (va + vb + vc);
    let (v, w) = (vb * denom, vc * denom);
    [1.0 - v - w, v, w]
}

/// [`closest_on_triangle`] of a triangle without area: the closest point of its three edges.
fn degenerate(p: Point, t: [Point; 3]) -> [f64; 3] {
    let mut best = (f64::INFINITY, [1.0, 0.0, 0.0]);
    for (i, j) in [(0, 1), (1, 2), (2, 0)] {
        let d = sub(t[j], t[i]);
        let len2 = dot(d, d);
        let s = if len2 > 0.0 {
            (dot(sub(p, t[i]), d) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let x = add(t[i], scale(d, s));
        let r = sub(p, x);
        let dist2 = dot(r, r);
        if dist2 < best.0 {
            let mut w = [0.0; 3];
            w[i] = 1.0 - s;
            w[j] += s;
            best = (dist2, w);
        }
    }
    best.1
}

/// `w[0] a + w[1] b + w[2] c` of three points.
pub(super) fn combine(w: [f64; 3], t: [Point; 3]) -> Point {
    std::array::from_fn(|k| w[0] * t[0][k] + w[1] * t[1][k] + w[2] * t[2][k])
}

/// `w[0] a + w[1] b + w[2] c` of three local points.
pub(super) fn combine_local(w: [f64; 3], t: [[f64; 2]; 3]) -> [f64; 2] {
    std::array::from_fn(|k| w[0] * t[0][k] + w[1] * t[1][k] + w[2] * t[2][k])
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn grids_are_cut_into_the_right_number_of_triangles() {
        assert_eq!(triangles(Shape::Quad, 5).len(), 32);
        assert_eq!(triangles(Shape::Triangle, 5).len(), 16);
        // every index names a sample of the grid
        assert!(
            triangles(Shape::Triangle, 5)
                .iter()
                .flatten()
                .all(|&i| i < 15)
        );
    }

    #[crate::unit::test]
    fn the_closest_point_of_a_triangle_is_the_brute_force_one() {
        let t = [[0.0, 0.0, 0.0], [2.0, 0.1, 0.0], [0.3, 1.5, 0.2]];
        let mut x = 0x1234_5678_9abc_def1u64;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 * 6.0 - 3.0
        };
        for _ in 0..200 {
            let p = [next(), next(), next()];
            let got = crate::geom::dist(combine(closest_on_triangle(p, t), t), p);
            let mut brute = f64::INFINITY;
            for i in 0..=200 {
                for j in 0..=200 - i {
                    let w = [
                        1.0 - (i + j) as f64 / 200.0,
                        i as f64 / 200.0,
                        j as f64 / 200.0,
                    ];
                    brute = brute.min(crate::geom::dist(combine(w, t), p));
                }
            }
            assert!(got <= brute + 1e-12 && brute - got < 0.02, "{got} {brute}");
        }
        // a triangle without area: its segment
        let flat = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
        let w = closest_on_triangle([0.5, 1.0, 0.0], flat);
        assert!(crate::geom::dist(combine(w, flat), [0.5, 0.0, 0.0]) < 1e-15);
    }
}
