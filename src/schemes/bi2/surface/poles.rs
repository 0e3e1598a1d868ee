//! The input-face cells of a pole's rings and cap (PolBS in `polar-bi2` and `bi2-mixed`;
//! evaluation at `(face, u, v)`, see [`crate::bezier::domain`]).
//!
//! Sector `s` of a pole `p` is its spoke to `a_s` (the local polar net's labelling,
//! [`crate::schemes::bi2::polar::polar_net`]); fan triangle `s` is `(p, a_s, a_(s+1))`, a
//! collapsed quad with `(0, 0)` at `a_s`, `(1, 0)` at `a_(s+1)` and `v = 1` at the pole (the
//! `halves` submodule of [`crate::bezier::domain`] documents it and the radii below). Ring
//! `l`'s patch of sector `s` is the bi-2 patch of `b_s` of the level-`l` polar net, `u`
//! radial (outward), `v` around the pole from the middle of triangle `s - 1` (`v = 0`) over
//! the spoke (`v = 1/2`) to the middle of triangle `s` (`v = 1`); the cap patch of sector `s`
//! is laid out alike with `u = 0` at the pole. In the characteristic chart (radii `a`: 1, `b`:
//! 3 at level 0, halved per level) ring `l` spans the radii `[2, 4] 2^-l`, the cap after ring
//! `L` `[0, 2] 2^-L`, the edge `a_s a_(s+1)` is radius 1 and the level-0 regular patches of
//! the `b` ring start at radius 2. So each patch is two pieces, its halves `v <= 1/2` and
//! `v >= 1/2`:
//! - ring 1: the quarters at `a_s` of the quad across edge `a_(s-1) a_s` (`v <= 1/2`; the
//!   piece's `(0, 0)` at that edge's midpoint, corner 1 of the quarter) and of the quad
//!   across edge `a_s a_(s+1)` (`v >= 1/2`; at `a_s`, corner 0);
//! - ring `l >= 2`: the band `1 - v` in `[2^(1-l), 2^(2-l)]` of the half `u >= 1/2` of
//!   triangle `s - 1` and of the half `u <= 1/2` of triangle `s`;
//! - the cap after `L >= 1` rings: the band `1 - v` in `[0, 2^(1-L)]` of the same halves; after
//!   no ring, its halves `u <= 1/2` (radii `[0, 1]`) cover the triangles' halves and its halves
//!   `u >= 1/2` the quarters of ring 1.
//!
//! Every piece on a triangle has the patch's `(0, 0)` at corner 3 of its cell (toward the
//! pole, the spoke side). When the pole replaced an `n`-gon cap of the input, the triangles
//! are faces of the polar layout, renamed to the cap's sub-faces by [`to_input_faces`].

use crate::bezier::complex::{Domain, PatchComplex, Piece};
use crate::mesh::{Element, PolyMesh};
use crate::schemes::bi2::polar::PolarNet;

/// Where the rings and the cap of one pole lie (see the [module](self) documentation).
#[derive(Debug, Clone)]
pub(super) struct PoleCells {
    /// Per sector: fan triangle `s`'s collapsed quad.
    triangle: Vec<Domain>,
    /// Per sector: the quarter at `a_s` of the quad across edge `a_s a_(s+1)`, turned for ring
    /// 1's piece `v >= 1/2`, and of the quad across edge `a_(s-1) a_s` for its piece `v <= 1/2`.
    quarters: Vec<[Domain; 2]>,
}

/// Ring 1's (and the cap's) window halves: `v <= 1/2`, `v >= 1/2`.
const BEFORE: [f64; 2] = [0.0, 0.5];
const AFTER: [f64; 2] = [0.5, 1.0];

impl PoleCells {
    /// The cells of the pole whose outgoing half-edges are `hs` (counter-clockwise, sector
    /// `s` along `hs[s]`), `None` when its faces are not triangles with quads beyond them.
    pub(super) fn of(mesh: &PolyMesh, hs: &[u32]) -> Option<PoleCells> {
        let n = hs.len();
        let mut triangle = Vec::with_capacity(n);
        let mut quarters = Vec::with_capacity(n);
        let quarter = |t: u32, rot: u32| -> Option<Domain> {
            let q = mesh.he_face(t) as usize;
            (mesh.face_size(q) == 4).then(|| {
                Domain::polygon(q as u32, 4)
                    .child(t - mesh.face_halfedge(q))
                    .rotated(rot)
            })
        };
        for s in 0..n {
            let g = mesh.he_face(hs[s]) as usize;
            if mesh.face_size(g) != 3 {
                return None;
            }
            triangle.push(Domain::pole_triangle(g as u32));
            // a_(s+1) -> a_s in the quad after the spoke; the half-edge after it leaves a_s
            let after = mesh.he_next(mesh.he_twin(mesh.he_next(hs[s]))?);
            // a_s -> a_(s-1) in the quad before the spoke
            let before = mesh.he_twin(mesh.he_next(hs[(s + n - 1) % n]))?;
            quarters.push([quarter(after, 0)?, quarter(before, 1)?]);
        }
        Some(PoleCells { triangle, quarters })
    }

    /// The band of fan triangle `t`'s half `half` (0: `u <= 1/2`, 1: `u >= 1/2`) that ring
    /// `l >= 2` covers, or the cap after `l` rings (`cap`, `l >= 1`), with the patch's
    /// `(0, 0)` at corner 3.
    fn band(&self, t: usize, half: u8, l: usize, cap: bool) -> Domain {
        let mut d = self.triangle[t].half_child(half);
        let inward = if cap { l - 1 } else { l - 2 };
        for _ in 0..inward.min(usize::from(crate::bezier::domain::MAX_DEPTH)) {
            d = d.half_child(3);
        }
        if !cap {
            d = d.half_child(2);
        }
        d.rotated(3)
    }

    /// The pieces of ring `l`'s patch `patch` of sector `s`.
    pub(super) fn ring(&self, l: usize, s: usize, patch: u32, out: &mut PatchComplex) {
        let n = self.triangle.len();
        let prev = (s + n - 1) % n;
        let cells = if l == 1 {
            [self.quarters[s][1], self.quarters[s][0]]
        } else {
            [self.band(prev, 1, l, false), self.band(s, 0, l, false)]
        };
        push(patch, [0.0, 1.0], cells, out);
    }

    /// The pieces of the cap patch `patch` of sector `s` after `l` rings.
    pub(super) fn cap(&self, l: usize, s: usize, patch: u32, out: &mut PatchComplex) {
        let n = self.triangle.len();
        let prev = (s + n - 1) % n;
        if l >= 1 {
            let cells = [self.band(prev, 1, l, true), self.band(s, 0, l, true)];
            push(patch, [0.0, 1.0], cells, out);
            return;
        }
        let halves = [
            self.triangle[prev].half_child(1).rotated(3),
            self.triangle[s].half_child(0).rotated(3),
        ];
        push(patch, [0.0, 0.5], halves, out);
        push(
            patch,
            [0.5, 1.0],
            [self.quarters[s][1], self.quarters[s][0]],
            out,
        );
    }
}

/// The two pieces of `patch` over `u` in `radial`: `v <= 1/2` on `cells[0]`, `v >= 1/2` on
/// `cells[1]`.
fn push(patch: u32, radial: [f64; 2], cells: [Domain; 2], out: &mut PatchComplex) {
    for (v, domain) in [BEFORE, AFTER].into_iter().zip(cells) {
        out.push_piece(Piece {
            patch,
            window: [[radial[0], v[0]], [radial[1], v[1]]],
            domain,
        });
    }
}

/// Renames the faces of the polar layout `net` of `input` in `complex`'s domains to the input
/// faces: a fan triangle `k` of a cap turned into a pole becomes sub-face `k` of the cap (the
/// strip of its fan triangles), every other face the input face it is.
pub(super) fn to_input_faces(input: &PolyMesh, net: &PolarNet, complex: &mut PatchComplex) {
    let mut origin: Vec<(u32, Option<u32>)> = Vec::with_capacity(net.mesh.num_faces());
    for f in 0..input.num_faces() {
        let capped = net
            .poles
            .iter()
            .any(|p| p.element == Element::Face(f as u32));
        if capped {
            origin.extend((0..input.face_size(f) as u32).map(|k| (f as u32, Some(k))));
        } else {
            origin.push((f as u32, None));
        }
    }
    let rename = |d: &mut Domain| {
        if let Some(&(face, sub)) = origin.get(d.face as usize) {
            d.face = face;
            if let Some(k) = sub {
                d.sub = k;
            }
        }
    };
    for d in complex.domains.iter_mut().flatten() {
        rename(d);
    }
    for p in &mut complex.pieces {
        rename(&mut p.domain);
    }
}
