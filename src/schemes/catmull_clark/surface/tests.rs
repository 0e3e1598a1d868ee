//! Unit tests of Catmull-Clark's adaptive surface, fills and capped complexes.

use super::*;
use crate::bezier::Side;

fn de_casteljau(c: &[Point], t: f64) -> Point {
    crate::bezier::curve::eval(c, t)
}

/// The four sides of a patch of any degree (the G^1 caps are bi-4 or bi-5).
fn sides(p: &BezierPatch) -> Vec<Vec<Point>> {
    [Side::V0, Side::U1, Side::V1, Side::U0]
        .into_iter()
        .map(|s| p.boundary(s))
        .collect()
}

/// Distance from `p` to a Bezier curve (dense sampling, then ternary search).
fn dist_to_curve(p: Point, c: &[Point]) -> f64 {
    let d = |t: f64| geom::dist(p, de_casteljau(c, t));
    let k = (0..=32)
        .min_by(|&a, &b| d(a as f64 / 32.0).total_cmp(&d(b as f64 / 32.0)))
        .unwrap();
    let (mut lo, mut hi) = (
        ((k as f64) - 1.0).max(0.0) / 32.0,
        ((k as f64) + 1.0).min(32.0) / 32.0,
    );
    for _ in 0..100 {
        let (m1, m2) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
        if d(m1) < d(m2) { hi = m2 } else { lo = m1 }
    }
    d(0.5 * (lo + hi))
}

/// Largest distance from a boundary sample of a patch to the nearest side curve of another
/// patch: 0 for a closed C^0 complex (T-junctions included).
pub(crate) fn max_gap(c: &PatchComplex) -> f64 {
    let all: Vec<Vec<Vec<Point>>> = c.patches.iter().map(sides).collect();
    let mut worst: f64 = 0.0;
    for (a, sa) in all.iter().enumerate() {
        for side in sa {
            for k in 0..=4 {
                let p = de_casteljau(side, k as f64 / 4.0);
                let mut best = f64::INFINITY;
                for (b, sb) in all.iter().enumerate() {
                    if a == b {
                        continue;
                    }
                    for other in sb {
                        // The curve lies in its control points' box: a lower bound.
                        let (lo, hi) = geom::bounding_box(other.iter().copied()).unwrap();
                        let mut gap2 = 0.0;
                        for d in 0..3 {
                            let e = (lo[d] - p[d]).max(p[d] - hi[d]).max(0.0);
                            gap2 += e * e;
                        }
                        if gap2.sqrt() >= best {
                            continue;
                        }
                        best = best.min(dist_to_curve(p, other));
                    }
                }
                worst = worst.max(best);
            }
        }
    }
    worst
}

#[crate::unit::test]
fn cube_rings_and_fill_are_closed() {
    let m = crate::mesh::nets::unit_cube();
    for rings in [1, 2, 3] {
        let c = catmull_clark_complex(&m, ComplexOptions { rings, fill: true }, |_| {}).unwrap();
        // 8 vertices of valence 3: the cube's faces all touch extraordinary vertices.
        let caps = c
            .provenance
            .iter()
            .filter(|p| matches!(p, Provenance::Cap { .. }))
            .count();
        assert_eq!(caps, 24, "rings {rings}");
        // Every boundary sample of every patch lies on another patch's boundary sample set.
        let worst = max_gap(&c);
        assert!(worst < 1e-12, "rings {rings}: gap {worst}");
    }
}
