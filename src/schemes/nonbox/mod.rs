//! Non-box subdivision (Huang): the C^1 scheme of the four-directional S_3^1 non-box splines,
//! on polygon meshes with face control vertices (FCVs) and on quasi-four-directional triangle
//! meshes, with boundaries, limit positions, tangents and normals.
//!
//! The paper's rules, written once here as stencils ([`step_stencils`]):
//!
//! | rule | new point | stencil |
//! | --- | --- | --- |
//! | V-vertex | old vertex `V` of valence `k` | `(1 - a_k) V + (a_k / k) sum FCV_i` over its `k` faces |
//! | E-vertex | old edge `V0 V1` | `(V0 + V1 + FCV_L + FCV_R) / 4` |
//! | FCV rule | old FCV of a `k`-gon | `(1 - a_k) FCV + (a_k / k) sum V_i` over its corners |
//! | NFCV rule | FCV of the new quad at corner `V0` of old face `F0` | `V0 / 4 + FCV_0 / 2 + (FCV_1 + FCV_-1) / 8` |
//!
//! with `a_3 = 3/4`, `a_k = 3/4 - (1/2 + cos(2 pi / k) / 4)^2` for `k >= 4` (Proposition 1,
//! [`a_k`]). `FCV_1`, `FCV_-1` are the FCVs of the faces across the two edges of `F0` at `V0`.
//! After one step every face is a quad with its FCV, and the old FCVs have become vertices (the
//! face points of the Catmull-Clark topology). The four-directional variant ([`fourdir`]) applies
//! the same four stencils to the triangulated net (type-1 E-vertex = E-vertex, type-2 E-vertex =
//! NFCV, type-1 V-vertex = V-vertex, type-2 V-vertex = FCV rule), so both variants give the same
//! points and the same limit surface from the same data. On a regular grid the scheme is the
//! vector subdivision of the matrix mask (3) ([`mask`]); its limit is the S_3^1 spline whose
//! cubic Bezier pieces [`bezier`] tabulates.
//!
//! # Data: nets with FCVs
//!
//! A [`FcvNet`] is a [`PolyMesh`] and one FCV per face. Stencils over a net index its *points*:
//! vertex `v` is point `v`, the FCV of face `f` is point `num_vertices + f`. One step
//! ([`NonBox::step`]) maps the points of a net to the points of its child:
//!
//! - child vertices (the Catmull-Clark order of [`crate::schemes::catmull_clark`]): one
//!   V-vertex per parent vertex, then one E-vertex per parent edge, then one face vertex (the
//!   parent's FCV moved by the FCV rule) per parent face;
//! - then the child FCVs: child face `h` is the quad of parent corner (half-edge) `h`
//!   (V-vertex, E-vertex of the outgoing edge, face vertex, E-vertex of the incoming edge), and
//!   its FCV is the NFCV of that corner.
//!
//! Through the plain [`Scheme`] interface a net with FCVs travels as a *layout mesh*
//! ([`FcvNet::to_layout_mesh`]): the mesh's vertices followed by one extra vertex per face (its
//! FCV, in face order) that no face uses. [`NonBox`]'s `refine` reads that layout (a mesh
//! without it gets its face barycentres as FCVs) and writes it, so several levels of `refine`
//! carry the FCVs, and an OBJ file written from it lists the FCVs as the last `v` lines (the
//! file formats and their readers and writers are in `io::fcv`). The layout mesh is only for the
//! non-box schemes: its FCV vertices have no faces, so other schemes must be given
//! [`FcvNet::mesh`] instead.
//!
//! # Boundaries
//!
//! Boundary V- and E-vertices follow the cubic B-spline rules of the boundary polygon
//! (`(a + 6 v + b) / 8`, `(a + b) / 2`; a vertex with a single face is a corner and stays put),
//! as the paper asks after Hoppe et al. \[HDD*94\]; the FCV rule needs no change. The boundary NFCV rule (its
//! Fig. 8b is lost) is fairsub's reconstruction: a missing neighbour FCV across a boundary edge
//! `V0 V1` of `F0` is replaced by the *ghost* `V0 + V1 - FCV_0`, the point reflection of `FCV_0`
//! through the edge midpoint:
//!
//! - one boundary edge `V0 V1` at `V0`: `3/8 V0 + 1/8 V1 + 3/8 FCV_0 + 1/8 FCV_1`;
//! - both edges at `V0` on the boundary (`V0` a corner, edges to `Va`, `Vb`):
//!   `1/2 V0 + 1/8 Va + 1/8 Vb + 1/4 FCV_0`.
//!
//! Why this rule: with the same ghosts the interior rules reproduce both published boundary rules
//! (the E-vertex of a boundary edge becomes `(a + b) / 2` and the V-vertex of a boundary vertex
//! with two faces `(a + 6 v + b) / 8`); the ghosts commute with refinement (the ghost of a refined
//! FCV equals the refined ghost), so near a boundary of vertices with two faces the surface is
//! exactly the S_3^1 spline of the net extended by ghost FCVs, C^1 up to the boundary, whose
//! boundary curve is the cubic B-spline of the boundary polygon; the weights are non-negative
//! (convex hull property) and linear functions are reproduced. At a corner (one face) the two
//! edge ghosts and the diagonal ghost `2 V0 - Va - Vb + FCV_0` turn the interior rules into the
//! corner rules too, so the cells at corners are exact spline pieces as well
//! ([`bezier`] documents the derivation). The tests check each claim.
//!
//! # Limit positions, tangents, normals (Section 4)
//!
//! Interior vertex of valence `k` with FCVs `F_j` (counter-clockwise):
//! `(k V + 4 a_k sum F_j) / (k (1 + 4 a_k))`, tangents `sum cos(2 pi j / k) F_j` and
//! `sum sin(2 pi j / k) F_j`, normal their cross product (outward for counter-clockwise faces).
//! Boundary vertex: `(a + 4 v + b) / 6` (cubic B-spline limit), corner: `v`; tangent along the
//! boundary `a - b`; across it `4 mean(F) - 2 v - a - b`, exact for two faces (the ghost
//! formula); at a boundary vertex of `k >= 3` quads the left eigenvector of the scheme's own
//! local matrix ([`boundary`]; the paper analyses no boundary vertex), and the `4 mean(F)`
//! formula, an approximation, only where the two rings around the vertex are not regular
//! quads. The
//! limit at an FCV's parameter point (the face centre) is the limit of the face vertex it
//! becomes after one step.

pub mod descriptor;
pub mod entry;
pub mod local;
pub mod surface;
pub use descriptor::{DESCRIPTOR, DESCRIPTOR_4DIR};

pub mod bezier;
pub mod boundary;
pub mod fourdir;
pub(crate) mod holes;
pub mod mask;
mod net;
pub(crate) mod sharp;

pub use fourdir::{FourDirNet, NonBox4Dir};
pub use net::{FcvNet, fcv_insertion, layout_vertex_count};

use super::{Refinement, Scheme};
use crate::error::{Error, Result};
use crate::geom::{self, Point};
use crate::mesh::PolyMesh;
use crate::schemes::CatmullClark;
use crate::schemes::sdc::crease::Scratch;
use crate::stencil::{Stencil, StencilTable};
use std::f64::consts::PI;

/// The weight `a_k` of Proposition 1: `3/4` for `k = 3`, else
/// `3/4 - (1/2 + cos(2 pi / k) / 4)^2`. Valence 2 (possible at interior vertices of some closed
/// nets; the paper needs `k >= 3`) uses the second formula, `11/16`, which keeps the weights in
/// the paper's convergence range `0 <= a_k <= 3/4`.
pub fn a_k(k: usize) -> f64 {
    if k == 3 {
        0.75
    } else {
        let l = subdominant_eigenvalue(k);
        0.75 - l * l
    }
}

/// The subdominant eigenvalue `lambda_1 = lambda_2 = 1/2 + cos(2 pi / k) / 4` at valence `k`.
pub fn subdominant_eigenvalue(k: usize) -> f64 {
    0.5 + 0.25 * (2.0 * PI / k as f64).cos()
}

/// One refinement step of a net: the child net and the table mapping parent points to child
/// points (see the [module](self) documentation for both orders).
#[derive(Debug, Clone)]
pub struct FcvStep {
    /// The child net (all quads).
    pub net: FcvNet,
    /// Row `r` computes child point `r` from the parent's points.
    pub stencils: StencilTable,
}

/// The FCVs of the faces around interior or boundary vertex `v`, counter-clockwise (from the
/// boundary for a boundary vertex), as point indices.
fn vertex_fcvs(mesh: &PolyMesh, v: usize) -> Vec<usize> {
    let nv = mesh.num_vertices();
    mesh.vertex_faces(v)
        .into_iter()
        .map(|f| nv + f as usize)
        .collect()
}

/// Stencil of the V-vertex of `v` (V-vertex rule; cubic B-spline rule on the boundary).
pub fn v_vertex_stencil(mesh: &PolyMesh, v: usize) -> Stencil {
    if mesh.is_boundary_vertex(v) {
        let nb = mesh.vertex_neighbors(v);
        if mesh.vertex_faces(v).len() == 1 {
            return Stencil::point(v);
        }
        let (a, b) = (nb[0] as usize, nb[nb.len() - 1] as usize);
        return Stencil::from_pairs([(v, 0.75), (a, 0.125), (b, 0.125)]);
    }
    let fs = vertex_fcvs(mesh, v);
    let k = fs.len();
    let a = a_k(k);
    let mut s = Stencil::new();
    s.add(v, 1.0 - a);
    for f in fs {
        s.add(f, a / k as f64);
    }
    s.merged()
}

/// Stencil of the E-vertex of edge `e` (E-vertex rule; midpoint on the boundary).
pub fn e_vertex_stencil(mesh: &PolyMesh, e: usize) -> Stencil {
    let [a, b] = mesh.edge(e);
    let h = mesh.edge_halfedge(e);
    let nv = mesh.num_vertices();
    match mesh.he_twin(h) {
        None => Stencil::from_pairs([(a as usize, 0.5), (b as usize, 0.5)]),
        Some(t) => Stencil::from_pairs([
            (a as usize, 0.25),
            (b as usize, 0.25),
            (nv + mesh.he_face(h) as usize, 0.25),
            (nv + mesh.he_face(t) as usize, 0.25),
        ]),
    }
}

/// Stencil of the face vertex of face `f`: its FCV moved by the FCV rule.
pub fn fcv_rule_stencil(mesh: &PolyMesh, f: usize) -> Stencil {
    let face = mesh.face(f);
    let k = face.len();
    let a = a_k(k);
    let mut s = Stencil::new();
    s.add(mesh.num_vertices() + f, 1.0 - a);
    for &v in face {
        s.add(v as usize, a / k as f64);
    }
    s.merged()
}

/// The FCV of the face across the edge of half-edge `g` (whose face is `F0`, with FCV point
/// `f0`), or the ghost `a + b - FCV_0` across a boundary edge `a b`.
fn across(mesh: &PolyMesh, g: u32, f0: usize) -> Stencil {
    match mesh.he_twin(g) {
        Some(t) => Stencil::point(mesh.num_vertices() + mesh.he_face(t) as usize),
        None => Stencil::from_pairs([
            (mesh.he_from(g) as usize, 1.0),
            (mesh.he_to(g) as usize, 1.0),
            (f0, -1.0),
        ]),
    }
}

/// Stencil of the new FCV of the child quad at parent corner (half-edge) `h`: the NFCV rule,
/// with ghosts across boundary edges (see the [module](self) documentation).
pub fn nfcv_stencil(mesh: &PolyMesh, h: u32) -> Stencil {
    nfcv_stencil_with(mesh, h, None)
}

/// [`nfcv_stencil`] on a net with sharp features: across a sharp edge the ghost, with the
/// weight of the edge's crease rule ([`sharp`]).
pub(crate) fn nfcv_stencil_with(
    mesh: &PolyMesh,
    h: u32,
    mut creases: Option<(&sharp::NonBoxCreases<'_>, &mut Scratch)>,
) -> Stencil {
    let v0 = mesh.he_from(h) as usize;
    let f0 = mesh.num_vertices() + mesh.he_face(h) as usize;
    let mut s = Stencil::new();
    s.add(v0, 0.25);
    s.add(f0, 0.5);
    for g in [h, mesh.he_prev(h)] {
        let plain = across(mesh, g, f0);
        let w = match (&mut creases, mesh.he_twin(g)) {
            (Some((c, scratch)), Some(_)) => c.crease_weight(mesh.he_edge(g) as usize, scratch),
            _ => 0.0,
        };
        if w == 0.0 {
            s.add_scaled(&plain, 0.125);
        } else {
            let ghost = Stencil::from_pairs([
                (mesh.he_from(g) as usize, 1.0),
                (mesh.he_to(g) as usize, 1.0),
                (f0, -1.0),
            ]);
            s.add_scaled(&ghost, 0.125 * w);
            s.add_scaled(&plain, 0.125 * (1.0 - w));
        }
    }
    s.merged()
}

/// The refinement stencils of one step of a net with topology `mesh`: rows are the child points
/// (V-vertices, E-vertices, face vertices, then one NFCV per parent half-edge), sources the
/// parent points (vertices, then FCVs).
pub fn step_stencils(mesh: &PolyMesh) -> StencilTable {
    step_stencils_with(mesh, None)
}

/// [`step_stencils`] with the net's sharp features ([`sharp`]) when given.
pub(crate) fn step_stencils_with(
    mesh: &PolyMesh,
    creases: Option<&sharp::NonBoxCreases<'_>>,
) -> StencilTable {
    let (nv, ne, nf, nh) = (
        mesh.num_vertices(),
        mesh.num_edges(),
        mesh.num_faces(),
        mesh.num_halfedges(),
    );
    let mut scratch = Scratch::default();
    let mut t = StencilTable::with_capacity(nv + nf, nv + ne + nf + nh, 5);
    for v in 0..nv {
        t.push(v_vertex_stencil_with(mesh, v, creases, &mut scratch));
    }
    for e in 0..ne {
        t.push(e_vertex_stencil_with(mesh, e, creases, &mut scratch));
    }
    for f in 0..nf {
        t.push(fcv_rule_stencil(mesh, f));
    }
    for h in 0..nh as u32 {
        t.push(nfcv_stencil_with(
            mesh,
            h,
            creases.map(|c| (c, &mut scratch)),
        ));
    }
    t
}

/// The V-vertex of `v`, by the vertex plan of the net's sharp features when given.
pub(crate) fn v_vertex_stencil_with(
    mesh: &PolyMesh,
    v: usize,
    creases: Option<&sharp::NonBoxCreases<'_>>,
    scratch: &mut Scratch,
) -> Stencil {
    let plain = v_vertex_stencil(mesh, v);
    match creases {
        Some(c) => c.v_vertex(v, &plain, scratch),
        None => plain,
    }
}

/// The E-vertex of `e`, by the edge plan of the net's sharp features when given.
pub(crate) fn e_vertex_stencil_with(
    mesh: &PolyMesh,
    e: usize,
    creases: Option<&sharp::NonBoxCreases<'_>>,
    scratch: &mut Scratch,
) -> Stencil {
    let plain = e_vertex_stencil(mesh, e);
    match creases {
        Some(c) if c.edge(e) > 0.0 => c.e_vertex(e, &plain, scratch),
        _ => plain,
    }
}

/// Interior limit stencil of vertex `v` with the FCVs `fs` of its faces (Section 4).
fn interior_limit(v: usize, fs: &[usize]) -> Stencil {
    let k = fs.len() as f64;
    let a = a_k(fs.len());
    let d = k * (1.0 + 4.0 * a);
    let mut s = Stencil::new();
    s.add(v, k / d);
    for &f in fs {
        s.add(f, 4.0 * a / d);
    }
    s.merged()
}

/// Interior tangent stencils of a vertex with the FCVs `fs` of its faces, counter-clockwise.
fn interior_tangents(fs: &[usize]) -> (Stencil, Stencil) {
    let k = fs.len() as f64;
    let mut t1 = Stencil::new();
    let mut t2 = Stencil::new();
    for (j, &f) in fs.iter().enumerate() {
        let a = 2.0 * PI * j as f64 / k;
        t1.add(f, a.cos());
        t2.add(f, a.sin());
    }
    (t1.merged(), t2.merged())
}

/// The non-box scheme on polygon meshes with FCVs (the paper's "quadrilateral subdivision with
/// FCVs"). Through [`Scheme`] it reads and writes [layout meshes](FcvNet::to_layout_mesh);
/// plain meshes get `fcv_scale` times their face barycentres as FCVs.
#[derive(Debug, Clone, Copy)]
pub struct NonBox {
    /// Scale of the default FCVs about the origin (1 = barycentres).
    pub fcv_scale: f64,
}

impl Default for NonBox {
    fn default() -> Self {
        NonBox { fcv_scale: 1.0 }
    }
}

impl NonBox {
    /// One refinement step of a net (child net and stencils; orders in the [module](self)
    /// documentation).
    pub fn step(net: &FcvNet) -> Result<FcvStep> {
        let mesh = &net.mesh;
        let creases = sharp::NonBoxCreases::of(mesh);
        let st = step_stencils_with(mesh, creases.as_ref());
        let (fs, cn) = CatmullClark::child_topology(mesh);
        let pts = st.apply(&net.points());
        let nv = mesh.num_vertices() as u32;
        let nc = mesh.num_vertices() + mesh.num_edges() + mesh.num_faces();
        let extras =
            holes::with_child_holes(mesh, creases.map(|c| c.child_extras(|v| v, |e| nv + e)));
        let child = PolyMesh::from_refinement(pts[..nc].to_vec(), fs, cn)?.with_extras(extras);
        let net = FcvNet::new(child, pts[nc..].to_vec())?;
        Ok(FcvStep { net, stencils: st })
    }

    /// `levels` refinement steps of a net; `progress(level)` is called after each.
    pub fn refine_levels(
        net: &FcvNet,
        levels: usize,
        mut progress: impl FnMut(usize),
    ) -> Result<FcvNet> {
        let mut n = net.clone();
        for l in 0..levels {
            n = Self::step(&n)?.net;
            progress(l + 1);
        }
        Ok(n)
    }

    /// Limit-position stencil of point `p` of the net (a vertex, or an FCV: the limit at the face
    /// centre), over the net's points. See the [module](self) documentation.
    pub fn limit_stencil(net: &FcvNet, p: usize) -> Stencil {
        let mesh = &net.mesh;
        let nv = mesh.num_vertices();
        if p >= nv {
            return Self::face_centre_stencils(mesh, p - nv).0;
        }
        if mesh.is_boundary_vertex(p) {
            let nb = mesh.vertex_neighbors(p);
            if sharp::is_corner(mesh, p) {
                return Stencil::point(p);
            }
            let (a, b) = (nb[0] as usize, nb[nb.len() - 1] as usize);
            return Stencil::from_pairs([(p, 4.0 / 6.0), (a, 1.0 / 6.0), (b, 1.0 / 6.0)]);
        }
        interior_limit(p, &vertex_fcvs(mesh, p))
    }

    /// Limit stencil and tangent stencils at the centre of face `f`, through the face vertex of
    /// one step (the step's rows are composed in, so all are over the parent's points).
    fn face_centre_stencils(mesh: &PolyMesh, f: usize) -> (Stencil, Stencil, Stencil) {
        // After one step the face vertex of `f` is an interior vertex of valence `k` whose FCVs
        // are the NFCVs of the face's corners, counter-clockwise. Local rows: 0 = face vertex,
        // 1..=k = those NFCVs.
        let h0 = mesh.face_halfedge(f);
        let k = mesh.face_size(f) as u32;
        let mut rows = vec![fcv_rule_stencil(mesh, f)];
        rows.extend((h0..h0 + k).map(|h| nfcv_stencil(mesh, h)));
        let ring: Vec<usize> = (1..=k as usize).collect();
        let lim = interior_limit(0, &ring);
        let (t1, t2) = interior_tangents(&ring);
        let compose = |s: &Stencil| {
            let mut out = Stencil::new();
            for &(i, w) in s.entries() {
                out.add_scaled(&rows[i as usize], w);
            }
            out.merged()
        };
        (compose(&lim), compose(&t1), compose(&t2))
    }

    /// Limit-position stencils of every point of the net (row `p` for point `p`: vertices, then
    /// FCVs).
    pub fn limit_stencils(net: &FcvNet) -> StencilTable {
        let n = net.num_points();
        let mut t = StencilTable::with_capacity(n, n, 9);
        for p in 0..n {
            t.push(Self::limit_stencil(net, p));
        }
        t
    }

    /// Tangent stencils `(t1, t2)` at point `p` (vertex or face centre) with `t1 x t2` the
    /// outward normal (counter-clockwise faces). See the [module](self) documentation.
    pub fn tangent_stencils(net: &FcvNet, p: usize) -> (Stencil, Stencil) {
        let mesh = &net.mesh;
        let nv = mesh.num_vertices();
        if p >= nv {
            let (_, t1, t2) = Self::face_centre_stencils(mesh, p - nv);
            return (t1, t2);
        }
        let fs = vertex_fcvs(mesh, p);
        if !mesh.is_boundary_vertex(p) {
            return interior_tangents(&fs);
        }
        let nb = mesh.vertex_neighbors(p);
        let (a, b) = (nb[0] as usize, nb[nb.len() - 1] as usize);
        if fs.len() == 1 {
            return (
                Stencil::from_pairs([(a, 1.0), (p, -1.0)]),
                Stencil::from_pairs([(b, 1.0), (p, -1.0)]),
            );
        }
        if fs.len() > 2
            && let Some(exact) = boundary::open_fan_tangents(net, p)
        {
            return exact;
        }
        let along = Stencil::from_pairs([(a, 1.0), (b, -1.0)]);
        let mut across = Stencil::new();
        let w = 4.0 / fs.len() as f64;
        for &f in &fs {
            across.add(f, w);
        }
        across.add(p, -2.0).add(a, -1.0).add(b, -1.0);
        (along, across.merged())
    }

    /// Unit limit normals of every point of the net (vertices, then face centres).
    pub fn limit_normals(net: &FcvNet) -> Vec<Point> {
        let pts = net.points();
        (0..net.num_points())
            .map(|p| {
                let (t1, t2) = Self::tangent_stencils(net, p);
                geom::normalize(geom::cross(t1.apply(&pts), t2.apply(&pts)))
            })
            .collect()
    }

    /// The limit mesh after `levels` steps: the refined net's quads split into four triangles
    /// around their FCVs, every point at its limit position (vertices first, then the face
    /// centres, as in the layout order).
    pub fn limit_mesh(net: &FcvNet, levels: usize) -> Result<PolyMesh> {
        Ok(Self::limit_mesh_with_normals(net, levels)?.0)
    }

    /// The [limit mesh](Self::limit_mesh) after `levels` steps and the unit limit normal at
    /// each of its vertices ([`Self::limit_normals`] of the refined net, in the same order).
    pub fn limit_mesh_with_normals(net: &FcvNet, levels: usize) -> Result<(PolyMesh, Vec<Point>)> {
        let fine = Self::refine_levels(net, levels, |_| {})?;
        let lim = Self::limit_stencils(&fine).apply(&fine.points());
        let normals = Self::limit_normals(&fine);
        let tri = fourdir::triangulate(&fine);
        let mesh = PolyMesh::from_refinement(
            lim,
            tri.mesh.face_starts().to_vec(),
            tri.mesh.corners().to_vec(),
        )?;
        Ok((holes::without_hole_triangles(mesh, &fine.mesh), normals))
    }
}

/// Notes for the user about how a non-box scheme (`nonbox` or `nonbox-4dir`) reads `mesh`:
/// where the FCVs come from, how a triangle mesh was typed, and whether the reconstructed
/// boundary NFCV rule is in use (it is fairsub's, not the paper's; see the [module](self)
/// documentation). Empty for a closed polygon mesh under `nonbox`.
pub fn input_notes(four_dir: bool, mesh: &PolyMesh) -> Vec<String> {
    let mut notes = Vec::new();
    if four_dir {
        notes.push(fourdir::describe_input(mesh));
    } else if let Some(nv) = layout_vertex_count(mesh) {
        notes.push(format!(
            "{}: the last {} vertices are the FCVs of the {} faces (layout mesh)",
            crate::schemes::options::ids::NONBOX,
            mesh.num_vertices() - nv,
            mesh.num_faces()
        ));
    }
    if !mesh.boundary_loops().is_empty() {
        notes.push(
            "the net has a boundary: boundary V- and E-vertices follow the cubic B-spline rules \
             of the paper, the boundary NFCV rule (ghost FCVs a + b - F) is fairsub's \
             reconstruction (the paper's Fig. 8b is lost)"
                .to_string(),
        );
    }
    notes
}

impl Scheme for NonBox {
    fn step_size(&self, s: &crate::schemes::growth::NetSize) -> crate::schemes::growth::NetSize {
        crate::schemes::growth::primal_quad_with_face_points(s)
    }

    fn fcv_layout(&self) -> crate::schemes::FcvLayout {
        crate::schemes::FcvLayout::Quads
    }

    fn input_notes(&self, mesh: &PolyMesh) -> Vec<String> {
        input_notes(false, mesh)
    }

    fn limit_mesh_with_normals(
        &self,
        mesh: &PolyMesh,
        levels: usize,
    ) -> Option<Result<(PolyMesh, Vec<Point>)>> {
        Some(NonBox::limit_mesh_with_normals(
            &FcvNet::from_mesh(mesh),
            levels,
        ))
    }

    fn name(&self) -> &'static str {
        crate::schemes::options::ids::NONBOX.name()
    }

    fn refine(&self, mesh: &PolyMesh) -> Result<Refinement> {
        let (net, insertion) = match FcvNet::from_layout_mesh(mesh) {
            Some(net) => (net, None),
            None => (
                FcvNet::scaled(mesh.clone(), self.fcv_scale)?,
                Some(fcv_insertion(mesh, self.fcv_scale)),
            ),
        };
        let step = Self::step(&net)?;
        let stencils = match insertion {
            Some(ins) => step.stencils.compose(&ins),
            None => step.stencils,
        };
        Ok(Refinement {
            mesh: step.net.to_layout_mesh(),
            stencils,
        })
    }

    fn limit_stencils(&self, mesh: &PolyMesh) -> Result<StencilTable> {
        match FcvNet::from_layout_mesh(mesh) {
            Some(net) => Ok(Self::limit_stencils(&net)),
            None => {
                let net = FcvNet::scaled(mesh.clone(), self.fcv_scale)?;
                let all = Self::limit_stencils(&net);
                let rows: Vec<usize> = (0..mesh.num_vertices()).collect();
                Ok(all
                    .select_rows(&rows)
                    .compose(&fcv_insertion(mesh, self.fcv_scale)))
            }
        }
    }
}
