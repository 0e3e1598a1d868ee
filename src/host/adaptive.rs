//! The one adaptive level loop behind every scheme whose exact surface is read off a partially
//! refined net (Catmull-Clark with or without caps, Doo-Sabin, Loop, non-box), and the
//! bookkeeping those schemes share: the trust of the points of a partially refined level, the
//! tags of active cells, the selection of the faces refined around marked cells, and the edge
//! curves shared by neighbouring cells.
//!
//! A scheme plugs in through [`AdaptiveRules`]: which cells are regular and what their patches
//! are, how a marked cell is tagged, how the faces around marked cells are refined, and how the
//! hole left after the last level is filled. [`run`] is the loop: at level `l` every active
//! cell that is regular and trusted becomes patches of ring `l` (regular at level 0), the rest
//! is refined with its neighbourhood, until the rings are done.

pub use super::fans::{
    QuadSector, quad_hole_segments, quad_sectors_around, quad_sectors_between, quad_sectors_open,
};
use crate::bezier::complex::{Domain, PatchComplex, Provenance};
use crate::error::Result;
use crate::geom::Point;
use crate::mesh::{Element, PolyMesh};
use std::collections::HashMap;

pub use super::ComplexOptions;

mod g1_caps;
mod trust;
pub use g1_caps::{
    CapData, MAX_EXTRA_CAP_LEVELS, NoCap, RingTargets, caps_waiting, fan_centre, fan_centre_from,
    g1_cap_elements, hole_centre, honour_ring_targets, with_ring_targets,
};
pub(crate) use trust::SplitTrust;

/// A scheme's rules for the adaptive loop ([`run`]).
pub trait AdaptiveRules {
    /// One level: the partially refined net, the trust of its points, its active cells.
    type Level: Cells;
    /// The edge curves of the cells emitted at one level, which the fill shares.
    type Curves: Default;

    /// Level 0 from the input net (errors name what the scheme cannot take).
    fn start(&self, mesh: &PolyMesh, opts: ComplexOptions) -> Result<Self::Level>;

    /// Pushes the patches of `cell` with provenance `prov` (recording its edge curves) when the
    /// cell is regular and all its control points are trusted; `false` otherwise.
    fn emit(
        &self,
        level: &Self::Level,
        cell: u32,
        prov: Provenance,
        to: Sink<Self::Curves>,
    ) -> bool;

    /// Emits every active cell of `level` (level `l`) that [`AdaptiveRules::emit`] takes, in
    /// order, each patch with its cell's domain, and returns the others (the marked cells) in
    /// order. The default calls `emit` per cell; a scheme may override it to compute the
    /// patches in parallel and push them in the same order (the same complex).
    fn emit_all(
        &self,
        level: &Self::Level,
        l: usize,
        curves: &mut Self::Curves,
        out: &mut PatchComplex,
    ) -> Vec<(u32, Tag)> {
        let mut marked: Vec<(u32, Tag)> = Vec::new();
        for &(f, tag) in level.active() {
            let first = out.len();
            let to = Sink {
                curves: &mut *curves,
                out: &mut *out,
            };
            if self.emit(level, f, provenance(l, tag), to) {
                for i in first..out.len() {
                    out.set_domain(i, tag.domain);
                }
            } else {
                marked.push((f, tag));
            }
        }
        marked
    }

    /// The tag of a cell that is not emitted at level `l`.
    fn retag(&self, level: &Self::Level, cell: u32, tag: Tag, l: usize) -> Tag;

    /// The tags of all cells not emitted at level `l`, in order. The default asks
    /// [`AdaptiveRules::retag`] for each; a scheme whose retag walks a vertex's fan overrides it
    /// to walk each fan once (else a vertex of valence n costs n^2).
    fn retag_all(&self, level: &Self::Level, cells: Vec<(u32, Tag)>, l: usize) -> Vec<(u32, Tag)> {
        cells
            .into_iter()
            .map(|(f, tag)| (f, self.retag(level, f, tag, l)))
            .collect()
    }

    /// Replaces marked cells by caps built from local nets (Catmull-Clark's caps of EG, QAS+ and
    /// guided subdivision); returns the cells left. The default caps nothing.
    fn caps(
        &self,
        level: &Self::Level,
        marked: Vec<(u32, Tag)>,
        l: usize,
        out: &mut PatchComplex,
    ) -> Result<Vec<(u32, Tag)>> {
        let _ = (level, l, out);
        Ok(marked)
    }

    /// Whether level `l` is the last (default: `l == rings`).
    fn is_last(&self, l: usize, rings: usize, level: &Self::Level, marked: &[(u32, Tag)]) -> bool {
        let _ = (level, marked);
        l == rings
    }

    /// Closes the hole of the marked cells of the last level.
    fn fill(
        &self,
        level: &Self::Level,
        marked: &[(u32, Tag)],
        to: Sink<Self::Curves>,
    ) -> Result<()>;

    /// Refines the marked cells with their neighbourhood: the next level, whose active cells are
    /// the children of the marked ones.
    fn refine_around(&self, level: &Self::Level, marked: &[(u32, Tag)]) -> Result<Self::Level>;
}

/// The adaptive loop: the patch complex of `mesh` under `rules`. `progress(level)` is called
/// after each refinement.
pub fn run<R: AdaptiveRules + ?Sized>(
    rules: &R,
    mesh: &PolyMesh,
    opts: ComplexOptions,
    progress: &mut dyn FnMut(usize),
) -> Result<PatchComplex> {
    let mut out = PatchComplex::new();
    let mut level = rules.start(mesh, opts)?;
    for l in 0.. {
        let mut curves = R::Curves::default();
        let mut marked = rules.emit_all(&level, l, &mut curves, &mut out);
        marked = rules.retag_all(&level, marked, l);
        marked = rules.caps(&level, marked, l, &mut out)?;
        if marked.is_empty() {
            break;
        }
        if rules.is_last(l, opts.rings, &level, &marked) {
            if opts.fill {
                let to = Sink {
                    curves: &mut curves,
                    out: &mut out,
                };
                rules.fill(&level, &marked, to)?;
            }
            break;
        }
        level = rules.refine_around(&level, &marked)?;
        progress(l + 1);
    }
    Ok(out)
}

/// A level's active cells, which [`run`] makes patches of or marks.
pub trait Cells {
    /// The cells still to be made patches at this level, with their tags.
    fn active(&self) -> &[(u32, Tag)];
}

/// The marked cells of one extraordinary element (`None`: cells of no element).
pub type Group = (Option<Element>, Vec<(u32, Tag)>);

/// The marked cells grouped by element, in order of first appearance (the caps of
/// [`crate::bezier::g1`] close one element's hole at a time).
pub fn by_element(marked: &[(u32, Tag)]) -> Vec<Group> {
    let mut index: HashMap<Option<Element>, usize> = HashMap::new();
    let mut groups: Vec<Group> = Vec::new();
    for &(f, tag) in marked {
        let k = *index.entry(tag.element).or_insert_with(|| {
            groups.push((tag.element, Vec::new()));
            groups.len() - 1
        });
        groups[k].1.push((f, tag));
    }
    groups
}

/// Where a level's patches go: the complex being built and the level's edge curves.
pub struct Sink<'a, C> {
    /// The edge curves of the cells emitted at this level.
    pub curves: &'a mut C,
    /// The complex.
    pub out: &'a mut PatchComplex,
}

/// A level of a scheme whose cells are the faces of a partially refined mesh (Catmull-Clark,
/// Loop): the mesh, the trust of its vertices and its active faces.
pub struct MeshLevel {
    /// The partially refined mesh.
    pub mesh: PolyMesh,
    /// The trust of its vertices.
    pub info: Vec<Info>,
    /// Faces to process at this level, with their tags.
    pub active: Vec<(u32, Tag)>,
}

impl MeshLevel {
    /// Level 0 of an input net: every vertex trusted, every face active and untagged.
    pub fn input(mesh: &PolyMesh) -> MeshLevel {
        // the copy of the mesh beside the cells (both fresh memory, about 1 and 4 ms on a
        // net of 100k faces)
        let (mesh_copy, active) = rayon::join(|| mesh.clone(), || input_active_in(mesh));
        MeshLevel {
            mesh: mesh_copy,
            info: input_vertex_info(mesh.num_vertices()),
            active,
        }
    }
}

impl Cells for MeshLevel {
    fn active(&self) -> &[(u32, Tag)] {
        &self.active
    }
}

/// Trust of a point of a partially refined level.
#[derive(Debug, Clone, Copy)]
pub struct Info {
    /// The position equals the one of full refinement.
    pub pos_ok: bool,
    /// (Vertices) the faces around it are all present, so its one-ring is the true one.
    pub fan_ok: bool,
    /// Input element this point descends from: an input vertex by vertex points, or an
    /// extraordinary face by its centre (Catmull-Clark) or FCV (non-box); Doo-Sabin sets it at
    /// level 0 only, where it names the V-face of level 1.
    pub origin: Option<Element>,
}

/// Extraordinary element and sector of an active cell, and its input face.
#[derive(Debug, Clone, Copy)]
pub struct Tag {
    /// The extraordinary element the cell belongs to, if any.
    pub element: Option<Element>,
    /// The cell's sector around that element.
    pub sector: u32,
    /// The input face the cell descends from.
    pub input_face: u32,
    /// The part of the input face the cell covers ([`Domain::UNTRACKED`] where the scheme does
    /// not track it); the scheme's `refine_around` gives each child its [`Domain::child`].
    pub domain: Domain,
}

/// The trust of the `n` vertices of an input net: all trusted, each its own origin.
pub fn input_vertex_info(n: usize) -> Vec<Info> {
    (0..n)
        .map(|v| Info {
            pos_ok: true,
            fan_ok: true,
            origin: Some(Element::Vertex(v as u32)),
        })
        .collect()
}

/// The active cells of an input net with `n` faces: every face, untagged.
pub fn input_active(n: usize) -> Vec<(u32, Tag)> {
    (0..n as u32).map(|f| (f, untagged(f))).collect()
}

/// The tag of input face `f` as a cell of level 0: no element, its domain untracked.
fn untagged(f: u32) -> Tag {
    Tag {
        element: None,
        sector: 0,
        input_face: f,
        domain: Domain::UNTRACKED,
    }
}

/// The active cells of an input net: every face, untagged, each covering its whole
/// [`Domain::face`] (for schemes whose cells lie in input faces and whose `refine_around` tracks
/// the children's domains).
pub fn input_active_in(mesh: &PolyMesh) -> Vec<(u32, Tag)> {
    use rayon::prelude::*;
    // one pass, in parallel: a cell is 160 bytes, and on a net of 100k faces the serial
    // two passes over fresh memory were 4 ms of the construction's serial start
    (0..mesh.num_faces() as u32)
        .into_par_iter()
        .map(|f| {
            let tag = Tag {
                domain: Domain::face(f, mesh.face_size(f as usize)),
                ..untagged(f)
            };
            (f, tag)
        })
        .collect()
}

/// The provenance of a cell with tag `tag` emitted at level `l`: regular at level 0 or without
/// an element, otherwise ring `l` of its element.
pub fn provenance(l: usize, tag: Tag) -> Provenance {
    match (l, tag.element) {
        (0, _) | (_, None) => Provenance::Regular {
            face: tag.input_face,
        },
        (_, Some(element)) => Provenance::Ring {
            element,
            ring: l as u32,
            sector: tag.sector,
        },
    }
}

/// Positions of faces in the fans of vertices, each fan walked once: the sector of a cell at an
/// extraordinary corner without a walk of that corner's whole fan per cell (which costs n^2 at
/// a vertex of valence n).
#[derive(Debug, Default)]
pub struct FanSectors(HashMap<u32, HashMap<u32, u32>>);

impl FanSectors {
    /// The position of face `f` in the fan of `v` (the first, if `f` comes twice), 0 if `f` is
    /// not in that fan.
    pub fn sector(&mut self, m: &PolyMesh, v: u32, f: u32) -> u32 {
        let fan = self.0.entry(v).or_insert_with(|| {
            let mut at = HashMap::new();
            for (i, g) in m.outgoing(v as usize).map(|h| m.he_face(h)).enumerate() {
                at.entry(g).or_insert(i as u32);
            }
            at
        });
        fan.get(&f).copied().unwrap_or(0)
    }
}

/// The tags of `cells` by `retag`, with one [`FanSectors`] memo shared by all of them (for
/// [`AdaptiveRules::retag_all`]).
pub fn retag_with_fans(
    cells: Vec<(u32, Tag)>,
    mut retag: impl FnMut(u32, Tag, &mut FanSectors) -> Tag,
) -> Vec<(u32, Tag)> {
    let mut fans = FanSectors::default();
    cells
        .into_iter()
        .map(|(f, tag)| (f, retag(f, tag, &mut fans)))
        .collect()
}

/// The tag of a marked cell `f`: its first corner that descends from an input element and is
/// not regular (by `is_regular`) gives the element, sector = the cell's position in that
/// vertex's fan (looked up in `fans`); otherwise (or if the element is already the tag's) the
/// inherited tag.
pub fn retag_by_corners(
    m: &PolyMesh,
    info: &[Info],
    f: usize,
    tag: Tag,
    is_regular: impl Fn(&PolyMesh, usize) -> bool,
    fans: &mut FanSectors,
) -> Tag {
    for &v in m.face(f) {
        if let Some(origin) = info[v as usize].origin
            && !is_regular(m, v as usize)
        {
            if tag.element == Some(origin) {
                return tag;
            }
            return Tag {
                element: Some(origin),
                sector: fans.sector(m, v, f as u32),
                ..tag
            };
        }
    }
    tag
}

/// The faces around the corners of the marked cells: a selection flag per face and the
/// selected faces in increasing order.
pub fn select_around(m: &PolyMesh, marked: &[(u32, Tag)]) -> (Vec<bool>, Vec<u32>) {
    let (sel, mut sel_faces) = select_rings(m, marked, 1);
    sel_faces.sort_unstable();
    (sel, sel_faces)
}

/// The marked cells and the faces within `rings` vertex-rings of them: a selection flag per
/// face and the selected faces in the order found. Each vertex's fan is walked once, so the
/// cost is linear in the selection also around a vertex of high valence.
pub fn select_rings(m: &PolyMesh, marked: &[(u32, Tag)], rings: usize) -> (Vec<bool>, Vec<u32>) {
    let mut sel = vec![false; m.num_faces()];
    let mut walked = vec![false; m.num_vertices()];
    let mut sel_faces: Vec<u32> = Vec::new();
    for &(f, _) in marked {
        if !sel[f as usize] {
            sel[f as usize] = true;
            sel_faces.push(f);
        }
    }
    let mut start = 0;
    for _ in 0..rings {
        let end = sel_faces.len();
        for i in start..end {
            for &v in m.face(sel_faces[i] as usize) {
                if std::mem::replace(&mut walked[v as usize], true) {
                    continue;
                }
                for h in m.outgoing(v as usize) {
                    let g = m.he_face(h);
                    if !sel[g as usize] {
                        sel[g as usize] = true;
                        sel_faces.push(g);
                    }
                }
            }
        }
        start = end;
    }
    (sel, sel_faces)
}

/// The active cells of the next level: the children `first .. first + count` of every marked
/// cell (`children(f) = (first, count)`), each with its parent's tag.
pub fn child_active(
    marked: &[(u32, Tag)],
    children: impl Fn(u32) -> (u32, u32),
) -> Vec<(u32, Tag)> {
    let mut active = Vec::new();
    for &(f, tag) in marked {
        let (first, count) = children(f);
        for c in first..first + count {
            active.push((c, tag));
        }
    }
    active
}

/// Edge curves keyed by vertex pairs `(min, max)`, oriented from the smaller vertex.
pub type Curves<const N: usize> = HashMap<(u32, u32), [Point; N]>;

/// Stores the curve `e` of edge `a -> b` unless the edge already has one.
pub fn record_edge<const N: usize>(curves: &mut Curves<N>, a: u32, b: u32, mut e: [Point; N]) {
    if a > b {
        e.reverse();
    }
    curves.entry((a.min(b), a.max(b))).or_insert(e);
}

/// The curve of edge `a -> b`: the stored one, else `make(min, max)` (oriented from the smaller
/// vertex), which is then stored.
pub fn edge_curve<const N: usize>(
    curves: &mut Curves<N>,
    a: u32,
    b: u32,
    make: impl FnOnce(usize, usize) -> [Point; N],
) -> [Point; N] {
    let key = (a.min(b), a.max(b));
    let mut e = *curves
        .entry(key)
        .or_insert_with(|| make(key.0 as usize, key.1 as usize));
    if a > b {
        e.reverse();
    }
    e
}
