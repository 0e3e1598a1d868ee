//! Guided subdivision acceptance: the G^2 guide space, the spectrum of table (5), continuity
//! certificates of the rings, caps and surroundings, and bounded curvature on the gallery nets.

use fairsub::schemes::guided::guide::{
    GuideDegree, GuideSpace, constraint_matrix, g2_defect, n_star, shear_coeffs,
};
use nalgebra::DMatrix;

/// A deterministic pseudo-random matrix.
fn random(rows: usize, cols: usize, seed: u64) -> DMatrix<f64> {
    let mut s = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    DMatrix::from_fn(rows, cols, |_, _| {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    })
}

#[test]
fn shear_satisfies_the_constraints() {
    for n in 3..=16 {
        for d in [3, 4, 5] {
            let l = shear_coeffs(n, d);
            let defect = g2_defect(n, d, &l);
            assert!(
                defect < 1e-13,
                "n={n} d={d}: L violates (1)-(2) by {defect}"
            );
            let res = (constraint_matrix(n, d) * &l).amax();
            assert!(res < 1e-12, "n={n} d={d}: {res}");
        }
    }
}

#[test]
fn paper_coordinates_span_the_g2_space() {
    for n in (3..=12).filter(|&n| n != 4) {
        let space = GuideSpace::paper_bi5(n).unwrap();
        assert_eq!(space.dim(), 17 * n + n_star(n) + 6, "n={n}");
        assert_eq!(space.dim(), GuideDegree::Bi5.paper_count(n));
        // Random elements are G^2 (measured along every ray).
        let p = random(space.dim(), 3, n as u64);
        let g = space.guide(&p);
        let defect = g2_defect(n, 5, &g);
        assert!(defect < 1e-11, "n={n}: G^2 defect {defect}");
        // The coordinates are coordinates: extract o basis = I.
        let id = &space.extract * &space.basis;
        let e = (id - DMatrix::identity(space.dim(), space.dim())).amax();
        assert!(e < 1e-11, "n={n}: {e}");
        // The whole null space of (1)-(2) is reached: same dimension as the numeric space.
        let numeric = GuideSpace::numeric(n, 5).unwrap();
        assert_eq!(numeric.dim(), space.dim(), "n={n}");
        // L is in the space and its coordinates give it back.
        let l = shear_coeffs(n, 5);
        let back = space.guide(&(&space.extract * &l));
        let e = (back - l).amax();
        assert!(e < 1e-11, "n={n}: L reproduced to {e}");
    }
}

#[test]
fn lower_degree_guides_have_the_paper_counts() {
    for n in (3..=10).filter(|&n| n != 4) {
        for deg in [GuideDegree::Bi4, GuideDegree::Bi3] {
            let s = GuideSpace::new(n, deg).unwrap();
            assert_eq!(s.dim(), deg.paper_count(n), "n={n} {deg:?}");
            let g = s.guide(&random(s.dim(), 2, 7));
            assert!(g2_defect(n, deg.degree(), &g) < 1e-10);
        }
    }
}
