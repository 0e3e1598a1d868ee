//! One dual step on a selection of faces: the mesh layer's dual split
//! ([`crate::mesh::dual_split`]) with this family's sharp features, its child points given their
//! stencils (corner points by the scheme's rule, Chaikin points on sharp edges, kept points)
//! and their trust, its child faces (F-, E- and V-faces) their input elements and sharpness.
//! The adaptive host refines the faces around its marked vertices with it
//! ([`super::refine`]); a whole net with sharp features is refined with all its faces selected
//! ([`crate::schemes::doo_sabin::refine_dual_with`]).
//!
//! Without creases ([`Creases`]) the points and faces are those of the boundary rules of
//! [`crate::schemes::doo_sabin`]. With creases
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
use crate::mesh::dual_split::{
    DualFace, DualFeatures, DualOrder, DualPoint, DualSplit, VFaces, dual_split,
};
use crate::mesh::tags::SubdOptions;
use crate::mesh::{Element, Extras, NONE, PolyMesh, SharpEdges};
use crate::schemes::doo_sabin::fourier::FaceCorners;
use crate::schemes::doo_sabin::fourier::LARGE_FACE;
use crate::schemes::doo_sabin::sharp::step::Creases;
use crate::schemes::doo_sabin::{CHAIKIN, sharp::is_kept_corner};
use crate::schemes::sdc::crease::{Scratch, VertexMask, VertexPlan};
use crate::stencil::{Stencil, StencilTable};

mod faces;
use faces::faces;

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
    /// Input element of each child face that is not a quad.
    pub face_origin: Vec<Option<Element>>,
    /// The split: its points (corner, Chaikin and kept points of each parent element) and
    /// child faces.
    pub split: DualSplit,
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

/// One step of the faces `sel_faces` of `inp` (see the [module](self) documentation): the
/// mesh layer's dual split ([`dual_split`]) with the sharp features of `creases` (or the plain
/// boundary rules), numbered by `order`; this function gives its points their stencils and
/// trust.
pub(crate) fn dual_step(
    inp: &StepIn<'_>,
    (sel_faces, order): (Vec<u32>, DualOrder),
    corner: &mut dyn FnMut(&PolyMesh, u32) -> Stencil,
    creases: Option<&Creases<'_>>,
) -> Result<StepOut> {
    let m = inp.mesh;
    let mut sel = vec![false; m.num_faces()];
    for &f in &sel_faces {
        sel[f as usize] = true;
    }
    let trust = SplitTrust::new(m, inp.info, &sel);
    let mut features = StepFeatures {
        inp,
        creases,
        trust: &trust,
        scratch: Scratch::default(),
        kept_plans: Vec::new(),
    };
    let split = dual_split(m, sel_faces, &mut features, order);
    let kept_plans = features.kept_plans;
    let n = split.points.len();
    let untrusted = Info {
        pos_ok: false,
        fan_ok: false,
        origin: None,
    };
    let mut o = StepOut {
        stencils: vec![Stencil::new(); n],
        info: vec![untrusted; n],
        rule_free: vec![false; n],
        fixed: Vec::new(),
        derived: Vec::new(),
        face_origin: Vec::new(),
        split,
        extras: None,
    };
    corner_points(inp, corner, creases, &trust, &mut o);
    let (blends, kept_blends) = edge_and_kept_points(inp, creases, &trust, &kept_plans, &mut o);
    blend_chaikin_points(m, &mut o, &blends);
    if let Some(c) = creases {
        blend_kept_points(m, c, &mut o, &kept_blends);
    }
    faces(inp, creases, &mut o)?;
    Ok(o)
}

/// Whether no boundary rule entered point `x` (always, unless the boundary mode is `none`).
fn rule_free(inp: &StepIn<'_>, x: u32) -> bool {
    inp.rule_free.is_none_or(|r| r[x as usize])
}

/// The corner points, face by face: by the scheme's corner rule (on the face alone where a
/// crease touches it), or a large face's all at once as positions; each trusted when every
/// point its rule reads is.
fn corner_points(
    inp: &StepIn<'_>,
    corner: &mut dyn FnMut(&PolyMesh, u32) -> Stencil,
    creases: Option<&Creases<'_>>,
    trust: &SplitTrust<'_>,
    o: &mut StepOut,
) {
    let m = inp.mesh;
    for i in 0..o.split.sel_faces.len() {
        let f = o.split.sel_faces[i] as usize;
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
                let rf = fc.reads.iter().all(|&x| rule_free(inp, x));
                (fc.points, ok, rf)
            });
        for h in h0..h0 + m.face_size(f) as u32 {
            let p = o.split.corner_pt[h as usize] as usize;
            let (st, pos, rf) = match &large {
                Some((points, ok, rf)) => {
                    o.fixed.push((p as u32, points[(h - h0) as usize]));
                    (Stencil::new(), *ok, *rf)
                }
                None => {
                    let st = match &alone {
                        Some(a) => a.corner(corner, (h - h0) as usize),
                        None => corner(m, h),
                    };
                    // trusted when every point the rule reads is (it may reach beyond the face)
                    let pos = trust.reads_ok(&st);
                    let rf = st.entries().iter().all(|&(x, _)| rule_free(inp, x));
                    (st, pos, rf)
                }
            };
            o.stencils[p] = st;
            o.info[p] = trust.dual_point(m.he_from(h) as usize, pos);
            o.rule_free[p] = rf;
        }
    }
}

/// A Chaikin point whose crease decays this step: `(point, edge, end)`.
type ChaikinBlend = (u32, usize, usize);

/// A kept point whose corner decays this step: `(point, vertex, plan)`.
type KeptBlend = (u32, usize, VertexPlan);

/// The Chaikin points of sharp edges and the kept points, in their order (`kept_plans`: the
/// kept points' vertex plans, in the same order). Returns the points whose feature decays
/// this step.
fn edge_and_kept_points(
    inp: &StepIn<'_>,
    creases: Option<&Creases<'_>>,
    trust: &SplitTrust<'_>,
    kept_plans: &[VertexPlan],
    o: &mut StepOut,
) -> (Vec<ChaikinBlend>, Vec<KeptBlend>) {
    let m = inp.mesh;
    let mut blends: Vec<ChaikinBlend> = Vec::new();
    let mut kept_blends: Vec<KeptBlend> = Vec::new();
    let mut plans = kept_plans.iter();
    for p in 0..o.split.points.len() {
        match o.split.points[p] {
            DualPoint::Corner(_) => {}
            DualPoint::Chaikin { edge, end } => {
                let (e, k) = (edge as usize, end as usize);
                let [a, b] = m.edge(e).map(|x| x as usize);
                let w = creases.map_or(1.0, |c| c.weight(e));
                let (wa, wb) = CHAIKIN[k];
                let mut st = Stencil::new();
                st.add(a, wa * w).add(b, wb * w);
                let pos = inp.info[a].pos_ok && inp.info[b].pos_ok;
                o.stencils[p] = st;
                o.info[p] = trust.dual_point([a, b][k], pos);
                if w < 1.0 {
                    blends.push((p as u32, e, k));
                }
            }
            DualPoint::Kept(x) => {
                let x = x as usize;
                let plan = *plans
                    .next()
                    .expect("the features gave a plan for every kept point");
                let w = match plan {
                    VertexPlan::Blend { w, .. } => w,
                    VertexPlan::Single(_) => 1.0,
                };
                o.stencils[p] = Stencil::from_pairs([(x, w)]);
                o.info[p] = trust.dual_point(x, inp.info[x].pos_ok);
                if w < 1.0 {
                    kept_blends.push((p as u32, x, plan));
                }
            }
        }
    }
    debug_assert!(plans.next().is_none(), "a plan without its kept point");
    (blends, kept_blends)
}

/// The sharp features of one dual step for the mesh layer's split: Chaikin points on sharp
/// edges (with creases, by sharpness; without, on the true boundary edges of the partial net:
/// an end has its true fan), kept points where the vertex rule keeps the corner, V-faces at
/// the vertices whose whole fan is refined, split into the sectors between sharp edges.
struct StepFeatures<'a> {
    inp: &'a StepIn<'a>,
    creases: Option<&'a Creases<'a>>,
    trust: &'a SplitTrust<'a>,
    scratch: Scratch,
    /// The vertex plan of each kept point, in the order the split numbers them (it asks
    /// [`DualFeatures::kept`] once per vertex and numbers a kept point at each yes).
    kept_plans: Vec<VertexPlan>,
}

impl DualFeatures for StepFeatures<'_> {
    fn chaikin(&mut self, e: usize) -> bool {
        let m = self.inp.mesh;
        match self.creases {
            Some(c) => c.is_sharp(e),
            None => {
                let h = m.edge_halfedge(e);
                let info = self.inp.info;
                m.he_twin(h).is_none()
                    && (info[m.he_from(h) as usize].fan_ok || info[m.he_to(h) as usize].fan_ok)
            }
        }
    }

    fn kept(&mut self, v: usize) -> bool {
        if !self.inp.info[v].fan_ok {
            return false;
        }
        let plan = match self.creases {
            Some(c) => c.kept(v, &mut self.scratch),
            None => {
                is_kept_corner(self.inp.mesh, v).then_some(VertexPlan::Single(VertexMask::Corner))
            }
        };
        match plan {
            Some(plan) => {
                self.kept_plans.push(plan);
                true
            }
            None => false,
        }
    }

    fn v_faces(&mut self, v: usize, hs: &[u32]) -> VFaces {
        match self.creases {
            _ if !self.trust.whole_fan(v) => VFaces::None,
            Some(c) => VFaces::Sectors(c.sectors(v, hs)),
            None => VFaces::Whole,
        }
    }
}

/// The blends of the Chaikin points of decaying creases: toward the midpoint of the two corner
/// points they sit between (the E-face's side at that end), with the weight left by the
/// edge's fractional sharpness. A point whose corner points are not made is not trusted.
fn blend_chaikin_points(m: &PolyMesh, o: &mut StepOut, blends: &[ChaikinBlend]) {
    for &(p, e, k) in blends {
        let h = m.edge_halfedge(e);
        let Some(t) = m.he_twin(h) else { continue };
        // the corners at the end `k` of the two faces of the edge
        let (c1, c2) = if k == 0 {
            (
                o.split.corner_pt[h as usize],
                o.split.corner_pt[m.he_next(t) as usize],
            )
        } else {
            (
                o.split.corner_pt[m.he_next(h) as usize],
                o.split.corner_pt[t as usize],
            )
        };
        let w = o.stencils[p as usize].weight_sum();
        if c1 == NONE || c2 == NONE {
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
fn blend_kept_points(m: &PolyMesh, c: &Creases<'_>, o: &mut StepOut, blends: &[KeptBlend]) {
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
                    let pt = c.spoke_to(v, to, &mut spokes).map_or(NONE, |e| {
                        let e = e as usize;
                        let near = usize::from(m.he_from(m.edge_halfedge(e)) as usize != v);
                        o.split.edge_pt[e][near]
                    });
                    (pt, 0.5 * rest)
                })
                .collect(),
            _ => {
                let hs = m.outgoing_halfedges(v);
                let k = hs.len() as f64;
                hs.iter()
                    .map(|&h| (o.split.corner_pt[h as usize], rest / k))
                    .collect()
            }
        };
        if parts.iter().any(|&(x, _)| x == NONE) {
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
