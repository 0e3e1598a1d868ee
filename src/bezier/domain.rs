//! Parameter domains of patches: which part of which input face a patch of a complex covers.
//!
//! Evaluation at `(face, u, v)` ([`crate::surface::eval`]) needs, for every patch, the map from
//! the patch's own parameters to its input face's. The adaptive host builds that map as it
//! refines: a cell of level `l + 1` is one child of a cell of level `l`, so a [`Domain`] is the
//! input face, the chain of child indices from the face down to the cell (two bits per dyadic
//! level), and the corner of the cell at which the patch's own `(0, 0)` sits (caps are
//! parametrised from the centre of their hole). The maps of dyadic cells are affine with
//! dyadic coefficients, so they are exact in floating point. A level may instead split its
//! cell in thirds (the 3 x 3 grid of the ternary schemes, or thirds of any dyadic cell), see
//! the `thirds` submodule ([`Domain::third_child`], [`Domain::third`]); their maps have the
//! coefficients `1/3`, rounded once per level. Adjustable TPS's levels split a cell 2 x 2 at a
//! ratio other than `1/2` (the `ratio` submodule, [`Domain::ratio_child`]), and after its
//! separating whole-net steps a chain starts from a rectangle of the face at its knots with
//! its own affine map instead of the face (the `frame` submodule, [`Domain::framed`]). The
//! radial rings of a pole (PolBS) lie in cells halved along one axis (the `halves` submodule,
//! [`Domain::half_child`]).
//!
//! # The parameter domain of an input face
//!
//! * A **quad** has `(u, v)` in `[0, 1]^2`: corner 0 at `(0, 0)`, `u` along the first edge
//!   (corner 0 -> corner 1), `v` along the last edge reversed (corner 0 -> corner 3); corner 2 is
//!   `(1, 1)`. Child `k` of a quad cell (Catmull-Clark's child at corner `k`: corner `k`, the
//!   midpoint of edge `k -> k+1`, the centre, the midpoint of edge `k-1 -> k`) is the quarter of
//!   the cell at corner `k`, with its own `u` toward corner `k + 1` and `v` toward corner `k - 1`.
//! * An **n-gon** (`n != 4`, triangles included; Catmull-Clark and the schemes on its host,
//!   which start from [`Domain::polygon`]) is split into `n` quads by its first refinement;
//!   sub-face `i` is the quad at corner `i` (corner `i`, the midpoint of edge `i -> i+1`, the
//!   face centre, the midpoint of edge `i-1 -> i`), parametrised like a quad: `(0, 0)` at corner
//!   `i`, `u` toward the midpoint of the outgoing edge, `v` toward the midpoint of the incoming
//!   edge, `(1, 1)` at the centre. The face's parameters lay the sub-faces out as a strip,
//!   `u` in `[0, n]`, `v` in `[0, 1]`: sub-face `i = min(floor(u), n - 1)` at local
//!   `(u - i, v)` (the "quadrangulated" parameterisation of OpenSubdiv's Bfr, with the
//!   sub-faces side by side instead of in a grid).
//! * A **triangle** of Loop's (cells of [`Shape::Triangle`]) has barycentric `(u, v)`, `u, v >= 0`, `u + v <= 1`, `w = 1 - u - v`:
//!   corner 0 at `(0, 0)`, `u` toward corner 1, `v` toward corner 2. Children 0, 1, 2 are the
//!   corner triangles (corner `k`, midpoints toward `k + 1` and `k + 2`), child 3 the middle one
//!   (midpoints of edges 0-1, 1-2, 2-0), as Loop's refinement orders them.
//!
//! # Dual schemes (Doo-Sabin, DS^CC, PGS)
//!
//! A dual scheme's patch is centred at a vertex, not in a face: the bi-2 patch of an input
//! vertex `v` has the centroids (limit points) of the four faces around `v` at its corners, so
//! it covers one quarter of each of them. The faces keep the domains above, with every face
//! that is not a quad (triangles included) an `n`-gon of `n` quad sub-faces: the quarter of
//! face `F` at its corner `k` is child `k` of `F` (sub-face `k` of an `n`-gon), the cell
//! whose corners are `v` (0), the midpoint of `F`'s outgoing edge (1), `F`'s centroid (2, the
//! centre `(1, 1)` of every sub-face) and the midpoint of the incoming edge (3). Such a patch
//! is recorded as four [`Piece`]s, one per quarter, each a quarter of the patch's own
//! parameter square. Every vertex made by refinement lies in one such cell and its patch
//! covers exactly that cell (its children those of the cell's four children, one per face
//! around it), so from level 1 on dual patches have ordinary domains. The hole of an
//! extraordinary vertex shrinks to corner `(0, 0)` of its faces' quarters, that of an `n`-gon
//! to the centre `(1, 1)` of its sub-faces. A regular boundary vertex (two quads, or a
//! corner with one) is the centre of its 3 x 3 net with the doubled boundary layer, so its
//! patch spans half a face beyond the boundary edges (the boundary curve is the knot line
//! between the phantom row and the boundary row, half a face outside the net's lattice); its
//! parts over the vertex's faces are their quarters at it, recorded as at an interior vertex.
//! The outer half-face strip of those patches lies over no face: the face's boundary edge is
//! the knot line through the boundary vertices, not the boundary curve. A boundary vertex
//! refined as an extraordinary element (three or more faces, an unkept corner under
//! `edge-only`) hands the quarters of its faces to its corner points, as an interior vertex
//! does; its Chaikin points and kept corner, and their descendants, lie beyond those knot
//! lines, over no face (tracked since 2026-12-04: `tests/it/eval_dual.rs` checks agreement and
//! continuity on an L-shaped net and a notched c-net). Quarters whose vertex writes no patch
//! (boundary mode `none`) are not tracked: evaluating there is an error.
//!
//! # TPS (primal ternary bi-2)
//!
//! TPS's patches are centred at vertices too, so an input vertex's patch covers the quarters
//! of its faces as above (quads only: TPS takes quad nets). Each ternary step splits a
//! vertex's piece in thirds, so in the quarter of a face at an extraordinary vertex (its own
//! `u` along the sector's first spoke) ring `l` covers the children in thirds of the square
//! `[0, 3^-(l-1)]^2` but its corner child, which is the next hole; the cap covers `[0, 3^-K]^2`
//! from the centre. Faces of a net refined by whole-net ternary steps (to separate
//! extraordinary vertices) are children in thirds of the input faces. The layout is documented
//! with the code in `crate::schemes::bi2::surface::thirds`.
//!
//! # Poles (PolBS)
//!
//! A pole's fan triangle `(pole, A, B)` is a collapsed quad `[0, 1]^2`: `(0, 0)` at `A` (the
//! corner after the pole), `(1, 0)` at `B`, the side `v = 1` the pole; an `n`-gon cap turned
//! into a pole keeps the strip `[0, n] x [0, 1]`, sub-face `i` the fan triangle at its edge
//! `i -> i + 1`. Its radial rings lie in cells halved along one axis (the `halves` submodule,
//! documented there).
//!
//! # Non-box
//!
//! `nonbox` parametrises faces as Catmull-Clark does (quads `[0, 1]^2`, n-gons and triangles
//! the strip of their quad sub-faces) and refines cells the same way; a regular cell is
//! covered by the four S_3^1 triangles of its criss-cross
//! ([`Domain::criss_cross`]). `nonbox-4dir` on a triangle mesh evaluates on its triangles,
//! each a fan triangle of a polygon of the net with FCVs ([`FanTriangle`], the `fan`
//! submodule).

use serde::Serialize;

mod carry;
mod fan;
mod frame;
mod halves;
mod ratio;
mod thirds;

pub use fan::FanTriangle;
pub use frame::Frame;

/// Shape of a cell: how its children split it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Shape {
    /// A quad cell, `[0, 1]^2`.
    Quad,
    /// A triangle cell, barycentric.
    Triangle,
}

/// Most levels a domain records (two bits each in a `u128`).
pub const MAX_DEPTH: u8 = 64;

/// The part of an input face a patch covers (see the [module](self) documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Domain {
    /// The input face.
    pub face: u32,
    /// Sub-face of an n-gon (`n != 4`), 0 for quads and triangles; [`Domain::WHOLE`] for the
    /// n-gon itself before its first refinement.
    pub sub: u32,
    /// Shape of the cells.
    pub shape: Shape,
    /// Levels below the face (or sub-face).
    pub depth: u8,
    /// Child index of each level as a mixed-radix number, level 1 the lowest digit: a dyadic
    /// level has radix 4, a level in thirds radix 9 ([`Domain::thirds`]). With dyadic levels
    /// only, two bits per level, level 1 in the lowest two bits.
    pub path: u128,
    /// Levels whose cells split in thirds (the 3 x 3 grid of [`Shape::third_map`]): bit
    /// `l - 1` set for level `l`. 0 for the dyadic cells of every scheme but TPS.
    pub thirds: u64,
    /// Levels whose cells split at [`Domain::ratio`] (2 x 2, cut at the ratio instead of
    /// `1/2`; adjustable TPS, the `ratio` submodule): bit `l - 1` set for level `l`. 0 for
    /// every other scheme.
    pub split_at: u64,
    /// The bits of the `f64` ratio of the levels in `split_at` (0 when there are none).
    pub ratio: u64,
    /// Levels whose cells split in two halves along one axis (a pole's fan triangles, the
    /// `halves` submodule, [`Domain::half_child`]): bit `l - 1` set for level `l`. 0 for the
    /// cells of every other element.
    pub halves: u64,
    /// The cell corner at which the patch's `(0, 0)` sits: for quads the patch's `u` runs
    /// toward corner `rot + 1`, its `v` toward corner `rot - 1`. Triangle patches have 0, except
    /// Loop's G^1 cap kites, whose `rot` is the corner of the hole's centre in their fan
    /// triangle ([`Shape::corner_map`]; `crate::surface::eval` maps the chart to the kites).
    /// `4 + k` marks triangle `k` of a quad cell's criss-cross ([`Domain::criss_cross`]), whose
    /// maps are those of `rot = 0`.
    pub rot: u8,
    /// The rectangle of the face the cell chain starts from ([`Domain::framed`], the `frame`
    /// submodule): [`Frame::NONE`] (the face itself) for every scheme but adjustable TPS
    /// after a separating step.
    pub frame: Frame,
}

/// A part of a patch that covers one cell: the patch's parameters in the box `window`
/// (`[lo, hi]` per parameter, dyadic, so the maps are exact) cover `domain`, whose `rot` places
/// the box's own `(0, 0)` corner (`lo`) in the cell, its `u` along the patch's `u` (see the
/// dual schemes in the [module](self) documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    /// The patch.
    pub patch: u32,
    /// `[lo, hi]`: `[[u_lo, v_lo], [u_hi, v_hi]]` of the patch's parameters.
    pub window: [[f64; 2]; 2],
    /// The cell the window covers, with the window's `(0, 0)` at corner `rot`.
    pub domain: Domain,
}

impl Piece {
    /// The quarter of a patch at its corner `r` (counter-clockwise from `(0, 0)`: `(0, 0)`,
    /// `(1, 0)`, `(1, 1)`, `(0, 1)`) covering `cell`, with patch corner `r` at the cell's corner
    /// `at`: the quarter's `(0, 0)` is its own corner `0`, and patch corner `r` its corner `r`.
    pub fn quarter(patch: u32, r: u8, cell: Domain, at: u8) -> Piece {
        let (u, v) = match r & 3 {
            0 => (0.0, 0.0),
            1 => (0.5, 0.0),
            2 => (0.5, 0.5),
            _ => (0.0, 0.5),
        };
        Piece {
            patch,
            window: [[u, v], [u + 0.5, v + 0.5]],
            domain: cell.rotated(u32::from((4 + at - (r & 3)) % 4)),
        }
    }

    /// The map from the window's coordinates (`[0, 1]^2`) to the patch's.
    pub fn window_map(&self) -> Affine {
        let [lo, hi] = self.window;
        Affine::new(lo, [hi[0] - lo[0], 0.0], [0.0, hi[1] - lo[1]])
    }
}

/// An affine map of the plane, `p -> origin + p[0] e[0] + p[1] e[1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Affine {
    /// Image of `(0, 0)`.
    pub origin: [f64; 2],
    /// Images of the unit vectors (the columns of the linear part).
    pub e: [[f64; 2]; 2],
}

/// Quad cell corners in cell coordinates, counter-clockwise from corner 0.
const QUAD: [[f64; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
/// Triangle cell corners in barycentric `(u, v)`.
const TRI: [[f64; 2]; 3] = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];

fn sub2(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn half(a: [f64; 2]) -> [f64; 2] {
    [0.5 * a[0], 0.5 * a[1]]
}

impl Affine {
    /// The identity.
    pub const IDENTITY: Affine = Affine {
        origin: [0.0, 0.0],
        e: [[1.0, 0.0], [0.0, 1.0]],
    };

    /// The map with `origin` and the columns `e0`, `e1`.
    fn new(origin: [f64; 2], e0: [f64; 2], e1: [f64; 2]) -> Affine {
        Affine {
            origin,
            e: [e0, e1],
        }
    }

    /// Image of `p`.
    pub fn apply(&self, p: [f64; 2]) -> [f64; 2] {
        [
            self.origin[0] + p[0] * self.e[0][0] + p[1] * self.e[1][0],
            self.origin[1] + p[0] * self.e[0][1] + p[1] * self.e[1][1],
        ]
    }

    /// `self o inner`.
    pub fn compose(&self, inner: &Affine) -> Affine {
        let lin = |p: [f64; 2]| {
            [
                p[0] * self.e[0][0] + p[1] * self.e[1][0],
                p[0] * self.e[0][1] + p[1] * self.e[1][1],
            ]
        };
        Affine {
            origin: self.apply(inner.origin),
            e: [lin(inner.e[0]), lin(inner.e[1])],
        }
    }

    /// The inverse of the linear part as rows: `inv[a][b] = d p_a / d q_b` for `q = apply(p)`.
    pub fn inverse_linear(&self) -> [[f64; 2]; 2] {
        let [[a, c], [b, d]] = self.e; // e0 = (a, c), e1 = (b, d): matrix [[a, b], [c, d]]
        let det = a * d - b * c;
        [[d / det, -b / det], [-c / det, a / det]]
    }

    /// The inverse map (exact for the dyadic maps of this module).
    pub fn inverse(&self) -> Affine {
        let inv = self.inverse_linear();
        Affine {
            origin: self.invert([0.0, 0.0]),
            e: [[inv[0][0], inv[1][0]], [inv[0][1], inv[1][1]]],
        }
    }

    /// Preimage of `q`.
    pub fn invert(&self, q: [f64; 2]) -> [f64; 2] {
        let inv = self.inverse_linear();
        let r = sub2(q, self.origin);
        [
            inv[0][0] * r[0] + inv[0][1] * r[1],
            inv[1][0] * r[0] + inv[1][1] * r[1],
        ]
    }
}

impl Shape {
    /// The map from child `k`'s coordinates to its parent cell's.
    pub fn child_map(self, k: u8) -> Affine {
        match self {
            Shape::Quad => {
                let k = k as usize & 3;
                let c = QUAD[k];
                Affine::new(
                    c,
                    half(sub2(QUAD[(k + 1) % 4], c)),
                    half(sub2(QUAD[(k + 3) % 4], c)),
                )
            }
            Shape::Triangle => match k {
                0..=2 => {
                    let k = k as usize;
                    let c = TRI[k];
                    Affine::new(
                        c,
                        half(sub2(TRI[(k + 1) % 3], c)),
                        half(sub2(TRI[(k + 2) % 3], c)),
                    )
                }
                _ => Affine::new(
                    [0.5, 0.0],
                    half(sub2(TRI[2], TRI[0])),
                    half(sub2(TRI[2], TRI[1])),
                ),
            },
        }
    }

    /// The child of a cell that holds the cell point `p` (ties go to the child at the larger
    /// coordinate, the middle triangle last).
    pub fn child_at(self, p: [f64; 2]) -> u8 {
        match self {
            Shape::Quad => match (p[0] >= 0.5, p[1] >= 0.5) {
                (false, false) => 0,
                (true, false) => 1,
                (true, true) => 2,
                (false, true) => 3,
            },
            Shape::Triangle => {
                if p[0] >= 0.5 {
                    1
                } else if p[1] >= 0.5 {
                    2
                } else if 1.0 - p[0] - p[1] >= 0.5 {
                    0
                } else {
                    3
                }
            }
        }
    }

    /// The map from a patch's coordinates to its cell's when the patch's `(0, 0)` sits at
    /// corner `rot`: for quads `u` toward corner `rot + 1`, `v` toward corner `rot - 1`; for
    /// triangles the barycentric chart with `(1, 0)` at corner `rot + 1` and `(0, 1)` at corner
    /// `rot + 2` (the identity for `rot = 0`, which every triangle patch but Loop's G^1 kites
    /// has).
    pub fn corner_map(self, rot: u8) -> Affine {
        match self {
            Shape::Quad => {
                let r = rot as usize & 3;
                let c = QUAD[r];
                Affine::new(c, sub2(QUAD[(r + 1) % 4], c), sub2(QUAD[(r + 3) % 4], c))
            }
            Shape::Triangle => {
                let r = rot as usize % 3;
                let c = TRI[r];
                Affine::new(c, sub2(TRI[(r + 1) % 3], c), sub2(TRI[(r + 2) % 3], c))
            }
        }
    }
}

impl Domain {
    /// The n-gon itself before its first refinement (not a cell any patch covers).
    pub const WHOLE: u32 = u32::MAX;

    /// A domain the host does not track (schemes without face domains, the dual schemes'
    /// boundary points, which lie over no face).
    pub const UNTRACKED: Domain = Domain {
        face: u32::MAX,
        sub: 0,
        shape: Shape::Quad,
        depth: 0,
        path: 0,
        thirds: 0,
        split_at: 0,
        ratio: 0,
        halves: 0,
        rot: 0,
        frame: Frame::NONE,
    };

    /// The whole input face `face` with `sides` corners: a quad, a triangle (Loop) or an n-gon
    /// before its split into sub-faces.
    pub fn face(face: u32, sides: usize) -> Domain {
        let (shape, sub) = match sides {
            3 => (Shape::Triangle, 0),
            4 => (Shape::Quad, 0),
            _ => (Shape::Quad, Domain::WHOLE),
        };
        Domain {
            face,
            sub,
            shape,
            ..Domain::UNTRACKED
        }
    }

    /// The whole input face `face` with `sides` corners as the quad-shaped schemes parametrise
    /// it: a quad, or an `n`-gon (triangles included) before its split into quad sub-faces.
    pub fn polygon(face: u32, sides: usize) -> Domain {
        Domain {
            face,
            sub: if sides == 4 { 0 } else { Domain::WHOLE },
            shape: Shape::Quad,
            ..Domain::UNTRACKED
        }
    }

    /// Whether the host tracked this domain.
    pub fn is_tracked(&self) -> bool {
        self.face != u32::MAX && self.depth <= MAX_DEPTH
    }

    /// Child `k` of this cell: for the n-gon itself ([`Domain::WHOLE`]) the quad sub-face `k`,
    /// otherwise the child cell `k` (see [`Shape::child_map`]). Past [`MAX_DEPTH`] levels the
    /// domain becomes untracked.
    pub fn child(self, k: u32) -> Domain {
        if !self.is_tracked() {
            return self;
        }
        if self.sub == Domain::WHOLE {
            return Domain {
                face: self.face,
                sub: k,
                ..Domain::UNTRACKED
            };
        }
        if self.depth == MAX_DEPTH {
            return Domain {
                depth: MAX_DEPTH + 1,
                ..self
            };
        }
        self.descend(u128::from(k & 3), false)
    }

    /// The same cell covered by the four triangles of its criss-cross (the cell split by both
    /// diagonals; non-box's S_3^1 cells), this patch being triangle `k`: the one on the cell's
    /// side from corner `k` to corner `k + 1`, apex at the centre, stored as the collapsed bi-3
    /// patch `T(u (1 - v), v)` of its barycentric `T(s, t)` (`s` toward corner `k + 1`, `t`
    /// toward the centre). The four are consecutive patches of the complex, triangle 0 first
    /// (`crate::surface::eval` finds the others from it). Its maps are those of `rot = 0`.
    pub fn criss_cross(self, k: u8) -> Domain {
        Domain {
            rot: 4 + (k & 3),
            ..self
        }
    }

    /// `Some(k)` for triangle `k` of a criss-cross cell ([`Domain::criss_cross`]).
    pub fn criss_cross_triangle(&self) -> Option<u8> {
        (self.shape == Shape::Quad && self.rot >= 4).then_some(self.rot - 4)
    }

    /// The same cell with the patch's `(0, 0)` at corner `rot`.
    pub fn rotated(self, rot: u32) -> Domain {
        Domain {
            rot: (rot & 3) as u8,
            ..self
        }
    }

    /// The dyadic square `[i, i + 1] x [j, j + 1] * 2^-level` of this patch frame (the cell's
    /// coordinates rotated so that `(0, 0)` sits at corner `rot`, as [`Domain::patch_map`]
    /// maps them), as a cell `level` levels down with the patch's `(0, 0)` at the square's
    /// corner nearest the frame's origin and its axes along the frame's: the domain of the
    /// cap schemes' ring patches, which tile a sector's face in its own chart (quads only).
    pub fn square(self, level: u8, i: u32, j: u32) -> Domain {
        let mut d = self;
        let mut r = u32::from(self.rot);
        for l in (0..u32::from(level)).rev() {
            let (qx, qy) = ((i >> l) & 1, (j >> l) & 1);
            // the quadrant's corner counted from the frame's origin, counter-clockwise
            let off = match (qx, qy) {
                (0, 0) => 0,
                (1, 0) => 1,
                (1, 1) => 2,
                _ => 3,
            };
            let k = (r + off) % 4;
            d = d.child(k);
            // child k's corner c sits where the parent's corner k + c does, scaled toward k
            r = (r + 4 - k) % 4;
        }
        d.rotated(r)
    }

    /// Child index at level `l` (1-based): `0..4` for a dyadic level, `0..9` for a level in
    /// thirds.
    pub fn step(&self, l: u8) -> u8 {
        if self.thirds == 0 {
            return ((self.path >> (2 * (l as u32 - 1))) & 3) as u8;
        }
        let place = self.place(l - 1).unwrap_or(u128::MAX);
        ((self.path / place) % self.radix(l)) as u8
    }

    /// The map from the cell's coordinates to the face's (the sub-face's for an n-gon; add
    /// `sub` to `u` for the face's strip coordinates).
    pub fn cell_map(&self) -> Affine {
        let mut m = self.frame_or_identity();
        for l in 1..=self.depth {
            let child = if self.splits_in_thirds(l) {
                Shape::third_map(self.step(l))
            } else if self.splits_at_ratio(l) {
                Shape::ratio_map(self.ratio(), self.step(l))
            } else if self.splits_in_halves(l) {
                Shape::half_map(self.step(l))
            } else {
                self.shape.child_map(self.step(l))
            };
            m = m.compose(&child);
        }
        m
    }

    /// The map from the patch's coordinates (barycentric for triangles) to the face's (the
    /// sub-face's for an n-gon).
    pub fn patch_map(&self) -> Affine {
        self.cell_map().compose(&self.shape.corner_map(self.rot))
    }
}

#[cfg(feature = "unit-tests")]
mod tests;
