//! The evaluation index of a [`super::Surface`]: per input face (per sub-face of an n-gon) a
//! flat tree of cells, so that locating a point is an array walk, not a hash look-up per level.
//!
//! Every node is a cell of its face: empty (no patch covers it), a leaf (the patch or piece
//! covering it) or split into `factor^2` children (4 for the dyadic quad and triangle cells,
//! 9 for a cell in thirds; 2 for a cell halved along one axis, a pole's radial rings), stored
//! contiguously so that the child holding a point is
//! `first + k` with `k` the child index of [`crate::bezier::domain`]. A regular face covered
//! by one patch is its root leaf: no descent at all. Each leaf points at what evaluating there
//! needs ([`LeafMaps`]), computed once with the same functions (and so the same rounding) as
//! before: the window of a piece, the inverse of the cell's corner map and the inverse linear
//! part of the map from the patch's parameters to the face's; root cells of one shape and
//! corner share theirs. (Patch indices stay below 2^31, the flag of a piece's domain.)
//!
//! The tree answers exactly as the per-level look-up it replaces: the first domain indexed
//! for a cell wins, and a cell covered by a patch hides every deeper cell below it (the
//! descent stops at the shallowest covered cell).

use crate::bezier::complex::PatchComplex;
use crate::bezier::domain::{Affine, Domain, Frame, Shape};

mod frames;

/// What covers a cell.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Node {
    /// No patch covers the cell (yet).
    Empty,
    /// Leaf `0` of [`CellTree::leaves`].
    Leaf(u32),
    /// Split into `factor^2` children from node `first` on.
    Split { first: u32, factor: u8 },
    /// Split 2 x 2 at the ratio [`CellTree::ratios`]`[ratio]` (adjustable TPS,
    /// [`Shape::ratio_map`]), children from node `first` on.
    SplitAt { first: u32, ratio: u32 },
    /// Halved along `axis` (0: `u`, 1: `v`; a pole's fan triangles, [`Shape::half_map`]), the
    /// lower half at node `first`, the upper at `first + 1`.
    Halves { first: u32, axis: u8 },
    /// Split into the rectangles of framed cells ([`Domain::framed`]): [`CellTree::frames`]
    /// `[set]` (adjustable TPS after a separating step, the `frames` submodule).
    Frames { set: u32 },
}

/// A cell covered by a patch (or a piece of one): 16 bytes, its maps in
/// [`CellTree::maps`] (shared by every leaf of a face's root cell with the same shape and
/// corner; on a mostly regular net of 100k faces the index was 25 MB of 256-byte leaves, each
/// with its domain and maps, and most of its build was the fresh memory).
#[derive(Debug, Clone, Copy)]
pub(super) struct Leaf {
    /// The patch.
    pub patch: u32,
    /// Where the domain the leaf covers is kept: the patch's domain in the complex, or
    /// (with [`PIECE`] set) that of the complex's piece `source & !PIECE`.
    source: u32,
    /// Its maps, [`CellTree::maps`]`[maps]`.
    maps: u32,
    /// The domain's shape and [`Domain::criss_cross_triangle`] (what evaluating reads of it).
    pub shape: Shape,
    pub criss_cross: Option<u8>,
}

/// [`Leaf::source`]'s flag of a piece.
const PIECE: u32 = 1 << 31;

impl Leaf {
    /// The domain the leaf covers, kept in `complex` (the complex the tree indexes).
    pub fn domain(&self, complex: &PatchComplex) -> Domain {
        if self.source & PIECE != 0 {
            complex.pieces[(self.source & !PIECE) as usize].domain
        } else {
            complex.domains[self.source as usize].expect("an indexed patch has a domain")
        }
    }
}

/// A leaf's maps, computed once with the same functions (and so the same rounding) as before:
/// the window of a piece, the inverse of the cell's corner map and the inverse linear part of
/// the map from the patch's parameters to the face's.
#[derive(Debug, Clone, Copy)]
pub(super) struct LeafMaps {
    /// The map from the cell's frame to the patch's parameters for a piece, else `None`.
    pub window: Option<Affine>,
    /// The cell corner map's origin and inverse linear part ([`Affine::invert`] split up).
    corner_origin: [f64; 2],
    corner_inv: [[f64; 2]; 2],
    /// `inv[a][b] = d q_a / d p_b`: patch parameters `q` by face parameters `p`.
    pub chain: [[f64; 2]; 2],
}

impl LeafMaps {
    fn new(domain: &Domain, window: Option<Affine>) -> LeafMaps {
        let corner = domain.shape.corner_map(domain.rot);
        let mut patch_map = domain.patch_map();
        if let Some(w) = window {
            patch_map = patch_map.compose(&w.inverse());
        }
        LeafMaps {
            window,
            corner_origin: corner.origin,
            corner_inv: corner.inverse_linear(),
            chain: patch_map.inverse_linear(),
        }
    }

    /// The patch's parameters at cell point `cell` (before a piece's window:
    /// `corner_map(rot).invert(cell)`, with the same arithmetic).
    #[inline]
    pub fn corner_point(&self, cell: [f64; 2]) -> [f64; 2] {
        let inv = self.corner_inv;
        let r = [
            cell[0] - self.corner_origin[0],
            cell[1] - self.corner_origin[1],
        ];
        [
            inv[0][0] * r[0] + inv[0][1] * r[1],
            inv[1][0] * r[0] + inv[1][1] * r[1],
        ]
    }
}

/// The inverse of a child map, split up like [`Affine::invert`].
#[derive(Debug, Clone, Copy)]
struct ChildInverse {
    origin: [f64; 2],
    inv: [[f64; 2]; 2],
}

impl ChildInverse {
    fn of(map: Affine) -> ChildInverse {
        ChildInverse {
            origin: map.origin,
            inv: map.inverse_linear(),
        }
    }

    /// `map.invert(p)`, with the same arithmetic.
    #[inline]
    fn apply(&self, p: [f64; 2]) -> [f64; 2] {
        let r = [p[0] - self.origin[0], p[1] - self.origin[1]];
        [
            self.inv[0][0] * r[0] + self.inv[0][1] * r[1],
            self.inv[1][0] * r[0] + self.inv[1][1] * r[1],
        ]
    }
}

/// The cells of every face of a complex.
#[derive(Debug, Clone)]
pub(super) struct CellTree {
    /// Face `f`'s root cells are nodes `root[f] .. root[f + 1]`, one per sub-face.
    root: Vec<u32>,
    nodes: Vec<Node>,
    leaves: Vec<Leaf>,
    /// The leaves' maps: the shared maps of root cells ([`CellTree::root_maps`]), then one
    /// per deeper leaf and piece.
    maps: Vec<LeafMaps>,
    /// The index in `maps` of the root cell maps of shape `[shape][rot]`, once computed.
    root_maps: [[Option<u32>; 8]; 2],
    /// Inverse child maps of quad cells, then of triangle cells.
    quad: [ChildInverse; 4],
    triangle: [ChildInverse; 4],
    /// Inverse maps of a quad cell's children in thirds ([`Shape::third_map`]).
    third: [ChildInverse; 9],
    /// The ratios of the cells split at a ratio, and the inverse maps of their children.
    ratios: Vec<(f64, [ChildInverse; 4])>,
    /// Inverse maps of a quad cell's halves ([`Shape::half_map`]).
    halves: [ChildInverse; 4],
    /// The rectangles of the nodes split into framed cells.
    frames: Vec<frames::FrameSet>,
}

/// How many ways level `l` (1-based) of `d` splits each side of its parent cell: 3 for a
/// level in thirds ([`Domain::splits_in_thirds`], TPS), else 2 (the dyadic cells).
fn factor_of(d: &Domain, l: u8) -> u8 {
    if d.splits_in_thirds(l) { 3 } else { 2 }
}

impl CellTree {
    /// The index of `complex`'s patches and pieces over a net whose faces have `sides`
    /// corners (a face of `n != 4` corners has `n` sub-faces; quads, Loop's triangles and the
    /// faces marked `single` (a pole's fan triangles, one collapsed quad) use the first).
    pub fn new(sides: &[u32], single: &[bool], complex: &PatchComplex) -> CellTree {
        let mut root = Vec::with_capacity(sides.len() + 1);
        let mut total = 0u32;
        for (f, &n) in sides.iter().enumerate() {
            root.push(total);
            let one = n == 4 || single.get(f).copied().unwrap_or(false);
            total += if one { 1 } else { n };
        }
        root.push(total);
        let mut tree = CellTree {
            root,
            nodes: vec![Node::Empty; total as usize],
            leaves: Vec::with_capacity(complex.len() + complex.pieces.len()),
            maps: Vec::new(),
            root_maps: [[None; 8]; 2],
            quad: std::array::from_fn(|k| ChildInverse::of(Shape::Quad.child_map(k as u8))),
            triangle: std::array::from_fn(|k| ChildInverse::of(Shape::Triangle.child_map(k as u8))),
            third: std::array::from_fn(|k| ChildInverse::of(Shape::third_map(k as u8))),
            ratios: Vec::new(),
            halves: std::array::from_fn(|k| ChildInverse::of(Shape::half_map(k as u8))),
            frames: Vec::new(),
        };
        debug_assert!(
            complex.len() < PIECE as usize,
            "patch indices below the piece flag"
        );
        for i in 0..complex.len() {
            if let Some(d) = complex.domain(i) {
                tree.insert(i as u32, i as u32, &d, None);
            }
        }
        for (k, p) in complex.pieces.iter().enumerate() {
            let window = Some(p.window_map());
            tree.insert(p.patch, k as u32 | PIECE, &p.domain, window);
        }
        for set in &mut tree.frames {
            set.build_grid();
        }
        tree
    }

    /// Adds a leaf at its domain's cell (ignored where a shallower cell is covered already or
    /// the same cell was indexed before; the domain of a face or sub-face the net does not
    /// have is never looked up).
    /// `patch` is the patch, `source` where the domain `d` is kept ([`Leaf::source`]) and
    /// `window` a piece's window.
    fn insert(&mut self, patch: u32, source: u32, d: &Domain, window: Option<Affine>) {
        let face = d.face as usize;
        let Some((&lo, &hi)) = self.root.get(face).zip(self.root.get(face + 1)) else {
            return;
        };
        if d.sub >= hi - lo || !d.is_tracked() {
            return;
        }
        let mut at = (lo + d.sub) as usize;
        if let Some(map) = d.frame_map() {
            let Some(child) = self.framed_child(at, map) else {
                return;
            };
            at = child as usize;
        }
        for l in 1..=d.depth {
            if d.splits_at_ratio(l) {
                let Some(first) = self.split_at_ratio(at, d.ratio()) else {
                    return;
                };
                at = first as usize + usize::from(d.step(l));
                continue;
            }
            if d.splits_in_halves(l) {
                let Some(first) = self.split_in_halves(at, d.step(l) / 2) else {
                    return;
                };
                at = first as usize + usize::from(d.step(l) % 2);
                continue;
            }
            let first = match self.nodes[at] {
                Node::Leaf(_)
                | Node::SplitAt { .. }
                | Node::Halves { .. }
                | Node::Frames { .. } => {
                    return;
                }
                // a cell split the other way (dyadic vs in thirds) by an earlier domain:
                // the first indexed wins, as for a covered cell
                Node::Split { first, factor } if factor == factor_of(d, l) => first,
                Node::Split { .. } => return,
                Node::Empty => {
                    let f = factor_of(d, l);
                    let first = self.nodes.len() as u32;
                    let count = usize::from(f) * usize::from(f);
                    self.nodes.extend(std::iter::repeat_n(Node::Empty, count));
                    self.nodes[at] = Node::Split { first, factor: f };
                    first
                }
            };
            at = first as usize + usize::from(d.step(l));
        }
        if !matches!(self.nodes[at], Node::Leaf(_)) {
            let maps = self.maps_of(d, window);
            self.nodes[at] = Node::Leaf(self.leaves.len() as u32);
            self.leaves.push(Leaf {
                patch,
                source,
                maps,
                shape: d.shape,
                criss_cross: d.criss_cross_triangle(),
            });
        }
    }

    /// The index of the maps of a leaf of domain `d` (and `window`): shared by the root cells
    /// of one shape and corner without a frame or window, whose maps depend on nothing else.
    fn maps_of(&mut self, d: &Domain, window: Option<Affine>) -> u32 {
        let root = d.depth == 0 && d.frame == Frame::NONE && window.is_none() && d.rot < 8;
        let slot = (d.shape == Shape::Triangle) as usize;
        if root && let Some(i) = self.root_maps[slot][d.rot as usize] {
            return i;
        }
        let i = self.maps.len() as u32;
        self.maps.push(LeafMaps::new(d, window));
        if root {
            self.root_maps[slot][d.rot as usize] = Some(i);
        }
        i
    }

    /// Every leaf with its domain that a point of its cell finds (a leaf hidden below a
    /// shallower covered cell is left out), and its root cell.
    pub fn reachable_leaves<'a>(
        &'a self,
        complex: &'a PatchComplex,
    ) -> impl Iterator<Item = (&'a Leaf, Domain)> + 'a {
        self.leaves.iter().filter_map(move |leaf| {
            let d = leaf.domain(complex);
            let centre = match d.shape {
                Shape::Quad => [0.5, 0.5],
                Shape::Triangle => [1.0 / 3.0, 1.0 / 3.0],
            };
            let p = d.cell_map().apply(centre);
            let sub = if self.root_count(d.face) == 1 {
                0
            } else {
                d.sub
            };
            let (found, _) = self.locate(d.face, sub, d.shape, p)?;
            std::ptr::eq(found, leaf).then_some((leaf, d))
        })
    }

    /// Number of root cells of `face` (1, or its sub-faces).
    fn root_count(&self, face: u32) -> u32 {
        let f = face as usize;
        match (self.root.get(f), self.root.get(f + 1)) {
            (Some(a), Some(b)) => b - a,
            _ => 0,
        }
    }

    /// The maps of `leaf`.
    #[inline]
    pub fn maps(&self, leaf: &Leaf) -> &LeafMaps {
        &self.maps[leaf.maps as usize]
    }

    /// The first child of node `at` split at ratio `t` (splitting it when empty); `None` when
    /// it is covered or split another way (the first indexed wins).
    fn split_at_ratio(&mut self, at: usize, t: f64) -> Option<u32> {
        match self.nodes[at] {
            Node::SplitAt { first, ratio } if self.ratios[ratio as usize].0 == t => Some(first),
            Node::Empty => {
                let ratio = match self.ratios.iter().position(|r| r.0 == t) {
                    Some(i) => i,
                    None => {
                        let maps =
                            std::array::from_fn(|k| ChildInverse::of(Shape::ratio_map(t, k as u8)));
                        self.ratios.push((t, maps));
                        self.ratios.len() - 1
                    }
                };
                let first = self.nodes.len() as u32;
                self.nodes.extend(std::iter::repeat_n(Node::Empty, 4));
                self.nodes[at] = Node::SplitAt {
                    first,
                    ratio: ratio as u32,
                };
                Some(first)
            }
            _ => None,
        }
    }

    /// The first child of node `at` halved along `axis` (halving it when empty); `None` when
    /// it is covered or split another way (the first indexed wins).
    fn split_in_halves(&mut self, at: usize, axis: u8) -> Option<u32> {
        match self.nodes[at] {
            Node::Halves { first, axis: a } if a == axis => Some(first),
            Node::Empty => {
                let first = self.nodes.len() as u32;
                self.nodes.extend(std::iter::repeat_n(Node::Empty, 2));
                self.nodes[at] = Node::Halves { first, axis };
                Some(first)
            }
            _ => None,
        }
    }

    /// The leaf covering point `p` of root cell `sub` of `face` (cell coordinates of the
    /// sub-face), and `p` in the leaf's cell coordinates; `None` where no patch covers it.
    #[inline]
    pub fn locate(
        &self,
        face: u32,
        sub: u32,
        shape: Shape,
        mut p: [f64; 2],
    ) -> Option<(&Leaf, [f64; 2])> {
        let mut at = *self.root.get(face as usize)? as usize + sub as usize;
        loop {
            match *self.nodes.get(at)? {
                Node::Leaf(i) => return Some((&self.leaves[i as usize], p)),
                Node::Empty => return None,
                Node::Split { first, factor: 2 } => {
                    let k = shape.child_at(p);
                    let maps = match shape {
                        Shape::Quad => &self.quad,
                        Shape::Triangle => &self.triangle,
                    };
                    p = maps[usize::from(k)].apply(p);
                    at = first as usize + usize::from(k);
                }
                Node::Split { first, factor: 3 } => {
                    let k = Shape::third_at(p);
                    p = self.third[usize::from(k)].apply(p);
                    at = first as usize + usize::from(k);
                }
                Node::SplitAt { first, ratio } => {
                    let (t, maps) = &self.ratios[ratio as usize];
                    let k = Shape::ratio_at(*t, p);
                    p = maps[usize::from(k)].apply(p);
                    at = first as usize + usize::from(k);
                }
                Node::Halves { first, axis } => {
                    let k = Shape::half_at(axis, p);
                    p = self.halves[usize::from(k)].apply(p);
                    at = first as usize + usize::from(k % 2);
                }
                Node::Frames { set } => {
                    let (node, inv) = self.frames[set as usize].find(p)?;
                    p = inv.apply(p);
                    at = node as usize;
                }
                Node::Split { .. } => return None,
            }
        }
    }
}
