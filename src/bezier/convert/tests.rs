//! Conversions checked against an independent B-spline evaluation (Cox-de Boor recursion on
//! explicit knot vectors), for continuity between neighbouring patches, and against the EG
//! paper's formula (6).

use super::*;
use crate::geom::{dist, sub};

/// Small deterministic generator (no external crates in tests).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64) / ((1u64 << 53) as f64) * 2.0 - 1.0
    }
    fn point(&mut self) -> Point {
        [self.next(), self.next(), self.next()]
    }
}

/// Cox-de Boor B-spline basis `N_{i,p}(t)` on `knots` (half-open intervals, 0/0 = 0).
fn basis(i: usize, p: usize, t: f64, knots: &[f64]) -> f64 {
    if p == 0 {
        return if knots[i] <= t && t < knots[i + 1] {
            1.0
        } else {
            0.0
        };
    }
    let mut r = 0.0;
    let d1 = knots[i + p] - knots[i];
    if d1 > 0.0 {
        r += (t - knots[i]) / d1 * basis(i, p - 1, t, knots);
    }
    let d2 = knots[i + p + 1] - knots[i + 1];
    if d2 > 0.0 {
        r += (knots[i + p + 1] - t) / d2 * basis(i + 1, p - 1, t, knots);
    }
    r
}

/// Tensor-product B-spline surface `sum N_k(u) N_l(v) d[k][l]` (same knots in u and v).
fn spline_surface(p: usize, knots: &[f64], net: &[Vec<Point>], u: f64, v: f64) -> Point {
    let mut s = [0.0; 3];
    for (k, row) in net.iter().enumerate() {
        let nu = basis(k, p, u, knots);
        if nu == 0.0 {
            continue;
        }
        for (l, d) in row.iter().enumerate() {
            let w = nu * basis(l, p, v, knots);
            for c in 0..3 {
                s[c] += w * d[c];
            }
        }
    }
    s
}

/// Knot vectors under which control points `0..=p` influence the parameter interval `[0, 1]`:
/// uniform integers for degrees 2 and 3; every knot double for the quartic EG spline (segment
/// `[0, 1]` between the double knots 0 and 1; `d2` has blossom arguments `(0, 0, 1, 1)`).
fn knots_for(p: usize) -> Vec<f64> {
    match p {
        2 => (0..6).map(|i| i as f64 - 2.0).collect(),
        3 => (0..8).map(|i| i as f64 - 3.0).collect(),
        _ => vec![-2.0, -1.0, -1.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0],
    }
}

fn random_net(rng: &mut Lcg, n: usize) -> Vec<Vec<Point>> {
    (0..n)
        .map(|_| (0..n).map(|_| rng.point()).collect())
        .collect()
}

fn sub_net<const N: usize>(net: &[Vec<Point>], a: usize, b: usize) -> [[Point; N]; N] {
    let mut s = [[[0.0; 3]; N]; N];
    for k in 0..N {
        for l in 0..N {
            s[k][l] = net[a + k][b + l];
        }
    }
    s
}

fn patch_from(p: usize, net: &[Vec<Point>], a: usize, b: usize) -> BezierPatch {
    match p {
        2 => biquadratic_bspline_to_bezier(&sub_net::<3>(net, a, b)),
        3 => bicubic_bspline_to_bezier(&sub_net::<4>(net, a, b)),
        _ => biquartic_c2_to_bezier(&sub_net::<5>(net, a, b)),
    }
}

#[crate::unit::test]
fn patches_equal_independent_bspline_evaluation() {
    let mut rng = Lcg(7);
    for p in [2usize, 3, 4] {
        let net = random_net(&mut rng, p + 1);
        let knots = knots_for(p);
        let patch = patch_from(p, &net, 0, 0);
        assert_eq!((patch.deg_u, patch.deg_v), (p, p));
        let mut worst: f64 = 0.0;
        for a in 0..=16 {
            for b in 0..=16 {
                // stay inside the half-open interval [0, 1)
                let (u, v) = (a as f64 / 16.0 * 0.999_999, b as f64 / 16.0 * 0.999_999);
                let e = dist(patch.eval(u, v), spline_surface(p, &knots, &net, u, v));
                worst = worst.max(e);
            }
        }
        assert!(worst < 1e-14, "degree {p}: deviation {worst:e}");
    }
}

#[crate::unit::test]
fn curve_conversions_equal_independent_evaluation() {
    let mut rng = Lcg(3);
    let d: Vec<Point> = (0..5).map(|_| rng.point()).collect();
    let c3 = cubic_bspline_to_bezier(&[d[0], d[1], d[2], d[3]]);
    let c2 = quadratic_bspline_to_bezier(&[d[0], d[1], d[2]]);
    let c4 = quartic_c2_to_bezier(&[d[0], d[1], d[2], d[3], d[4]]);
    for k in 0..20 {
        let t = k as f64 / 20.0;
        for (p, cps) in [(2usize, &c2[..]), (3, &c3[..]), (4, &c4[..])] {
            let knots = knots_for(p);
            let mut s = [0.0; 3];
            for (i, q) in d.iter().take(p + 1).enumerate() {
                let w = basis(i, p, t, &knots);
                for c in 0..3 {
                    s[c] += w * q[c];
                }
            }
            assert!(dist(crate::bezier::curve::eval(cps, t), s) < 1e-14);
        }
    }
    // the printed formulas (5) for the quartic
    let b0 = [0, 1, 2].map(|c| (d[0][c] + 2.0 * d[1][c] + d[2][c]) / 4.0);
    let b3 = [0, 1, 2].map(|c| (d[2][c] + d[3][c]) / 2.0);
    assert!(dist(c4[0], b0) < 1e-15 && dist(c4[3], b3) < 1e-15 && c4[2] == d[2]);
}

/// Largest jump of position, first and second u-derivatives (all mixed ones included) across
/// the boundary `u = 1` of `a` / `u = 0` of `b`, and likewise in `v`.
fn jumps(a: &BezierPatch, b: &BezierPatch, along_u: bool) -> [f64; 3] {
    let mut j = [0.0f64; 3];
    for k in 0..=10 {
        let t = k as f64 / 10.0;
        let (da, db) = if along_u {
            (a.derivatives(1.0, t), b.derivatives(0.0, t))
        } else {
            (a.derivatives(t, 1.0), b.derivatives(t, 0.0))
        };
        let n = |x: Point, y: Point| crate::geom::norm(sub(x, y));
        j[0] = j[0].max(n(da.p, db.p));
        j[1] = j[1].max(n(da.du, db.du)).max(n(da.dv, db.dv));
        j[2] = j[2]
            .max(n(da.duu, db.duu))
            .max(n(da.duv, db.duv))
            .max(n(da.dvv, db.dvv));
    }
    j
}

#[crate::unit::test]
fn neighbouring_patches_join_with_the_spline_continuity() {
    let mut rng = Lcg(11);
    // (degree, node shift between neighbouring patches, expected continuity order)
    for (p, shift, order) in [(3usize, 1usize, 2usize), (2, 1, 1), (4, 2, 2)] {
        let net = random_net(&mut rng, p + 1 + 2 * shift);
        let base = patch_from(p, &net, 0, 0);
        let right = patch_from(p, &net, shift, 0);
        let up = patch_from(p, &net, 0, shift);
        for (other, along_u) in [(&right, true), (&up, false)] {
            let j = jumps(&base, other, along_u);
            for (k, &jk) in j.iter().enumerate().take(order + 1) {
                assert!(jk < 1e-12, "degree {p}: order {k} jump {jk:e}");
            }
            if order < 2 {
                // bi-2 splines are only C^1: the second derivatives do jump
                assert!(
                    j[2] > 1e-3,
                    "degree {p}: second derivatives unexpectedly continuous"
                );
            }
        }
    }
}

#[crate::unit::test]
fn stencils_and_point_conversions_agree() {
    let mut rng = Lcg(5);
    let net = random_net(&mut rng, 5);
    let flat: Vec<Point> = net.iter().flatten().copied().collect();
    let idx: [[usize; 5]; 5] = std::array::from_fn(|k| std::array::from_fn(|l| k * 5 + l));
    let patch = biquartic_c2_to_bezier(&sub_net::<5>(&net, 0, 0));
    let st = biquartic_c2_stencils(&idx);
    assert_eq!(st.len(), 25);
    for (s, b) in st.iter().zip(&patch.cps) {
        assert_eq!(s.apply(&flat), *b);
        assert!((s.weight_sum() - 1.0).abs() < 1e-15);
    }
    let idx4: [[usize; 4]; 4] = std::array::from_fn(|k| std::array::from_fn(|l| k * 5 + l));
    let p3 = bicubic_bspline_to_bezier(&sub_net::<4>(&net, 0, 0));
    for (s, b) in bicubic_bspline_stencils(&idx4).iter().zip(&p3.cps) {
        assert!(dist(s.apply(&flat), *b) < 1e-15);
    }
    // corner of a bicubic patch: the limit point (d00 + 4 d01 + ... )/36 mask
    let c = bicubic_bspline_stencils(&idx4)[0].clone();
    let w11 = c.entries().iter().find(|e| e.0 == 6).map(|e| e.1);
    assert_eq!(w11, Some(16.0 / 36.0));
    let idx3: [[usize; 3]; 3] = std::array::from_fn(|k| std::array::from_fn(|l| k * 5 + l));
    let p2 = biquadratic_bspline_to_bezier(&sub_net::<3>(&net, 0, 0));
    for (s, b) in biquadratic_bspline_stencils(&idx3).iter().zip(&p2.cps) {
        assert!(dist(s.apply(&flat), *b) < 1e-15);
    }
    // univariate stencils with a repeated node merge
    let cs = curve_stencils(quadratic_bspline_matrix(), &[4, 4, 9]);
    assert_eq!(cs[0].entries(), &[(4, 1.0)]);
    assert_eq!(cs[2].entries(), &[(4, 0.5), (9, 0.5)]);
}

/// Node index of `d[k][l]` in a 5x5 net.
fn d(k: usize, l: usize) -> usize {
    k * 5 + l
}

/// A stencil from weights (in 16ths) over the paper's ordering
/// `[d00, d10, d01, d20, d02, d11, d21, d12, d22]`.
fn paper(w16: [f64; 9]) -> Stencil {
    let order = [
        d(0, 0),
        d(1, 0),
        d(0, 1),
        d(2, 0),
        d(0, 2),
        d(1, 1),
        d(2, 1),
        d(1, 2),
        d(2, 2),
    ];
    Stencil::from_pairs(order.iter().zip(w16).map(|(&i, w)| (i, w / 16.0)))
}

#[crate::unit::test]
fn eg_formula_6_matches_tensor_form() {
    let idx: [[usize; 5]; 5] = std::array::from_fn(|k| std::array::from_fn(|l| d(k, l)));
    let st = biquartic_c2_stencils(&idx);
    let b = |i: usize, j: usize| st[i * 5 + j].clone();
    // b00 = [1,2,2,1,1,4,2,2,1]/16, b10 = [0,2,0,2,0,4,4,2,2]/16
    assert_eq!(b(0, 0), paper([1., 2., 2., 1., 1., 4., 2., 2., 1.]));
    assert_eq!(b(1, 0), paper([0., 2., 0., 2., 0., 4., 4., 2., 2.]));
    // b20 = (d20 + 2 d21 + d22)/4
    assert_eq!(b(2, 0), paper([0., 0., 0., 4., 0., 0., 8., 0., 4.]));
    // b11 = (d11 + d21 + d12 + d22)/4, b22 = d22
    assert_eq!(b(1, 1), paper([0., 0., 0., 0., 0., 4., 4., 4., 4.]));
    assert_eq!(b(2, 2), Stencil::point(d(2, 2)));
    // The paper prints b21 = (d12 + d22)/2; with the index convention fixed by b10 and b20
    // (first index along u for both b and d) that expression is b12, and b21 = (d21 + d22)/2.
    assert_eq!(b(1, 2), paper([0., 0., 0., 0., 0., 0., 0., 8., 8.]));
    assert_eq!(b(2, 1), paper([0., 0., 0., 0., 0., 0., 8., 0., 8.]));
    // The paper's symmetry rules hold for every coefficient.
    let remap = |s: &Stencil, f: &dyn Fn(usize, usize) -> (usize, usize)| {
        Stencil::from_pairs(s.entries().iter().map(|&(n, w)| {
            let (k, l) = f(n as usize / 5, n as usize % 5);
            (d(k, l), w)
        }))
    };
    for i in 0..5 {
        for j in 0..5 {
            assert_eq!(b(j, i), remap(&b(i, j), &|k, l| (l, k)));
            assert_eq!(b(4 - i, j), remap(&b(i, j), &|k, l| (4 - k, l)));
            assert_eq!(b(i, 4 - j), remap(&b(i, j), &|k, l| (k, 4 - l)));
        }
    }
}
