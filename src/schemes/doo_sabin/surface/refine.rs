//! One adaptive step of the dual schemes: the faces around the marked vertices refined with the
//! scheme's own rules (corner points, Chaikin points on boundary and sharp edges, kept
//! corners; [`super::step`]), the children of the marked vertices the next level's active
//! vertices. Split from the parent module, which holds the host, the regular patches and the
//! centroid fill.

use super::step::{StepIn, StepOut, dual_step};
use super::{DualRules, Level};
use crate::bezier::domain::Domain;
use crate::error::Result;
use crate::host::adaptive::Tag;
use crate::mesh::dual_split::DualOrder;
use crate::mesh::{NONE, PolyMesh};
use crate::schemes::doo_sabin::sharp::step::Creases;
use std::collections::HashMap;

/// Refines the faces around the marked vertices with the scheme's rules ([`dual_step`], with
/// the level's creases); the next level's active vertices are the children of the marked
/// vertices (they tile the marked patches' regions), each inheriting its parent's tag.
pub(super) fn refine_around(
    level: &Level,
    marked: &[(u32, Tag)],
    rules: &DualRules<'_>,
    name: &str,
) -> Result<Level> {
    let m = &level.mesh;
    let creases = Creases::of(m, name)?;
    let sel_faces = faces_around(m, marked);
    let inp = StepIn {
        mesh: m,
        info: &level.info,
        rule_free: level.rule_free.as_deref(),
        face_origin: &level.face_origin,
        face_corners: Some(rules.face_corners),
    };
    let mut corner = |mm: &PolyMesh, h: u32| (rules.corner)(mm, h);
    let sel = (sel_faces, DualOrder::ByFace);
    let out = dual_step(&inp, sel, &mut corner, creases.as_ref())?;
    let positions = out.positions(m.positions());
    let child = PolyMesh::from_partial_refinement(
        positions,
        out.split.face_start.clone(),
        out.split.corners.clone(),
    )?
    .with_extras(out.extras.clone());
    let mut active = active_children(level, marked, &out, &child, creases.as_ref());
    // Children that could not be made (a cut the bookkeeping did not trust) stay out.
    active.retain(|&(x, _)| x != NONE);
    debug_assert_eq!(out.rule_free.len(), out.info.len());
    // a child descends from its parent's element: a V-face it makes later (a sector of a
    // crease vertex, a dart's tip, a kept point of valence 3) is a facet of that element
    let mut info = out.info;
    for &(x, tag) in &active {
        let o = &mut info[x as usize].origin;
        if o.is_none() {
            *o = tag.element;
        }
    }
    let rule_free = level.rule_free.as_ref().map(|_| out.rule_free);
    let child = Level::new(
        child,
        info,
        out.face_origin,
        active,
        rule_free,
        level.calm,
        false,
    );
    if child.calm > 0 && child.creased.is_some() {
        // every semi-sharp value is spent and infinitely sharp creases are left: from here on
        // they are boundaries of the net cut along them, as for a net without semi-sharp ones
        return cut_child(child, name);
    }
    Ok(child)
}

/// The faces around the marked vertices, each once, in the order the marked vertices meet
/// them.
fn faces_around(m: &PolyMesh, marked: &[(u32, Tag)]) -> Vec<u32> {
    let mut sel = vec![false; m.num_faces()];
    let mut sel_faces = Vec::new();
    for &(v, _) in marked {
        for f in m.vertex_faces(v as usize) {
            if !sel[f as usize] {
                sel[f as usize] = true;
                sel_faces.push(f);
            }
        }
    }
    sel_faces
}

/// The children of the marked vertices with their tags (`NONE` for a child not made): the
/// corner points of each marked vertex, with the quarters of its cell as domains, then, over
/// no face, the Chaikin points near it of its sharp edges and its kept point.
fn active_children(
    level: &Level,
    marked: &[(u32, Tag)],
    out: &StepOut,
    child: &PolyMesh,
    creases: Option<&Creases<'_>>,
) -> Vec<(u32, Tag)> {
    let m = &level.mesh;
    let mut active = Vec::new();
    // The F-face of each selected face in the child (the first faces, in `sel_faces` order).
    let f_face: HashMap<u32, u32> = out
        .split
        .sel_faces
        .iter()
        .enumerate()
        .map(|(i, &f)| (f, i as u32))
        .collect();
    for &(v, tag) in marked {
        let v = v as usize;
        let hs = m.outgoing_halfedges(v);
        // on the true boundary (its whole fan present): the corner points of an input
        // vertex get the quarters of its faces as anywhere (their patches' sides toward the
        // boundary edges are knot lines inside the surface, as the regular boundary vertices'
        // are); on later levels boundary vertices are Chaikin points and kept corners, whose
        // patches lie beyond the knot lines, over no face
        let on_boundary = m.is_boundary_vertex(v) && level.info[v].fan_ok;
        for (i, &h) in hs.iter().enumerate() {
            let w = out.split.corner_pt[h as usize];
            let mut t = tag;
            t.domain = Domain::UNTRACKED;
            if w != NONE && (level.first || !on_boundary) {
                let g = m.he_face(h);
                t.domain = child_domain(m, level.first, child, h, i, tag.domain, f_face[&g], w);
            }
            active.push((w, t));
        }
        // the Chaikin points near v of its sharp edges (boundary edges: the outgoing one
        // first, the incoming one last) and its kept point: over no face
        let untracked = Tag {
            domain: Domain::UNTRACKED,
            ..tag
        };
        for e in sharp_spokes(m, v, &hs, creases) {
            let k = usize::from(m.he_from(m.edge_halfedge(e as usize)) as usize != v);
            active.push((out.split.edge_pt[e as usize][k], untracked));
        }
        if out.split.kept[v] != NONE {
            active.push((out.split.kept[v], untracked));
        }
    }
    active
}

/// `level` cut along its (infinitely sharp) creases ([`crate::schemes::doo_sabin::sharp::cut_level`]):
/// each vertex's copies keep its trust and its tag.
fn cut_child(level: Level, name: &str) -> Result<Level> {
    let (mesh, origin) = crate::schemes::doo_sabin::sharp::cut_level(&level.mesh, name)?;
    let info = origin.iter().map(|&o| level.info[o as usize]).collect();
    let mut copies: Vec<Vec<u32>> = vec![Vec::new(); level.mesh.num_vertices()];
    for (c, &o) in origin.iter().enumerate() {
        copies[o as usize].push(c as u32);
    }
    let active = level
        .active
        .iter()
        .flat_map(|&(v, tag)| copies[v as usize].iter().map(move |&c| (c, tag)))
        .collect();
    Ok(Level::new(
        mesh,
        info,
        level.face_origin,
        active,
        None,
        level.calm - 1,
        false,
    ))
}

/// The sharp edges at `v` whose Chaikin points near `v` are its children: on the boundary the
/// outgoing boundary edge, the sharp edges inside the surface counter-clockwise, the incoming
/// boundary edge; inside the surface its sharp edges counter-clockwise.
fn sharp_spokes(m: &PolyMesh, v: usize, hs: &[u32], creases: Option<&Creases<'_>>) -> Vec<u32> {
    let boundary = m.is_boundary_vertex(v);
    let mut out = Vec::new();
    for (i, &h) in hs.iter().enumerate() {
        let e = m.he_edge(h);
        if (boundary && i == 0) || creases.is_some_and(|c| c.is_crease(e as usize)) {
            out.push(e);
        }
    }
    if boundary {
        let last = *hs.last().expect("a vertex has a face");
        out.push(m.he_edge(m.he_prev(last)));
    }
    out
}

/// The domain of the child `w` (in `child`) of a vertex `v` of `m` that is the new corner
/// of face `g = face(h)`, `h` being `v`'s `i`-th outgoing half-edge and `cell` `v`'s domain
/// (unused when `first`, `m` being the input net): the quarter of `v`'s cell toward `g`'s
/// centroid (when `first` the quarter of the input face `g` at `v`, see
/// [`crate::bezier::domain`]), turned so that its `rot` is the corner of the patch's `(0, 0)`
/// for `w`'s outgoing order in `child`. The faces around `v` sit at its cell's corners
/// `rot + 2 + i` (the patch of `v`, `u` along its first outgoing half-edge, has face `i`'s
/// centroid at its corner `2 + i`); `w`'s cell has `g`'s F-face `fg` at its corner 0 (when
/// `first`: 2, the input face's centroid).
#[allow(clippy::too_many_arguments)]
fn child_domain(
    m: &PolyMesh,
    first: bool,
    child: &PolyMesh,
    h: u32,
    i: usize,
    cell: Domain,
    fg: u32,
    w: u32,
) -> Domain {
    let (d, at) = if first {
        let g = m.he_face(h) as usize;
        let k = h - m.face_halfedge(g);
        (Domain::polygon(g as u32, m.face_size(g)).child(k), 2)
    } else if cell.is_tracked() {
        let c = (u32::from(cell.rot) + 2 + i as u32) % 4;
        (cell.child(c), 0)
    } else {
        return Domain::UNTRACKED;
    };
    let hs = child.outgoing_halfedges(w as usize);
    match hs.iter().position(|&x| child.he_face(x) == fg) {
        // face p of w's fan is g's F-face at corner `at`: the patch's (0, 0) at at - 2 - p
        Some(p) => d.rotated((at + 8 - 2 - p as u32) % 4),
        None => Domain::UNTRACKED,
    }
}

/// The cells of the vertices of `child`, one whole-net step of a dual scheme on `m` (the
/// layout of [`crate::schemes::doo_sabin`]: child vertex `h` is the new corner of half-edge
/// `h`, child face `f` the F-face of face `f`), from the cells of `m`'s vertices (`None`: `m`
/// is the input net, whose vertices' patches cover quarters of their faces). Each child of an
/// interior vertex gets the quarter of its parent's cell toward its face, exactly as the
/// adaptive refinement gives it (`rot` the corner of its patch's `(0, 0)`), and so does each
/// corner point of an input boundary vertex; boundary points (Chaikin points, kept corners)
/// are untracked (see
/// [`crate::bezier::domain`]). PGS after DS^CC steps (`pgs-dscc`) starts its complex from
/// these cells ([`super::dual_complex_in_cells`]).
pub fn step_cells(m: &PolyMesh, cells: Option<&[Domain]>, child: &PolyMesh) -> Vec<Domain> {
    let mut out = vec![Domain::UNTRACKED; child.num_vertices()];
    for v in 0..m.num_vertices() {
        // the corner points of an input boundary vertex get their quarters as in the adaptive
        // refinement; later boundary vertices (Chaikin points, kept corners) cover no face
        if m.is_boundary_vertex(v) && cells.is_some() {
            continue;
        }
        let cell = cells.map_or(Domain::UNTRACKED, |c| c[v]);
        for (i, h) in m.outgoing_halfedges(v).into_iter().enumerate() {
            out[h as usize] = child_domain(m, cells.is_none(), child, h, i, cell, m.he_face(h), h);
        }
    }
    out
}

/// Whether the patch (or fill patch) of vertex `v` is computed without any boundary rule: always
/// unless the boundary mode is `none`; then `v` is interior and every point of its faces (and
/// of what the facet limit of a non-quad face among them reads) is rule-free.
pub(super) fn rule_free(level: &Level, v: usize, rules: &DualRules<'_>) -> bool {
    let Some(free) = &level.rule_free else {
        return true;
    };
    let m = &level.mesh;
    !m.is_boundary_vertex(v)
        && m.vertex_faces(v).into_iter().all(|f| {
            let f = f as usize;
            m.face(f).iter().all(|&x| free[x as usize])
                && (m.face_size(f) == 4
                    || (rules.facet_limit)(m, f)
                        .entries()
                        .iter()
                        .all(|&(x, _)| free[x as usize]))
        })
}
