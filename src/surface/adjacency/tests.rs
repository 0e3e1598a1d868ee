//! Adjacency on grids with 2:1 and 3:1 T-junctions, reversed patches, collapsed sides and a
//! closed torus, checked by counts and by evaluating both sides of every record.

use super::*;
use crate::bezier::BezierPatch;
use crate::surface::testing::{grid, lunes, refine_some, torus};
use crate::surface::{PatchComplex, Provenance};

/// Largest distance between the two sides of every record at 11 parameters.
fn max_mismatch(c: &PatchComplex, sb: &[SharedBoundary]) -> f64 {
    let mut worst: f64 = 0.0;
    for r in sb {
        for k in 0..=10 {
            let t = r.t[0] + (r.t[1] - r.t[0]) * k as f64 / 10.0;
            let [ua, va] = r.side_a.domain_point(t);
            let [ub, vb] = r.side_b.domain_point(r.map_to_b(t));
            let d = dist(c.patches[r.a].eval(ua, va), c.patches[r.b].eval(ub, vb));
            worst = worst.max(d);
        }
        assert!(
            (r.map_to_a(r.map_to_b(0.3 * r.t[0] + 0.7 * r.t[1])) - (0.3 * r.t[0] + 0.7 * r.t[1]))
                .abs()
                < 1e-14
        );
    }
    worst
}

#[crate::unit::test]
fn regular_grid_edges() {
    let c = grid(4);
    let sb = shared_boundaries(&c, default_tolerance(&c));
    // 2 * 4 * 3 interior edges, all edge to edge, same direction (consistent parametrisation)
    assert_eq!(sb.len(), 24);
    assert!(
        sb.iter()
            .all(|r| r.is_full() && !r.is_reversed() && r.a < r.b)
    );
    assert!(sb.iter().all(|r| r.s == [0.0, 1.0]));
    // patch 0 (i = 0, j = 0) meets patch 1 (j = 1) along its V1 side and patch 4 along U1
    assert!(
        sb.iter()
            .any(|r| r.a == 0 && r.side_a == Side::V1 && r.b == 1 && r.side_b == Side::V0)
    );
    assert!(
        sb.iter()
            .any(|r| r.a == 0 && r.side_a == Side::U1 && r.b == 4 && r.side_b == Side::U0)
    );
    assert!(max_mismatch(&c, &sb) < 1e-14);
}

#[crate::unit::test]
fn two_to_one_t_junctions() {
    // 3x3 grid with the centre patch (index 4) split into four
    let c = refine_some(&grid(3), &[4]);
    assert_eq!(c.len(), 12);
    let sb = shared_boundaries(&c, default_tolerance(&c));
    let full: Vec<_> = sb.iter().filter(|r| r.is_full()).collect();
    let partial: Vec<_> = sb.iter().filter(|r| !r.is_full()).collect();
    // 12 coarse edges minus the 4 of the centre patch, plus 4 edges inside the split patch
    assert_eq!(full.len(), 12);
    // each of the 4 sides around the split patch is covered by two halves
    assert_eq!(partial.len(), 8);
    for r in &partial {
        assert!(r.a < 8 && r.b >= 8, "{r:?}");
        let half = |x: [f64; 2], y: [f64; 2]| (x[0] - y[0]).abs() + (x[1] - y[1]).abs() < 1e-12;
        assert!(half(r.t, [0.0, 0.5]) || half(r.t, [0.5, 1.0]), "{r:?}");
        assert_eq!(r.s, [0.0, 1.0]);
    }
    assert!(max_mismatch(&c, &sb) < 1e-14);
}

#[crate::unit::test]
fn reversed_patches_and_three_to_one_junction() {
    // two patches side by side; the right one split in three along v and reversed in v
    let c0 = grid(2);
    let left = c0.patches[0].clone(); // its U1 side meets the right patch's U0
    let right = c0.patches[2].clone();
    let (r0, rest) = right.split_v(1.0 / 3.0);
    let (r1, r2) = rest.split_v(0.5);
    let mut c = PatchComplex::new();
    c.push(left, Provenance::Unknown);
    for p in [r0, r1, r2] {
        c.push(p.reversed_v(), Provenance::Unknown);
    }
    let sb = shared_boundaries(&c, 1e-9);
    let junction: Vec<_> = sb.iter().filter(|r| r.a == 0).collect();
    assert_eq!(junction.len(), 3, "{sb:?}");
    let expect = [[0.0, 1.0 / 3.0], [1.0 / 3.0, 2.0 / 3.0], [2.0 / 3.0, 1.0]];
    for (r, e) in junction.iter().zip(expect) {
        assert_eq!(r.side_a, Side::U1);
        assert_eq!(r.side_b, Side::U0);
        assert!(
            (r.t[0] - e[0]).abs() < 1e-12 && (r.t[1] - e[1]).abs() < 1e-12,
            "{r:?}"
        );
        assert!(r.is_reversed() && r.s == [1.0, 0.0]);
    }
    // the three pieces meet each other edge to edge
    assert_eq!(sb.iter().filter(|r| r.is_full()).count(), 2);
    assert!(max_mismatch(&c, &sb) < 1e-13);
}

#[crate::unit::test]
fn collapsed_sides_share_nothing() {
    let c = lunes(5);
    let sb = shared_boundaries(&c, default_tolerance(&c));
    assert_eq!(sb.len(), 5);
    for r in &sb {
        assert!(r.is_full() && !r.is_reversed());
        assert!(matches!(
            (r.side_a, r.side_b),
            (Side::V0, Side::V1) | (Side::V1, Side::V0)
        ));
    }
    assert!(max_mismatch(&c, &sb) < 1e-14);
}

#[crate::unit::test]
fn closed_torus_with_junctions() {
    let c = refine_some(&torus(6, 4), &[0, 7, 14]);
    let sb = shared_boundaries(&c, default_tolerance(&c));
    // every side of every patch is covered exactly once: coarse sides by one full record or
    // two halves, fine sides by one record
    let mut cover = vec![0.0; 4 * c.len()];
    for r in &sb {
        cover[4 * r.a + r.side_a.index()] += r.t[1] - r.t[0];
        cover[4 * r.b + r.side_b.index()] += (r.s[1] - r.s[0]).abs();
    }
    assert!(cover.iter().all(|&x| (x - 1.0).abs() < 1e-12), "{cover:?}");
    assert_eq!(sb.iter().filter(|r| !r.is_full()).count(), 3 * 8);
    assert!(max_mismatch(&c, &sb) < 1e-13);
}

fn bilinear_grid(m: usize) -> PatchComplex {
    let mut c = PatchComplex::new();
    for i in 0..m {
        for j in 0..m {
            let q = |a: usize, b: usize| [(i + a) as f64, (j + b) as f64, 0.0];
            c.push(
                BezierPatch::new(1, 1, vec![q(0, 0), q(0, 1), q(1, 0), q(1, 1)]),
                Provenance::Unknown,
            );
        }
    }
    c
}

#[crate::unit::test]
fn many_patches() {
    let m = 120;
    let sb = shared_boundaries(&bilinear_grid(m), 1e-9);
    assert_eq!(sb.len(), 2 * m * (m - 1));
}

#[crate::unit::test]
fn welding() {
    let pts = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1e-10, 0.0, 0.0],
        [1.0, 5e-11, 0.0],
        [2.0; 3],
    ];
    let (ids, n) = weld_points(&pts, 1e-9);
    assert_eq!((ids, n), (vec![0, 1, 0, 1, 2], 3));
    let (ids, n) = weld_points(&pts, 0.0);
    assert_eq!((ids, n), (vec![0, 1, 2, 3, 4], 5));
    // far from the origin the cells stay coarser than the coordinates' rounding
    let far = [[1e12, 0.0, 0.0], [1e12 + 1e-4, 0.0, 0.0]];
    assert_eq!(weld_points(&far, 1e-300).1, 2);
    assert_eq!(weld_points(&far, 1e-3).1, 1);
}
