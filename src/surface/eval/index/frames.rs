//! Nodes of the evaluation index split into framed cells ([`Domain::framed`]): the rectangles
//! of a face that adjustable TPS's cells start from after a separating whole-net step (knot
//! positions such as `(1 -/+ e) / 2`, not children of the face).
//!
//! The rectangles of one node tile its cell. A point is located on the grid of their sides
//! (sorted `u` and `v` cuts, binary search, ties to the larger coordinate as for the other
//! splits), whose every grid cell is assigned once, when the index is complete, to the
//! rectangle that holds its centre (or, where rounding leaves a sliver between two sides
//! that should coincide, the nearest one).

use super::{CellTree, ChildInverse, Node};
use crate::bezier::domain::{Affine, Frame};

/// The framed cells of one node.
#[derive(Debug, Clone, Default)]
pub(super) struct FrameSet {
    /// Per rectangle: its frame, the inverse of its map and its node.
    children: Vec<(Affine, ChildInverse, u32)>,
    /// The cuts in `u` and in `v` (sorted, distinct).
    xs: Vec<f64>,
    ys: Vec<f64>,
    /// The rectangle of each grid cell `i + (xs.len() - 1) j`.
    table: Vec<u32>,
}

/// How far `p` lies outside `[0, 1]^2` (0 inside).
fn outside(p: [f64; 2]) -> f64 {
    p.iter()
        .map(|&x| (-x).max(x - 1.0).max(0.0))
        .fold(0.0, f64::max)
}

impl FrameSet {
    /// The sorted grid of the rectangles' sides and the rectangle of each grid cell.
    pub fn build_grid(&mut self) {
        let mut xs = Vec::new();
        let mut ys = Vec::new();
        for (map, _, _) in &self.children {
            if let Some([lo, hi]) = Frame::of(*map).bounds() {
                xs.extend([lo[0], hi[0]]);
                ys.extend([lo[1], hi[1]]);
            }
        }
        for c in [&mut xs, &mut ys] {
            c.sort_by(f64::total_cmp);
            c.dedup();
        }
        let (nx, ny) = (xs.len().saturating_sub(1), ys.len().saturating_sub(1));
        let mut table = Vec::with_capacity(nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let c = [0.5 * (xs[i] + xs[i + 1]), 0.5 * (ys[j] + ys[j + 1])];
                let best = self
                    .children
                    .iter()
                    .enumerate()
                    .map(|(k, (_, inv, _))| (outside(inv.apply(c)), k))
                    .min_by(|a, b| a.0.total_cmp(&b.0));
                // a grid cell outside every rectangle (a gap the frames leave) stays empty
                table.push(match best {
                    Some((d, k)) if d <= 1e-9 => k as u32,
                    _ => u32::MAX,
                });
            }
        }
        (self.xs, self.ys, self.table) = (xs, ys, table);
    }

    /// The node of the rectangle holding face point `p` and the inverse of its map.
    #[inline]
    pub fn find(&self, p: [f64; 2]) -> Option<(u32, &ChildInverse)> {
        let (nx, ny) = (self.xs.len().checked_sub(1)?, self.ys.len().checked_sub(1)?);
        let cut = |c: &[f64], x: f64, n: usize| c.partition_point(|&y| y <= x).max(1).min(n) - 1;
        let (i, j) = (cut(&self.xs, p[0], nx), cut(&self.ys, p[1], ny));
        let k = *self.table.get(i + nx * j)?;
        let (_, inv, node) = self.children.get(k as usize)?;
        Some((*node, inv))
    }
}

impl CellTree {
    /// The node of the framed cell `map` in node `at` (split into framed cells when empty);
    /// `None` when `at` is covered or split another way (the first indexed wins).
    pub(super) fn framed_child(&mut self, at: usize, map: Affine) -> Option<u32> {
        let set = match self.nodes[at] {
            Node::Frames { set } => set as usize,
            Node::Empty => {
                self.frames.push(FrameSet::default());
                let set = self.frames.len() - 1;
                self.nodes[at] = Node::Frames { set: set as u32 };
                set
            }
            _ => return None,
        };
        if let Some(c) = self.frames[set].children.iter().find(|c| c.0 == map) {
            return Some(c.2);
        }
        let node = self.nodes.len() as u32;
        self.nodes.push(Node::Empty);
        self.frames[set]
            .children
            .push((map, ChildInverse::of(map), node));
        Some(node)
    }
}
