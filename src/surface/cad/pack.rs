//! Packed faces: the `input` faces of regular regions merged into rectangles of the quad
//! layout, each one B-spline (`--faces packed`).
//!
//! A region is *regular* here when its input faces are each one polynomial piece (a merged
//! `input` face without interior knots: Catmull-Clark's bi-3 patches away from extraordinary
//! vertices and creases, the regular patches of the other schemes). The faces next to an
//! extraordinary vertex carry its rings as knot lines, so a rectangle holding one would put
//! those lines across all of it; they stay faces of their own, and their sides are the
//! separatrices the rectangles stop at.
//!
//! The quad layout is found from the geometry, as the B-rep's topology is: the faces' corners
//! are welded into vertices, two faces are neighbours across a side when they share its two
//! end vertices, and a neighbour's orientation (one of the four rotations of its parameter
//! square; reflections would turn its normal) is the one that puts its corners where the
//! rectangle's grid expects them. Rectangles grow greedily, as a row along `+u` from a seed
//! and then row by row along `+v` while the whole next row is free, regular and consistently
//! joined (so every vertex inside a rectangle has four faces around it). This is a greedy
//! cover of the regular region, not the motorcycle graph's tracing of separatrices: it never
//! crosses a separatrix, but may cut a regular region into more rectangles than the graph
//! would.
//!
//! A rectangle of `W x H` faces becomes one B-spline on `[0, 1]^2` by the same exact merge as an
//! input face (`merge`): its faces are pieces over the cells `[i/W, (i+1)/W] x [j/H, (j+1)/H]`,
//! knot multiplicities follow the continuity measured across each line (C^2 between
//! Catmull-Clark's regular faces: simple knots), and the result is checked against every face.
//! A rectangle that fails the check is written as its faces.

use super::merge::{FacePiece, merge_face};
use super::spline::SplineSurface;
use crate::bezier::BezierPatch;
use crate::surface::adjacency::weld_points;
use std::collections::HashMap;

/// How a face sits in a rectangle: its parameter square transposed (`swap`), then reversed in
/// `u` and in `v`; only the four rotations (an even number of flips) occur.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Orient {
    swap: bool,
    ru: bool,
    rv: bool,
}

/// The rotations of the parameter square.
const ROTATIONS: [Orient; 4] = [
    Orient {
        swap: false,
        ru: false,
        rv: false,
    },
    Orient {
        swap: true,
        ru: true,
        rv: false,
    },
    Orient {
        swap: false,
        ru: true,
        rv: true,
    },
    Orient {
        swap: true,
        ru: false,
        rv: true,
    },
];

impl Orient {
    /// The face's own corner (index `u + 2 v` into its corner list `(0,0), (1,0), (0,1),
    /// (1,1)`) at the rectangle's local corner `(x, y)`.
    fn corner(self, x: usize, y: usize) -> usize {
        let a = if self.ru { 1 - x } else { x };
        let b = if self.rv { 1 - y } else { y };
        let (u, v) = if self.swap { (b, a) } else { (a, b) };
        u + 2 * v
    }

    /// The Bezier patch as the rectangle sees it.
    fn apply(self, p: &BezierPatch) -> BezierPatch {
        let mut q = if self.swap { p.transposed() } else { p.clone() };
        if self.ru {
            q = q.reversed_u();
        }
        if self.rv {
            q = q.reversed_v();
        }
        q
    }
}

/// A face placed in a rectangle.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Placed {
    face: usize,
    orient: Orient,
}

/// The quad layout of the regular faces.
struct Layout<'a> {
    /// Corner vertices of every face, `(0,0), (1,0), (0,1), (1,1)`.
    corners: Vec<[u32; 4]>,
    /// Faces by side (unordered pair of end vertices).
    by_side: HashMap<[u32; 2], Vec<usize>>,
    regular: &'a [bool],
}

impl Layout<'_> {
    /// The rectangle's corners `(x, y)` of a placed face.
    fn at(&self, p: Placed, x: usize, y: usize) -> u32 {
        self.corners[p.face][p.orient.corner(x, y)]
    }

    /// The free regular face beyond `p`'s side in direction `dir` (0: `+u`, 1: `+v`), placed
    /// so that it continues the grid; `None` when there is none or the side is not manifold.
    fn next(&self, p: Placed, dir: usize, used: &[bool]) -> Option<Placed> {
        // the side's ends in p's frame, and where they must be in the neighbour's
        let (a, b) = if dir == 0 {
            (self.at(p, 1, 0), self.at(p, 1, 1))
        } else {
            (self.at(p, 0, 1), self.at(p, 1, 1))
        };
        let faces = self.by_side.get(&[a.min(b), a.max(b)])?;
        if faces.len() != 2 {
            return None;
        }
        let g = *faces.iter().find(|&&g| g != p.face)?;
        if !self.regular[g] || used[g] {
            return None;
        }
        ROTATIONS.iter().find_map(|&orient| {
            let q = Placed { face: g, orient };
            let ok = if dir == 0 {
                self.at(q, 0, 0) == a && self.at(q, 0, 1) == b
            } else {
                self.at(q, 0, 0) == a && self.at(q, 1, 0) == b
            };
            ok.then_some(q)
        })
    }
}

/// The rectangles of the regular faces: rows of placed faces, every face in one rectangle
/// (a single face is a `1 x 1` rectangle). `surfaces[f]` is regular when `regular[f]`; the
/// others are not placed.
fn rectangles(surfaces: &[SplineSurface], regular: &[bool], tol: f64) -> Vec<Vec<Vec<Placed>>> {
    let corner_points: Vec<_> = surfaces
        .iter()
        .flat_map(|s| {
            let [[u0, u1], [v0, v1]] = s.range();
            [
                s.eval(u0, v0),
                s.eval(u1, v0),
                s.eval(u0, v1),
                s.eval(u1, v1),
            ]
        })
        .collect();
    let (vid, _) = weld_points(&corner_points, tol);
    let corners: Vec<[u32; 4]> = vid
        .chunks_exact(4)
        .map(|c| [c[0], c[1], c[2], c[3]])
        .collect();
    let mut by_side: HashMap<[u32; 2], Vec<usize>> = HashMap::new();
    let mut ok = regular.to_vec();
    for (f, c) in corners.iter().enumerate() {
        let mut distinct = c.to_vec();
        distinct.sort_unstable();
        distinct.dedup();
        if distinct.len() != 4 {
            ok[f] = false; // a collapsed side: no quad of the layout
            continue;
        }
        if !ok[f] {
            continue;
        }
        for (i, j) in [(0, 1), (1, 3), (3, 2), (2, 0)] {
            let (a, b) = (c[i], c[j]);
            by_side.entry([a.min(b), a.max(b)]).or_default().push(f);
        }
    }
    let layout = Layout {
        corners,
        by_side,
        regular: &ok,
    };
    let mut used = vec![false; surfaces.len()];
    let mut out = Vec::new();
    for seed in 0..surfaces.len() {
        if !ok[seed] || used[seed] {
            continue;
        }
        let first = Placed {
            face: seed,
            orient: ROTATIONS[0],
        };
        used[seed] = true;
        let mut row = vec![first];
        while let Some(n) = layout.next(*row.last().expect("non-empty"), 0, &used) {
            used[n.face] = true;
            row.push(n);
        }
        let mut rows = vec![row];
        loop {
            let last = rows.last().expect("non-empty");
            let mut taken: Vec<Placed> = Vec::with_capacity(last.len());
            for p in last {
                match layout.next(*p, 1, &used) {
                    Some(n) if !taken.iter().any(|t| t.face == n.face) => taken.push(n),
                    _ => break,
                }
            }
            // the new row is one row of the grid: full, and each face the `+u` neighbour of
            // the one before it
            let joined = taken.len() == last.len()
                && taken.windows(2).all(|w| {
                    let a = w[0];
                    let (x, y) = (layout.at(a, 1, 0), layout.at(a, 1, 1));
                    layout.at(w[1], 0, 0) == x && layout.at(w[1], 0, 1) == y
                });
            if !joined {
                break;
            }
            for t in &taken {
                used[t.face] = true;
            }
            rows.push(taken);
        }
        out.push(rows);
    }
    out
}

/// What [`pack`] made of one rectangle.
pub(crate) struct Packed {
    /// The faces of `surfaces` it holds (first the seed).
    pub faces: Vec<usize>,
    /// Its size in faces, `[W, H]`.
    pub size: [usize; 2],
    /// The merged surface, or `None` for a single face or a merge that failed (its faces are
    /// then written as they are).
    pub surface: Option<SplineSurface>,
    /// Largest deviation of the merged surface from its faces.
    pub deviation: f64,
}

/// Whether `s` is one polynomial piece (no interior knots).
pub(crate) fn is_single_span(s: &SplineSurface) -> bool {
    (0..2).all(|k| s.knots[k].len() == 2 * (s.deg[k] + 1))
}

/// Packs the faces `surfaces` whose `regular` flag is set into rectangles (see the
/// [module](self) doc); `tol` is the welding tolerance of the corners, `merge_tol` and `limit`
/// those of [`merge_face`].
pub(crate) fn pack(
    surfaces: &[SplineSurface],
    regular: &[bool],
    tol: f64,
    merge_tol: f64,
    limit: f64,
) -> Vec<Packed> {
    use rayon::prelude::*;
    let rects = rectangles(surfaces, regular, tol);
    rects
        .par_iter()
        .map(|rows| {
            let (w, h) = (rows[0].len(), rows.len());
            let faces: Vec<usize> = rows.iter().flatten().map(|p| p.face).collect();
            let mut packed = Packed {
                faces,
                size: [w, h],
                surface: None,
                deviation: 0.0,
            };
            if w * h == 1 {
                return packed;
            }
            let pieces: Vec<FacePiece> = rows
                .iter()
                .enumerate()
                .flat_map(|(j, row)| {
                    row.iter().enumerate().map(move |(i, p)| {
                        let (_, b) = surfaces[p.face]
                            .bezier_pieces()
                            .pop()
                            .expect("a face has a piece");
                        FacePiece {
                            patch: p.face,
                            window: [[0.0, 0.0], [1.0, 1.0]],
                            rect: [
                                [i as f64 / w as f64, (i + 1) as f64 / w as f64],
                                [j as f64 / h as f64, (j + 1) as f64 / h as f64],
                            ],
                            bezier: p.orient.apply(&b),
                        }
                    })
                })
                .collect();
            if let Some(m) = merge_face(&pieces, merge_tol, limit) {
                packed.surface = Some(m.surface);
                packed.deviation = m.deviation;
            }
            packed
        })
        .collect()
}
