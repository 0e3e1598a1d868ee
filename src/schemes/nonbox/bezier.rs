//! The regular limit of non-box subdivision as cubic Bezier triangles: the S_3^1 spline pieces.
//!
//! On a regular region the limit surface is the four-directional S_3^1 spline of the control
//! points: on each quad cell of the net it is four cubic polynomials, one per triangle of the
//! cell's criss-cross (the cell split by both diagonals). The piece over the triangle with
//! corners `P0 = c00`, `P1 = c10` (an edge of the cell) and `P2` = the cell centre depends on the
//! cell's four corners and the FCVs of the 3 x 3 cells around it; [`CELL_TRIANGLE_BEZIER`] gives
//! its ten Bezier coefficients. The other three triangles use the same table in the cell's frame
//! turned to start at their edge.
//!
//! # Derivation of the table
//!
//! The generators are `phi_1 * chi_C` and `phi_2 * chi_C` (Section 2.2): a vertex `p` of the net
//! carries the square pyramid of `[p - 1/2, p + 1/2]^2` convolved with the unit box, an FCV at
//! the centre `q` of a cell the pyramid over the diamond `|x - q| + |y - q| <= 1` convolved with
//! the unit box (vertices on the integer lattice, FCVs at cell centres; the constants are
//! reproduced: the two kinds integrate to 1/3 and 2/3 and sum to one). The values of each
//! generator at the ten points of the cubic lattice of the triangle were computed in exact
//! rational arithmetic (clipping the pyramids' linear pieces against the box) and turned into
//! Bezier coefficients by solving the 10 x 10 Bernstein collocation system; an eleventh point
//! confirmed the pieces are cubic, and the generators were checked to satisfy the refinement
//! rules of [`super`] exactly. Every weight is a non-negative multiple of 1/24; the corner
//! coefficient is the paper's limit mask at valence 4 (`V / 3 + sum F / 6`), each row sums to
//! one and the table is symmetric under the cell's reflection. The test
//! `cell_table_is_the_limit_of_the_rules` repeats the derivation from the scheme itself: it
//! compares the patches with the limit positions (Section 4's formula) of every vertex of a net
//! refined four times.
//!
//! # Regular cells and boundaries
//!
//! A cell is regular when it is a quad and each corner is an interior vertex of valence 4 or a
//! boundary vertex with one or two faces. At a boundary vertex the missing FCVs are the ghosts
//! of the boundary NFCV rule (the reflection `a + b - F` of the FCV `F` of the face at the
//! boundary edge `a b`), which turn the boundary rules into the interior ones, so boundary cells
//! are exact pieces too. At a corner `w` (one face, boundary neighbours `a`, `b`, FCV `F`) the
//! two edge ghosts are joined by the diagonal ghost `2 w - a - b + F` (`F` moved by both edge
//! reflections): with these four FCVs the interior valence-4 rules give the corner rules (the
//! corner stays put: `w / 2 + (F + (w + a - F) + (w + b - F) + (2 w - a - b + F)) / 8 = w`; the
//! boundary E-vertices are midpoints; the NFCV at `w` is the corner NFCV rule), and the cell's
//! corner coefficient `w / 3 + sum F / 6` is `w`. The test `patches_are_exact_limits` checks the
//! corner cells of the c-nets and the open grid against the limit points of the refined net.
//!
//! # Storage as tensor-product patches
//!
//! A cubic triangle `T` is stored either as the degenerate bi-3 patch `X(u, v) = T(u (1 - v), v)`
//! ([`triangle_to_tensor`]; side `v = 1` collapses to `P2`, the other sides are the triangle's
//! edges with linear parameters, the layout of [`crate::schemes::loop_subdivision::surface::loop_complex`]), or, where a
//! collapsed corner would spoil a Jacobian certificate (the characteristic map), as three
//! non-degenerate bi-3 patches ([`triangle_to_quads`]): the triangle cut by its medians into the
//! quads `(P_k, mid(P_k P_k+1), centroid, mid(P_k-1 P_k))`, each an exact bilinear
//! reparametrisation (barycentric coordinates bilinear in `(s, t)`, so a cubic becomes bi-3).

use crate::bezier::BezierPatch;
use crate::geom::{self, Point};
use crate::mesh::PolyMesh;
use crate::stencil::Stencil;

/// Bezier coefficients of the triangle `(c00, c10, centre)` of a regular cell, times 24. Entry
/// `([i, j, k], w)`: the coefficient `b_ijk` of `3! / (i! j! k!) l0^i l1^j l2^k` (barycentric
/// `l0, l1, l2` of `P0 = c00`, `P1 = c10`, `P2` = centre, counter-clockwise) is
/// `sum_s w[s] q_s / 24` over the 13 control points
/// `q = [c00, c10, c11, c01, F(-1,-1), F(0,-1), F(1,-1), F(-1,0), F(0,0), F(1,0), F(-1,1), F(0,1), F(1,1)]`:
/// the cell's corners counter-clockwise and the FCVs of the cells `(i, j)` around it (`(0, 0)`
/// the cell itself, `i` along `c00 -> c10`, `j` along `c00 -> c01`). Derived in the
/// [module](self) documentation.
pub const CELL_TRIANGLE_BEZIER: [([usize; 3], [u8; 13]); 10] = [
    ([3, 0, 0], [8, 0, 0, 0, 4, 4, 0, 4, 4, 0, 0, 0, 0]),
    ([2, 1, 0], [8, 0, 0, 0, 0, 8, 0, 0, 8, 0, 0, 0, 0]),
    ([2, 0, 1], [8, 0, 0, 0, 0, 4, 0, 4, 8, 0, 0, 0, 0]),
    ([1, 2, 0], [0, 8, 0, 0, 0, 8, 0, 0, 8, 0, 0, 0, 0]),
    ([1, 1, 1], [4, 4, 0, 0, 0, 4, 0, 0, 12, 0, 0, 0, 0]),
    ([1, 0, 2], [4, 2, 0, 2, 0, 2, 0, 2, 12, 0, 0, 0, 0]),
    ([0, 3, 0], [0, 8, 0, 0, 0, 4, 4, 0, 4, 4, 0, 0, 0]),
    ([0, 2, 1], [0, 8, 0, 0, 0, 4, 0, 0, 8, 4, 0, 0, 0]),
    ([0, 1, 2], [2, 4, 2, 0, 0, 2, 0, 0, 12, 2, 0, 0, 0]),
    ([0, 0, 3], [2, 2, 2, 2, 0, 1, 0, 1, 12, 1, 0, 1, 0]),
];

/// A cubic Bezier triangle: coefficients in the order of [`CELL_TRIANGLE_BEZIER`].
pub type CubicTriangle = [Point; 10];

/// Position of `b_ijk` (`i + j + k = 3`) in a [`CubicTriangle`].
pub fn tri_index(i: usize, j: usize, k: usize) -> usize {
    debug_assert_eq!(i + j + k, 3);
    let before: usize = (i + 1..=3).map(|a| 4 - a).sum();
    before + (3 - i - j)
}

/// The FCV stencils of the four faces around the start vertex `w` of half-edge `g`,
/// counter-clockwise from `g`'s face; `None` unless `w` is an interior vertex of valence 4 or a
/// boundary vertex with two faces (whose two missing faces get ghost FCVs) or one face (three
/// ghosts; see the [module](self) documentation).
pub fn corner_fcvs(m: &PolyMesh, g: u32) -> Option<[Stencil; 4]> {
    let w = m.he_from(g) as usize;
    let nv = m.num_vertices();
    let fcv = |h: u32| Stencil::point(nv + m.he_face(h) as usize);
    // At most five half-edges: the rest of a fan of high valence is never needed (the vertex
    // is then not regular), and collecting it would cost its valence per call.
    let hs: Vec<u32> = m.outgoing(w).take(5).collect();
    let rot = |h: u32| m.he_twin(m.he_prev(h));
    if !m.is_boundary_vertex(w) {
        if hs.len() != 4 {
            return None;
        }
        let g1 = rot(g)?;
        let g2 = rot(g1)?;
        let g3 = rot(g2)?;
        return Some([fcv(g), fcv(g1), fcv(g2), fcv(g3)]);
    }
    if hs.len() == 1 {
        // A corner (one face): the two edge ghosts and, diagonally, the ghost `2 w - a - b + F`
        // (the FCV `F` moved by both edge reflections), under which the interior rules give the
        // corner rules (the corner stays put, boundary E-vertices are midpoints, the corner
        // NFCV is fairsub's reconstruction).
        let g0 = hs[0];
        let a = m.he_to(g0) as usize;
        let b = m.he_from(m.he_prev(g0)) as usize;
        let f0 = nv + m.he_face(g0) as usize;
        return Some([
            fcv(g0),
            Stencil::from_pairs([(w, 1.0), (b, 1.0), (f0, -1.0)]),
            Stencil::from_pairs([(w, 2.0), (a, -1.0), (b, -1.0), (f0, 1.0)]),
            Stencil::from_pairs([(w, 1.0), (a, 1.0), (f0, -1.0)]),
        ]);
    }
    if hs.len() != 2 {
        return None;
    }
    let (b0, b1) = (hs[0], hs[1]);
    let first = m.he_to(b0) as usize;
    let last = m.he_from(m.he_prev(b1)) as usize;
    let ghost = |other: usize, h: u32| {
        Stencil::from_pairs([(w, 1.0), (other, 1.0), (nv + m.he_face(h) as usize, -1.0)])
    };
    let cyc = [fcv(b0), fcv(b1), ghost(last, b1), ghost(first, b0)];
    let start = hs.iter().position(|&h| h == g)?;
    Some(std::array::from_fn(|i| cyc[(start + i) % 4].clone()))
}

/// The 13 control points of the cell of half-edge `h` in the frame starting at `h` (order of
/// [`CELL_TRIANGLE_BEZIER`]) as stencils over the net's points (vertices, then FCVs); `None`
/// unless the cell is regular (see the [module](self) documentation).
pub fn cell_net(m: &PolyMesh, h: u32) -> Option<[Stencil; 13]> {
    let f = m.he_face(h) as usize;
    if m.face_size(f) != 4 {
        return None;
    }
    let h1 = m.he_next(h);
    let h2 = m.he_next(h1);
    let h3 = m.he_next(h2);
    let r0 = corner_fcvs(m, h)?;
    let r1 = corner_fcvs(m, h1)?;
    let r2 = corner_fcvs(m, h2)?;
    let r3 = corner_fcvs(m, h3)?;
    let v = |g: u32| Stencil::point(m.he_from(g) as usize);
    Some([
        v(h),
        v(h1),
        v(h2),
        v(h3),
        r0[2].clone(),
        r0[3].clone(),
        r1[2].clone(),
        r0[1].clone(),
        r0[0].clone(),
        r1[3].clone(),
        r3[2].clone(),
        r2[3].clone(),
        r2[2].clone(),
    ])
}

/// The ten Bezier coefficients of the bottom triangle of a cell net, as stencils.
pub fn triangle_stencils(net: &[Stencil; 13]) -> Vec<Stencil> {
    CELL_TRIANGLE_BEZIER
        .iter()
        .map(|(_, w)| Stencil::integer_combination(net, w.iter().map(|&x| u32::from(x)), 24.0))
        .collect()
}

/// The Bezier stencils of the four triangles of the regular cell `f` (triangle `k` on the edge
/// from corner `k` to corner `k + 1`), over the net's points; `None` if the cell is not regular.
pub fn cell_stencils(m: &PolyMesh, f: usize) -> Option<[Vec<Stencil>; 4]> {
    let h0 = m.face_halfedge(f);
    if m.face_size(f) != 4 {
        return None;
    }
    let mut out: [Vec<Stencil>; 4] = Default::default();
    for (k, o) in out.iter_mut().enumerate() {
        *o = triangle_stencils(&cell_net(m, h0 + k as u32)?);
    }
    Some(out)
}

/// The four cubic triangles of the regular cell `f` for the given net points.
pub fn cell_triangles(m: &PolyMesh, f: usize, points: &[Point]) -> Option<[CubicTriangle; 4]> {
    let st = cell_stencils(m, f)?;
    Some(std::array::from_fn(|k| {
        std::array::from_fn(|i| st[k][i].apply(points))
    }))
}

/// Evaluates a cubic triangle at barycentric coordinates `l`.
pub fn eval_triangle(tri: &CubicTriangle, l: [f64; 3]) -> Point {
    let fact = [1.0, 1.0, 2.0, 6.0];
    let mut p = [0.0; 3];
    for (k, (m, _)) in CELL_TRIANGLE_BEZIER.iter().enumerate() {
        let w = 6.0 / (fact[m[0]] * fact[m[1]] * fact[m[2]])
            * l[0].powi(m[0] as i32)
            * l[1].powi(m[1] as i32)
            * l[2].powi(m[2] as i32);
        p = geom::axpy(p, w, tri[k]);
    }
    p
}

/// The cubic triangle as the degenerate bi-3 patch `X(u, v) = T(u (1 - v), v)` (side `v = 1`
/// collapsed to `P2`).
pub fn triangle_to_tensor(tri: &CubicTriangle) -> BezierPatch {
    crate::bezier::convert::triangle_to_tensor(3, tri)
}

/// The inverse of the cubic Bernstein collocation matrix at `0, 1/3, 2/3, 1`.
const BERNSTEIN3_INVERSE: [[f64; 4]; 4] = [
    [1.0, 0.0, 0.0, 0.0],
    [-5.0 / 6.0, 3.0, -1.5, 1.0 / 3.0],
    [1.0 / 3.0, -1.5, 3.0, -5.0 / 6.0],
    [0.0, 0.0, 0.0, 1.0],
];

/// The cubic triangle as three non-degenerate bi-3 patches: quad `k` has corners `P_k`,
/// `mid(P_k P_(k+1))`, the centroid and `mid(P_(k-1) P_k)` (counter-clockwise, `u` along the
/// first side), an exact bilinear reparametrisation.
pub fn triangle_to_quads(tri: &CubicTriangle) -> [BezierPatch; 3] {
    std::array::from_fn(|k| {
        let e = |i: usize| {
            let mut b = [0.0; 3];
            b[i % 3] = 1.0;
            b
        };
        let mid =
            |a: [f64; 3], b: [f64; 3]| std::array::from_fn::<f64, 3, _>(|i| 0.5 * (a[i] + b[i]));
        let a = e(k);
        let b = mid(e(k), e(k + 1));
        let c = [1.0 / 3.0; 3];
        let d = mid(e(k), e(k + 2));
        let at = |s: f64, t: f64| -> [f64; 3] {
            std::array::from_fn(|i| {
                (1.0 - s) * (1.0 - t) * a[i]
                    + s * (1.0 - t) * b[i]
                    + s * t * c[i]
                    + (1.0 - s) * t * d[i]
            })
        };
        // Values on the 4 x 4 grid, then the tensor inverse of the collocation matrix.
        let vals: Vec<Vec<Point>> = (0..4)
            .map(|i| {
                (0..4)
                    .map(|j| eval_triangle(tri, at(i as f64 / 3.0, j as f64 / 3.0)))
                    .collect()
            })
            .collect();
        BezierPatch::from_fn(3, 3, |i, j| {
            let mut p = [0.0; 3];
            for (a, row) in vals.iter().enumerate() {
                for (b, v) in row.iter().enumerate() {
                    let w = BERNSTEIN3_INVERSE[i][a] * BERNSTEIN3_INVERSE[j][b];
                    if w != 0.0 {
                        p = geom::axpy(p, w, *v);
                    }
                }
            }
            p
        })
    })
}
