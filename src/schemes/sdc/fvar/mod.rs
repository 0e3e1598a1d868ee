//! Face-varying data (texture coordinates, OBJ `vt` with `f v/vt`) refined with OpenSubdiv's
//! face-varying rules for Catmull-Clark and Loop (`Sdc::Options::FVarLinearInterpolation`:
//! none, corners-only, corners-plus1, corners-plus2, boundaries, all; `--fvar`).
//!
//! One step, given the step's vertex stencils (the one source of the vertex rules):
//!
//! - a face point is the centroid of the face's values;
//! - an edge point of an edge whose values agree across it takes the edge's own stencil, each
//!   parent vertex read as its value in a face of the edge; on a seam (or a linear boundary)
//!   each face side gets the midpoint of its two values;
//! - a vertex point of a vertex whose value topology matches takes the vertex's own stencil
//!   (sharpness, boundary and transition rules included), each parent vertex read as its value
//!   in a face around the vertex; otherwise each value refines by its `level::Tag`: it stays
//!   (a corner), follows the crease rule `3/4 u + 1/8 (u_a + u_b)` along its span's fvar
//!   boundary, or blends the two while the semi-sharp features inside its span decay;
//! - with `all` everything is linear (values stay, midpoints, centroids).
//!
//! The face-varying topology of each level (`level::FvLevel`) is derived from that level's
//! values. The rules are those of OpenSubdiv 3.5's `Vtr::FVarLevel`, `Vtr::FVarRefinement` and
//! `Far::PrimvarRefiner` (`docs/opensubdiv-rules.md` section 9); `tests/it/osd_peer.rs` checks
//! them value by value.

mod level;
#[cfg(feature = "unit-tests")]
mod tests;

use crate::mesh::tags::{FvarInterpolation, SubdOptions};
use crate::mesh::{FaceVarying, PolyMesh};
use crate::schemes::sdc::crease::CREASE_VERTEX;
use crate::stencil::StencilTable;
use level::{FvLevel, Tag};

/// How a scheme splits faces: where each child face comes from and which child vertices are
/// face points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Split {
    /// Catmull-Clark: child face `h` is the quad at parent corner `h`; child vertices are
    /// vertex points, edge points, face points.
    Quads,
    /// Loop: child faces `4f..4f + 4` come from parent triangle `f`; child vertices are vertex
    /// points and edge points.
    Triangles,
}

/// What a scheme tells the face-varying refinement.
#[derive(Debug, Clone, Copy)]
pub struct FvarRules {
    /// The face split.
    pub split: Split,
    /// OpenSubdiv's options (the face-varying option and the sharp-feature options).
    pub options: SubdOptions,
}

/// The face-varying data of `child`, one step of `parent` (whose data is `uv`) under `rules`;
/// `stencils` are the step's vertex stencils (row `i` gives child vertex `i`). `base`: the
/// parent is the net as read (its values are grouped per vertex as OpenSubdiv groups the base
/// level's, `FvLevel::new`); refined parents carry the values this function gave them.
pub fn refine(
    parent: &PolyMesh,
    uv: &FaceVarying,
    base: bool,
    child: &PolyMesh,
    stencils: &StencilTable,
    rules: &FvarRules,
) -> FaceVarying {
    let pa = FvLevel::new(parent, &uv.corners, &rules.options, base, &uv.classes);
    let ncv = child.num_vertices();
    // Child values: per vertex point the parent's values, per seam edge one per face.
    let mut offset = Vec::with_capacity(ncv + 1);
    offset.push(0u32);
    for c in 0..ncv {
        offset.push(offset[c] + value_count(&pa, c));
    }
    let corners = child_corners(&pa, child, rules.split, &offset);
    let classes = child_classes(&pa, uv, ncv);
    let ca = FvLevel::new(child, &corners, &rules.options, false, &classes);
    let linear = rules.options.fvar() == FvarInterpolation::All;
    let mut out = vec![[0.0; 2]; *offset.last().unwrap_or(&0) as usize];
    let (nv, ne) = (parent.num_vertices(), parent.num_edges());
    for c in 0..ncv {
        let o = offset[c] as usize;
        if c < nv {
            vertex_values(&pa, &ca, uv, stencils, linear, c, o, &mut out);
        } else if c < nv + ne {
            edge_values(&pa, uv, stencils, linear, c, &mut out[o..]);
        } else {
            let f = (c - nv - ne) as u32;
            let vals: Vec<u32> = face_halfedges(&pa, f)
                .map(|h| uv.corners[h as usize])
                .collect();
            let w = 1.0 / vals.len() as f64;
            out[o] = combine(
                &vals
                    .iter()
                    .map(|&x| (uv.values[x as usize], w))
                    .collect::<Vec<_>>(),
            );
        }
    }
    FaceVarying {
        values: out,
        corners,
        names: uv.names.clone(),
        classes,
    }
}

/// How many values child vertex `c` gets: a vertex point one per parent value of its vertex,
/// an edge point one per face of its edge on a seam (else one), a face point one.
fn value_count(pa: &FvLevel<'_>, c: usize) -> u32 {
    let (nv, ne) = (pa.num_vertices(), pa.num_edges());
    if c < nv {
        pa.values(c).len() as u32
    } else if c < nv + ne && pa.discts[c - nv] {
        pa.edge_faces(c - nv).len() as u32
    } else {
        1
    }
}

/// The value of every child corner: the child vertex's first value (`offset`) plus the
/// sibling its parent corner (vertex point) or its parent face (seam edge point) picks.
fn child_corners(pa: &FvLevel<'_>, child: &PolyMesh, split: Split, offset: &[u32]) -> Vec<u32> {
    let m = pa.m;
    let (nv, ne) = (pa.num_vertices(), pa.num_edges());
    let k = child.uniform_face_size().unwrap_or(0).max(1);
    child
        .corners()
        .iter()
        .enumerate()
        .map(|(i, &c)| {
            let cf = (i / k) as u32;
            let f = match split {
                Split::Quads => m.face(cf),
                Split::Triangles => cf / 4,
            };
            let c = c as usize;
            let sibling = if c < nv {
                // The parent corner of a vertex point's corner: child face `h` (quads), the
                // corner triangle `4f + i` at `3f + i` (triangles).
                let own = match split {
                    Split::Quads => cf,
                    Split::Triangles => 3 * f + cf % 4,
                };
                let h = if (own as usize) < pa.sibling.len() && m.from(own) as usize == c {
                    Some(own)
                } else {
                    face_halfedges(pa, f).find(|&h| m.from(h) as usize == c)
                };
                h.map_or(0, |h| pa.sibling[h as usize])
            } else if c < nv + ne && pa.discts[c - nv] {
                pa.edge_faces(c - nv)
                    .iter()
                    .position(|&h| m.face(h) == f)
                    .unwrap_or(0) as u32
            } else {
                0
            };
            offset[c] + sibling
        })
        .collect()
}

/// Seam classes of the child values: a vertex point's values keep their parent values'
/// classes, every other value is a class of its own.
fn child_classes(pa: &FvLevel<'_>, uv: &FaceVarying, ncv: usize) -> Vec<u32> {
    let nv = pa.num_vertices();
    let class_of = |v: u32| uv.classes.get(v as usize).copied().unwrap_or(v);
    let space = uv
        .classes
        .iter()
        .max()
        .map_or(0, |&c| c + 1)
        .max(uv.values.len() as u32);
    let mut classes = Vec::new();
    for c in 0..ncv {
        for s in 0..value_count(pa, c) as usize {
            let own = space + classes.len() as u32;
            classes.push(if c < nv {
                class_of(pa.values(c)[s])
            } else {
                own
            });
        }
    }
    classes
}

/// The values of vertex point `c` (its first at `out[o]`): the vertex's own stencil where its
/// value topology matches, else each value by its tag (it stays, follows the crease rule along
/// its span's fvar boundary, or blends the two while a semi-sharp feature decays).
#[allow(clippy::too_many_arguments)]
fn vertex_values(
    pa: &FvLevel<'_>,
    ca: &FvLevel<'_>,
    uv: &FaceVarying,
    stencils: &StencilTable,
    linear: bool,
    c: usize,
    o: usize,
    out: &mut [[f64; 2]],
) {
    let src = &uv.values;
    let at = |val: u32| src[val as usize];
    let tags = pa.tags(c);
    if tags.first() == Some(&Tag::Match) && !linear {
        out[o] = mapped(pa, stencils.row(c), pa.ring(c), src);
        return;
    }
    for (j, (&val, &tag)) in pa.values(c).iter().zip(tags).enumerate() {
        let child_tag = ca
            .values(c)
            .iter()
            .position(|&x| x as usize == o + j)
            .and_then(|k| ca.tags(c).get(k).copied())
            .unwrap_or(Tag::Corner);
        out[o + j] = match tag.span() {
            Some((start, end)) if !linear && !child_tag.stays() => {
                let w = match tag {
                    Tag::SemiSharp { .. } => pa.fractional_weight(c, start, end),
                    Tag::DepSharp { .. } => other_weight(pa, c, j),
                    _ => 0.0,
                };
                let [a, b] = pa.crease_ends(c, start, end);
                let (cv, ce) = CREASE_VERTEX;
                let (vw, ew) = ((1.0 - w) * cv + w, (1.0 - w) * ce);
                combine(&[(at(val), vw), (at(a), ew), (at(b), ew)])
            }
            _ => at(val),
        };
    }
}

/// The values of edge point `c` (from `out[0]`): the edge's own stencil where its values agree
/// across it, else each face side's midpoint of its two values (a seam, a linear boundary, or
/// everything linear).
fn edge_values(
    pa: &FvLevel<'_>,
    uv: &FaceVarying,
    stencils: &StencilTable,
    linear: bool,
    c: usize,
    out: &mut [[f64; 2]],
) {
    let e = c - pa.num_vertices();
    let hs = pa.edge_faces(e);
    if !pa.discts[e] && !pa.linear[e] && !linear {
        out[0] = mapped(pa, stencils.row(c), hs, &uv.values);
        return;
    }
    let sides = if pa.discts[e] { hs.len() } else { 1 };
    for (j, &h) in hs.iter().take(sides).enumerate() {
        let [a, b] = pa.edge_values(h);
        out[j] = combine(&[(uv.values[a as usize], 0.5), (uv.values[b as usize], 0.5)]);
    }
}

/// The half-edges of parent face `f`.
fn face_halfedges<'a>(pa: &'a FvLevel<'_>, f: u32) -> impl Iterator<Item = u32> + 'a {
    let m = pa.m;
    let h0 = m.faces.start(f as usize);
    let n = m.face_corners(f as usize).len() as u32;
    h0..h0 + n
}

/// A vertex stencil row applied to face-varying values: each parent vertex is read as its
/// value at the ends of the half-edges `hes` (one per face), else at its corners in the faces of
/// `hes`. A vertex that is a corner of several of those faces (or twice a corner of one, a face
/// that repeats a vertex) with different values there gets its weight split among them in
/// proportion to each corner's share of its face's centroid (`1 / face size`): the scheme's
/// stencil row sums these face contributions into one column, and every rule that reads a face
/// beyond the half-edge ends (Catmull-Clark's face points, Loop's opposite vertices) reads it
/// through the centroid with the same weight for all faces of the ring.
fn mapped(pa: &FvLevel<'_>, row: (&[u32], &[f64]), hes: &[u32], src: &[[f64; 2]]) -> [f64; 2] {
    let m = pa.m;
    let mut terms: Vec<([f64; 2], f64)> = Vec::with_capacity(row.0.len());
    let mut shares: Vec<(u32, f64)> = Vec::new();
    for (&u, &w) in row.0.iter().zip(row.1) {
        // The corners of the half-edges themselves first (a face may repeat a vertex).
        let own = hes.iter().find_map(|&h| {
            let n = m.faces.next(h);
            [h, n]
                .into_iter()
                .find(|&x| m.from(x) == u)
                .map(|x| pa.corner_value[x as usize])
        });
        if let Some(val) = own {
            terms.push((src[val as usize], w));
            continue;
        }
        shares.clear();
        for (i, &h) in hes.iter().enumerate() {
            let f = m.face(h);
            if hes[..i].iter().any(|&g| m.face(g) == f) {
                continue;
            }
            let size = m.face_corners(f as usize).len() as f64;
            for x in face_halfedges(pa, f).filter(|&x| m.from(x) == u) {
                shares.push((pa.corner_value[x as usize], 1.0 / size));
            }
        }
        let total: f64 = shares.iter().map(|s| s.1).sum();
        match shares.first() {
            Some(&(first, _)) if shares.iter().any(|s| s.0 != first) => {
                terms.extend(
                    shares
                        .iter()
                        .map(|&(val, s)| (src[val as usize], w * s / total)),
                );
            }
            first => terms.push((src[first.map_or(0, |s| s.0) as usize], w)),
        }
    }
    combine(&terms)
}

/// The corner weight of the other value of a two-value vertex (a dependent-sharp value takes
/// the decay of the value it depends on).
fn other_weight(pa: &FvLevel<'_>, v: usize, j: usize) -> f64 {
    match pa.tags(v).get(1 - j.min(1)).and_then(|t| t.span()) {
        Some((s, e)) => pa.fractional_weight(v, s, e),
        None => 0.0,
    }
}

/// `sum w_i p_i`.
fn combine(terms: &[([f64; 2], f64)]) -> [f64; 2] {
    let mut acc = [0.0; 2];
    for (p, w) in terms {
        acc[0] += w * p[0];
        acc[1] += w * p[1];
    }
    acc
}
