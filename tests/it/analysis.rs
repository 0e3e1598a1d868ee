//! Analysis acceptance: spectra and limit stencils of the classic schemes, computed from the
//! schemes' own refinement stencils, against their closed forms.

use fairsub::analysis::{self, local};
use std::f64::consts::PI;

#[test]
fn catmull_clark_lambda_matches_closed_form_n3_to_16() {
    for n in 3..=16 {
        let lm = local::catmull_clark(n).unwrap();
        assert!(lm.rotation_defect() < 1e-15);
        let s = analysis::spectrum(&lm.matrix);
        assert!(
            (s.dominant - 1.0).abs() < 1e-12,
            "n={n}: dominant {}",
            s.dominant
        );
        let expect = analysis::catmull_clark_lambda(n);
        assert!(
            (s.lambda - expect).abs() < 1e-12,
            "n={n}: lambda {} vs {}",
            s.lambda,
            expect
        );
        assert_eq!(s.lambda_multiplicity, 2, "n={n}");
    }
}

#[test]
fn catmull_clark_limit_stencil_is_the_published_formula() {
    for n in 3..=10 {
        let lm = local::catmull_clark(n).unwrap();
        let w = lm.limit_stencil().unwrap();
        let nf = n as f64;
        let d = nf * (nf + 5.0);
        assert!((w[0] - nf * nf / d).abs() < 1e-12, "n={n} centre {}", w[0]);
        for s in 0..n {
            // Sector layout: (i, j) for i = 1, 2 and j = 0, 1, 2 -> offsets 0..6.
            let base = 1 + 6 * s;
            let at = |i: usize, j: usize| w[base + (i - 1) * 3 + j];
            assert!((at(1, 0) - 4.0 / d).abs() < 1e-12, "edge neighbour");
            assert!((at(1, 1) - 1.0 / d).abs() < 1e-12, "face neighbour");
            for (i, j) in [(1, 2), (2, 0), (2, 1), (2, 2)] {
                assert!(
                    at(i, j).abs() < 1e-12,
                    "outer weight ({i},{j}) = {}",
                    at(i, j)
                );
            }
        }
    }
}

#[test]
fn doo_sabin_facet_blocks() {
    for n in 3..=10 {
        let lm = local::doo_sabin_facet(n).unwrap();
        let s = analysis::spectrum(&lm.matrix);
        let ev = &s.eigenvalues;
        assert!((ev[0].re - 1.0).abs() < 1e-12 && ev[0].multiplicity == 1);
        assert!(
            (ev[1].re - 0.5).abs() < 1e-12 && ev[1].multiplicity == 2,
            "n={n}: {ev:?}"
        );
        if n > 3 {
            assert!(
                (ev[2].re - 0.25).abs() < 1e-12 && ev[2].multiplicity == n - 3,
                "n={n}: {ev:?}"
            );
        }
    }
}

#[test]
fn loop_one_ring_spectrum() {
    // Loop's one-ring matrix: 1, 5/8 - n beta, and 3/8 + cos(2 pi k / n) / 4 for k = 1..n-1.
    for n in 3..=12 {
        let lm = local::loop_one_ring(n).unwrap();
        let nf = n as f64;
        let beta = (5.0 / 8.0 - (3.0 / 8.0 + (2.0 * PI / nf).cos() / 4.0).powi(2)) / nf;
        let mut expect: Vec<f64> = vec![1.0, 5.0 / 8.0 - nf * beta];
        for k in 1..n {
            expect.push(3.0 / 8.0 + (2.0 * PI * k as f64 / nf).cos() / 4.0);
        }
        let mut got: Vec<f64> = analysis::eigenvalues(&lm.matrix)
            .iter()
            .map(|z| z.re)
            .collect();
        for z in analysis::eigenvalues(&lm.matrix) {
            assert!(z.im.abs() < 1e-12);
        }
        got.sort_by(f64::total_cmp);
        expect.sort_by(f64::total_cmp);
        for (g, e) in got.iter().zip(&expect) {
            assert!((g - e).abs() < 1e-12, "n={n}: {got:?} vs {expect:?}");
        }
        let s = analysis::spectrum(&lm.matrix);
        assert!((s.lambda - (3.0 / 8.0 + (2.0 * PI / nf).cos() / 4.0)).abs() < 1e-12);
    }
}

#[test]
fn fourier_blocks_reassemble_the_spectrum() {
    for n in [3, 5, 7] {
        let lm = local::catmull_clark(n).unwrap();
        let mut all: Vec<analysis::C64> = Vec::new();
        for b in lm.fourier_blocks().unwrap() {
            all.extend(b.eigenvalues());
        }
        let mut a: Vec<f64> = all.iter().map(|z| z.norm()).collect();
        let mut b: Vec<f64> = analysis::eigenvalues(&lm.matrix)
            .iter()
            .map(|z| z.norm())
            .collect();
        a.sort_by(f64::total_cmp);
        b.sort_by(f64::total_cmp);
        assert_eq!(a.len(), b.len());
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() < 1e-8, "n={n}");
        }
        // lambda lies in the frequency-1 block.
        let blocks = lm.fourier_blocks().unwrap();
        let lam = analysis::catmull_clark_lambda(n);
        assert!(
            blocks[1]
                .eigenvalues()
                .iter()
                .any(|z| (z.re - lam).abs() < 1e-10 && z.im.abs() < 1e-10)
        );
    }
}

#[test]
fn catmull_clark_characteristic_maps_are_injective_n3_to_16() {
    for n in 3..=16 {
        let (ring, lambda) = local::characteristic_ring("catmull-clark", n).unwrap();
        let cert = fairsub::analysis::certify::certify_ring(&ring, lambda);
        assert!(cert.injective, "n={n}: {cert:?}");
        assert!(cert.jacobian_min_coefficient > 0.0);
        assert_eq!(cert.windings, vec![1, -1]);
    }
}

#[test]
fn a_folded_ring_is_refuted() {
    // Mirror one patch of the ring: the Jacobian of that patch is negative.
    let (mut ring, lambda) = local::characteristic_ring("catmull-clark", 5).unwrap();
    ring[0] = ring[0].reversed_u();
    let cert = fairsub::analysis::certify::certify_ring(&ring, lambda);
    assert!(!cert.jacobian_positive && !cert.injective);
}

#[test]
fn replicated_centre_form_keeps_the_spectrum() {
    for n in [3, 5, 6] {
        let lm = local::catmull_clark(n).unwrap();
        let rep = lm.replicated_centre();
        assert_eq!(rep.matrix.nrows(), n * 7);
        assert!(rep.rotation_defect() < 1e-15);
        let nonzero = |v: Vec<analysis::C64>| {
            let mut m: Vec<f64> = v.iter().map(|z| z.norm()).filter(|&x| x > 1e-9).collect();
            m.sort_by(f64::total_cmp);
            m
        };
        let a = nonzero(analysis::eigenvalues(&lm.matrix));
        let b = nonzero(analysis::eigenvalues(&rep.matrix));
        assert_eq!(a.len(), b.len());
        for (x, y) in a.iter().zip(&b) {
            assert!((x - y).abs() < 1e-9);
        }
        // Every Fourier block has the same size; lambda sits in block 1.
        let blocks = rep.fourier_blocks().unwrap();
        assert!(blocks.iter().all(|b| b.matrix.nrows() == 7));
        let lam = analysis::catmull_clark_lambda(n);
        assert!(
            blocks[1]
                .eigenvalues()
                .iter()
                .any(|z| (z.re - lam).abs() < 1e-10)
        );
    }
}
