//! Framed cells: a rectangle of an input face with its own affine map, for cells that are not
//! reached from the face by dyadic, ternary or ratio splits.
//!
//! Adjustable TPS separates close extraordinary vertices by whole-net steps that cut every
//! piece `e : 1 - 2e : e` (knot insertion, `crate::schemes::bi2::ternary`). The input net's
//! knots are uniform, so a face's `[0, 1]^2` is its knot coordinates, and after such steps
//! the part of a vertex's piece inside an input face is an axis-parallel rectangle at knot
//! positions like `(1 -/+ e) / 2`: not a chain of children of the face. A framed [`Domain`]
//! starts from such a rectangle instead of the whole face: [`Domain::cell_map`] is the frame's
//! map composed with the levels below it (ratio splits of the rings, any other child), so the
//! rest of the machinery (pieces, rings, caps) applies unchanged. The evaluation index
//! (`crate::surface::eval::index`) splits a face whose cells are framed into the rectangles
//! of their frames (found on the grid of their sides) and descends each as a cell.
//!
//! A frame is stored as the bits of its six `f64`s (so that a [`Domain`] stays `Eq` and
//! `Hash`); all zero bits (a degenerate map) means "no frame", the face itself.

use super::{Affine, Domain, Shape};

/// The affine map from a framed cell's coordinates (`[0, 1]^2`) to its face's, or none
/// ([`Frame::NONE`]: the cell chain starts at the face).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Frame([u64; 6]);

impl Frame {
    /// No frame: the cell chain starts at the face (or sub-face) itself.
    pub const NONE: Frame = Frame([0; 6]);

    /// The frame of `map` (cell coordinates to face coordinates).
    pub fn of(map: Affine) -> Frame {
        let [o, [a, b], [c, d]] = [map.origin, map.e[0], map.e[1]];
        Frame([o[0], o[1], a, b, c, d].map(f64::to_bits))
    }

    /// The map, `None` for [`Frame::NONE`].
    pub fn map(&self) -> Option<Affine> {
        if *self == Frame::NONE {
            return None;
        }
        let x = self.0.map(f64::from_bits);
        Some(Affine {
            origin: [x[0], x[1]],
            e: [[x[2], x[3]], [x[4], x[5]]],
        })
    }

    /// The rectangle the frame covers in face coordinates, `[[u_lo, v_lo], [u_hi, v_hi]]`
    /// (the bounding box of the image of `[0, 1]^2`; the image itself for the axis-parallel
    /// frames fairsub makes).
    pub fn bounds(&self) -> Option<[[f64; 2]; 2]> {
        let m = self.map()?;
        let pts = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]].map(|p| m.apply(p));
        let mut lo = pts[0];
        let mut hi = pts[0];
        for p in &pts[1..] {
            for a in 0..2 {
                lo[a] = lo[a].min(p[a]);
                hi[a] = hi[a].max(p[a]);
            }
        }
        Some([lo, hi])
    }
}

impl Domain {
    /// The cell of quad face `face` that `map` (an orientation-preserving or reversing affine
    /// map, invertible) takes `[0, 1]^2` onto, as a cell of depth 0 with the patch's `(0, 0)`
    /// at its corner 0 (see the module documentation). A degenerate map gives an
    /// untracked domain.
    pub fn framed(face: u32, map: Affine) -> Domain {
        let det = map.e[0][0] * map.e[1][1] - map.e[1][0] * map.e[0][1];
        if !(det.is_finite() && det != 0.0 && map.origin.iter().all(|x| x.is_finite())) {
            return Domain::UNTRACKED;
        }
        Domain {
            face,
            frame: Frame::of(map),
            ..Domain::polygon(face, 4)
        }
    }

    /// The frame's map, `None` when the cell chain starts at the face itself.
    pub fn frame_map(&self) -> Option<Affine> {
        self.frame.map()
    }

    /// The map from the cell's coordinates to the frame's origin cell: the face's
    /// (sub-face's) coordinates without a frame.
    pub(super) fn frame_or_identity(&self) -> Affine {
        match self.shape {
            Shape::Quad => self.frame.map().unwrap_or(Affine::IDENTITY),
            Shape::Triangle => Affine::IDENTITY,
        }
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn framed_cells_compose_with_ratio_children() {
        // [0.3, 0.45] x [0.2, 0.3] of face 5, (0, 0) at its corner (0.45, 0.2), u toward +v,
        // v toward -u (a quarter at corner 1 of a refined face, say)
        let map = Affine {
            origin: [0.45, 0.2],
            e: [[0.0, 0.1], [-0.15, 0.0]],
        };
        let d = Domain::framed(5, map);
        assert!(d.is_tracked());
        assert_eq!(d.frame_map(), Some(map));
        let b = d.frame.bounds().unwrap();
        assert!((b[0][0] - 0.3).abs() < 1e-15 && (b[1][0] - 0.45).abs() < 1e-15);
        assert!((b[0][1] - 0.2).abs() < 1e-15 && (b[1][1] - 0.3).abs() < 1e-15);
        let c = d.ratio_child(0.6, 2).rotated(1);
        let want = map
            .compose(&Shape::ratio_map(0.6, 2))
            .compose(&Shape::Quad.corner_map(1));
        assert_eq!(c.patch_map(), want);
        assert_eq!(c.frame, d.frame);
        assert!(
            !Domain::framed(
                1,
                Affine {
                    e: [[0.0; 2]; 2],
                    ..map
                }
            )
            .is_tracked()
        );
        assert_eq!(Domain::face(3, 4).frame_map(), None);
    }
}
