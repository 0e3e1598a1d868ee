//! The rate at which limit evaluations approach an extraordinary element's limit point
//! (`tests/eval_dual.rs`, `tests/evalmore.rs`, `tests/eval_ternary.rs`, `tests/eval_nonbox.rs`).

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
/// ([`crate::support::limit_along`], at least `min_rings` rings); asserts that the ratios of
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
    let evals = crate::support::limit_along(scheme, mesh, &at, min_rings);
    let (centre, ratios) = error_ratios(&evals);
    eprintln!("{scheme} {what}: lambda {lambda:.6}, error ratios {ratios:.6?}");
    for (k, &ratio) in ratios.iter().enumerate().skip(4) {
        assert!(
            (ratio / lambda - 1.0).abs() < 0.1,
            "{scheme} {what}: error ratio {ratio} at k = {}, lambda {lambda}",
            k + 2
        );
    }
    (centre, ratios)
}

/// The limit surface of `scheme` on `mesh` ([`evaluate_limit`]) at `at(ratio^k)` for
/// `k = 2 ..= last` and, last, at `at(0)` (for schemes whose rings shrink by `ratio`, not 2:
/// TPS's thirds, adjustable TPS's `1 - 2e`), with the rings used; asserts at least `last`.
#[allow(dead_code)]
pub fn limit_at_ratio(
    scheme: &str,
    mesh: &fairsub::mesh::PolyMesh,
    at: &dyn Fn(f64) -> (u32, f64, f64),
    ratio: f64,
    last: i32,
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
        rings >= last as usize,
        "{scheme}: {rings} rings for points at {ratio}^{last}"
    );
    (evals, rings)
}
