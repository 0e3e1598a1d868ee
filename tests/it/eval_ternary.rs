//! Evaluation of TPS (primal ternary bi-2) at `(face, u, v)`: a vertex's patch covers the
//! quarter of each face around it (four pieces of one patch), ring `l` of an extraordinary
//! vertex the band between `3^-l` and `3^-(l-1)` of each sector's quarter (children in thirds
//! of the quarter's corner cells, `bezier::domain`), the cap the square `[0, 3^-K]^2` inside
//! the last ring. Tests: agreement with the patches `subdivide --rings` writes at random points
//! of every face (caps included; quarters at boundary vertices are errors), continuity across
//! the lines of the `1 / (2 3^m)` grid of every face (a piece in the wrong third or turned the
//! wrong way jumps there), and convergence to the limit point at the rate of TPS's subdominant
//! eigenvalue per ring, without `--rings`.

use fairsub::analysis::report;
use fairsub::geom::dist;
use fairsub::schemes::registry::{ids, registry};

// `limit_along` samples at 2^-k and asks for 12 rings; TPS's rings shrink by 3, so the
// convergence test below samples at 3^-k itself
use crate::eval_helpers::faces;
use crate::eval_helpers::ratios;
#[allow(dead_code)]
use crate::eval_helpers::support;
use faces::{all_agree, all_continuous, largest_jump, surface_of};
use ratios::{error_ratios, limit_at_ratio};
use support::{gallery, toward_ev};

#[test]
fn tps_eval_agrees_with_the_written_patches() {
    // closed nets (the cube's valence-3 corners are separated by one whole-net step first,
    // so its cells are thirds of the input faces) and c-nets with a boundary (valences 3, 5, 6)
    let nets = [
        "cube",
        "torus-evs",
        "cnet-3-saddle",
        "cnet-5-saddle",
        "cnet-6-convex",
    ];
    all_agree(&[ids::TPS.name()], &nets, &[1, 2, 3, 2, 1], &|_, _| true);
}

#[test]
fn tps_evaluation_is_continuous_across_patch_boundaries() {
    // quarters at 1/2, thirds of the faces after a separating step at 1/3, ring cells at
    // 1 / (2 3^l) and 1 / (6 3^l): all on the grid of 1 / (2 3^5)
    for (net, rings) in [("cube", 3), ("torus-evs", 3)] {
        let (mesh, s) = surface_of(gallery(net), ids::TPS.name(), rings);
        let jump = largest_jump(&mesh, &s, 2 * 243, 1e-10, &|_, _| true);
        eprintln!("{net} under tps, {rings} rings: largest jump {jump:.3e}");
        assert!(jump < 1e-7, "{net}: jump {jump:e}");
    }
    // and across the dyadic lines i 2^-6 (the quarters' edges at 1/2 among them)
    all_continuous(&[ids::TPS.name()], &["cube", "torus-evs"]);
    // and on c-nets, the quarters at boundary vertices included
    all_continuous(&[ids::TPS.name()], &["cnet-5-saddle", "cnet-3-saddle"]);
}

#[test]
fn tps_limit_evaluation_converges_at_rate_lambda() {
    let spec = registry().lookup(ids::TPS.name()).expect("scheme");
    for n in [3, 5, 6] {
        let lambda = report::analyze(&spec, n, false)
            .expect("analysis")
            .spectrum
            .lambda;
        let mesh = gallery(&format!("cnet-{n}-saddle"));
        let (_, at) = toward_ev(&mesh, n);
        // points at 3^-k of the face, k = 2..=10, then the vertex itself
        let (evals, rings) = limit_at_ratio(ids::TPS.name(), &mesh, &at, 1.0 / 3.0, 10, 10);
        let (centre, ratios) = error_ratios(&evals);
        eprintln!("tps n = {n}: {rings} rings, lambda {lambda:.6}, error ratios {ratios:.6?}");
        for (k, ratio) in ratios.iter().enumerate().skip(2) {
            assert!(
                (ratio / lambda - 1.0).abs() < 0.05,
                "n = {n}: error ratio {ratio} at k = {}, lambda {lambda}",
                k + 3
            );
        }
        // the centre is TPS's limit point (21) over the vertex's 1-ring
        let (ev, _) = toward_ev(&mesh, n);
        let lim = ratios::tps_limit_point(&mesh, ev, n);
        assert!(dist(centre, lim) < 1e-12, "n = {n}: {centre:?} {lim:?}");
    }
}
