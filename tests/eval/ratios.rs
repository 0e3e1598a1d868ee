//! The rate at which limit evaluations approach an extraordinary element's limit point
//! (`tests/eval_dual.rs`, `tests/evalmore.rs`, `tests/eval_ternary.rs`).

use fairsub::geom::{Point, norm, sub};
use fairsub::surface::eval::Evaluation;

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
