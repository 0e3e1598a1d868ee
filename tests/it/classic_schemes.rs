//! Tests of the classic schemes (Loop, Doo-Sabin, DS^CC) against independently computed numbers:
//! box-spline and B-spline subdivision masks from their symbols, limit values from the cascade
//! algorithm, circulant spectra from the DFT, and Euler counts.

use fairsub::PolyMesh;
use fairsub::schemes::Scheme;
use fairsub::schemes::doo_sabin::{self, DooSabin, DooSabinCc};
use fairsub::schemes::loop_subdivision::Loop;
use fairsub::stencil::StencilTable;

// ---------------------------------------------------------------------------------------------
// Nets

/// Index of lattice point (i, j) in a grid with m + 1 points per row.
fn gid(m: usize, i: usize, j: usize) -> usize {
    j * (m + 1) + i
}

/// A regular triangle grid over the lattice points (i, j), 0 <= i, j <= m, triangulated along
/// the three directions (1, 0), (0, 1), (1, 1). Heights `z(i, j)`.
fn tri_grid(m: usize, z: impl Fn(f64, f64) -> f64) -> PolyMesh {
    let mut pos = Vec::new();
    for j in 0..=m {
        for i in 0..=m {
            let (x, y) = (i as f64 - 0.5 * j as f64, j as f64 * 3f64.sqrt() / 2.0);
            pos.push([x, y, z(x, y)]);
        }
    }
    let mut faces = Vec::new();
    for j in 0..m {
        for i in 0..m {
            let (a, b, c, d) = (
                gid(m, i, j),
                gid(m, i + 1, j),
                gid(m, i + 1, j + 1),
                gid(m, i, j + 1),
            );
            faces.push(vec![a, b, c]);
            faces.push(vec![a, c, d]);
        }
    }
    PolyMesh::new(pos, &faces).unwrap()
}

fn tetrahedron() -> PolyMesh {
    let pos = vec![
        [1.0, 1.0, 1.0],
        [1.0, -1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
    ];
    PolyMesh::new(pos, &[[0, 1, 2], [0, 2, 3], [0, 3, 1], [1, 3, 2]]).unwrap()
}

fn octahedron() -> PolyMesh {
    fairsub::mesh::nets::octahedron()
}

/// A fan of `k` triangles around vertex 0: a closed disk (vertex 0 interior, valence k) or,
/// with `open`, a half disk (vertex 0 on the boundary with k faces). Wavy heights so that no
/// test passes by planarity.
fn fan(k: usize, open: bool) -> PolyMesh {
    let mut pos = vec![[0.0, 0.0, 0.3]];
    let rim = if open { k + 1 } else { k };
    let span = if open {
        std::f64::consts::PI / k as f64
    } else {
        2.0 * std::f64::consts::PI / k as f64
    };
    for i in 0..rim {
        let t = span * i as f64;
        pos.push([t.cos(), t.sin(), 0.2 * (3.0 * t).sin() + 0.05 * i as f64]);
    }
    let faces: Vec<[usize; 3]> = (0..k).map(|i| [0, 1 + i, 1 + (i + 1) % rim]).collect();
    PolyMesh::new(pos, &faces).unwrap()
}

/// Deterministic pseudo-random perturbation of the positions.
fn jiggle(mesh: &mut PolyMesh, amount: f64) {
    let pos: Vec<[f64; 3]> = mesh
        .positions()
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let s = |k: f64| ((i as f64 + 1.0) * k).sin() * amount;
            [p[0] + s(12.9898), p[1] + s(78.233), p[2] + s(37.719)]
        })
        .collect();
    mesh.set_positions(pos);
}

// ---------------------------------------------------------------------------------------------
// Helpers

/// Row `r` of a table as a dense vector over its sources.
fn dense_row(t: &StencilTable, r: usize) -> Vec<f64> {
    let mut out = vec![0.0; t.num_sources()];
    let (i, w) = t.row(r);
    for (&s, &x) in i.iter().zip(w) {
        out[s as usize] += x;
    }
    out
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Product of two bivariate polynomials given as coefficient grids `c[p][q]` of `x^p y^q`.
fn poly_mul(a: &[Vec<f64>], b: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let (na, ma, nb, mb) = (a.len(), a[0].len(), b.len(), b[0].len());
    let mut c = vec![vec![0.0; ma + mb - 1]; na + nb - 1];
    for p in 0..na {
        for q in 0..ma {
            for r in 0..nb {
                for s in 0..mb {
                    c[p + r][q + s] += a[p][q] * b[r][s];
                }
            }
        }
    }
    c
}

/// Univariate polynomial product.
fn poly_mul1(a: &[f64], b: &[f64]) -> Vec<f64> {
    let mut c = vec![0.0; a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            c[i + j] += x * y;
        }
    }
    c
}

/// `(1 + z)^d / 2^(d - 1)`: the subdivision mask of the uniform B-spline curve of degree d - 1.
fn bspline_mask(d: usize) -> Vec<f64> {
    let mut m = vec![1.0];
    for _ in 0..d {
        m = poly_mul1(&m, &[1.0, 1.0]);
    }
    let s = 2f64.powi(d as i32 - 1);
    m.iter().map(|x| x / s).collect()
}

/// Values at the integers of the basis function of a univariate subdivision mask `a`
/// (support 0..len-1), by the cascade algorithm `v(k) <- sum_j a_j v(2k - j)`.
fn cascade_values_1d(a: &[f64]) -> Vec<f64> {
    let n = a.len();
    let mut v = vec![0.0; n];
    v[0] = 1.0;
    for _ in 0..200 {
        let mut w = vec![0.0; n];
        for (k, wk) in w.iter_mut().enumerate() {
            for (j, aj) in a.iter().enumerate() {
                let idx = 2 * k as i64 - j as i64;
                if idx >= 0 && (idx as usize) < n {
                    *wk += aj * v[idx as usize];
                }
            }
        }
        v = w;
    }
    v
}

/// Checks that `child` is a valid manifold net: re-validating its flat arrays from scratch with
/// the full input validation passes and drops nothing.
fn assert_valid(child: &PolyMesh) {
    let again = PolyMesh::from_flat(
        child.positions().to_vec(),
        child.face_starts().to_vec(),
        child.corners().to_vec(),
    )
    .expect("child net passes validation");
    assert!(again.dropped_vertices().is_empty());
    assert_eq!(again.num_edges(), child.num_edges());
}

fn euler(m: &PolyMesh) -> i64 {
    m.num_vertices() as i64 - m.num_edges() as i64 + m.num_faces() as i64
}

// ---------------------------------------------------------------------------------------------
// Loop

/// The quartic three-direction box spline's symbol (1+x)^2 (1+y)^2 (1+xy)^2 / 16 as a 5 x 5
/// coefficient grid a[p][q] of x^p y^q.
fn box_spline_symbol() -> Vec<Vec<f64>> {
    let x = vec![vec![1.0], vec![1.0]];
    let y = vec![vec![1.0, 1.0]];
    let xy = vec![vec![1.0, 0.0], vec![0.0, 1.0]];
    let mut a = vec![vec![1.0]];
    for f in [&x, &x, &y, &y, &xy, &xy] {
        a = poly_mul(&a, f);
    }
    a.iter()
        .map(|r| r.iter().map(|c| c / 16.0).collect())
        .collect()
}

#[test]
fn loop_regular_refinement_is_the_box_spline() {
    let a = box_spline_symbol();
    assert_eq!(a.len(), 5);
    assert_eq!(a[2][2], 10.0 / 16.0);
    let m = 8;
    let mesh = tri_grid(m, |x, y| x * y);
    let r = Loop.refine(&mesh).unwrap();
    let nv = mesh.num_vertices();
    assert_eq!(r.stencils.num_rows(), nv + mesh.num_edges());
    // Lattice coordinates of every child point in units of the child lattice.
    let lat = |v: usize| ((v % (m + 1)) as i64, (v / (m + 1)) as i64);
    let mut child_lat = Vec::new();
    for v in 0..nv {
        let (i, j) = lat(v);
        child_lat.push((2 * i, 2 * j));
    }
    for e in 0..mesh.num_edges() {
        let [p, q] = mesh.edge(e);
        let ((i0, j0), (i1, j1)) = (lat(p as usize), lat(q as usize));
        child_lat.push((i0 + i1, j0 + j1));
    }
    let mut checked = (0, 0);
    for (c, &(ai, aj)) in child_lat.iter().enumerate() {
        // Rows whose rule is the regular one: interior valence-6 vertices and interior edges.
        let regular = if c < nv {
            !mesh.is_boundary_vertex(c) && mesh.valence(c) == 6
        } else {
            !mesh.is_boundary_edge(c - nv)
        };
        if !regular {
            continue;
        }
        // p'_alpha = sum_beta a_{alpha - 2 beta + (2, 2)} p_beta.
        let mut expected = vec![0.0; nv];
        for (b, w) in expected.iter_mut().enumerate() {
            let (bi, bj) = lat(b);
            let (p, q) = (ai - 2 * bi + 2, aj - 2 * bj + 2);
            if (0..5).contains(&p) && (0..5).contains(&q) {
                *w = a[p as usize][q as usize];
            }
        }
        assert_eq!(dense_row(&r.stencils, c), expected, "child point {c}");
        if c < nv {
            checked.0 += 1;
        } else {
            checked.1 += 1;
        }
    }
    assert_eq!(checked, ((m - 1) * (m - 1), 3 * m * m - 2 * m));
}

#[test]
fn loop_regular_limit_is_the_box_spline_value() {
    // Box-spline values at the lattice points by the cascade algorithm on the symbol.
    let a = box_spline_symbol();
    let mut v = vec![vec![0.0; 5]; 5];
    v[0][0] = 1.0;
    for _ in 0..200 {
        let mut w = vec![vec![0.0; 5]; 5];
        for k in 0..5i64 {
            for l in 0..5i64 {
                for p in 0..5i64 {
                    for q in 0..5i64 {
                        let (s, t) = (2 * k - p, 2 * l - q);
                        if (0..5).contains(&s) && (0..5).contains(&t) {
                            w[k as usize][l as usize] +=
                                a[p as usize][q as usize] * v[s as usize][t as usize];
                        }
                    }
                }
            }
        }
        v = w;
    }
    // Centre (2, 2) and its six neighbours along +-(1,0), +-(0,1), +-(1,1).
    assert!((v[2][2] - 0.5).abs() < 1e-14, "{}", v[2][2]);
    for (p, q) in [(3, 2), (1, 2), (2, 3), (2, 1), (3, 3), (1, 1)] {
        assert!((v[p][q] - 1.0 / 12.0).abs() < 1e-14);
    }
    assert!(v[3][1].abs() < 1e-14 && v[1][3].abs() < 1e-14);

    let m = 4;
    let mesh = tri_grid(m, |_, _| 0.0);
    let lim = Loop.limit_stencils(&mesh).unwrap();
    let c = gid(m, 2, 2);
    let row = dense_row(&lim, c);
    for j in 0..=m {
        for i in 0..=m {
            let (p, q) = (i as i64 - 2 + 2, j as i64 - 2 + 2);
            let expected = if (0..5).contains(&p) && (0..5).contains(&q) {
                v[p as usize][q as usize]
            } else {
                0.0
            };
            assert!((row[gid(m, i, j)] - expected).abs() < 1e-14);
        }
    }
}

#[test]
fn loop_boundary_is_the_cubic_bspline_of_the_boundary_polygon() {
    // Cubic B-spline curve mask (1+z)^4 / 8 = (1, 4, 6, 4, 1) / 8 and its values at the knots.
    let mask = bspline_mask(4);
    assert_eq!(mask, vec![0.125, 0.5, 0.75, 0.5, 0.125]);
    let knots = cascade_values_1d(&mask);
    assert!((knots[1] - 1.0 / 6.0).abs() < 1e-14 && (knots[2] - 2.0 / 3.0).abs() < 1e-14);

    let m = 5;
    let mesh = tri_grid(m, |x, y| (x + 2.0 * y).sin());
    let r = Loop.refine(&mesh).unwrap();
    let lim = Loop.limit_stencils(&mesh).unwrap();
    let loops = mesh.boundary_loops();
    assert_eq!(loops.len(), 1);
    let bl = &loops[0];
    let nb = bl.len();
    assert_eq!(nb, 4 * m);
    let nv = mesh.num_vertices();
    let mut corners = 0;
    for k in 0..nb {
        let (u, v, w) = (bl[(k + nb - 1) % nb], bl[k], bl[(k + 1) % nb]);
        let row = dense_row(&r.stencils, v as usize);
        let lrow = dense_row(&lim, v as usize);
        if mesh.valence(v as usize) == 2 {
            // A corner stays put and is its own limit.
            corners += 1;
            assert_eq!(row[v as usize], 1.0);
            assert_eq!(lrow[v as usize], 1.0);
            continue;
        }
        // Vertex rule: the even coefficients (1, 6, 1)/8 at (u, v, w); limit (1, 4, 1)/6.
        let mut expect = vec![0.0; nv];
        expect[u as usize] = mask[0];
        expect[v as usize] = mask[2];
        expect[w as usize] = mask[4];
        assert_eq!(row, expect);
        let mut lexp = vec![0.0; nv];
        lexp[u as usize] = knots[1];
        lexp[v as usize] = knots[2];
        lexp[w as usize] = knots[3];
        assert!(max_diff(&lrow, &lexp) < 1e-14);
        // Edge rule on the boundary edge v -> w: the odd coefficients (4, 4)/8.
        let h = mesh.find_halfedge(v as usize, w as usize).unwrap();
        let e = mesh.he_edge(h) as usize;
        assert!(mesh.is_boundary_edge(e));
        let erow = dense_row(&r.stencils, nv + e);
        let mut eexp = vec![0.0; nv];
        eexp[v as usize] = mask[1];
        eexp[w as usize] = mask[3];
        assert_eq!(erow, eexp);
    }
    assert_eq!(corners, 2);
    // The child's boundary polygon is the refined boundary polygon: one loop, twice as long.
    assert_eq!(r.mesh.boundary_loops().len(), 1);
    assert_eq!(r.mesh.boundary_loops()[0].len(), 2 * nb);
}

#[test]
fn loop_limit_stencils_are_affine_and_refinement_invariant() {
    let mut open = tri_grid(4, |x, y| 0.3 * x * y);
    jiggle(&mut open, 0.1);
    let mut ico_like = octahedron();
    jiggle(&mut ico_like, 0.05);
    let nets = [
        tetrahedron(),
        ico_like,
        open,
        fan(5, false),
        fan(7, false),
        fan(4, true),
        fan(6, true),
    ];
    for mesh in &nets {
        let lim = Loop.limit_stencils(mesh).unwrap();
        assert!(lim.max_affine_defect() < 1e-15);
        let r = Loop.refine(mesh).unwrap();
        let lim_child = Loop.limit_stencils(&r.mesh).unwrap();
        // Limit of child vertex v, expressed in parent points, equals the limit of parent v.
        let composed = lim_child.compose(&r.stencils);
        for v in 0..mesh.num_vertices() {
            let d = max_diff(&dense_row(&composed, v), &dense_row(&lim, v));
            assert!(d < 1e-12, "vertex {v}: {d}");
        }
        // Same for the positions after two steps.
        let r2 = Loop.refine(&r.mesh).unwrap();
        let p0 = lim.apply(mesh.positions());
        let p2 = Loop
            .limit_stencils(&r2.mesh)
            .unwrap()
            .apply(r2.mesh.positions());
        for v in 0..mesh.num_vertices() {
            for k in 0..3 {
                assert!((p0[v][k] - p2[v][k]).abs() < 1e-12);
            }
        }
    }
}

#[test]
fn loop_tangents_are_eigenvectors_and_normals_are_exact() {
    // Interior valence n: t(child) = (3/8 + cos(2 pi/n)/4) t(parent).
    for n in 3..=9 {
        let mesh = fan(n, false);
        let r = Loop.refine(&mesh).unwrap();
        let [p1, p2] = Loop.limit_tangent_stencils(&mesh).unwrap();
        let [c1, c2] = Loop.limit_tangent_stencils(&r.mesh).unwrap();
        let l = 0.375 + 0.25 * (2.0 * std::f64::consts::PI / n as f64).cos();
        for (c, p) in [(c1, p1), (c2, p2)] {
            let lhs = dense_row(&c.compose(&r.stencils), 0);
            let rhs: Vec<f64> = dense_row(&p, 0).iter().map(|x| l * x).collect();
            assert!(max_diff(&lhs, &rhs) < 1e-14, "n = {n}");
        }
    }
    // Boundary vertex with k faces: along 1/2, across 3/8 + cos(pi/k)/4.
    for k in 2..=6 {
        let mesh = fan(k, true);
        let r = Loop.refine(&mesh).unwrap();
        let [p1, p2] = Loop.limit_tangent_stencils(&mesh).unwrap();
        let [c1, c2] = Loop.limit_tangent_stencils(&r.mesh).unwrap();
        let across = 0.375 + 0.25 * (std::f64::consts::PI / k as f64).cos();
        for (c, p, l) in [(c1, p1, 0.5), (c2, p2, across)] {
            assert!(p.stencil(0).weight_sum().abs() < 1e-14);
            let lhs = dense_row(&c.compose(&r.stencils), 0);
            let rhs: Vec<f64> = dense_row(&p, 0).iter().map(|x| l * x).collect();
            assert!(max_diff(&lhs, &rhs) < 1e-14, "k = {k}");
        }
    }
    // Regular boundary (k = 3): (sqrt 3 / 4)(2 p1 + 2 p2 - 2 v - p0 - p3).
    let mesh = fan(3, true);
    let [_, t2] = Loop.limit_tangent_stencils(&mesh).unwrap();
    let s = 3f64.sqrt() / 4.0;
    let expect = [-2.0 * s, -s, 2.0 * s, 2.0 * s, -s];
    assert!(max_diff(&dense_row(&t2, 0), &expect) < 1e-15);

    // A planar net has the normal +z everywhere, boundary and corners included.
    let flat = tri_grid(4, |_, _| 0.0);
    for nrm in Loop.limit_normals(&flat).unwrap() {
        assert!(max_diff(&nrm, &[0.0, 0.0, 1.0]) < 1e-14, "{nrm:?}");
    }
    // On a regular net sampled from a quadratic, the limit surface is the quadratic plus a
    // constant over the same (x, y): its normals at regular vertices are the graph's normals.
    let f = |x: f64, y: f64| 0.1 * x * x - 0.2 * x * y + 0.15 * y * y + 0.3 * x;
    let m = 6;
    let mesh = tri_grid(m, f);
    let normals = Loop.limit_normals(&mesh).unwrap();
    let lim = Loop.limit_stencils(&mesh).unwrap().apply(mesh.positions());
    for v in 0..mesh.num_vertices() {
        if mesh.is_boundary_vertex(v) {
            continue;
        }
        let [x, y, _] = mesh.position(v);
        assert!((lim[v][0] - x).abs() < 1e-13 && (lim[v][1] - y).abs() < 1e-13);
        let (fx, fy) = (0.2 * x - 0.2 * y + 0.3, -0.2 * x + 0.3 * y);
        let len = (fx * fx + fy * fy + 1.0).sqrt();
        let expect = [-fx / len, -fy / len, 1.0 / len];
        assert!(max_diff(&normals[v], &expect) < 1e-13, "vertex {v}");
    }
}

#[test]
fn loop_topology_counts() {
    // (V, E, F) after one step: V + E, 2E + 3F, 4F.
    for (mesh, counts) in [
        (tetrahedron(), (10, 24, 16)),
        (octahedron(), (18, 48, 32)),
        (tri_grid(3, |_, _| 0.0), (49, 120, 72)),
    ] {
        let r = Loop.refine(&mesh).unwrap();
        let c = &r.mesh;
        assert_eq!((c.num_vertices(), c.num_edges(), c.num_faces()), counts);
        assert_eq!(euler(c), euler(&mesh));
        assert_eq!(c.boundary_loops().len(), mesh.boundary_loops().len());
        assert!(c.is_all_triangles());
        assert_valid(c);
        assert!(r.stencils.max_affine_defect() < 1e-15);
    }
    // Child faces keep the parent's orientation: the normal of every child triangle of a convex
    // closed net points outwards.
    let r = Loop.refine(&octahedron()).unwrap();
    for f in r.mesh.faces() {
        let p: Vec<[f64; 3]> = f.iter().map(|&v| r.mesh.position(v as usize)).collect();
        let n = fairsub::geom::cross(
            fairsub::geom::sub(p[1], p[0]),
            fairsub::geom::sub(p[2], p[0]),
        );
        assert!(fairsub::geom::dot(n, p[0]) > 0.0);
    }
}

#[test]
fn loop_rejects_non_triangles_naming_the_face() {
    let err = Loop.refine(&fairsub::gallery::unit_cube()).unwrap_err();
    let msg = err.to_string();
    assert!(matches!(
        err,
        fairsub::Error::UnsupportedFace { face: 0, .. }
    ));
    assert!(
        msg.contains("face 0 has 4 corners") && msg.contains("catmull-clark"),
        "{msg}"
    );
}

// ---------------------------------------------------------------------------------------------
// Doo-Sabin and DS^CC

fn prism(n: usize) -> PolyMesh {
    let mut pos = Vec::new();
    for z in [0.0, 1.0] {
        for i in 0..n {
            let t = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
            pos.push([t.cos(), t.sin(), z]);
        }
    }
    let mut faces: Vec<Vec<usize>> = vec![(0..n).rev().collect(), (n..2 * n).collect()];
    for i in 0..n {
        let j = (i + 1) % n;
        faces.push(vec![i, j, n + j, n + i]);
    }
    PolyMesh::new(pos, &faces).unwrap()
}

/// The centred uniform quadratic B-spline, support [-3/2, 3/2].
fn quad_bspline(x: f64) -> f64 {
    let a = x.abs();
    if a <= 0.5 {
        0.75 - a * a
    } else if a <= 1.5 {
        0.5 * (1.5 - a) * (1.5 - a)
    } else {
        0.0
    }
}

/// Child lattice index (0 ..= 2m + 1) of a coordinate of a child point of the flat quad grid of
/// size m: corner points sit at i + 1/4 and i + 3/4, boundary points on 0 and m.
fn child_index(c: f64, m: usize) -> usize {
    if c == 0.0 {
        0
    } else if c == m as f64 {
        2 * m + 1
    } else {
        (2.0 * c + 0.5).round() as usize
    }
}

/// Weight of parent lattice point b in child point a for bi-2 refinement (Chaikin mask
/// (1+z)^3/4 in each direction) of the net extended by a phantom copy of its boundary layer.
fn doubled_chaikin_weight(mask: &[f64], a: usize, b: usize, m: usize) -> f64 {
    let mut w = 0.0;
    for c in -1..=(m as i64 + 1) {
        if c.clamp(0, m as i64) as usize != b {
            continue;
        }
        let k = a as i64 - 2 * c + 1;
        if (0..mask.len() as i64).contains(&k) {
            w += mask[k as usize];
        }
    }
    w
}

fn dual_schemes() -> [(&'static str, &'static dyn Scheme); 2] {
    [("doo-sabin", &DooSabin), ("doo-sabin-cc", &DooSabinCc)]
}

#[test]
fn doo_sabin_regular_grid_is_bi2_refinement() {
    let mask = bspline_mask(3);
    assert_eq!(mask, vec![0.25, 0.75, 0.75, 0.25]);
    let m = 4;
    let mesh = fairsub::gallery::quad_grid(m, |_, _| 0.0);
    for (name, scheme) in dual_schemes() {
        let r = scheme.refine(&mesh).unwrap();
        assert_eq!(r.mesh.num_vertices(), (2 * m + 2) * (2 * m + 2));
        assert!(r.mesh.is_all_quads());
        let mut seen = vec![false; (2 * m + 2) * (2 * m + 2)];
        for c in 0..r.mesh.num_vertices() {
            let p = r.mesh.position(c);
            let (ai, aj) = (child_index(p[0], m), child_index(p[1], m));
            seen[aj * (2 * m + 2) + ai] = true;
            let mut expect = vec![0.0; mesh.num_vertices()];
            for bj in 0..=m {
                for bi in 0..=m {
                    expect[gid(m, bi, bj)] = doubled_chaikin_weight(&mask, ai, bi, m)
                        * doubled_chaikin_weight(&mask, aj, bj, m);
                }
            }
            assert_eq!(dense_row(&r.stencils, c), expect, "{name}, child {c}");
        }
        assert!(
            seen.iter().all(|&s| s),
            "{name}: child lattice covered once"
        );
        // Interior corner points carry the 9/16, 3/16, 3/16, 1/16 mask.
        let (i, w) = r.stencils.row(0);
        assert_eq!(i.len(), 4);
        let mut ws = w.to_vec();
        ws.sort_by(f64::total_cmp);
        assert_eq!(ws, [1.0 / 16.0, 3.0 / 16.0, 3.0 / 16.0, 9.0 / 16.0]);
    }
}

#[test]
fn doo_sabin_limit_is_the_bi2_spline_of_the_doubled_net() {
    let m = 4;
    let mesh = fairsub::gallery::quad_grid(m, |_, _| 0.0);
    // Bi-2 spline of the doubled net at (s, t), as a stencil over the parent points.
    let spline = |s: f64, t: f64| {
        let mut w = vec![0.0; mesh.num_vertices()];
        for cj in -1..=(m as i64 + 1) {
            for ci in -1..=(m as i64 + 1) {
                let b = gid(
                    m,
                    ci.clamp(0, m as i64) as usize,
                    cj.clamp(0, m as i64) as usize,
                );
                w[b] += quad_bspline(s - ci as f64) * quad_bspline(t - cj as f64);
            }
        }
        w
    };
    // Where a point's limit lies in the parameter plane of the parent: a point of lattice index
    // a out of 0 ..= top sits at a * scale + shift, except that the limits of boundary points
    // (a = 0 or a = top) lie on the boundary curve, at -1/2 or m + 1/2.
    let param = |a: usize, top: usize, scale: f64, shift: f64| {
        if a == 0 {
            -0.5
        } else if a == top {
            m as f64 + 0.5
        } else {
            a as f64 * scale + shift
        }
    };
    for (name, scheme) in dual_schemes() {
        // Parent vertices: interior ones at the integers.
        let lim = scheme.limit_stencils(&mesh).unwrap();
        assert!(lim.max_affine_defect() < 1e-15);
        for j in 0..=m {
            for i in 0..=m {
                let (s, t) = (param(i, m, 1.0, 0.0), param(j, m, 1.0, 0.0));
                let d = max_diff(&dense_row(&lim, gid(m, i, j)), &spline(s, t));
                assert!(d < 1e-15, "{name}: parent vertex ({i}, {j}): {d}");
            }
        }
        // Child vertices, expressed in parent points, at their parameters.
        let r = scheme.refine(&mesh).unwrap();
        let composed = scheme.limit_stencils(&r.mesh).unwrap().compose(&r.stencils);
        for c in 0..r.mesh.num_vertices() {
            let p = r.mesh.position(c);
            let (ai, aj) = (child_index(p[0], m), child_index(p[1], m));
            let top = 2 * m + 1;
            let (s, t) = (param(ai, top, 0.5, -0.25), param(aj, top, 0.5, -0.25));
            let d = max_diff(&dense_row(&composed, c), &spline(s, t));
            assert!(d < 1e-15, "{name}: child ({ai}, {aj}): {d}");
        }
    }
}

#[test]
fn doo_sabin_ngon_block_spectrum() {
    for n in 3..=10 {
        for (name, w, expect) in [
            (
                "doo-sabin",
                DooSabin::weights(n),
                (0..n)
                    .map(|k| match k {
                        0 => 1.0,
                        _ if k == 1 || k == n - 1 => 0.5,
                        _ => 0.25,
                    })
                    .collect::<Vec<f64>>(),
            ),
            (
                "doo-sabin-cc",
                DooSabinCc::weights(n),
                (0..n)
                    .map(|k| match k {
                        0 => 1.0,
                        _ => 0.5 + 0.25 * (2.0 * std::f64::consts::PI * k as f64 / n as f64).cos(),
                    })
                    .collect(),
            ),
        ] {
            // Eigenvalues of a circulant: the DFT of its first row.
            for (k, e) in expect.iter().enumerate() {
                let (mut re, mut im) = (0.0, 0.0);
                for (d, wd) in w.iter().enumerate() {
                    let t = 2.0 * std::f64::consts::PI * (d * k) as f64 / n as f64;
                    re += wd * t.cos();
                    im += wd * t.sin();
                }
                assert!(
                    (re - e).abs() < 1e-14 && im.abs() < 1e-14,
                    "{name} n={n} k={k}"
                );
            }
            // The block of a real refinement: the top n-gon of a prism.
            let mesh = prism(n);
            let scheme: &dyn Scheme = if name == "doo-sabin" {
                &DooSabin
            } else {
                &DooSabinCc
            };
            let r = scheme.refine(&mesh).unwrap();
            let top = mesh.face(1).to_vec();
            let h0 = mesh.face_halfedge(1) as usize;
            let mut block = nalgebra::DMatrix::<f64>::zeros(n, n);
            for i in 0..n {
                let row = dense_row(&r.stencils, h0 + i);
                for (j, &v) in top.iter().enumerate() {
                    block[(i, j)] = row[v as usize];
                    assert_eq!(row[v as usize], w[(j + n - i) % n]);
                }
                assert!((row.iter().sum::<f64>() - 1.0).abs() < 1e-15);
                assert!(
                    row.iter()
                        .enumerate()
                        .all(|(v, &x)| x == 0.0 || top.contains(&(v as u32)))
                );
            }
            let mut eig: Vec<f64> = block.symmetric_eigenvalues().iter().copied().collect();
            let mut exp = expect.clone();
            eig.sort_by(f64::total_cmp);
            exp.sort_by(f64::total_cmp);
            assert!(max_diff(&eig, &exp) < 1e-13, "{name} n={n}: {eig:?}");
        }
    }
}

#[test]
fn doo_sabin_cc_is_the_mean_of_vertex_centroid_and_edge_midpoints() {
    let mut mesh = prism(5);
    jiggle(&mut mesh, 0.2);
    let r = DooSabinCc.refine(&mesh).unwrap();
    let p = mesh.positions();
    for f in 0..mesh.num_faces() {
        let fv = mesh.face(f);
        let n = fv.len();
        let c = mesh.face_centroid(f);
        for i in 0..n {
            let (v, a, b) = (
                p[fv[i] as usize],
                p[fv[(i + n - 1) % n] as usize],
                p[fv[(i + 1) % n] as usize],
            );
            let q = r.mesh.position(mesh.face_halfedge(f) as usize + i);
            for k in 0..3 {
                let expect = (v[k] + c[k] + 0.5 * (v[k] + a[k]) + 0.5 * (v[k] + b[k])) / 4.0;
                assert!((q[k] - expect).abs() < 1e-14);
            }
        }
    }
}

#[test]
fn dual_topology_counts() {
    // (V, E, F) after one step.
    let nets: Vec<(PolyMesh, (usize, usize, usize))> = vec![
        (fairsub::gallery::unit_cube(), (24, 48, 26)),
        (tetrahedron(), (12, 24, 14)),
        (prism(5), (30, 60, 32)),
        (fairsub::gallery::quad_grid(3, |_, _| 0.0), (64, 112, 49)),
        // 54 corner points, 2 x 12 boundary points, 2 kept corners; 18 + 33 + 16 faces.
        (tri_grid(3, |_, _| 0.0), (80, 146, 67)),
    ];
    for (mesh, counts) in &nets {
        for (name, scheme) in dual_schemes() {
            let r = scheme.refine(mesh).unwrap();
            let c = &r.mesh;
            assert_eq!(
                (c.num_vertices(), c.num_edges(), c.num_faces()),
                *counts,
                "{name}"
            );
            assert_eq!(euler(c), euler(mesh));
            assert_eq!(c.boundary_loops().len(), mesh.boundary_loops().len());
            assert_valid(c);
            assert!(r.stencils.max_affine_defect() < 1e-15);
            // Every child vertex but the kept corners has valence 4 (3 on the boundary).
            for v in 0..c.num_vertices() {
                let expect = if !c.is_boundary_vertex(v) {
                    4
                } else if c.vertex_faces(v).len() == 1 {
                    2
                } else {
                    3
                };
                assert_eq!(c.valence(v), expect, "{name} child vertex {v}");
            }
        }
    }
    // Orientation: every child face of a convex closed net faces outwards.
    for mesh in [fairsub::gallery::unit_cube(), prism(7)] {
        let r = DooSabin.refine(&mesh).unwrap();
        let centre = fairsub::geom::centroid(mesh.positions().iter().copied());
        for f in 0..r.mesh.num_faces() {
            let fv = r.mesh.face(f);
            let mut n = [0.0; 3];
            for i in 0..fv.len() {
                let a = r.mesh.position(fv[i] as usize);
                let b = r.mesh.position(fv[(i + 1) % fv.len()] as usize);
                n = fairsub::geom::add(n, fairsub::geom::cross(a, b));
            }
            let out = fairsub::geom::sub(r.mesh.face_centroid(f), centre);
            assert!(fairsub::geom::dot(n, out) > 0.0, "child face {f}");
        }
    }
}

#[test]
fn doo_sabin_boundary_is_the_chaikin_curve_of_the_boundary_polygon() {
    let mut mesh = tri_grid(3, |x, y| (x - y).cos());
    jiggle(&mut mesh, 0.1);
    let nv = mesh.num_vertices();
    let bl = &mesh.boundary_loops()[0];
    // The boundary polygon with every corner doubled, as stencils over the parent points.
    let mut poly: Vec<usize> = Vec::new();
    for &v in bl {
        poly.push(v as usize);
        if mesh.valence(v as usize) == 2 {
            poly.push(v as usize);
        }
    }
    assert_eq!(poly.len(), bl.len() + 2);
    let np = poly.len();
    // The quadratic B-spline curve of that polygon at parameter x (P_t at x = t, cyclic).
    let curve = |x: f64| {
        let mut w = vec![0.0; nv];
        for t in -(np as i64)..2 * np as i64 {
            w[poly[t.rem_euclid(np as i64) as usize]] += quad_bspline(x - t as f64);
        }
        w
    };
    for (name, scheme) in dual_schemes() {
        let r = scheme.refine(&mesh).unwrap();
        let lim = scheme.limit_stencils(&mesh).unwrap();
        // Parent boundary vertices' limits lie on the curve at their parameter.
        for (t, &v) in poly.iter().enumerate() {
            let corner = mesh.valence(v) == 2;
            let x = if corner && poly[(t + 1) % np] == v {
                t as f64 + 0.5
            } else if corner {
                continue;
            } else {
                t as f64
            };
            assert!(max_diff(&dense_row(&lim, v), &curve(x)) < 1e-15, "{name}");
        }
        // Chaikin of the polygon: 3/4 P_t + 1/4 P_{t+1} at t + 1/4, 1/4 P_t + 3/4 P_{t+1} at
        // t + 3/4; a doubled corner's two coincident points are the one kept corner, at t + 1/2.
        let mut chaikin: Vec<(Vec<f64>, f64)> = Vec::new();
        for t in 0..np {
            let (a, b) = (poly[t], poly[(t + 1) % np]);
            if a == b {
                let mut w = vec![0.0; nv];
                w[a] = 1.0;
                chaikin.push((w, t as f64 + 0.5));
                continue;
            }
            for (wa, s) in [(0.75, 0.25), (0.25, 0.75)] {
                let mut w = vec![0.0; nv];
                w[a] += wa;
                w[b] += 1.0 - wa;
                chaikin.push((w, t as f64 + s));
            }
        }
        let child_loops = r.mesh.boundary_loops();
        assert_eq!(child_loops.len(), 1);
        let cl = &child_loops[0];
        assert_eq!(cl.len(), chaikin.len());
        let rows: Vec<Vec<f64>> = cl
            .iter()
            .map(|&c| dense_row(&r.stencils, c as usize))
            .collect();
        let shift = (0..cl.len())
            .find(|&s| rows[s] == chaikin[0].0)
            .expect("the child boundary starts somewhere on the Chaikin polygon");
        let composed = scheme.limit_stencils(&r.mesh).unwrap().compose(&r.stencils);
        for (k, (w, x)) in chaikin.iter().enumerate() {
            let c = cl[(k + shift) % cl.len()] as usize;
            assert_eq!(
                &rows[(k + shift) % cl.len()],
                w,
                "{name}: Chaikin point {k}"
            );
            // The child's limit there is the parent polygon's quadratic B-spline.
            let d = max_diff(&dense_row(&composed, c), &curve(*x));
            assert!(d < 1e-15, "{name}: limit at Chaikin point {k}: {d}");
        }
    }
}

#[test]
fn doo_sabin_faces_shrink_to_their_limit_points() {
    let mut open = tri_grid(3, |x, y| 0.2 * x * y);
    jiggle(&mut open, 0.1);
    let mut box_net = fairsub::gallery::unit_cube();
    jiggle(&mut box_net, 0.1);
    for mesh in [box_net, open, prism(6)] {
        for (name, scheme) in dual_schemes() {
            let face_lim = doo_sabin::face_limit_stencils(&mesh).apply(mesh.positions());
            let vert_lim = scheme
                .limit_stencils(&mesh)
                .unwrap()
                .apply(mesh.positions());
            // Track face f (index f at every level) and the V-face of every interior vertex v
            // (index F + E + v at level 1, then the same index as an F-face).
            let (nf, ne) = (mesh.num_faces(), mesh.num_edges());
            let mut tracked: Vec<(usize, [f64; 3])> = (0..nf).map(|f| (f, face_lim[f])).collect();
            for v in (0..mesh.num_vertices()).filter(|&v| !mesh.is_boundary_vertex(v)) {
                tracked.push((nf + ne + v, vert_lim[v]));
            }
            let mut m = mesh.clone();
            let mut spread = Vec::new();
            for _ in 1..=6 {
                m = scheme.refine(&m).unwrap().mesh;
                let mut worst: f64 = 0.0;
                for &(f, target) in &tracked {
                    // The centroid of a nested F-face is its limit point, exactly.
                    let d = max_diff(&m.face_centroid(f), &target);
                    assert!(d < 1e-12, "{name} face {f}: {d}");
                    for &q in m.face(f) {
                        worst = worst.max(fairsub::geom::dist(m.position(q as usize), target));
                    }
                }
                spread.push(worst);
            }
            // The faces contract at the rate of the largest subdominant eigenvalue of their
            // n-gon blocks: 1/2 for Doo-Sabin, 1/2 + cos(2 pi / n) / 4 for DS^CC.
            let rate = tracked
                .iter()
                .map(|&(f, _)| {
                    let n = m.face_size(f) as f64;
                    if name == "doo-sabin" {
                        0.5
                    } else {
                        0.5 + 0.25 * (2.0 * std::f64::consts::PI / n).cos()
                    }
                })
                .fold(0.0, f64::max);
            let last = spread[5] / spread[4];
            assert!((last - rate).abs() < 0.02, "{name}: {spread:?}");
            assert!(spread.windows(2).all(|w| w[1] < w[0]), "{name}: {spread:?}");
        }
    }
}

#[test]
fn every_child_net_is_valid_over_several_levels() {
    let mut nets = vec![
        fairsub::gallery::unit_cube(),
        tetrahedron(),
        prism(7),
        fairsub::gallery::quad_grid(2, |x, _| x),
        tri_grid(2, |_, y| y),
    ];
    jiggle(&mut nets[0], 0.05);
    // Single faces: every vertex is a corner.
    let ngon = |n: usize| {
        let pos = (0..n)
            .map(|i| {
                let t = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
                [t.cos(), t.sin(), 0.0]
            })
            .collect();
        PolyMesh::new(pos, &[(0..n).collect::<Vec<usize>>()]).unwrap()
    };
    nets.push(ngon(3));
    nets.push(ngon(5));
    for mesh in &nets {
        for (_, scheme) in dual_schemes() {
            let mut m = mesh.clone();
            for _ in 0..3 {
                m = scheme.refine(&m).unwrap().mesh;
                assert_valid(&m);
                assert_eq!(euler(&m), euler(mesh));
                assert_eq!(m.boundary_loops().len(), mesh.boundary_loops().len());
            }
        }
        if mesh.is_all_triangles() {
            let mut m = mesh.clone();
            for _ in 0..3 {
                m = Loop.refine(&m).unwrap().mesh;
                assert_valid(&m);
                assert_eq!(euler(&m), euler(mesh));
            }
        }
    }
}
