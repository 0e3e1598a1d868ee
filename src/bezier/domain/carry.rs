//! Domains carried through whole-net steps taken before a scheme's construction (the
//! preparation of `crate::schemes::prepare`): a patch's domain in a face of the prepared net
//! becomes a domain in the input face that face lies in.
//!
//! A prepared face (or the quarter of one at a corner, after a dual step) lies in one input
//! face (or sub-face of an n-gon) as the image of its `[0, 1]^2` under an affine map. The
//! domain below it keeps its chain of children (dyadic, in thirds, at a ratio, halves) and
//! starts from that image as its frame ([`Domain::framed`]): [`Domain::framed_in`]. A dual
//! step's prepared faces straddle several input faces, so only their quarters have a cell:
//! [`Domain::peel`] splits a domain into the quarter it lies in and the domain below it.

use super::{Affine, Domain, Frame, MAX_DEPTH, Shape};

impl Domain {
    /// This domain (of a face, or of a quarter of a face, of a prepared net; `[0, 1]^2` its
    /// coordinates) moved into sub-face `sub` of input face `face` (`0` for a quad), where
    /// `map` takes `[0, 1]^2` onto the region the prepared face covers: the same chain below
    /// the frame `map` composed with this domain's own frame. Untracked for untracked or
    /// triangle-shaped domains (the preparation steps make quad faces) and degenerate maps.
    pub fn framed_in(self, face: u32, sub: u32, map: Affine) -> Domain {
        if !self.is_tracked() || self.shape != Shape::Quad || self.sub == Domain::WHOLE {
            return Domain::UNTRACKED;
        }
        let framed = Domain::framed(face, map.compose(&self.frame_or_identity()));
        if !framed.is_tracked() {
            return Domain::UNTRACKED;
        }
        Domain {
            face,
            sub,
            frame: framed.frame,
            ..self
        }
    }

    /// The quarter of its face this domain lies in and the domain below it, as a domain of
    /// that quarter: for a face of `sides != 4` corners its sub-face (the quarter at that
    /// corner) and the same chain; for a quad its first level, which must be dyadic (child `k`,
    /// the quarter at corner `k`), and the chain below it. `None` for untracked domains, the
    /// n-gon itself, a quad's whole face, a first level in thirds, at a ratio or in halves, and
    /// framed domains (whose frame is not a quarter's).
    pub fn peel(self, sides: usize) -> Option<(u32, Domain)> {
        if !self.is_tracked()
            || self.sub == Domain::WHOLE
            || self.shape != Shape::Quad
            || self.frame != Frame::NONE
        {
            return None;
        }
        if sides != 4 {
            return Some((self.sub, Domain { sub: 0, ..self }));
        }
        if self.depth == 0
            || self.depth > MAX_DEPTH
            || self.splits_in_thirds(1)
            || self.splits_at_ratio(1)
            || self.splits_in_halves(1)
        {
            return None;
        }
        let k = self.step(1);
        let rest = Domain {
            depth: self.depth - 1,
            path: self.path / 4,
            thirds: self.thirds >> 1,
            split_at: self.split_at >> 1,
            halves: self.halves >> 1,
            ratio: if self.split_at >> 1 == 0 {
                0
            } else {
                self.ratio
            },
            ..self
        };
        Some((u32::from(k), rest))
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    fn close(a: [f64; 2], b: [f64; 2]) -> bool {
        (a[0] - b[0]).abs() < 1e-15 && (a[1] - b[1]).abs() < 1e-15
    }

    #[crate::unit::test]
    fn framed_in_composes_the_cell_map() {
        // a ring cell in thirds of a prepared quad, carried into the quarter at corner 2 of
        // input face 5 with its (0, 0) at the quarter's corner 1
        let d = Domain::polygon(0, 4)
            .child(1)
            .third_child(4)
            .child(3)
            .rotated(2);
        let quarter = Shape::Quad.child_map(2).compose(&Shape::Quad.corner_map(1));
        let c = d.framed_in(5, 0, quarter);
        assert_eq!((c.face, c.sub, c.depth, c.rot), (5, 0, d.depth, 2));
        for p in [[0.0, 0.0], [1.0, 0.0], [0.3, 0.7]] {
            let want = quarter.apply(d.patch_map().apply(p));
            assert!(close(c.patch_map().apply(p), want), "{p:?}");
        }
        assert!(!Domain::UNTRACKED.framed_in(1, 0, quarter).is_tracked());
    }

    #[crate::unit::test]
    fn peel_splits_off_the_quarter() {
        let d = Domain::polygon(3, 4)
            .child(2)
            .third_child(7)
            .child(1)
            .rotated(3);
        let (k, rest) = d.peel(4).expect("a quarter");
        assert_eq!(k, 2);
        assert_eq!(rest.depth, 2);
        // the quarter's map then the rest's is the whole domain's map
        for p in [[0.0, 0.0], [1.0, 0.5], [0.25, 0.75]] {
            let whole = d.patch_map().apply(p);
            let parts = Shape::Quad.child_map(2).apply(rest.patch_map().apply(p));
            assert!(close(whole, parts), "{p:?}");
        }
        // an n-gon's sub-face is its quarter
        let n = Domain::polygon(4, 5).child(3).child(0);
        let (k, rest) = n.peel(5).expect("a sub-face");
        assert_eq!((k, rest.sub, rest.depth), (3, 0, 1));
        assert!(Domain::polygon(4, 4).peel(4).is_none());
        assert!(Domain::polygon(4, 4).third_child(1).peel(4).is_none());
    }
}
