//! `fairsub eval` run in-process, for the evaluation tests that check the command line
//! (`tests/it/eval.rs`, `tests/it/eval_polar.rs`).

use fairsub::cli::{capture, run_words};

/// `fairsub eval` with `extra`, its output or error.
pub fn eval_words(extra: &[&str]) -> Result<String, String> {
    let mut words = vec!["fairsub", "eval"];
    words.extend_from_slice(extra);
    let (r, out) = capture(|| run_words(words));
    r.map(|()| out).map_err(|e| e.to_string())
}
