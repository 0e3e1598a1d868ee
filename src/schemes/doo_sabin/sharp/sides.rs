//! The crease sides of a patch complex built on a cut net: of the sides on the cut net's
//! boundary, those that lie along another (the two sides of a crease) are kept as sharp joins,
//! the rest is the surface's boundary.

use crate::bezier::Side;
use crate::bezier::complex::PatchComplex;
use crate::geom::{Point, dist};
use std::collections::HashMap;

/// Of the sides the host marked as lying on the cut net's boundary (the Doo-Sabin host marks
/// them as it emits the patches), keeps those that lie along another marked side: the two sides
/// of a crease, which end on the same curve, so that `check` reports the crease as a sharp
/// join. The others are the surface's boundary and are cleared. The two sides of a crease may
/// be refined to different levels (a regular patch on one side, ring patches on the other), so
/// a side is kept when its midpoint is a dyadic point (`t = k / 2^SPLIT`) of another marked
/// side or another marked side's midpoint is one of its own: points agreeing to `1e-9` of the
/// complex's size, found through a grid of cells of `1e-6` of its size.
pub(crate) fn keep_crease_sides(c: &mut PatchComplex) {
    const SPLIT: u32 = 6;
    let marks = std::mem::take(&mut c.sharp_sides);
    if marks.is_empty() {
        return;
    }
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in c.patches.iter().flat_map(|p| &p.cps) {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let size = dist(lo, hi).max(f64::MIN_POSITIVE);
    let (tol, cell) = (1e-9 * size, 1e-6 * size);
    let key =
        |x: Point| std::array::from_fn::<i64, 3, _>(|k| ((x[k] - lo[k]) / cell).floor() as i64);
    let sides: Vec<(u32, Side)> = marks
        .iter()
        .flat_map(|&(p, m)| {
            Side::ALL
                .into_iter()
                .filter(move |s| m & (1 << s.index()) != 0)
                .map(move |s| (p, s))
        })
        .collect();
    let n = 1u32 << SPLIT;
    // the dyadic points of every side (the midpoint is point n / 2)
    let points: Vec<Vec<Point>> = sides
        .iter()
        .map(|&(p, s)| {
            let patch = &c.patches[p as usize];
            (0..=n)
                .map(|k| {
                    let [u, v] = s.domain_point(f64::from(k) / f64::from(n));
                    patch.eval(u, v)
                })
                .collect()
        })
        .collect();
    let mut grid: HashMap<[i64; 3], Vec<(usize, u32)>> = HashMap::new();
    for (i, pts) in points.iter().enumerate() {
        for (k, &x) in pts.iter().enumerate().skip(1).take(n as usize - 1) {
            grid.entry(key(x)).or_default().push((i, k as u32));
        }
    }
    // the sides other than `i` with x as an inner dyadic point (the side, the point's index)
    let found = |x: Point, i: usize| -> Vec<(usize, u32)> {
        let k = key(x);
        let mut out = Vec::new();
        for d in 0..27 {
            let cell = [k[0] + d % 3 - 1, k[1] + d / 3 % 3 - 1, k[2] + d / 9 - 1];
            if let Some(js) = grid.get(&cell) {
                out.extend(
                    js.iter()
                        .filter(|&&(j, q)| j != i && dist(points[j][q as usize], x) <= tol),
                );
            }
        }
        out
    };
    let mut keep = vec![false; sides.len()];
    for i in 0..sides.len() {
        let mid = points[i][n as usize / 2];
        // a side j with an inner dyadic point at i's midpoint: i lies along j when its ends
        // and midpoint are points of j (j as long or longer; a longer i finds a shorter j
        // the other way round, from j's midpoint)
        for (j, _) in found(mid, i) {
            if same_curve(&points[i], &points[j], tol) {
                keep[i] = true;
                keep[j] = true;
            }
        }
    }
    for (i, &(p, side)) in sides.iter().enumerate() {
        if keep[i] {
            c.mark_sharp(p as usize, side.index());
        }
    }
}

/// Whether side `a` lies along side `b`: its ends and its midpoint are dyadic points of `b`.
fn same_curve(a: &[Point], b: &[Point], tol: f64) -> bool {
    let on_b = |x: Point| b.iter().any(|&y| dist(x, y) <= tol);
    on_b(a[0]) && on_b(a[a.len() - 1]) && on_b(a[a.len() / 2])
}
