//! Unit tests of Loop's box-spline triangles, the quartic table and the Hermite fill.

use super::fill::{Jets, limit_and_derivative};
use super::*;
use crate::schemes::loop_subdivision::limit::tangent_mask;
use crate::schemes::{Loop, Scheme};

#[crate::unit::test]
fn table_is_affine_and_symmetric() {
    for (m, w) in BOX_SPLINE_BEZIER {
        assert_eq!(m.iter().sum::<usize>(), 4);
        assert_eq!(w.iter().sum::<u32>(), 24);
        assert_eq!(BOX_SPLINE_BEZIER[tri_index(m[0], m[1], m[2])].0, m);
    }
    // Rotation P0 -> P1 -> P2 maps slots [P0, P1, P2, A01, A12, A20, X0a, X0b, X1a, X1b,
    // X2a, X2b] to [P1, P2, P0, A12, A20, A01, X1a, X1b, X2a, X2b, X0a, X0b].
    let rot = [1, 2, 0, 4, 5, 3, 8, 9, 10, 11, 6, 7];
    for (m, w) in BOX_SPLINE_BEZIER {
        let r = BOX_SPLINE_BEZIER[tri_index(m[2], m[0], m[1])].1;
        for s in 0..12 {
            assert_eq!(w[s], r[rot[s]], "{m:?} slot {s}");
        }
    }
    // Corner coefficient = Loop's valence-6 limit mask (1/2, 1/12 each neighbour).
    assert_eq!(
        BOX_SPLINE_BEZIER[0].1,
        [12, 2, 2, 2, 0, 2, 2, 2, 0, 0, 0, 0]
    );
}

/// The derivation of [`BOX_SPLINE_BEZIER`], repeated: on a planar three-direction lattice
/// (x, y = lattice coordinates, which Loop's rules reproduce) put height 1 on one of the 12
/// control points of a middle triangle, take Loop limit heights at the 15 degree-4 lattice
/// points of the triangle after two steps, and solve the Bernstein collocation system.
#[crate::unit::test]
fn table_is_loops_limit_interpolant() {
    let n = 6;
    let id = |i: usize, j: usize| j * (n + 1) + i;
    let mut pos = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            pos.push([i as f64, j as f64, 0.0]);
        }
    }
    let mut faces = Vec::new();
    for j in 0..n {
        for i in 0..n {
            faces.push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            faces.push(vec![id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    let m = PolyMesh::new(pos, &faces).unwrap();
    // Triangle (2,2), (3,2), (3,3).
    let f = 2 * (2 * n) + 2 * 2;
    assert_eq!(
        m.face(f),
        [id(2, 2) as u32, id(3, 2) as u32, id(3, 3) as u32]
    );
    let net = box_spline_net(&super::Level::input(&m, None), f).unwrap();
    let fine = Loop.refine(&Loop.refine(&m).unwrap().mesh).unwrap().mesh;
    let (s1, s2) = (
        Loop.refine(&m).unwrap().stencils,
        Loop.refine(&Loop.refine(&m).unwrap().mesh)
            .unwrap()
            .stencils,
    );
    let lim = Loop.limit_stencils(&fine).unwrap();
    let fact = [1.0, 1.0, 2.0, 6.0, 24.0];
    let bary = |a: usize, b: usize, c: usize| [a as f64 / 4.0, b as f64 / 4.0, c as f64 / 4.0];
    let bern = nalgebra::DMatrix::from_fn(15, 15, |r, k| {
        let l = {
            let m = BOX_SPLINE_BEZIER[r].0;
            bary(m[0], m[1], m[2])
        };
        let e = BOX_SPLINE_BEZIER[k].0;
        24.0 / (fact[e[0]] * fact[e[1]] * fact[e[2]])
            * l[0].powi(e[0] as i32)
            * l[1].powi(e[1] as i32)
            * l[2].powi(e[2] as i32)
    });
    let lu = bern.lu();
    for (slot, st) in net.iter().enumerate() {
        let v = st.entries()[0].0 as usize;
        let mut data = vec![[0.0f64; 1]; m.num_vertices()];
        data[v] = [1.0];
        let limits = lim.apply(&s2.apply(&s1.apply(&data)));
        // Level-2 vertices sit on the quarter lattice: find each lattice point by position.
        let values = nalgebra::DVector::from_fn(15, |r, _| {
            let [a, b, c] = BOX_SPLINE_BEZIER[r].0;
            let [l0, l1, l2] = bary(a, b, c);
            let q = [2.0 * l0 + 3.0 * (l1 + l2), 2.0 * (l0 + l1) + 3.0 * l2];
            let k = fine
                .positions()
                .iter()
                .position(|p| (p[0] - q[0]).abs() + (p[1] - q[1]).abs() < 1e-12)
                .unwrap();
            limits[k][0]
        });
        let coef = lu.solve(&values).unwrap();
        for (r, (_, w)) in BOX_SPLINE_BEZIER.iter().enumerate() {
            assert!(
                (coef[r] * 24.0 - w[slot] as f64).abs() < 1e-12,
                "slot {slot} coefficient {r}: {} vs {}",
                coef[r] * 24.0,
                w[slot]
            );
        }
    }
}

#[crate::unit::test]
fn tensor_form_equals_triangle() {
    let tri: [Point; 15] = std::array::from_fn(|k| {
        let x = k as f64;
        [x.sin(), (1.3 * x).cos(), 0.1 * x * x]
    });
    let p = triangle_to_tensor(&tri);
    for (u, v) in [(0.0, 0.0), (0.3, 0.2), (1.0, 0.5), (0.7, 0.9), (0.5, 1.0)] {
        let (s, t) = (u * (1.0 - v), v);
        let q = eval_triangle(&tri, [1.0 - s - t, s, t]);
        assert!(geom::dist(p.eval(u, v), q) < 1e-14);
    }
}

/// On the open triangle grid every regular triangle (boundary ones included) is a box-spline
/// piece: its corners are Loop limit points, its half-lattice points limit points of the
/// refined net and its quarter-lattice points those of the twice refined net.
#[crate::unit::test]
fn box_spline_matches_loop_limits() {
    let m = crate::mesh::nets::tri_grid();
    let c = loop_complex(
        &m,
        ComplexOptions {
            rings: 0,
            fill: false,
        },
        |_| {},
    )
    .unwrap();
    let fine = Loop.refine(&m).unwrap().mesh;
    let lim0 = Loop.limit_stencils(&m).unwrap().apply(m.positions());
    let lim1 = Loop.limit_stencils(&fine).unwrap().apply(fine.positions());
    let finer = Loop.refine(&fine).unwrap().mesh;
    let lim2 = Loop
        .limit_stencils(&finer)
        .unwrap()
        .apply(finer.positions());
    assert!(!c.is_empty());
    for p in &c.patches {
        let samples = [
            (0.0, 0.0, &lim0),
            (0.5, 0.0, &lim1),
            (1.0, 0.5, &lim1),
            (0.0, 0.5, &lim1),
            (1.0 / 3.0, 0.25, &lim2),
            (0.5, 0.5, &lim2),
        ];
        for (u, v, set) in samples {
            let q = p.eval(u, v);
            let best = set
                .iter()
                .map(|l| geom::dist(*l, q))
                .fold(f64::INFINITY, f64::min);
            assert!(best < 1e-13, "({u}, {v}): {best}");
        }
    }
}

/// Above `fill::FOURIER_ABOVE` the fill's edge derivatives at an interior vertex come from the
/// fan's mode-1 sums: equal to the tangent mask's sum to rounding.
#[crate::unit::test]
fn fourier_fan_derivative_equals_the_mask() {
    for n in [33usize, 40, 101] {
        // A wavy fan of n triangles around vertex 0, closed by an outer ring of triangles.
        let mut pts = vec![[0.0, 0.0, 0.1]];
        for i in 0..n {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            pts.push([t.cos(), t.sin(), 0.2 * (3.0 * t).sin()]);
        }
        for i in 0..n {
            let t = std::f64::consts::TAU * (i as f64 + 0.5) / n as f64;
            pts.push([2.0 * t.cos(), 2.0 * t.sin(), 0.0]);
        }
        let mut faces = Vec::new();
        for i in 0..n {
            let (a, b) = (1 + i, 1 + (i + 1) % n);
            faces.push(vec![0, a, b]);
            faces.push(vec![a, 1 + n + i, b]);
        }
        let m = PolyMesh::new(pts, &faces).unwrap();
        let level = super::Level::input(&m, None);
        let mut jets = Jets::new(&level);
        for b in [1usize, 2, n / 2, n] {
            let (_, d) = limit_and_derivative(&m, &mut jets, 0, b);
            let hs = m.outgoing_halfedges(0);
            let j = hs.iter().position(|&h| m.he_to(h) as usize == b).unwrap();
            let mut want = [0.0; 3];
            for (h, (c, _)) in hs.iter().zip(tangent_mask(n, j)) {
                want = geom::axpy(want, (2.0 / n as f64) * c, m.position(m.he_to(*h) as usize));
            }
            for k in 0..3 {
                assert!(
                    (d[k] - want[k]).abs() < 1e-14,
                    "n {n}, b {b}: {d:?} {want:?}"
                );
            }
        }
    }
}
