//! EG's local analysis: the subdivision matrix `A_n` on the local vector `(c0, d-net)` and the
//! characteristic ring, of the printed rules or of any given [`EgRules`] (the derived ones).

use super::{Eg, EgRules};
use crate::bezier::BezierPatch;
use crate::error::Result;
use crate::geom::Point;
use crate::schemes::local::{LocalMatrix, check_valence, dense};
use crate::schemes::options::ids;

/// EG subdivision's matrix `A_n` of the printed rules on the local vector `(c0, d-net)`
/// (`12 n + 1` points).
pub fn local_matrix(n: usize) -> Result<LocalMatrix> {
    check_valence(n)?;
    local_matrix_of(&EgRules::new(n)?, ids::EG.name())
}

/// The matrix `A_n` of given rules, labelled `label` in reports.
pub fn local_matrix_of(rules: &EgRules, label: &str) -> Result<LocalMatrix> {
    check_valence(rules.n)?;
    let st = Eg::with_rules(rules.clone()).step()?;
    Ok(LocalMatrix {
        scheme: label.into(),
        n: rules.n,
        centre: 1,
        sector: 12,
        matrix: dense(&st.step),
    })
}

/// EG's characteristic ring at valence `n` (printed rules): the ring patches of the
/// characteristic map's control points on the local vector, and lambda.
pub fn characteristic_ring(n: usize) -> Result<(Vec<BezierPatch>, f64)> {
    characteristic_ring_of(&EgRules::new(n)?)
}

/// The characteristic ring of given rules, and lambda.
pub fn characteristic_ring_of(rules: &EgRules) -> Result<(Vec<BezierPatch>, f64)> {
    let lm = local_matrix_of(rules, ids::EG.name())?;
    let (pts, lambda) = lm.characteristic_points()?;
    let ring = Eg::with_rules(rules.clone()).step()?.ring.apply(&pts);
    Ok((dnet_ring_patches(&ring, rules.n), lambda))
}

/// The `3 n` bi-4 patches of a d-net ring table's output, sector by sector (`A, B, C`),
/// transposed from the EG chart into the mesh's orientation.
pub fn dnet_ring_patches(ring: &[Point], n: usize) -> Vec<BezierPatch> {
    (0..3 * n)
        .map(|k| BezierPatch::new(4, 4, ring[25 * k..25 * k + 25].to_vec()).transposed())
        .collect()
}
