//! OpenSubdiv's sharp features on the levels of the adaptive loop ([`crate::host::adaptive`]),
//! written once for the patch output of Catmull-Clark and Loop.
//!
//! A [`Level`] of either scheme's adaptive refinement carries its sharpness twice: as the
//! mesh's extras (already sharpened, so that the scheme's rules refine the partial level
//! exactly as `--levels` refines the whole net) and in dense arrays ([`Features`]). This module
//! holds what does not depend on the faces' shape:
//!
//! * the start level ([`start`]) and the child level's sharpness ([`child`]: edge halves by
//!   OpenSubdiv's subdivision of sharpness, vertex sharpness decremented, the edges where the
//!   partial refinement stops infinitely sharp);
//! * the *sector* of a face's corner ([`sector`]): the faces between the infinitely sharp
//!   (or boundary) edges around the corner and the corner's rule. A scheme's regular patch
//!   needs every corner's sector to be its regular smooth, crease or corner configuration
//!   (four quads, two quads, one quad for Catmull-Clark; six, three, one triangles for Loop);
//!   semi-sharp features never are, they are refined until spent;
//! * the trust of edge points under semi-sharp rules ([`edge_known`]), holes ([`is_hole`]),
//!   the vertices with a feature ([`is_special`], [`chord_vertices`]);
//! * the exact limit curve of an infinitely sharp edge between two crease or corner vertices
//!   ([`crease_curve`]: the uniform cubic B-spline of the crease polygon, which the fills of
//!   both schemes take), and the marking of patch sides on such edges as sharp joins
//!   ([`mark_sides`]).

use crate::bezier::Side;
use crate::bezier::complex::PatchComplex;
use crate::geom::{self, Point};
use crate::host::adaptive::{Cells, MeshLevel, Tag};
use crate::mesh::tags::SubdOptions;
use crate::mesh::{Extras, PolyMesh, SharpEdges};

use super::{INFINITE, Rule, Scratch, SharpLevel, classify, decrement};

mod side_caps;
mod sides;
pub(crate) use side_caps::*;
pub(crate) use sides::*;

/// One level of the adaptive refinement of a mesh-based scheme with OpenSubdiv's features.
pub struct Level {
    /// The mesh, trust and active faces, as for every mesh-based scheme.
    pub(crate) base: MeshLevel,
    /// The level's sharp features, when the net has them.
    pub(crate) sharp: Option<Features>,
    /// When the construction tracks its patch table: the stencils of the level's points over
    /// the previous level's points (the refinement's own table; `None` at level 0), taken by
    /// the tracker.
    pub(crate) rows: Option<crate::stencil::StencilTable>,
}

impl std::ops::Deref for Level {
    type Target = MeshLevel;
    fn deref(&self) -> &MeshLevel {
        &self.base
    }
}

impl Cells for Level {
    fn active(&self) -> &[(u32, Tag)] {
        &self.base.active
    }
}

impl Level {
    /// Level 0 of `mesh`: with its sharp features under `subd` ([`start`]), or plain when the
    /// plain rules give the same surface (or `subd` is `None`).
    pub(crate) fn input(mesh: &PolyMesh, subd: Option<&SubdOptions>) -> Level {
        match subd.and_then(|o| start(mesh, o)) {
            Some((m, s)) => Level {
                base: MeshLevel::input(&m),
                sharp: Some(s),
                rows: None,
            },
            None => Level {
                base: MeshLevel::input(mesh),
                sharp: None,
                rows: None,
            },
        }
    }

    /// OpenSubdiv's options of the level's rules (the defaults without features).
    pub(crate) fn options(&self) -> SubdOptions {
        self.sharp.as_ref().map(|s| s.opts).unwrap_or_default()
    }
}

/// The sharp features of one level of the adaptive loop.
pub struct Features {
    /// OpenSubdiv's options (the crease method, smooth triangles).
    pub(crate) opts: SubdOptions,
    /// Sharpness per edge of the level's mesh.
    pub(crate) edges: Vec<f32>,
    /// Sharpness per vertex.
    pub(crate) vertices: Vec<f32>,
    /// Hole faces of the level: the input's hole faces and, on later levels, their
    /// descendants (never active: they exist as neighbours of active faces, and tell the G^1
    /// caps which sectors around a vertex are cut away).
    hole: Vec<bool>,
    /// Levels since the last one that held a finite (semi-sharp) sharpness: 0 at such a
    /// level, [`CALM`] when no level did. Holes that wait for their ring get their extra
    /// levels counted from there ([`is_last_cap_level`]).
    pub(crate) calm: usize,
}

/// [`Features::calm`] of a level after no semi-sharp one.
pub(crate) const CALM: usize = usize::MAX / 2;

/// [`Features::calm`] of a level with these sharpness values after a level with `parent`
/// (the dual bi-2 schemes and non-box count their levels the same way).
pub(crate) fn calm_after(parent: usize, edges: &[f32], vertices: &[f32]) -> usize {
    if edges.iter().chain(vertices).any(|&s| is_semi(s)) {
        0
    } else {
        parent.saturating_add(1).min(CALM)
    }
}

/// Whether a sharpness value is infinitely sharp.
pub(crate) fn is_inf(s: f32) -> bool {
    s >= INFINITE
}

/// Whether a sharpness value is semi-sharp.
pub(crate) fn is_semi(s: f32) -> bool {
    s > 0.0 && s < INFINITE
}

/// Level 0 with sharp features: the net with its sharpened extras and their arrays, or `None`
/// when the plain rules give the same surface (no feature, edge-and-corner boundaries).
pub(crate) fn start(mesh: &PolyMesh, opts: &SubdOptions) -> Option<(PolyMesh, Features)> {
    let SharpLevel {
        edges,
        vertices,
        holes,
        ..
    } = SharpLevel::new(mesh, opts)?;
    let mut hole = vec![false; mesh.num_faces()];
    for &f in &holes {
        hole[f as usize] = true;
    }
    let extras = Extras {
        sharp_edges: SharpEdges::ById(
            (0..edges.len() as u32)
                .filter(|&e| edges[e as usize] > 0.0)
                .map(|e| (e, edges[e as usize]))
                .collect(),
        ),
        sharp_vertices: (0..vertices.len() as u32)
            .filter(|&v| vertices[v as usize] > 0.0)
            .map(|v| (v, vertices[v as usize]))
            .collect(),
        holes,
        sharpened: true,
        ..Extras::default()
    };
    let features = Features {
        opts: *opts,
        calm: calm_after(CALM, &edges, &vertices),
        edges,
        vertices,
        hole,
    };
    Some((mesh.clone().with_extras(Some(extras)), features))
}

/// Whether face `f` of `level` is a hole (consumed without a patch).
pub(crate) fn is_hole(level: &Level, f: usize) -> bool {
    level
        .sharp
        .as_ref()
        .is_some_and(|s| s.hole.get(f).copied().unwrap_or(false))
}

/// The edges at `v`: one per outgoing half-edge, and the incoming boundary edge.
fn spoke_edges(m: &PolyMesh, v: usize) -> Vec<u32> {
    let hs = m.outgoing_halfedges(v);
    let mut out: Vec<u32> = hs.iter().map(|&h| m.he_edge(h)).collect();
    if let Some(&last) = hs.last()
        && m.is_boundary_vertex(v)
    {
        out.push(m.he_edge(m.he_prev(last)));
    }
    out
}

/// Whether a vertex of the c-net `idx` has a sharp feature ([`is_special`]) or one of
/// its faces is a hole: the cap schemes' rules then do not apply.
pub(crate) fn touches_features(level: &Level, idx: &[u32]) -> bool {
    level.sharp.is_some()
        && idx.iter().any(|&w| {
            let w = w as usize;
            is_special(level, w)
                || level
                    .mesh
                    .vertex_faces(w)
                    .iter()
                    .any(|&f| is_hole(level, f as usize))
        })
}

/// Whether vertex `v` of `level` has a sharp feature (a sharp incident edge, boundary edges
/// included, or sharpness of its own): its limit and derivatives are not the smooth ones.
pub(crate) fn is_special(level: &Level, v: usize) -> bool {
    let Some(ft) = &level.sharp else {
        return false;
    };
    ft.vertices[v] > 0.0
        || spoke_edges(&level.mesh, v)
            .iter()
            .any(|&e| ft.edges[e as usize] > 0.0)
}

/// Whether every feature of the special vertex `v` is semi-sharp (its own sharpness and that
/// of its edges inside the surface are finite): refined further it becomes a plain (boundary)
/// vertex, whose G^1 cap then applies. Sharpness below [`INFINITE`] is spent after at most
/// [`SPENT_BY_LEVEL`] levels under either crease method.
pub(crate) fn spends(level: &Level, v: usize) -> bool {
    let Some(ft) = &level.sharp else {
        return true;
    };
    let m = &level.mesh;
    let hs = m.outgoing_halfedges(v);
    // an open fan's first outgoing half-edge and its incoming one are its boundary edges
    let skip = usize::from(m.is_boundary_vertex(v));
    ft.vertices[v] < INFINITE
        && hs
            .iter()
            .skip(skip)
            .all(|&h| ft.edges[m.he_edge(h) as usize] < INFINITE)
}

/// Whether the centre `x` of a G^1 cap's fan has a feature its cap does not take (anything
/// but the boundary rule at a boundary vertex, any feature inside the surface): `Some(true)`
/// when the feature is only semi-sharp and more levels spend it ([`spends`]), `Some(false)`
/// when it never is, `None` without such a feature.
pub(crate) fn cap_feature(level: &Level, x: usize) -> Option<bool> {
    let featured = if level.mesh.is_boundary_vertex(x) {
        !is_plain_boundary(level, x)
    } else {
        is_special(level, x)
    };
    featured.then(|| spends(level, x))
}

/// The adaptive loop's last level for the G^1 caps of Catmull-Clark and Loop: the requested
/// `rings`; while the level holds a semi-sharp feature, up to level [`SPENT_BY_LEVEL`] (by
/// which every finite sharpness is spent: the faces there become regular patches and an
/// extraordinary vertex whose features were all semi-sharp gets its cap, as OpenSubdiv's
/// adaptive isolation refines semi-sharp features until they are smooth); and up to
/// `MAX_EXTRA_CAP_LEVELS` more while holes still touch (`waiting`), counted from the requested
/// rings or from the last level with a semi-sharp feature, whichever is later.
pub(crate) fn is_last_cap_level(
    (l, rings, fill): (usize, usize, bool),
    level: &Level,
    waiting: impl FnOnce() -> bool,
) -> bool {
    let calm = level.sharp.as_ref().map_or(CALM, |ft| ft.calm);
    is_last_cap_level_calm((l, rings, fill), calm, waiting)
}

/// [`is_last_cap_level`] for a level `calm` levels after the last one with a semi-sharp
/// feature ([`CALM`] when none had one): the one decision of every adaptive host that spends
/// semi-sharp features (Catmull-Clark, Loop, the dual bi-2 schemes, non-box).
pub(crate) fn is_last_cap_level_calm(
    (l, rings, fill): (usize, usize, bool),
    calm: usize,
    waiting: impl FnOnce() -> bool,
) -> bool {
    use crate::host::adaptive::MAX_EXTRA_CAP_LEVELS;
    let spending = calm == 0 && l < SPENT_BY_LEVEL;
    let extra_over = l >= rings + MAX_EXTRA_CAP_LEVELS && calm > MAX_EXTRA_CAP_LEVELS;
    l >= rings && (!fill || (!spending && (extra_over || !waiting())))
}

/// The level by which every finite sharpness is spent (it drops by at least 1 per level from
/// below [`INFINITE`]).
pub(crate) const SPENT_BY_LEVEL: usize = INFINITE as usize;

/// Whether `v` is a plain boundary vertex of `level`: on the boundary, without sharpness of
/// its own or at an edge inside the surface (its two boundary edges are its only sharp ones),
/// so its rule is the boundary crease rule and its G^1 cap the open fan's.
pub(crate) fn is_plain_boundary(level: &Level, v: usize) -> bool {
    let m = &level.mesh;
    if !m.is_boundary_vertex(v) {
        return false;
    }
    let Some(ft) = &level.sharp else {
        return true;
    };
    let hs = m.outgoing_halfedges(v);
    ft.vertices[v] == 0.0
        && hs
            .iter()
            .skip(1)
            .all(|&h| ft.edges[m.he_edge(h) as usize] == 0.0)
}

/// The sector of a face's corner between infinitely sharp (or boundary) edges.
pub(crate) struct Sector {
    /// The corner's rule (its own sharpness and its infinitely sharp edges).
    pub rule: Rule,
    /// The outgoing half-edges of the corner's vertex in the sector, counter-clockwise from
    /// the one after the clockwise cut (from the face's own half-edge when `closed`).
    pub out: Vec<u32>,
    /// Whether the sector is the whole fan (no cut around the vertex).
    pub closed: bool,
}

/// The sector of the corner `v = from(h)` of the face of `h` (see [`Sector`]); `None` when
/// `v` has more than `max` faces (checked first: O(1) at high valence), or a semi-sharp
/// feature of its own or at an incident edge (such corners are refined until spent).
pub(crate) fn sector(m: &PolyMesh, ft: &Features, h: u32, max: usize) -> Option<Sector> {
    let v = m.he_from(h) as usize;
    if m.outgoing(v).take(max + 1).count() > max {
        return None;
    }
    let vs = ft.vertices[v];
    if is_semi(vs) {
        return None;
    }
    let mut k = 0;
    for e in spoke_edges(m, v) {
        let s = ft.edges[e as usize];
        if is_semi(s) {
            return None;
        }
        k += usize::from(is_inf(s));
    }
    // the twin of `g` across an edge that is not cut
    let across = |g: u32| {
        m.he_twin(g)
            .filter(|_| !is_inf(ft.edges[m.he_edge(g) as usize]))
    };
    // clockwise to the cut (or around)
    let mut first = h;
    let mut closed = false;
    while let Some(t) = across(first) {
        let g = m.he_next(t);
        if g == h {
            closed = true;
            break;
        }
        first = g;
    }
    // counter-clockwise from there to the other cut (or around); a fan of at most `max` faces
    let mut out = vec![first];
    let mut g = first;
    while let Some(t) = across(m.he_prev(g)) {
        if t == first || out.len() > max {
            break;
        }
        out.push(t);
        g = t;
    }
    if out.len() > max {
        return None;
    }
    Some(Sector {
        rule: classify(vs, k),
        out,
        closed,
    })
}

/// Whether the edge point of edge `e` is known from what is known at its ends (`a_ok`, `b_ok`:
/// their fans are complete) when the scheme's plain rule is (`plain`): a semi-sharp edge's plan
/// (and its halves' Chaikin sharpness) reads the incident edges at both ends.
pub(crate) fn edge_known(level: &Level, e: usize, a_ok: bool, b_ok: bool, plain: bool) -> bool {
    match &level.sharp {
        Some(ft) if is_semi(ft.edges[e]) => a_ok && b_ok,
        _ => plain,
    }
}

/// The child level's mesh with its sharpness and its [`Features`]: child edge halves by
/// OpenSubdiv's subdivision of sharpness (`sl`, the level's sharp rules; `vid`, `eid`: the
/// child vertex of each parent vertex and edge, `u32::MAX` when not refined), vertex
/// sharpness decremented, the child's boundary edges (those of the net and those where the
/// partial refinement stops) infinitely sharp.
pub(crate) fn child(
    level: &Level,
    sl: Option<&SharpLevel<'_>>,
    child: PolyMesh,
    (vid, eid): (&[u32], &[u32]),
    hole: Vec<bool>,
) -> (PolyMesh, Option<Features>) {
    let Some(ft) = &level.sharp else {
        return (child, None);
    };
    let m = &level.mesh;
    let mut pairs = Vec::new();
    if let Some(sl) = sl {
        let mut scratch = Scratch::default();
        for (e, &s) in ft.edges.iter().enumerate() {
            if s <= 0.0 || eid[e] == u32::MAX {
                continue;
            }
            for v in m.edge(e) {
                if vid[v as usize] == u32::MAX {
                    continue;
                }
                let c = sl.child_half(e as u32, v, &mut scratch);
                if c > 0.0 {
                    pairs.push(([vid[v as usize], eid[e]], c));
                }
            }
        }
    }
    for h in 0..child.num_halfedges() as u32 {
        if child.he_twin(h).is_none() {
            pairs.push(([child.he_from(h), child.he_to(h)], INFINITE));
        }
    }
    let mut vertices = vec![0f32; child.num_vertices()];
    let mut sharp_vertices = Vec::new();
    for (v, &s) in ft.vertices.iter().enumerate() {
        let c = decrement(s);
        if c > 0.0 && vid[v] != u32::MAX {
            vertices[vid[v] as usize] = c;
            sharp_vertices.push((vid[v], c));
        }
    }
    sharp_vertices.sort_unstable_by_key(|p| p.0);
    let extras = Extras {
        sharp_edges: SharpEdges::ByPair(pairs),
        sharp_vertices,
        sharpened: true,
        ..Extras::default()
    };
    let child = child.with_extras(Some(extras));
    let edges = match SharpLevel::new(&child, &ft.opts) {
        Some(sl) => sl.edges,
        None => vec![0.0; child.num_edges()],
    };
    let features = Features {
        opts: ft.opts,
        calm: calm_after(ft.calm, &edges, &vertices),
        edges,
        vertices,
        hole: if hole.contains(&true) {
            hole
        } else {
            Vec::new()
        },
    };
    (child, Some(features))
}

/// Whether the fill takes the chord of the limit points as the derivative at `v` of `mesh` (a
/// level of the adaptive loop): `v` has a sharp feature other than being a plain boundary
/// vertex (whose derivatives the fill knows).
pub(crate) fn chord_vertices(mesh: &PolyMesh) -> Option<Vec<bool>> {
    let sl = SharpLevel::new(mesh, &SubdOptions::default())?;
    let mut spokes = Vec::new();
    Some(
        (0..mesh.num_vertices())
            .map(|v| {
                if !sl.special[v] {
                    return false;
                }
                sl.spokes(v as u32, &mut spokes);
                let k = spokes
                    .iter()
                    .filter(|s| sl.edges[s.edge as usize] > 0.0)
                    .count();
                !mesh.is_boundary_vertex(v) || sl.vertices[v] > 0.0 || k > 2
            })
            .collect(),
    )
}

/// Marks the sides of the last patch of `out`, the patch of face `f` of `level`, that lie on
/// an infinitely sharp edge inside the surface (boundary edges are the surface's boundary, not
/// a join); `sides[k]` is the patch side on the face's edge from corner `k` to corner `k + 1`.
pub(crate) fn mark_sides(level: &Level, f: usize, sides: &[Side], out: &mut PatchComplex) {
    let Some(ft) = &level.sharp else {
        return;
    };
    let m = &level.mesh;
    let h0 = m.face_halfedge(f);
    for (k, side) in sides.iter().enumerate() {
        let h = h0 + k as u32;
        if m.he_twin(h).is_some() && is_inf(ft.edges[m.he_edge(h) as usize]) {
            out.mark_sharp(out.len() - 1, side.index());
        }
    }
}

/// The exact limit curve of the infinitely sharp edge `a -> b` of `level` as a cubic Bezier
/// curve, when both ends take the crease or corner rule for good (their sharp edges and their
/// own sharpness 0 or infinite): crease points are refined from crease points alone, so the
/// curve is the uniform cubic B-spline of the crease polygon, with ghosts `2 a - b` at corners.
/// `None` otherwise (darts, semi-sharp ends: the fill's Hermite curve).
pub(crate) fn crease_curve(level: &Level, a: u32, b: u32) -> Option<[Point; 4]> {
    let ft = level.sharp.as_ref()?;
    let m = &level.mesh;
    let e = m.find_edge(a, b)?;
    if !is_inf(ft.edges[e as usize]) {
        return None;
    }
    let pos = m.positions();
    // the crease neighbour of `v` beyond the edge to `w`, or the ghost at a corner
    let beyond = |v: u32, w: u32| -> Option<Point> {
        let vs = ft.vertices[v as usize];
        if is_semi(vs) {
            return None;
        }
        let mut others = Vec::new();
        for s in spoke_edges(m, v as usize) {
            let x = ft.edges[s as usize];
            if is_semi(x) {
                return None;
            }
            if is_inf(x) {
                let [p, q] = m.edge(s as usize);
                others.push(if p == v { q } else { p });
            }
        }
        let (pv, pw) = (pos[v as usize], pos[w as usize]);
        match classify(vs, others.len()) {
            Rule::Crease => others
                .into_iter()
                .find(|&o| o != w)
                .map(|o| pos[o as usize]),
            Rule::Corner => Some(geom::sub(geom::scale(pv, 2.0), pw)),
            Rule::Smooth | Rule::Dart => None,
        }
    };
    let d = [
        beyond(a, b)?,
        pos[a as usize],
        pos[b as usize],
        beyond(b, a)?,
    ];
    Some(crate::bezier::convert::cubic_bspline_to_bezier(&d))
}
