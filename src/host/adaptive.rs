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

/// The hole data of one element's G^1 cap: the hole (centre set), two vectors spanning its
/// limit tangent plane (normal `plane[0] x plane[1]`; both linear in the control points, so a
/// patch stencil table can tabulate them), and the tag of each sector's cell in the hole's
/// sector order.
pub type CapData = (crate::bezier::g1::Hole, [Point; 2], Vec<Tag>);

/// Closes with the G^1 cap of [`crate::bezier::g1`] (spoke tangents from the ring's chart,
/// [`crate::bezier::g1::ring::cap_from_plane`]) every element of the marked cells for which
/// `hole_of` gives the data (one hole, or several: the sectors of a crease vertex, capped all
/// or none); the cap patches are pushed with the sectors' tags (domain and
/// sector), and the cap's data as a [`crate::bezier::complex::CapStep`] of the complex. Returns the cells left for the
/// scheme's C^0 fill. The elements' caps are independent: they are computed in parallel and
/// pushed in the elements' order (the same complex as one after another). An element whose
/// hole data exist but whose cap cannot be built is recorded with the reason in
/// [`PatchComplex::uncapped`] (the user is told; the fill closes it).
pub fn g1_cap_elements<I>(
    marked: &[(u32, Tag)],
    out: &mut PatchComplex,
    hole_of: impl Fn(Element, &[(u32, Tag)]) -> I + Sync,
) -> Vec<(u32, Tag)>
where
    I: IntoIterator<Item = CapData>,
{
    use crate::bezier::g1::{CapOptions, ring::cap_step};
    use rayon::prelude::*;
    let groups = by_element(marked);
    let caps: Vec<_> = groups
        .par_iter()
        .map(|(element, cells)| {
            let e = (*element)?;
            // an element's holes (one, or one per sector of a crease vertex): all or none
            let mut built = Vec::new();
            for (hole, plane, tags) in hole_of(e, cells) {
                match cap_step(hole, plane, CapOptions::default(), 0) {
                    Ok((patches, step)) => built.push((patches, tags, step)),
                    Err(why) => return Some(Err((e, why.to_string()))),
                }
            }
            (!built.is_empty()).then_some(Ok((e, built)))
        })
        .collect();
    let mut left = Vec::new();
    for ((_, cells), capped) in groups.into_iter().zip(caps) {
        let (element, built) = match capped {
            Some(Ok(c)) => c,
            Some(Err(why)) => {
                // the hole is there and the cap failed: the fill closes it, the user is told
                out.uncapped.push(why);
                left.extend(cells);
                continue;
            }
            None => {
                left.extend(cells);
                continue;
            }
        };
        for (patches, tags, mut step) in built {
            let first = out.len();
            step.first = first as u32;
            let sharp_ends = step.hole.fan().hermite_ends();
            out.caps.push(step);
            let count = patches.len();
            for (p, tag) in patches.into_iter().zip(tags) {
                let sector = tag.sector;
                out.push_in(p, Provenance::Cap { element, sector }, tag.domain);
            }
            if sharp_ends {
                // a crease's or a dart's fan: its boundary spokes lie on the sharp edge
                out.mark_sharp(first, crate::bezier::Side::V0.index());
                out.mark_sharp(first + count - 1, crate::bezier::Side::U0.index());
            }
        }
    }
    left
}

/// Per-element ring counts of one construction: the limit surface's evaluation
/// ([`crate::surface::eval::limit_surface`]) refines each extraordinary element only as far as
/// its own points need. Rules that honour them (Catmull-Clark without a scheme's caps) close
/// an element's hole from the level of its count on (its rings are the same patches as with
/// that many rings for all); the others build `max` rings everywhere. Passed down through
/// [`with_ring_targets`] (the construction's options are shared by every scheme and caller).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RingTargets {
    /// Rings of the elements not in `per`.
    pub base: usize,
    /// Rings per element.
    pub per: HashMap<Element, usize>,
}

impl RingTargets {
    /// The rings of `element` (`base` for none or an unlisted one).
    pub fn of(&self, element: Option<Element>) -> usize {
        element
            .and_then(|e| self.per.get(&e).copied())
            .unwrap_or(self.base)
    }

    /// The most rings of any element.
    pub fn max(&self) -> usize {
        self.per.values().copied().fold(self.base, usize::max)
    }
}

thread_local! {
    static RING_TARGETS: std::cell::RefCell<Option<(std::sync::Arc<RingTargets>, bool)>> =
        const { std::cell::RefCell::new(None) };
}

/// Runs `f` (a construction on this thread) with the per-element ring counts `targets`, and
/// says whether it honoured them ([`honour_ring_targets`]). Call it outside rayon jobs (as the
/// CLI and the tests do): a worker stealing another construction inside `f` would pass it on.
pub fn with_ring_targets<T>(
    targets: std::sync::Arc<RingTargets>,
    f: impl FnOnce() -> T,
) -> (T, bool) {
    let old = RING_TARGETS.with(|t| t.replace(Some((targets, false))));
    let out = f();
    let honoured = RING_TARGETS
        .with(|t| std::mem::replace(&mut *t.borrow_mut(), old))
        .is_some_and(|(_, h)| h);
    (out, honoured)
}

/// The per-element ring counts of the construction running on this thread, if any, noted as
/// honoured: rules that close each element's hole from its own count on call this.
pub fn honour_ring_targets() -> Option<std::sync::Arc<RingTargets>> {
    RING_TARGETS.with(|t| {
        let mut t = t.borrow_mut();
        t.as_mut().map(|(targets, honoured)| {
            *honoured = true;
            targets.clone()
        })
    })
}

/// Levels computed beyond the requested rings, at most, so that holes that still touch
/// separate and get their G^1 caps (Catmull-Clark, the dual bi-2 schemes, non-box).
pub const MAX_EXTRA_CAP_LEVELS: usize = 2;

/// Why an element has no G^1 cap at a level.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoCap {
    /// More levels would give the data (the element's hole touches another element's).
    Later,
    /// The element's hole never gets the data (boundary, non-quad faces, no single centre).
    Never,
}

/// The centre of an element's hole: the corner of its marked cell `f0` that descends from
/// `element`, and its valence; `NoCap::Never` when there is none, it lies on the boundary or
/// its valence is below 3 (the checks every vertex-centred cap provider starts with).
pub fn hole_centre(
    m: &PolyMesh,
    info: &[Info],
    element: Element,
    f0: u32,
) -> std::result::Result<(u32, usize), NoCap> {
    match fan_centre(m, info, element, f0, 3)? {
        (x, n, false) => Ok((x, n)),
        _ => Err(NoCap::Never),
    }
}

/// [`hole_centre`] that also takes a boundary vertex: the centre, its number of sectors (the
/// valence of an interior vertex, the number of faces, valence - 1, of a boundary vertex) and
/// whether the fan is open (on the boundary); `NoCap::Never` below 3 sectors, or below
/// `min_open` sectors of an open fan (2 for a fan of triangles, whose two sectors span a
/// right angle each in the chart).
pub fn fan_centre(
    m: &PolyMesh,
    info: &[Info],
    element: Element,
    f0: u32,
    min_open: usize,
) -> std::result::Result<(u32, usize, bool), NoCap> {
    fan_centre_from(m, info, element, f0, (min_open, 3))
}

/// [`fan_centre`] with the fewest sectors of an open and of a closed fan: `(min_open, 2)`
/// for the providers that close a valence-2 vertex with the half-plane cap of two quad
/// sectors ([`crate::bezier::g1`], "Two sectors").
pub fn fan_centre_from(
    m: &PolyMesh,
    info: &[Info],
    element: Element,
    f0: u32,
    (min_open, min_closed): (usize, usize),
) -> std::result::Result<(u32, usize, bool), NoCap> {
    let x = m
        .face(f0 as usize)
        .iter()
        .copied()
        .find(|&v| info[v as usize].origin == Some(element))
        .ok_or(NoCap::Never)?;
    let n = m.valence(x as usize);
    let open = m.is_boundary_vertex(x as usize);
    let sectors = if open { n - 1 } else { n };
    if sectors < if open { min_open } else { min_closed } {
        return Err(NoCap::Never);
    }
    Ok((x, sectors, open))
}

/// Whether some element of the marked cells would get its G^1 cap after more levels (`hole`
/// says `NoCap::Later` for it): the adaptive loop then goes on.
pub fn caps_waiting<T>(
    marked: &[(u32, Tag)],
    mut hole: impl FnMut(Element, &[(u32, Tag)]) -> std::result::Result<T, NoCap>,
) -> bool {
    by_element(marked).iter().any(|(e, cells)| match e {
        Some(e) => matches!(hole(*e, cells), Err(NoCap::Later)),
        None => false,
    })
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
