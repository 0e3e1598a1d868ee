//! The input-face cells of a PGS facet's rings and cap in `bi2-mixed` (evaluation at
//! `(face, u, v)`, see [`crate::bezier::domain`]).
//!
//! The regular patch of an input vertex covers the quarter of each of its four faces at it
//! (as for Doo-Sabin). The hole of an `n`-gon facet `f` with corners `a_s` is the union of the
//! quarters at the `a_s`: sub-face `s` of `f` and the quarters at `a_s` of the three quads
//! around it. In sector `s`'s chart of the DS-net ([`crate::schemes::bi2::pgs::ds_net_chart`],
//! `a_s` at `(1/2, 1/2)`, the facet's centroid at the origin, level-`l` points at `2^-l`
//! times their chart coordinates) sub-face `s` is `[0, 1/2]^2`, its own `(u, v)` being
//! `(1 - 2x, 1 - 2y)`: turned to its corner 2 (the centroid), its frame is the chart scaled by
//! 2. Ring `l`'s patches of `b, c, d` (centred at `(3, 1), (3, 3), (1, 3)` half-units of the
//! level-`l` chart, `u` along `x`, `v` along `y`) cover the squares `[1, 2] x [0, 1]`,
//! `[1, 2]^2`, `[0, 1] x [1, 2]` times `2^-l`:
//! - for `l >= 2` the squares `(1, 0)`, `(1, 1)`, `(0, 1)` of level `l - 1` of sub-face `s`'s
//!   frame ([`Domain::square`]), and the cap or fill after ring `L >= 1` the square `(0, 0)`
//!   of level `L - 1` (`(0, 0)` at the centroid);
//! - for `l = 1` the quarters at `a_s` of the quad across edge `a_(s-1) a_s` (`b`: the patch's
//!   `(0, 0)` at that edge's midpoint, corner 1 of the quarter), of the corner quad (`c`: at
//!   `a_s`, corner 0) and of the quad across edge `a_s a_(s+1)` (`d`: at that edge's midpoint,
//!   corner 3).
//!
//! TPS vertices (ternary rings, which no dyadic cell holds) lay their rings and cap in thirds
//! of their quarters, as `tps` does ([`super::thirds`]); PolBS poles have
//! their own cells ([`super::poles`]); the regular patches' quarters at boundary vertices are
//! tracked, as for the dual schemes.

use crate::bezier::complex::Domain;
use crate::mesh::PolyMesh;

/// Where the rings and the cap of one facet lie (see the [module](self) documentation).
#[derive(Debug, Clone)]
pub(super) struct FacetCells {
    face: u32,
    sides: usize,
    /// Per sector: the domains of ring 1's `b, c, d` patches.
    ring1: Vec<[Domain; 3]>,
}

impl FacetCells {
    /// The cells of facet `f`, whose corners are interior vertices of valence 4 with quads
    /// across its edges (checked by the caller: `None` otherwise).
    pub(super) fn of(mesh: &PolyMesh, f: usize) -> Option<FacetCells> {
        let n = mesh.face_size(f);
        let h0 = mesh.face_halfedge(f);
        let quarter = |h: u32, rot: u32| {
            let g = mesh.he_face(h) as usize;
            let k = h - mesh.face_halfedge(g);
            Domain::polygon(g as u32, mesh.face_size(g))
                .child(k)
                .rotated(rot)
        };
        let ring1 = (0..n as u32)
            .map(|s| {
                let prev = h0 + (s + n as u32 - 1) % n as u32;
                // a_s -> a_(s-1) in the quad across that edge, then a_s -> b_s in the corner
                // quad, and a_s -> d_s in the quad across edge a_s a_(s+1)
                let tb = mesh.he_twin(prev)?;
                let tc = mesh.he_twin(mesh.he_prev(tb))?;
                let td = mesh.he_next(mesh.he_twin(h0 + s)?);
                Some([quarter(tb, 1), quarter(tc, 0), quarter(td, 3)])
            })
            .collect::<Option<Vec<_>>>()?;
        Some(FacetCells {
            face: f as u32,
            sides: n,
            ring1,
        })
    }

    /// Sub-face `s` turned to the centroid: its frame is sector `s`'s chart scaled by 2.
    fn frame(&self, s: usize) -> Domain {
        Domain::polygon(self.face, self.sides)
            .child(s as u32)
            .rotated(2)
    }

    /// The cell of ring `l`'s patch `t` (`b, c, d`) of sector `s`.
    pub(super) fn ring(&self, l: usize, s: usize, t: usize) -> Domain {
        if l == 1 {
            return self.ring1[s][t];
        }
        let (i, j) = [(1, 0), (1, 1), (0, 1)][t];
        match u8::try_from(l - 1) {
            Ok(level) => self.frame(s).square(level, i, j),
            Err(_) => Domain::UNTRACKED,
        }
    }

    /// The cell of sector `s`'s cap or fill patch after ring `l` (untracked for `l = 0`, whose
    /// fill covers four quarters).
    pub(super) fn cap(&self, l: usize, s: usize) -> Domain {
        match u8::try_from(l) {
            Ok(level) if level >= 1 => self.frame(s).square(level - 1, 0, 0),
            _ => Domain::UNTRACKED,
        }
    }
}
