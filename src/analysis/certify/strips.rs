//! Closed polylines indexed by horizontal strips, so that the global half of the injectivity
//! certificate (winding numbers of sample points, simplicity of the boundary curves) costs time
//! close to linear in the length of the curves instead of quadratic: a characteristic ring of
//! valence 100 has boundary polylines of thousands of points and thousands of sample points.
//!
//! Each edge `(p_i, p_{i+1})` (cyclic) is listed in every strip its `y` range meets. The
//! winding number of a point is counted from the signed crossings of a horizontal ray with the
//! edges of the point's strip (exact for points off the curve, no trigonometry); two edges can
//! only cross when their bounding boxes meet, so simplicity tests pairs within the cells of a
//! grid only.

use crate::geom::Point;

/// A closed polyline with its edges sorted into strips of equal height.
pub(super) struct Strips<'a> {
    poly: &'a [Point],
    y0: f64,
    height: f64,
    bins: Vec<Vec<u32>>,
}

/// Twice the signed area of `(a, b, c)`: positive when `c` lies left of `a -> b`.
fn orient(a: Point, b: Point, c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

impl<'a> Strips<'a> {
    /// The index of the closed polyline `poly`.
    pub fn new(poly: &'a [Point]) -> Self {
        let n = poly.len();
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in poly {
            lo = lo.min(p[1]);
            hi = hi.max(p[1]);
        }
        let nbins = (n / 4).max(1);
        let height = if hi > lo && hi.is_finite() && lo.is_finite() {
            (hi - lo) / nbins as f64
        } else {
            0.0
        };
        let mut s = Strips {
            poly,
            y0: lo,
            height,
            bins: vec![Vec::new(); if height > 0.0 { nbins } else { 1 }],
        };
        for i in 0..n {
            let (a, b) = (poly[i][1], poly[(i + 1) % n][1]);
            let (b0, b1) = (s.bin(a.min(b)), s.bin(a.max(b)));
            for bin in &mut s.bins[b0..=b1] {
                bin.push(i as u32);
            }
        }
        s
    }

    /// The strip of height `y` (clamped to the strips).
    fn bin(&self, y: f64) -> usize {
        if self.height <= 0.0 || y.is_nan() {
            return 0;
        }
        let b = ((y - self.y0) / self.height).floor();
        (b.max(0.0) as usize).min(self.bins.len() - 1)
    }

    fn edge(&self, i: u32) -> (Point, Point) {
        let i = i as usize;
        (self.poly[i], self.poly[(i + 1) % self.poly.len()])
    }

    /// The winding number of the curve around `o` (counter-clockwise positive).
    pub fn winding(&self, o: [f64; 2]) -> i64 {
        if self.poly.is_empty() || o[1].is_nan() || o[1] < self.y0 {
            return 0;
        }
        let mut w = 0;
        for &i in &self.bins[self.bin(o[1])] {
            let (a, b) = self.edge(i);
            if a[1] <= o[1] {
                if b[1] > o[1] && orient(a, b, o) > 0.0 {
                    w += 1;
                }
            } else if b[1] <= o[1] && orient(a, b, o) < 0.0 {
                w -= 1;
            }
        }
        w
    }

    /// Whether no two non-adjacent edges cross (properly). Two edges can only cross where their
    /// bounding boxes meet, so the edges are listed in the cells of a uniform grid of about as
    /// many cells as edges that their boxes cover, and pairs are tested within cells: the
    /// strips alone would pair every edge of a curve with long radial spikes (the outer boundary
    /// of a characteristic ring at valence 1000 is a star of 2000 spikes, each crossing
    /// thousands of strips) with every other, quadratically.
    pub fn is_simple(&self) -> bool {
        let n = self.poly.len();
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in self.poly {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let g = ((n as f64).sqrt().ceil() as usize).max(1);
        let cell = |k: usize, v: f64| -> usize {
            let span = hi[k] - lo[k];
            if !(span > 0.0 && span.is_finite()) || v.is_nan() {
                return 0;
            }
            (((v - lo[k]) / span * g as f64).floor().max(0.0) as usize).min(g - 1)
        };
        let mut cells: Vec<Vec<u32>> = vec![Vec::new(); g * g];
        for i in 0..n {
            let (a, b) = self.edge(i as u32);
            let (x0, x1) = (cell(0, a[0].min(b[0])), cell(0, a[0].max(b[0])));
            let (y0, y1) = (cell(1, a[1].min(b[1])), cell(1, a[1].max(b[1])));
            for x in x0..=x1 {
                for y in y0..=y1 {
                    cells[x * g + y].push(i as u32);
                }
            }
        }
        for bin in &cells {
            for (x, &i) in bin.iter().enumerate() {
                for &j in &bin[x + 1..] {
                    let (i, j) = (i.min(j) as usize, i.max(j) as usize);
                    if j == i + 1 || (i == 0 && j == n - 1) {
                        continue;
                    }
                    let (a, b) = self.edge(i as u32);
                    let (c, d) = self.edge(j as u32);
                    if super::segments_cross(a, b, c, d) {
                        return false;
                    }
                }
            }
        }
        true
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    /// A circle of `n` points, counter-clockwise.
    fn circle(n: usize, r: f64) -> Vec<Point> {
        (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                [r * a.cos(), r * a.sin(), 0.0]
            })
            .collect()
    }

    #[crate::unit::test]
    fn windings_match_the_angle_sum() {
        let c = circle(200, 1.0);
        let s = Strips::new(&c);
        assert_eq!(s.winding([0.0, 0.0]), 1);
        assert_eq!(s.winding([0.3, -0.7]), 1);
        assert_eq!(s.winding([1.5, 0.0]), 0);
        assert_eq!(s.winding([0.0, -3.0]), 0);
        let mut r = c.clone();
        r.reverse();
        assert_eq!(Strips::new(&r).winding([0.1, 0.1]), -1);
    }

    #[crate::unit::test]
    fn a_figure_eight_is_not_simple() {
        let c = circle(100, 1.0);
        assert!(Strips::new(&c).is_simple());
        // a bow tie: (0,0) (1,1) (1,0) (0,1)
        let bow = [
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        assert!(!Strips::new(&bow).is_simple());
    }
}
