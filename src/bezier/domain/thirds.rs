//! Cells split in thirds: the 3 x 3 grid children of a quad cell, for the ternary schemes
//! (TPS) and for any piece of a cell cut in thirds (a dyadic cell's 3 x 3 sub-squares are its
//! children in thirds).
//!
//! A [`Domain`] is a chain of children from the face down; each level is either dyadic (the
//! rotated corner quarters of [`Shape::child_map`], radix 4) or in thirds (radix 9), and the
//! levels in thirds are marked in [`Domain::thirds`]. The chain is stored as one mixed-radix
//! number ([`Domain::path`]: level `l`'s index times the product of the radices of the levels
//! above it), so a dyadic-only path is exactly the two-bits-per-level number it always was,
//! and a cell is still one key `(face, sub, depth, path)` of the evaluation index. Any
//! sequence is expressible: thirds of a dyadic cell (`d.third_child(k)`), quarters of a third
//! (`d.third_child(k).child(c)`), and so on, as long as the product of the radices fits in a
//! `u128` (64 dyadic levels, or one dyadic and 39 levels in thirds; a deeper cell becomes
//! untracked, like a dyadic one past [`MAX_DEPTH`]).
//!
//! Child `k = i + 3 j` (`i, j` in `0..3`) of a quad cell in thirds is the square
//! `[i / 3, (i + 1) / 3] x [j / 3, (j + 1) / 3]` of the cell, not turned: its `u` and `v` run
//! along the cell's. The maps have the coefficients `1/3` and `i/3`, which are not exact in
//! floating point; a point is mapped with an error of a few units in the last place per level.

use super::{Affine, Domain, MAX_DEPTH, Shape};

impl Shape {
    /// The map from child `k = i + 3 j` (in thirds) of a quad cell to the cell:
    /// `p -> ((i, j) + p) / 3`.
    pub fn third_map(k: u8) -> Affine {
        let (i, j) = (f64::from(k % 3), f64::from(k / 3));
        Affine::new([i / 3.0, j / 3.0], [1.0 / 3.0, 0.0], [0.0, 1.0 / 3.0])
    }

    /// The child in thirds of a quad cell that holds the cell point `p` (ties go to the child
    /// at the larger coordinate).
    pub fn third_at(p: [f64; 2]) -> u8 {
        let third = |x: f64| -> u8 {
            if x >= 2.0 / 3.0 {
                2
            } else if x >= 1.0 / 3.0 {
                1
            } else {
                0
            }
        };
        third(p[0]) + 3 * third(p[1])
    }
}

impl Domain {
    /// Whether level `l` (1-based) of this cell's chain splits its parent in thirds.
    pub fn splits_in_thirds(&self, l: u8) -> bool {
        (1..=64).contains(&l) && (self.thirds >> (l - 1)) & 1 == 1
    }

    /// The radix of level `l`: 9 in thirds, else 4.
    pub(super) fn radix(&self, l: u8) -> u128 {
        if self.splits_in_thirds(l) { 9 } else { 4 }
    }

    /// The place value of level `l + 1`'s index in [`Domain::path`]: the product of the
    /// radices of levels `1..=l` (`None` past `u128`).
    pub fn place(&self, l: u8) -> Option<u128> {
        if self.thirds == 0 {
            return 1u128.checked_shl(2 * u32::from(l));
        }
        (1..=l).try_fold(1u128, |w, m| w.checked_mul(self.radix(m)))
    }

    /// `(depth, path)` of this cell's ancestor at `depth` (`depth <= self.depth`): the key of
    /// the cell whose children make this cell's level `depth + 1`.
    pub fn ancestor_key(&self, depth: u8) -> (u8, u128) {
        let place = self.place(depth).unwrap_or(u128::MAX);
        (depth, self.path % place)
    }

    /// Child `k` (`0..4`) one dyadic level down of a quad cell, marked by `mark` (which records
    /// the level's kind, e.g. halves or a split ratio); untracked for the n-gon itself, triangle
    /// cells, untracked domains, when `allowed` is false, or when the path does not fit. The
    /// one step of the cell kinds that refine a quad cell 2 x 2 in their own way.
    pub(super) fn quad_child(
        self,
        k: u8,
        allowed: bool,
        mark: impl FnOnce(Domain) -> Domain,
    ) -> Domain {
        if !allowed || !self.is_tracked() || self.sub == Domain::WHOLE || self.shape != Shape::Quad
        {
            return Domain {
                depth: MAX_DEPTH + 1,
                ..self
            };
        }
        let d = self.descend(u128::from(k & 3), false);
        if !d.is_tracked() {
            return d;
        }
        mark(d)
    }

    /// The child with index `k` one level down, in thirds or dyadic; untracked when the
    /// path does not fit ([`MAX_DEPTH`] levels, or the radices' product past `u128`).
    pub(super) fn descend(self, k: u128, thirds: bool) -> Domain {
        let next = if self.depth >= MAX_DEPTH {
            None
        } else {
            self.place(self.depth)
                .and_then(|w| k.checked_mul(w))
                .and_then(|x| self.path.checked_add(x))
        };
        match next {
            Some(path) => Domain {
                depth: self.depth + 1,
                path,
                thirds: self.thirds | (u64::from(thirds) << self.depth),
                rot: 0,
                ..self
            },
            None => Domain {
                depth: MAX_DEPTH + 1,
                ..self
            },
        }
    }

    /// Child `k = i + 3 j` (in thirds) of this quad cell ([`Shape::third_map`]), with the
    /// patch's `(0, 0)` at corner 0. The n-gon itself ([`Domain::WHOLE`]), triangle cells and
    /// untracked domains give an untracked domain.
    pub fn third_child(self, k: u8) -> Domain {
        if !self.is_tracked() || self.sub == Domain::WHOLE || self.shape != Shape::Quad {
            return Domain {
                depth: MAX_DEPTH + 1,
                ..self
            };
        }
        self.descend(u128::from(k % 9), true)
    }

    /// The square `[i, i + 1] x [j, j + 1] / 3` of this patch frame (the cell's coordinates
    /// rotated so that `(0, 0)` sits at corner `rot`, as [`Domain::patch_map`] maps them) as
    /// the cell one level down in thirds, with the patch's `(0, 0)` at the square's corner
    /// nearest the frame's origin and its axes along the frame's (`rot` kept: the children in
    /// thirds are not turned).
    pub fn third(self, i: u8, j: u8) -> Domain {
        let (i, j) = (i.min(2), j.min(2));
        let (ci, cj) = match self.rot & 3 {
            0 => (i, j),
            1 => (2 - j, i),
            2 => (2 - i, 2 - j),
            _ => (j, 2 - i),
        };
        self.third_child(ci + 3 * cj).rotated(u32::from(self.rot))
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn thirds_tile_the_cell_and_keep_dyadic_paths() {
        for k in 0..9u8 {
            let m = Shape::third_map(k);
            let c = m.apply([0.5, 0.5]);
            assert_eq!(Shape::third_at(c), k);
            let back = m.invert(c);
            assert!((back[0] - 0.5).abs() < 1e-15 && (back[1] - 0.5).abs() < 1e-15);
        }
        // a dyadic chain keeps its two-bits-per-level path
        let d = Domain::face(1, 4).child(2).child(3).child(1);
        assert_eq!(d.path, 2 | (3 << 2) | (1 << 4));
        assert_eq!(d.thirds, 0);
        // quarter 1, then thirds 5 and 7, then quarter 2: radices 4, 9, 9, 4
        let t = Domain::face(1, 4)
            .child(1)
            .third_child(5)
            .third_child(7)
            .child(2);
        assert_eq!(t.path, 1 + 4 * 5 + 36 * 7 + 324 * 2);
        assert_eq!((t.step(1), t.step(2), t.step(3), t.step(4)), (1, 5, 7, 2));
        assert_eq!(t.ancestor_key(2), (2, 1 + 4 * 5));
        let expect = Shape::Quad
            .child_map(1)
            .compose(&Shape::third_map(5))
            .compose(&Shape::third_map(7))
            .compose(&Shape::Quad.child_map(2));
        assert_eq!(t.cell_map(), expect);
        // one dyadic level and 39 in thirds fit; the 40th does not
        let mut deep = Domain::face(0, 4).child(0);
        for _ in 0..39 {
            deep = deep.third_child(8);
        }
        assert!(deep.is_tracked());
        assert!(!deep.third_child(8).is_tracked());
    }

    #[crate::unit::test]
    fn thirds_of_a_turned_frame_are_the_frame_scaled() {
        for rot in 0..4u32 {
            let base = Domain::face(2, 4).child(3).rotated(rot);
            let frame = base.patch_map();
            for i in 0..3u8 {
                for j in 0..3u8 {
                    let d = base.third(i, j);
                    for p in [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.25, 0.625]] {
                        let want =
                            frame.apply([(f64::from(i) + p[0]) / 3.0, (f64::from(j) + p[1]) / 3.0]);
                        let got = d.patch_map().apply(p);
                        let err = (got[0] - want[0]).abs().max((got[1] - want[1]).abs());
                        assert!(err < 1e-15, "rot {rot} ({i}, {j}): {got:?} {want:?}");
                    }
                }
            }
        }
    }
}
