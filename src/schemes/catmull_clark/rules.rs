//! Catmull-Clark's rules, written once (the module documentation of [`super`] says how they
//! are applied): the face, edge and vertex rules against [`CcTerms`], with OpenSubdiv's sharp
//! features through the crease plans, and the two ways of receiving their terms (a stencil row
//! with face points expanded, or points evaluated directly).

use super::*;

/// Receives the terms of a Catmull-Clark rule: weights on parent vertices and on parent face
/// points (see the module documentation).
pub(crate) trait CcTerms {
    /// Adds `w` times parent vertex `v`.
    fn vertex(&mut self, v: u32, w: f64);
    /// Adds `w` times the face point of parent face `f` ([`face_rule`]).
    fn face_point(&mut self, f: u32, w: f64);
}

/// Catmull-Clark's receiver of [`edge_terms`]: the smooth mask of edge `e` ([`smooth_edge`])
/// and vertex weights into `out`.
struct CcEdge<'r, 'm, O> {
    m: &'r MeshView<'m>,
    e: usize,
    tris: bool,
    out: &'r mut O,
}

impl<O: CcTerms> EdgeTerms for CcEdge<'_, '_, O> {
    #[inline(always)]
    fn smooth(&mut self, s: f64) {
        smooth_edge(self.m, self.e, self.tris, s, self.out)
    }

    #[inline(always)]
    fn vertex(&mut self, u: u32, w: f64) {
        self.out.vertex(u, w)
    }
}

/// Face point of face `f`, scaled by `scale`: `scale / k` times each of its `k` corners.
#[inline]
pub(super) fn face_rule(m: &MeshView<'_>, f: usize, scale: f64, out: &mut impl CcTerms) {
    let face = m.face_corners(f);
    let w = scale / face.len() as f64;
    for &v in face {
        out.vertex(v, w);
    }
}

/// OpenSubdiv's face weight of a triangle in the smooth edge mask under
/// `TriangleSubdivision::Smooth` (`CATMARK_SMOOTH_TRI_EDGE_WEIGHT`).
const SMOOTH_TRI_WEIGHT: f64 = 0.47;

/// The smooth mask of interior edge `e`, scaled: `(a + b + F1 + F2) / 4`; with smooth
/// triangles and a triangle among its two faces, face weights `w = (w1 + w2) / 2` (0.47 for a
/// triangle, 1/4 otherwise) and vertex weights `(1 - 2w) / 2`.
#[inline(always)]
pub(super) fn smooth_edge(
    m: &MeshView<'_>,
    e: usize,
    tris: bool,
    scale: f64,
    out: &mut impl CcTerms,
) {
    let h = m.edge_he[e];
    let (a, b, t) = (m.from(h), m.to(h), m.twin(h));
    let (f1, f2) = (m.face(h), m.face(t));
    let (mut vw, mut fw) = (0.25, 0.25);
    if tris {
        let w = |f: u32| {
            if m.face_corners(f as usize).len() == 3 {
                SMOOTH_TRI_WEIGHT
            } else {
                0.25
            }
        };
        let (w1, w2) = (w(f1), w(f2));
        if w1 != 0.25 || w2 != 0.25 {
            fw = 0.5 * (w1 + w2);
            vw = 0.5 * (1.0 - 2.0 * fw);
        }
    }
    out.vertex(a, vw * scale);
    out.vertex(b, vw * scale);
    out.face_point(f1, fw * scale);
    out.face_point(f2, fw * scale);
}

/// The smooth mask of interior vertex `v`, scaled:
/// `(n - 2)/n v + 1/n^2 sum(edge neighbours) + 1/n^2 sum(face points)`.
#[inline(always)]
pub(super) fn smooth_vertex(m: &MeshView<'_>, v: usize, scale: f64, out: &mut impl CcTerms) {
    let n = m.outgoing(v).count() as f64;
    out.vertex(v as u32, scale * (n - 2.0) / n);
    let w = scale / (n * n);
    for h in m.outgoing(v) {
        out.vertex(m.to(h), w);
        out.face_point(m.face(h), w);
    }
}

/// The rules of one step: plain, or with the sharp features of the level.
pub(crate) struct Rules<'a> {
    pub(super) m: MeshView<'a>,
    pub(super) sharp: Option<SharpLevel<'a>>,
    pub(super) tris: bool,
}

impl<'a> Rules<'a> {
    /// The rules for `mesh` under `opts`.
    pub fn new(mesh: &'a PolyMesh, opts: &Opts) -> Rules<'a> {
        let tris =
            opts.triangles() == TriangleSubdivision::Smooth && mesh.uniform_face_size() != Some(4);
        Rules {
            m: mesh.view(),
            sharp: SharpLevel::new(mesh, opts),
            tris,
        }
    }

    /// Edge point of edge `e`: the smooth mask inside, the midpoint on the boundary; with
    /// sharp features the edge's plan.
    #[inline(always)]
    pub(super) fn edge(&self, e: usize, scratch: &mut Scratch, out: &mut impl CcTerms) {
        self.edge_in::<false>(e, scratch, out)
    }

    /// Whether the level has neither sharp features nor smooth triangles: the plain rules.
    pub(super) fn plain(&self) -> bool {
        self.sharp.is_none() && !self.tris
    }

    /// [`Rules::edge`]; `PLAIN` (only where [`Rules::plain`] holds) compiles the feature checks
    /// away.
    #[inline(always)]
    pub(super) fn edge_in<const PLAIN: bool>(
        &self,
        e: usize,
        scratch: &mut Scratch,
        out: &mut impl CcTerms,
    ) {
        let (sharp, tris) = if PLAIN {
            (None, false)
        } else {
            (self.sharp.as_ref(), self.tris)
        };
        let m = &self.m;
        edge_terms(m, e, sharp, scratch, &mut CcEdge { m, e, tris, out });
    }

    /// Vertex point of `v`: the smooth mask inside; `3/4 v + 1/8 (a + b)` on the boundary; a
    /// corner stays put; with sharp features the vertex's plan.
    #[inline(always)]
    pub(super) fn vertex(&self, v: usize, scratch: &mut Scratch, out: &mut impl CcTerms) {
        self.vertex_in::<false>(v, scratch, out)
    }

    /// [`Rules::vertex`]; `PLAIN` as in [`Rules::edge_in`].
    #[inline(always)]
    pub(super) fn vertex_in<const PLAIN: bool>(
        &self,
        v: usize,
        scratch: &mut Scratch,
        out: &mut impl CcTerms,
    ) {
        let m = &self.m;
        let sharp = if PLAIN { None } else { self.sharp.as_ref() };
        match sharp {
            Some(sl) if sl.special[v] => {
                sl.vertex_plan(v as u32, scratch)
                    .emit(v as u32, |t| match t {
                        Emit::Smooth(s) => smooth_vertex(m, v, s, out),
                        Emit::Vertex(u, w) => out.vertex(u, w),
                    })
            }
            None if m.is_boundary_vertex(v) => {
                if m.is_corner(v) {
                    out.vertex(v as u32, 1.0);
                } else {
                    let (a, b) = m.boundary_neighbors(v);
                    out.vertex(v as u32, 0.75);
                    out.vertex(a, 0.125);
                    out.vertex(b, 0.125);
                }
            }
            _ => smooth_vertex(m, v, 1.0, out),
        }
    }
}

/// Expands face-point terms into the face's corners: the table form of a rule.
pub(super) struct Expand<'a, T> {
    pub(super) m: MeshView<'a>,
    pub(super) row: &'a mut T,
}

impl<T: Terms> CcTerms for Expand<'_, T> {
    #[inline]
    fn vertex(&mut self, v: u32, w: f64) {
        self.row.add(v, w);
    }

    #[inline]
    fn face_point(&mut self, f: u32, w: f64) {
        let m = self.m;
        face_rule(&m, f as usize, w, self);
    }
}

/// Evaluates a rule on point data, reading face points from the already computed child points.
pub(super) struct Eval<'a, const D: usize> {
    pub(super) src: &'a [[f64; D]],
    pub(super) faces: &'a [[f64; D]],
    pub(super) acc: [f64; D],
}

impl<'a, const D: usize> Eval<'a, D> {
    #[inline]
    pub(super) fn new(src: &'a [[f64; D]], faces: &'a [[f64; D]]) -> Self {
        Eval {
            src,
            faces,
            acc: [0.0; D],
        }
    }
}

impl<const D: usize> CcTerms for Eval<'_, D> {
    #[inline]
    fn vertex(&mut self, v: u32, w: f64) {
        axpy(&mut self.acc, w, &self.src[v as usize]);
    }

    #[inline]
    fn face_point(&mut self, f: u32, w: f64) {
        axpy(&mut self.acc, w, &self.faces[f as usize]);
    }
}

impl Rules<'_> {
    /// The stencil of the vertex point of `v` under these rules (the tests' reference for the
    /// rows [`Rules::push_vertex_row`] writes).
    #[cfg(feature = "unit-tests")]
    pub(crate) fn vertex_stencil(&self, v: usize) -> crate::stencil::Stencil {
        let mut s = crate::stencil::Stencil::new();
        let m = self.m;
        self.vertex(v, &mut Scratch::default(), &mut Expand { m, row: &mut s });
        s.merged()
    }

    /// Appends the row of the vertex point of `v` ([`Rules::vertex_stencil`]) to `table`,
    /// through the reusable buffers `scratch` and `row` (no allocation per row).
    pub(crate) fn push_vertex_row(
        &self,
        v: usize,
        scratch: &mut Scratch,
        row: &mut RowWriter,
        table: &mut StencilTable,
    ) {
        let m = self.m;
        self.vertex(v, scratch, &mut Expand { m, row: &mut *row });
        row.push_into(table);
    }

    /// Appends the row of the edge point of `e` ([`Rules::edge_stencil`]) to `table`, as
    /// [`Rules::push_vertex_row`].
    pub(crate) fn push_edge_row(
        &self,
        e: usize,
        scratch: &mut Scratch,
        row: &mut RowWriter,
        table: &mut StencilTable,
    ) {
        let m = self.m;
        self.edge(e, scratch, &mut Expand { m, row: &mut *row });
        row.push_into(table);
    }

    /// The stencil of the edge point of edge `e` under these rules.
    #[cfg(feature = "unit-tests")]
    pub(crate) fn edge_stencil(&self, e: usize) -> crate::stencil::Stencil {
        let mut s = crate::stencil::Stencil::new();
        let m = self.m;
        self.edge(e, &mut Scratch::default(), &mut Expand { m, row: &mut s });
        s.merged()
    }
}
