//! Cells split at a ratio: the 2 x 2 children of a quad cell cut at `t` (not at `1/2`) in both
//! directions, for adjustable TPS, whose steps split a piece `e : 1 - 2e : e`, so that the hole
//! inside ring `l` of an extraordinary vertex is `[0, s^l]^2` of the quarter at the vertex
//! (`s = 1 - 2e`, knot coordinates; `crate::schemes::bi2::surface::thirds`).
//!
//! Child `k` of a cell split at `t` is, in the cell's coordinates (not turned, like the
//! children in thirds): `0` the corner square `[0, t]^2`, `1` the rectangle `[t, 1] x [0, t]`,
//! `2` `[t, 1]^2`, `3` `[0, t] x [t, 1]`; each child's own `(u, v)` runs along the cell's,
//! scaled. Such a level has radix 4 in [`Domain::path`] (so the key is a dyadic-looking path)
//! and is marked in [`Domain::split_at`]; one ratio per domain ([`Domain::ratio`], the `f64`'s
//! bits), the same at all its levels split so. The maps have the coefficients `t` and `1 - t`,
//! rounded once per level.

use super::{Affine, Domain, Shape};

impl Shape {
    /// The map from child `k` of a quad cell split at `t` to the cell (see the
    /// module documentation).
    pub fn ratio_map(t: f64, k: u8) -> Affine {
        let (x, y) = ratio_box(t, k);
        Affine::new([x[0], y[0]], [x[1] - x[0], 0.0], [0.0, y[1] - y[0]])
    }

    /// The child of a quad cell split at `t` that holds the cell point `p` (ties go to the
    /// child at the larger coordinate).
    pub fn ratio_at(t: f64, p: [f64; 2]) -> u8 {
        match (p[0] >= t, p[1] >= t) {
            (false, false) => 0,
            (true, false) => 1,
            (true, true) => 2,
            (false, true) => 3,
        }
    }
}

/// The child's `[lo, hi]` in `u` and in `v`.
pub(super) fn ratio_box(t: f64, k: u8) -> ([f64; 2], [f64; 2]) {
    let (lo, hi) = ([0.0, t], [t, 1.0]);
    match k & 3 {
        0 => (lo, lo),
        1 => (hi, lo),
        2 => (hi, hi),
        _ => (lo, hi),
    }
}

impl Domain {
    /// Whether level `l` (1-based) of this cell's chain splits its parent at
    /// [`Domain::ratio`].
    pub fn splits_at_ratio(&self, l: u8) -> bool {
        (1..=64).contains(&l) && (self.split_at >> (l - 1)) & 1 == 1
    }

    /// The ratio of the levels split at a ratio.
    pub fn ratio(&self) -> f64 {
        f64::from_bits(self.ratio)
    }

    /// Child `k` of this quad cell split at `t` (`0 < t < 1`), with the patch's `(0, 0)` at
    /// corner 0. The n-gon itself, triangle cells, untracked domains and a domain whose other
    /// levels split at another ratio give an untracked domain.
    pub fn ratio_child(self, t: f64, k: u8) -> Domain {
        let other = self.split_at != 0 && self.ratio != t.to_bits();
        self.quad_child(k, !other && t > 0.0 && t < 1.0, |d| Domain {
            split_at: d.split_at | (1u64 << (d.depth - 1)),
            ratio: t.to_bits(),
            ..d
        })
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn ratio_children_tile_the_cell() {
        let t = 0.6;
        for k in 0..4u8 {
            let m = Shape::ratio_map(t, k);
            let c = m.apply([0.5, 0.5]);
            assert_eq!(Shape::ratio_at(t, c), k);
        }
        let d = Domain::face(3, 4)
            .child(2)
            .ratio_child(t, 0)
            .ratio_child(t, 2);
        assert_eq!((d.depth, d.step(1), d.step(2), d.step(3)), (3, 2, 0, 2));
        assert!(!d.splits_at_ratio(1) && d.splits_at_ratio(2) && d.splits_at_ratio(3));
        let want = Shape::Quad
            .child_map(2)
            .compose(&Shape::ratio_map(t, 0))
            .compose(&Shape::ratio_map(t, 2));
        assert_eq!(d.cell_map(), want);
        // [0.36, 0.6]^2 of child 2 of the face
        let p = d.cell_map().apply([0.0, 0.0]);
        let q = Shape::Quad.child_map(2).apply([0.36, 0.36]);
        assert!((p[0] - q[0]).abs() < 1e-15 && (p[1] - q[1]).abs() < 1e-15);
        // another ratio below is refused
        assert!(!d.ratio_child(0.5, 1).is_tracked());
    }
}
