//! Evaluation at `(face, u, v)` of the schemes made evaluable after the dual schemes: PGS after
//! DS^CC steps (`pgs-dscc`), whose refined net's vertices carry the input faces' cells, and
//! `bi2-mixed` at its PGS facets (regular patches as Doo-Sabin's, the facet's rings in its
//! sub-faces and the quarters of the quads at its corners; a TPS vertex's rings in thirds of
//! its quarters, as in `tps`; poles in their fan triangles). Tests as for the other schemes:
//! agreement with the patches `subdivide --rings` writes at random points of every face (caps
//! included), continuity across every line of a dyadic grid of every face, convergence to the limit point at the scheme's `lambda` per ring;
//! and `bi2-mixed` against `pgs` on a DS-net, where both have the same rings.

use fairsub::bezier::complex::Provenance;
use fairsub::geom::dist;
use fairsub::mesh::PolyMesh;
use fairsub::schemes::bi2::mixed::fig15_like_net;
use fairsub::schemes::bi2::pgs::ds_net;
use fairsub::schemes::registry::ids;

use crate::eval_helpers::faces;
use crate::eval_helpers::ratios;
use crate::eval_helpers::support;
use faces::{
    agrees_with, all_agree, all_continuous, face_points, jump_across, largest_jump, surface_of,
};
use ratios::lambda;
use support::{gallery, toward_ev, via_obj, written_from};

/// The error ratios of the limit evaluation along `at` ([`ratios::converges`]: asserted to
/// be `lambda` within 10% from k = 6).
fn converges(
    scheme: &str,
    mesh: &PolyMesh,
    at: impl Fn(f64) -> (u32, f64, f64),
    lambda: f64,
    min_rings: usize,
    what: &str,
) -> Vec<f64> {
    ratios::converges(scheme, mesh, at, lambda, min_rings, what).1
}

#[test]
fn pgs_dscc_eval_agrees_with_the_written_patches() {
    all_agree(
        &[ids::PGS_DSCC.name()],
        &["cube", "prism-5", "tetrahedron", "cnet-5-saddle"],
        &[1, 2, 1, 2],
        // the DS^CC steps carry the quarters at boundary vertices into the corner points
        // (until 2026-12-04 they were errors)
        &|_, _| true,
    );
}

#[test]
fn pgs_dscc_evaluation_is_continuous_across_patch_boundaries() {
    all_continuous(&[ids::PGS_DSCC.name()], &["cube", "prism-5", "tetrahedron"]);
}

#[test]
fn pgs_dscc_limit_evaluation_converges_at_rate_lambda() {
    // two DS^CC steps turn the vertex of valence n into an n-gon facet, which PGS's rings
    // close at its own lambda_sub
    let scheme = ids::PGS_DSCC.name();
    for n in [3, 5, 6] {
        let mesh = gallery(&format!("cnet-{n}-saddle"));
        let (_, at) = toward_ev(&mesh, n);
        converges(
            scheme,
            &mesh,
            at,
            lambda(ids::PGS.name(), n),
            10,
            &format!("vertex n = {n}"),
        );
    }
}

/// A DS-net of an `n`-gon (the facet and two rings of quads, a boundary), curved.
fn dsnet(n: usize) -> PolyMesh {
    ds_net(n, |x, y| -0.15 * (x * x + y * y) + 0.05 * x * y).expect("DS-net")
}

#[test]
fn bi2_mixed_eval_agrees_with_the_written_patches() {
    let scheme = ids::BI2_MIXED.name();
    for (name, net, rings) in [
        ("dsnet-5", dsnet(5), 2),
        ("dsnet-3", dsnet(3), 3),
        ("fig15-5", fig15_like_net(5).expect("net"), 2),
    ] {
        let (mesh, src) = via_obj(&net, name);
        let written = written_from(&src, name, scheme, rings);
        let (mesh, s) = surface_of(mesh, scheme, rings);
        // every point, TPS vertices included (their rings in thirds of their quarters, as in
        // `tps`; errors before 2026-12-04)
        let (worst, in_caps) = agrees_with(&written, &mesh, &s, &|_, _| true);
        eprintln!(
            "{name} under {scheme}, {rings} rings: largest difference {worst:.3e}, {in_caps} points on caps"
        );
        assert!(worst <= 1e-12, "{name}: {worst:e}");
        assert!(in_caps > 0, "{name}: no point on a cap");
    }
}

#[test]
fn bi2_mixed_evaluation_is_continuous_across_patch_boundaries() {
    for (name, net) in [
        ("dsnet-5", dsnet(5)),
        ("fig15-5", fig15_like_net(5).expect("net")),
    ] {
        let (mesh, s) = surface_of(net, ids::BI2_MIXED.name(), 3);
        let jump = largest_jump(&mesh, &s, 1 << 6, 1e-10, &|_, _| true);
        eprintln!("{name} under bi2-mixed: largest jump {jump:.3e}");
        assert!(jump < 1e-7, "{name}: jump {jump:e}");
        // the ring lines of a TPS vertex's quarters: k 3^-l / 2 from the face's corners
        let mut xs = Vec::new();
        for l in 1..=4 {
            for k in [1.0, 2.0] {
                let x = 0.5 * k * 3f64.powi(-l);
                xs.extend([x, 1.0 - x]);
            }
        }
        let jump = jump_across(&mesh, &s, &xs, 1e-10, &|_, _| true);
        eprintln!("{name} under bi2-mixed: largest jump across TPS ring lines {jump:.3e}");
        assert!(jump < 1e-7, "{name}: jump {jump:e}");
    }
}

/// On a DS-net `bi2-mixed`'s local-net rings are PGS's rings (tests/it/bi2.rs), so outside the
/// caps the two evaluate to the same points at the same face parameters, although their
/// domains are built apart (PGS's through the adaptive host's cells, bi2-mixed's from the
/// DS-net's chart).
#[test]
fn bi2_mixed_equals_pgs_on_a_ds_net() {
    for n in [3, 5, 6] {
        let (mesh, mixed) = surface_of(dsnet(n), ids::BI2_MIXED.name(), 3);
        let (_, pgs) = surface_of(dsnet(n), ids::PGS.name(), 3);
        let mut worst: f64 = 0.0;
        let mut compared = 0;
        for p in face_points(&mesh, 60, 5) {
            let a = mixed.evaluate(p.0, p.1, p.2).expect("bi2-mixed point");
            let b = pgs.evaluate(p.0, p.1, p.2).expect("pgs point");
            let cap = |s: &fairsub::surface::eval::Surface, i: usize| {
                matches!(s.complex().provenance[i], Provenance::Cap { .. })
            };
            if cap(&mixed, a.patch) || cap(&pgs, b.patch) {
                continue;
            }
            worst = worst.max(dist(a.point, b.point));
            worst = worst.max(dist(a.du, b.du)).max(dist(a.dv, b.dv));
            compared += 1;
        }
        eprintln!("n = {n}: {compared} points, largest difference {worst:.3e}");
        assert!(compared > 100, "n = {n}: {compared} points");
        assert!(worst < 1e-12, "n = {n}: {worst:e}");
    }
}

#[test]
fn bi2_mixed_limit_evaluation_converges_at_rate_lambda() {
    // toward the centre (1, 1) of the last sub-face of the facet (face 0 of the DS-net; u = n
    // on its strip, where u = 1 would be sub-face 1's corner 0)
    let scheme = ids::BI2_MIXED.name();
    for n in [5, 6] {
        let mesh = dsnet(n);
        let at = |h: f64| (0u32, n as f64 - 0.6 * h, 1.0 - 0.3 * h);
        converges(
            scheme,
            &mesh,
            at,
            lambda(ids::PGS.name(), n),
            12,
            &format!("facet n = {n}"),
        );
    }
}

/// `bi2-mixed` and `polar-bi2` at the TPS vertex of a c-net (their rings in thirds of its
/// quarters since 2026-12-04): without `--rings` the error to the vertex shrinks by TPS's
/// `lambda` per ring (points at `3^-k` of the face), and the centre is `tps`'s.
#[test]
fn tps_vertices_of_mixed_nets_converge_at_rate_lambda() {
    for n in [3, 5, 6] {
        let mesh = gallery(&format!("cnet-{n}-saddle"));
        let (_, at) = toward_ev(&mesh, n);
        let tps_lambda = lambda(ids::TPS.name(), n);
        let (tps_centre, ..) = ratios::converges_at_ratio(
            ids::TPS.name(),
            &mesh,
            &at,
            (1.0 / 3.0, 10),
            10,
            tps_lambda,
            &format!("vertex n = {n}"),
        );
        for scheme in [ids::BI2_MIXED.name(), ids::POLAR_BI2.name()] {
            let (centre, ..) = ratios::converges_at_ratio(
                scheme,
                &mesh,
                &at,
                (1.0 / 3.0, 10),
                10,
                tps_lambda,
                &format!("TPS vertex n = {n}"),
            );
            assert!(dist(centre, tps_centre) < 1e-12, "{scheme}, n = {n}");
        }
    }
}
