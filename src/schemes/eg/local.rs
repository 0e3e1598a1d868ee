//! EG's local analysis: the subdivision matrix `A_n` on the local vector `(c0, d-net)` and the
//! characteristic ring.

use super::Eg;
use crate::bezier::BezierPatch;
use crate::error::Result;
use crate::geom::Point;
use crate::schemes::local::{LocalMatrix, check_valence, dense};
use crate::schemes::registry::ids;

/// EG subdivision's matrix `A_n` on the local vector `(c0, d-net)` (`12 n + 1` points).
pub fn local_matrix(n: usize) -> Result<LocalMatrix> {
    check_valence(n)?;
    let st = Eg::new(n)?.step()?;
    Ok(LocalMatrix {
        scheme: ids::EG.name().into(),
        n,
        centre: 1,
        sector: 12,
        matrix: dense(&st.step),
    })
}

/// EG's characteristic ring at valence `n`: the ring patches of the characteristic map's
/// control points on the local vector, and lambda.
pub fn characteristic_ring(n: usize) -> Result<(Vec<BezierPatch>, f64)> {
    let lm = local_matrix(n)?;
    let (pts, lambda) = lm.characteristic_points()?;
    let ring = Eg::new(n)?.step()?.ring.apply(&pts);
    Ok((dnet_ring_patches(&ring, n), lambda))
}

/// The `3 n` bi-4 patches of a d-net ring table's output, sector by sector (`A, B, C`),
/// transposed from the EG chart into the mesh's orientation.
pub fn dnet_ring_patches(ring: &[Point], n: usize) -> Vec<BezierPatch> {
    (0..3 * n)
        .map(|k| BezierPatch::new(4, 4, ring[25 * k..25 * k + 25].to_vec()).transposed())
        .collect()
}
