//! Tensor-product Bezier patches and Bezier curves.
//!
//! Every surface fairsub outputs is a set of polynomial pieces in Bernstein-Bezier form. A
//! [`BezierPatch`] of bi-degree `(du, dv)` stores its coefficients `b[i][j]` row-major with `i`
//! along `u` (`cps[i * (dv + 1) + j]`), the convention of the papers and of BezierView.

use crate::geom::Point;

/// A tensor-product Bezier patch of bi-degree `(deg_u, deg_v)`.
#[derive(Debug, Clone, PartialEq)]
pub struct BezierPatch {
    /// Degree in `u` (the first coefficient index).
    pub deg_u: usize,
    /// Degree in `v` (the second coefficient index).
    pub deg_v: usize,
    /// Coefficients, `b[i][j]` at `i * (deg_v + 1) + j`.
    pub cps: Vec<Point>,
}

impl BezierPatch {
    /// A patch from its coefficients (`(deg_u + 1) * (deg_v + 1)` of them, row-major, `i` along u).
    ///
    /// # Panics
    /// Panics when the number of coefficients does not match the degrees.
    pub fn new(deg_u: usize, deg_v: usize, cps: Vec<Point>) -> Self {
        assert_eq!(
            cps.len(),
            (deg_u + 1) * (deg_v + 1),
            "coefficient count does not match degrees"
        );
        BezierPatch { deg_u, deg_v, cps }
    }

    /// Coefficient `b[i][j]`.
    #[inline]
    pub fn cp(&self, i: usize, j: usize) -> Point {
        self.cps[i * (self.deg_v + 1) + j]
    }

    /// Mutable coefficient `b[i][j]`.
    #[inline]
    pub fn cp_mut(&mut self, i: usize, j: usize) -> &mut Point {
        &mut self.cps[i * (self.deg_v + 1) + j]
    }
}
