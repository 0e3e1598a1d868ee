//! Cells halved along one axis: the cells of a pole's fan triangles under polar bi-2
//! subdivision (PolBS), whose rings halve only radially.
//!
//! # The domain of a pole's fan triangle
//!
//! A fan triangle `(pole, A, B)` (`A` the corner after the pole, `B` the one after `A`) is a
//! collapsed quad, `(u, v)` in `[0, 1]^2`: `(0, 0)` at `A`, `(1, 0)` at `B`, the side `v = 1`
//! collapsed to the pole; `u` runs around the pole (from the spoke of `A` to that of `B`), `v`
//! from the edge `A B` (`v = 0`) to the pole (`v = 1`). An input triangle at a pole is one such
//! quad (its root cell, [`Domain::pole_triangle`]); an `n`-gon cap that PolBS turns into a pole
//! keeps the strip `[0, n] x [0, 1]` of an `n`-gon, its sub-face `i` being the fan triangle
//! `(pole, corner i, corner i + 1)` as such a quad (so the strip's `u` goes around the pole and
//! `v = 1` is the pole, the collapsed top of every sub-face).
//!
//! In the characteristic chart of PolBS (subdominant eigenvalue `1/2`) the level-`l` polar net
//! has its ring `a` at radius `2^-l`, `b` at `3 2^-l`, `c` at `5 2^-l`; the bi-2 patch of `b`
//! (ring `l`) spans the radii `[2, 4] 2^-l`, the collapsed cap after ring `L` the radii
//! `[0, 2] 2^-L`. With the radius `rho = 1 - v` (the edge `A B` at radius 1, the level-0 `a`
//! ring) ring `1` covers the halves of the quads outside `A B` next to it (quarters at `A` and
//! `B`, dyadic cells), ring `k >= 2` the band `1 - v` in `[2^(1-k), 2^(2-k)]` of the
//! triangle, and the cap after `L >= 1` rings `1 - v` in `[0, 2^(1-L)]`. Ring and cap
//! patches are centred on a spoke (around the pole their `v` runs from the middle of one
//! triangle to the middle of the next), so each covers the half `u <= 1/2` of the triangle
//! after its spoke and the half `u >= 1/2` of the one before it.
//!
//! These cells are halves: level 1 splits the triangle's quad into its halves in `u`, every
//! later level halves the cell in `v`, the half toward the pole being the hole of the next
//! ring. A level halved so is marked in [`Domain::halves`]; its child index `k` (radix 4 in
//! [`Domain::path`], so the key stays a dyadic-looking path) says which half: `0`, `1` the
//! halves `[0, 1/2] x [0, 1]`, `[1/2, 1] x [0, 1]` (in `u`), `2`, `3` the halves
//! `[0, 1] x [0, 1/2]`, `[0, 1] x [1/2, 1]` (in `v`). Halves are not turned: their `u` and `v`
//! run along the cell's, scaled. The maps are dyadic, so exact. Every patch on such cells is a
//! [`super::Piece`] with the patch's `(0, 0)` at corner 3 of the cell (the side toward the
//! pole, `u` of the cell along the patch's `v`), so the patch's `u` points away from the pole.

use super::{Affine, Domain, Shape};

impl Shape {
    /// The map from half `k` (see the module documentation) of a quad cell to the
    /// cell.
    pub fn half_map(k: u8) -> Affine {
        match k & 3 {
            0 => Affine::new([0.0, 0.0], [0.5, 0.0], [0.0, 1.0]),
            1 => Affine::new([0.5, 0.0], [0.5, 0.0], [0.0, 1.0]),
            2 => Affine::new([0.0, 0.0], [1.0, 0.0], [0.0, 0.5]),
            _ => Affine::new([0.0, 0.5], [1.0, 0.0], [0.0, 0.5]),
        }
    }

    /// The half of a quad cell halved along `axis` (0: `u`, 1: `v`) that holds the cell point
    /// `p`, as a child index (ties go to the upper half).
    pub fn half_at(axis: u8, p: [f64; 2]) -> u8 {
        let upper = u8::from(p[usize::from(axis & 1)] >= 0.5);
        2 * (axis & 1) + upper
    }
}

impl Domain {
    /// The whole fan triangle `face` at a pole as its collapsed quad (see the
    /// module documentation): the root of its halves.
    pub fn pole_triangle(face: u32) -> Domain {
        Domain::polygon(face, 4)
    }

    /// Whether level `l` (1-based) of this cell's chain halves its parent.
    pub fn splits_in_halves(&self, l: u8) -> bool {
        (1..=64).contains(&l) && (self.halves >> (l - 1)) & 1 == 1
    }

    /// Half `k` of this quad cell (see the module documentation), with the patch's
    /// `(0, 0)` at corner 0. The n-gon itself, triangle cells and untracked domains give an
    /// untracked domain.
    pub fn half_child(self, k: u8) -> Domain {
        self.quad_child(k, true, |d| Domain {
            halves: d.halves | (1u64 << (d.depth - 1)),
            ..d
        })
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn halves_tile_the_cell() {
        for k in 0..4u8 {
            let m = Shape::half_map(k);
            let c = m.apply([0.5, 0.5]);
            assert_eq!(Shape::half_at(k / 2, c), k);
            let det = m.e[0][0] * m.e[1][1] - m.e[1][0] * m.e[0][1];
            assert_eq!(det, 0.5);
            assert_eq!(m.invert(c), [0.5, 0.5]);
        }
        // ring 3's band of a fan triangle: the half u <= 1/2, then the half toward the pole,
        // then its half away from it: v in [1/2, 3/4]
        let d = Domain::pole_triangle(4)
            .half_child(0)
            .half_child(3)
            .half_child(2);
        assert_eq!((d.depth, d.step(1), d.step(2), d.step(3)), (3, 0, 3, 2));
        assert!(d.splits_in_halves(1) && d.splits_in_halves(3) && !d.splits_in_halves(4));
        let m = d.cell_map();
        assert_eq!(m.apply([0.0, 0.0]), [0.0, 0.5]);
        assert_eq!(m.apply([1.0, 1.0]), [0.5, 0.75]);
        // a patch with its (0, 0) at corner 3: u away from the pole, v around it
        let p = d.rotated(3).patch_map();
        assert_eq!(p.apply([0.0, 0.0]), [0.0, 0.75]);
        assert_eq!(p.apply([1.0, 0.0]), [0.0, 0.5]);
        assert_eq!(p.apply([0.0, 1.0]), [0.5, 0.75]);
        // mixed with dyadic levels it is refused nowhere, but a triangle cell has no halves
        assert!(!Domain::face(0, 3).half_child(1).is_tracked());
    }
}
