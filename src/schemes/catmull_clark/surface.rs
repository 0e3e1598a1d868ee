//! Catmull-Clark surfaces as exact patch complexes, by adaptive refinement.
//!
//! Every regular quad (see [`super::regular::bi3_net`]) is one exact bi-3 patch. Faces that are not
//! regular (they touch an extraordinary vertex, a non-quad facet or an irregular boundary vertex)
//! are refined with Catmull-Clark's own stencils ([`crate::schemes::catmull_clark`]) together with
//! the ring of faces around them (every face sharing a vertex with one); the children that have become regular are emitted as
//! ring `l` (the papers' layout: ring `l` lies at refinement level `l`, `3n` patches around an
//! isolated vertex of valence `n`), the rest is refined again. After `rings` levels the faces
//! still touching an extraordinary element are closed by a G^1 cap or the *Hermite-Coons fill*
//! below, or left open.
//!
//! Only a neighbourhood of the irregular faces is refined, so the cost per level stays
//! proportional to the number of extraordinary elements. A vertex of a partially refined level is
//! trusted only where its position and its whole fan of faces are known to equal those of the
//! uniformly refined mesh; regular patches are emitted only from trusted vertices.
//!
//! One ring of faces around the marked faces is enough: the B-spline net of a child of a marked
//! face `F` consists of the vertex points of `F`'s corners (whose stencils read the faces around
//! those corners: the ring), edge and face points of `F` and of the faces across its edges and
//! corners (the ring again), and the fan of each of the child's corners consists of children of
//! `F` and of the ring. The cap schemes' two-ring c-nets at the next level lie in the same
//! children. Refining two rings (as before 2026-12-04) gave byte-identical complexes and tables
//! on 680 gallery and OpenSubdiv-tagged cases (Catmull-Clark, EG, QAS+, guided bi-6, 1 and 3
//! rings) at 56% of the refined points (quad-evs 100k: 3.4M against 6.1M); the trust flags
//! would keep a patch back rather than emit it from an untrusted point.
//!
//! # Caps
//!
//! After `rings` levels every extraordinary element whose hole is surrounded by patches of the
//! last level gets the G^1 cap of `g1` (the module documents its conditions, free parameters
//! and the extra levels where two holes still touch; at a plain boundary vertex the open fan).
//! The others (vertices on creases or with sharpness, and elements whose holes do not
//! separate) are closed by the Hermite-Coons fill below, or left open (`--no-fill`).
//!
//! # The Hermite-Coons fill (fairsub's own, documented construction)
//!
//! Each face left inside the last ring becomes one bi-3 patch. Its four boundary curves are
//! cubics defined once per edge and shared by both faces at the edge, so the fill is C^0
//! everywhere: an edge shared with an emitted ring patch takes that patch's boundary curve
//! (exact); any other edge is the cubic Hermite interpolant of the Catmull-Clark limit
//! positions of its end points and the limit derivatives along the edge (exact at regular
//! vertices, the Halstead et al. eigenvector tangent scaled by `1 / (3 n)` at an extraordinary
//! vertex of valence `n`, which is exact for `n = 4`; at irregular boundary vertices the chord).
//! All spokes at an extraordinary vertex therefore lie in its limit tangent plane. The interior
//! coefficients are those of the bilinearly blended Coons patch of the four curves. The fill is
//! C^0 to the last ring and between fill patches and G^1 at the centre; it is not G^1 across its
//! own boundaries. `fairsub check` measures its defects.

mod caps;
mod emit;
mod fill;
mod g1;
mod jets;
pub mod sharp;
mod track;

use super::regular::{Net, bi3_net};
use crate::bezier::BezierPatch;
use crate::bezier::complex::{Domain, PatchComplex, Provenance};
use crate::error::{Error, Result};
use crate::geom::{self, Point};
use crate::host::ComplexOptions;
use crate::host::adaptive::{
    self, AdaptiveRules, Curves, FanSectors, Info, MeshLevel, Sink, SplitTrust, Tag, record_edge,
    select_around,
};
use crate::host::caps::CapBuilder;
use crate::mesh::split::{Numbering, SplitPoint, sparse_split};
use crate::mesh::tags::SubdOptions;
use crate::mesh::{Element, PolyMesh};
use crate::schemes::sdc::crease::Scratch;
pub use crate::schemes::sdc::crease::adaptive::Level;
use crate::schemes::sdc::crease::adaptive::{
    child as sharp_child, crease_curve, edge_known, is_hole, is_last_cap_level, touches_features,
};
use crate::stencil::{RowWriter, StencilTable, Terms};
use caps::apply_caps;
use fill::fill;
use rayon::prelude::*;
use std::collections::{HashMap, HashSet};
pub use track::{bspline_coefficients, bspline_patch, catmull_clark_tracked};

/// The Catmull-Clark surface of `mesh` as a patch complex: bi-3 patches on regular faces,
/// `opts.rings` rings of bi-3 patches around every extraordinary element and, if `opts.fill`, the
/// Hermite-Coons fill. `progress(level)` is called after each level.
pub fn catmull_clark_complex(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    progress: impl FnMut(usize),
) -> Result<PatchComplex> {
    catmull_clark_complex_with(mesh, opts, SubdOptions::default(), progress)
}

/// [`catmull_clark_complex`] with OpenSubdiv's options: the net's sharp features, boundary
/// option and holes as [`sharp`] documents.
pub fn catmull_clark_complex_with(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    subd: SubdOptions,
    mut progress: impl FnMut(usize),
) -> Result<PatchComplex> {
    let rules = CcRules {
        caps: None,
        opts,
        subd: Some(subd),
        track: None,
    };
    adaptive::run(&rules, mesh, opts, &mut progress)
}

/// The Catmull-Clark surface of `mesh` with the caps of `caps` around every extraordinary vertex
/// it takes (the adaptive loop with [`CcRules`]). A net that tags sharp features (creases,
/// corners, holes) is refined with OpenSubdiv's rules under the net's own option tags, as
/// [`catmull_clark_complex_with`] does; an extraordinary vertex whose c-net touches a feature is
/// left to Catmull-Clark's rings and cap (the cap schemes' rules are for smooth c-nets), with a
/// note. A net without features is refined with the plain rules (the outputs of before).
pub fn capped_complex(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    caps: &dyn CapBuilder,
    progress: &mut dyn FnMut(usize),
) -> Result<PatchComplex> {
    let subd = mesh
        .extras()
        .filter(|e| e.has_features())
        .map(|e| e.options);
    adaptive::run(
        &CcRules {
            caps: Some(caps),
            opts,
            subd,
            track: None,
        },
        mesh,
        opts,
        progress,
    )
}

/// Catmull-Clark's rules for the adaptive loop, with the caps of a scheme that replaces its
/// rings around extraordinary vertices (EG, QAS+, guided) or none.
pub struct CcRules<'a> {
    /// The cap builder, if any.
    pub caps: Option<&'a dyn CapBuilder>,
    /// Rings and fill (the G^1 caps of `g1` come after `opts.rings` levels when filling).
    pub opts: ComplexOptions,
    /// OpenSubdiv's options when the net's sharp features are honoured ([`sharp`]); `None`
    /// refines every net with the plain rules (the cap schemes on a net without features).
    pub subd: Option<SubdOptions>,
    /// The patch table's rows, when tracked beside the points ([`catmull_clark_tracked`]).
    pub(crate) track: Option<std::cell::RefCell<track::Tracker>>,
}

impl AdaptiveRules for CcRules<'_> {
    type Level = Level;
    /// The faces emitted at the level and their patches: the fill reads the edge curves it
    /// shares with them off these patches (`fill`), so a level that needs no fill records
    /// nothing per patch but the pair.
    type Curves = Vec<(u32, u32)>;

    fn start(&self, mesh: &PolyMesh, opts: ComplexOptions) -> Result<Level> {
        if opts.rings == 0 && !mesh.is_all_quads() {
            let f = mesh.extraordinary_faces()[0];
            return Err(Error::InvalidArgument(format!(
                "face {f} has {} sides; the fill needs quads, so at least one ring (--rings 1) is required",
                mesh.face_size(f)
            )));
        }
        let mut level = Level::input(mesh, self.subd.as_ref());
        // Catmull-Clark splits a triangle into three quads like any n-gon: its domain is the
        // 3-gon's strip of quad sub-faces, not Loop's barycentric triangle
        // (the two differ on triangles only: no pass over the cells of an all-quad net)
        let base = &mut level.base;
        if !base.mesh.is_all_quads() {
            for (f, tag) in &mut base.active {
                tag.domain = Domain::polygon(*f, base.mesh.face_size(*f as usize));
            }
        }
        Ok(level)
    }

    fn emit(&self, level: &Level, f: u32, prov: Provenance, to: Sink<Vec<(u32, u32)>>) -> bool {
        if is_hole(level, f as usize) {
            return true;
        }
        let Some(net) = regular_net(level, f as usize) else {
            return false;
        };
        let p = net_patch(level, &net);
        let rows = emit::NetRows::of(net, self.track.is_some());
        self.push_regular(level, f, rows, p, prov, to);
        true
    }

    /// The regular patches (nets and Bezier conversion) are computed in parallel
    /// (`emit::emit_all`): the complex and table of the per-cell [`AdaptiveRules::emit`].
    fn emit_all(
        &self,
        level: &Level,
        l: usize,
        curves: &mut Vec<(u32, u32)>,
        out: &mut PatchComplex,
    ) -> Vec<(u32, Tag)> {
        emit::emit_all(self, level, l, curves, out)
    }

    fn retag(&self, level: &Level, f: u32, tag: Tag, _l: usize) -> Tag {
        tag_irregular(level, f as usize, tag, &mut FanSectors::default())
    }

    fn retag_all(&self, level: &Level, cells: Vec<(u32, Tag)>, _l: usize) -> Vec<(u32, Tag)> {
        adaptive::retag_with_fans(cells, |f, tag, fans| {
            tag_irregular(level, f as usize, tag, fans)
        })
    }

    fn caps(
        &self,
        level: &Level,
        marked: Vec<(u32, Tag)>,
        l: usize,
        out: &mut PatchComplex,
    ) -> Result<Vec<(u32, Tag)>> {
        let marked = match self.caps {
            Some(b) => apply_caps(level, marked, b, l as u32, out)?,
            None => marked,
        };
        // per-element ring counts (the limit surface's evaluation): plain Catmull-Clark only
        if self.caps.is_none()
            && self.track.is_none()
            && self.opts.fill
            && let Some(t) = adaptive::honour_ring_targets()
        {
            return Ok(g1::g1_caps_by_targets(level, marked, l, &t, out));
        }
        if self.opts.fill && l >= self.opts.rings {
            let before = out.caps.len();
            let left = g1::g1_caps(level, &marked, out);
            if let Some(t) = &self.track {
                t.borrow_mut().caps(level, &marked, out, before);
            }
            Ok(left)
        } else {
            Ok(marked)
        }
    }

    /// `is_last_cap_level`: holes that touch or wait for semi-sharp features to be spent.
    fn is_last(&self, l: usize, rings: usize, level: &Level, marked: &[(u32, Tag)]) -> bool {
        let waiting = || g1::waiting(level, marked);
        is_last_cap_level((l, rings, self.opts.fill), level, waiting)
    }

    fn fill(&self, level: &Level, marked: &[(u32, Tag)], to: Sink<Vec<(u32, u32)>>) -> Result<()> {
        fill(level, marked, to.curves, to.out)
    }

    fn refine_around(&self, level: &Level, marked: &[(u32, Tag)]) -> Result<Level> {
        let mut next = refine_around(level, marked, self.track.is_some())?;
        if let (Some(t), Some(step)) = (&self.track, next.rows.take()) {
            t.borrow_mut().level(step);
        }
        Ok(next)
    }
}

/// The bi-3 patch of face `f` if it is regular and all its net points are trusted.
fn regular_patch(level: &Level, f: usize) -> Option<BezierPatch> {
    regular_net(level, f).map(|net| net_patch(level, &net))
}

/// The bi-3 B-spline net of face `f` (stencils over the level's points) if the face is regular
/// and all its net points are trusted.
fn regular_net(level: &Level, f: usize) -> Option<Net> {
    let m = &level.mesh;
    if m.face(f).iter().any(|&v| !level.info[v as usize].fan_ok) {
        return None;
    }
    let net = match &level.sharp {
        Some(ft) => sharp::bi3_net(level, ft, f)?,
        None => bi3_net(m, f)?,
    };
    if net
        .rows()
        .any(|r| r.iter().any(|&(v, _)| !level.info[v as usize].pos_ok))
    {
        return None;
    }
    Some(net)
}

/// The bi-3 patch of a B-spline net of the level.
fn net_patch(level: &Level, net: &Net) -> BezierPatch {
    bspline_patch(&net.points(level.mesh.positions()))
}

/// Tag of an irregular face: the element of its first extraordinary corner (or its own element
/// for a non-quad input face); faces without one inherit their parent's tag. `fans` keeps the
/// position of each face in the fans walked so far.
fn tag_irregular(level: &Level, f: usize, tag: Tag, fans: &mut FanSectors) -> Tag {
    let m = &level.mesh;
    if m.face_size(f) != 4 {
        return Tag {
            element: Some(Element::Face(tag.input_face)),
            ..tag
        };
    }
    for &v in m.face(f) {
        let origin = level.info[v as usize].origin;
        if origin.is_some() && sharp::irregular_vertex(level, v as usize) {
            let sector = fans.sector(m, v, f as u32);
            return Tag {
                element: origin,
                sector,
                ..tag
            };
        }
    }
    tag
}

/// Stores the boundary curves of an emitted patch of face `f`, keyed by the edge's vertices
/// (oriented from the smaller index).
fn record_curves(m: &PolyMesh, f: usize, p: &BezierPatch, curves: &mut Curves<4>) {
    let c = m.face(f);
    // Face corners 0..3 sit at (u, v) = (0,0), (1,0), (1,1), (0,1).
    let sides: [[(usize, usize); 4]; 4] = [
        [(0, 0), (1, 0), (2, 0), (3, 0)],
        [(3, 0), (3, 1), (3, 2), (3, 3)],
        [(3, 3), (2, 3), (1, 3), (0, 3)],
        [(0, 3), (0, 2), (0, 1), (0, 0)],
    ];
    for (k, side) in sides.iter().enumerate() {
        record_edge(curves, c[k], c[(k + 1) % 4], side.map(|(i, j)| p.cp(i, j)));
    }
}

/// Refines the marked faces and the ring of faces around them on the mesh layer's quad split
/// ([`sparse_split`]); returns the next level, whose active faces are the children of the
/// marked faces (with its stencils over `level`'s points in [`Level::rows`] when `keep`).
fn refine_around(level: &Level, marked: &[(u32, Tag)], keep: bool) -> Result<Level> {
    let m = &level.mesh;
    // The marked faces and the faces sharing a vertex with them.
    let (sel, sel_faces) = select_around(m, marked);
    let nv = m.num_vertices();
    let rules = sharp::rules(level);
    // Child vertex ids: numbered in one pass over the selected faces; their rows and trust are
    // then computed in parallel blocks in that order (the same table as one after another).
    let split = sparse_split(m, sel_faces, true, Numbering::FaceFirst);
    // per child face: a hole's descendant
    let hole: Vec<bool> = split
        .faces
        .iter()
        .flat_map(|&f| std::iter::repeat_n(is_hole(level, f as usize), m.face_size(f as usize)))
        .collect();
    let jobs = &split.points;
    // the child points' rows, written in place (no stencil per point)
    let table = StencilTable::build_par(nv, jobs.len(), 9, |range, table| {
        let (mut row, mut scratch) = (RowWriter::new(), Scratch::default());
        for &job in &jobs[range] {
            match job {
                SplitPoint::Face(f) => {
                    let face = m.face(f as usize);
                    for &x in face {
                        row.add(x, 1.0 / face.len() as f64);
                    }
                    row.push_into(table);
                }
                SplitPoint::Vertex(v) => {
                    rules.push_vertex_row(v as usize, &mut scratch, &mut row, table)
                }
                SplitPoint::Edge(e) => {
                    rules.push_edge_row(e as usize, &mut scratch, &mut row, table)
                }
            }
        }
    });
    let trust = SplitTrust::new(m, &level.info, &sel);
    let mut info: Vec<Info> = jobs
        .par_iter()
        .map(|&job| match job {
            SplitPoint::Face(f) => trust.face_point(trust.face_ok(f), None),
            SplitPoint::Vertex(v) => {
                let v = v as usize;
                trust.vertex(v, m.outgoing(v).all(|h| trust.face_ok(m.he_face(h))))
            }
            SplitPoint::Edge(e) => {
                let e = e as usize;
                let [a, b] = m.edge(e);
                let (a_ok, b_ok) = (level.info[a as usize].fan_ok, level.info[b as usize].fan_ok);
                let known = edge_known(level, e, a_ok, b_ok, a_ok || b_ok);
                let hh = m.edge_halfedge(e);
                let faces = [Some(m.he_face(hh)), m.he_twin(hh).map(|t| m.he_face(t))];
                trust.edge(e, known, faces.iter().flatten().all(|&g| trust.face_ok(g)))
            }
        })
        .collect();
    // Children of a face point of a non-quad input face are extraordinary: origin = that face.
    for &(f, tag) in marked {
        if m.face_size(f as usize) != 4 {
            info[split.face_point[f as usize] as usize].origin =
                Some(Element::Face(tag.input_face));
        }
    }
    let positions = table.apply(m.positions());
    let child = PolyMesh::from_partial_refinement(positions, split.face_start, split.corners)?;
    let ids = (&split.vertex_point[..], &split.edge_point[..]);
    let (child, sharp) = sharp_child(level, rules.sharp.as_ref(), child, ids, hole);
    let mut active = Vec::new();
    for &(f, tag) in marked {
        for k in 0..m.face_size(f as usize) {
            let c = split.first_child[f as usize] + k as u32;
            let mut t = tag;
            // child k is the quad at corner k (of the face, or the sub-face k of an n-gon)
            t.domain = tag.domain.child(k as u32);
            if m.face_size(f as usize) != 4 {
                // Children of an n-gon: one per corner, sector = corner index.
                t.element = Some(Element::Face(tag.input_face));
                t.sector = k as u32;
            }
            active.push((c, t));
        }
    }
    Ok(Level {
        base: MeshLevel {
            mesh: child,
            info,
            active,
        },
        sharp,
        rows: keep.then_some(table),
    })
}

#[cfg(feature = "unit-tests")]
mod tests;
