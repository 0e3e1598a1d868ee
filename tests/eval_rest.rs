//! Evaluation at `(face, u, v)` of the schemes evaluated last: the guided macro-patch variants
//! (`guided-bi4-macro`: each ring patch's 2 x 2 bi-4 pieces on the dyadic quarters of its
//! square, `guided-bi3-macro`: 3 x 3 bi-3 pieces on its thirds, and their split G^1 caps laid
//! out the same way). Tests: agreement with the patches `subdivide --rings` writes at random
//! points of every face (caps included), continuity across the lines of the cells (a piece in
//! the wrong quarter or third, or transposed, jumps there), and convergence to the limit point
//! at the rate of the characteristic map's `lambda` per ring, without `--rings`.

use fairsub::schemes::catmull_clark::catmull_clark_lambda;
use fairsub::schemes::registry::ids;

#[allow(dead_code)]
#[path = "eval/support.rs"]
mod support;
use support::{gallery, limit_along, toward_ev};
#[allow(dead_code)]
#[path = "eval/faces.rs"]
mod faces;
use faces::{all_agree, largest_jump, surface_of};
#[path = "eval/ratios.rs"]
mod ratios;
use ratios::error_ratios;

fn macro_schemes() -> [&'static str; 2] {
    [ids::GUIDED_BI4_MACRO.name(), ids::GUIDED_BI3_MACRO.name()]
}

#[test]
fn guided_macro_eval_agrees_with_the_written_patches() {
    let nets = [
        "cnet-5-saddle",
        "cnet-3-convex",
        "cube",
        "prism-5",
        "torus-evs",
    ];
    all_agree(&macro_schemes(), &nets, &[1, 2, 3, 1, 2], &|_, _| true);
}

#[test]
fn guided_macro_evaluation_is_continuous_across_piece_boundaries() {
    // ring squares at 2^-l, their quarters at 2^-(l+1) and thirds at 2^-l / 3: all on the
    // lines i / (3 2^6) for the 3 rings (prism-5: one Catmull-Clark step first)
    for scheme in macro_schemes() {
        for net in ["cnet-5-saddle", "cube", "prism-5"] {
            let (mesh, s) = surface_of(gallery(net), scheme, 3);
            let jump = largest_jump(&mesh, &s, 3 << 6, 1e-10, &|_, _| true);
            eprintln!("{net} under {scheme}: largest jump {jump:.3e}");
            assert!(jump < 1e-7, "{net} under {scheme}: jump {jump:e}");
        }
    }
}

#[test]
fn guided_macro_limit_evaluation_converges_at_rate_lambda() {
    for scheme in macro_schemes() {
        for n in [3, 5] {
            let lambda = catmull_clark_lambda(n);
            let mesh = gallery(&format!("cnet-{n}-saddle"));
            let (_, at) = toward_ev(&mesh, n);
            let evals = limit_along(scheme, &mesh, &at, 12);
            let (_, ratios) = error_ratios(&evals);
            eprintln!("{scheme} n = {n}: lambda {lambda:.6}, error ratios {ratios:.6?}");
            for (k, ratio) in ratios.iter().enumerate().skip(3) {
                assert!(
                    (ratio / lambda - 1.0).abs() < 0.05,
                    "{scheme} n = {n}: error ratio {ratio} at k = {}, lambda {lambda}",
                    k + 3
                );
            }
        }
    }
}
