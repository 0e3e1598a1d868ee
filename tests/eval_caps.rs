//! Evaluation of the cap schemes (EG, QAS+ and its variants) at `(face, u, v)`: their rings tile
//! each sector's face dyadically in the d-net's chart, so a face point lies on one ring or cap
//! patch. Tests: agreement with the patches `subdivide --rings` writes at random points of every
//! face (caps included), continuity of the evaluation across every patch boundary of the tiling
//! (a patch placed in the wrong square or with a transposed or rotated parameter jumps there),
//! and convergence to the limit point at the rate of the scheme's subdominant eigenvalue.

use fairsub::geom::{Point, dist, norm, sub};
use fairsub::mesh::PolyMesh;
use fairsub::schemes::catmull_clark::catmull_clark_lambda;
use fairsub::schemes::registry::{ids, registry};
use fairsub::surface::ComplexOptions;
use fairsub::surface::eval::{Surface, evaluate_limit};

#[path = "eval/support.rs"]
mod support;
use support::{gallery, toward_ev};
#[path = "eval/faces.rs"]
mod faces;
use faces::{agrees_with_written, largest_jump, surface};

const NETS: [&str; 5] = [
    "cnet-5-saddle",
    "cnet-3-convex",
    "cube",
    "prism-5",
    "torus-evs",
];

fn cap_schemes() -> [&'static str; 7] {
    [
        ids::GUIDED_BI5.name(),
        ids::GUIDED_BI6.name(),
        ids::EG.name(),
        ids::QAS_PLUS.name(),
        ids::QAS_PLUS_BI3.name(),
        ids::QAS_04.name(),
        ids::QAS_05_04.name(),
    ]
}

#[test]
fn cap_schemes_eval_agrees_with_the_written_patches() {
    for scheme in cap_schemes() {
        for (k, net) in NETS.iter().enumerate() {
            let rings = 1 + k % 3;
            let (worst, in_caps) = agrees_with_written(net, scheme, rings, &|_, _| true);
            eprintln!(
                "{net} under {scheme}, {rings} rings: largest difference {worst:.3e}, {in_caps} points on caps"
            );
            assert!(worst <= 1e-12, "{net} under {scheme}: {worst:e}");
            assert!(in_caps > 0, "{net} under {scheme}: no point on a cap");
        }
    }
}

#[test]
fn cap_scheme_evaluation_is_continuous_across_patch_boundaries() {
    for scheme in cap_schemes() {
        for net in ["cnet-5-saddle", "cube", "prism-5"] {
            let (mesh, s) = surface(net, scheme, 3);
            // the tiling's lines go down to 2^-4 (prism-5: one local Catmull-Clark step, then
            // 3 rings, QAS+^3's quarters one level more)
            let jump = largest_jump(&mesh, &s, 6, 1e-10);
            eprintln!("{net} under {scheme}: largest jump {jump:.3e}");
            assert!(jump < 1e-7, "{net} under {scheme}: jump {jump:e}");
        }
    }
}

/// EG's limit point `c0` of the c-net of `ev` by the paper's formula (3).
fn eg_limit_point(mesh: &PolyMesh, ev: usize) -> Point {
    let n = mesh.valence(ev);
    let idx = mesh.cnet_indices(ev, 2).expect("c-net");
    let pts: Vec<Point> = idx.iter().map(|&w| mesh.position(w as usize)).collect();
    fairsub::schemes::eg::from_cnet(n)
        .expect("stencils")
        .apply(&pts)[0]
}

#[test]
fn cap_scheme_limit_evaluation_converges_at_rate_lambda() {
    for (scheme, n, lambda) in [
        (ids::EG.name(), 3, None),
        (ids::EG.name(), 5, None),
        (ids::QAS_PLUS.name(), 5, Some(0.5)),
        (ids::QAS_PLUS.name(), 6, Some(0.5)),
        (ids::QAS_04.name(), 5, Some(0.4)),
        (ids::GUIDED_BI5.name(), 5, Some(catmull_clark_lambda(5))),
        (ids::GUIDED_BI6.name(), 3, Some(catmull_clark_lambda(3))),
    ] {
        let mesh = gallery(&format!("cnet-{n}-saddle"));
        let (ev, at) = toward_ev(&mesh, n);
        let ks: Vec<i32> = (2..=12).collect();
        let mut pts: Vec<(u32, f64, f64)> = ks.iter().map(|&k| at(0.5f64.powi(k))).collect();
        pts.push(at(0.0));
        let spec = registry().lookup(scheme).expect("scheme");
        let (evals, rings) = evaluate_limit(&pts, &mut |k| {
            Surface::build(
                &spec,
                &mesh,
                ComplexOptions {
                    rings: k,
                    fill: true,
                },
            )
        })
        .expect("limit evaluation");
        assert!(rings >= 12, "{scheme} n = {n}: {rings} rings");
        let centre = evals.last().expect("the centre").point;
        let lambda = match lambda {
            Some(l) => l,
            None => {
                // EG: the centre is c0 of (3), lambda that of the rules' characteristic ring
                let c0 = eg_limit_point(&mesh, ev);
                assert!(dist(centre, c0) < 1e-12, "{scheme} n = {n}: limit point");
                fairsub::schemes::eg::local::characteristic_ring(n)
                    .expect("rules")
                    .1
            }
        };
        let err: Vec<f64> = evals[..ks.len()]
            .iter()
            .map(|e| norm(sub(e.point, centre)))
            .collect();
        let ratios: Vec<f64> = err.windows(2).map(|w| w[1] / w[0]).collect();
        eprintln!("{scheme} n = {n}: lambda {lambda:.6}, {rings} rings, error ratios {ratios:.6?}");
        for k in 4..err.len() - 1 {
            let ratio = err[k + 1] / err[k];
            assert!(
                (ratio / lambda - 1.0).abs() < 0.1,
                "{scheme} n = {n}: error ratio {ratio} at k = {}, lambda {lambda}",
                ks[k]
            );
        }
    }
}
