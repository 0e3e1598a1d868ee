//! Split-sector caps ([`Layout::Split`]): the conditions checked on the caps of random
//! compatible data (C^1 to every data piece, C^0 and the spoke relation on every spoke piece,
//! C^2 between the pieces of a sector), and the lowest certified degrees.

use super::system::{inner_rows, piece, spoke_rows, weight_part};
use super::tests::{Lcg, random_split_hole};
use super::*;
use crate::bezier::BezierCurve;
use crate::geom::{Point, add, axpy, norm, sub};

#[crate::unit::test]
fn random_compatible_data_give_split_g1_caps() {
    let mut rng = Lcg(5);
    for (m, n) in [(2, 3), (2, 5), (2, 6), (3, 5)] {
        let d = 5;
        let hole = random_split_hole(n, d, m, 0.0, &mut rng);
        let cap = g1_cap_with(
            &hole,
            CapOptions {
                degree: Some(d),
                centre: Centre::TangentPlane,
            },
        )
        .unwrap();
        let p = &cap.patches;
        assert_eq!(p.len(), n * m * m);
        let x: Vec<Point> = p.iter().flat_map(|b| b.cps.iter().copied()).collect();
        let size = hole.data().iter().map(|p| norm(*p)).fold(0.0, f64::max);
        let resid =
            |r: &Vec<(usize, f64)>| norm(r.iter().fold([0.0; 3], |a, &(c, w)| axpy(a, w, x[c])));
        for s in 0..n {
            let q = (s + n - 1) % n;
            for k in 0..m {
                let (ps, pq) = (piece(m, s, k, 0), piece(m, q, 0, k));
                for r in spoke_rows(
                    d,
                    weight_part(n, super::hole::Fan::Closed, (0.0, 0.0), m, k),
                    ps,
                    pq,
                ) {
                    assert!(resid(&r) < 1e-10 * size, "m {m} n {n} spoke {s} piece {k}");
                }
                for i in 0..=10 {
                    let t = i as f64 / 10.0;
                    assert!(norm(sub(p[ps].eval(t, 0.0), p[pq].eval(0.0, t))) < 1e-10 * size);
                    // C^1 to the data of piece k of side a (piece-local cross derivative)
                    let a = &hole.sectors[s][k];
                    let pa = &p[piece(m, s, m - 1, k)];
                    let want = BezierCurve::new(a.cross.clone()).eval(t);
                    assert!(norm(add(pa.derivatives(1.0, t).du, want)) < 1e-9 * size);
                    let b = &hole.sectors[s][m + k];
                    let pb = &p[piece(m, s, k, m - 1)];
                    let want = BezierCurve::new(b.cross.clone()).eval(t);
                    assert!(norm(add(pb.derivatives(t, 1.0).dv, want)) < 1e-9 * size);
                }
            }
        }
        for r in inner_rows(n, d, m, 2) {
            assert!(
                resid(&r) < 1e-10 * size,
                "m {m} n {n}: inner join {:e}",
                resid(&r)
            );
        }
    }
}

/// The lowest certified degree of split caps for every valence 3..=16 (segment degree 3 for
/// `m = 2, 3`, as QAS+^3's and guided-bi3-macro's rings; 4 for `m = 2`, as guided-bi4-macro's),
/// printed as the table of the module documentation. Slow (the `m = 3` maps at `n = 16` have
/// 5184 unknowns): `cargo test --release -p fairsub-unit split_lowest -- --ignored --nocapture`.
#[crate::unit::test]
#[ignore = "slow: the table of the module documentation"]
fn split_lowest_certified_degrees() {
    for (m, db) in [(2, 3), (2, 4), (3, 3)] {
        let deg = Degrees {
            boundary: db,
            cross: db,
        };
        for centre in [Centre::TangentPlane, Centre::QuadraticJet] {
            let mut row = Vec::new();
            for n in 3..=16 {
                let d = lowest_certified_degree(n, Layout::Split(m), deg, centre).unwrap();
                let map = cap_map(n, Layout::Split(m), deg, d, centre).unwrap();
                row.push(format!("{n}:{d}({:.0e})", map.certificate));
                // never lower than the one-patch cap: the centre piece meets the same
                // enclosure conditions (module documentation)
                assert!(d >= 4 || n == 4, "m {m} n {n}: {d}");
                assert!(d <= 5, "m {m} n {n}: {d}");
            }
            eprintln!("split {m} data {db} {centre:?}: {}", row.join(" "));
        }
    }
}
