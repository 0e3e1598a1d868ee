//! Catmull-Clark patch output with OpenSubdiv's sharp features: infinitely sharp creases and
//! corners, semi-sharp ones, the boundary options and holes, as OpenSubdiv's adaptive patches
//! treat them.
//!
//! The levels of the adaptive loop carry their sharpness as the mesh's extras (already
//! sharpened, so that the rules of [`crate::schemes::catmull_clark`] refine them exactly as
//! `--levels` does) and in dense arrays ([`Features`]). A quad is one exact bi-3 patch when
//! every corner is regular *with respect to the features*: all its edges and itself of sharpness
//! 0 or infinite, quads around it, and the sector of the face between infinitely sharp edges (or
//! boundary edges) one of
//!
//! * four quads and no sharp edge (the smooth regular vertex),
//! * two quads between the vertex's two sharp edges (the crease rule: the regular crease vertex,
//!   whatever lies on the other side),
//! * one quad between two sharp edges at a corner (the corner rule).
//!
//! The net is then [`bi3_net_cut`]'s: the grid stops at the crease and ghosts `2 b - i` are
//! mirrored across it, so the patch's side on the crease is the cubic B-spline of the crease
//! vertices, and the patches on the two sides share it exactly (C^0, sharp); elsewhere they
//! are C^2. The limit of such a face depends only on its own side of the crease, since crease
//! points are refined from crease points alone.
//!
//! Everything else (semi-sharp edges and vertices, darts, crease ends, crease vertices with
//! other sectors, corners meeting creases, edge-only boundary corners) is refined with its
//! neighbourhood like an extraordinary element: semi-sharp values decay by one per level (or
//! by Chaikin's rule) until they are spent and the faces become regular; what is left after
//! the rings is closed by the Hermite-Coons fill (C^0; the derivatives at sharp vertices are
//! the chords of the limit points), never by a G^1 cap. Hole faces (the net's and those that
//! boundary `none` makes) are refined for support but not written.

use super::Level;
use crate::bezier::Side;
use crate::bezier::complex::PatchComplex;
use crate::geom::{self, Point};
use crate::mesh::tags::SubdOptions;
use crate::mesh::{Extras, PolyMesh, SharpEdges};
use crate::schemes::catmull_clark::Rules;
use crate::schemes::catmull_clark::crease::{
    INFINITE, Rule, Scratch, SharpLevel, classify, decrement,
};
use crate::schemes::catmull_clark::regular::bi3_net_cut;
use crate::stencil::Stencil;

/// The sharp features of one level of the adaptive loop.
pub struct Features {
    /// OpenSubdiv's options (the crease method, smooth triangles).
    opts: SubdOptions,
    /// Sharpness per edge of the level's mesh.
    edges: Vec<f32>,
    /// Sharpness per vertex.
    vertices: Vec<f32>,
    /// Hole faces of the level (only the input level has active holes).
    hole: Vec<bool>,
}

fn is_inf(s: f32) -> bool {
    s >= INFINITE
}

fn is_semi(s: f32) -> bool {
    s > 0.0 && s < INFINITE
}

/// Level 0 with sharp features: the net with its sharpened extras and their arrays, or `None`
/// when the plain rules give the same surface (no feature, edge-and-corner boundaries).
pub(super) fn start(mesh: &PolyMesh, opts: &SubdOptions) -> Option<(PolyMesh, Features)> {
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
        edges,
        vertices,
        hole,
    };
    Some((mesh.clone().with_extras(Some(extras)), features))
}

/// The rules of one refinement step of `level` (its features' options, or the defaults).
pub(super) fn rules(level: &Level) -> Rules<'_> {
    let opts = level.sharp.as_ref().map(|s| s.opts).unwrap_or_default();
    Rules::new(&level.mesh, &opts)
}

/// Whether face `f` of `level` is a hole (consumed without a patch).
pub(super) fn is_hole(level: &Level, f: usize) -> bool {
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

/// Whether vertex `v` of `level` has a sharp feature (a sharp incident edge, boundary edges
/// included, or sharpness of its own): its limit and derivatives are not the smooth ones.
pub(super) fn is_special(level: &Level, v: usize) -> bool {
    let Some(ft) = &level.sharp else {
        return false;
    };
    ft.vertices[v] > 0.0
        || spoke_edges(&level.mesh, v)
            .iter()
            .any(|&e| ft.edges[e as usize] > 0.0)
}

/// Whether the corner `v = from(h)` of the face of `h` is regular with respect to the features
/// (see the module documentation).
fn corner_regular(m: &PolyMesh, ft: &Features, h: u32) -> bool {
    let v = m.he_from(h) as usize;
    // more than four faces: never regular (checked first: O(1) at high valence)
    if m.outgoing(v).take(5).count() > 4 {
        return false;
    }
    let vs = ft.vertices[v];
    if is_semi(vs) {
        return false;
    }
    let mut k = 0;
    for e in spoke_edges(m, v) {
        let s = ft.edges[e as usize];
        if is_semi(s) {
            return false;
        }
        k += usize::from(is_inf(s));
    }
    if m.vertex_faces(v)
        .iter()
        .any(|&g| m.face_size(g as usize) != 4)
    {
        return false;
    }
    let cut = |g: u32| m.he_twin(g).is_none() || is_inf(ft.edges[m.he_edge(g) as usize]);
    // counter-clockwise to a cut (or around)
    let mut n = 1;
    let mut g = h;
    loop {
        let p = m.he_prev(g);
        if cut(p) {
            break;
        }
        let t = m.he_twin(p).expect("not a cut");
        if t == h {
            return n == 4 && vs == 0.0;
        }
        g = t;
        n += 1;
    }
    // clockwise to the other cut
    let mut g = h;
    while !cut(g) {
        g = m.he_next(m.he_twin(g).expect("not a cut"));
        n += 1;
        if n > 4 {
            return false;
        }
    }
    match n {
        2 => classify(vs, k) == Rule::Crease,
        1 => classify(vs, k) == Rule::Corner,
        _ => false,
    }
}

/// The 4x4 net of face `f` when it is one exact bi-3 patch under the features (every corner
/// regular, see the module documentation), the crease edges cut.
pub(super) fn bi3_net(level: &Level, ft: &Features, f: usize) -> Option<Vec<Stencil>> {
    let m = &level.mesh;
    if m.face_size(f) != 4 {
        return None;
    }
    let h0 = m.face_halfedge(f);
    if !(h0..h0 + 4).all(|h| corner_regular(m, ft, h)) {
        return None;
    }
    bi3_net_cut(m, f, &|e| is_inf(ft.edges[e as usize]))
}

/// Whether vertex `v` of `level` makes its faces irregular (an extraordinary element for the
/// tags): not a regular quad vertex, or (with features) some face at it not regular there.
pub(super) fn irregular_vertex(level: &Level, v: usize) -> bool {
    let m = &level.mesh;
    match &level.sharp {
        None => !m.is_regular_quad_vertex(v),
        Some(ft) => {
            m.outgoing(v).take(5).count() > 4
                || m.outgoing_halfedges(v)
                    .into_iter()
                    .any(|h| !corner_regular(m, ft, h))
        }
    }
}

/// Whether the edge point of edge `e` is known from what is known at its ends (`a_ok`, `b_ok`:
/// their fans are complete): one end suffices for the plain rules; a semi-sharp edge's plan
/// (and its halves' Chaikin sharpness) reads the incident edges at both ends.
pub(super) fn edge_known(level: &Level, e: usize, a_ok: bool, b_ok: bool) -> bool {
    match &level.sharp {
        Some(ft) if is_semi(ft.edges[e]) => a_ok && b_ok,
        _ => a_ok || b_ok,
    }
}

/// The child level's mesh with its sharpness and its [`Features`]: child edge halves by
/// OpenSubdiv's subdivision of sharpness (`vid`, `eid`: the child vertex of each parent vertex
/// and edge, `u32::MAX` when not refined), vertex sharpness decremented, the child's boundary
/// edges (those of the net and those where the partial refinement stops) infinitely sharp.
pub(super) fn child(
    level: &Level,
    rules: &Rules<'_>,
    child: PolyMesh,
    vid: &[u32],
    eid: &[u32],
) -> (PolyMesh, Option<Features>) {
    let Some(ft) = &level.sharp else {
        return (child, None);
    };
    let m = &level.mesh;
    let mut pairs = Vec::new();
    if let Some(sl) = &rules.sharp {
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
        edges,
        vertices,
        hole: Vec::new(),
    };
    (child, Some(features))
}

/// Whether the fill takes the chord of the limit points as the derivative at `v` of `mesh` (a
/// level of the adaptive loop): `v` has a sharp feature other than being a plain boundary
/// vertex (whose derivatives the fill knows).
pub(super) fn chord_vertices(mesh: &PolyMesh) -> Option<Vec<bool>> {
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

/// Marks the sides of the last patch of `out`, the patch of quad `f` of `level` (corner `k` at
/// the domain corner `k` of `(0,0), (1,0), (1,1), (0,1)`), that lie on an infinitely sharp
/// edge inside the surface (boundary edges are the surface's boundary, not a join).
pub(super) fn mark_sides(level: &Level, f: usize, out: &mut PatchComplex) {
    let Some(ft) = &level.sharp else {
        return;
    };
    let m = &level.mesh;
    let h0 = m.face_halfedge(f);
    // edge k runs from corner k to corner k + 1: sides V0, U1, V1, U0
    const SIDE: [Side; 4] = [Side::V0, Side::U1, Side::V1, Side::U0];
    for (k, side) in SIDE.iter().enumerate() {
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
pub(super) fn crease_curve(level: &Level, a: u32, b: u32) -> Option<[Point; 4]> {
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
