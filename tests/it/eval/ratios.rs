//! The rate at which limit evaluations approach an extraordinary element's limit point
//! (`tests/it/eval_dual.rs`, `tests/it/evalmore.rs`, `tests/it/eval_ternary.rs`, `tests/it/eval_nonbox.rs`).

use fairsub::geom::{Point, norm, sub};
use fairsub::surface::eval::Evaluation;

/// `fairsub analyze`'s subdominant eigenvalue of `scheme` at valence `n`.
#[allow(dead_code)]
pub fn lambda(scheme: &str, n: usize) -> f64 {
    let spec = fairsub::schemes::registry::registry()
        .lookup(scheme)
        .expect("scheme");
    fairsub::analysis::report::analyze(&spec, n, false)
        .expect("analysis")
        .spectrum
        .lambda
}

/// The last evaluation's point (the centre) and the ratios of successive distances of the
/// other evaluations to it.
pub fn error_ratios(evals: &[Evaluation]) -> (Point, Vec<f64>) {
    let centre = evals.last().expect("the centre").point;
    let err: Vec<f64> = evals[..evals.len() - 1]
        .iter()
        .map(|e| norm(sub(e.point, centre)))
        .collect();
    (centre, err.windows(2).map(|w| w[1] / w[0]).collect())
}

/// The limit evaluation of `scheme` on `mesh` at `at(2^-k)` (k = 2..=12) and `at(0)`
/// ([`super::support::limit_along`], at least `min_rings` rings); asserts that the ratios of
/// successive errors to the centre are `lambda` within 10% from k = 6 and returns the centre
/// and the ratios.
#[allow(dead_code)]
pub fn converges(
    scheme: &str,
    mesh: &fairsub::mesh::PolyMesh,
    at: impl Fn(f64) -> (u32, f64, f64),
    lambda: f64,
    min_rings: usize,
    what: &str,
) -> (Point, Vec<f64>) {
    let evals = super::support::limit_along(scheme, mesh, &at, min_rings);
    let (centre, ratios) = error_ratios(&evals);
    eprintln!("{scheme} {what}: lambda {lambda:.6}, error ratios {ratios:.6?}");
    assert_rate(&format!("{scheme} {what}"), &ratios, lambda, 4, 0.1);
    (centre, ratios)
}

/// Asserts that the error ratios from index `from` on are `lambda` within `tol` (relative);
/// ratio `k` is that of the points `k + 2` and `k + 3` of the sequence.
pub fn assert_rate(what: &str, ratios: &[f64], lambda: f64, from: usize, tol: f64) {
    for (k, &ratio) in ratios.iter().enumerate().skip(from) {
        assert!(
            (ratio / lambda - 1.0).abs() < tol,
            "{what}: error ratio {ratio} at k = {}, lambda {lambda}",
            k + 2
        );
    }
}

/// [`converges`] for schemes whose rings shrink by `ratio` (not 2): the limit evaluation at
/// `at(ratio^k)` (`(ratio, last)`, k = 2..=last, [`limit_at_ratio`]) and `at(0)`, whose successive errors to
/// the centre must shrink by `lambda` within 5% from k = 5 on (one ring per point), with at
/// least `min_rings` rings; returns the centre, the ratios and the rings used.
#[allow(dead_code)]
pub fn converges_at_ratio(
    scheme: &str,
    mesh: &fairsub::mesh::PolyMesh,
    at: &dyn Fn(f64) -> (u32, f64, f64),
    (ratio, last): (f64, i32),
    min_rings: usize,
    lambda: f64,
    what: &str,
) -> (Point, Vec<f64>, usize) {
    let (evals, rings) = limit_at_ratio(scheme, mesh, at, ratio, last, min_rings);
    let (centre, ratios) = error_ratios(&evals);
    eprintln!("{scheme} {what}: {rings} rings, lambda {lambda:.6}, error ratios {ratios:.6?}");
    assert_rate(&format!("{scheme} {what}"), &ratios, lambda, 3, 0.05);
    (centre, ratios, rings)
}

/// The limit surface of `scheme` on `mesh` ([`evaluate_limit`]) at `at(ratio^k)` for
/// `k = 2 ..= last` and, last, at `at(0)` (for schemes whose rings shrink by `ratio`, not 2:
/// TPS's thirds, adjustable TPS's `1 - 2e`), with the rings used; asserts at least
/// `min_rings` (`last` where ring `k` lies at `ratio^k` of the face; fewer after separating
/// whole-net steps, whose elements are smaller than the face).
#[allow(dead_code)]
pub fn limit_at_ratio(
    scheme: &str,
    mesh: &fairsub::mesh::PolyMesh,
    at: &dyn Fn(f64) -> (u32, f64, f64),
    ratio: f64,
    last: i32,
    min_rings: usize,
) -> (Vec<Evaluation>, usize) {
    use fairsub::surface::ComplexOptions;
    use fairsub::surface::eval::{Surface, evaluate_limit};
    let spec = fairsub::schemes::registry::registry()
        .lookup(scheme)
        .expect("scheme");
    let mut pts: Vec<(u32, f64, f64)> = (2..=last).map(|k| at(ratio.powi(k))).collect();
    pts.push(at(0.0));
    let (evals, rings) = evaluate_limit(&pts, &mut |k| {
        Surface::build(
            &spec,
            mesh,
            ComplexOptions {
                rings: k,
                fill: true,
            },
        )
    })
    .expect("limit evaluation");
    assert!(
        rings >= min_rings,
        "{scheme}: {rings} rings for points at {ratio}^{last}"
    );
    (evals, rings)
}

/// TPS's limit point (21) of vertex `ev` of valence `n`: `(1 - tau_1 - tau_2) q + tau_1
/// mean(a_i) + tau_2 mean(b_i)` over its 1-ring.
#[allow(dead_code)]
pub fn tps_limit_point(
    mesh: &fairsub::mesh::PolyMesh,
    ev: usize,
    n: usize,
) -> fairsub::geom::Point {
    use fairsub::geom::axpy;
    let p = fairsub::schemes::bi2::TpsParams::new(n).expect("valence");
    let ring = mesh.cnet_indices(ev, 1).expect("the 1-ring");
    let mut lim = fairsub::geom::scale(mesh.position(ev), 1.0 - p.tau1 - p.tau2);
    for s in 0..n {
        let (a, b) = (ring[1 + 2 * s] as usize, ring[2 + 2 * s] as usize);
        lim = axpy(lim, p.tau1 / n as f64, mesh.position(a));
        lim = axpy(lim, p.tau2 / n as f64, mesh.position(b));
    }
    lim
}
