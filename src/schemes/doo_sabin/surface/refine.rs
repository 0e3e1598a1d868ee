//! One adaptive step of the dual schemes: the faces around the marked vertices refined with the
//! scheme's own rules (corner points, Chaikin boundary points, kept corners), the children of
//! the marked vertices the next level's active vertices. Split from the parent module, which
//! holds the host, the regular patches and the centroid fill.

use super::{DualRules, Level};
use crate::bezier::domain::Domain;
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::host::adaptive::{Info, Tag};
use crate::mesh::PolyMesh;
use crate::schemes::doo_sabin::boundary_edge_point_stencil;
use crate::schemes::doo_sabin::fourier::LARGE_FACE;
use crate::stencil::{Stencil, StencilTable};
use std::collections::HashMap;

/// Refines the faces around the marked vertices with the scheme's rules; the next level's
/// active vertices are the children of the marked vertices (they tile the marked patches'
/// regions), each inheriting its parent's tag.
pub(super) fn refine_around(
    level: &Level,
    marked: &[(u32, Tag)],
    rules: &DualRules<'_>,
) -> Result<Level> {
    const UNSET: u32 = u32::MAX;
    let m = &level.mesh;
    let (nv, nf, ne) = (m.num_vertices(), m.num_faces(), m.num_edges());
    let mut sel = vec![false; nf];
    let mut sel_faces = Vec::new();
    for &(v, _) in marked {
        for f in m.vertex_faces(v as usize) {
            if !sel[f as usize] {
                sel[f as usize] = true;
                sel_faces.push(f);
            }
        }
    }
    sel_faces.sort_unstable();
    // Whether a corner of a selected face has its whole fan selected, found once per vertex
    // (asking per corner walks a fan of valence n for each of its n faces).
    let mut fan_selected = vec![false; nv];
    let mut fan_known = vec![false; nv];
    for &f in &sel_faces {
        for &x in m.face(f as usize) {
            let x = x as usize;
            if !fan_known[x] {
                fan_known[x] = true;
                fan_selected[x] =
                    level.info[x].fan_ok && m.outgoing(x).all(|h| sel[m.he_face(h) as usize]);
            }
        }
    }
    let whole_fan = |v: usize| fan_selected[v];
    // A boundary edge of the partial mesh is a true boundary edge when an end has its true fan.
    let true_boundary = |h: u32| {
        m.he_twin(h).is_none()
            && (level.info[m.he_from(h) as usize].fan_ok || level.info[m.he_to(h) as usize].fan_ok)
    };
    let mut stencils: Vec<Stencil> = Vec::new();
    let mut info: Vec<Info> = Vec::new();
    // Boundary `none`: whether each new point is computed without a boundary rule (see the
    // parent module's boundary modes); the Chaikin points and kept corners are not.
    let free = |x: u32| level.rule_free.as_ref().is_none_or(|r| r[x as usize]);
    let mut rule_free: Vec<bool> = Vec::new();
    let mut corner_pt = vec![UNSET; m.num_halfedges()];
    let mut edge_pt = vec![[UNSET; 2]; ne];
    let mut kept = vec![UNSET; nv];
    fn push(s: Stencil, i: Info, stencils: &mut Vec<Stencil>, info: &mut Vec<Info>) -> u32 {
        stencils.push(s);
        info.push(i);
        (stencils.len() - 1) as u32
    }
    // Corners of large faces come as positions (`fixed`), their stencils left empty.
    let mut fixed: Vec<(u32, Point)> = Vec::new();
    for &f in &sel_faces {
        let f = f as usize;
        let h0 = m.face_halfedge(f);
        let large = (m.face_size(f) > LARGE_FACE).then(|| {
            let fc = (rules.face_corners)(m, f);
            let ok = fc.reads.iter().all(|&x| level.info[x as usize].pos_ok);
            let rf = fc.reads.iter().all(|&x| free(x));
            (fc.points, ok, rf)
        });
        for h in h0..h0 + m.face_size(f) as u32 {
            let v = m.he_from(h) as usize;
            let (st, pos) = match &large {
                Some((points, ok, rf)) => {
                    fixed.push((stencils.len() as u32, points[(h - h0) as usize]));
                    rule_free.push(*rf);
                    (Stencil::new(), *ok)
                }
                None => {
                    let st = (rules.corner)(m, h);
                    // Trusted when every point the rule reads is (it may reach beyond the face).
                    let pos = st
                        .entries()
                        .iter()
                        .all(|&(x, _)| level.info[x as usize].pos_ok);
                    rule_free.push(st.entries().iter().all(|&(x, _)| free(x)));
                    (st, pos)
                }
            };
            corner_pt[h as usize] = push(
                st,
                Info {
                    pos_ok: pos,
                    fan_ok: whole_fan(v),
                    origin: None,
                },
                &mut stencils,
                &mut info,
            );
            if true_boundary(h) {
                let e = m.he_edge(h) as usize;
                let (a, b) = (v, m.he_to(h) as usize);
                let pos = level.info[a].pos_ok && level.info[b].pos_ok;
                for (k, end) in [a, b].into_iter().enumerate() {
                    rule_free.push(false);
                    edge_pt[e][k] = push(
                        boundary_edge_point_stencil(m, h, k == 1),
                        Info {
                            pos_ok: pos,
                            fan_ok: whole_fan(end),
                            origin: None,
                        },
                        &mut stencils,
                        &mut info,
                    );
                }
            }
        }
        for &x in m.face(f) {
            let x = x as usize;
            if kept[x] == UNSET
                && level.info[x].fan_ok
                && crate::schemes::doo_sabin::sharp::is_kept_corner(m, x)
            {
                rule_free.push(false);
                kept[x] = push(
                    Stencil::point(x),
                    Info {
                        pos_ok: level.info[x].pos_ok,
                        fan_ok: whole_fan(x),
                        origin: None,
                    },
                    &mut stencils,
                    &mut info,
                );
            }
        }
    }
    // Faces: F-faces, E-faces, V-faces (the layout of `refine_dual`).
    let mut face_start = vec![0u32];
    let mut corners: Vec<u32> = Vec::new();
    let mut face_origin = Vec::new();
    for &f in &sel_faces {
        let h0 = m.face_halfedge(f as usize);
        for h in h0..h0 + m.face_size(f as usize) as u32 {
            corners.push(corner_pt[h as usize]);
        }
        face_start.push(corners.len() as u32);
        face_origin.push(level.face_origin[f as usize]);
    }
    for (e, pts) in edge_pt.iter().enumerate() {
        let h = m.edge_halfedge(e);
        let quad = match m.he_twin(h) {
            Some(t) if sel[m.he_face(h) as usize] && sel[m.he_face(t) as usize] => [
                corner_pt[m.he_next(h) as usize],
                corner_pt[h as usize],
                corner_pt[m.he_next(t) as usize],
                corner_pt[t as usize],
            ],
            None if pts[0] != UNSET => [
                corner_pt[m.he_next(h) as usize],
                corner_pt[h as usize],
                pts[0],
                pts[1],
            ],
            _ => continue,
        };
        corners.extend_from_slice(&quad);
        face_start.push(corners.len() as u32);
        face_origin.push(None);
    }
    let mut done = vec![false; nv];
    for &f in &sel_faces {
        for &x in m.face(f as usize) {
            let v = x as usize;
            if done[v] || !whole_fan(v) {
                continue;
            }
            done[v] = true;
            let start = corners.len();
            let hs = m.outgoing_halfedges(v);
            let boundary = m.is_boundary_vertex(v);
            if boundary {
                corners.push(edge_pt[m.he_edge(hs[0]) as usize][0]);
            }
            corners.extend(hs.iter().map(|&h| corner_pt[h as usize]));
            if boundary {
                let last = *hs.last().expect("a vertex has a face");
                corners.push(edge_pt[m.he_edge(m.he_prev(last)) as usize][1]);
                if kept[v] != UNSET {
                    corners.push(kept[v]);
                }
            }
            let size = corners.len() - start;
            face_start.push(corners.len() as u32);
            face_origin.push(if size != 4 {
                level.info[v].origin
            } else {
                None
            });
        }
    }
    if corners.contains(&UNSET) {
        return Err(Error::Unsupported(
            "adaptive Doo-Sabin refinement met an inconsistent neighbourhood (a boundary edge \
             whose Chaikin points are unknown); refine the net once with --levels 1 and retry"
                .into(),
        ));
    }
    let mut positions = StencilTable::from_rows(nv, stencils, 6).apply(m.positions());
    for (i, p) in fixed {
        positions[i as usize] = p;
    }
    let child = PolyMesh::from_partial_refinement(positions, face_start, corners)?;
    // The F-face of each selected face in the child (the first faces, in `sel_faces` order).
    let f_face: HashMap<u32, u32> = sel_faces
        .iter()
        .enumerate()
        .map(|(i, &f)| (f, i as u32))
        .collect();
    let mut active = Vec::new();
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
            let w = corner_pt[h as usize];
            let mut t = tag;
            t.domain = Domain::UNTRACKED;
            if w != UNSET && (level.first || !on_boundary) {
                let g = m.he_face(h);
                t.domain = child_domain(m, level.first, &child, h, i, tag.domain, f_face[&g], w);
            }
            active.push((w, t));
        }
        if m.is_boundary_vertex(v) {
            let untracked = Tag {
                domain: Domain::UNTRACKED,
                ..tag
            };
            let first = hs[0];
            let last = *hs.last().expect("a vertex has a face");
            active.push((edge_pt[m.he_edge(first) as usize][0], untracked));
            active.push((edge_pt[m.he_edge(m.he_prev(last)) as usize][1], untracked));
            if kept[v] != UNSET {
                active.push((kept[v], untracked));
            }
        }
    }
    // Children that could not be made (a cut the bookkeeping did not trust) stay out.
    active.retain(|&(x, _)| x != UNSET);
    debug_assert_eq!(rule_free.len(), info.len());
    Ok(Level {
        mesh: child,
        info,
        face_origin,
        active,
        first: false,
        rule_free: level.rule_free.as_ref().map(|_| rule_free),
    })
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
