//! Patch mathematics checked against independent formulas: explicit Bernstein sums, finite
//! differences, surfaces with known curvature (plane, parabolic cylinder, paraboloid, graph
//! surfaces), a polar patch with a collapsed edge, splitting and degree raising identities.

use super::*;
use crate::geom::{dist, dot, normalize, sub};

struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64) / ((1u64 << 53) as f64) * 2.0 - 1.0
    }
}

fn random_patch(rng: &mut Lcg, du: usize, dv: usize) -> BezierPatch {
    BezierPatch::from_fn(du, dv, |_, _| [rng.next(), rng.next(), rng.next()])
}

fn binom(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// Explicit `sum b_ij B_i(u) B_j(v)` with `B_i^d(t) = C(d,i) (1-t)^(d-i) t^i`.
fn reference_eval(p: &BezierPatch, u: f64, v: f64) -> Point {
    let mut s = [0.0; 3];
    for i in 0..=p.deg_u {
        let bu = binom(p.deg_u, i) * (1.0 - u).powi((p.deg_u - i) as i32) * u.powi(i as i32);
        for j in 0..=p.deg_v {
            let bv = binom(p.deg_v, j) * (1.0 - v).powi((p.deg_v - j) as i32) * v.powi(j as i32);
            s = crate::geom::axpy(s, bu * bv, p.cp(i, j));
        }
    }
    s
}

#[crate::unit::test]
fn eval_matches_explicit_bernstein_sum() {
    let mut rng = Lcg(1);
    for (du, dv) in [(0, 0), (1, 3), (3, 2), (4, 4), (8, 5), (20, 3)] {
        let p = random_patch(&mut rng, du, dv);
        for k in 0..=7 {
            for l in 0..=7 {
                let (u, v) = (k as f64 / 7.0, l as f64 / 7.0);
                let e = dist(p.eval(u, v), reference_eval(&p, u, v));
                assert!(e < 1e-12, "({du},{dv}) at ({u},{v}): {e:e}");
                assert!(dist(p.derivatives(u, v).p, p.eval(u, v)) < 1e-12);
            }
        }
    }
}

#[crate::unit::test]
fn derivatives_match_derivative_nets_and_finite_differences() {
    let mut rng = Lcg(2);
    for (du, dv) in [(3, 3), (2, 4), (1, 1), (5, 2), (17, 2)] {
        let p = random_patch(&mut rng, du, dv);
        // derivative nets: d/du has coefficients du (b[i+1][j] - b[i][j])
        let pu = p.map_u_curves(curve::hodograph);
        let pv = p.map_v_curves(curve::hodograph);
        let puu = pu.map_u_curves(curve::hodograph);
        let puv = pu.map_v_curves(curve::hodograph);
        let pvv = pv.map_v_curves(curve::hodograph);
        for (u, v) in [(0.0, 0.0), (0.3, 0.8), (1.0, 0.5), (0.5, 1.0), (0.77, 0.01)] {
            let d = p.derivatives(u, v);
            let s = 1.0 + crate::geom::norm(d.duu) + crate::geom::norm(d.dvv);
            assert!(dist(d.du, pu.eval(u, v)) < 1e-12 * s);
            assert!(dist(d.dv, pv.eval(u, v)) < 1e-12 * s);
            assert!(dist(d.duu, puu.eval(u, v)) < 1e-11 * s);
            assert!(dist(d.duv, puv.eval(u, v)) < 1e-11 * s);
            assert!(dist(d.dvv, pvv.eval(u, v)) < 1e-11 * s);
            // central differences of the value
            let h = 1e-5;
            let fd = crate::geom::scale(sub(p.eval(u + h, v), p.eval(u - h, v)), 0.5 / h);
            assert!(dist(d.du, fd) < 1e-6 * s, "{:?} {:?}", d.du, fd);
            let fd = crate::geom::scale(sub(p.eval(u, v + h), p.eval(u, v - h)), 0.5 / h);
            assert!(dist(d.dv, fd) < 1e-6 * s);
        }
    }
}

#[crate::unit::test]
fn curvature_of_plane_cylinder_paraboloid() {
    // plane, tilted: everything zero
    let plane = BezierPatch::from_fn(3, 2, |i, j| {
        let (x, y) = (i as f64 / 3.0, j as f64 / 2.0);
        [x, y, 0.3 * x - 0.2 * y + 1.0]
    });
    let c = plane.curvatures(0.4, 0.7);
    assert!(c.gauss.abs() < 1e-14 && c.mean.abs() < 1e-14 && c.k1.abs() < 1e-14);

    // parabolic cylinder z = x^2 / (2r), x = 2u - 1, y = v: K = 0 everywhere; at x = 0 the
    // curvature across is exactly 1/r, so |H| = 1/(2r); it bends toward +z = du x dv, so > 0.
    let r = 2.5;
    let cyl = BezierPatch::from_fn(2, 1, |i, j| {
        // quadratic x(u) = 2u - 1 has coefficients -1, 0, 1; z = x^2/(2r) has 1/(2r), -1/(2r), 1/(2r)
        let x = [-1.0, 0.0, 1.0][i];
        let z = [1.0, -1.0, 1.0][i] / (2.0 * r);
        [x, j as f64, z]
    });
    assert!(dist(cyl.eval(0.75, 0.3), [0.5, 0.3, 0.25 / (2.0 * r)]) < 1e-15);
    let c = cyl.curvatures(0.5, 0.3);
    assert!(c.gauss.abs() < 1e-14, "{c:?}");
    assert!((c.mean - 1.0 / (2.0 * r)).abs() < 1e-14, "{c:?}");
    assert!((c.k1 - 1.0 / r).abs() < 1e-14 && c.k2.abs() < 1e-14);
    for (u, v) in [(0.1, 0.2), (0.9, 0.9)] {
        assert!(cyl.curvatures(u, v).gauss.abs() < 1e-14);
    }

    // dome z = -(x^2 + y^2)/(2r) with normal +z (outward): a sphere-like cap. At the apex
    // k1 = k2 = H = -1/r and K = 1/r^2 (negative: bends away from the normal).
    let dome = BezierPatch::from_fn(2, 2, |i, j| {
        let x = [-1.0, 0.0, 1.0][i];
        let y = [-1.0, 0.0, 1.0][j];
        let zx = [1.0, -1.0, 1.0][i];
        let zy = [1.0, -1.0, 1.0][j];
        [x, y, -(zx + zy) / (2.0 * r)]
    });
    assert!(dot(dome.normal(0.5, 0.5), [0.0, 0.0, 1.0]) > 1.0 - 1e-15);
    let c = dome.curvatures(0.5, 0.5);
    assert!((c.gauss - 1.0 / (r * r)).abs() < 1e-14, "{c:?}");
    assert!((c.mean + 1.0 / r).abs() < 1e-14 && (c.k1 + 1.0 / r).abs() < 1e-13);
    assert!((c.k2 + 1.0 / r).abs() < 1e-13);
    // the same surface with u reversed has the inward normal and opposite H, same K
    let c2 = dome.reversed_u().curvatures(0.5, 0.5);
    assert!((c2.mean - 1.0 / r).abs() < 1e-14 && (c2.gauss - c.gauss).abs() < 1e-14);
}

#[crate::unit::test]
fn curvature_matches_graph_formulas() {
    // height field z = f(x, y) with x = u, y = v exactly (linear precision in x, y)
    let mut rng = Lcg(4);
    let p = BezierPatch::from_fn(3, 3, |i, j| {
        [i as f64 / 3.0, j as f64 / 3.0, 0.4 * rng.next()]
    });
    for (u, v) in [(0.2, 0.3), (0.5, 0.5), (0.9, 0.1), (0.0, 1.0)] {
        let d = p.derivatives(u, v);
        let (fx, fy, fxx, fxy, fyy) = (d.du[2], d.dv[2], d.duu[2], d.duv[2], d.dvv[2]);
        let w = 1.0 + fx * fx + fy * fy;
        let k = (fxx * fyy - fxy * fxy) / (w * w);
        let h = ((1.0 + fy * fy) * fxx - 2.0 * fx * fy * fxy + (1.0 + fx * fx) * fyy)
            / (2.0 * w.powf(1.5));
        let c = p.curvatures(u, v);
        assert!(
            (c.gauss - k).abs() < 1e-12 && (c.mean - h).abs() < 1e-12,
            "{c:?} {k} {h}"
        );
        assert!((c.k1 * c.k2 - k).abs() < 1e-12 && c.k1 >= c.k2);
    }
}

#[crate::unit::test]
fn approximate_circular_cylinder() {
    // quarter circle of radius r as a cubic (kappa = 0.5523), extruded: K = 0 and |H| ~ 1/(2r)
    let r = 3.0;
    let k = 0.552_284_749_8 * r;
    let arc = [[r, 0.0], [r, k], [k, r], [0.0, r]];
    let p = BezierPatch::from_fn(3, 1, |i, j| [arc[i][0], arc[i][1], 2.0 * j as f64]);
    for u in [0.0, 0.25, 0.5, 0.75, 1.0] {
        let c = p.curvatures(u, 0.5);
        assert!(c.gauss.abs() < 1e-14);
        // the cubic arc's curvature deviates from 1/r by at most about 2.5%
        assert!((c.mean.abs() * 2.0 * r - 1.0).abs() < 0.025, "{c:?}");
        // du x dv points away from the axis here: the cylinder bends away, H < 0
        assert!(c.mean < 0.0);
    }
}

/// A polar patch: `p(u, v) = (u c(v), -u^2)` with `c` a quadratic arc; the side `U0` collapses
/// to the apex, where the tangent plane is `z = 0`.
fn polar_patch() -> BezierPatch {
    let c = [[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    // x, y linear in u times c(v); z = -u^2 has u-coefficients 0, 0, -1
    BezierPatch::from_fn(2, 2, |i, j| {
        let s = i as f64 / 2.0;
        [s * c[j][0], s * c[j][1], [0.0, 0.0, -1.0][i]]
    })
}

#[crate::unit::test]
fn normal_at_collapsed_edge_is_the_limit() {
    let p = polar_patch();
    assert!(p.is_collapsed(Side::U0, 0.0) && !p.is_collapsed(Side::U1, 0.0));
    assert!(!p.derivatives(0.0, 0.3).is_regular());
    for v in [0.0, 0.3, 0.5, 1.0] {
        let n = p.normal(0.0, v);
        assert!(dist(n, [0.0, 0.0, 1.0]) < 1e-14, "v = {v}: {n:?}");
        // continuity: agrees with the regular normal just inside
        assert!(dist(n, p.normal(1e-7, v)) < 1e-6);
        // curvature falls back to a point just inside and stays finite
        assert!(p.curvatures(0.0, v).gauss.is_finite());
    }
    // a regular point is unaffected by the fallback
    let d = p.derivatives(0.6, 0.4);
    let n = normalize(cross(d.du, d.dv));
    assert_eq!(p.normal(0.6, 0.4), p.normal_from(0.6, 0.4, &d));
    assert!(dist(p.normal(0.6, 0.4), n) < 1e-15);

    // both partials vanish at the corner: (u^2, v^2, uv); limit along the diagonal
    let q = BezierPatch::from_fn(2, 2, |i, j| {
        let x = [0.0, 0.0, 1.0][i];
        let y = [0.0, 0.0, 1.0][j];
        let z = (i as f64 / 2.0) * (j as f64 / 2.0);
        [x, y, z]
    });
    let d = q.derivatives(0.0, 0.0);
    assert_eq!((d.du, d.dv), ([0.0; 3], [0.0; 3]));
    let n = q.normal(0.0, 0.0);
    let expect = normalize([-2.0, -2.0, 4.0]);
    assert!(dist(n, expect) < 1e-14, "{n:?}");
    assert!(dist(n, q.normal(1e-6, 1e-6)) < 1e-6);

    // a patch collapsed to a point has no normal and no curvature
    let point = BezierPatch::from_fn(2, 2, |_, _| [1.0, 2.0, 3.0]);
    assert_eq!(point.normal(0.5, 0.5), [0.0; 3]);
    assert!(point.curvatures(0.5, 0.5).mean.is_nan());
}

#[crate::unit::test]
fn split_subpatch_raise_transpose_reverse() {
    let mut rng = Lcg(9);
    let p = random_patch(&mut rng, 3, 4);
    let (a, b) = p.split_u(0.3);
    let (c, e) = p.split_v(0.6);
    let s = p.subpatch(0.2, 0.9, 0.7, 0.1);
    let r = p.raised_to(5, 6).map(|r| (r.deg_u, r.deg_v, r));
    let Some((5, 6, r)) = r else {
        panic!("raising failed")
    };
    assert!(p.raised_to(2, 4).is_none());
    let t = p.transposed();
    let ru = p.reversed_u();
    let rv = p.reversed_v();
    for k in 0..=6 {
        for l in 0..=6 {
            let (x, y) = (k as f64 / 6.0, l as f64 / 6.0);
            let tol = 1e-13;
            assert!(dist(a.eval(x, y), p.eval(0.3 * x, y)) < tol);
            assert!(dist(b.eval(x, y), p.eval(0.3 + 0.7 * x, y)) < tol);
            assert!(dist(c.eval(x, y), p.eval(x, 0.6 * y)) < tol);
            assert!(dist(e.eval(x, y), p.eval(x, 0.6 + 0.4 * y)) < tol);
            assert!(dist(s.eval(x, y), p.eval(0.2 + 0.7 * x, 0.7 - 0.6 * y)) < tol);
            assert!(dist(r.eval(x, y), p.eval(x, y)) < tol);
            assert!(dist(t.eval(y, x), p.eval(x, y)) < tol);
            assert!(dist(ru.eval(1.0 - x, y), p.eval(x, y)) < tol);
            assert!(dist(rv.eval(x, 1.0 - y), p.eval(x, y)) < tol);
        }
    }
    // transposing flips the normal
    assert!(dist(t.normal(0.4, 0.3), scale(p.normal(0.3, 0.4), -1.0)) < 1e-12);
    assert_eq!(p.raise_u().deg_u, 4);
    assert_eq!(p.raise_v().deg_v, 5);
}

#[crate::unit::test]
fn boundaries_corners_bbox_map() {
    let mut rng = Lcg(12);
    let p = random_patch(&mut rng, 2, 3);
    for side in Side::ALL {
        let b = p.boundary(side);
        for k in 0..=5 {
            let t = k as f64 / 5.0;
            let [u, v] = side.domain_point(t);
            assert!(dist(curve::eval(&b, t), p.eval(u, v)) < 1e-14, "{side:?}");
        }
        assert_eq!(Side::ALL[side.index()], side);
        assert_eq!(side.opposite().opposite(), side);
    }
    assert_eq!(p.boundary(Side::U0).len(), 4);
    assert_eq!(p.boundary(Side::V1).len(), 3);
    assert_eq!(p.corner(false, false), p.eval(0.0, 0.0));
    assert_eq!(p.corner(true, false), p.cp(2, 0));
    assert_eq!(p.corner(false, true), p.cp(0, 3));
    assert_eq!(p.corner(true, true), p.eval(1.0, 1.0));
    let (lo, hi) = p.control_bbox();
    for k in 0..=10 {
        let q = p.eval(k as f64 / 10.0, 1.0 - k as f64 / 10.0);
        assert!((0..3).all(|c| lo[c] <= q[c] && q[c] <= hi[c]));
    }
    let m = p.map_points(|q| [q[0] + 1.0, 2.0 * q[1], q[2]]);
    let (q0, q1) = (p.eval(0.3, 0.6), m.eval(0.3, 0.6));
    assert!(dist(q1, [q0[0] + 1.0, 2.0 * q0[1], q0[2]]) < 1e-14);
}
