//! Evaluation of the cap schemes (EG, QAS+ and its variants) at `(face, u, v)`: their rings tile
//! each sector's face dyadically in the d-net's chart, so a face point lies on one ring or cap
//! patch. Tests: agreement with the patches `subdivide --rings` writes at random points of every
//! face (caps included), continuity of the evaluation across every patch boundary of the tiling
//! (a patch placed in the wrong square or with a transposed or rotated parameter jumps there),
//! and convergence to the limit point at the rate of the scheme's subdominant eigenvalue.

use fairsub::geom::{Point, dist, norm, sub};
use fairsub::mesh::PolyMesh;
use fairsub::schemes::catmull_clark::catmull_clark_lambda;
use fairsub::schemes::registry::ids;

use crate::eval_helpers::faces;
use crate::eval_helpers::support;
use faces::{all_agree, all_continuous};
use support::{gallery, limit_along, toward_ev};

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
    all_agree(&cap_schemes(), &NETS, &[1, 2, 3, 1, 2], &|_, _| true);
}

#[test]
fn cap_scheme_evaluation_is_continuous_across_patch_boundaries() {
    // the tiling's lines go down to 2^-4 (prism-5: one local Catmull-Clark step, then 3
    // rings, QAS+^3's quarters one level more)
    all_continuous(&cap_schemes(), &["cnet-5-saddle", "cube", "prism-5"]);
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
        let evals = limit_along(scheme, &mesh, &at, 12);
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
        let err: Vec<f64> = evals[..evals.len() - 1]
            .iter()
            .map(|e| norm(sub(e.point, centre)))
            .collect();
        let ratios: Vec<f64> = err.windows(2).map(|w| w[1] / w[0]).collect();
        eprintln!("{scheme} n = {n}: lambda {lambda:.6}, error ratios {ratios:.6?}");
        for k in 4..err.len() - 1 {
            let ratio = err[k + 1] / err[k];
            assert!(
                (ratio / lambda - 1.0).abs() < 0.1,
                "{scheme} n = {n}: error ratio {ratio} at k = {}, lambda {lambda}",
                k + 2
            );
        }
    }
}
