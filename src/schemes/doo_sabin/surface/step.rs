//! One dual step on a selection of faces: the child points (corner points by the scheme's rule,
//! Chaikin points on sharp edges, kept points), their trust, and the child faces (F-, E- and
//! V-faces). The adaptive host refines the faces around its marked vertices with it
//! ([`super::refine`]); a whole net with sharp features is refined with all its faces selected
//! ([`crate::schemes::doo_sabin::refine_dual_with`]).
//!
//! Without creases ([`Creases`]) the points and faces are those of the boundary rules of
//! [`crate::schemes::doo_sabin`] in the order the adaptive host has always used. With creases
//! they follow fairsub's crease construction ([`crate::schemes::doo_sabin::sharp`]): a sharp
//! edge inside the surface gets the two Chaikin points of its sides (shared by both sides),
//! its E-face splits into one half per side, a vertex's V-face into the sectors between its
//! sharp edges, and a point whose feature decays this step blends from its sharp position
//! toward the smooth one ([`Derived`]).

#[cfg(doc)]
use super::DualRules;
use crate::error::{Error, Result};
use crate::geom::Point;
use crate::host::adaptive::{Info, SplitTrust};
use crate::mesh::tags::SubdOptions;
use crate::mesh::{Element, Extras, PolyMesh, SharpEdges};
use crate::schemes::doo_sabin::fourier::FaceCorners;
use crate::schemes::doo_sabin::fourier::LARGE_FACE;
use crate::schemes::doo_sabin::sharp::step::{Creases, Sector};
use crate::schemes::doo_sabin::{CHAIKIN, sharp::is_kept_corner};
use crate::schemes::sdc::crease::{Scratch, VertexMask, VertexPlan};
use crate::stencil::{Stencil, StencilTable};

mod faces;
use faces::faces;

/// A point not made yet.
pub(crate) const UNSET: u32 = u32::MAX;

/// What one step reads: a level's net, the trust of its points and, under the boundary mode
/// `none`, which of them are rule-free.
pub(crate) struct StepIn<'a> {
    /// The net (a whole net, or a partially refined level).
    pub mesh: &'a PolyMesh,
    /// Trust of its points.
    pub info: &'a [Info],
    /// Boundary `none`: per point, whether no boundary rule entered it.
    pub rule_free: Option<&'a [bool]>,
    /// Input element of each non-quad face.
    pub face_origin: &'a [Option<Element>],
    /// All new corners of a face at once as positions, for the faces above [`LARGE_FACE`]
    /// (the adaptive host); `None`: stencils for every corner (a stencil table is wanted).
    pub face_corners: Option<&'a FaceCornersFn<'a>>,
}

/// The rule giving all new corners of a face at once ([`DualRules::face_corners`]).
pub(crate) type FaceCornersFn<'a> = dyn Fn(&PolyMesh, usize) -> FaceCorners + Sync + 'a;

/// A child point whose position adds weighted child points to its stencil's (the blend of a
/// decaying feature toward the smooth position, made of other child points).
#[derive(Debug, Clone)]
pub(crate) struct Derived {
    /// The point.
    pub point: u32,
    /// Child points and their weights.
    pub parts: Vec<(u32, f64)>,
}

/// The child of one step (see the [module](self) documentation).
pub(crate) struct StepOut {
    /// Per child point: its stencil over the parent's points (empty for `fixed` ones).
    pub stencils: Vec<Stencil>,
    /// Per child point: its trust.
    pub info: Vec<Info>,
    /// Per child point: rule-free (boundary `none`).
    pub rule_free: Vec<bool>,
    /// Corners of large faces, as positions.
    pub fixed: Vec<(u32, Point)>,
    /// Blended points, in an order where parts come first.
    pub derived: Vec<Derived>,
    /// The corner point of each parent half-edge (`UNSET` outside the selection).
    pub corner_pt: Vec<u32>,
    /// The two Chaikin points of each sharp parent edge (near the start, near the end of its
    /// edge half-edge).
    pub edge_pt: Vec<[u32; 2]>,
    /// The kept point of each parent vertex.
    pub kept: Vec<u32>,
    /// Child faces.
    pub face_start: Vec<u32>,
    /// Child face corners.
    pub corners: Vec<u32>,
    /// Input element of each child face that is not a quad.
    pub face_origin: Vec<Option<Element>>,
    /// The selected parent faces (the F-faces are the first child faces, in this order).
    pub sel_faces: Vec<u32>,
    /// The child's sharp features (with creases only).
    pub extras: Option<Extras>,
}

impl StepOut {
    /// The child positions: the stencils applied to `parent`, the fixed positions, then the
    /// blended points.
    pub fn positions(&self, parent: &[Point]) -> Vec<Point> {
        let rows = self.stencils.clone();
        let mut pos = StencilTable::from_rows(parent.len(), rows, 6).apply(parent);
        for &(i, p) in &self.fixed {
            pos[i as usize] = p;
        }
        for d in &self.derived {
            let mut p = pos[d.point as usize];
            for &(x, w) in &d.parts {
                p = crate::geom::axpy(p, w, pos[x as usize]);
            }
            pos[d.point as usize] = p;
        }
        pos
    }

    /// The stencils with the blended points composed in (no fixed positions).
    pub fn composed_stencils(&self) -> Vec<Stencil> {
        let mut st = self.stencils.clone();
        for d in &self.derived {
            let mut s = std::mem::take(&mut st[d.point as usize]);
            for &(x, w) in &d.parts {
                s.add_scaled(&st[x as usize], w);
            }
            st[d.point as usize] = s.merged();
        }
        st
    }
}

/// One step of the faces `sel_faces` of `inp` (see the [module](self) documentation).
pub(crate) fn dual_step(
    inp: &StepIn<'_>,
    mut sel_faces: Vec<u32>,
    corner: &mut dyn FnMut(&PolyMesh, u32) -> Stencil,
    creases: Option<&Creases<'_>>,
) -> Result<StepOut> {
    let m = inp.mesh;
    let (nv, nf, ne) = (m.num_vertices(), m.num_faces(), m.num_edges());
    sel_faces.sort_unstable();
    let mut sel = vec![false; nf];
    for &f in &sel_faces {
        sel[f as usize] = true;
    }
    let trust = SplitTrust::new(m, inp.info, &sel);
    let whole_fan = |v: usize| trust.whole_fan(v);
    // A parent edge gets Chaikin points when it is sharp: with creases, by its sharpness
    // (boundary edges are infinitely sharp); without, when it is a true boundary edge (of the
    // partial net: an end has its true fan).
    let sharp_edge = |h: u32| match creases {
        Some(c) => c.is_sharp(m.he_edge(h) as usize),
        None => {
            m.he_twin(h).is_none()
                && (inp.info[m.he_from(h) as usize].fan_ok || inp.info[m.he_to(h) as usize].fan_ok)
        }
    };
    let free = |x: u32| inp.rule_free.is_none_or(|r| r[x as usize]);
    let mut o = StepOut {
        stencils: Vec::new(),
        info: Vec::new(),
        rule_free: Vec::new(),
        fixed: Vec::new(),
        derived: Vec::new(),
        corner_pt: vec![UNSET; m.num_halfedges()],
        edge_pt: vec![[UNSET; 2]; ne],
        kept: vec![UNSET; nv],
        face_start: vec![0],
        corners: Vec::new(),
        face_origin: Vec::new(),
        sel_faces: Vec::new(),
        extras: None,
    };
    let push = |o: &mut StepOut, s: Stencil, i: Info, rf: bool| -> u32 {
        o.stencils.push(s);
        o.info.push(i);
        o.rule_free.push(rf);
        (o.stencils.len() - 1) as u32
    };
    let mut scratch = Scratch::default();
    let mut blends: Vec<(u32, usize, usize)> = Vec::new();
    let mut kept_blends: Vec<(u32, usize, VertexPlan)> = Vec::new();
    for &f in &sel_faces {
        let f = f as usize;
        let h0 = m.face_halfedge(f);
        let alone = creases
            .is_some_and(|c| c.touches(f))
            .then(|| FaceAlone::new(m, f));
        let large = inp
            .face_corners
            .filter(|_| m.face_size(f) > LARGE_FACE)
            .map(|rule| {
                let rule: &FaceCornersFn<'_> = rule;
                let fc = match &alone {
                    Some(a) => a.face_corners(rule),
                    None => rule(m, f),
                };
                let ok = fc.reads.iter().all(|&x| inp.info[x as usize].pos_ok);
                let rf = fc.reads.iter().all(|&x| free(x));
                (fc.points, ok, rf)
            });
        for h in h0..h0 + m.face_size(f) as u32 {
            let v = m.he_from(h) as usize;
            let (st, pos, rf) = match &large {
                Some((points, ok, rf)) => {
                    o.fixed
                        .push((o.stencils.len() as u32, points[(h - h0) as usize]));
                    (Stencil::new(), *ok, *rf)
                }
                None => {
                    let st = match &alone {
                        Some(a) => a.corner(corner, (h - h0) as usize),
                        None => corner(m, h),
                    };
                    // trusted when every point the rule reads is (it may reach beyond the face)
                    let pos = st
                        .entries()
                        .iter()
                        .all(|&(x, _)| inp.info[x as usize].pos_ok);
                    let rf = st.entries().iter().all(|&(x, _)| free(x));
                    (st, pos, rf)
                }
            };
            o.corner_pt[h as usize] = push(&mut o, st, trust.dual_point(v, pos), rf);
            let e = m.he_edge(h) as usize;
            if sharp_edge(h) && o.edge_pt[e][0] == UNSET {
                let eh = m.edge_halfedge(e);
                let (a, b) = (m.he_from(eh) as usize, m.he_to(eh) as usize);
                let pos = inp.info[a].pos_ok && inp.info[b].pos_ok;
                let w = creases.map_or(1.0, |c| c.weight(e));
                for (k, end) in [a, b].into_iter().enumerate() {
                    let (wa, wb) = CHAIKIN[k];
                    let mut s = Stencil::new();
                    s.add(a, wa * w).add(b, wb * w);
                    o.edge_pt[e][k] = push(&mut o, s, trust.dual_point(end, pos), false);
                    if w < 1.0 {
                        blends.push((o.edge_pt[e][k], e, k));
                    }
                }
            }
        }
        for &x in m.face(f) {
            let x = x as usize;
            if o.kept[x] != UNSET || !inp.info[x].fan_ok {
                continue;
            }
            let plan = match creases {
                Some(c) => c.kept(x, &mut scratch),
                None => is_kept_corner(m, x).then_some(VertexPlan::Single(VertexMask::Corner)),
            };
            let Some(plan) = plan else { continue };
            let w = match plan {
                VertexPlan::Blend { w, .. } => w,
                VertexPlan::Single(_) => 1.0,
            };
            let info = trust.dual_point(x, inp.info[x].pos_ok);
            o.kept[x] = push(&mut o, Stencil::from_pairs([(x, w)]), info, false);
            if w < 1.0 {
                kept_blends.push((o.kept[x], x, plan));
            }
        }
    }
    blend_chaikin_points(m, &mut o, &blends);
    if let Some(c) = creases {
        blend_kept_points(m, c, &mut o, &kept_blends);
    }
    o.sel_faces = sel_faces;
    faces(inp, &sel, &whole_fan, creases, &mut o)?;
    Ok(o)
}

/// The blends of the Chaikin points of decaying creases: toward the midpoint of the two corner
/// points they sit between (the E-face's side at that end), with the weight left by the
/// edge's fractional sharpness. A point whose corner points are not made is not trusted.
fn blend_chaikin_points(m: &PolyMesh, o: &mut StepOut, blends: &[(u32, usize, usize)]) {
    for &(p, e, k) in blends {
        let h = m.edge_halfedge(e);
        let Some(t) = m.he_twin(h) else { continue };
        // the corners at the end `k` of the two faces of the edge
        let (c1, c2) = if k == 0 {
            (o.corner_pt[h as usize], o.corner_pt[m.he_next(t) as usize])
        } else {
            (o.corner_pt[m.he_next(h) as usize], o.corner_pt[t as usize])
        };
        let w = o.stencils[p as usize].weight_sum();
        if c1 == UNSET || c2 == UNSET {
            o.info[p as usize].pos_ok = false;
            continue;
        }
        let ok = o.info[c1 as usize].pos_ok && o.info[c2 as usize].pos_ok;
        o.info[p as usize].pos_ok &= ok;
        let r = 0.5 * (1.0 - w);
        o.derived.push(Derived {
            point: p,
            parts: vec![(c1, r), (c2, r)],
        });
    }
}

/// The blends of the kept points of decaying corners: toward the midpoint of the Chaikin points
/// of the two edges that stay sharp when the child's rule is the crease rule, else toward the
/// centroid of the vertex's corner points.
fn blend_kept_points(
    m: &PolyMesh,
    c: &Creases<'_>,
    o: &mut StepOut,
    blends: &[(u32, usize, VertexPlan)],
) {
    let mut spokes = Vec::new();
    for &(p, v, plan) in blends {
        let VertexPlan::Blend { child, w, .. } = plan else {
            continue;
        };
        let rest = 1.0 - w;
        let parts: Vec<(u32, f64)> = match child {
            VertexMask::Crease(a, b) => [a, b]
                .into_iter()
                .map(|to| {
                    let pt = c.spoke_to(v, to, &mut spokes).map_or(UNSET, |e| {
                        let e = e as usize;
                        let near = usize::from(m.he_from(m.edge_halfedge(e)) as usize != v);
                        o.edge_pt[e][near]
                    });
                    (pt, 0.5 * rest)
                })
                .collect(),
            _ => {
                let hs = m.outgoing_halfedges(v);
                let k = hs.len() as f64;
                hs.iter()
                    .map(|&h| (o.corner_pt[h as usize], rest / k))
                    .collect()
            }
        };
        if parts.iter().any(|&(x, _)| x == UNSET) {
            o.info[p as usize].pos_ok = false;
            continue;
        }
        let ok = parts.iter().all(|&(x, _)| o.info[x as usize].pos_ok);
        o.info[p as usize].pos_ok &= ok;
        o.derived.push(Derived { point: p, parts });
    }
}

/// The corner points of one face computed on the face alone (a one-face net): the corner
/// rule of a net cut along its creases at a face whose corner lies on one, where that corner
/// is a boundary vertex (PGS then falls back to Doo-Sabin's rule; Doo-Sabin's and DS^CC's
/// rules read the face alone anyway).
struct FaceAlone {
    net: PolyMesh,
    verts: Vec<u32>,
}

impl FaceAlone {
    fn new(m: &PolyMesh, f: usize) -> FaceAlone {
        let verts = m.face(f).to_vec();
        let pos = verts.iter().map(|&v| m.positions()[v as usize]).collect();
        let face: Vec<usize> = (0..verts.len()).collect();
        let net =
            PolyMesh::new(pos, &[face]).expect("a face of a valid net is a valid one-face net");
        FaceAlone { net, verts }
    }

    fn corner(&self, rule: &mut dyn FnMut(&PolyMesh, u32) -> Stencil, k: usize) -> Stencil {
        let s = rule(&self.net, k as u32);
        Stencil::from_pairs(
            s.entries()
                .iter()
                .map(|&(x, w)| (self.verts[x as usize] as usize, w)),
        )
    }

    fn face_corners(&self, rule: &FaceCornersFn<'_>) -> FaceCorners {
        let mut fc = rule(&self.net, 0);
        for r in &mut fc.reads {
            *r = self.verts[*r as usize];
        }
        fc
    }
}
