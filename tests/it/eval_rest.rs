//! Evaluation at `(face, u, v)` of the schemes evaluated last: the guided macro-patch variants
//! (`guided-bi4-macro`: each ring patch's 2 x 2 bi-4 pieces on the dyadic quarters of its
//! square, `guided-bi3-macro`: 3 x 3 bi-3 pieces on its thirds, and their split G^1 caps laid
//! out the same way) and adjustable TPS (`tps-adjustable`: knot coordinates, its rings on the
//! cells of the quarters at extraordinary vertices split 2 x 2 at `s = 1 - 2e`). Tests: agreement with the patches `subdivide --rings` writes at random
//! points of every face (caps included), continuity across the lines of the cells (a piece in
//! the wrong quarter or third, or transposed, jumps there), and convergence to the limit point
//! at the rate of the characteristic map's `lambda` per ring, without `--rings`.

use fairsub::schemes::catmull_clark::catmull_clark_lambda;
use fairsub::schemes::registry::ids;

#[allow(dead_code)]
use crate::eval_helpers::faces;
use crate::eval_helpers::ratios;
#[allow(dead_code)]
use crate::eval_helpers::support;
use faces::{all_agree, jump_across, largest_jump, surface_of};
use ratios::{converges_at_ratio, error_ratios};
use support::{gallery, limit_along, toward_ev};

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

/// `s = 1 - 2e` of adjustable TPS at its default `e = 0.2`.
const S: f64 = 0.6;

#[test]
fn tps_adjustable_eval_agrees_with_the_written_patches() {
    // c-nets, the quarters at boundary vertices included
    let nets = [
        "cnet-3-saddle",
        "cnet-5-saddle",
        "cnet-6-convex",
        "cnet-7-convex",
    ];
    all_agree(
        &[ids::TPS_ADJUSTABLE.name()],
        &nets,
        &[3, 2, 1, 2],
        &|_, _| true,
    );
}

#[test]
fn tps_adjustable_evaluation_is_continuous_across_patch_boundaries() {
    let scheme = ids::TPS_ADJUSTABLE.name();
    // the ring lines of the quarters at the face corners: s^l / 2 and 1 - s^l / 2
    let mut xs = Vec::new();
    for l in 1..=4 {
        let x = 0.5 * S.powi(l);
        xs.extend([x, 1.0 - x]);
    }
    xs.push(0.5);
    for net in ["cnet-3-saddle", "cnet-5-saddle", "cnet-6-convex"] {
        let (mesh, s) = surface_of(gallery(net), scheme, 3);
        let jump = jump_across(&mesh, &s, &xs, 1e-10, &|_, _| true);
        eprintln!("{net} under {scheme}, 3 rings: largest jump across ring lines {jump:.3e}");
        assert!(jump < 1e-7, "{net}: jump {jump:e}");
        let jump = largest_jump(&mesh, &s, 1 << 6, 1e-10, &|_, _| true);
        eprintln!("{net} under {scheme}, 3 rings: largest jump across i 2^-6 {jump:.3e}");
        assert!(jump < 1e-7, "{net}: jump {jump:e}");
    }
}

/// Face parameters are knot coordinates, so first derivatives in `(u, v)` are continuous
/// across ring lines (a chart with other ring sizes would scale them by ring: placing
/// adjustable TPS's pieces in TPS's cells in thirds gives ratios `3 e = 0.6` and
/// `3 (1 - 2e) = 1.8` here, and jumps of 7e-2 in the points). In the quarter of a face at the
/// vertex (`(X, Y)` from the vertex, the quarter `[0, 1]^2`): across `X = 1` inside ring 1's
/// `b` (ring 1 inside, a regular patch outside) and across the corner `(s, s)` of ring 1's and
/// ring 2's `b` on the diagonal.
#[test]
fn tps_adjustable_first_derivatives_are_continuous() {
    let mesh = gallery("cnet-5-saddle");
    let (_, at) = toward_ev(&mesh, 5);
    let (f, _, _) = at(0.0);
    let corner = mesh
        .face(f as usize)
        .iter()
        .position(|&w| mesh.valence(w as usize) == 5)
        .expect("the vertex");
    let c = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let (o, a, b) = (c[corner], c[(corner + 1) % 4], c[(corner + 3) % 4]);
    let point = |x: f64, y: f64| -> (f64, f64) {
        let (x, y) = (x / 2.0, y / 2.0);
        (
            o[0] + x * (a[0] - o[0]) + y * (b[0] - o[0]),
            o[1] + x * (a[1] - o[1]) + y * (b[1] - o[1]),
        )
    };
    for (scheme, s_ring) in [
        (ids::TPS.name(), 1.0 / 3.0),
        (ids::TPS_ADJUSTABLE.name(), S),
    ] {
        let (_, s) = surface_of(mesh.clone(), scheme, 3);
        let d = 1e-9;
        let jet = |x: f64, y: f64| {
            let (u, v) = point(x, y);
            let p = s.evaluate(f, u, v).expect("point");
            [p.du, p.dv]
        };
        let y = 0.5 * (1.0 + s_ring);
        let pairs = [
            (jet(1.0 - d, y), jet(1.0 + d, y)),
            (jet(s_ring - d, s_ring - d), jet(s_ring + d, s_ring + d)),
        ];
        let mut worst: f64 = 0.0;
        for (inner, outer) in pairs {
            for k in 0..2 {
                let rel = fairsub::geom::dist(inner[k], outer[k]) / fairsub::geom::norm(outer[k]);
                worst = worst.max(rel);
            }
        }
        eprintln!("{scheme}: largest relative jump of du, dv across ring lines {worst:.3e}");
        assert!(worst < 1e-6, "{scheme}: {worst:e}");
    }
}

#[test]
fn tps_adjustable_limit_evaluation_converges_at_rate_lambda() {
    for n in [3, 5, 6] {
        let lambda = ratios::lambda(ids::TPS_ADJUSTABLE.name(), n);
        let mesh = gallery(&format!("cnet-{n}-saddle"));
        let (_, at) = toward_ev(&mesh, n);
        // ring k lies at s^k of the quarter
        let what = format!("n = {n}");
        converges_at_ratio(
            ids::TPS_ADJUSTABLE.name(),
            &mesh,
            &at,
            (S, 12),
            12,
            lambda,
            &what,
        );
    }
}

/// The lines of the cells of adjustable TPS on a face of a net refined by `steps` separating
/// whole-net steps (knot coordinates, the input knots uniform): in each direction the centres
/// and the ends of the pieces after the steps (every piece cut `e : 1 - 2e : e`, the face
/// `[0, 1]` spanning from the centre of one input piece to the next), and the ring lines
/// `c -/+ h s^l` around every piece `[c - h, c + h]` (`l = 1..=4`), all inside `(0, 1)`.
fn knot_lines(steps: usize) -> Vec<f64> {
    let e = (1.0 - S) / 2.0;
    let mut pieces = vec![(-0.5, 0.5), (0.5, 1.5)];
    for _ in 0..steps {
        pieces = pieces
            .iter()
            .flat_map(|&(a, b)| {
                let w = b - a;
                [(a, a + e * w), (a + e * w, b - e * w), (b - e * w, b)]
            })
            .collect();
    }
    let mut xs = Vec::new();
    for &(a, b) in &pieces {
        let (c, h) = (0.5 * (a + b), 0.5 * (b - a));
        xs.extend([a, c]);
        for l in 1..=4 {
            xs.extend([c - h * S.powi(l), c + h * S.powi(l)]);
        }
    }
    xs.retain(|&x| x > 1e-9 && x < 1.0 - 1e-9);
    xs.sort_by(f64::total_cmp);
    xs.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    xs
}

/// Nets whose extraordinary vertices are separated by whole-net steps first (the cube's
/// valence-3 corners, torus-evs): the refined net's pieces are rectangles of the input faces
/// at the knots (framed cells), its rings cells of the quarters at the vertices split at `s`.
const SEPARATED: [&str; 2] = ["cube", "torus-evs"];

#[test]
fn tps_adjustable_after_separating_steps_agrees_with_the_written_patches() {
    all_agree(
        &[ids::TPS_ADJUSTABLE.name()],
        &SEPARATED,
        &[1, 2],
        &|_, _| true,
    );
    all_agree(
        &[ids::TPS_ADJUSTABLE.name()],
        &SEPARATED,
        &[3, 1],
        &|_, _| true,
    );
}

#[test]
fn tps_adjustable_after_separating_steps_is_continuous() {
    let scheme = ids::TPS_ADJUSTABLE.name();
    let mut xs = knot_lines(1);
    xs.extend(knot_lines(2));
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    for net in SEPARATED {
        let (mesh, s) = surface_of(gallery(net), scheme, 3);
        let jump = jump_across(&mesh, &s, &xs, 1e-10, &|_, _| true);
        eprintln!(
            "{net} under {scheme}, 3 rings: largest jump across {} knot and ring lines {jump:.3e}",
            xs.len()
        );
        assert!(jump < 1e-7, "{net}: jump {jump:e}");
        let jump = largest_jump(&mesh, &s, 1 << 6, 1e-10, &|_, _| true);
        eprintln!("{net} under {scheme}, 3 rings: largest jump across i 2^-6 {jump:.3e}");
        assert!(jump < 1e-7, "{net}: jump {jump:e}");
    }
}

#[test]
fn tps_adjustable_after_separating_steps_converges_at_rate_lambda() {
    // torus-evs: its vertices of valence 3 and 5; the cube's corners (valence 3)
    for (net, n) in [("cube", 3), ("torus-evs", 3), ("torus-evs", 5)] {
        let lambda = ratios::lambda(ids::TPS_ADJUSTABLE.name(), n);
        let mesh = gallery(net);
        let (ev, at) = toward_ev(&mesh, n);
        let what = format!("{net} n = {n}");
        // the quarter at the vertex is 0.3 of the face after one step: a ring or two fewer
        let (centre, _, _) = converges_at_ratio(
            ids::TPS_ADJUSTABLE.name(),
            &mesh,
            &at,
            (S, 12),
            10,
            lambda,
            &what,
        );
        // the limit point is TPS's (21) over the input net's 1-ring (the first step's
        // alphas) where the 1-ring's vertices are regular (the cube's corners are neighbours,
        // whose own rule (18) the averaged rows behind (21) do not take)
        let lim = ratios::tps_limit_point(&mesh, ev, n);
        let d = fairsub::geom::dist(centre, lim);
        let ring = mesh.cnet_indices(ev, 1).expect("the 1-ring");
        let regular = ring[1..].iter().all(|&w| mesh.valence(w as usize) == 4);
        eprintln!("{what}: centre to TPS's limit point (21) {d:.3e} (regular 1-ring: {regular})");
        assert!(!regular || d < 1e-12, "{what}: {centre:?} {lim:?}");
    }
}
