//! Face domains of the TPS complex, for evaluation at `(face, u, v)`
//! ([`crate::surface::eval`]).
//!
//! # The parameter domain (primal ternary bi-2)
//!
//! TPS is primal, but its patches are centred at vertices like a dual scheme's: the bi-2 patch
//! of a regular vertex `v` spans half-way to its neighbours, so it covers the quarter of each of
//! its four faces at `v` (corners: `v`, the two edge midpoints, the face centre). Faces keep
//! the quad domain of [`crate::bezier::domain`] (`[0, 1]^2`), and the quarter of face `F` at
//! its corner `k` is `F`'s dyadic child `k`; the vertex's patch is recorded as four
//! [`Piece`]s, exactly as the dual schemes' patches of input vertices
//! ([`crate::schemes::doo_sabin::surface`]).
//!
//! A ternary step splits every vertex's piece in thirds, so the pieces of level `l` are the
//! squares of side `3^-l` around the level-`l` vertices. In the quarter of face `F` at an
//! extraordinary vertex (sector `s`: `F`'s corners `v`, `a_s`, `b_s`, `a_(s+1)` of the q-net,
//! the quarter's `u` along spoke `a_s`, its `v` along spoke `a_(s+1)`), the hole left after
//! ring `l` is the square `[0, 3^-l]^2`: the corner child in thirds of the hole before. Ring
//! `l`'s patches cover the other children in thirds of that square: the patch of `b_s`
//! (q-net `(1, 1)`) the four children `(1..=2) x (1..=2)`, each a quarter of its parameter
//! square; the patch of `a_s` (q-net `(1, 0)`, centred on the spoke) the children `(1, 0)`,
//! `(2, 0)` of sector `s` with its half `v >= 1/2`, and the children `(0, 1)`, `(0, 2)` of
//! sector `s - 1` with its half `v <= 1/2`, turned (its `u` runs along sector `s - 1`'s `v`).
//! The cap or fill of sector `s` covers the last hole `[0, 3^-K]^2` with `(0, 0)` at the
//! centre and `u` along spoke `s` (how [`super::g1`] and the fill lay it out).
//!
//! Extraordinary vertices too close for rings are separated by whole-net steps first; a face
//! of the refined net is then child `i + 3 j` in thirds of its parent face (the face children
//! of `ternary_step`, face `9 f + 3 i + j` at `(i, j) / 3` of face `f`), so its quarters and
//! the cells in them are cells of an input face all the same (adjustable TPS's refined faces
//! are rectangles at its knots instead, below). As for the dual schemes, the patch of a
//! regular boundary vertex covers its faces' quarters (the rest of it, over the doubled
//! boundary layer, lies over no face); the faces of the boundary layer a step adds are not
//! tracked.
//!
//! # Adjustable TPS: cells split at `s = 1 - 2e`
//!
//! Adjustable TPS splits every piece `e : 1 - 2e : e` (knot insertion,
//! [`crate::schemes::bi2::ternary`]). The input net's knots are uniform, so a face's `[0, 1]^2`
//! is its knot coordinates and a vertex's patch covers the quarters of its faces as above. In
//! the quarter at an extraordinary vertex (scaled to `[0, 1]^2`, knot coordinates), the centre
//! piece after `l` steps is `[-s^l, s^l]^2`, so the hole after ring `l` is `[0, s^l]^2` with
//! `s = 1 - 2e`, and ring `l` covers the rest of `[0, s^(l-1)]^2`: the hole of the step before
//! split 2 x 2 at the ratio `s` ([`Domain::ratio_child`]): `b_s` its child `[s, 1]^2` (the whole
//! patch, `(0, 0)` at the inner corner), `a_s` with its half `v >= 1/2` the child
//! `[s, 1] x [0, s]` of sector `s` and with its half `v <= 1/2` the child `[0, s] x [s, 1]` of
//! sector `s - 1`, turned as for TPS. The cap covers `[0, s^K]^2` from the centre. So the
//! face parameters are the spline's own knot coordinates: the pieces join C^1 in them as the
//! spline does. With `e = 1/3` the cells are TPS's thirds' sizes (`s = 1/3`), cut as 2 x 2
//! at `1/3`.
//!
//! A whole-net step (to separate extraordinary vertices) cuts every piece `e : 1 - 2e : e`,
//! so a face of the refined net is not a dyadic or ternary child of its input face: in knot
//! coordinates it is the rectangle between the centres of its four vertices' pieces (the
//! children of `ternary_step`'s 4 x 4 grid of the face: vertex child at 0, edge children at
//! `a (1 - e) / (a + b)` and `(a + e b) / (a + b)`, far vertex child at 1, `a`, `b` the
//! pieces' widths along the side; `(1 -/+ e) / 2` on the uniform input), and its corner
//! vertex's piece covers the part from the corner to the knot crossing, at `a / (a + b)` of
//! each side. [`FaceCells::Knots`] tracks each refined face as that rectangle of its input
//! face (an affine map, composed step by step) and gives each quarter its own framed cell
//! ([`Domain::framed`]: `(0, 0)` at the corner, `u` toward the next corner). A face line of
//! the input net runs through the middle of the middle piece of every vertex on it, so every
//! quarter lies in one input face. The sector quarters at the extraordinary vertices are
//! framed squares, and the rings split them at `s` as above; the boundary layer a step adds
//! stays untracked.

use crate::bezier::complex::{Domain, PatchComplex, Piece};
use crate::bezier::domain::Affine;
use crate::mesh::PolyMesh;
use crate::schemes::bi2::ternary::Widths;

/// The cells of the faces of the net after whole-net ternary steps: `parent` holds the cells
/// of the faces before the step (of `before`, with `before.num_faces()` entries), the result
/// those of the `9 F` face children of the step (then untracked boundary-layer faces up to
/// `after_faces`).
fn refined_face_cells(parent: &[Domain], after_faces: usize) -> Vec<Domain> {
    let mut out = Vec::with_capacity(after_faces);
    for &d in parent {
        for i in 0..3u8 {
            for j in 0..3u8 {
                out.push(d.third_child(i + 3 * j));
            }
        }
    }
    out.resize(after_faces, Domain::UNTRACKED);
    out
}

/// Where the faces of a TPS net (the input net, or the net after whole-net steps) lie in the
/// input faces, and so the cell of the quarter of each face at each of its corners (the part
/// of the corner vertex's piece in the face).
pub(super) enum FaceCells {
    /// Each face is a cell of an input face (the input net, and TPS's refined faces, which
    /// are thirds): the quarter at corner `k` is its child `k`.
    Cells(Vec<Domain>),
    /// Adjustable TPS after whole-net steps (see the [module](self) documentation): each face
    /// is the rectangle of input face `.0` that the map `.1` takes its `[0, 1]^2` onto (corner
    /// 0 at `(0, 0)`, `u` toward corner 1, `v` toward corner 3; knot coordinates), `None`
    /// for the boundary layer; `corners` the framed quarters, cut at the knot crossing.
    Knots {
        faces: Vec<Option<(u32, Affine)>>,
        corners: Vec<[Domain; 4]>,
    },
}

impl FaceCells {
    /// The cells of an input net's faces (quads; other faces untracked, TPS refuses them).
    pub fn input(mesh: &PolyMesh) -> FaceCells {
        FaceCells::Cells(
            (0..mesh.num_faces())
                .map(|f| match mesh.face_size(f) {
                    4 => Domain::polygon(f as u32, 4),
                    _ => Domain::UNTRACKED,
                })
                .collect(),
        )
    }

    /// The quarter of face `g` at its corner `k`, `(0, 0)` at the corner, `u` toward corner
    /// `k + 1` (untracked for faces out of range).
    pub fn corner(&self, g: usize, k: u32) -> Domain {
        match self {
            FaceCells::Cells(c) => c.get(g).map_or(Domain::UNTRACKED, |d| d.child(k)),
            FaceCells::Knots { corners, .. } => corners
                .get(g)
                .map_or(Domain::UNTRACKED, |c| c[(k & 3) as usize]),
        }
    }

    /// The cells after a whole-net step from `before` (knot widths `w`) to `after` (knot
    /// widths `w_after`): thirds of the faces for TPS, the rectangles at the knots for
    /// adjustable TPS (split ratio `e`).
    pub fn step(
        self,
        split: Split,
        before: &PolyMesh,
        w: &Widths,
        after: &PolyMesh,
        w_after: &Widths,
        e: f64,
    ) -> FaceCells {
        let nf = after.num_faces();
        let faces: Vec<Option<(u32, Affine)>> = match (self, split) {
            (FaceCells::Cells(c), Split::Thirds) => {
                return FaceCells::Cells(refined_face_cells(&c, nf));
            }
            (FaceCells::Cells(c), Split::At(_)) => c
                .iter()
                .enumerate()
                .map(|(f, d)| d.is_tracked().then_some((f as u32, Affine::IDENTITY)))
                .collect(),
            (FaceCells::Knots { faces, .. }, _) => faces,
        };
        let mut out = Vec::with_capacity(nf);
        for (f, rect) in faces.iter().enumerate().take(before.num_faces()) {
            let h0 = before.face_halfedge(f);
            let h3 = h0 + 3;
            // the child vertices' centres along the face, in its cell coordinates: the vertex
            // child at 0, the two edge children at the centres of the end pieces next to the
            // knot, the far vertex child at 1 (`ternary_step`'s 4 x 4 grid of the face)
            let cuts = |a: f64, b: f64| [0.0, a * (1.0 - e) / (a + b), (a + e * b) / (a + b), 1.0];
            let xs = cuts(w[h0 as usize][0], w[h0 as usize][1]);
            let ys = cuts(w[h3 as usize][1], w[h3 as usize][0]);
            for i in 0..3 {
                for j in 0..3 {
                    let child = Affine {
                        origin: [xs[i], ys[j]],
                        e: [[xs[i + 1] - xs[i], 0.0], [0.0, ys[j + 1] - ys[j]]],
                    };
                    out.push(rect.map(|(face, m)| (face, m.compose(&child))));
                }
            }
        }
        out.resize(nf, None);
        let corners = out
            .iter()
            .enumerate()
            .map(|(g, rect)| match rect {
                Some((face, m)) => knot_quarters(after, w_after, g, *face, m),
                None => [Domain::UNTRACKED; 4],
            })
            .collect();
        FaceCells::Knots {
            faces: out,
            corners,
        }
    }
}

/// The quarters of face `g` of a net with knot widths `w` (the face the rectangle `m` of
/// input face `face`): the part of each corner vertex's piece in the face, from the corner
/// to the knot crossing (at `a / (a + b)` of each side, `a` and `b` the pieces' widths along
/// it), framed with `(0, 0)` at the corner and `u` toward the next corner.
fn knot_quarters(mesh: &PolyMesh, w: &Widths, g: usize, face: u32, m: &Affine) -> [Domain; 4] {
    const QUAD: [[f64; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let h0 = mesh.face_halfedge(g) as usize;
    let h3 = h0 + 3;
    let x = [
        w[h0][0] / (w[h0][0] + w[h0][1]),
        w[h3][1] / (w[h3][1] + w[h3][0]),
    ];
    std::array::from_fn(|k| {
        let c = QUAD[k];
        let toward = |q: [f64; 2]| {
            // the side from corner k toward corner q, as far as the knot crossing
            let d = [q[0] - c[0], q[1] - c[1]];
            let t = (x[0] - c[0]) * d[0] + (x[1] - c[1]) * d[1];
            [d[0] * t, d[1] * t]
        };
        let quarter = Affine {
            origin: c,
            e: [toward(QUAD[(k + 1) % 4]), toward(QUAD[(k + 3) % 4])],
        };
        Domain::framed(face, m.compose(&quarter))
    })
}

/// The quarters of the four faces around interior vertex `v` that its regular patch (patch
/// `patch`, `u` along `v`'s first outgoing half-edge, `v` counter-clockwise) covers, as the
/// dual schemes record them.
pub(super) fn vertex_pieces(
    mesh: &PolyMesh,
    cells: &FaceCells,
    v: usize,
    patch: u32,
    out: &mut PatchComplex,
) {
    let cell = |g: usize, k: u32| cells.corner(g, k);
    crate::schemes::doo_sabin::surface::vertex_quarter_pieces(mesh, v, patch, &cell, out);
}

/// The quarter of each sector's face at extraordinary vertex `v` of valence `n` (sector `s`
/// the face `v, a_s, b_s, a_(s+1)` of its q-net, as [`crate::mesh::PolyMesh::cnet_indices`]
/// orders it), its `(0, 0)` at `v` and `u` along spoke `a_s`; all untracked when a face does
/// not run counter-clockwise through `v, a_s, b_s`.
pub(super) fn sector_cells(mesh: &PolyMesh, cells: &FaceCells, v: usize) -> Vec<Domain> {
    let Some(idx) = mesh.cnet_indices(v, 1) else {
        return Vec::new();
    };
    let n = (idx.len() - 1) / 2;
    let mut out = Vec::with_capacity(n);
    for s in 0..n {
        let (a, b) = (idx[1 + 2 * s], idx[2 + 2 * s]);
        let h = mesh
            .outgoing(v)
            .find(|&h| mesh.he_to(h) == a && mesh.he_to(mesh.he_next(h)) == b);
        match h {
            Some(h) => {
                let g = mesh.he_face(h) as usize;
                out.push(cells.corner(g, h - mesh.face_halfedge(g)));
            }
            None => return vec![Domain::UNTRACKED; n],
        }
    }
    out
}

/// How the rings of a TPS-like element split the hole before them: in thirds (TPS) or 2 x 2
/// at a ratio `s = 1 - 2e` (adjustable TPS; see the [module](self) documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Split {
    /// The 3 x 3 grid.
    Thirds,
    /// 2 x 2 at the ratio.
    At(f64),
}

/// The hole of sector cell `q` after `l` rings: its corner child `l` times.
fn hole(q: Domain, l: usize, split: Split) -> Domain {
    (0..l).fold(q, |d, _| match split {
        Split::Thirds => d.third_child(0),
        Split::At(t) => d.ratio_child(t, 0),
    })
}

/// Records where ring `l`'s patches of an element lie (see the [module](self) documentation):
/// patches `first + 2 s` (`a_s`) and `first + 2 s + 1` (`b_s`) for each sector `s` of
/// `sectors`.
pub(super) fn ring_pieces(
    sectors: &[Domain],
    l: usize,
    first: usize,
    split: Split,
    out: &mut PatchComplex,
) {
    let n = sectors.len();
    let half = |u: f64, v: f64| [[u, v], [u + 0.5, v + 0.5]];
    for (s, &q) in sectors.iter().enumerate() {
        let here = hole(q, l - 1, split);
        let before = hole(sectors[(s + n - 1) % n], l - 1, split);
        let (a, b) = ((first + 2 * s) as u32, (first + 2 * s + 1) as u32);
        if let Split::At(t) = split {
            // (window, patch, cell, corner of the window's (0, 0))
            let pieces = [
                ([[0.0, 0.5], [1.0, 1.0]], a, here.ratio_child(t, 1), 0),
                ([[0.0, 0.0], [1.0, 0.5]], a, before.ratio_child(t, 3), 1),
                ([[0.0, 0.0], [1.0, 1.0]], b, here.ratio_child(t, 2), 0),
            ];
            for (window, patch, cell, rot) in pieces {
                out.push_piece(Piece {
                    patch,
                    window,
                    domain: cell.rotated(rot),
                });
            }
            continue;
        }
        // (window, patch, cell, corner of the window's (0, 0))
        let pieces = [
            (half(0.0, 0.5), a, here.third_child(1), 0),
            (half(0.5, 0.5), a, here.third_child(2), 0),
            (half(0.0, 0.0), a, before.third_child(3), 1),
            (half(0.5, 0.0), a, before.third_child(6), 1),
            (half(0.0, 0.0), b, here.third_child(4), 0),
            (half(0.5, 0.0), b, here.third_child(5), 0),
            (half(0.0, 0.5), b, here.third_child(7), 0),
            (half(0.5, 0.5), b, here.third_child(8), 0),
        ];
        for (window, patch, cell, rot) in pieces {
            out.push_piece(Piece {
                patch,
                window,
                domain: cell.rotated(rot),
            });
        }
    }
}

/// Records that cap (or fill) patches `first .. first + n` cover the holes of their sectors
/// after `rings` rings, `(0, 0)` at the centre.
pub(super) fn cap_domains(
    sectors: &[Domain],
    rings: usize,
    first: usize,
    split: Split,
    out: &mut PatchComplex,
) {
    for (s, &q) in sectors.iter().enumerate() {
        out.set_domain(first + s, hole(q, rings, split));
    }
}
