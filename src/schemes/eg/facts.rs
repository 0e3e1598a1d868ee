//! Published numbers of the EG paper that derived rules are measured against, each with its
//! source. The printed arrays themselves are in [`super::tables`].

/// `mu / lambda^2` of the published rules (Section 6, the table after "the deviation of
/// mu / lambda^2 from 1 is small"), by valence.
pub const MU_OVER_LAMBDA2: [(usize, f64); 7] = [
    (3, 1.00015),
    (5, 1.00016),
    (6, 1.00151),
    (7, 1.00241),
    (8, 1.02887),
    (9, 1.04865),
    (10, 1.05815),
];

/// Source of [`MU_OVER_LAMBDA2`].
pub const MU_OVER_LAMBDA2_SOURCE: &str =
    "EG paper, Section 6 (Limit Analysis), table of mu / lambda^2";

/// Section 6: "The double subdominant eigenvalue lambda differs from that of Catmull-Clark
/// subdivision by less than 10^-3 for any n >= 3".
pub const LAMBDA_VS_CATMULL_CLARK: f64 = 1e-3;

/// Valences for which the paper claims rules (Conclusion: "Rules for n > 10 exist").
pub const CLAIMED_VALENCES: std::ops::RangeInclusive<usize> = 3..=10;

/// The published `mu / lambda^2` at valence `n`, if the paper gives one.
pub fn mu_over_lambda2(n: usize) -> Option<f64> {
    MU_OVER_LAMBDA2.iter().find(|(m, _)| *m == n).map(|x| x.1)
}
