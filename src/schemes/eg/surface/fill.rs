//! The C^0 fills of the d-net caps' holes (EG's and QAS+'s bi-4 fill, QAS+^3's bi-3 Coons
//! fill; documented in [`super`]): what closes a hole where the G^1 cap of [`super::g1`] is not
//! built (`--rings 0` aside, a cap whose tangents degenerate), and what the G^1 cap reads its
//! hole data from (the bi-4 fill's two outer layers are the ring's C^1 continuation).
//! Patches are returned per sector, transposed to the mesh chart as the rings are.

use super::{ring_patch, ring_patch3};
use crate::bezier::{BezierPatch, curve};
use crate::geom::{self, Point};

/// The fill inside a bi-3 ring (QAS+^3): per sector 2 x 2 bi-3 Coons patches. The outer sides are
/// the ring's inner sides (exact), the spokes cubics through `c0`, the next ring's corner at half
/// the distance and the ring's corner with its derivative (split in two), the inner lines straight
/// through a centre point set by the bilinear Coons rule. C^0 to the ring and between sectors.
pub(super) fn fill_bi3(ring: &[Point], next: &[Point], c0: Point, n: usize) -> Vec<BezierPatch> {
    let mut out = Vec::with_capacity(4 * n);
    let spokes: Vec<[Point; 4]> = (0..n)
        .map(|s| {
            let a = ring_patch3(ring, s, 0, 0);
            let q = a.cp(0, 0);
            // The sub-patch spans half the spoke's parameter: the spoke's derivative is twice.
            let d = geom::scale(a.derivatives(0.0, 0.0).du, 2.0);
            let mid = ring_patch3(next, s, 0, 0).cp(0, 0);
            let b2 = geom::axpy(q, -1.0 / 3.0, d);
            let mut b1 = [0.0; 3];
            for k in 0..3 {
                b1[k] = (8.0 * mid[k] - c0[k] - 3.0 * b2[k] - q[k]) / 3.0;
            }
            [c0, b1, b2, q]
        })
        .collect();
    let halves = |c: &[Point; 4]| {
        let (lo, hi) = curve::split(c, 0.5);
        (lo, hi)
    };
    let line = |a: Point, b: Point| {
        vec![
            a,
            geom::lerp(a, b, 1.0 / 3.0),
            geom::lerp(a, b, 2.0 / 3.0),
            b,
        ]
    };
    for s in 0..n {
        let (sp_lo, sp_hi) = halves(&spokes[s]);
        let (sq_lo, sq_hi) = halves(&spokes[(s + n - 1) % n]);
        let a00 = ring_patch3(ring, s, 0, 0).boundary(crate::bezier::Side::U0);
        let a01 = ring_patch3(ring, s, 0, 2).boundary(crate::bezier::Side::U0);
        let c00 = ring_patch3(ring, s, 2, 0).boundary(crate::bezier::Side::V0);
        let c10 = ring_patch3(ring, s, 2, 1).boundary(crate::bezier::Side::V0);
        let (m1, m3) = (sp_lo[3], sq_lo[3]);
        let (m2, m4) = (c00[3], a00[3]);
        let corner = a01[3];
        let (q_s, q_p) = (sp_hi[3], sq_hi[3]);
        let mut x = [0.0; 3];
        for k in 0..3 {
            x[k] = 0.5 * (m1[k] + m2[k] + m3[k] + m4[k])
                - 0.25 * (c0[k] + q_s[k] + q_p[k] + corner[k]);
        }
        // Sub-patches of the sector fill over [0, 1/2]^2 etc. of its EG chart: (v0, u1, v1, u0).
        // Each cell lists its sides (v0, u1, v1, u0).
        let cells: [[Vec<Point>; 4]; 4] = [
            [sp_lo.to_vec(), line(m1, x), line(m3, x), sq_lo.to_vec()],
            [sp_hi.to_vec(), a00.clone(), line(x, m4), line(m1, x)],
            [line(m3, x), line(x, m2), c00.clone(), sq_hi.to_vec()],
            [line(x, m4), a01.clone(), c10.clone(), line(x, m2)],
        ];
        for [v0, u1, v1, u0] in cells.iter() {
            out.push(BezierPatch::coons(3, v0, u1, v1, u0).transposed());
        }
    }
    out
}

/// The EG fill of the hole inside `ring` (see [`super`]); `next` is the ring after
/// it (only its corner points are used), `c0` the limit point.
pub(super) fn fill(ring: &[Point], next: &[Point], c0: Point, n: usize) -> Vec<BezierPatch> {
    // Spoke s runs along the ray between sectors s and s + 1 (the EG chart's u axis of sector s):
    // the cubic through c0, the next ring's corner at half the distance and the ring's corner Q
    // with the ring's derivative there, raised to degree 4 (its last two coefficients are then
    // exactly the C^1 continuation of the ring along the ray).
    let spokes: Vec<Vec<Point>> = (0..n)
        .map(|s| {
            let a = ring_patch(ring, s, 0);
            let q = a.cp(0, 0);
            let d = a.derivatives(0.0, 0.0).du;
            let mid = ring_patch(next, s, 0).cp(0, 0);
            let b2 = geom::axpy(q, -1.0 / 3.0, d);
            let mut b1 = [0.0; 3];
            for k in 0..3 {
                b1[k] = (8.0 * mid[k] - c0[k] - 3.0 * b2[k] - q[k]) / 3.0;
            }
            curve::raise(&[c0, b1, b2, q])
        })
        .collect();
    let mut out = Vec::with_capacity(n);
    for s in 0..n {
        let a = ring_patch(ring, s, 0);
        let c = ring_patch(ring, s, 2);
        let mut b = [[[0.0; 3]; 5]; 5];
        let mut fixed = [[false; 5]; 5];
        for t in 0..5 {
            // Spokes (C^0 between sectors).
            b[t][0] = spokes[s][t];
            b[0][t] = spokes[(s + n - 1) % n][t];
            fixed[t][0] = true;
            fixed[0][t] = true;
        }
        for t in 0..5 {
            // C^0 and C^1 to patch A across u = 1 and to patch C across v = 1.
            b[4][t] = a.cp(0, t);
            b[3][t] = geom::sub(geom::scale(a.cp(0, t), 2.0), a.cp(1, t));
            b[t][4] = c.cp(t, 0);
            b[t][3] = geom::sub(geom::scale(c.cp(t, 0), 2.0), c.cp(t, 1));
            fixed[4][t] = true;
            fixed[3][t] = true;
            fixed[t][4] = true;
            fixed[t][3] = true;
        }
        fair_interior(&mut b, &fixed);
        out.push(BezierPatch::from_fn(4, 4, |i, j| b[i][j]).transposed());
    }
    out
}

/// Sets the free coefficients of a 5 x 5 net to minimise the sum of squared second differences
/// (`u u`, `v v` and twice the mixed ones): a discrete thin-plate energy, solved exactly by the
/// normal equations.
fn fair_interior(b: &mut [[Point; 5]; 5], fixed: &[[bool; 5]; 5]) {
    let free: Vec<(usize, usize)> = (0..5)
        .flat_map(|i| (0..5).map(move |j| (i, j)))
        .filter(|&(i, j)| !fixed[i][j])
        .collect();
    if free.is_empty() {
        return;
    }
    let col = |i: usize, j: usize| free.iter().position(|&f| f == (i, j));
    // Each second difference is a row: sum_k w_k b_k; split into free (matrix) and fixed (rhs).
    let mut stencils: Vec<Vec<((usize, usize), f64)>> = Vec::new();
    for i in 0..5 {
        for j in 0..5 {
            if i + 2 < 5 {
                stencils.push(vec![((i, j), 1.0), ((i + 1, j), -2.0), ((i + 2, j), 1.0)]);
            }
            if j + 2 < 5 {
                stencils.push(vec![((i, j), 1.0), ((i, j + 1), -2.0), ((i, j + 2), 1.0)]);
            }
            if i + 1 < 5 && j + 1 < 5 {
                let w = std::f64::consts::SQRT_2;
                stencils.push(vec![
                    ((i, j), w),
                    ((i + 1, j), -w),
                    ((i, j + 1), -w),
                    ((i + 1, j + 1), w),
                ]);
            }
        }
    }
    let k = free.len();
    let mut m = nalgebra::DMatrix::<f64>::zeros(stencils.len(), k);
    let mut rhs = nalgebra::DMatrix::<f64>::zeros(stencils.len(), 3);
    for (r, st) in stencils.iter().enumerate() {
        for &((i, j), w) in st {
            match col(i, j) {
                Some(c) => m[(r, c)] += w,
                None => {
                    for d in 0..3 {
                        rhs[(r, d)] -= w * b[i][j][d];
                    }
                }
            }
        }
    }
    let ata = m.transpose() * &m;
    let atb = m.transpose() * rhs;
    if let Some(x) = ata.lu().solve(&atb) {
        for (c, &(i, j)) in free.iter().enumerate() {
            b[i][j] = [x[(c, 0)], x[(c, 1)], x[(c, 2)]];
        }
    }
}
