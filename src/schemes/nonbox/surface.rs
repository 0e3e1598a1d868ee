//! Non-box surfaces as exact patch complexes: S_3^1 cubic triangles, rings, and the G^1 cap
//! (or a fill).
//!
//! Where a quad cell of the net is regular (each corner an interior vertex of valence 4 or a
//! boundary vertex with one or two faces), the limit over it is four cubic triangles of the S_3^1
//! spline ([`crate::schemes::nonbox::bezier`]), each stored as the degenerate bi-3 patch
//! `T(u (1 - v), v)` (side `v = 1` collapsed to the cell centre; the layout of
//! [`crate::schemes::loop_subdivision::surface::loop_complex`]). Other cells (at extraordinary vertices, at boundary vertices with
//! more than two faces, and the non-quad faces of the input) are refined with the
//! scheme's own rules ([`crate::schemes::nonbox`]) together with the faces around their
//! corners; their regular children are emitted as ring `l` at level `l` (three cells, twelve
//! triangles, per sector of an isolated extraordinary vertex), the rest refined again. Points
//! near the cut of a partial refinement are flagged untrusted and never used.
//!
//! # The fill (fairsub's own, documented construction)
//!
//! After `K` rings each remaining cell becomes one bi-3 Coons patch of its four edge curves, each
//! defined once per edge and shared by both cells at the edge, so the fill is C^0:
//!
//! - an edge of a cell emitted at the same level takes that cell's exact edge curve;
//! - a boundary edge takes the exact limit boundary curve, the cubic B-spline of the boundary
//!   polygon (a corner stays put: ghost point `2 c - n`);
//! - any other edge is the cubic Hermite interpolant of the limit positions of its end points
//!   and the derivatives along the edge: at a regular vertex the exact S_3^1 derivative
//!   `(F_l + F_r - F_l' - F_r') / 2` (the FCVs of the two faces beside the edge minus the two
//!   behind it), which makes such an edge the exact limit curve wherever both ends are regular;
//!   at an interior extraordinary vertex of valence `k`, along its edge `j`,
//!   `(2 sqrt 2 / k) (cos(t_j) u1 + sin(t_j) u2)`, `t_j = (2 j - 1) pi / k`, with the paper's
//!   tangents `u1 = sum cos(2 pi i / k) F_i`, `u2 = sum sin(2 pi i / k) F_i` (exact for
//!   `k = 4`), so the spokes lie in the limit tangent plane; at an irregular boundary vertex the
//!   chord projected into the limit tangent plane.
//!
//! The fill is C^0 to the last ring and between fill patches, not G^1 across its edges; with
//! `K` rings it covers a region of size about `lambda^K`. It closes only the holes that get no
//! G^1 cap (`g1`: read off the ring triangles across the hole's edges, centred at the limit
//! point in the limit tangent plane; up to two more levels while holes touch).
//!
//! # Evaluation domains
//!
//! Every patch records the cell of its input face it covers ([`crate::bezier::domain`]): the
//! input faces start as Catmull-Clark's (a quad `[0, 1]^2`, an n-gon or triangle the strip of
//! the quad sub-faces its first refinement makes), and the scheme's refinement splits a cell
//! into the same four quads (child `k` at corner `k`: corner `k`, the midpoint of the outgoing
//! edge, the centre (FCV), the midpoint of the incoming edge), so a cell of level `l` is a
//! dyadic square of its face. The four triangles of a regular cell carry the cell as its
//! criss-cross ([`crate::bezier::domain::Domain::criss_cross`]: triangle `k` on the side from
//! corner `k` to corner `k + 1`, apex at the cell's centre, the split by both diagonals);
//! a G^1 cap sector covers its cell with `(0, 0)` at the extraordinary vertex (the cell rotated
//! to that corner, `u` along the sector's first spoke), a fill patch its cell with the cell's
//! own corners. `nonbox-4dir`'s triangles are fan triangles of these polygons
//! ([`nonbox_4dir_fan_faces`]).

use super::bezier::{CubicTriangle, cell_stencils, corner_fcvs, tri_index, triangle_to_tensor};
use super::{FcvNet, NonBox, fcv_rule_stencil};
use crate::bezier::complex::{Domain, PatchComplex, Provenance};
use crate::bezier::convert::cubic_bspline_to_bezier;
use crate::bezier::domain::FanTriangle;
use crate::bezier::{BezierPatch, Side};
use crate::error::Result;
use crate::geom::{self, Point};
use crate::host::ComplexOptions;
use crate::host::adaptive::{
    self, AdaptiveRules, Cells, Curves, FanSectors, Info, Sink, SplitTrust, Tag, edge_curve,
    input_active, input_vertex_info, record_edge, retag_by_corners, select_around,
};
use crate::mesh::split::{Numbering, SplitPoint, sparse_split};
use crate::mesh::{Element, PolyMesh};
use crate::schemes::nonbox::sharp::{NonBoxCreases, is_regular};
use crate::schemes::nonbox::{e_vertex_stencil_with, nfcv_stencil_with, v_vertex_stencil_with};
use crate::schemes::sdc::crease::Scratch;
use crate::schemes::sdc::crease::adaptive::{CALM, is_last_cap_level_calm};
use crate::stencil::{Stencil, StencilTable};
use std::cell::RefCell;
use std::collections::HashMap;
use std::f64::consts::PI;

mod fill;
mod g1;
mod sharp;
use fill::fill;

/// One level of the adaptive refinement: the net with its FCVs.
pub struct Level {
    net: FcvNet,
    points: Vec<Point>,
    info: Vec<Info>,
    active: Vec<(u32, Tag)>,
    /// Per vertex: within one face of a semi-sharp feature ([`sharp`]; `None`: none).
    near_semi: Option<Vec<bool>>,
    /// Per edge: an infinitely sharp crease left inside the surface ([`sharp`]).
    uncut: Option<Vec<bool>>,
    /// Levels since the last one with a semi-sharp feature.
    calm: usize,
    /// Where infinitely sharp creases end at darts: the level's net before the cut, which is
    /// refined (`net` is cut along every crease, the dart chains too, and gives the patches).
    uncut_net: Option<Box<UncutNet>>,
}

/// A level's net before the cut along the crease chains that end at darts (its darts refine
/// by OpenSubdiv's smooth rule; a slit's end in the cut net would refine by the boundary rule):
/// its points and trust, and each cut vertex's origin in it.
struct UncutNet {
    net: FcvNet,
    points: Vec<Point>,
    info: Vec<Info>,
    origin: Vec<u32>,
}

impl Level {
    /// A level from its net; when it holds no semi-sharp value, the net cut along its
    /// infinitely sharp creases ([`sharp`]).
    fn new(
        net: FcvNet,
        points: Vec<Point>,
        info: Vec<Info>,
        active: Vec<(u32, Tag)>,
        parent_calm: usize,
    ) -> Result<Level> {
        let mut ls = sharp::level_sharp(&net, parent_calm)?;
        // once no semi-sharp value is left: cut along the infinitely sharp creases, those of
        // chains ending at darts too, whose level keeps its uncut net for refinement
        let to_cut = match (ls.calm > 0, &ls.cut, &ls.uncut) {
            (false, ..) | (true, None, None) => None,
            (true, Some(cut), None) => Some(cut.clone()),
            (true, None, Some(uncut)) => Some(uncut.clone()),
            (true, Some(cut), Some(uncut)) => {
                Some(cut.iter().zip(uncut).map(|(&a, &b)| a || b).collect())
            }
        };
        let (net, info, points, uncut_net) = match to_cut {
            Some(cut) => {
                let darts = ls.uncut.is_some();
                let (cut_net, cut_info, origin) = sharp::cut_net(&net, &info, &cut)?;
                ls = sharp::level_sharp(&cut_net, ls.calm - 1)?;
                let cut_points = cut_net.points();
                let uncut = darts.then(|| {
                    Box::new(UncutNet {
                        net,
                        points,
                        info,
                        origin,
                    })
                });
                (cut_net, cut_info, cut_points, uncut)
            }
            None => (net, info, points, None),
        };
        Ok(Level {
            net,
            points,
            info,
            active,
            near_semi: ls.near_semi,
            uncut: ls.uncut,
            calm: ls.calm,
            uncut_net,
        })
    }

    /// The net refinement reads, with its points and their trust: the uncut net where crease
    /// chains end at darts, else the level's own.
    fn refined(&self) -> (&FcvNet, &[Point], &[Info]) {
        match &self.uncut_net {
            Some(u) => (&u.net, &u.points, &u.info),
            None => (&self.net, &self.points, &self.info),
        }
    }
}

impl Cells for Level {
    fn active(&self) -> &[(u32, Tag)] {
        &self.active
    }
}

/// The non-box surface of a net with FCVs as a patch complex: four degenerate bi-3 patches per
/// regular cell, `opts.rings` rings around every extraordinary element and, if `opts.fill`, the
/// fill of the [module](self) documentation. Non-quad faces are always refined once (they are
/// extraordinary elements whose first ring is at level 1). `progress(level)` is called after
/// each refinement level.
pub fn nonbox_complex(
    net: &FcvNet,
    opts: ComplexOptions,
    mut progress: impl FnMut(usize),
) -> Result<PatchComplex> {
    let rules = NonBoxRules {
        net,
        fill: opts.fill,
        cells: RefCell::new(Vec::new()),
    };
    let mut complex = adaptive::run(&rules, &net.mesh, opts, &mut progress)?;
    // the host gave each triangle its cell's domain: mark them as the cell's criss-cross
    for first in rules.cells.into_inner() {
        for k in 0..4u8 {
            let i = first as usize + usize::from(k);
            if let Some(d) = complex.domain(i) {
                complex.set_domain(i, d.criss_cross(k));
            }
        }
    }
    Ok(complex)
}

/// The non-box rules for the adaptive loop: cells are quads with their FCV, each regular cell
/// four cubic triangles.
struct NonBoxRules<'a> {
    net: &'a FcvNet,
    /// Whether holes are closed (then touching holes get more levels for their G^1 caps).
    fill: bool,
    /// The first patch of each emitted cell (its four triangles are consecutive).
    cells: RefCell<Vec<u32>>,
}

impl AdaptiveRules for NonBoxRules<'_> {
    type Level = Level;
    type Curves = Curves<4>;

    fn start(&self, _mesh: &PolyMesh, _opts: ComplexOptions) -> Result<Level> {
        let m = &self.net.mesh;
        let mut info = input_vertex_info(m.num_vertices());
        info.extend((0..m.num_faces()).map(|_| Info {
            pos_ok: true,
            fan_ok: true,
            origin: None,
        }));
        // every face (triangles included) is parametrised as Catmull-Clark's: a quad is its
        // [0, 1]^2, an n-gon the strip of the quad sub-faces its first refinement makes
        let mut active = input_active(m.num_faces());
        for (f, tag) in &mut active {
            tag.domain = Domain::polygon(*f, m.face_size(*f as usize));
        }
        Level::new(self.net.clone(), self.net.points(), info, active, CALM)
    }

    fn emit(&self, level: &Level, f: u32, prov: Provenance, to: Sink<Curves<4>>) -> bool {
        let m = &level.net.mesh;
        if let Some(near) = &level.near_semi
            && m.face(f as usize).iter().any(|&v| near[v as usize])
        {
            return false;
        }
        let Some(tris) = trusted_cell(level, f as usize) else {
            return false;
        };
        record_curves(&level.net.mesh, f as usize, &tris, to.curves);
        // the four triangles split the cell by its diagonals (the host gives each the cell's
        // domain, `nonbox_complex` then marks them `Domain::criss_cross`)
        self.cells.borrow_mut().push(to.out.len() as u32);
        for t in &tris {
            to.out.push(triangle_to_tensor(t), prov);
        }
        mark_boundary_sides(m, f as usize, to.out);
        true
    }

    fn retag(&self, level: &Level, f: u32, tag: Tag, _l: usize) -> Tag {
        retag(level, f as usize, tag, &mut FanSectors::default())
    }

    fn retag_all(&self, level: &Level, cells: Vec<(u32, Tag)>, _l: usize) -> Vec<(u32, Tag)> {
        adaptive::retag_with_fans(cells, |f, tag, fans| retag(level, f as usize, tag, fans))
    }

    /// Non-quad faces are always refined (their first ring is at level 1); with a fill, up to
    /// [`crate::host::adaptive::MAX_EXTRA_CAP_LEVELS`] more levels while holes touch.
    /// The levels that spend semi-sharp features go on too ([`is_last_cap_level_calm`]).
    fn is_last(&self, l: usize, rings: usize, level: &Level, marked: &[(u32, Tag)]) -> bool {
        marked
            .iter()
            .all(|&(f, _)| level.net.mesh.face_size(f as usize) == 4)
            && is_last_cap_level_calm((l, rings, self.fill), level.calm, || {
                g1::waiting(level, &self.net.mesh, marked)
            })
    }

    fn fill(&self, level: &Level, marked: &[(u32, Tag)], to: Sink<Curves<4>>) -> Result<()> {
        let left = g1::g1_caps(level, &self.net.mesh, marked, to.out);
        fill(level, &left, to.curves, to.out);
        Ok(())
    }

    fn refine_around(&self, level: &Level, marked: &[(u32, Tag)]) -> Result<Level> {
        refine_around(level, marked)
    }
}

/// The complex of a plain mesh under `nonbox`: a [layout mesh](FcvNet::to_layout_mesh) gives
/// its FCVs, any other mesh its face barycentres.
pub fn nonbox_mesh_complex(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    progress: impl FnMut(usize),
) -> Result<PatchComplex> {
    nonbox_complex(&FcvNet::from_mesh(mesh), opts, progress)
}

/// The complex of a plain mesh under `nonbox-4dir` (read as in
/// [`crate::schemes::nonbox::NonBox4Dir`]; provenance faces number the polygons, i.e. the
/// type-2 vertices in order).
///
/// # Evaluation domains
///
/// The patches are those of `nonbox` on the polygon net with FCVs, with its domains. When the
/// input is a polygon net (a layout mesh, or a mesh fanned around inserted barycentres) its
/// faces are those polygons and the domains are theirs. When the input is the quasi-four-
/// directional triangle mesh itself, its faces are the triangles `(V_i, V_(i+1), FCV)`: each
/// keeps the barycentric domain of a triangle and is mapped to its polygon as a fan triangle
/// ([`crate::bezier::domain::FanTriangle`], given to evaluation by the descriptor's
/// `eval_faces`, [`nonbox_4dir_fan_faces`]): on a quad it is
/// exactly one of the four S_3^1 triangles of the regular cell (the limit surface over it is
/// one cubic polynomial), on an n-gon it lies across two quad sub-faces.
pub fn nonbox_4dir_mesh_complex(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    progress: impl FnMut(usize),
) -> Result<PatchComplex> {
    let (net, _) = crate::schemes::nonbox::fourdir::four_dir_of(mesh)?;
    let (fcv, _) = net.to_fcv_net()?;
    nonbox_complex(&fcv, opts, progress)
}

/// The input faces of `mesh` under `nonbox-4dir` as fan triangles of the polygons the
/// complex is built on, when `mesh` is read as the quasi-four-directional triangle mesh
/// itself (see [`nonbox_4dir_mesh_complex`]); `None` when its faces are the polygons.
///
/// # Errors
/// Those of reading the mesh as [`nonbox_4dir_mesh_complex`] does.
pub fn nonbox_4dir_fan_faces(mesh: &PolyMesh) -> Result<Option<Vec<FanTriangle>>> {
    let (net, table) = crate::schemes::nonbox::fourdir::four_dir_of(mesh)?;
    // the triangle mesh itself was read (not a polygon net triangulated for it)
    let own = table.is_none() && net.mesh.num_faces() == mesh.num_faces();
    Ok(own.then(|| net.fan_triangles()))
}

/// Marks the sides of the four triangles just pushed for cell `f` (the last four patches of
/// `out`) that lie on the boundary of a net with sharp features (its extras): on a net cut
/// along its creases they are crease sides or the surface's boundary;
/// [`crate::schemes::doo_sabin::sharp::keep_crease_sides`] keeps the crease sides only.
fn mark_boundary_sides(m: &PolyMesh, f: usize, out: &mut PatchComplex) {
    if m.extras().is_none() {
        return;
    }
    let first = out.len() - 4;
    let h0 = m.face_halfedge(f);
    for k in 0..4u32 {
        if m.he_twin(h0 + k).is_none() {
            out.mark_sharp(first + k as usize, Side::V0.index());
        }
    }
}

/// The four cubic triangles of cell `f` if it is regular and all its data are trusted.
fn trusted_cell(level: &Level, f: usize) -> Option<[CubicTriangle; 4]> {
    let m = &level.net.mesh;
    if m.face(f)
        .iter()
        .any(|&v| !level.info[v as usize].fan_ok || !is_regular(m, v as usize))
    {
        return None;
    }
    let st = cell_stencils(m, f)?;
    let ok = st.iter().flatten().all(|s| {
        s.entries()
            .iter()
            .all(|&(x, _)| level.info[x as usize].pos_ok)
    });
    if !ok {
        return None;
    }
    Some(std::array::from_fn(|k| {
        std::array::from_fn(|i| st[k][i].apply(&level.points))
    }))
}

/// Stores the four edge curves of an emitted cell, keyed by vertex pairs (from the smaller).
fn record_curves(m: &PolyMesh, f: usize, tris: &[CubicTriangle; 4], curves: &mut Curves<4>) {
    let c = m.face(f);
    for k in 0..4 {
        let t = &tris[k];
        let e = [
            t[tri_index(3, 0, 0)],
            t[tri_index(2, 1, 0)],
            t[tri_index(1, 2, 0)],
            t[tri_index(0, 3, 0)],
        ];
        record_edge(curves, c[k], c[(k + 1) % 4], e);
    }
}

/// The tag of a marked cell: its first irregular corner's input element (sector = the cell's
/// position in that vertex's fan), or the input face of a non-quad; else the inherited tag.
fn retag(level: &Level, f: usize, tag: Tag, fans: &mut FanSectors) -> Tag {
    let m = &level.net.mesh;
    if m.face_size(f) != 4 && tag.element.is_none() {
        return Tag {
            element: Some(Element::Face(tag.input_face)),
            sector: 0,
            ..tag
        };
    }
    retag_by_corners(m, &level.info, f, tag, is_regular, fans)
}

/// Refines the faces around the corners of the marked cells with the non-box rules on the mesh
/// layer's quad split ([`sparse_split`]: child `k` of a cell is the quad at its corner `k`, of
/// the face or sub-face `k` of an n-gon, as Catmull-Clark's); the next level's active cells are
/// the children of the marked ones. Every child face gets its FCV.
fn refine_around(level: &Level, marked: &[(u32, Tag)]) -> Result<Level> {
    let (net, level_points, info) = level.refined();
    let m = &net.mesh;
    let (nv, nf) = (m.num_vertices(), m.num_faces());
    let creases = NonBoxCreases::of(m);
    let mut scratch = Scratch::default();
    let (sel, sel_faces) = select_around(m, marked);
    let marked_tag: HashMap<u32, Tag> = marked.iter().copied().collect();
    let trust = SplitTrust::new(m, info, &sel);
    let known = |h: u32| trust.edge_side_known(h);
    let mut split = sparse_split(m, sel_faces, true, Numbering::CornersFirst);
    let mut stencils: Vec<Stencil> = Vec::with_capacity(split.points.len());
    let mut child_info: Vec<Info> = Vec::with_capacity(split.points.len());
    for &p in &split.points {
        let (s, i) = match p {
            SplitPoint::Vertex(v) => {
                let v = v as usize;
                let s = v_vertex_stencil_with(m, v, creases.as_ref(), &mut scratch);
                let i = trust.vertex(v, trust.reads_ok(&s));
                (s, i)
            }
            SplitPoint::Edge(e) => {
                let h = m.edge_halfedge(e as usize);
                let s = e_vertex_stencil_with(m, e as usize, creases.as_ref(), &mut scratch);
                let i = trust.edge(e as usize, known(h), trust.reads_ok(&s));
                (s, i)
            }
            SplitPoint::Face(g) => {
                let s = fcv_rule_stencil(m, g as usize);
                let origin = match marked_tag.get(&g) {
                    Some(t) if m.face_size(g as usize) != 4 => Some(Element::Face(t.input_face)),
                    _ => None,
                };
                let i = trust.face_point(trust.reads_ok(&s), origin);
                (s, i)
            }
        };
        stencils.push(s);
        child_info.push(i);
    }
    // the FCV of every child face: one per corner of a selected face
    let mut fcv_stencils: Vec<Stencil> = Vec::with_capacity(split.corners.len() / 4);
    for &g in &split.faces {
        let h0 = m.face_halfedge(g as usize);
        for h in h0..h0 + m.face_size(g as usize) as u32 {
            let s = nfcv_stencil_with(m, h, creases.as_ref().map(|c| (c, &mut scratch)));
            let reads_ok = known(h) && known(m.he_prev(h)) && trust.reads_ok(&s);
            child_info.push(trust.face_point(reads_ok, None));
            fcv_stencils.push(s);
        }
    }
    let nc = stencils.len();
    let table = StencilTable::from_rows(nv + nf, stencils.into_iter().chain(fcv_stencils), 6);
    let points = table.apply(level_points);
    let (vid, eid) = (&split.vertex_point, &split.edge_point);
    let extras = creases.map(|c| c.child_extras(|v| vid[v as usize], |e| eid[e as usize]));
    let mesh = PolyMesh::from_partial_refinement(
        points[..nc].to_vec(),
        std::mem::take(&mut split.face_start),
        std::mem::take(&mut split.corners),
    )?
    .with_extras(extras);
    let net = FcvNet {
        mesh,
        fcv: points[nc..].to_vec(),
    };
    let mut active = Vec::new();
    for &(f, tag) in marked {
        for (k, c) in split.children(m, f, true).enumerate() {
            let mut t = tag;
            t.domain = tag.domain.child(k as u32);
            active.push((c, t));
        }
    }
    Level::new(net, points, child_info, active, level.calm)
}
