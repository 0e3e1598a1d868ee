//! The surface cut into charts for closest-point queries ([`crate::surface::closest`]): one
//! chart per cell of the evaluation index (a leaf of `index`'s tree), in the *local*
//! coordinates of its face, where a chart's points are evaluated without a search.
//!
//! Local coordinates: a quad's `(u, v)` in `[0, 1]^2`; a Loop triangle's barycentric `(u, v)`;
//! a pole's fan triangle's `[0, 1]^2`; an n-gon's (and a dual scheme's triangle's) sub-face
//! square, whose face parameters are `(sub + x, y)` ([`Surface::face_params`] handles the
//! side `x = 1`, which the strip gives to the next sub-face); with fan-triangle input faces
//! (`nonbox-4dir`), the input triangle's barycentric `(u, v)`, one chart per input face.

use super::Surface;
use crate::bezier::domain::{Affine, Shape};
use crate::error::{Error, Result};
use crate::geom::Point;

/// The domain of a chart's local coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Local {
    /// `[0, 1]^2`.
    Square,
    /// `u, v >= 0`, `u + v <= 1`.
    Triangle,
}

/// One chart: a cell of face `face` (root cell `sub`), in local coordinates.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Chart {
    pub face: u32,
    pub sub: u32,
    /// The domain the local coordinates range over (where a search may move).
    pub local: Local,
    /// The cell: its own coordinates (`[0, 1]^2`, or barycentric for `Triangle`) to local.
    pub cell: Affine,
    pub shape: Shape,
    /// A box holding the surface over the cell (its patches' control points).
    pub bbox: (Point, Point),
}

fn union(a: (Point, Point), b: (Point, Point)) -> (Point, Point) {
    (
        std::array::from_fn(|k| a.0[k].min(b.0[k])),
        std::array::from_fn(|k| a.1[k].max(b.1[k])),
    )
}

impl Surface {
    /// Whether face `face`'s local coordinates are a sub-face square of its strip.
    fn has_strip(&self, face: u32) -> bool {
        let f = face as usize;
        self.fans.is_empty()
            && match self.sides[f] {
                4 => false,
                3 => self.tri_strips[f] && !self.pole_triangles[f],
                _ => true,
            }
    }

    /// The local domain of face `face` (see the module documentation).
    fn local_domain(&self, face: u32) -> Local {
        let f = face as usize;
        let triangle = !self.fans.is_empty()
            || (self.sides[f] == 3 && !self.has_strip(face) && !self.pole_triangles[f]);
        if triangle {
            Local::Triangle
        } else {
            Local::Square
        }
    }

    /// The charts of the surface (see the module documentation).
    pub(crate) fn charts(&self) -> Vec<Chart> {
        let c = &self.complex;
        let bbox = |i: usize| c.patches[i].control_bbox();
        if !self.fans.is_empty() {
            // one chart per input face, boxed by every patch of its host face
            let mut host_box: Vec<Option<(Point, Point)>> = vec![None; self.sides.len()];
            let domains = (0..c.len())
                .filter_map(|i| c.domain(i).map(|d| (i, d.face)))
                .chain(c.pieces.iter().map(|p| (p.patch as usize, p.domain.face)));
            for (i, f) in domains {
                if let Some(slot) = host_box.get_mut(f as usize) {
                    *slot = Some(slot.map_or(bbox(i), |b| union(b, bbox(i))));
                }
            }
            return self
                .fans
                .iter()
                .enumerate()
                .filter_map(|(f, t)| {
                    Some(Chart {
                        face: f as u32,
                        sub: 0,
                        local: Local::Triangle,
                        cell: Affine::IDENTITY,
                        shape: Shape::Triangle,
                        bbox: host_box.get(t.host as usize).copied().flatten()?,
                    })
                })
                .collect();
        }
        self.cells
            .reachable_leaves(c)
            .filter(|(_, d)| (d.face as usize) < self.sides.len())
            .map(|(leaf, d)| {
                let i = leaf.patch as usize;
                let mut b = bbox(i);
                if leaf.criss_cross.is_some() {
                    for k in 1..4 {
                        if i + k < c.len() {
                            b = union(b, bbox(i + k));
                        }
                    }
                }
                if let Some(&k) = self.kites.get(&i) {
                    b = union(b, bbox(k));
                }
                Chart {
                    face: d.face,
                    sub: if self.has_strip(d.face) { d.sub } else { 0 },
                    local: self.local_domain(d.face),
                    cell: d.cell_map(),
                    shape: d.shape,
                    bbox: b,
                }
            })
            .collect()
    }

    /// The face parameters `(u, v)` [`Surface::evaluate`] takes for local point `p` of root
    /// cell `sub` of `face`: `(sub + x, y)` on a strip, where the side `x = 1` of sub-face `i`
    /// (which the strip's `floor` gives to sub-face `i + 1`) is written as the same points'
    /// `(y, 1)` of sub-face `i + 1`, and the centre as `(n, 1)`.
    pub(crate) fn face_params(&self, face: u32, sub: u32, p: [f64; 2]) -> [f64; 2] {
        if !self.has_strip(face) {
            return p;
        }
        let n = self.sides[face as usize];
        let [x, y] = p;
        if x < 1.0 || sub + 1 == n {
            return [f64::from(sub) + x, y];
        }
        if y >= 1.0 {
            return [f64::from(n), 1.0];
        }
        [f64::from((sub + 1) % n) + y, 1.0]
    }

    /// The surface at local point `p` of root cell `sub` of `face`, with its derivatives by
    /// the local coordinates: [`Surface::evaluate`] without the normal and the curvature
    /// (what the closest-point search's samples and Newton steps need).
    ///
    /// # Errors
    /// Those of [`Surface::evaluate`] (a point no patch covers).
    pub(crate) fn derivatives_local(
        &self,
        face: u32,
        sub: u32,
        p: [f64; 2],
    ) -> Result<crate::bezier::Derivatives> {
        let (at, cell, fan) = if self.has_strip(face) {
            let q = [p[0].clamp(0.0, 1.0), p[1].clamp(0.0, 1.0)];
            let (at, cell) = self
                .cells
                .locate(face, sub, Shape::Quad, q)
                .ok_or_else(|| {
                    Error::InvalidArgument(format!(
                        "no patch of the surface covers sub-face {sub} of face {face} at {q:?}"
                    ))
                })?;
            (at, cell, None)
        } else {
            self.locate(face, p[0], p[1])?
        };
        let (df, ..) = self.leaf_derivatives(at, cell, false)?;
        Ok(match fan {
            Some(jac) => super::chain(&df, jac),
            None => df,
        })
    }
}
