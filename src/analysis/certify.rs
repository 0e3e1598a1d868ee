//! Injectivity certificates of characteristic maps.
//!
//! A characteristic ring is a planar ring of Bezier patches (the ring of the characteristic
//! map). Its certificate has two parts:
//!
//! 1. *Local injectivity, exactly:* the Jacobian determinant `x_u y_v - x_v y_u` of each patch
//!    is a polynomial of bi-degree `(2du - 1, 2dv - 1)` whose Bezier coefficients are computed
//!    exactly (products of Bernstein polynomials). All coefficients positive proves the
//!    determinant positive; where some are not, the polynomial is split by de Casteljau (up to
//!    depth [`MAX_DEPTH`]) until every piece has positive coefficients (certified) or a corner
//!    value is not positive (refuted). The minimum coefficient over the final pieces is reported.
//! 2. *Global injectivity, numerically:* the boundary of the ring consists of two closed curves;
//!    each must be simple (no self-intersection of a dense polyline) and wind once around the
//!    origin, and the copy of the ring scaled by lambda (the next ring) must lie inside the inner
//!    curve (sampled points, winding numbers). A locally injective map of an annulus whose
//!    boundary curves are simple and nested is injective, and the nesting of the scaled copy
//!    makes the union of all rings injective.

use crate::bezier::{BezierPatch, Side};
use crate::geom::{self, Point};
use crate::surface::PatchComplex;
use crate::surface::adjacency::{default_tolerance, shared_boundaries};
use serde::Serialize;

mod strips;
use strips::Strips;

/// Deepest de Casteljau splitting of a Jacobian polynomial.
pub const MAX_DEPTH: usize = 8;

/// The injectivity certificate of a characteristic ring.
#[derive(Debug, Clone, Serialize)]
pub struct InjectivityCertificate {
    /// Number of patches of the ring.
    pub patches: usize,
    /// Whether every Jacobian determinant is certified positive.
    pub jacobian_positive: bool,
    /// Minimum Bezier coefficient of the (normalised) Jacobian over the final split pieces.
    pub jacobian_min_coefficient: f64,
    /// Minimum Bezier coefficient before any splitting.
    pub jacobian_min_coefficient_unsplit: f64,
    /// Pieces examined (1 per patch without splitting).
    pub pieces: usize,
    /// Number of closed boundary curves found (2 for a ring).
    pub boundary_curves: usize,
    /// Winding numbers of the boundary curves around the origin (outer first).
    pub windings: Vec<i64>,
    /// Whether the boundary curves are simple.
    pub boundaries_simple: bool,
    /// Whether the lambda-scaled ring lies inside the inner boundary curve.
    pub scaled_copy_inside: bool,
    /// All of the above: the characteristic map is injective.
    pub injective: bool,
}

fn binom(n: usize, k: usize) -> f64 {
    let mut r = 1.0;
    for i in 0..k {
        r = r * (n - i) as f64 / (i + 1) as f64;
    }
    r
}

/// A scalar tensor Bezier polynomial: `c[i * (dv + 1) + j]`.
#[derive(Debug, Clone)]
struct Scalar {
    du: usize,
    dv: usize,
    c: Vec<f64>,
}

impl Scalar {
    fn at(&self, i: usize, j: usize) -> f64 {
        self.c[i * (self.dv + 1) + j]
    }

    fn product(&self, o: &Scalar) -> Scalar {
        let (du, dv) = (self.du + o.du, self.dv + o.dv);
        let mut c = vec![0.0; (du + 1) * (dv + 1)];
        for i in 0..=self.du {
            for j in 0..=self.dv {
                let a = self.at(i, j) * binom(self.du, i) * binom(self.dv, j);
                for k in 0..=o.du {
                    for l in 0..=o.dv {
                        c[(i + k) * (dv + 1) + j + l] +=
                            a * o.at(k, l) * binom(o.du, k) * binom(o.dv, l);
                    }
                }
            }
        }
        for k in 0..=du {
            for l in 0..=dv {
                c[k * (dv + 1) + l] /= binom(du, k) * binom(dv, l);
            }
        }
        Scalar { du, dv, c }
    }

    fn sub(&self, o: &Scalar) -> Scalar {
        Scalar {
            du: self.du,
            dv: self.dv,
            c: self.c.iter().zip(&o.c).map(|(a, b)| a - b).collect(),
        }
    }

    fn as_patch(&self) -> BezierPatch {
        BezierPatch::new(
            self.du,
            self.dv,
            self.c.iter().map(|&x| [x, 0.0, 0.0]).collect(),
        )
    }

    fn from_patch(p: &BezierPatch) -> Scalar {
        Scalar {
            du: p.deg_u,
            dv: p.deg_v,
            c: p.cps.iter().map(|q| q[0]).collect(),
        }
    }

    fn min(&self) -> f64 {
        self.c.iter().copied().fold(f64::INFINITY, f64::min)
    }

    fn corners_min(&self) -> f64 {
        let (du, dv) = (self.du, self.dv);
        [
            self.at(0, 0),
            self.at(du, 0),
            self.at(0, dv),
            self.at(du, dv),
        ]
        .into_iter()
        .fold(f64::INFINITY, f64::min)
    }
}

/// The Bezier form of the Jacobian determinant of the planar map `(x, y)` of a patch.
fn jacobian(p: &BezierPatch) -> Scalar {
    let (du, dv) = (p.deg_u, p.deg_v);
    let comp = |k: usize, di: usize, dj: usize, fu: bool| -> Scalar {
        let (nu, nv) = if fu { (du - 1, dv) } else { (du, dv - 1) };
        let mut c = Vec::with_capacity((nu + 1) * (nv + 1));
        for i in 0..=nu {
            for j in 0..=nv {
                let (a, b) = (p.cp(i + di, j + dj)[k], p.cp(i, j)[k]);
                c.push((if fu { du } else { dv }) as f64 * (a - b));
            }
        }
        Scalar { du: nu, dv: nv, c }
    };
    let xu = comp(0, 1, 0, true);
    let xv = comp(0, 0, 1, false);
    let yu = comp(1, 1, 0, true);
    let yv = comp(1, 0, 1, false);
    xu.product(&yv).sub(&xv.product(&yu))
}

/// Certifies a scalar polynomial positive: `(certified, min coefficient of final pieces, pieces)`.
fn certify_positive(s: &Scalar, depth: usize, scale: f64) -> (bool, f64, usize) {
    let m = s.min() / scale;
    if m > 0.0 {
        return (true, m, 1);
    }
    if s.corners_min() <= 0.0 || depth == 0 {
        return (false, m, 1);
    }
    let p = s.as_patch();
    let (a, b) = p.split_u(0.5);
    let mut ok = true;
    let mut mn = f64::INFINITY;
    let mut pieces = 0;
    for half in [a, b] {
        let (c, d) = half.split_v(0.5);
        for q in [c, d] {
            let (o, m, k) = certify_positive(&Scalar::from_patch(&q), depth - 1, scale);
            ok &= o;
            mn = mn.min(m);
            pieces += k;
        }
    }
    (ok, mn, pieces)
}

/// Points of side `side` of `p`, oriented counter-clockwise around the patch, `k + 1` samples.
fn side_polyline(p: &BezierPatch, side: Side, k: usize) -> Vec<Point> {
    let mut pts: Vec<Point> = (0..=k)
        .map(|i| {
            let [u, v] = side.domain_point(i as f64 / k as f64);
            p.eval(u, v)
        })
        .collect();
    // V0 runs with +u and U1 with +v (counter-clockwise); V1 and U0 run backwards.
    if matches!(side, Side::V1 | Side::U0) {
        pts.reverse();
    }
    pts
}

fn segments_cross(a: Point, b: Point, c: Point, d: Point) -> bool {
    let orient = |p: Point, q: Point, r: Point| {
        (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])
    };
    let (d1, d2) = (orient(a, b, c), orient(a, b, d));
    let (d3, d4) = (orient(c, d, a), orient(c, d, b));
    d1 * d2 < 0.0 && d3 * d4 < 0.0
}

/// Chains the open (unshared) sides of a planar ring into closed polylines.
fn boundary_loops(ring: &[BezierPatch]) -> Vec<Vec<Point>> {
    let c = PatchComplex {
        patches: ring.to_vec(),
        provenance: vec![crate::surface::Provenance::Unknown; ring.len()],
        ..PatchComplex::default()
    };
    let tol = default_tolerance(&c);
    let shared = shared_boundaries(&c, tol);
    let mut covered = vec![[0.0f64; 4]; ring.len()];
    for sb in &shared {
        covered[sb.a][sb.side_a.index()] += sb.t[1] - sb.t[0];
        covered[sb.b][sb.side_b.index()] += 1.0;
    }
    let mut pieces: Vec<Vec<Point>> = Vec::new();
    for (i, p) in ring.iter().enumerate() {
        for side in Side::ALL {
            if covered[i][side.index()] < 1.0 - 1e-9 && !p.is_collapsed(side, tol) {
                pieces.push(side_polyline(p, side, 32));
            }
        }
    }
    let mut loops = Vec::new();
    let mut used = vec![false; pieces.len()];
    let close = |a: Point, b: Point| geom::dist(a, b) <= 1e3 * tol;
    for start in 0..pieces.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let mut lp = pieces[start].clone();
        loop {
            let end = *lp.last().expect("non-empty");
            if close(end, lp[0]) && lp.len() > 2 {
                lp.pop();
                break;
            }
            match (0..pieces.len()).find(|&k| !used[k] && close(pieces[k][0], end)) {
                Some(k) => {
                    used[k] = true;
                    lp.extend_from_slice(&pieces[k][1..]);
                }
                None => break,
            }
        }
        loops.push(lp);
    }
    loops
}

/// Certifies a planar characteristic ring (patches in the `xy` plane, counter-clockwise) and its
/// nesting with the copy scaled by `lambda`.
pub fn certify_ring(ring: &[BezierPatch], lambda: f64) -> InjectivityCertificate {
    let scale = ring
        .iter()
        .flat_map(|p| p.cps.iter())
        .map(|q| q[0] * q[0] + q[1] * q[1])
        .fold(0.0, f64::max)
        .max(1e-300);
    let mut ok = true;
    let mut mn = f64::INFINITY;
    let mut mn0 = f64::INFINITY;
    let mut pieces = 0;
    for p in ring {
        let j = jacobian(p);
        mn0 = mn0.min(j.min() / scale);
        let (o, m, k) = certify_positive(&j, MAX_DEPTH, scale);
        ok &= o;
        mn = mn.min(m);
        pieces += k;
    }
    let mut loops = boundary_loops(ring);
    // Outer first: by largest mean radius.
    let radius = |l: &Vec<Point>| l.iter().map(|p| p[0].hypot(p[1])).sum::<f64>() / l.len() as f64;
    loops.sort_by(|a, b| radius(b).total_cmp(&radius(a)));
    let indexed: Vec<Strips<'_>> = loops.iter().map(|l| Strips::new(l)).collect();
    let windings: Vec<i64> = indexed.iter().map(|l| l.winding([0.0, 0.0])).collect();
    let simple = indexed.iter().all(|l| l.is_simple());
    let scaled_inside = if loops.len() == 2 {
        let inner = &indexed[1];
        ring.iter().all(|p| {
            (1..8).all(|i| {
                (1..8).all(|j| {
                    let q = p.eval(i as f64 / 8.0, j as f64 / 8.0);
                    inner.winding([lambda * q[0], lambda * q[1]]).abs() == 1
                        && inner.winding([q[0], q[1]]) == 0
                })
            })
        })
    } else {
        false
    };
    let injective = ok && loops.len() == 2 && windings == vec![1, -1] && simple && scaled_inside;
    InjectivityCertificate {
        patches: ring.len(),
        jacobian_positive: ok,
        jacobian_min_coefficient: mn,
        jacobian_min_coefficient_unsplit: mn0,
        pieces,
        boundary_curves: loops.len(),
        windings,
        boundaries_simple: simple,
        scaled_copy_inside: scaled_inside,
        injective,
    }
}

#[cfg(feature = "unit-tests")]
mod tests {
    use super::*;

    #[crate::unit::test]
    fn jacobian_of_a_bilinear_square_is_its_area() {
        // Square [0,2]^2 as a bi-1 patch: x_u = 2, y_v = 2 -> J = 4.
        let p = BezierPatch::new(
            1,
            1,
            vec![
                [0.0, 0.0, 0.0],
                [0.0, 2.0, 0.0],
                [2.0, 0.0, 0.0],
                [2.0, 2.0, 0.0],
            ],
        );
        let j = jacobian(&p);
        assert_eq!((j.du, j.dv), (1, 1));
        for &c in &j.c {
            assert!((c - 4.0).abs() < 1e-14);
        }
        // A fold: reversing u gives -4.
        let j = jacobian(&p.reversed_u());
        assert!(j.c.iter().all(|&c| (c + 4.0).abs() < 1e-14));
    }

    #[crate::unit::test]
    fn jacobian_matches_pointwise_determinant() {
        let p = BezierPatch::from_fn(3, 3, |i, j| {
            let (x, y) = (i as f64, j as f64);
            [x + 0.1 * y * y, y + 0.05 * x * y, 0.0]
        });
        let jac = jacobian(&p).as_patch();
        for &(u, v) in &[(0.1, 0.2), (0.5, 0.5), (0.9, 0.3)] {
            let d = p.derivatives(u, v);
            let det = d.du[0] * d.dv[1] - d.dv[0] * d.du[1];
            assert!((jac.eval(u, v)[0] - det).abs() < 1e-12);
        }
    }
}
