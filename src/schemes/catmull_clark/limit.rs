//! Catmull-Clark's limit positions (plain and with sharp features), limit tangents and limit
//! normals.

use super::{CatmullClark, Opts};
use crate::geom::{self, Point};
use crate::mesh::{MeshView, PolyMesh};
use crate::schemes::sdc::crease::{Emit, LimitPlan, Scratch, SharpLevel};
use crate::stencil::{RowWriter, Stencil, StencilTable, Terms};
use std::collections::HashMap;
use std::f64::consts::PI;
use std::sync::OnceLock;

/// Limit-position stencils of single vertices of one mesh under the default options, with the
/// mesh's sharp level built once (and the child of a mesh with non-quads built once, on first
/// need): the per-level object behind the fills' limit points, which ask for one vertex at a
/// time and would otherwise rebuild the whole level per vertex (quadratic on creased nets).
pub struct LimitStencils<'m> {
    mesh: &'m PolyMesh,
    sharp: Option<SharpLevel<'m>>,
    /// The composed stencils of the vertices whose limit goes through the child (next to a
    /// non-quad and smooth), all computed from one child.
    through_child: OnceLock<HashMap<usize, Stencil>>,
}

/// Terms that are dropped (to ask [`limit_terms`] only whether it applies).
struct Discard;

impl Terms for Discard {
    fn add(&mut self, _: u32, _: f64) {}
}

impl<'m> LimitStencils<'m> {
    /// The limit stencils of `mesh` (its sharp features as its extras say, default options).
    pub fn new(mesh: &'m PolyMesh) -> Self {
        LimitStencils {
            mesh,
            sharp: SharpLevel::new(mesh, &Opts::default()),
            through_child: OnceLock::new(),
        }
    }

    /// The mesh the stencils are of.
    pub fn mesh(&self) -> &'m PolyMesh {
        self.mesh
    }

    /// Limit-position stencil of vertex `v` (as [`CatmullClark::limit_stencil`]).
    pub fn stencil(&self, v: usize) -> Stencil {
        if let Some(s) = CatmullClark::direct_limit_stencil(self.mesh, self.sharp.as_ref(), v) {
            return s;
        }
        self.through_child.get_or_init(|| self.child_stencils())[&v].clone()
    }

    /// The limit point of vertex `v`.
    pub fn limit(&self, v: usize) -> Point {
        self.stencil(v).apply(self.mesh.positions())
    }

    fn child_stencils(&self) -> HashMap<usize, Stencil> {
        let opts = Opts::default();
        let (cm, cs) = CatmullClark::child(self.mesh, &opts);
        let child_sharp = SharpLevel::new(&cm, &opts);
        let m = self.mesh.view();
        let mut scratch = Scratch::default();
        (0..self.mesh.num_vertices())
            .filter(|&v| !limit_terms(&m, self.sharp.as_ref(), v, &mut scratch, &mut Discard))
            .map(|v| {
                let s = CatmullClark::limit_through_child(&cm, &cs, child_sharp.as_ref(), v);
                (v, s)
            })
            .collect()
    }
}

/// The smooth limit mask of interior vertex `v` when all its faces are quads:
/// `(n^2 v + 4 sum e_j + sum f_j) / (n (n + 5))` (a vertex with two faces stays, as in
/// OpenSubdiv); returns `false`, writing nothing, next to a non-quad.
#[inline]
fn smooth_limit(m: &MeshView<'_>, v: usize, t: &mut impl Terms) -> bool {
    if m.outgoing(v)
        .any(|h| m.face_corners(m.face(h) as usize).len() != 4)
    {
        return false;
    }
    let n = m.outgoing(v).count() as f64;
    if n == 2.0 {
        t.add(v as u32, 1.0);
        return true;
    }
    let d = n * (n + 5.0);
    t.add(v as u32, n * n / d);
    for h in m.outgoing(v) {
        t.add(m.to(h), 4.0 / d);
        t.add(m.from(m.faces.next(m.faces.next(h))), 1.0 / d);
    }
    true
}

/// The limit-position rule of vertex `v` (see [`CatmullClark::limit_stencils`]): with a sharp
/// level the vertex's rule at this level (crease `2/3 v + 1/6 (a + b)`, corner `v`), else the
/// plain boundary rules; returns `false`, writing nothing, for a smooth vertex next to a
/// non-quad. Walks the connectivity in place (no allocation per vertex).
fn limit_terms(
    m: &MeshView<'_>,
    sharp: Option<&SharpLevel<'_>>,
    v: usize,
    scratch: &mut Scratch,
    t: &mut impl Terms,
) -> bool {
    let vv = v as u32;
    match sharp {
        Some(sl) if sl.special[v] => {
            let plan = sl.limit_plan(vv, scratch);
            if plan != LimitPlan::Smooth {
                plan.emit(vv, |e| {
                    if let Emit::Vertex(u, w) = e {
                        t.add(u, w)
                    }
                });
                return true;
            }
        }
        Some(_) => {}
        None if m.is_boundary_vertex(v) => {
            if m.is_corner(v) {
                t.add(vv, 1.0);
            } else {
                let (a, b) = m.boundary_neighbors(v);
                t.add(vv, 4.0 / 6.0);
                t.add(a, 1.0 / 6.0);
                t.add(b, 1.0 / 6.0);
            }
            return true;
        }
        None => {}
    }
    smooth_limit(m, v, t)
}

impl CatmullClark {
    /// Limit-position stencils of every vertex of `mesh` (row `v` for vertex `v`) with the
    /// default options.
    ///
    /// Interior vertex surrounded by quads: `(n^2 v + 4 sum e_j + sum f_j) / (n (n + 5))` with edge
    /// neighbours `e_j` and diagonal neighbours `f_j`; boundary vertex: `(a + 4 v + b) / 6`;
    /// corner: `v`; with sharp features OpenSubdiv's masks by the vertex's rule at this level.
    /// A vertex next to a non-quad face takes the limit of its child after one step (composed
    /// with that step's stencils), which is the same limit point.
    ///
    /// Rows are built in parallel blocks.
    pub fn limit_stencils(mesh: &PolyMesh) -> StencilTable {
        Self::limit_stencils_with(mesh, &Opts::default())
    }

    /// [`CatmullClark::limit_stencils`] with OpenSubdiv's options.
    pub fn limit_stencils_with(mesh: &PolyMesh, opts: &Opts) -> StencilTable {
        let nv = mesh.num_vertices();
        // Only a vertex next to a non-quad face needs the child.
        let child = (!mesh.is_all_quads()).then(|| Self::child(mesh, opts));
        let child_sharp = child.as_ref().and_then(|(cm, _)| SharpLevel::new(cm, opts));
        let sharp = SharpLevel::new(mesh, opts);
        let m = mesh.view();
        StencilTable::build_par(nv, nv, 9, |rows, t| {
            let mut row = RowWriter::new();
            let mut scratch = Scratch::default();
            for v in rows {
                if limit_terms(&m, sharp.as_ref(), v, &mut scratch, &mut row) {
                    row.push_into(t);
                } else {
                    let (cm, cs) = child.as_ref().expect("a non-quad face is next to v");
                    t.push(Self::limit_through_child(cm, cs, child_sharp.as_ref(), v));
                }
            }
        })
    }

    /// Limit-position stencil of one vertex (see [`CatmullClark::limit_stencils`]). Builds the
    /// sharp level of the whole mesh: for many vertices of one mesh use [`LimitStencils`].
    pub fn limit_stencil(mesh: &PolyMesh, v: usize) -> Stencil {
        LimitStencils::new(mesh).stencil(v)
    }

    fn child(mesh: &PolyMesh, opts: &Opts) -> (PolyMesh, StencilTable) {
        let st = Self::stencils_with(mesh, opts);
        let m = Self::child_mesh_with(mesh, st.apply(mesh.positions()), opts);
        (m, st)
    }

    fn limit_through_child(
        cm: &PolyMesh,
        cs: &StencilTable,
        sharp: Option<&SharpLevel<'_>>,
        v: usize,
    ) -> Stencil {
        let s = Self::direct_limit_stencil(cm, sharp, v)
            .expect("child of a vertex is surrounded by quads");
        let mut out = Stencil::new();
        for &(i, w) in s.entries() {
            out.add_scaled(&cs.stencil(i as usize), w);
        }
        out.merged()
    }

    /// Limit stencil when all faces at `v` are quads (or `v` is sharp or on the boundary).
    fn direct_limit_stencil(
        mesh: &PolyMesh,
        sharp: Option<&SharpLevel<'_>>,
        v: usize,
    ) -> Option<Stencil> {
        let mut s = Stencil::new();
        let mut scratch = Scratch::default();
        limit_terms(&mesh.view(), sharp, v, &mut scratch, &mut s).then(|| s.merged())
    }

    /// Limit tangent stencils `(t1, t2)` at vertex `v` when all faces at `v` are quads: for an
    /// interior vertex the eigenvector masks of Halstead et al. (t1 x t2 is the outward normal);
    /// for a boundary vertex of valence 3 and a corner the exact derivatives of the regular
    /// boundary patch (ghost points mirrored across the boundary); at a boundary vertex of
    /// `k >= 3` quads the boundary curve's tangent and the subdominant eigen tangent across the
    /// boundary ([`super::boundary_tangent`]; they span the plane its G^1 cap is centred in).
    /// Returns `None` next to non-quads and at boundary vertices of more than
    /// [`super::boundary_tangent::MAX_BOUNDARY_FACES`] quads.
    pub fn tangent_stencils(mesh: &PolyMesh, v: usize) -> Option<(Stencil, Stencil)> {
        let hs = mesh.outgoing_halfedges(v);
        if hs
            .iter()
            .any(|&h| mesh.face_size(mesh.he_face(h) as usize) != 4)
        {
            return None;
        }
        if mesh.is_boundary_vertex(v) {
            let nb = mesh.vertex_neighbors(v);
            let (a, b) = (nb[0] as usize, *nb.last()? as usize);
            let mut along = Stencil::new();
            let mut across = Stencil::new();
            match nb.len() {
                2 => {
                    // Corner: the face is (v, a, d, b); tangents along both boundary edges.
                    along.add(a, 1.0).add(v, -1.0);
                    across.add(b, 1.0).add(v, -1.0);
                }
                3 => {
                    // Regular boundary vertex: nb = [a, c, b] counter-clockwise.
                    along.add(a, 1.0).add(b, -1.0);
                    across = Self::boundary_cross_stencil(mesh, v, &hs, &nb);
                }
                k1 => {
                    // extraordinary boundary vertex of k = k1 - 1 quads: the boundary curve's
                    // tangent and the subdominant left eigenvector (see `boundary_tangent`)
                    let w = super::boundary_tangent::across_weights(k1 - 1)?;
                    let diag = |h: u32| mesh.he_from(mesh.he_next(mesh.he_next(h))) as usize;
                    along.add(a, 1.0).add(b, -1.0);
                    across.add(v, w.1[0]);
                    for (i, &e) in nb.iter().enumerate() {
                        across.add(e as usize, w.1[1 + i]);
                    }
                    for (i, &h) in hs.iter().enumerate() {
                        across.add(diag(h), w.1[k1 + 1 + i]);
                    }
                }
            }
            return Some((along.merged(), across.merged()));
        }
        Some((
            Self::eigen_tangent(mesh, &hs, 0).merged(),
            Self::eigen_tangent(mesh, &hs, 1).merged(),
        ))
    }

    /// Halstead et al.'s eigenvector tangent mask at an interior vertex of valence `n` with only
    /// quads around it (`hs` its outgoing half-edges), phased to its `j`-th edge:
    /// `sum_i a_n cos(2 pi (i - j) / n) e_i + (cos(2 pi (i - j) / n) + cos(2 pi (i + 1 - j) / n)) f_i`
    /// over the edge neighbours `e_i` and face neighbours `f_i`, `a_n = 1 + c + cos(pi / n)
    /// sqrt(2 (9 + c))`. It points along the limit tangent of edge `j`; divided by `3 n` it is the
    /// derivative along that edge in its unit parameter (exact for `n = 4`).
    pub fn eigen_tangent(mesh: &PolyMesh, hs: &[u32], j: usize) -> Stencil {
        let nf = hs.len() as f64;
        let c = (2.0 * PI / nf).cos();
        let a_n = 1.0 + c + (PI / nf).cos() * (2.0 * (9.0 + c)).sqrt();
        let j = j as isize;
        let cj = |k: isize| (2.0 * PI * (k - j) as f64 / nf).cos();
        let diag = |h: u32| mesh.he_from(mesh.he_next(mesh.he_next(h))) as usize;
        let mut t = Stencil::new();
        for (i, &h) in hs.iter().enumerate() {
            let i = i as isize;
            t.add(mesh.he_to(h) as usize, a_n * cj(i));
            t.add(diag(h), cj(i) + cj(i + 1));
        }
        t
    }

    /// Six times the derivative across the boundary, in the unit edge parameter, at a regular
    /// boundary vertex `v` (two quads; `hs` its outgoing half-edges, `nb = [a, c, b]` its
    /// neighbours counter-clockwise): `d1 + 4 c + d2 - a - 4 v - b`, the exact derivative of the
    /// regular boundary patch with ghost points mirrored across the boundary.
    pub fn boundary_cross_stencil(mesh: &PolyMesh, v: usize, hs: &[u32], nb: &[u32]) -> Stencil {
        let diag = |h: u32| mesh.he_from(mesh.he_next(mesh.he_next(h))) as usize;
        let (a, c, b) = (nb[0] as usize, nb[1] as usize, nb[2] as usize);
        let mut across = Stencil::new();
        across
            .add(diag(hs[0]), 1.0)
            .add(c, 4.0)
            .add(diag(hs[1]), 1.0)
            .add(a, -1.0)
            .add(v, -4.0)
            .add(b, -1.0);
        across
    }

    /// Unit limit normals of every vertex (outward for counter-clockwise faces). Vertices whose
    /// tangents have no closed form here (next to non-quads, irregular boundary vertices) use the
    /// limit normal of their child after one step, found the same way, and after two steps fall
    /// back to the area-weighted normal of the child's limit positions.
    pub fn limit_normals(mesh: &PolyMesh) -> Vec<Point> {
        Self::normals_rec(mesh, 2)
    }

    fn normals_rec(mesh: &PolyMesh, depth: usize) -> Vec<Point> {
        let pos = mesh.positions();
        let mut out = vec![[0.0; 3]; mesh.num_vertices()];
        let mut missing = Vec::new();
        for (v, o) in out.iter_mut().enumerate() {
            match Self::tangent_stencils(mesh, v) {
                Some((t1, t2)) => *o = geom::normalize(geom::cross(t1.apply(pos), t2.apply(pos))),
                None => missing.push(v),
            }
        }
        if missing.is_empty() {
            return out;
        }
        let child = Self::child_mesh(mesh, Self::refine_points(mesh, pos));
        let child_normals = if depth > 0 {
            Self::normals_rec(&child, depth - 1)
        } else {
            let lim = Self::limit_stencils(&child).apply(child.positions());
            (0..child.num_vertices())
                .map(|v| {
                    let mut nrm = [0.0; 3];
                    for h in child.outgoing_halfedges(v) {
                        let a = geom::sub(lim[child.he_to(h) as usize], lim[v]);
                        let p = child.he_prev(h);
                        let b = geom::sub(lim[child.he_from(p) as usize], lim[v]);
                        nrm = geom::add(nrm, geom::cross(a, b));
                    }
                    geom::normalize(nrm)
                })
                .collect()
        };
        for v in missing {
            out[v] = child_normals[v];
        }
        out
    }
}
