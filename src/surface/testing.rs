//! Patch complexes with known structure, and the chain rule of the chart tests, for the tests
//! of the surface modules.

use super::{PatchComplex, Provenance};
use crate::bezier::convert::bicubic_bspline_to_bezier;
use crate::bezier::{BezierPatch, Derivatives};
use crate::geom::{Point, axpy};
use std::f64::consts::PI;

/// Closed torus of `m x k` bi-3 patches from a periodic regular net (all valence 4): u runs
/// around the axis, v around the tube, normal `du x dv` outward.
pub(crate) fn torus(m: usize, k: usize) -> PatchComplex {
    let (big, small) = (3.0, 1.0);
    let node = |i: usize, j: usize| -> Point {
        let th = 2.0 * PI * (i % m) as f64 / m as f64;
        let ph = 2.0 * PI * (j % k) as f64 / k as f64;
        let r = big + small * ph.cos();
        [r * th.cos(), r * th.sin(), small * ph.sin()]
    };
    let mut c = PatchComplex::new();
    for i in 0..m {
        for j in 0..k {
            let net: [[Point; 4]; 4] = std::array::from_fn(|a| {
                std::array::from_fn(|b| node(i + m + a - 1, j + k + b - 1))
            });
            c.push(
                bicubic_bspline_to_bezier(&net),
                Provenance::Regular {
                    face: (i * k + j) as u32,
                },
            );
        }
    }
    c
}

/// An open `m x m` grid of bi-3 patches from a gently curved regular net.
pub(crate) fn grid(m: usize) -> PatchComplex {
    let node = |i: usize, j: usize| -> Point {
        let (x, y) = (i as f64, j as f64);
        [x, y, 0.1 * (0.7 * x).sin() * (0.5 * y).cos()]
    };
    let mut c = PatchComplex::new();
    for i in 0..m {
        for j in 0..m {
            let net: [[Point; 4]; 4] =
                std::array::from_fn(|a| std::array::from_fn(|b| node(i + a, j + b)));
            c.push(bicubic_bspline_to_bezier(&net), Provenance::Unknown);
        }
    }
    c
}

/// The four quarter patches of `p` (split at `u = v = 1/2`), in the order `(u, v)` =
/// low-low, low-high, high-low, high-high.
pub(crate) fn quarters(p: &BezierPatch) -> [BezierPatch; 4] {
    let (a, b) = p.split_u(0.5);
    let (a0, a1) = a.split_v(0.5);
    let (b0, b1) = b.split_v(0.5);
    [a0, a1, b0, b1]
}

/// Replaces the patches with the given indices by their quarters (appended at the end).
pub(crate) fn refine_some(c: &PatchComplex, which: &[usize]) -> PatchComplex {
    let mut out = PatchComplex::new();
    for (k, (p, prov)) in c.patches.iter().zip(&c.provenance).enumerate() {
        if !which.contains(&k) {
            out.push(p.clone(), *prov);
        }
    }
    for &k in which {
        for q in quarters(&c.patches[k]) {
            out.push(q, c.provenance[k]);
        }
    }
    out
}

/// A closed sphere-like surface of `n` bi-(2,2) lunes: each lune's side `U0` collapses to the
/// north pole and `U1` to the south pole; lune `k` spans angles `2 pi k / n .. 2 pi (k+1) / n`
/// and its side `V1` is the side `V0` of lune `k + 1`. Normal `du x dv` outward.
pub(crate) fn lunes(n: usize) -> PatchComplex {
    let rho = 1.5;
    let mut c = PatchComplex::new();
    for k in 0..n {
        let (t0, t1) = (
            2.0 * PI * k as f64 / n as f64,
            2.0 * PI * (k + 1) as f64 / n as f64,
        );
        let tm = 0.5 * (t0 + t1);
        let w = rho / (0.5 * (t1 - t0)).cos();
        let ring = [
            [rho * t0.cos(), rho * t0.sin(), 0.0],
            [w * tm.cos(), w * tm.sin(), 0.0],
            [rho * t1.cos(), rho * t1.sin(), 0.0],
        ];
        let p = BezierPatch::from_fn(2, 2, |i, j| match i {
            0 => [0.0, 0.0, 1.0],
            1 => ring[j],
            _ => [0.0, 0.0, -1.0],
        });
        c.push(p, Provenance::Unknown);
    }
    c
}

/// The derivatives of `f(K(u, v))` from those of `f` at `K(u, v)` (`t`) by the second-order
/// chain rule, for a map `K` with Jacobian `j` (`j[a][q] = d K_a / d q`) and twist
/// `d^2 K / du dv = tw` (its other second derivatives zero); for the chart tests.
pub(crate) fn chain_rule(t: &Derivatives, j: [[f64; 2]; 2], tw: [f64; 2]) -> Derivatives {
    let g = [t.du, t.dv];
    let h = [[t.duu, t.duv], [t.duv, t.dvv]];
    let pd = |q: usize| (0..2).fold([0.0; 3], |r, a| axpy(r, j[a][q], g[a]));
    let pdd = |q: usize, w: usize| {
        let mut r = [0.0; 3];
        for a in 0..2 {
            for c in 0..2 {
                r = axpy(r, j[a][q] * j[c][w], h[a][c]);
            }
        }
        if q != w {
            for a in 0..2 {
                r = axpy(r, tw[a], g[a]);
            }
        }
        r
    };
    Derivatives {
        p: t.p,
        du: pd(0),
        dv: pd(1),
        duu: pdd(0, 0),
        duv: pdd(0, 1),
        dvv: pdd(1, 1),
    }
}
