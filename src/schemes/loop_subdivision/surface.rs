//! Loop surfaces as exact patch complexes: quartic box-spline triangles, rings, and a fill.
//!
//! Where all three corners of a triangle are regular (interior valence 6, or boundary vertices
//! with three triangles), Loop's limit over the triangle is one piece of the quartic
//! three-direction box spline: a triangular Bezier patch of degree 4 (15 coefficients) computed
//! from the 12 control points around the triangle with the weights [`BOX_SPLINE_BEZIER`]. Other
//! triangles are refined with Loop's own rules ([`crate::schemes::loop_subdivision`]) together
//! with the triangles around their corners; regular children are emitted as ring `l` at level
//! `l`, the rest refined again; after `K` levels the hole around an interior extraordinary
//! vertex is closed by a G^1 cap of kites, the hole at an extraordinary boundary vertex by an
//! open fan cap (`g1`: C^1 to the last ring, centred at Loop's limit point with its limit
//! tangent plane), other holes by the C^0 fill below.
//!
//! # Storage as tensor-product patches
//!
//! A [`PatchComplex`] holds tensor-product patches, so a triangle `T(s, t)` over the corners
//! `P0 (s, t) = (0, 0)`, `P1 (1, 0)`, `P2 (0, 1)` is stored as the exactly equivalent patch of
//! bi-degree (4, 4) `X(u, v) = T(u (1 - v), v)`. Its barycentric coordinates are bilinear in
//! `(u, v)`: `(1 - u)(1 - v)`, `u (1 - v)`, `v`, so column `j` (`v`-index) of its coefficients is
//! the degree-`4 - j` curve `b_{4-j-r, r, j}`, `r = 0 ..= 4 - j`, degree-raised to 4
//! ([`triangle_to_tensor`]). Side `v = 0` is the edge `P0 P1`, `u = 0` the edge `P0 P2` and
//! `u = 1` the edge `P1 P2` (each linearly parametrised, so the sides of neighbouring triangles
//! match as curves); side `v = 1` is collapsed to `P2`. The normal `du x dv` points like the
//! triangle's.
//!
//! # Derivation of the Bezier weights
//!
//! Loop's limit on a regular region is the quartic box spline (Loop 1987), a polynomial of total
//! degree 4 on each triangle, determined by its values at the 15 points of the degree-4 lattice
//! of the triangle. Loop's own rules give those values exactly: two refinement steps put a
//! vertex on every lattice point (the corners, the level-1 edge points at the edge midpoints,
//! the level-2 points at the quarter points and inside), and the valence-6 limit mask
//! `v / 2 + (sum of the six neighbours) / 12` gives their limit positions. Solving the 15 x 15
//! Bernstein collocation system in exact rational arithmetic expresses every Bezier coefficient
//! in the 12 control points; all weights are multiples of 1/24 ([`BOX_SPLINE_BEZIER`]). The
//! corner coefficients are Loop's limit mask, the coefficients sum to one and the table is
//! invariant under the rotation of the triangle. The test `table_is_loops_limit_interpolant`
//! repeats the derivation in floating point (Loop's stencils, then an LU solve of the
//! collocation system) and reproduces every weight to 1e-12; `box_spline_matches_loop_limits`
//! (and the integration tests) compare the patches with Loop limit positions of refined nets.
//!
//! # Boundaries
//!
//! With the OpenSubdiv boundary rules of [`crate::schemes::loop_subdivision`] (edge midpoints,
//! boundary vertices `(1, 6, 1) / 8`) a boundary vertex with three triangles is regular: the
//! missing control points are phantoms `a + b - c` across each boundary edge `a b` of a triangle
//! `a b c` (parallelogram completion). With them Loop's interior rules reproduce the boundary
//! rules (`e + f = 2 v + a + b - c - d` turns the valence-6 vertex rule into `(1, 6, 1) / 8`, and
//! the edge rule into the midpoint), so boundary triangles are exact box-spline pieces (the
//! tests compare them with Loop limit points of refined nets). Corners and boundary vertices with other
//! numbers of triangles are extraordinary.
//!
//! # Layout
//!
//! Ring `l` lies at level `l`. A triangle at an isolated extraordinary vertex of valence `n`
//! splits into one triangle at the vertex (refined again) and three regular ones, so every ring
//! holds `3 n` triangles, three per sector (= triangle of the vertex's fan), and the fill `n`.
//! A triangle touching several extraordinary vertices belongs to the first one among its
//! corners; its children are re-attributed to the vertex they touch.
//!
//! # The Hermite fill (fairsub's own, documented construction)
//!
//! The holes without a G^1 cap (a centre or boundary with a sharp feature, holes whose ring is
//! not complete after the extra levels, see `g1`; extraordinary boundary vertices until
//! 2026-12-04) are filled (`fill.rs`).
//! Each triangle left after the last ring becomes one quartic triangle. Its three edge curves
//! are defined once per edge and shared by both triangles at the edge, so the fill is C^0: an
//! edge shared with a triangle emitted at the same level takes that triangle's edge (exact); a
//! boundary edge takes the exact limit boundary curve, the cubic B-spline of the boundary
//! polygon (a corner stays put: ghost point `2 c - n`); any other edge is the cubic Hermite
//! interpolant, degree-raised to 4, of the Loop limit positions of its end points and the
//! derivatives along the edge: `(2 / n) sum_i cos(2 pi i / n) p_i` over the `n` neighbours
//! counted from the edge's far end (Loop's cosine tangent; the exact box-spline derivative for
//! `n = 6`, and with phantoms at regular boundary vertices), the chord at other boundary
//! vertices. The spokes at an extraordinary vertex therefore lie in its limit tangent plane.
//! The three interior coefficients are discrete harmonic (each the mean of its six neighbours
//! in the Bezier net), which reproduces linear functions. The fill is C^0 to the last ring and
//! between fill triangles; it is not G^1 across its edges.

use super::Rules;
use crate::bezier::BezierPatch;
use crate::bezier::complex::{PatchComplex, Provenance};
use crate::error::Result;
use crate::geom::{self, Point};
use crate::host::ComplexOptions;
use crate::host::adaptive::{
    self, AdaptiveRules, Curves, FanSectors, Info, MeshLevel, Sink, SplitTrust, Tag, child_active,
    record_edge, retag_by_corners, select_around,
};
use crate::mesh::PolyMesh;
use crate::mesh::split::{Numbering, SplitPoint, sparse_split};
use crate::mesh::tags::SubdOptions;
use crate::schemes::sdc::crease::adaptive::{
    self as features, edge_known, is_hole, is_last_cap_level,
};
use crate::stencil::{Stencil, StencilTable};

mod fill;
mod g1;
pub mod sharp;

/// Bezier coefficients of one triangle of the quartic box spline (Loop's regular limit), times
/// 24. Entry `([i, j, k], w)`: the coefficient `b_ijk` of the Bernstein polynomial
/// `4! / (i! j! k!) l0^i l1^j l2^k` (barycentric `l0, l1, l2` of the corners `P0, P1, P2`, which
/// are counter-clockwise) is `sum_s w[s] q_s / 24` over the 12 control points
/// `q = [P0, P1, P2, A01, A12, A20, X0a, X0b, X1a, X1b, X2a, X2b]`: `Aab` is the apex of the
/// triangle across edge `Pa Pb`, and walking counter-clockwise around corner `Pk` from
/// `P(k+1)`, its six neighbours are `P(k+1), P(k+2), A(k+2)k, Xka, Xkb, Ak(k+1)`. Derived in the
/// [module](self) documentation.
pub const BOX_SPLINE_BEZIER: [([usize; 3], [u32; 12]); 15] = [
    ([4, 0, 0], [12, 2, 2, 2, 0, 2, 2, 2, 0, 0, 0, 0]),
    ([3, 1, 0], [12, 4, 3, 3, 0, 1, 0, 1, 0, 0, 0, 0]),
    ([3, 0, 1], [12, 3, 4, 1, 0, 3, 1, 0, 0, 0, 0, 0]),
    ([2, 2, 0], [8, 8, 4, 4, 0, 0, 0, 0, 0, 0, 0, 0]),
    ([2, 1, 1], [10, 6, 6, 1, 0, 1, 0, 0, 0, 0, 0, 0]),
    ([2, 0, 2], [8, 4, 8, 0, 0, 4, 0, 0, 0, 0, 0, 0]),
    ([1, 3, 0], [4, 12, 3, 3, 1, 0, 0, 0, 1, 0, 0, 0]),
    ([1, 2, 1], [6, 10, 6, 1, 1, 0, 0, 0, 0, 0, 0, 0]),
    ([1, 1, 2], [6, 6, 10, 0, 1, 1, 0, 0, 0, 0, 0, 0]),
    ([1, 0, 3], [4, 3, 12, 0, 1, 3, 0, 0, 0, 0, 0, 1]),
    ([0, 4, 0], [2, 12, 2, 2, 2, 0, 0, 0, 2, 2, 0, 0]),
    ([0, 3, 1], [3, 12, 4, 1, 3, 0, 0, 0, 0, 1, 0, 0]),
    ([0, 2, 2], [4, 8, 8, 0, 4, 0, 0, 0, 0, 0, 0, 0]),
    ([0, 1, 3], [3, 4, 12, 0, 3, 1, 0, 0, 0, 0, 1, 0]),
    ([0, 0, 4], [2, 2, 12, 0, 2, 2, 0, 0, 0, 0, 2, 2]),
];

/// Position in [`BOX_SPLINE_BEZIER`] (and in a triangle net `[Point; 15]`) of `b_ijk`,
/// `i + j + k = 4`.
pub fn tri_index(i: usize, j: usize, k: usize) -> usize {
    debug_assert_eq!(i + j + k, 4);
    // Rows of decreasing i; within a row decreasing j.
    let before: usize = (i + 1..=4).map(|a| 5 - a).sum();
    before + (4 - i - j)
}

/// The quartic triangular Bezier patch with coefficients `tri` (order of
/// [`BOX_SPLINE_BEZIER`]) as the equivalent degenerate tensor-product patch of bi-degree (4, 4),
/// `X(u, v) = T(u (1 - v), v)` (see the [module](self) documentation; side `v = 1` collapses to
/// the corner `P2`).
pub fn triangle_to_tensor(tri: &[Point; 15]) -> BezierPatch {
    crate::bezier::convert::triangle_to_tensor(4, tri)
}

/// Evaluates the triangular patch `tri` at barycentric `(l0, l1, l2)` (an independent check of
/// [`triangle_to_tensor`] and a convenience for tests).
pub fn eval_triangle(tri: &[Point; 15], l: [f64; 3]) -> Point {
    let fact = [1.0, 1.0, 2.0, 6.0, 24.0];
    let mut p = [0.0; 3];
    for (k, (m, _)) in BOX_SPLINE_BEZIER.iter().enumerate() {
        let w = 24.0 / (fact[m[0]] * fact[m[1]] * fact[m[2]])
            * l[0].powi(m[0] as i32)
            * l[1].powi(m[1] as i32)
            * l[2].powi(m[2] as i32);
        p = geom::axpy(p, w, tri[k]);
    }
    p
}

/// The Loop surface of `mesh` (a triangle net) as a patch complex: one degenerate bi-4 patch per
/// regular triangle, `opts.rings` rings around every extraordinary vertex and, if `opts.fill`,
/// the G^1 caps and the Hermite fill (see the [module](self) documentation). `progress(level)` is called after
/// each refinement level.
///
/// # Errors
/// [`Error::Unsupported`](crate::error::Error::Unsupported) naming the first face that is not a triangle.
pub fn loop_complex(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    progress: impl FnMut(usize),
) -> Result<PatchComplex> {
    loop_complex_with(mesh, opts, SubdOptions::default(), progress)
}

/// [`loop_complex`] with OpenSubdiv's options: the net's sharp features, boundary option and
/// holes as [`sharp`] documents.
///
/// # Errors
/// [`Error::Unsupported`](crate::error::Error::Unsupported) naming the first face that is not a triangle.
pub fn loop_complex_with(
    mesh: &PolyMesh,
    opts: ComplexOptions,
    subd: SubdOptions,
    mut progress: impl FnMut(usize),
) -> Result<PatchComplex> {
    adaptive::run(&LoopRules { opts, subd }, mesh, opts, &mut progress)
}

/// Loop's rules for the adaptive loop: cells are triangles.
struct LoopRules {
    opts: ComplexOptions,
    /// OpenSubdiv's options under which the net's features are honoured.
    subd: SubdOptions,
}

impl AdaptiveRules for LoopRules {
    type Level = Level;
    type Curves = Curves<5>;

    fn start(&self, mesh: &PolyMesh, _opts: ComplexOptions) -> Result<Level> {
        crate::schemes::common::require_triangles(mesh, "Loop patches need")?;
        Ok(Level::input(mesh, Some(&self.subd)))
    }

    fn emit(&self, level: &Level, f: u32, prov: Provenance, to: Sink<Curves<5>>) -> bool {
        if is_hole(level, f as usize) {
            return true;
        }
        let Some(tri) = trusted_net(level, f as usize) else {
            return false;
        };
        record_curves(&level.mesh, f as usize, &tri, to.curves);
        to.out.push(triangle_to_tensor(&tri), prov);
        sharp::mark_sides(level, f as usize, to.out);
        true
    }

    fn retag(&self, level: &Level, f: u32, tag: Tag, _l: usize) -> Tag {
        retag(level, f as usize, tag, &mut FanSectors::default())
    }

    fn retag_all(&self, level: &Level, cells: Vec<(u32, Tag)>, _l: usize) -> Vec<(u32, Tag)> {
        adaptive::retag_with_fans(cells, |f, tag, fans| retag(level, f as usize, tag, fans))
    }

    /// From the requested ring on, the G^1 cap of every hole with complete data ([`g1`]).
    fn caps(
        &self,
        level: &Level,
        marked: Vec<(u32, Tag)>,
        l: usize,
        out: &mut PatchComplex,
    ) -> Result<Vec<(u32, Tag)>> {
        if self.opts.fill && l >= self.opts.rings {
            Ok(g1::g1_caps(level, &marked, out))
        } else {
            Ok(marked)
        }
    }

    /// [`is_last_cap_level`]: holes that wait for their ring or for semi-sharp features to be
    /// spent.
    fn is_last(&self, l: usize, rings: usize, level: &Level, marked: &[(u32, Tag)]) -> bool {
        let waiting = || g1::waiting(level, marked);
        is_last_cap_level((l, rings, self.opts.fill), level, waiting)
    }

    fn fill(&self, level: &Level, marked: &[(u32, Tag)], to: Sink<Curves<5>>) -> Result<()> {
        fill::fill(level, marked, to.curves, to.out);
        Ok(())
    }

    fn refine_around(&self, level: &Level, marked: &[(u32, Tag)]) -> Result<Level> {
        refine_around(level, marked)
    }
}

type Level = features::Level;

/// Whether `v` is a regular Loop vertex: interior of valence 6 or boundary with 3 triangles.
fn is_regular(m: &PolyMesh, v: usize) -> bool {
    // At most seven half-edges are counted: O(1) at a vertex of high valence too.
    let n = m.outgoing(v).take(7).count();
    if m.is_boundary_vertex(v) {
        n == 3
    } else {
        n == 6
    }
}

/// The six neighbours of a regular vertex counter-clockwise from the end of its first outgoing
/// half-edge under the plain rules, phantoms (`v + a - c`, see the module documentation) for
/// the two missing ones of a boundary vertex. `None` for a vertex that is not regular.
fn ring6(m: &PolyMesh, v: usize) -> Option<[Stencil; 6]> {
    let h = m.outgoing(v).next()?;
    sharp::corner_ring(m, None, h)
}

/// The 12 control points of triangle `f` of `level` (order of [`BOX_SPLINE_BEZIER`]) as
/// stencils, or `None` unless all its corners are regular (with respect to the level's
/// features, [`sharp`]).
fn box_spline_net(level: &Level, f: usize) -> Option<[Stencil; 12]> {
    let m = &level.mesh;
    let h0 = m.face_halfedge(f);
    let mut rings: Vec<[Stencil; 6]> = Vec::with_capacity(3);
    for h in h0..h0 + 3 {
        rings.push(sharp::corner_ring(m, level.sharp.as_ref(), h)?);
    }
    let corner = |k: usize| Stencil::point(m.face(f)[k] as usize);
    Some([
        corner(0),
        corner(1),
        corner(2),
        rings[0][5].clone(),
        rings[1][5].clone(),
        rings[2][5].clone(),
        rings[0][3].clone(),
        rings[0][4].clone(),
        rings[1][3].clone(),
        rings[1][4].clone(),
        rings[2][3].clone(),
        rings[2][4].clone(),
    ])
}

/// The 15 Bezier coefficients of a regular triangle as stencils over the mesh vertices.
fn box_spline_stencils(net: &[Stencil; 12]) -> Vec<Stencil> {
    BOX_SPLINE_BEZIER
        .iter()
        .map(|(_, w)| Stencil::integer_combination(net, w.iter().copied(), 24.0))
        .collect()
}

/// The triangular Bezier net of triangle `f` if it is regular and trusted.
fn trusted_net(level: &Level, f: usize) -> Option<[Point; 15]> {
    let m = &level.mesh;
    if m.face(f).iter().any(|&v| !level.info[v as usize].fan_ok) {
        return None;
    }
    let s = box_spline_stencils(&box_spline_net(level, f)?);
    if s.iter().any(|st| {
        st.entries()
            .iter()
            .any(|&(x, _)| !level.info[x as usize].pos_ok)
    }) {
        return None;
    }
    let pts: Vec<Point> = s.iter().map(|st| st.apply(m.positions())).collect();
    pts.try_into().ok()
}

/// Coefficients of the edge from corner `k` to corner `k + 1` of a triangular net.
fn tri_edge(tri: &[Point; 15], k: usize) -> [Point; 5] {
    std::array::from_fn(|r| {
        let mut m = [0usize; 3];
        m[k] = 4 - r;
        m[(k + 1) % 3] = r;
        tri[tri_index(m[0], m[1], m[2])]
    })
}

/// Stores the edge curves of a triangle, keyed by its vertex pairs (oriented from the smaller).
fn record_curves(m: &PolyMesh, f: usize, tri: &[Point; 15], curves: &mut Curves<5>) {
    let c = m.face(f);
    for k in 0..3 {
        record_edge(curves, c[k], c[(k + 1) % 3], tri_edge(tri, k));
    }
}

/// The tag of a marked triangle: its first extraordinary corner's input vertex, sector = the
/// triangle's position in that vertex's fan; otherwise the inherited tag.
fn retag(level: &Level, f: usize, tag: Tag, fans: &mut FanSectors) -> Tag {
    let regular = |_: &PolyMesh, v: usize| !sharp::irregular_vertex(level, v);
    retag_by_corners(&level.mesh, &level.info, f, tag, regular, fans)
}

/// Refines the triangles around the corners of the marked triangles with Loop's rules on the
/// mesh layer's triangle 1-4 split ([`sparse_split`]); the next level's active triangles are
/// the four children of each marked triangle.
fn refine_around(level: &Level, marked: &[(u32, Tag)]) -> Result<Level> {
    let m = &level.mesh;
    let nv = m.num_vertices();
    let (sel, sel_faces) = select_around(m, marked);
    let rules = Rules::new(m, &level.options());
    let trust = SplitTrust::new(m, &level.info, &sel);
    let split = sparse_split(m, sel_faces, false, Numbering::CornersFirst);
    let mut stencils: Vec<Stencil> = Vec::with_capacity(split.points.len());
    let mut info: Vec<Info> = Vec::with_capacity(split.points.len());
    for &p in &split.points {
        match p {
            SplitPoint::Vertex(v) => {
                let s = rules.vertex_stencil(v as usize);
                info.push(trust.vertex(v as usize, trust.reads_ok(&s)));
                stencils.push(s);
            }
            SplitPoint::Edge(e) => {
                let e = e as usize;
                let h = m.edge_halfedge(e);
                let [a, b] = m.edge(e);
                let (a_ok, b_ok) = (level.info[a as usize].fan_ok, level.info[b as usize].fan_ok);
                let known = edge_known(level, e, a_ok, b_ok, trust.edge_side_known(h));
                let s = rules.edge_stencil(e);
                info.push(trust.edge(e, known, trust.reads_ok(&s)));
                stencils.push(s);
            }
            SplitPoint::Face(_) => unreachable!("the triangle split has no face points"),
        }
    }
    // per child triangle: a hole's descendant
    let hole: Vec<bool> = split
        .faces
        .iter()
        .flat_map(|&f| [is_hole(level, f as usize); 4])
        .collect();
    let positions = StencilTable::from_rows(nv, stencils, 7).apply(m.positions());
    let child = PolyMesh::from_partial_refinement(positions, split.face_start, split.corners)?;
    let ids = (&split.vertex_point[..], &split.edge_point[..]);
    let (child, sharp) = features::child(level, rules.sharp(), child, ids, hole);
    let mut active = child_active(marked, |f| (split.first_child[f as usize], 4));
    // four children per marked triangle, in the order of the corners above: the child domains
    for (i, (_, t)) in active.iter_mut().enumerate() {
        t.domain = t.domain.child((i % 4) as u32);
    }
    Ok(Level {
        base: MeshLevel {
            mesh: child,
            info,
            active,
        },
        sharp,
        rows: None,
    })
}

#[cfg(feature = "unit-tests")]
mod tests;
